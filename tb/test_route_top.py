"""Free output assignment at the top level (issue 16 item 4): lx_rocon_top with NAXES = 2 and out_route
between the axes' pwm_center pairs and out_kill, through tb/hdl/cosim4_top.v (the board's 16 outputs; the
co-simulation's pin emulators hold the sensors at rest, the test drives the CPU bus only).

One run (`route`):
 1. after reset: CAPS.route = 1, OUT_SEL0/1 read the reset map (output 3a + p = axis a, phase p),
    ROUTE_STATUS.mapped = 0b111 for axes 0 and 1 (0 for the axes the build lacks), bad_sel 0; axis 0
    enabled (CTRL.enable = 1, run = 0: bridges on at zero voltage, LX_PWR mode: enable high, PWM low)
    drives outputs 0..2 only (enable high for the whole period, every other pin low);
 2. with every axis off: axis 1 moved to outputs 12..14, its old outputs 3..5 set to 0 (off); the writes
    are accepted (read back, CNT_WR_REFUSED unchanged), ROUTE_STATUS still 0b111 / 0b111; axis 1 enabled:
    outputs 12..14 enabled for the whole period, every other pin (PWM and enable) low
    (outputs 6..11 name axes 2, 3 the build lacks: held off);
 3. an OUT_SEL0 write while axis 1 is live is refused: the register unchanged, CNT_WR_REFUSED + 1;
 4. with every axis off, IN_SEL gives axis 1 HALL set 3 (tied to 000 in the harness): FAULT.hall on axis 1
    only; restored and cleared: FAULT 0.
 5. an axis with a phase on no output stays off (issue 16 item 4): output 14 (axis 1, phase C) set to 0,
    ROUTE_STATUS.mapped1 = 0b011; CTRL.enable of axis 1 is stored but STATUS.bridges_on stays 0 and every
    pin stays low for a PWM period; the axis is live (CTRL.enable), so mapping the phase back is refused
    (CNT_WR_REFUSED + 1) until the CPU clears CTRL.enable; then mapped back, 0b111, axis 1 enables on
    outputs 12..14 again;
 6. ADC_SEL: axis 1's currents moved to MISO lines 6..8 (the harness's spare emulator g_spare, SPARE = 1):
    an overcurrent code on its old lines 3..5 trips nothing; the same code on lines 6..8 latches
    FAULT.overcurrent on axis 1, axis 0's FAULT stays 0; restored and cleared;
 7. IN_SEL.enc: axis 1 on IRC input 2 (the spare's encoder): axis 1's POS follows the spare's count (+100),
    not its old emulator's (-60), axis 0's POS does not move; restored (both encoders back at 0 first).
 8. a routed axis faulted: axis 1 on outputs 12..14, an overcurrent code at its ADC lines: every pin off,
    STATUS.bridges_on 0, FAULT.overcurrent on axis 1 only, the routing unchanged; the code removed, one
    fault clear: axis 1 back on outputs 12..14 only within a PWM period, OUT_SEL and ROUTE_STATUS intact.
Mutants (`full`): route_locked tied to 0 in lx_rocon_top (writes accepted while an axis is live): step 3
fails; route_ok tied to 1 (an axis on two of three phases switches): step 5 fails.
"""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
ROOT = Path(__file__).resolve().parents[1]
NAXES = 2
RESET_SEL0, RESET_SEL1 = 0x87654321, 0x0000CBA9
NEW_SEL0 = 0x87000321           # outputs 0..2 axis 0, 3..5 off, 6..7 axis 2 (not in the build)
NEW_SEL1 = 0x0654CBA9           # outputs 8..11 axes 2, 3 (not in the build), 12..14 axis 1, 15 off
RESET_IN = 0x32103210           # IN_SEL: IRC input a, HALL set a
HALL1_SET3 = 0x32303210         # axis 1 on HALL set 3
UNMAP1_SEL1 = NEW_SEL1 & ~(0xF << 24)   # output 14 (axis 1, phase C) off: axis 1 on two of three phases
RESET_ADC0 = 0x76543210         # ADC_SEL0: channel 3a + p
ADC1_SPARE = 0x76876210         # axis 1 on MISO lines 6..8 (the spare emulator's)
AX01_FIELDS = 0x00FFFFFF        # ADC_SEL0's fields of axes 0 and 1
ENC1_SPARE = 0x32103220         # IN_SEL: axis 1 on IRC input 2 (the spare emulator's)

