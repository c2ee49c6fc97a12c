"""mx_axes (NAXES axes on the shared engine) against the one-axis drive: time-shift equivalence.

tb/hdl/mx_axes_tb.v runs NAXES one-axis mpc_axis (the references) and mx_axes side by side.  Axis n of
mx_axes gets exactly reference n's stimuli delayed by its carrier phase PHASE_n = n x
EMPC_PWM_STAGGER_<NAXES>: encoder motion, HALL, the ADC codes (per lane on its own PWM period, read
through the shared SCLK / CS) and the register writes (UDC, the fault clear, IQ_REF, ID_REF, CTRL with a
control period every PWM period).  The stimuli differ between the axes (HALL sector, ADC codes and noise
seed, encoder speed, IQ_REF / ID_REF), so a register or measurement of the wrong axis shows.  The
algorithms differ too: the ALG2 axes (1, and 3 at NAXES = 4) upload the algorithm-2 speed image into
reference and mx_axes axis (coefficient window, before the register writes) and CMD.coef_swap to it, the
others keep the boot image (algorithm 1); IQ_HOLD is small on axis 1 (the core's anti-windup input aw,
from the job axis's IQ_HOLD, holds its speed increment in some periods) and 0 (off) on axis 3.  Checked,
bit- and clock-exact without a model:
  * every axis's six PWM outputs equal its reference's outputs PHASE_n clocks earlier, on every clock
    (the MPC runs: every reference switches, runs and counts its control periods);
  * STATUS.coef_bank is 1 on the ALG2 axes only, SAT_EBAR_INC of mx_axes equals the reference's (> 0 on
    axis 1), and the control periods ending with aw[0] are as many in mx_axes as in the reference: some
    but not all on axis 1, none elsewhere;
  * an overcurrent at the last axis's ADC pins (its channel 0 forced to full scale) trips that axis
    only: its outputs are 0 on every clock its fault is latched (from the clock the cause is
    registered), FAULT.overcurrent is set there and nowhere else, every other axis stays equal to the
    reference; after the cause is gone one CMD.fault_clear on that axis restarts it (bridges on).
Every axis runs at CTRL.pwm_per_control = 1 on the build's images re-encoded for that control period
(roms_at_period: the same gains and fingerprint; mpc_core runs an image only at its own period).
"""
from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
ROOT = Path(__file__).resolve().parents[1]

T0 = 8000              # first image / register write of the reference (mpc_core of 4 axes has booted: 3843 clk)
WRITE_GAP = 4          # clocks between two register writes of one lane
ALG2 = (1, 3)          # the axes that upload the algorithm-2 speed image (the others keep the boot image)
IQ_HOLD = {1: 6}       # the axes' IQ_HOLD (ADC LSB; 0 = the anti-windup off): axis 3 (NAXES = 4) runs alg. 2 with 0


def _roms() -> Path:
    return Path(os.environ.get("EMPC_ROMS", ROOT / "build" / "roms" / "default"))


PPC = 1     # CTRL.pwm_per_control of every axis: a control period every PWM period (many in a short run)


def roms_at_period(ppc: int = PPC) -> Path:
    """The build's ROM directory (EMPC_ROMS or build/roms/default) at control period ``ppc``: the images
    re-encoded with CFG[23:16] = ppc (the same gains and fingerprint: Ts is not in it, image layout 4)
    and the header's PWM_PER_CONTROL (CTRL.pwm_per_control after reset, CAPS) = ppc; everything else
    the same.  mpc_core runs an image only at its own control period (img_ok); this test checks the
    engine's bit-equality with the one-axis drive, not the gains' Ts."""
    import re
    import shutil
    from empc import header, image
    src = _roms()
    if header.read(src / "empc_formats.vh")["PWM_PER_CONTROL"] == ppc:
        return src
    out = ROOT / "build" / "roms" / f"{src.name}_ppc{ppc}"
    out.mkdir(parents=True, exist_ok=True)
    for f in src.iterdir():
        if f.is_file():
            shutil.copyfile(f, out / f.name)
    for f in out.glob("coef_*.hex"):
        image.write_hex(image.with_period(image.read_hex(f), ppc), f)
    vh = out / "empc_formats.vh"
    text, n = re.subn(r"^`define EMPC_PWM_PER_CONTROL \d+$", f"`define EMPC_PWM_PER_CONTROL {ppc}",
                      vh.read_text(), flags=re.M)
    assert n == 1
    vh.write_text(text)
    return out


