"""Register map (gen/empc/regmap.py): every file generated from it is current, the map is
consistent, bad maps give a one-line error naming the register, and the read-back format
the co-simulation checks the RTL against."""
from pathlib import Path

import pytest

from empc import regblock, regmap
from empc.regmap import Block, Ext, Field, MapError, Reg

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("rel", ["docs/registers.md", "fw/empc_regs.h", "rtl/global_regs.v", "rtl/axis_regs.v"])
def test_generated_files_current(rel):
    files = {str(p.relative_to(ROOT)): t for p, t in regmap.generated_files(ROOT).items()}
    assert set(files) == {"docs/registers.md", "fw/empc_regs.h", "rtl/global_regs.v", "rtl/axis_regs.v"}
    assert (ROOT / rel).read_text() == files[rel], f"{rel} is stale: python -m empc.regmap --all (make regs)"


def test_generated_rtl_listed_and_marked():
    listed = (ROOT / "rtl" / "rtl_files.f").read_text().split()
    for b in regmap.BLOCKS:
        assert f"rtl/{b.module}.v" in listed
        assert "Do not edit" in regblock.render(b).splitlines()[0]


@pytest.mark.parametrize("block", regmap.BLOCKS, ids=lambda b: b.module)
def test_map_consistent(block):
    regmap.check(block.regs, block.span, block.ext, what=block.module)
    for r in block.regs:
        assert r.mask >> r.bits == 0 and r.reset_int() & ~r.mask == 0, r.name
        assert r.reset_build_mask() & ~r.mask == 0
    # the ext table names the blocks that keep storage, and every group is used
    assert {r.ext for r in block.regs if r.ext} <= {e.name for e in regmap.EXT}


def test_map_layout_lines_short():
    """Readable map: no generated or hand-written line of the map modules over 120 characters."""
    for rel in ("gen/empc/regmap.py", "gen/empc/regblock.py", "gen/empc/fwheader.py"):
        long = [i + 1 for i, l in enumerate((ROOT / rel).read_text().splitlines()) if len(l) > 120]
        assert not long, f"{rel}: lines {long} longer than 120 characters"


def test_vh_widths_and_build_resets():
    vh = regmap.render_vh()
    assert "`define EMPC_A_KDC_W 18\n" in vh and "`define EMPC_A_FAULT_W 7\n" in vh
    assert "`define EMPC_A_ADC_OFF0_RESET `EMPC_ADC_OFFSET\n" in vh
    assert "`define EMPC_A_CTRL_PWM_PER_CONTROL_W 8\n" in vh


def test_reset_words():
    ctrl = regmap.axis_reg("CTRL")
    assert ctrl.reset_build_mask() == 0xFF00 and ctrl.reset_int() == 0
    assert ctrl.reset_word({"PWM_PER_CONTROL": 5}) == 0x500
    kacc = regmap.axis_reg("KACC")
    assert kacc.reset_word({"KACC": 0x3FFFF, "KACC_SHIFT": 31, "KACC_LOAD_SHIFT": 6}) == 0x1F1BFFFF
    assert regmap.axis_reg("UDC").reset_word({}) == 36000


def test_readback():
    assert regmap.axis_reg("DEAD_TIME").readback(0xFFFFFF37) == 0x37                 # width mask
    assert regmap.axis_reg("KDC").readback(0xFFFFFFFF) == 0x3FFFF
    idr = regmap.axis_reg("ID_REF")
    assert idr.readback(0x00020000) == 0xFFFE0000                                   # sign-extended
    assert idr.readback(0xFFF1FFFF) == 0x0001FFFF
    assert regmap.axis_reg("KACC").readback(0xFFFFFFFF) == 0x1F3FFFFF               # fields only
    assert regmap.axis_reg("SEG_LEN").readback(0xDEADBEEF) == 0xDEADBEEF
    with pytest.raises(KeyError):
        regmap.axis_reg("NO_SUCH")


