"""Four-axis RTL-in-the-loop motor co-simulation (issue 16): lx_rocon_top at NAXES = 4 (mx_axes, one shared
engine) with four Python plants and four bit-accurate axis models in lockstep.

tb/hdl/cosim4_top.v wraps lx_rocon_top #(.NAXES(4)) and per axis a cosim_axis (g_ax[n].u_ax: encoder,
HALL and ADC pin emulators on the drive's one SCLK / CS, the per-period observation registers under the
names of the one-axis harness tb/hdl/cosim_top.v).  Each axis is one tb/test_closed_loop.py CoSim (plant,
pins, AxisModel, the compare-value and core-input-word checks) bound to its cosim_axis instance and to a
register driver of its axis page; its loop (test_closed_loop.period_loop) wakes at its own period start
(the carriers are staggered by EMPC_PWM_STAGGER_4).  The four loops run at once; the CPU configures the
axes one after the other (the plans do not overlap on the bus, each period's mirrored accesses end before
the axis's ADC trigger, checked), then every axis runs its scenario (AXES):

  axis 0  speed task, algorithm 1, 20 kHz control (Ts = 50 us, CTRL.pwm_per_control = 1): the Ts = 50 us
          design, registers KACC / FW / FW_R2 / IQ_HOLD and governor words of that Ts;
  axis 1  position task, algorithm 2 (uploaded image, bank swap);
  axis 2  position task with a load-torque step (algorithm 2), plant at the robustness box's
          least-damped corner (corner_a of the design's worst damping, empc.corners);
  axis 3  the 20 rad position step of the fault runs, an overcurrent at its ADC pins (one frame, channel 0
          at full scale) and one CMD.fault_clear (test_closed_loop FAULTS["overcurrent"]: pins off within
          the stated latency, STATUS vs pins, FAULT, restart within one PWM period, peak after the restart).

Checked per axis: every PWM period's compare values and every control period's MPC core input words
bit-exact against the model (0 mismatches, the faulted axis included), the latency from the last ADC bit
to the compare values (<= LATENCY_MAX), the status words of the last control period, and (axes 0-2) the
trajectory's RMS error within the one-axis tolerance of the float loop (same Ts, plant and load);
the faulted axis's fault stays on its own pins (the other axes' FAULT read 0 and their compare values stay
exact).  Report: build/reports/closed_loop_4axes.json.

Motors: the build's formats are per build (empc_formats.vh; an image carries the build's fingerprint, which
covers the motor's raw-unit scalings), so every axis runs the BLWR233D; the axes differ in task,
algorithm, control period, load and plant parameters.  The fingerprint does not cover Ts (image layout 4:
the image records its control period in CFG[23:16] instead), so axis 0 uploads the generator's own
Ts = 50 us image (`empc roms --set control.Ts=5e-5 --set inverter.f_pwm=20000`; image_at_ts checks that its
formats and fingerprint are the build's and that the drivers refuse it at the build's 5 PWM periods), after
CTRL.pwm_per_control = 1.  Until its swap the active image is the boot image (5 PWM periods): mpc_core holds
img_ok low (FAULT.coef, checked set), one CMD.fault_clear after the swap; see docs/four_axes.md.
"""
from __future__ import annotations

