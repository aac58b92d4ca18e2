#!/usr/bin/env bash
# Runs the ABI fuzzer (native/fuzz/README.md): native/fuzz/tools/fuzz.sh BINARY SECONDS JOBS
#   JOBS 0: one process with a fixed seed that stops at the first crash (`make test`);
#   JOBS >= 1: JOBS worker processes for SECONDS in all, each started again after a crash, a
#   hang or an out-of-memory, so that one known crash does not hide the others (`make fuzz`).
# Workers share out/fuzz/corpus (libFuzzer reloads it, so each sees what the others found); the
# committed seeds in native/fuzz/corpus are read only; crashing inputs go to out/fuzz/artifacts.
# The run fails if it wrote any artifact.
#
# Why not libFuzzer's -fork mode, which also survives crashes: its short-lived children reload
# the corpus and restart the library each time, and ran 50-120 executions/s on the 2-core CI
# machine where one plain process runs ~225/s (two share it at ~205/s).
set -euo pipefail
cd "$(dirname "$0")/../../.."
binary=$1 seconds=$2 jobs=$3
out=out/fuzz
mkdir -p "$out/corpus" "$out/artifacts"
marker=$(mktemp)
trap 'rm -f "$marker"' EXIT
# Leak checks are left to the replays in ctest: run after every input they cost 3.5x the
# executions, because the TBB and Embree thread pools keep allocating across inputs.
common=(-detect_leaks=0 -timeout=30 -rss_limit_mb=4096 -max_len=512
        -artifact_prefix="$out/artifacts/" -print_final_stats=1)
# detect_leaks=0 for ASan too: its leak check when a worker exits would be taken for a crash.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0}

# One worker: runs the fuzzer until `end` (epoch seconds), again after each finding. libFuzzer
# first runs every corpus input (minutes once out/fuzz/corpus has grown: a run may end that much
# after `end`); a run that ends before it printed INITED crashed on a corpus input, which every
# new run would find again, so the worker stops there.
worker() {
  local index=$1 end=$2 log=$3 run=0 remaining lines
  : > "$log"
  while remaining=$((end - $(date +%s))); [ "$remaining" -gt 0 ]; do
    lines=$(wc -l < "$log")
    "$binary" "${common[@]}" -max_total_time="$remaining" -seed=$((1000 * index + run + 1)) \
      "$out/corpus" native/fuzz/corpus >> "$log" 2>&1 || true
    run=$((run + 1))
    if ! tail -n "+$((lines + 1))" "$log" | grep -qE '^#[0-9]+[[:space:]]+INITED'; then
      echo "fuzz worker $index: run $run ended before the corpus was loaded (a crash in the corpus)" >> "$log"
      break
    fi
  done
}

status=0
if [ "$jobs" -eq 0 ]; then
  "$binary" "${common[@]}" -max_total_time="$seconds" -seed=1 "$out/corpus" native/fuzz/corpus \
    > "$out/last-run.log" 2>&1 || status=$?
  grep -E '^#[0-9]+' "$out/last-run.log" | tail -1 || true
  grep -E '^stat::number_of_executed_units|^stat::average_exec_per_sec' "$out/last-run.log" || true
  logs=("$out/last-run.log")
else
  end=$(( $(date +%s) + seconds ))
  logs=()
  for ((i = 1; i <= jobs; i++)); do
    logs+=("$out/worker-$i.log")
    worker "$i" "$end" "$out/worker-$i.log" &
  done
  wait
  cat "${logs[@]}" > "$out/last-run.log"
  # Each run's executions: its last "#N" status line (a run that crashed prints no final stats).
  read -r executions runs < <(awk '/^INFO: Seed:/ {total += last; last = 0; runs++}
                                   /^#[0-9]+/ {last = substr($1, 2) + 0}
                                   END {print total + last, runs + 0}' "${logs[@]}")
  echo "fuzz: $executions executions in $seconds s by $jobs workers ($runs fuzzer runs)"
fi
new=$(find "$out/artifacts" -type f -newer "$marker" | sort)
if [ -n "$new" ] || [ "$status" -ne 0 ]; then
  echo "fuzz: the run found crashes, hangs or leaks (logs: ${logs[*]}):"
  for f in $new; do echo "  $f"; done
  echo "  replay one with its ABI calls: STRATUM_FUZZ_TRACE=1 $binary <file>"
  echo "  group them by cause: .venv/bin/python native/fuzz/tools/fuzz_triage.py $out/artifacts"
  exit 1
fi
echo "fuzz: no crash in $seconds s (log: $out/last-run.log)"