try:
    import cocotb
    from cocotb.triggers import ClockCycles, RisingEdge
except ImportError:                     # collection without cocotb: only the pytest wrappers below
    cocotb = None


if cocotb is not None:
    async def _pins(dut, nclk: int) -> tuple[int, int, int]:
        """Over nclk clocks: OR of pwm_out, OR of pwm_en, AND of pwm_en."""
        o_or = e_or = 0
        e_and = (1 << 16) - 1
        for _ in range(nclk):
            await RisingEdge(dut.clk)
            o, e = int(dut.pwm_out.value), int(dut.pwm_en.value)
            o_or, e_or, e_and = o_or | o, e_or | e, e_and & e
        return o_or, e_or, e_and

    async def _on(dut, drv, P: int, on: bool) -> None:
        """CTRL.enable (run 0: zero voltage) and wait for STATUS.bridges_on to follow."""
        from empc import regmap
        await drv.kick()
        await drv.control(on, False)
        bit = {f.name: f.lsb for f in regmap.axis_reg("STATUS").fields}["bridges_on"]
        for _ in range(6):
            await ClockCycles(dut.clk, P)
            st = await drv.read("STATUS")
            if bool((st >> bit) & 1) == on:
                await ClockCycles(dut.clk, 4)
                return
        f = await drv.read("FAULT")
        raise AssertionError(f"axis {drv.axis}: bridges_on did not become {on} (STATUS {st:#x}, FAULT {f:#x})")

    def _lsb(reg: str, field: str) -> int:
        from empc import regmap
        r = regmap.axis_reg(reg) if reg in ("STATUS", "FAULT") else next(g for g in regmap.GLOBAL if g.name == reg)
        return {f.name: f.lsb for f in r.fields}[field]

    @cocotb.test()
    async def route(dut):
        from empc import driver, regmap
        from emc_bfm import EmcBfm
        import test_closed_loop as tcl

        bfm = EmcBfm(dut, pins=dict(cs_n="cpu_cs_n", oe_n="cpu_oe_n", we_n="cpu_we_n", a="cpu_a", d="cpu_d",
                                    d_oe="cpu_d_oe", bus="emc_d_seen"))
        from test_closed_loop_4axes import LockedBus, pins_at_rest
        bus = LockedBus(bfm)
        d0, d1 = driver.Drive(bus, axis=0), driver.Drive(bus, axis=1)
        dut.pwr_fault_n.value = 1
        dut.rst_n.value = 0
        from empc import config
        for p in [dut.g_ax[n].u_ax for n in range(NAXES)] + [dut.g_spare.u_ax]:   # ADC lines at zero current
            pins_at_rest(p, config.default().sensors.adc_offset)
        bfm.idle()
        await ClockCycles(dut.clk, 20)
        dut.rst_n.value = 1
        await ClockCycles(dut.clk, 3000)

        # 1. reset map
        caps = await d0.read("CAPS")
        cf = {f.name: f.lsb for f in next(r for r in regmap.GLOBAL if r.name == "CAPS").fields}
        assert caps & 0xF == NAXES and (caps >> cf["route"]) & 1, f"CAPS {caps:#x}: not a routed {NAXES}-axis build"
        s0, s1 = await d0.read("OUT_SEL0"), await d0.read("OUT_SEL1")
        assert (s0, s1) == (RESET_SEL0, RESET_SEL1), f"OUT_SEL after reset {s0:#x} {s1:#x}"
        rs = await d0.read("ROUTE_STATUS")
        assert rs == 0x077, f"ROUTE_STATUS after reset {rs:#x} (want mapped0 = mapped1 = 0b111, bad_sel 0)"
        P = 2 * await d0.read("PWM_HALF")

        async def keeper():             # the CPU's periodic duties: DC-link voltage of both axes, watchdog
            while True:
                for d in (d0, d1):
                    await d.udc(tcl.UDC_MV)
                await d0.kick()
                await ClockCycles(dut.clk, P)
        cocotb.start_soon(keeper())
        await ClockCycles(dut.clk, 3 * P)
        for d in (d0, d1):              # FAULT.dclink latched before the first UDC write
            await d.command(fault_clear=1)
            f = await d.read("FAULT")
            assert f == 0, f"axis {d.axis}: FAULT {f:#x} after the clear"
        o, e, _ = await _pins(dut, 100)
        assert o == 0 and e == 0, f"pins on with every axis off: out {o:#06x} en {e:#06x}"
        await _on(dut, d0, P, True)
        o, e, ea = await _pins(dut, P)
        assert o & ~0b111 == 0 and e == 0b111 and ea == 0b111, \
            f"axis 0 on, reset map: out {o:#06x} en {e:#06x} (always {ea:#06x}), want outputs 0..2 only"
        await _on(dut, d0, P, False)
        o, e, _ = await _pins(dut, 100)
        assert o == 0 and e == 0, f"pins on after axis 0 off: out {o:#06x} en {e:#06x}"

        # 2. remap with every axis off: axis 1 -> outputs 12..14, outputs 3..5 off
        c0 = await d1.read("CNT_WR_REFUSED")
        await d0.write("OUT_SEL0", NEW_SEL0)
        await d0.write("OUT_SEL1", NEW_SEL1)
        s0, s1 = await d0.read("OUT_SEL0"), await d0.read("OUT_SEL1")
        assert (s0, s1) == (NEW_SEL0, NEW_SEL1), f"OUT_SEL write with every axis off not taken: {s0:#x} {s1:#x}"
        c1 = await d1.read("CNT_WR_REFUSED")
        assert c1 == c0, f"CNT_WR_REFUSED {c0} -> {c1} on accepted writes"
        await ClockCycles(dut.clk, 40)
        rs = await d0.read("ROUTE_STATUS")
        assert rs == 0x077, f"ROUTE_STATUS after the remap {rs:#x}"
        await _on(dut, d1, P, True)
        o, e, ea = await _pins(dut, P)
        want = 0b111 << 12
        assert o & ~want == 0 and e == want and ea == want, \
            f"axis 1 on, remapped: out {o:#06x} en {e:#06x} (always {ea:#06x}), want outputs 12..14 only"
        dut._log.info("remap: axis 1 on outputs 12..14 (out %#06x en %#06x), outputs 0..11, 15 off", o, e)

        # 3. a routing write while axis 1 is live is refused
        await d0.write("OUT_SEL0", RESET_SEL0)
        s0 = await d0.read("OUT_SEL0")
        c2 = await d1.read("CNT_WR_REFUSED")
        assert s0 == NEW_SEL0 and c2 == c1 + 1, \
            f"OUT_SEL0 write while axis 1 live: register {s0:#x} (want {NEW_SEL0:#x}), CNT_WR_REFUSED {c1} -> {c2}"
        o, e, ea = await _pins(dut, P)
        assert o & ~want == 0 and e == want and ea == want, f"pins after the refused write: out {o:#06x} en {e:#06x}"
        await _on(dut, d1, P, False)
        o, e, _ = await _pins(dut, 100)
        assert o == 0 and e == 0, f"pins on after axis 1 off: out {o:#06x} en {e:#06x}"

        # 4. an input select: axis 1's HALL from set 3 (a board line beyond the axes': 000, illegal)
        iv = await d0.read("IN_SEL")
        assert iv == RESET_IN, f"IN_SEL {iv:#x}"
        await d0.write("IN_SEL", HALL1_SET3)
        await ClockCycles(dut.clk, 2 * P)
        hb = 1 << {f.name: f.lsb for f in regmap.axis_reg("FAULT").fields}["hall"]
        f0, f1 = await d0.read("FAULT"), await d1.read("FAULT")
        assert f1 & hb and not f0 & hb, f"axis 1 on HALL set 3: FAULT axis 0 {f0:#x}, axis 1 {f1:#x} (want hall on 1 only)"
        await d0.write("IN_SEL", RESET_IN)
        await ClockCycles(dut.clk, 2 * P)
        await d1.command(fault_clear=1)
        f1 = await d1.read("FAULT")
        assert f1 == 0, f"axis 1 FAULT {f1:#x} after the HALL select restored and a clear"

        # 5. axis 1 on two of three phases: CTRL.enable stored, the bridges stay off
        await d0.write("OUT_SEL1", UNMAP1_SEL1)
        await ClockCycles(dut.clk, 40)
        rs = await d0.read("ROUTE_STATUS")
        assert rs == 0x037, f"ROUTE_STATUS with output 14 off {rs:#x} (want mapped1 = 0b011)"
        await d1.control(True, False)
        await ClockCycles(dut.clk, 3 * P)
        ctrl, st = await d1.read("CTRL"), await d1.read("STATUS")
        assert ctrl & 1 and not (st >> _lsb("STATUS", "bridges_on")) & 1, \
            f"axis 1 unmapped phase: CTRL {ctrl:#x}, STATUS {st:#x} (want enable stored, bridges_on 0)"
        o, e, _ = await _pins(dut, P)
        assert o == 0 and e == 0, f"axis 1 on two phases switched: out {o:#06x} en {e:#06x}"
        c3 = await d1.read("CNT_WR_REFUSED")
        await d0.write("OUT_SEL1", NEW_SEL1)            # the axis is live (CTRL.enable): refused
        s1, c4 = await d0.read("OUT_SEL1"), await d1.read("CNT_WR_REFUSED")
        assert s1 == UNMAP1_SEL1 and c4 == c3 + 1, \
            f"OUT_SEL1 write with axis 1 enabled: register {s1:#x}, CNT_WR_REFUSED {c3} -> {c4} (want refused)"
        dut._log.info("unmapped phase: axis 1 CTRL %#x STATUS %#x ROUTE_STATUS %#x, pins off, remap refused",
                      ctrl, st, rs)
        await d1.control(False, False)
        await d0.write("OUT_SEL1", NEW_SEL1)
        await ClockCycles(dut.clk, 40)
        rs = await d0.read("ROUTE_STATUS")
        assert rs == 0x077, f"ROUTE_STATUS after mapping phase C back {rs:#x}"
        await _on(dut, d1, P, True)
        o, e, ea = await _pins(dut, P)
        assert o & ~want == 0 and e == want and ea == want, \
            f"axis 1 mapped back: out {o:#06x} en {e:#06x} (always {ea:#06x}), want outputs 12..14 only"
        await _on(dut, d1, P, False)

        # 6. ADC_SEL: axis 1's currents from the spare emulator's MISO lines 6..8
        off = config.default().sensors.adc_offset
        oc_code = off + await d1.read("OC_THRESH") + 100
        ocb = 1 << _lsb("FAULT", "overcurrent")
        old, new = dut.g_ax[1].u_ax, dut.g_spare.u_ax
        await d0.write("ADC_SEL0", ADC1_SPARE)
        a0 = await d0.read("ADC_SEL0")
        assert a0 & AX01_FIELDS == ADC1_SPARE & AX01_FIELDS, f"ADC_SEL0 {a0:#x}"   # axis 2's fields: not in the build
        await ClockCycles(dut.clk, 2 * P)
        for line, what in ((old, "old lines 3..5"), (new, "new lines 6..8")):
            line.adc_code0.value = oc_code
            await ClockCycles(dut.clk, 2 * P)
            line.adc_code0.value = off
            f0, f1 = await d0.read("FAULT"), await d1.read("FAULT")
            hit = line is new
            assert f0 == 0 and bool(f1 & ocb) == hit, \
                f"overcurrent code on axis 1's {what}: FAULT axis 0 {f0:#x}, axis 1 {f1:#x} (want overcurrent {hit})"
            dut._log.info("ADC_SEL: overcurrent on %s: FAULT axis 0 %#x, axis 1 %#x", what, f0, f1)
        await ClockCycles(dut.clk, 2 * P)
        await d0.write("ADC_SEL0", RESET_ADC0)
        await ClockCycles(dut.clk, 2 * P)
        await d1.command(fault_clear=1)
        f1 = await d1.read("FAULT")
        assert f1 == 0, f"axis 1 FAULT {f1:#x} after ADC_SEL restored and a clear"

        # 7. IN_SEL.enc: axis 1's position from the spare emulator's IRC input 2
        p0, p1 = await d0.read("POS"), await d1.read("POS")
        await d0.write("IN_SEL", ENC1_SPARE)
        await ClockCycles(dut.clk, 100)
        for line, delta, want_d in ((new, 100, 100), (old, -60, 100)):   # want_d: POS - the POS before
            line.enc_target.value = delta & 0xFFFFFFFF
            await ClockCycles(dut.clk, abs(delta) * 16 + 200)      # STEP_CLKS = 16 per count
            q0, q1 = await d0.read("POS"), await d1.read("POS")
            d_1 = ((q1 - p1 + (1 << 31)) & 0xFFFFFFFF) - (1 << 31)
            assert q0 == p0 and d_1 == want_d, \
                f"IN_SEL.enc1 = 2, {'spare' if line is new else 'old'} encoder at {delta}: axis 1 POS moved {d_1} " \
                f"(want {want_d}), axis 0 POS {p0} -> {q0}"
        for line in (new, old):
            line.enc_target.value = 0
        await ClockCycles(dut.clk, 160 * 16 + 200)
        await d0.write("IN_SEL", RESET_IN)
        await ClockCycles(dut.clk, 100)
        f0, f1 = await d0.read("FAULT"), await d1.read("FAULT")
        assert f0 == 0 and f1 == 0, f"FAULT after the IRC select: axis 0 {f0:#x}, axis 1 {f1:#x}"

        # 8. a fault on a routed axis: axis 1 on outputs 12..14, an overcurrent code at its ADC lines (3..5): every
        #    pin off while FAULT.overcurrent is latched (axis 0 unaffected); the code removed, ONE clear: the bridges
        #    back on outputs 12..14 only within a PWM period, the routing (OUT_SEL, ROUTE_STATUS) unchanged
        await _on(dut, d1, P, True)
        o, e, ea = await _pins(dut, P)
        assert o & ~want == 0 and e == want and ea == want, f"axis 1 on before the fault: out {o:#06x} en {e:#06x}"
        old.adc_code0.value = oc_code
        await ClockCycles(dut.clk, 2 * P)
        old.adc_code0.value = off
        o, e, _ = await _pins(dut, 2 * P)
        f0, f1, st = await d0.read("FAULT"), await d1.read("FAULT"), await d1.read("STATUS")
        assert f0 == 0 and f1 & ocb, f"overcurrent on routed axis 1: FAULT axis 0 {f0:#x}, axis 1 {f1:#x}"
        assert o == 0 and e == 0 and not (st >> _lsb("STATUS", "bridges_on")) & 1, \
            f"axis 1 faulted: out {o:#06x} en {e:#06x}, STATUS {st:#x} (want every pin off, bridges_on 0)"
        s0, s1, rs = await d0.read("OUT_SEL0"), await d0.read("OUT_SEL1"), await d0.read("ROUTE_STATUS")
        assert (s0, s1, rs) == (NEW_SEL0, NEW_SEL1, 0x077), f"routing during the fault: {s0:#x} {s1:#x} {rs:#x}"
        await d1.command(fault_clear=1)                 # one clear, nothing else
        await ClockCycles(dut.clk, P + 20)              # the restart: at the next period boundary
        o, e, ea = await _pins(dut, P)
        f1, st = await d1.read("FAULT"), await d1.read("STATUS")
        assert f1 == 0 and (st >> _lsb("STATUS", "bridges_on")) & 1, f"after one clear: FAULT {f1:#x}, STATUS {st:#x}"
        assert o & ~want == 0 and e == want and ea == want, \
            f"axis 1 after the clear: out {o:#06x} en {e:#06x} (always {ea:#06x}), want outputs 12..14 only"
        s0, s1, rs = await d0.read("OUT_SEL0"), await d0.read("OUT_SEL1"), await d0.read("ROUTE_STATUS")
        assert (s0, s1, rs) == (NEW_SEL0, NEW_SEL1, 0x077), f"routing after the clear: {s0:#x} {s1:#x} {rs:#x}"
        dut._log.info("routed axis 1 faulted (overcurrent): every pin off, FAULT %#x; one clear: back on outputs "
                      "12..14 (en %#06x), ROUTE_STATUS %#x", f1 | ocb, e, rs)
        await _on(dut, d1, P, False)
        dut._log.info("route: reset map, remap, refused write while live, HALL select, unmapped phase held off, "
                      "ADC_SEL, IN_SEL.enc, a routed axis faulted and restarted by one clear: ok")