import dataclasses
import json
import os
import sys
import time
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
ROOT = Path(__file__).resolve().parents[1]
NAXES = 4
DURATION = float(os.environ.get("EMPC_COSIM4_S", "0.040"))   # s of each axis's scenario after its enable
TS_20KHZ = 50e-6               # axis 0's control period: one PWM period at 20 kHz (corners.TS_PWM)
LOAD_AT = 0.025                # axis 2: the load step's time in its profile (the paper scenario's is 0.1 s)
# axis: (name, (paper scenario, s, fault), control period (None: the build's), plant corner (None: nominal),
#        load-step time (None: the scenario's))
AXES = (
    ("speed_20khz", ("speed_steps", DURATION, None), TS_20KHZ, None, None),
    ("position_alg2", ("position_alg2", DURATION, None), None, None, None),
    ("load_step_corner", ("load_step", DURATION, None), None, "corner_a", LOAD_AT),
    ("fault_overcurrent", ("fault_step", DURATION, "overcurrent"), None, None, None),
)
SEED = 4088                    # EMPC_SEED's default; axis n's ADC noise seed is seed + n
# a mutant run (EMPC_COSIM4_MUTANT, make sim-full's test_closed_loop_4axes_mutant, MUTANTS below): "adc_swap" is
# the test's own deliberate error (axis 1's model takes axis 2's ADC sample), any other name an RTL mutant's
# run (no report is written)
MUTANT = os.environ.get("EMPC_COSIM4_MUTANT", "")


def _roms() -> Path:
    return Path(os.environ.get("EMPC_ROMS", ROOT / "build" / "roms" / "default"))


def ts_overrides(ts: float | None) -> dict:
    from empc import corners
    return {} if ts is None else {"control.Ts": ts, "inverter.f_pwm": corners.TS_PWM}


def image_at_ts(ts: float, alg: int, task: str) -> tuple[list, dict]:
    """The generator's own (alg, task) image for control period ``ts`` (what `empc roms --set control.Ts=...`
    writes, its own fingerprint and control period), checked to be accepted by this build: the same
    formats and fingerprint as the build (Ts is not in it), refused only for another CTRL.pwm_per_control
    (the drivers' rule).  Returns the words and what the header constants differ in (all Ts-dependent
    register reset values: image.FMT_EXCLUDE)."""
    from empc import config, design, driver, header, image
    build = header.read(_roms() / "empc_formats.vh")
    base = config.default()
    cfg = config.load(None, ts_overrides(ts)).with_control(algorithm=alg, task=task)
    mine, other = header.flat(base), header.flat(cfg)
    assert mine["IMG_FMT_ID"] == build["IMG_FMT_ID"], "build/roms is not the default configuration's"
    assert {k: header.FORMATS[k] for k in header.FORMATS} == {k: other[k] for k in header.FORMATS}, \
        "the formats differ at this Ts"
    assert other["IMG_FMT_ID"] == build["IMG_FMT_ID"], "the Ts = %g image has another fingerprint" % ts
    diff = sorted(k for k in set(mine) | set(other) if mine.get(k) != other.get(k))
    assert set(diff) <= set(image.FMT_EXCLUDE), diff
    words = image.encode(design.design(cfg, alg, task)["params"], other["IMG_FMT_ID"], period=cfg.pwm_per_control)
    assert image.check(words, cfg.control.N, build["IMG_FMT_ID"], cfg.pwm_per_control) == []
    refused = driver.period_mismatch(words, build["PWM_PER_CONTROL"])
    assert refused, "the drivers would load the Ts = %g image on an axis at the build's period" % ts
    return words, {"image_period_pwm_periods": image.period(words), "header_constants_differ": diff,
                   "refused_at_build_period": refused}


def reset_regs() -> dict:
    """The sequencer registers (ctrl_seq.Regs fields) the four-axis run writes per axis, at their reset values
    (the build's header)."""
    from empc import header
    h = header.read(_roms() / "empc_formats.vh")
    return {"pwm_per_control": h["PWM_PER_CONTROL"], "kacc": h["KACC"], "kacc_shift": h["KACC_SHIFT"],
            "load_shift": h["KACC_LOAD_SHIFT"], "fw_nmax": h["FW_NMAX"], "fw_thr": (h["FW_R2_HI"], h["FW_R2_LO"]),
            "iq_hold": h["IQ_HOLD"]}


try:
    import cocotb
    from cocotb.triggers import ClockCycles, Lock, RisingEdge
    from cocotb.utils import get_sim_time
except ImportError:                     # collection without cocotb: only the pytest wrapper below
    cocotb = None