def _hdr() -> dict:
    from empc import header
    return header.read(_roms() / "empc_formats.vh")


try:
    import cocotb
    from cocotb.triggers import ClockCycles, ReadOnly, RisingEdge
except ImportError:                     # collection without cocotb: only the pytest wrapper below
    cocotb = None


class _Recorder:
    """A bus for empc.driver.Drive that records the (word address, data) writes."""

    def __init__(self):
        self.ops: list[tuple[int, int]] = []

    async def write(self, addr: int, data: int) -> None:
        self.ops.append((addr, data))

    async def read(self, addr: int) -> int:     # pragma: no cover
        raise AssertionError("recorder: no reads")


async def _ops(fn) -> list[tuple[int, int]]:
    from empc import driver
    rec = _Recorder()
    await fn(driver.Drive(rec))
    return rec.ops


def _split(addr: int) -> tuple[int, int]:
    from empc import regmap
    off = addr - regmap.AXIS_BASE
    assert 0 <= off < 4 * regmap.AXIS_STRIDE, hex(addr)
    return off // regmap.AXIS_STRIDE, off % regmap.AXIS_STRIDE


async def _play(dut, events: list[tuple[int, dict]]) -> None:
    """events: (clock relative to the first, {port: value}); a write pulse is cleared a clock later."""
    cur = 0
    for t, assign in sorted(events, key=lambda e: e[0]):
        if t > cur:
            await ClockCycles(dut.clk, t - cur)
            cur = t
        for k, v in assign.items():
            getattr(dut, k).value = v


def _write_events(t: int, axis: int, ops: list[tuple[int, int]]) -> list:
    """mx_axes's register port: axis `axis`'s writes from clock t."""
    ev = []
    for i, (addr, data) in enumerate(ops):
        ax, off = _split(addr)
        assert ax == 0
        ev.append((t + WRITE_GAP * i, {"m_wr": 1, "m_addr": (axis << 8) | off, "m_wdata": data}))
        ev.append((t + WRITE_GAP * i + 1, {"m_wr": 0}))
    return ev


def _ref_events(t: int, ops_per_axis: list[list[tuple[int, int]]]) -> list:
    """The references' ports: the same register sequence, each reference its own values, from clock t."""
    ev = []
    na = len(ops_per_axis)
    for i in range(len(ops_per_axis[0])):
        offs = {_split(o[i][0])[1] for o in ops_per_axis}
        assert len(offs) == 1
        data = sum(o[i][1] << (32 * k) for k, o in enumerate(ops_per_axis))
        ev.append((t + WRITE_GAP * i, {"r_wr": (1 << na) - 1, "r_addr": offs.pop(), "r_wdata": data}))
        ev.append((t + WRITE_GAP * i + 1, {"r_wr": 0}))
    return ev


async def _read(dut, port: str, addr: int, sel: int = 0) -> int:
    await RisingEdge(dut.clk)
    if port == "r":
        dut.r_sel.value = sel
    getattr(dut, f"{port}_rd").value = 1
    getattr(dut, f"{port}_addr").value = addr
    await RisingEdge(dut.clk)
    getattr(dut, f"{port}_rd").value = 0
    await ReadOnly()
    v = int(getattr(dut, f"{port}_rdata").value)
    await RisingEdge(dut.clk)
    return v


def _vec(sig, k: int, w: int = 32) -> int:
    return (int(sig.value) >> (w * k)) & ((1 << w) - 1)


