"""Groups the ABI fuzzer's crashing inputs by cause.

    python native/fuzz/tools/fuzz_triage.py [ARTIFACT_DIR_OR_FILES...]
        [--binary build-asan/stratum_fuzz]

Each input is replayed with its ABI calls traced (STRATUM_FUZZ_TRACE=1); its cause is the
first report found in the output (the harness's own finding, an Embree assertion, a UBSan or
ASan report, libFuzzer's out-of-memory or timeout) with its location, and the ABI call that was
running (the last traced call that did not return). Prints one line per cause with the number
of inputs and the smallest one, which is the one to minimise and commit as a regression.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]  # the repository

PATTERNS = [
    (re.compile(r"STRATUM FUZZ FINDING: (.*)"), "finding: {0}"),
    (re.compile(r"(\S+\.(?:cpp|h)):(\d+): .*Assertion `(.*)' failed"), "assertion {0}:{1}: {2}"),
    (re.compile(r"(\S+):(\d+):\d+: runtime error: (.*)"), "UBSan {0}:{1}: {2}"),
    (re.compile(r"ERROR: AddressSanitizer: (out-of-memory|allocator is out of memory)"), "out of memory"),
    (re.compile(r"ERROR: libFuzzer: out-of-memory"), "out of memory"),
    (re.compile(r"ERROR: AddressSanitizer: ([\w-]+)"), "ASan {0}"),
    (re.compile(r"ERROR: LeakSanitizer"), "leak"),
    (re.compile(r"ERROR: libFuzzer: timeout"), "timeout"),
    (re.compile(r"ERROR: libFuzzer: deadly signal"), "deadly signal"),
]
# The first stack frame in the project's own native code names where a report comes from.
PROJECT_FRAME = re.compile(r"#\d+ 0x[0-9a-f]+ in (\S+) .*?/native/src/([\w/]+\.(?:cpp|h)):(\d+)")
NUMBER = re.compile(r"(?<![\w.])-?\d+(\.\d+)?(e[+-]?\d+)?(?![\w.])")


def cause(output: str) -> str:
    for pattern, text in PATTERNS:
        match = pattern.search(output)
        if match:
            found = text.format(*(Path(g).name if "/" in g else g for g in match.groups()))
            # Numbers vary between inputs of one cause (pixel coordinates, sizes).
            found = NUMBER.sub("N", found) if found.startswith(("finding", "UBSan")) else found
            frame = PROJECT_FRAME.search(output)
            return found + (f" [{frame.group(2)}:{frame.group(3)} {frame.group(1)}]" if frame else "")
    return "no crash on replay"


def running_call(output: str) -> str:
    """The last traced ABI call: the one that crashed or hung, or (when it returned) the one
    after which the harness found a violated invariant or a render thread crashed."""
    calls = [line.strip() for line in output.splitlines() if line.startswith("  stratum_")]
    return (calls or ["(none)"])[-1].split("(", 1)[0]


def replay(binary: Path, path: Path) -> str:
    env = dict(os.environ, STRATUM_FUZZ_TRACE="1")
    env.setdefault("LSAN_OPTIONS", f"suppressions={ROOT / 'native/fuzz/lsan.supp'}")
    try:
        run = subprocess.run(
            [str(binary), "-timeout=30", "-rss_limit_mb=4096", str(path)],
            check=False,
            capture_output=True,
            text=True,
            errors="replace",
            env=env,
            timeout=120,
        )
        return run.stderr + run.stdout
    except subprocess.TimeoutExpired as e:
        return (e.stderr or b"").decode(errors="replace") + "\nERROR: libFuzzer: timeout"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("inputs", nargs="*", default=[str(ROOT / "out/fuzz/artifacts")])
    parser.add_argument("--binary", default=str(ROOT / "build-asan/stratum_fuzz"))
    args = parser.parse_args()
    files = []
    for item in map(Path, args.inputs):
        files += sorted(p for p in item.iterdir() if p.is_file()) if item.is_dir() else [item]
    groups: dict[tuple[str, str], list[Path]] = defaultdict(list)
    for path in files:
        output = replay(Path(args.binary), path)
        groups[(cause(output), running_call(output))].append(path)
    print("| inputs | cause | running call | smallest input |")
    print("|---|---|---|---|")
    for (found, call), paths in sorted(groups.items(), key=lambda g: -len(g[1])):
        smallest = min(paths, key=lambda p: p.stat().st_size)
        print(f"| {len(paths)} | {found} | {call} | {smallest} ({smallest.stat().st_size} bytes) |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