def pins_at_rest(p, adc_code: int, adc_noise: int = 0) -> None:
    """One axis's pin emulators (tb/hdl/cosim_axis.v) at rest: encoder at 0 without index pulses, HALL of
    angle 0, the three ADC lines at ``adc_code`` without ripple, no injected ADC fault."""
    import test_closed_loop as tcl
    p.enc_target.value = 0
    p.idx_enable.value = 0
    p.hall.value = tcl.hall_code(0.0)
    for i in range(3):
        getattr(p, f"adc_code{i}").value = adc_code
        getattr(p, f"adc_amp{i}").value = 0
    p.adc_seed.value = 12345
    p.adc_noise.value = adc_noise
    for sg in ("adc_inj_en", "adc_inj_tau", "adc_inj_ch", "adc_inj_code", "adc_hold", "adc_lead"):
        getattr(p, sg).value = 0


class LockedBus:
    """The one EMC bus-functional model shared by the four axes' drivers: one access at a time."""

    def __init__(self, bus):
        self.bus, self.lock = bus, Lock()

    async def write(self, addr: int, data: int) -> None:
        async with self.lock:
            await self.bus.write(addr, data)

    async def read(self, addr: int) -> int:
        async with self.lock:
            return await self.bus.read(addr)


def _guard(cs, acts: list) -> list:
    """A plan entry whose mirrored CPU accesses must end before the axis's ADC trigger (half a period after
    its start): the model takes them at that trigger or at the next boundary."""
    t = {}

    async def start():
        t[0] = get_sim_time("ns")

    async def end():
        dt = get_sim_time("ns") - t[0]
        assert dt < cs.P * 10, f"{cs.name}: the configuration accesses of period {cs.period} took {dt} ns"
    return [start, *acts, end] if acts else acts


