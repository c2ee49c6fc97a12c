"""Every repository path the documentation and the source comments mention exists (issue 13: docs drifted).

Checked text: README.md, docs/*.md, docs/blocks/*.md (all of it, backquoted or not) and the sources
(rtl/, tb/hdl/, formal/ Verilog; gen/, flow/, tb/ Python; Makefile):
- paths under a top-level directory (``rtl/...``, ``gen/empc/...``, ``tb/...``, ...) must exist;
- ``empc.<module>[.<attribute>...]`` references must import and resolve;
- bare file names (``foo.py``, ``bar.v``, ``x.vh``, ``y.sv``, ``z.sby``) in the prose (documents,
  comments, docstrings) must name a file somewhere in the repository.
Placeholders are skipped: ``<block>``, ``*``, ``{...}``, ``foo``, ``NAME``; so are ``build/`` paths and
the headers ``empc roms`` generates.
"""
from __future__ import annotations

import ast
import functools
import importlib
import io
import re
import tokenize
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TOP_DIRS = ("rtl", "tb", "gen", "flow", "docs", "constraints", "formal", ".ci")
PATH = re.compile(r"(?<![\w./<-])((?:%s)/[\w./<>*{}\-]*)" % "|".join(re.escape(d) for d in TOP_DIRS))
MODULE = re.compile(r"(?<![\w./])(empc(?:\.[A-Za-z_]\w*)+)")
BARE = re.compile(r"(?<![\w./<>{}*-])([A-Za-z_][\w-]*\.(?:py|v|vh|sv|sby))\b")
PLACEHOLDER = re.compile(r"[<>*{}]|(?:^|[/_.])(?:foo|NAME)(?:[_./]|$)")
GENERATED = {"empc_formats.vh", "empc_regs.vh"}          # written by `empc roms` into the ROM directory

DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")), *sorted((ROOT / "docs" / "blocks").glob("*.md"))]
VERILOG = sorted([*(ROOT / "rtl").glob("*.v"), *(ROOT / "rtl").glob("*.vh"), *(ROOT / "tb" / "hdl").glob("*.v"),
                  *(ROOT / "formal").glob("*.sv")])
PYTHON = sorted(p for p in [*(ROOT / "gen").rglob("*.py"), *(ROOT / "flow").glob("*.py"), *(ROOT / "tb").glob("*.py")]
                if p != Path(__file__).resolve())       # this file names stale paths on purpose (mutants)
SOURCES = VERILOG + PYTHON + [ROOT / "Makefile"]


def _repo_names() -> set[str]:
    skip = {".git", ".venv", "build", "__pycache__", "sim_build"}
    return {p.name for p in ROOT.rglob("*") if not skip & set(p.relative_to(ROOT).parts)}


def _prose(p: Path) -> str:
    """The human-readable part of a file: documents whole, comments and docstrings of sources."""
    text = p.read_text()
    if p.suffix == ".md":
        return text
    if p.suffix == ".py":
        out = [t.string for t in tokenize.generate_tokens(io.StringIO(text).readline) if t.type == tokenize.COMMENT]
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
                out.append(ast.get_docstring(node, clean=False) or "")
        return "\n".join(out)
    if p.suffix in (".v", ".vh", ".sv"):
        return "\n".join(re.findall(r"//[^\n]*|/\*.*?\*/", text, re.S))
    return "\n".join(re.findall(r"#[^\n]*", text))          # Makefile


@functools.lru_cache(maxsize=None)
def _resolve_module(ref: str) -> str | None:
    """None if ``empc.a.b.C.d`` imports (longest module prefix) and its attributes exist, else why not."""
    if (ROOT / ref).exists():                              # empc.core is the FuseSoC file
        return None
    parts = ref.split(".")
    for i in range(len(parts), 1, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ModuleNotFoundError:
            continue
        for a in parts[i:]:
            if not hasattr(obj, a):
                return f"{'.'.join(parts[:i])} has no attribute {a!r}"
            obj = getattr(obj, a)
        return None
    return "no such module"


def problems(files, names=None) -> list[str]:
    names = _repo_names() if names is None else names
    out = []
    for p in files:
        text, rel = p.read_text(), p.relative_to(ROOT) if p.is_relative_to(ROOT) else p
        for n, line in enumerate(text.splitlines(), 1):
            for m in PATH.finditer(line):
                tok = re.sub(r":\d+$", "", m.group(1).rstrip(".,;:)'\""))
                if not PLACEHOLDER.search(tok) and not tok.startswith("build/") and not (ROOT / tok).exists():
                    out.append(f"{rel}:{n}: {tok} does not exist")
            for m in MODULE.finditer(line):
                why = _resolve_module(m.group(1).rstrip("."))
                if why:
                    out.append(f"{rel}:{n}: {m.group(1)}: {why}")
        for m in BARE.finditer(_prose(p)):
            tok = m.group(1)
            if tok not in names and tok not in GENERATED and not PLACEHOLDER.search(tok):
                out.append(f"{rel}: {tok}: no file of that name in the repository")
    return out


@pytest.mark.parametrize("group", ["docs", "sources"])
def test_mentioned_paths_exist(group):
    files = DOCS if group == "docs" else SOURCES
    found = problems(files)
    assert not found, f"{len(found)} stale references:\n" + "\n".join(found)
    print(f"{group}: {len(files)} files, every path, empc.* reference and file name they mention exists")


def test_mutants_are_caught(tmp_path):
    """A deleted RTL file, a moved module, a wrong attribute and a renamed file are each reported."""
    doc = tmp_path / "x.md"
    doc.write_text("model of `rtl/clarke.v`, see `empc.rtlmodel.park.rotate`, `empc.formats.no_such`,\n"
                   "(see mpc_fixed.py); fine: `rtl/xform.v`, `empc.formats.sat`, `tb/test_<block>.py`, xform.py\n")
    found = problems([doc])
    assert len(found) == 4, found
    assert any("rtl/clarke.v" in f for f in found) and any("empc.rtlmodel.park.rotate" in f for f in found)
    assert any("no_such" in f for f in found) and any("mpc_fixed.py" in f for f in found)
    src = tmp_path / "m.py"
    src.write_text('"""Bit-exact model of ``rtl/park.v``."""\n# see sincos.py, clarke_step.py\nx = a.vh  # attribute, not a file\n')
    found = problems([src])
    assert len(found) == 2 and "rtl/park.v" in found[0] and "clarke_step.py" in found[1], found
