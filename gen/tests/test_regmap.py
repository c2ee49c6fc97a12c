"""Register map (gen/empc/regmap.py): the generated docs are current, the map is consistent,
and the read-back format the co-simulation checks the RTL against."""
from pathlib import Path

import pytest

from empc import regmap

ROOT = Path(__file__).resolve().parents[2]


def test_docs_current():
    assert (ROOT / "docs" / "registers.md").read_text() == regmap.render_md(), \
        "docs/registers.md is stale: python -m empc.regmap --md docs/registers.md"


@pytest.mark.parametrize("regs,span", [(regmap.GLOBAL, regmap.AXIS_BASE), (regmap.AXIS, regmap.AXIS_STRIDE)])
def test_map_consistent(regs, span):
    offs = [r.offset for r in regs]
    assert len(set(offs)) == len(offs), "two registers share an offset"
    assert len({r.name for r in regs}) == len(regs)
    for r in regs:
        assert 0 <= r.offset < span and r.access in ("RO", "RW", "WO", "W1C")
        assert 1 <= r.width <= 32 and 0 <= r.reset < (1 << 32)
        assert not (r.signed and r.fields), r.name
        bits = 0
        for f in r.fields:
            m = ((1 << f.width) - 1) << f.lsb
            assert f.lsb + f.width <= 32 and not bits & m, f"{r.name}.{f.name} overlaps or exceeds 32 bits"
            bits |= m


def test_readback():
    assert regmap.axis_reg("DEAD_TIME").readback(0xFFFFFF37) == 0x37                 # width mask
    assert regmap.axis_reg("KDC").readback(0xFFFFFFFF) == 0x3FFFF
    idr = regmap.axis_reg("ID_REF")
    assert idr.readback(0x00020000) == 0xFFFE0000                                   # sign-extended
    assert idr.readback(0xFFF1FFFF) == 0x0001FFFF
    assert regmap.axis_reg("KACC").readback(0xFFFFFFFF) == 0x1F03FFFF               # fields only
    assert regmap.axis_reg("SEG_LEN").readback(0xDEADBEEF) == 0xDEADBEEF
    with pytest.raises(KeyError):
        regmap.axis_reg("NO_SUCH")