if cocotb is not None:
    @cocotb.test()
    async def four_axes(dut):
        from empc import config, corners, driver, regmap, robust, scenarios
        from emc_bfm import EmcBfm
        import test_closed_loop as tcl

        seed = int(os.environ.get("EMPC_SEED", str(SEED)))
        dut._log.info("four-axis co-simulation: seed %d, %.0f ms per axis, mutant %r", seed, DURATION * 1e3, MUTANT)
        bfm = EmcBfm(dut, pins=dict(cs_n="cpu_cs_n", oe_n="cpu_oe_n", we_n="cpu_we_n", a="cpu_a", d="cpu_d",
                                    d_oe="cpu_d_oe", bus="emc_d_seen"))
        bus = LockedBus(bfm)
        axes, extra = [], {}
        for n, (name, spec, ts, corner, load_at) in enumerate(AXES):
            sc, alg = scenarios.get(spec[0])
            ov = ts_overrides(ts)
            words, pm, scen = None, None, None
            if ts is not None:
                words, extra[name] = image_at_ts(ts, alg, sc.task)
            if corner is not None:
                cfg = config.load(None, ov or None).with_control(algorithm=alg, task=sc.task)
                f = corners.plant_factors(cfg, alg, sc.task, corner)
                pm = robust.perturbed(cfg.motor, f)
                extra[name] = dict(extra.get(name, {}), plant=corner, plant_factors=f)
            if load_at is not None:
                tq = sc.load(1e9)
                scen = dataclasses.replace(sc, load=lambda t, tq=tq, at=load_at: tq if t >= at else 0.0,
                                           description=f"{sc.description.split(', then')[0]}, then a {tq:.4g} N m "
                                                       f"load-torque step at {load_at * 1e3:.0f} ms")
                extra[name] = dict(extra.get(name, {}), load_torque_nm=tq, load_at_s=load_at)
            cs = tcl.CoSim(dut.g_ax[n].u_ax, name, spec=spec, overrides=ov, image_words=words, plant_motor=pm,
                           scenario=scen, seed=seed + n)
            # the model's sequencer registers as after reset (the build's header values) until the CPU writes
            # the axis's own (the regs action below): they act with the law off too (speed estimate)
            cs.want = dataclasses.replace(cs.regs)
            for k, v in reset_regs().items():
                setattr(cs.regs, k, v)
            axes.append((cs, driver.Drive(bus, axis=n)))

        # reset and the pins at rest; the decoders settle, then the first index pulses align the angles
        dut.pwr_fault_n.value = 1
        dut.rst_n.value = 0
        off = axes[0][0].cfg.sensors.adc_offset
        for cs, _ in axes:
            pins_at_rest(cs.dut, off, cs.adc_noise)
        bfm.idle()
        await ClockCycles(dut.clk, 20)
        dut.rst_n.value = 1
        await ClockCycles(dut.clk, 3000)
        for cs, _ in axes:
            cs.dut.idx_enable.value = 1
        drv0 = axes[0][1]
        assert await drv0.read("ID") == regmap.ID_MAGIC, "bus or bitstream: ID register"
        caps = await drv0.read("CAPS")
        assert caps & 0xF == NAXES, f"CAPS {caps:#x}: not a {NAXES}-axis build"

        if MUTANT == "adc_swap":         # the deliberate error: axis 1's model fed axis 2's ADC sample
            a1, a2 = axes[1][0], axes[2][0]
            orig = a1.end_period

            def end_period():
                a1.sampled = (a2.sampled[0], a1.sampled[1])
                orig()
            a1.end_period = end_period

        coef_bit = {f.name: f.lsb for f in regmap.axis_reg("FAULT").fields}["coef"]
        wall0, cpu0 = time.perf_counter(), time.process_time()
        plans, kicks = [], []
        for cs, drv in axes:
            plan, kick = tcl.config_plan(cs, bus, drv, regcheck=False)

            async def regs(cs=cs, drv=drv):
                # the sequencer registers of the axis's configuration (regs_for: those of its Ts) and
                # CTRL.pwm_per_control (drive off), read back; the model takes them at this period's trigger
                r = cs.want
                vals = {"CTRL": driver.field_value("CTRL", enable=0, run=0, pwm_per_control=cs.M),
                        "KACC": driver.field_value("KACC", kacc=r.kacc & 0x3FFFF, load_shift=r.load_shift,
                                                   shift=r.kacc_shift),
                        "FW": driver.field_value("FW", nmax=r.fw_nmax),
                        "FW_R2": driver.field_value("FW_R2", hi=r.fw_thr[0], lo=r.fw_thr[1]), "IQ_HOLD": r.iq_hold}
                for k, v in vals.items():
                    await drv.write(k, v)
                for k, v in vals.items():
                    got = await drv.read(k)
                    assert got == v, f"{cs.name} {k}: read {got:#x}, wrote {v:#x}"
                    cs.reg_checks += 1
                for k in reset_regs():
                    setattr(cs.regs, k, getattr(r, k))
            plan.insert(1, [regs])
            if cs.M != reset_regs()["pwm_per_control"]:
                async def coef_clear(cs=cs, drv=drv):
                    # from the CTRL write above until the swap the active image was the boot image, of the build's
                    # control period: FAULT.coef (mpc_core img_ok needs the active image's period = CTRL.
                    # pwm_per_control; the bridges were off); the swapped image is of this period: one clear
                    f = await drv.read("FAULT")
                    assert (f >> coef_bit) & 1, f"{cs.name}: FAULT {f:#x}: the control-period mismatch was not seen"
                    await drv.command(fault_clear=1)
                    f2 = await drv.read("FAULT")
                    assert f2 == 0, f"{cs.name}: FAULT {f2:#x} after the clear (image of period {cs.M} active)"
                    extra[cs.name]["fault_while_boot_image_at_other_period"] = f
                k = next(i for i, acts in enumerate(plan) if acts and getattr(acts[0], "__name__", "") == "ref_setup")
                plan.insert(k, [coef_clear])
            plans.append([_guard(cs, acts) for acts in plan])
            kicks.append(kick)
        # the axes are configured one after the other: axis n's plan starts when axis n-1's has ended
        offs = [sum(len(p) for p in plans[:n]) for n in range(NAXES)]
        n_run = int(round(DURATION / axes[0][0].Tpwm))
        k_end = offs[-1] + len(plans[-1]) + n_run            # every axis runs until the last one's run ends

        async def axis_run(n):
            cs, drv = axes[n]
            await tcl.lockstep_start(cs)
            plan = [[] for _ in range(offs[n])] + plans[n]
            fr = await tcl.period_loop(cs, drv, plan, kicks[n], k_end - len(plan))
            t = (time.perf_counter(), time.process_time())
            try:                         # (a failure here must not stop the other axes' loops)
                status, err = await tcl.final_status(cs, drv), None
            except AssertionError as e:
                status, err = None, f"final status: {e}"
            return {"cs": cs, "fault": fr, "status": status, "status_error": err, "t_end": t}
        tasks = [cocotb.start_soon(axis_run(n)) for n in range(NAXES)]
        res = [await t for t in tasks]
        wall = max(r["t_end"][0] for r in res) - wall0
        cpu = max(r["t_end"][1] for r in res) - cpu0
        faults = {n: (r["status"] or {}).get("FAULT") for n, r in enumerate(res)}
        out, errors = [], []
        for n, r in enumerate(res):
            r["wall"], r["cpu"] = wall, cpu
            cs = r["cs"]
            summary = {"axis": n, "name": cs.name, "paper_scenario": cs.sc.name, "task": cs.sc.task,
                       "algorithm": cs.params.algorithm, "Ts_us": cs.cfg.control.Ts * 1e6,
                       "pwm_per_control": cs.M, "fault_injection": cs.fault, **extra.get(cs.name, {}),
                       "pwm_periods": cs.period, "compare_sets_checked": cs.checked,
                       "mismatches": len(cs.mismatches), "core_input_word_sets_checked": cs.words_checked,
                       "core_input_word_mismatches": len(cs.word_mismatches),
                       "latency_last_adc_bit_to_cmp_load_max_cycles": cs.lat_bit}
            try:
                if r["status_error"]:
                    mism = f"compare values or core input words differ from the model: {len(cs.mismatches)} " \
                           f"compare-value mismatches (first {cs.mismatches[:2]}), {len(cs.word_mismatches)} " \
                           f"core input word sets (first {cs.word_mismatches[:1]}); " \
                        if cs.mismatches or cs.word_mismatches else ""
                    raise AssertionError(mism + r["status_error"])
                rep, _ = tcl.check_run(cs, r)
                if cs.fault is None:
                    summary.update(rms_error=rep["metrics"]["rms_error"],
                                   rms_error_float=rep["float_metrics"]["rms_error"],
                                   rms_error_rtl_vs_float_rel=rep["rms_error_rtl_vs_float_rel"])
                else:
                    summary["fault"] = rep["fault"]
                # a fault stays on its axis: the others' FAULT read 0 at the end
                assert cs.fault is not None or faults[n] == 0, f"axis {n}: FAULT {faults[n]:#x}"
            except AssertionError as e:
                errors.append(f"axis {n} ({cs.name}): {e}")
                rep = {"error": str(e)}
                summary["error"] = str(e)
            summary["detail"] = rep
            out.append(summary)
        sim_ms = k_end * axes[0][0].Tpwm * 1e3
        report = {"naxes": NAXES, "seed": seed, "mutant": MUTANT or None, "simulated_ms": sim_ms,
                  "wall_s": wall, "cpu_s": cpu, "sim_ms_per_cpu_s": sim_ms / cpu,
                  "load_avg_1min": os.getloadavg()[0], "latency_max_cycles": tcl.LATENCY_MAX,
                  "axes": out}
        for s in out:
            dut._log.info("axis %d %-18s %5d periods, %5d compare sets, %d mismatches, %d word mismatches, "
                          "latency %s clk, RMS error %s (float %s, rel %s)%s", s["axis"], s["name"], s["pwm_periods"],
                          s["compare_sets_checked"], s["mismatches"], s["core_input_word_mismatches"],
                          s["latency_last_adc_bit_to_cmp_load_max_cycles"], s.get("rms_error"),
                          s.get("rms_error_float"), s.get("rms_error_rtl_vs_float_rel"),
                          f"; ERROR {s['error']}" if "error" in s else "")
        dut._log.info("%.1f ms simulated in %.1f s wall, %.1f s CPU", sim_ms, wall, cpu)
        if not MUTANT:
            tcl.REPORTS.mkdir(parents=True, exist_ok=True)
            (tcl.REPORTS / "closed_loop_4axes.json").write_text(json.dumps(report, indent=1, default=float) + "\n")
        assert not errors, "; ".join(errors)