def _run(name: str = "route_top", run_name: str = "route"):
    from runner import run
    import test_closed_loop as tcl
    run(toplevel="cosim4_top", test_module="test_route_top", sim="verilator", name=name,
        public=ROOT / "tb" / "hdl" / "cosim4_top.vlt", timing=True,
        parameters={"NAXES": NAXES, "CLK_HALF_PS": tcl.CLK_PERIOD_NS * 500, "SPARE": 1}, defines={"EMPC_SIM_GATE": 1},
        run_name=run_name, testcase="route")


@pytest.mark.full
@pytest.mark.cost(120)           # Verilator build of the two-axis top (about 100 s) + a few PWM periods
def test_route_top():
    """Reset map, a remap with every axis off (the axis on the new pins only), a refused write while live, an
    input select, an axis with an unmapped phase held off, ADC_SEL and IN_SEL.enc moving axis 1's inputs."""
    _run()


# mutant: (file in rtl/, its text, the mutant's text, what results.xml must say)
MUTANTS = {
    "route_unlocked": ("lx_rocon_top.v", ".route_locked((|live) || !CAP_ROUTE)", ".route_locked(1'b0)",
                       "OUT_SEL0 write while axis 1 live"),
    "route_ok_tied": ("lx_rocon_top.v", "assign route_ok[n] = &mapped[3*n +: 3];", "assign route_ok[n] = 1'b1;",
                      "axis 1 unmapped phase"),
}


@pytest.mark.full
@pytest.mark.cost(120)
@pytest.mark.parametrize("mutant", list(MUTANTS))
def test_route_top_mutant(mutant, tmp_path):
    """The run must fail with route_locked tied to 0 (a routing write accepted while an axis is live) and with
    route_ok tied to 1 (an axis on two of three phases switches)."""
    import runner
    fname, good, bad, why = MUTANTS[mutant]
    name = f"route_top_mutant_{mutant}"
    with runner.rtl_mutant(fname, good, bad, tmp_path):
        with pytest.raises((AssertionError, SystemExit)):  # cocotb's runner exits on a failed test
            _run(name=name)
    res = runner.results_text(name, "cosim4_top", "route")
    assert why in res, res[-2000:]
