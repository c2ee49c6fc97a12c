"""Register map (gen/empc/regmap.py): every file generated from it is current, the map is
consistent, bad maps give a one-line error naming the register, and the read-back format
the co-simulation checks the RTL against."""
from pathlib import Path

import pytest

from empc import regblock, regmap
from empc.regmap import Block, Ext, Field, MapError, Reg

ROOT = Path(__file__).resolve().parents[2]


GENERATED = ["docs/registers.md", "fw/empc_regs.h", "rtl/global_regs.v", "rtl/axis_regs.v", "rtl/axis_rd.v"]


@pytest.mark.parametrize("rel", GENERATED)
def test_generated_files_current(rel):
    files = {str(p.relative_to(ROOT)): t for p, t in regmap.generated_files(ROOT).items()}
    assert set(files) == set(GENERATED)
    assert (ROOT / rel).read_text() == files[rel], f"{rel} is stale: python -m empc.regmap --all (make regs)"


def test_generated_rtl_listed_and_marked():
    listed = (ROOT / "rtl" / "rtl_files.f").read_text().split()
    for b in regmap.BLOCKS:
        assert f"rtl/{b.module}.v" in listed
        assert "Do not edit" in regblock.render(b).splitlines()[0]
        if b.shared:
            assert f"rtl/{b.shared}.v" in listed
            assert "Do not edit" in regblock.render_shared(b).splitlines()[0]


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
    nfault = len(regmap.axis_reg("FAULT").fields)        # one bit per cause, contiguous from bit 0
    assert "`define EMPC_A_KDC_W 18\n" in vh and f"`define EMPC_A_FAULT_W {nfault}\n" in vh
    assert f"`define EMPC_A_FAULT_MASK_W {nfault}\n" in vh
    assert "`define EMPC_A_ADC_OFF0_RESET `EMPC_ADC_OFFSET\n" in vh
    assert "`define EMPC_A_CTRL_PWM_PER_CONTROL_W 8\n" in vh


def test_reset_words():
    ctrl = regmap.axis_reg("CTRL")
    assert ctrl.reset_build_mask() == 0xFF00 and ctrl.reset_int() == 0
    assert ctrl.reset_word({"PWM_PER_CONTROL": 5}) == 0x500
    kacc = regmap.axis_reg("KACC")
    assert kacc.reset_word({"KACC": 0x3FFFF, "KACC_SHIFT": 31, "KACC_LOAD_SHIFT": 6, "KACC_WIN": 0}) == 0x1F1BFFFF
    assert kacc.reset_word({"KACC": 0x3FFFF, "KACC_SHIFT": 31, "KACC_LOAD_SHIFT": 6, "KACC_WIN": 3}) == 0x7F1BFFFF
    # DC link: UDC resets to 0, below the reset UDC_MIN: a missing value trips (issue 14 item 2)
    udc, lo, hi = (regmap.axis_reg(n).reset_word({}) for n in ("UDC", "UDC_MIN", "UDC_MAX"))
    assert udc == 0 and 0 < lo < hi


def test_pack():
    """Reg.pack: the fields by name into their bits (a negative value two's complement); every field exactly
    once and each value fitting its width, else MapError (KACC: the word empc_designs.h and the manifest hold)."""
    r = regmap.axis_reg("KACC")
    f = {x.name: x for x in r.fields}
    w = r.pack({"kacc": -2, "load_shift": 6, "shift": 17, "win": 3})
    assert w == (((1 << 18) - 2) | 6 << f["load_shift"].lsb | 17 << f["shift"].lsb | 3 << f["win"].lsb)
    assert w == r.readback(w) and w & ~r.mask == 0
    assert r.pack({"kacc": 5, "load_shift": 0, "shift": 0, "win": 0}) == 5
    for bad in ({"kacc": 1 << 18, "load_shift": 0, "shift": 0, "win": 0},
                {"kacc": -(1 << 17) - 1, "load_shift": 0, "shift": 0, "win": 0},
                {"kacc": 0, "load_shift": 0, "shift": 0, "win": 8}, {"kacc": 0, "load_shift": 0, "shift": 0},
                {"kacc": 0, "load_shift": 0, "shift": 0, "win": 0, "speed_window": 1}):
        with pytest.raises(MapError):
            r.pack(bad)