def _run(mutant: str = "", name: str = "cosim4", run_name: str = "four_axes"):
    from runner import run
    import test_closed_loop as tcl
    run(toplevel="cosim4_top", test_module="test_closed_loop_4axes", sim="verilator", name=name,
        public=ROOT / "tb" / "hdl" / "cosim4_top.vlt", timing=True,
        parameters={"NAXES": NAXES, "CLK_HALF_PS": tcl.CLK_PERIOD_NS * 500}, defines={"EMPC_SIM_GATE": 1},
        run_name=run_name, extra_env={"EMPC_COSIM4_MUTANT": mutant}, testcase="four_axes",
        opt_fast="-O1")     # C++ -O1 (tb/runner.py opt_fast): build 44 -> 26 CPU s, the same 29 CPU s of simulation


# Verilator build of the four-axis top (70-115 s at -O2; -O1: 26 instead of 44 CPU s idle) + 44 ms of four axes (23-42 s);
# the mark stays above position_alg1/2's so that make sim's first tests are unchanged (the PGO build's lock)
@pytest.mark.cost(130)
def test_closed_loop_4axes():
    """Four axes on one engine, four plants and four bit-accurate models: every compare value of every axis
    bit-exact, each trajectory within the one-axis float tolerance, a fault on one axis only (AXES)."""
    _run()


