"""Runs corpus cases in worker subprocesses of one Blender (no bpy here).

A worker runs the cases it is given one after another (Blender's start-up is paid once) and
writes a line when it starts a case and one when it is done (worker.py). If the worker dies,
the case it had started is recorded as a crash with the signal or exit status and the end of its
log (Embree's assertion message is there), and a new worker continues with the cases left. A
case that gives no result within `timeout` seconds is a hang: its worker is killed. Workers run
under an address-space limit so that a case which makes the renderer allocate tens of gigabytes
(an image header claiming 65535x65535) fails by itself instead of exhausting the machine.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[2]
WORKER = HERE / "worker.py"

# Address-space limit of a worker. Blender 3.4 and the bpy wheel map about 2-3 GiB of virtual
# memory when rendering these scenes (thread stacks and allocator arenas included); 8 GiB
# leaves room and still stops a runaway allocation at a third of the machine's memory.
MEMORY_LIMIT = int(os.environ.get("STRATUM_CORPUS_MEMORY", str(8 << 30)))
# Seconds a case may take before it counts as a hang (a case takes about a second).
TIMEOUT = float(os.environ.get("STRATUM_CORPUS_TIMEOUT", "60"))


@dataclass(frozen=True)
class Blender:
    """A Blender to run workers in: `command` + worker arguments."""

    name: str
    command: tuple[str, ...]

    def available(self) -> bool:
        return shutil.which(self.command[0]) is not None or Path(self.command[0]).is_file()


def blenders() -> list[Blender]:
    """Blender 3.4 (`blender -b`, $BLENDER overrides) and the bpy wheel of the project's venv."""
    exe = os.environ.get("BLENDER", "blender")
    venv_python = REPO / ".venv" / "bin" / "python"
    python = str(venv_python) if venv_python.is_file() else sys.executable
    return [
        Blender("blender", (exe, "-b", "--factory-startup", "-noaudio", "--python",
                            str(WORKER), "--")),
        Blender("bpy", (python, str(WORKER))),
    ]


@dataclass
class Outcome:
    """One case in one Blender. status: 'ok' (the worker judged it: see failures), 'crash',
    'hang' or 'not run' (the worker could not start)."""

    case: str
    blender: str
    status: str
    failures: list[str] = field(default_factory=list)
    reports: list[list[str]] = field(default_factory=list)
    stats: dict[str, Any] = field(default_factory=dict)
    seconds: float = 0.0
    detail: str = ""
    version: str = ""  # the Blender version the worker reported

    @property
    def passed(self) -> bool:
        return self.status == "ok" and not self.failures

    def verdict(self) -> str:
        if self.status != "ok":
            return f"{self.status.upper()} {self.detail.splitlines()[0] if self.detail else ''}"
        levels = {lvl for lvl, _ in self.reports}
        shown = "ERROR" if levels & {"ERROR", "BLENDER"} else (
            "WARNING" if "WARNING" in levels else "clean")
        return f"{'pass' if not self.failures else 'FAIL'} ({shown})"

    def message(self) -> str:
        """The failure, or the message the user sees (first ERROR, else first WARNING)."""
        if self.status != "ok":
            return ": ".join(self.detail.splitlines()[:2])
        if self.failures:
            return self.failures[0]
        for level in ("ERROR", "BLENDER", "WARNING"):
            for lvl, text in self.reports:
                if lvl == level:
                    return text
        return ""

    def describe(self) -> str:
        lines = [f"{self.case} in {self.blender}: {self.verdict()}"]
        lines += [f"  failure: {f}" for f in self.failures]
        lines += [f"  {lvl}: {text}" for lvl, text in self.reports]
        if self.stats:
            lines.append(f"  image: {self.stats}")
        if self.detail:
            lines.append("  " + self.detail.replace("\n", "\n  "))
        return "\n".join(lines)


def _exit_text(code: int | None) -> str:
    if code is None:
        return "killed"
    if code < 0:
        try:
            return f"signal {signal.Signals(-code).name}"
        except ValueError:
            return f"signal {-code}"
    return f"exit status {code}"


# Blender's progress lines, which bury the lines that explain a crash.
_NOISE = ("Fra:", " Time:", "Saved:", "Blender quit")
# Lines that say why a process died (Embree's assertion, a sanitizer, a C++ terminate).
_CAUSES = ("Assertion", "Sanitizer", "runtime error", "terminate", "what()", "Segmentation",
           "Traceback", "Error")