if cocotb is not None:
    @cocotb.test()
    async def time_shift(dut):
        from empc import regmap
        na = int(os.environ["MXA_NAXES"])
        periods = int(os.environ.get("MXA_PERIODS", "10"))
        h = _hdr()
        P2 = 2 * h["PWM_HALF_PERIOD"]
        st = h[f"PWM_STAGGER_{na}"]
        off = h["ADC_OFFSET"]
        last = na - 1
        reg = {r.name: r.offset for r in regmap.AXIS}
        bit = {f.name: f.lsb for f in regmap.axis_reg("FAULT").fields}
        sbit = {f.name: f.lsb for f in regmap.axis_reg("STATUS").fields}
        dut.rst.value = 1
        for p in ("r", "m"):
            for sg, v in (("wr", 0), ("rd", 0), ("addr", 0), ("wdata", 0)):
                getattr(dut, f"{p}_{sg}").value = v
        dut.r_sel.value = 0
        dut.t_move.value = T0 + 2 * P2
        halls = [0b001, 0b011, 0b010, 0b110]            # a valid HALL code per axis (different sectors)
        dut.hall_code.value = sum(halls[k] << (3 * k) for k in range(na))
        # phase currents summing to 0 (the sum check), different per axis
        # (small: the MPC is not driven into its voltage limit, u follows the references and the noise)
        b0 = [off + 6 + 2 * k for k in range(na)]
        b1 = [off - 2 - k for k in range(na)]
        b2 = [off - 4 - k for k in range(na)]
        for name, b in (("base0", b0), ("base1", b1), ("base2", b2)):
            getattr(dut, name).value = sum(v << (12 * k) for k, v in enumerate(b))
        dut.adc_seed.value = sum((12345 + 977 * k) << (32 * k) for k in range(na))
        dut.adc_noise.value = 8
        dut.inj.value = 0
        dut.inj_ax.value = last
        dut.cmp_en.value = 0
        for sg in ("r_cwe", "r_caddr", "m_cwe", "m_caddr"):
            getattr(dut, sg).value = 0
        await ClockCycles(dut.clk, 10)
        dut.rst.value = 0
        await RisingEdge(dut.clk)

        # the algorithm-2 speed image into the inactive bank of the ALG2 axes: every reference's at once,
        # one word a clock, then mx_axes's axes one after the other (not time-shifted: the upload does not
        # change the outputs; the swap command below is)
        from empc import image
        img2 = image.read_hex(_roms() / "coef_alg2_speed.hex")
        a2 = [k for k in ALG2 if k < na]
        ev = [(T0 + i, {"r_cwe": sum(1 << k for k in a2), "r_caddr": i,
                        "r_wdata": sum(img2[i] << (32 * k) for k in a2)}) for i in range(image.USED)]
        ev.append((T0 + image.USED, {"r_cwe": 0}))
        for j, k in enumerate(a2):
            ev += [(T0 + j * image.USED + i, {"m_cwe": 1, "m_caddr": (k << 10) | i, "m_wdata": img2[i]})
                   for i in range(image.USED)]
        ev.append((T0 + len(a2) * image.USED, {"m_cwe": 0}))
        t1 = T0 + len(a2) * image.USED + 64        # the first register write of the reference

        def setup(k):
            async def f(drv):
                await drv.udc(36000 - 1000 * k)
                await drv.command(fault_clear=1)
                await drv.write("IQ_REF", 2000 + 3000 * k)
                await drv.write("ID_REF", (-(500 + 1500 * k)) & 0x3FFFF)
                await drv.write("KDC", 65536 - 6000 * k)        # the job axis's registers must be its own
                await drv.write("IQ_HOLD", IQ_HOLD.get(k, 0))   # the job axis's IQ_HOLD drives the core's aw
                await drv.command(coef_swap=int(k in a2))       # decided at the axis's next boundary
                await drv.control(enable=True, run=True, pwm_per_control=PPC)   # the images' period (roms_at_period)
            return f
        ops = [await _ops(setup(k)) for k in range(na)]
        ev += _ref_events(t1, ops)
        for n in range(na):
            ev += _write_events(t1 + n * st, n, ops[n])
        # compare from the clock after every axis's first fault clear (UDC resets to 0: FAULT.dclink is
        # latched from reset until then, and a latched fault ends an axis's comparison); before it every
        # output is off anyway
        ev.append((t1 + (na - 1) * st + WRITE_GAP * len(ops[0]), {"cmp_en": 1}))
        t_end = t1 + (na - 1) * st + periods * P2
        ev.append((t_end, {}))
        await _play(dut, ev)

        mism = [_vec(dut.mism, n) for n in range(na)]
        tm = [_vec(dut.t_mism, n) for n in range(na)]
        nz = [_vec(dut.nz, n) for n in range(na)]
        nz_ref = [_vec(dut.nz_ref, n) for n in range(na)]
        n_ctl = [_vec(dut.n_ctl_ref, n) for n in range(na)]
        dut._log.info(f"NAXES={na} stagger {st}: mismatches {mism} (first {tm}), clocks on {nz}, reference on "
                      f"{nz_ref}, reference control periods {n_ctl}")
        for n in range(na):
            st_ref = await _read(dut, "r", reg["STATUS"], n)
            assert (st_ref >> sbit["running"]) & 1, f"reference {n} not running (STATUS {st_ref:#x}, FAULT " \
                                                     f"{await _read(dut, 'r', reg['FAULT'], n):#x})"
        assert all(x > 0 for x in nz_ref) and all(c >= periods for c in n_ctl), (nz_ref, n_ctl)
        dchg = [_vec(dut.n_duty_chg, n) for n in range(na)]
        words = {}
        for n in range(na):
            words[n] = {w: await _read(dut, "r", reg[w], n) for w in ("U_D", "U_Q", "I_D", "I_Q", "SAT_U", "SAT_LIMIT",
                                                                      "SAT_EBAR_INC", "STATUS")}
        dut._log.info(f"references: duty changes per axis {dchg}; status words {words}")
        assert all(c >= 3 for c in dchg), f"the references' duty does not move: {dchg}"
        assert all(words[n]["SAT_U"] == 0 for n in range(na)), f"a reference's u saturates: {words}"
        assert len({(words[n]["U_D"], words[n]["U_Q"]) for n in range(na)}) == na, f"equal voltages {words}"
        assert all(m == 0 for m in mism), f"axes differ from the shifted reference: {mism} first at {tm}"
        om_bad = [_vec(dut.om_bad, n) for n in range(na)]
        om_chg = [_vec(dut.om_chg, n) for n in range(na)]
        assert all(b == 0 for b in om_bad), f"an axis's held omega differs from the multiplexer form: {om_bad}"
        assert all(c > 0 for c in om_chg), f"an axis's held omega never changed: {om_chg}"
        # the images: the ALG2 axes switched to the uploaded bank (reference and mx_axes), the others not
        for n in range(na):
            m_st = await _read(dut, "m", (n << 8) | reg["STATUS"])
            bank = ((words[n]["STATUS"] >> sbit["coef_bank"]) & 1, (m_st >> sbit["coef_bank"]) & 1)
            assert bank == ((n in a2),) * 2, f"axis {n}: active bank (reference, mx_axes) {bank}"

        # counters at the same local time (mx axis n: PHASE_n clocks after its reference): SAT_EBAR_INC and
        # the control periods ending with aw[0] (|i_q| >= IQ_HOLD, the job axis's register; harness monitors)
        async def snap(port, n, delay):
            if delay:
                await ClockCycles(dut.clk, delay)
            await RisingEdge(dut.clk)
            sfx = "ref" if port == "r" else "mx"
            aw, nc = _vec(getattr(dut, f"n_aw_{sfx}"), n), _vec(dut.n_ctl_ref, n)
            a = reg["SAT_EBAR_INC"] if port == "r" else (n << 8) | reg["SAT_EBAR_INC"]
            return await _read(dut, port, a, n), aw, nc
        cnt = []
        for n in range(na):
            t_r = cocotb.start_soon(snap("r", n, 0))
            t_m = cocotb.start_soon(snap("m", n, n * st))
            cnt.append((await t_r, await t_m))
        dut._log.info(f"algorithm-2 axes {a2}, IQ_HOLD {IQ_HOLD}: (SAT_EBAR_INC, periods with aw[0]) reference / "
                      f"mx_axes per axis {[(r[:2], m[:2]) for r, m in cnt]}, of {[r[2] for r, m in cnt]} periods")
        for n, (r, m) in enumerate(cnt):
            assert r[:2] == m[:2], f"axis {n}: (SAT_EBAR_INC, aw[0] periods) reference {r[:2]} mx_axes {m[:2]}"
            if IQ_HOLD.get(n, 0):
                assert r[0] > 0 and 0 < r[1] < r[2], f"axis {n}: IQ_HOLD acted in {r[1]} of {r[2]} periods"
            else:
                assert r[1] == 0, f"axis {n} (IQ_HOLD 0): aw[0] in {r[1]} periods"
        assert all(x > 2 * P2 for x in nz), f"an axis hardly switched while compared: {nz}"
        assert int(dut.dev.value) == 0, "an axis's comparison ended before the fault"
        assert int(dut.fault_any.value) == 0 and int(dut.ref_fault.value) == 0

        # ---- overcurrent at the last axis's pins ----
        dut.inj.value = 1
        await ClockCycles(dut.clk, 2 * P2)
        fa = int(dut.fault_any.value)
        assert fa == 1 << last, f"fault_any {fa:#x}: only axis {last} may trip"
        f_last = await _read(dut, "m", (last << 8) | reg["FAULT"])
        assert (f_last >> bit["overcurrent"]) & 1, f"axis {last} FAULT {f_last:#x}: no overcurrent"
        for n in range(na - 1):
            assert await _read(dut, "m", (n << 8) | reg["FAULT"]) == 0, f"axis {n} latched a fault"
        off_bad = _vec(dut.off_bad, last)
        assert off_bad == 0, f"axis {last}: {off_bad} clocks with an output on while its fault was latched"
        assert _vec(dut.nz_ref_f, last) > 0, "the shifted reference did not switch during the fault"
        dut.inj.value = 0
        await ClockCycles(dut.clk, P2)
        nz_before = _vec(dut.nz, last)
        ops_clr = await _ops(lambda drv: drv.command(fault_clear=1))
        await _play(dut, _write_events(1, last, ops_clr) + [(3 * P2, {})])
        assert (int(dut.fault_any.value) >> last) & 1 == 0, "the clear did not clear the fault"
        s_last = await _read(dut, "m", (last << 8) | reg["STATUS"])
        assert (s_last >> sbit["bridges_on"]) & 1, f"axis {last} did not restart (STATUS {s_last:#x})"
        assert _vec(dut.nz, last) > nz_before, f"axis {last} does not switch after the clear"
        assert _vec(dut.off_bad, last) == 0
        mism2 = [_vec(dut.mism, n) for n in range(na)]
        assert all(mism2[n] == 0 for n in range(na)), f"mismatches {mism2} (axes other than {last} " \
                                                      f"compared to the end, axis {last} up to its trip)"
        dut._log.info(f"fault at axis {last}: only it tripped, off on every clock of the fault "
                      f"({_vec(dut.nz_ref_f, last)} clocks the reference switched), restarted after the clear; "
                      f"tick {int(dut.tick.value)}")


