"""`make lint`: verilator --lint-only -Wall on every RTL module as its own top.

Every file in rtl/rtl_files.f is linted with itself as the top module (so
unused or parameterised blocks are covered too) with all other RTL files
available as libraries.  Zero warnings are allowed; waivers must be local
(`/* verilator lint_off RULE */ ... lint_on` around the line, with a reason).
Usage: python flow/lint.py [module ...]
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from files import ROOT, VENV_VERILATOR_BIN, rtl_sources, roms_dir  # noqa: E402


def main(argv: list[str]) -> int:
    env = dict(os.environ)
    env["PATH"] = f"{VENV_VERILATOR_BIN}{os.pathsep}{env.get('PATH', '')}"
    sources = rtl_sources()
    tops = [p for p in sources if p.suffix == ".v"]
    if argv:
        tops = [p for p in tops if p.stem in argv]
        if not tops:
            print(f"no RTL module named {argv}")
            return 2
    failed = []
    for top in tops:
        cmd = ["verilator", "--lint-only", "-Wall", f"-I{ROOT / 'rtl'}", f"-I{roms_dir()}",
               "--top-module", top.stem, str(top)] + [a for p in sources if p != top for a in ("-v", str(p))]
        r = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True)
        out = "\n".join(l for l in (r.stdout + r.stderr).splitlines()
                        if l.strip() and not l.startswith(("- V e r i l a t i o n", "- Verilator:"))).strip()
        if r.returncode != 0 or out:
            failed.append(top.stem)
            print(f"--- {top.stem}: FAIL\n{out}")
        else:
            print(f"lint ok   {top.stem}")
    print(f"lint: {len(tops) - len(failed)}/{len(tops)} modules clean")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