def _log_tail(log: Path, lines: int = 12) -> str:
    """The cause of a death (the last line matching _CAUSES) and the log's last lines."""
    try:
        text = [line for line in log.read_text(errors="replace").splitlines()
                if line.strip() and not line.startswith(_NOISE)]
    except OSError:
        return ""
    tail = text[-lines:]
    causes = [line for line in tail if any(c in line for c in _CAUSES)]
    return "\n".join(([short_cause(causes[-1])] if causes else []) + tail)


def short_cause(line: str) -> str:
    """An assertion as file:line and its condition (the function signature between them is
    hundreds of characters of Embree templates)."""
    found = re.search(r"([\w./-]+:\d+): .*?(Assertion .*)", line)
    return f"{found.group(1)}: {found.group(2)}" if found else line[:400]


class _Results:
    """Reads the lines a worker appends to its results file, as they come."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self._offset = 0
        self._partial = ""

    def new_records(self) -> list[dict[str, Any]]:
        if not self.path.is_file():
            return []
        with self.path.open(encoding="utf-8") as f:
            f.seek(self._offset)
            chunk = f.read()
            self._offset = f.tell()
        text = self._partial + chunk
        lines = text.split("\n")
        self._partial = lines.pop()
        return [json.loads(line) for line in lines if line.strip()]


def run(blender: Blender, names: list[str], work: Path, capture: Path | None = None,
        timeout: float = TIMEOUT) -> dict[str, Outcome]:
    """Runs the cases `names` in `blender`; `work` receives results, logs and the cases'
    files; `capture` (optional) the captured native scenes."""
    work.mkdir(parents=True, exist_ok=True)
    tmp = work / "tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir()
    outcomes: dict[str, Outcome] = {}
    pending = list(names)
    attempt = 0
    while pending:
        attempt += 1
        results = work / f"results-{attempt}.jsonl"
        results.unlink(missing_ok=True)
        log = work / f"worker-{attempt}.log"
        args = ["--results", str(results), "--tmp", str(tmp)]
        if capture is not None:
            args += ["--capture", str(capture)]
        with log.open("wb") as log_file:
            proc = subprocess.Popen([*blender.command, *args, *pending], stdout=log_file,
                                    stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                    start_new_session=True)
            # Set from outside (a preexec_fn is unsafe with the runner's threads); the worker
            # is still starting up then, long before its first case allocates anything.
            with contextlib.suppress(ProcessLookupError):  # it may have failed already
                resource.prlimit(proc.pid, resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
            current, hung = _watch(proc, _Results(results), outcomes, blender, timeout)
        progressed = False
        for name in list(pending):
            if name in outcomes:
                pending.remove(name)
                progressed = True
        if current is not None:
            status = "hang" if hung else "crash"
            what = f"no result after {timeout:g} s (worker killed)" if hung else \
                _exit_text(proc.returncode)
            outcomes[current] = Outcome(current, blender.name, status,
                                        detail=f"{what}\n{_log_tail(log)}")
            pending.remove(current)
        elif not progressed and pending:
            detail = f"the worker ended ({_exit_text(proc.returncode)}) without running a " \
                     f"case\n{_log_tail(log)}"
            for name in pending:
                outcomes[name] = Outcome(name, blender.name, "not run", detail=detail)
            break
    return outcomes


def _watch(proc: subprocess.Popen[bytes], results: _Results, outcomes: dict[str, Outcome],
           blender: Blender, timeout: float) -> tuple[str | None, bool]:
    """Follows a worker until it exits or a case hangs: (case in progress, hung)."""
    current: str | None = None
    since = time.monotonic()
    while True:
        exited = proc.poll() is not None
        for record in results.new_records():
            name = record["case"]
            if record["event"] == "start":
                current, since = name, time.monotonic()
            elif record["event"] == "done":
                outcomes[name] = Outcome(name, blender.name, "ok", record["failures"],
                                         record["reports"], record["stats"], record["seconds"],
                                         version=record["version"])
                current = None
        if exited:
            return current, False
        if current is not None and time.monotonic() - since > timeout:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            return current, True
        time.sleep(0.05)