def test_readback():
    assert regmap.axis_reg("DEAD_TIME").readback(0xFFFFFF37) == 0x37                 # width mask
    assert regmap.axis_reg("KDC").readback(0xFFFFFFFF) == 0x3FFFF
    idr = regmap.axis_reg("ID_REF")
    assert idr.readback(0x00020000) == 0xFFFE0000                                   # sign-extended
    assert idr.readback(0xFFF1FFFF) == 0x0001FFFF
    assert regmap.axis_reg("KACC").readback(0xFFFFFFFF) == 0xFF3FFFFF               # fields only
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


# ---------------------------------------------------------------- issue 14: the safety settings
SAFETY_REGS = ("FAULT_MASK", "DEAD_TIME", "OC_THRESH", "ADC_SUM_THRESH", "UDC_MIN", "UDC_MAX", "ANGLE_CAL",
               "HALL_OFFSET", "ADC_OFF0", "ADC_OFF1", "ADC_OFF2")


def test_safety_settings_protected():
    """Every safety setting is refused while the bridges are live; FAULT_MASK and WDOG_TIMEOUT also
    need the unlock; the build limits are legal ranges; the bridge mode is not a register."""
    for n in SAFETY_REGS:
        assert regmap.axis_reg(n).guard == "bridges_live", n
    ctrl = {f.name: f for f in regmap.axis_reg("CTRL").fields}
    assert "complementary" not in ctrl, "the bridge mode is a build parameter (CAPS.complementary)"
    assert ctrl["pwm_per_control"].guard == "bridges_live" and 0 not in ctrl["pwm_per_control"].legal
    assert ctrl["enable"].safe == 0 and ctrl["run"].safe == 0          # switching off is never refused
    assert {f.name: f for f in regmap.axis_reg("CMD").fields}["adc_cal"].guard == "bridges_live"
    assert regmap.axis_reg("FAULT_MASK").unlock == "UNLOCK"
    wdog = next(r for r in regmap.GLOBAL if r.name == "WDOG_TIMEOUT")
    assert wdog.unlock == "WDOG_UNLOCK" and wdog.guard == "bridges_live" and 0 not in wdog.legal
    assert max(wdog.legal) == regmap.WDOG_TIMEOUT_MAX
    assert min(regmap.axis_reg("DEAD_TIME").legal) == regmap.DEAD_TIME_MIN > 0
    assert max(regmap.axis_reg("OC_THRESH").legal) == regmap.OC_THRESH_MAX
    # any legal offset with any legal threshold: both rails of the ADC are beyond the threshold
    full = (1 << regmap.ADC_CODE_BITS) - 1
    offs = regmap.axis_reg("ADC_OFF0").legal
    assert min(offs) - 0 > regmap.OC_THRESH_MAX and full - max(offs) > regmap.OC_THRESH_MAX
    assert regmap.axis_reg("UDC").wstrobe


def test_fault_causes_contiguous():
    """FAULT: one bit per cause from bit 0 (axis_periph wires cause k to FAULT bit k); FAULT_MASK the same bits."""
    f = regmap.axis_reg("FAULT").fields
    assert [x.lsb for x in f] == list(range(len(f))) and all(x.width == 1 for x in f)
    m = regmap.axis_reg("FAULT_MASK")
    assert m.width == len(f) and m.reset == (1 << len(f)) - 1


@pytest.mark.parametrize("bad, msg", [
    (dict(arm=5), "arm needs a key register"),
    (dict(unlock="NOPE"), "is not a key register with arm"),
    (dict(wstrobe=True, access="WO"), "wstrobe needs a stored RW register"),
])
def test_bad_safety_attributes(bad, msg):
    kw = dict(width=8)
    access = bad.pop("access", "RW")
    kw.update(bad)
    regs = (regmap.Reg("A", 0, access, 0, "a", **kw),)
    with pytest.raises(regmap.MapError, match=msg):
        regmap.check(regs, 256, ())


def test_bad_field_safety_attributes():
    F, R = regmap.Field, regmap.Reg
    with pytest.raises(regmap.MapError, match="safe of x needs"):
        regmap.check((R("A", 0, "RW", 0, "a", (F("x", 0, 1, "x", safe=2),)),), 256, ())
    with pytest.raises(regmap.MapError, match="field guard of x"):
        regmap.check((R("A", 0, "RO", 0, "a", (F("x", 0, 1, "x", guard="g"),)),), 256, ())