# The run must fail on (mutant: RTL change from test_mx_axes.MUTANTS or None, what results.xml must say):
MUTANTS = {
    # the test's own deliberate error: axis 1's model fed axis 2's ADC sample (the same build)
    "adc_swap": (None, "axis 1 (position_alg2): compare values or core input words differ"),
    # the engine reads axis 0's registers for every job (axis 0 runs at Ts = 50 us: KACC, KACC_SHIFT and the
    # control-period count differ); its own build
    "job_regs": ("job_regs", "axis 1 (position_alg2): compare values or core input words differ"),
}


@pytest.mark.full
@pytest.mark.parametrize("mutant", [pytest.param("adc_swap", marks=pytest.mark.cost(45)),
                                    pytest.param("job_regs", marks=pytest.mark.cost(150))])
def test_closed_loop_4axes_mutant(mutant, tmp_path):
    """The four-axis run must fail on a deliberate error in its own checking (adc_swap) and on an engine that
    reads the wrong axis's registers (job_regs), naming the axis."""
    import contextlib
    import runner
    import test_mx_axes
    rtl, why = MUTANTS[mutant]
    name = "cosim4" if rtl is None else f"cosim4_mutant_{mutant}"
    ctx = runner.rtl_mutant(*test_mx_axes.MUTANTS[rtl][:3], tmp_path) if rtl else contextlib.nullcontext()
    with ctx:
        with pytest.raises((AssertionError, SystemExit)):   # cocotb's runner exits on a failed test
            _run(mutant, name=name, run_name=f"mutant_{mutant}")
    res = runner.results_text(name, "cosim4_top", f"mutant_{mutant}")
    assert why in res, res[-2000:]