# C++ -O1 for the model: the build is most of this test (runner.py, opt_fast: 36 -> 24 CPU s, the same 1.1 s simulation)
OPT_FAST = "-O1"


@pytest.mark.cost(59)            # Verilator build at -O1 (three drives' worth of RTL: 0.74 of the -O2 build's 55-75 s) + 94k clocks with the image upload (2 s)
@pytest.mark.parametrize("na", [2, pytest.param(4, marks=[pytest.mark.full, pytest.mark.cost(135)])])   # NAXES = 4: 101k clocks (3 s)
def test_mx_axes_time_shift(na, monkeypatch):
    """NAXES axes against the one-axis drive, each shifted by its carrier phase: every PWM output bit- and
    clock-equal; an overcurrent at one axis's pins switches off that axis only, a clear restarts it."""
    from runner import run
    monkeypatch.setenv("EMPC_ROMS", str(roms_at_period()))
    h = _hdr()
    run(toplevel="mx_axes_tb", test_module="test_mx_axes", sim="verilator", name=f"mx_axes{na}",
        public=ROOT / "tb" / "hdl" / "mx_axes_tb.vlt", timing=True, opt_fast=OPT_FAST,
        parameters={"NAXES": na, "STAGGER": h[f"PWM_STAGGER_{na}"]}, run_name="time_shift",
        extra_env={"MXA_NAXES": str(na), "MXA_PERIODS": "10"}, testcase="time_shift")