def test_routing_registers():
    """Issue 16 item 4: the routing registers are guarded (route_locked: an axis live, or no out_route in the
    build, CAPS.route), OUT_SEL refuses codes
    beyond the routable pairs, the reset map is today's pinout, the fields hold the board's resources."""
    g = {r.name: r for r in regmap.GLOBAL}
    route = ("OUT_SEL0", "OUT_SEL1", "ADC_SEL0", "ADC_SEL1", "IN_SEL")
    for n in route:
        assert g[n].guard == "route_locked" and g[n].access == "RW", n
        assert all(f.lsb % regmap.ROUTE_NIB == 0 for f in g[n].fields), n
    npair = regmap.ROUTE_AXES * regmap.ROUTE_PHASES
    outs = [f for n in ("OUT_SEL0", "OUT_SEL1") for f in g[n].fields]
    assert [f.name for f in outs] == [f"out{k}" for k in range(regmap.ROUTE_OUTPUTS)]
    assert all(f.legal == range(0, npair + 1) and (1 << f.width) > npair for f in outs)
    assert g["OUT_SEL0"].wstrobe and g["OUT_SEL1"].wstrobe          # restart out_route's mapped scan
    reset = [f.reset for f in outs]
    assert reset == [k + 1 if k < npair else 0 for k in range(regmap.ROUTE_OUTPUTS)]   # output 3a+p = (a, p)
    for a in range(regmap.ROUTE_AXES):
        assert regmap.route_out_code(a, 0) == 1 + regmap.ROUTE_PHASES * a
    adc = [f for n in ("ADC_SEL0", "ADC_SEL1") for f in g[n].fields]
    assert [f.reset for f in adc] == list(range(npair)) and all((1 << f.width) >= regmap.ROUTE_ADC for f in adc)
    ins = {f.name: f for f in g["IN_SEL"].fields}
    for a in range(regmap.ROUTE_AXES):
        assert ins[f"enc{a}"].reset == a and (1 << ins[f"enc{a}"].width) >= regmap.ROUTE_ENC
        assert ins[f"hall{a}"].reset == a and (1 << ins[f"hall{a}"].width) >= regmap.ROUTE_HALL
    st = g["ROUTE_STATUS"]
    assert st.access == "RO" and [f.name for f in st.fields][:regmap.ROUTE_AXES] == [
        f"mapped{a}" for a in range(regmap.ROUTE_AXES)]
    # a write naming a code beyond the pairs, or while live, is refused as a whole
    w = sum(1 << (regmap.ROUTE_NIB * k) for k in range(regmap.ROUTE_PER_WORD))
    assert g["OUT_SEL0"].accepts(w) and not g["OUT_SEL0"].accepts(w, live=True)
    assert not g["OUT_SEL0"].accepts(w | ((npair + 1) << (regmap.ROUTE_NIB * 7)))


def test_driver_axis_range_and_control_period():
    """empc.driver refuses an axis outside the map (it would alias: axis 15's registers are axis 0's
    coefficient window; the C driver refuses axes >= CAPS.naxes, tb/test_empc_drv.py), and Drive.control
    keeps the axis's control period unless one is given (no hidden default that would change it)."""
    import asyncio
    from empc import driver

    for ax in (-1, regmap.ROUTE_AXES, 15, 1.0):
        with pytest.raises(ValueError, match="axis"):
            driver.address("CTRL", ax)
        with pytest.raises(ValueError, match="axis"):
            driver.Drive(None, ax)
    last = regmap.ROUTE_AXES - 1
    assert driver.address("CTRL", last) == regmap.AXIS_BASE + last * regmap.AXIS_STRIDE + regmap.axis_reg("CTRL").offset
    assert driver.address("ID", 99) == next(r.offset for r in regmap.GLOBAL if r.name == "ID")   # global: no axis

    class Bus:
        def __init__(self):
            self.mem = {}

        async def write(self, a, v):
            self.mem[a] = v

        async def read(self, a):
            return self.mem.get(a, 0)

    bus = Bus()
    d = driver.Drive(bus, last)
    a = driver.address("CTRL", last)
    for ppc in (1, 3, 8):
        bus.mem[a] = driver.field_value("CTRL", pwm_per_control=ppc)
        asyncio.run(d.control(True, True))
        assert bus.mem[a] == driver.field_value("CTRL", enable=1, run=1, pwm_per_control=ppc)
    asyncio.run(d.control(False, False, pwm_per_control=2))
    assert bus.mem[a] == driver.field_value("CTRL", pwm_per_control=2)
