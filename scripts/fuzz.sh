#!/usr/bin/env bash
# Runs the ABI fuzzer (native/fuzz/README.md): scripts/fuzz.sh BINARY SECONDS JOBS
#   JOBS 0: one process with a fixed seed that stops at the first crash (`make test`);
#   JOBS >= 1: libFuzzer's fork mode with JOBS workers that keeps going after crashes, hangs
#   and out-of-memory, so that one known crash does not hide the others (`make fuzz`).
# New inputs go to out/fuzz/corpus (the committed seeds in native/fuzz/corpus are read only),
# crashing inputs to out/fuzz/artifacts; the run fails if it wrote any artifact.
set -euo pipefail
cd "$(dirname "$0")/.."
binary=$1 seconds=$2 jobs=$3
out=out/fuzz
mkdir -p "$out/corpus" "$out/artifacts"
marker=$(mktemp)
trap 'rm -f "$marker"' EXIT
# Leak checks are left to the replays in ctest: run after every input they cost 3.5x the
# executions, because the TBB and Embree thread pools keep allocating across inputs.
common=(-detect_leaks=0 -timeout=30 -rss_limit_mb=4096 -max_len=512 -max_total_time="$seconds"
        -artifact_prefix="$out/artifacts/" -print_final_stats=1)
if [ "$jobs" -eq 0 ]; then
  mode=(-seed=1)
else
  mode=(-fork="$jobs" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
fi
status=0
# detect_leaks=0 for ASan too: its leak check when a worker exits would be taken for a crash.
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0} "$binary" "${common[@]}" "${mode[@]}" "$out/corpus" native/fuzz/corpus > "$out/last-run.log" 2>&1 || status=$?
grep -E '^#[0-9]+' "$out/last-run.log" | tail -1 || true
grep -E '^stat::number_of_executed_units|^stat::average_exec_per_sec' "$out/last-run.log" || true
new=$(find "$out/artifacts" -type f -newer "$marker" | sort)
if [ -n "$new" ] || [ "$status" -ne 0 ]; then
  echo "fuzz: the run found crashes, hangs or leaks (log: $out/last-run.log):"
  for f in $new; do echo "  $f"; done
  echo "  replay one with its ABI calls: STRATUM_FUZZ_TRACE=1 $binary <file>"
  exit 1
fi
echo "fuzz: no crash in $seconds s (log: $out/last-run.log)"