OK = Reg("OK", 0x00, "RW", 0, "fine", width=8)
BAD = [  # (registers, words that the one-line message must contain)
    ((OK, Reg("B", 0x00, "RW", 0, "x")), ["B", "0x0", "OK"]),
    ((OK, Reg("OK", 0x01, "RW", 0, "x")), ["OK", "twice"]),
    ((Reg("B", 0x100, "RW", 0, "x"),), ["B", "outside"]),
    ((Reg("B", 0x01, "RX", 0, "x"),), ["B", "access"]),
    ((Reg("B", 0x01, "RW", 0, "x", (Field("a", 0, 4, ""), Field("b", 3, 2, ""))),), ["B", "overlaps"]),
    ((Reg("B", 0x01, "RW", 0, "x", (Field("a", 30, 4, ""),)),), ["B", "exceeds"]),
    ((Reg("B", 0x01, "RW", 300, "x", width=8),), ["B", "reset 300", "fit"]),
    ((Reg("B", 0x01, "RW", 250, "x", width=8, legal=range(0, 200)),), ["B", "250", "legal"]),
    ((Reg("B", 0x01, "RW", 0, "x", width=4, legal=range(0, 20)),), ["B", "fit"]),
    ((Reg("B", 0x01, "RW", 0, "x", width=4, legal=range(1, 5)),), ["B", "reset", "legal"]),
    ((Reg("B", 0x01, "RO", 0, "x", legal=(0, 1)),), ["B", "legal"]),
    ((Reg("B", 0x01, "RO", 0, "x", guard="on"),), ["B", "guard"]),
    ((Reg("B", 0x01, "RW", 0, "x", guard="Bad Name"),), ["B", "guard"]),
    ((Reg("TIME", 0x01, "RO", 0, "x"),), ["TIME", "keyword", "port="]),
    ((Reg("B", 0x01, "RW", 0, "x", ext="nope"),), ["B", "ext"]),
    ((Reg("B", 0x01, "WO", 0, "x", width=8, key=0x1FF),), ["B", "key"]),
    ((Reg("B", 0x01, "RW", 0, "x", const=True),), ["B", "const"]),
    ((Reg("B", 0x01, "RW", 0, "x", width=8, floor=300),), ["B", "floor"]),
    ((Reg("B", 0x01, "RW", "FOO", "x", width=8),), ["B", "EMPC_"]),
    ((Reg("B", 0x01, "W1C", 0, "x", (Field("a", 0, 2, ""),)),), ["B", "W1C"]),
    ((Reg("B", 0x01, "RW", 0, "x", read="fast"),), ["B", "read"]),
    ((Reg("B", 0x01, "RW", 0, "x", ext="w"), Reg("C", 0x03, "RW", 0, "x", ext="w")), ["w", "contiguous"]),
    ((Reg("B", 0x01, "RW", 0, "x", ext="w", guard="g1"), Reg("C", 0x02, "RW", 0, "x", ext="w", guard="g2")),
     ["w", "guard"]),
    ((Reg("B", 0x01, "RW", 0, "x", ext="w", legal=(0, 1)),), ["B", "legal"]),
]


@pytest.mark.parametrize("regs,words", BAD, ids=[f"bad{i}" for i in range(len(BAD))])
def test_bad_maps_refused(regs, words):
    ext = (Ext("w", "window", "test window", idx=True),)
    with pytest.raises(MapError) as e:
        regblock.render(Block("bad_regs", "T", regs, "copy", "bad", ext=ext))
    msg = str(e.value)
    assert "\n" not in msg and all(w in msg for w in words), msg


def test_macro_clash_refused(monkeypatch):
    """A register named like another register's field macro: refused, not silently redefined."""
    regs = regmap.AXIS + (Reg("STATUS_FAULT", 0x3f, "RO", 0, "clash"),)
    monkeypatch.setattr(regmap, "BLOCKS", (regmap.BLOCKS[0], regmap.Block("axis_regs", "A", regs, "copy", "x")))
    with pytest.raises(MapError, match="STATUS_FAULT"):
        regmap.render_vh()