MUTANTS = {    # name: (file in rtl/, its text, the mutant's text, the failure the test must report)
    # the engine reads axis 0's registers for every job (the job_axis multiplexer ignored)
    "job_regs": ("mx_axes.v", "        for (ji = 0; ji < NAXES; ji = ji + 1) if (job_axis == ji[AXB-1:0]) begin\n",
                 "        for (ji = 0; ji < NAXES; ji = ji + 1) if (ji == 0) begin\n",
                 "axes differ from the shifted reference"),
    # any axis's overcurrent trips every axis (a shared fault cause)
    "shared_oc": ("mx_axes.v", ".adc_oc(adc_oc[n])", ".adc_oc(|adc_oc)",
                  "only axis 1 may trip"),
    # the core's anti-windup input from axis 0's IQ_HOLD comparison for every job (axis 0: IQ_HOLD 0, off)
    "aw_axis0": ("mx_axes.v", ".aw({st_iq[IW-1], iq_big_v[job_axis]})", ".aw({st_iq[IW-1], iq_big_v[0]})",
                 "axes differ from the shifted reference"),
    # mx_seq hands every job axis 0's held ebar(k-1) (axis 0 runs algorithm 1: its ebar stays 0)
    "ebar_axis0": ("mx_seq.v", "            hq <= zeroed_nx[ax] ? {(2*UW+3*SW){1'b0}} : hold[ax];\n",
                   "            hq <= zeroed_nx[ax] ? {(2*UW+3*SW){1'b0}} : {hold[0][2*UW +: 3*SW], hold[ax][0 +: 2*UW]};\n",
                   "axes differ from the shifted reference"),
}


@pytest.mark.full
@pytest.mark.cost(90)
@pytest.mark.parametrize("mutant", list(MUTANTS))
def test_mx_axes_mutant(mutant, tmp_path, monkeypatch):
    """The time-shift test must fail on a wrong job-axis register multiplexer, a shared fault cause, the
    anti-windup input or the held ebar(k-1) of the wrong axis."""
    import runner
    monkeypatch.setenv("EMPC_ROMS", str(roms_at_period()))
    fname, good, bad, why = MUTANTS[mutant]
    h = _hdr()
    with runner.rtl_mutant(fname, good, bad, tmp_path):
        with pytest.raises((AssertionError, SystemExit)):  # cocotb's runner exits on a failed test
            runner.run(toplevel="mx_axes_tb", test_module="test_mx_axes", sim="verilator",
                       name=f"mx_axes_mutant_{mutant}", public=ROOT / "tb" / "hdl" / "mx_axes_tb.vlt", timing=True,
                       opt_fast=OPT_FAST,
                       parameters={"NAXES": 2, "STAGGER": h["PWM_STAGGER_2"]}, run_name="time_shift",
                       extra_env={"MXA_NAXES": "2", "MXA_PERIODS": "10"}, testcase="time_shift")
    res = runner.results_text(f"mx_axes_mutant_{mutant}", "mx_axes_tb", "time_shift")
    assert why in res, res[-2000:]
