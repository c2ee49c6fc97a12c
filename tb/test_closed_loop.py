"""RTL-in-the-loop motor co-simulation of the whole drive (lx_rocon_top, one axis).

The Python PMSM model (gen/empc/pmsm.py) drives the encoder (tb/hdl/quad_gen.v,
a target count per half PWM period), the HALL pins and the ADC SPI slave
(tb/hdl/adc_spi_slave.v, phase-current codes per period), and reads the compare
values the drive loads every PWM period.  The CPU side is the EMC bus-functional
model (tb/emc_bfm.py) through the register-map driver (gen/empc/driver.py).

In lockstep, the bit-accurate axis model (gen/empc/bitloop.py AxisModel: sequencer
with front end, MPC core and modulation, gen/empc/rtlmodel/ctrl_seq.py, and the
reference generator's model) sees the same inputs at every ADC trigger and, like the
RTL's sequencer (rtl/mx_seq.v), decides the period's kind and advances the references
at the PWM boundary before the sample (AxisModel.boundary); every
compare value the RTL loads must equal the model's (bit-exact).  The resulting
trajectory is also compared with the float closed loop (closedloop.py, fitted
gains) within the stated tolerance.  Reports: build/reports/closed_loop_<scenario>.{json,png}.

Speed (issue 17): Verilator sees only cosim_top's ports through VPI (tb/hdl/cosim_top.vlt),
cosim_top runs the clock (--timing), and Python wakes once per PWM period, at its start
(CoSim.end_period / begin_period); the harness registers what happens inside the period.
COSIM is the scenario table; every entry not in SOAK is one pytest test of make sim.
"""
from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path

import numpy as np
import pytest

import cocotb
from cocotb.triggers import ClockCycles, RisingEdge, ReadOnly

from empc import closedloop as cl
from empc import bitloop, config, driver, header, image, pmsm, regmap, scenarios
from empc import formats as F
from empc.bitloop import AxisModel
from empc.rtlmodel.hall_decoder import DEFAULT_SEQUENCE
from empc.rtlmodel.ref_gen import GOV_FIELD, RefGen, gov_words, segments_from_points

ROOT = Path(__file__).resolve().parents[1]
REPORTS = ROOT / "build" / "reports"
CLK_PERIOD_NS = 10                    # fabric clock (100 MHz); the PLL model passes it through
LATENCY_MAX = 300                     # clocks from the last ADC bit to the compare values (issue 16 item 3)

# Co-simulation scenarios: (paper scenario, simulated seconds, fault injection or None)
COSIM = {
    "short": ("position_alg2", 0.080, None),
    "overcurrent": ("position_alg2", 0.030, "overcurrent"),
    "encoder": ("position_alg2", 0.030, "encoder"),
    "watchdog": ("position_alg2", 0.040, "watchdog"),
    "position_alg1": ("position_alg1", 0.70, None),
    "position_alg2": ("position_alg2", 0.70, None),
    "speed_steps": ("speed_steps", 0.40, None),
    "load_step": ("load_step", 0.30, None),
    # issue 15: the current limit (reference governor) and field weakening (1.35 x base speed)
    "speed_limit": ("speed_limit", 0.30, None),
    "field_weakening": ("field_weakening", 0.56, None),
    # make sim-full (SOAK): algorithm 2 on the speed task, and 2 s of position_alg2 (1.3 s of hold at 0 after the profile)
    "speed_alg2": ("speed_alg2", 0.40, None),
    "soak": ("position_alg2", 2.0, None),
}


def hall_code(theta_e: float) -> int:
    s = int((theta_e % (2 * math.pi)) // (math.pi / 3))
    return DEFAULT_SEQUENCE[s]


class CoSim:
    """One co-simulation run: the plant, its pins, and the axis model the RTL is checked against.

    Python wakes once per PWM period, at the period start (:meth:`end_period` of the period
    that just ended, then :meth:`begin_period` of the new one); the harness (tb/hdl/cosim_top.v)
    registers what happened inside the period (compare values loaded, latency, run flag at the
    trigger).  The pins change at the same instants as when Python waited for each event.
    """

    def __init__(self, dut, name: str):
        self.dut = dut
        self.name = name
        scen_name, self.duration, self.fault = COSIM[name]
        self.sc, alg = scenarios.get(scen_name)
        self.cfg = config.default().with_control(algorithm=alg, task=self.sc.task)
        c = self.cfg.control
        self.M = self.cfg.pwm_per_control
        self.P = self.cfg.pwm_half_period
        self.Tpwm = 1.0 / self.cfg.inverter.f_pwm
        self.plant = pmsm.Plant(self.cfg.motor, self.cfg.inverter.Udc, self.cfg.inverter.f_pwm, substeps=4)
        self.sensors = pmsm.Sensors(self.cfg)
        roms_dir = Path(os.environ.get("EMPC_ROMS", ROOT / "build" / "roms" / "default"))
        self.image = image.read_hex(roms_dir / f"coef_alg{alg}_{self.sc.task}.hex")
        self.boot = image.decode(image.read_hex(roms_dir / "coef_boot.hex"))
        self.params = image.decode(self.image)
        # the bit-accurate axis (gen/empc/bitloop.py), fed with what the RTL's trigger sampled; its
        # registers as after reset (header values, the law off until enabled); CPU writes are
        # mirrored into regs / seq / ref by the actions that make them
        self.axis = AxisModel(self.cfg, self.boot, refgen=RefGen(c.N),
                              regs=bitloop.regs_for(self.cfg, self.sc.task, run=False))
        self.regs, self.seq, self.ref = self.axis.regs, self.axis.seq, self.axis.ref
        gp = bitloop.gov_params(self.cfg, self.sc.task)          # the governor words the CPU writes
        self.ref.write_gov(gp["vmax"], gp["a"], gp["ksh"], gp["enable"])
        self.gov = gp
        unit = 1.0 / (self.cfg.rad_per_count if self.sc.task == "position" else self.cfg.rad_s_per_count_ts)
        self.ref_unit = unit
        self.slots = segments_from_points(scenarios.POINTS[self.sc.name], unit, c.Ts)
        self.cmp_rtl = (0, 0, 0)
        self.mismatches = []
        self.checked = 0
        self.lat_max = {"control": 0, "modulation": 0}   # adc_trig -> cmp_load, clock cycles
        self.lat_bit = {"control": 0, "modulation": 0}   # last ADC SCLK rising edge -> cmp_load
        self.lat_valid = {"control": 0, "modulation": 0}  # ADC valid -> cmp_load
        self.rec = {k: [] for k in ("t", "i_d", "i_q", "w_e", "theta_e", "u_d", "u_q", "ref", "ipk")}
        self.period = 0
        self.t = 0.0
        self.inject = False
        self.started = False       # SEG_START written: the next control period takes the profile
        self.reg_checks = 0
        self.t_profile0 = None     # sim time of profile time 0 (see end_period)
        self.duties = None         # duties of the running period (None: bridges off)
        self.sampled = None        # (ADC codes, encoder count) the running period's trigger samples
        self.py_cpu = 0.0          # CPU seconds in the per-period Python (plant, pins, axis model, check)
        self.lockstep = hasattr(dut, "dbg_ls_errors")   # COSIM_LOCKSTEP build: gated vs ungated MPC core

    @property
    def last_control(self):
        """Model outputs of the last control period (status words)."""
        return self.axis.last_control

    @property
    def u_applied(self):
        return self.axis.u

    # ------------------------------------------------------------------ pins
    def drive_plant_pins(self):
        st = self.plant.state
        codes = self.sensors.adc_codes(self.plant.phase_currents())
        if self.fault == "overcurrent" and self.inject:
            codes = [4095, codes[1], codes[2]]
        count = self.sensors.encoder_count(st.theta_e)
        self.dut.enc_target.value = count & 0xFFFFFFFF
        self.dut.adc_code0.value = codes[0]
        self.dut.adc_code1.value = codes[1]
        self.dut.adc_code2.value = codes[2]
        self.dut.hall.value = hall_code(st.theta_e)
        return codes, count

    # ------------------------------------------------------------------ one PWM period
    async def begin_period(self, actions):
        """At the period start: the duties of this period, the CPU accesses of its first half
        (mirrored in the model), the plant to the period centre, the pins the trigger samples."""
        bridges_on = int(self.dut.pwm_en.value) == 0b111
        self.duties = np.array(self.cmp_rtl, dtype=float) / self.P if bridges_on else None
        # the boundary before the sample: the period's kind, the references advance (before this
        # half period's CPU commands, which the next advance takes)
        if self.axis.boundary() and self.started and self.t_profile0 is None:
            # this advance loads the profile's first value into the head w_{k+N}: the
            # sample instant (half a period from now) is profile time -N Ts
            self.t_profile0 = self.t + 0.5 * self.Tpwm + self.cfg.control.N * self.cfg.control.Ts
        for act in actions:
            await act()
        c0 = time.process_time()
        self._plant_half(self.duties)
        self.sampled = self.drive_plant_pins()
        self.py_cpu += time.process_time() - c0

    def end_period(self):
        """At the next period start: the period's compare values (registered by the harness at
        cmp_load) against the axis model fed with the trigger's samples, then the plant's second half."""
        c0 = time.process_time()
        dut = self.dut
        if self.lockstep and int(dut.dbg_ls_errors.value):
            raise AssertionError(f"period {self.period}: the gated MPC core differs from its ungated copy in "
                                 f"{int(dut.dbg_ls_errors.value)} clocks, first at lockstep clock "
                                 f"{int(dut.dbg_ls_first.value)} (EMPC_SIM_GATE in rtl/mpc_core.v)")
        n_trig, n_load = int(dut.dbg_n_trig.value), int(dut.dbg_n_load.value)
        lat = int(dut.dbg_lat_q.value)
        assert n_trig == 1 and n_load == 1 and lat < self.P, \
            f"period {self.period}: {n_trig} ADC triggers, {n_load} compare loads, load {lat} clocks after the trigger"
        self.regs.run = bool(int(dut.dbg_run_trig.value))
        control = self.axis.control_next                 # decided at the period's start (boundary)
        codes, count = self.sampled
        out = self.axis.period(count, codes)
        kind = "control" if control else "modulation"
        self.lat_max[kind] = max(self.lat_max[kind], lat)
        self.lat_bit[kind] = max(self.lat_bit[kind], int(dut.dbg_lat_bit_q.value))
        self.lat_valid[kind] = max(self.lat_valid[kind], int(dut.dbg_lat_valid_q.value))
        v = int(dut.dbg_cmp_q.value)
        self.cmp_rtl = tuple((v >> (12 * i)) & 0xFFF for i in range(3))
        self.checked += 1
        if self.cmp_rtl != tuple(out["cmp"]):
            self.mismatches.append((self.period, self.cmp_rtl, tuple(out["cmp"])))
            if len(self.mismatches) == 1:
                dut._log.error("first mismatch, period %d (%s): RTL cmp %s, model %s; trigger samples: count %d, "
                               "ADC codes %s, run %s; model %s", self.period, kind, self.cmp_rtl, tuple(out["cmp"]),
                               count, list(codes), self.regs.run,
                               {k: v for k, v in out.items() if k not in ("cmp", "core", "ref_w")})
                if "core" in out:
                    dut._log.error("model core %s; references %s", out["core"], out["ref_w"])
        self._plant_half(self.duties)
        if control:
            st = self.plant.state
            vpu = self.cfg.volts_per_tick / 256
            self.rec["t"].append(self.t - 0.5 * self.Tpwm)
            for k, val in (("i_d", st.i_d), ("i_q", st.i_q), ("w_e", st.w_e), ("theta_e", st.theta_e),
                           ("u_d", self.axis.u[0] * vpu), ("u_q", self.axis.u[1] * vpu)):
                self.rec[k].append(val)
            self.rec["ipk"].append(float(np.max(np.abs(self.plant.phase_currents()))))
            w0 = out["ref_w"][0]
            self.rec["ref"].append((w0 - (1 << 64) if w0 >> 63 else w0) / 2.0 ** 32 / self.ref_unit)
        self.period += 1
        self.py_cpu += time.process_time() - c0

    def _plant_half(self, duties):
        if duties is None:           # bridges off: currents decay through the diodes, motor coasts
            self.plant.state.i_d = 0.0
            self.plant.state.i_q = 0.0
            self.plant.step(0.5 * self.Tpwm, [0.0, 0.0, 0.0])
            self.plant.state.i_d = 0.0
            self.plant.state.i_q = 0.0
        else:
            if self.sc.load is not None and self.t_profile0 is not None:
                self.plant.tau_load = self.sc.load(self.t - self.t_profile0)
            self.plant.step(0.5 * self.Tpwm, duties)
        self.t += 0.5 * self.Tpwm


async def check_global_regs(dut, bus, drv) -> None:
    """Global register read path (lx_rocon_top): constants, RW readback, TIME, and that the
    axis and coefficient-window addresses do not leak into a global read."""
    roms = Path(os.environ.get("EMPC_ROMS", ROOT / "build" / "roms" / "default"))
    h = header.read(roms / "empc_formats.vh")
    assert await drv.read("VERSION") == regmap.VERSION
    caps = 1 | (h["N"] << 4) | (h["IMG_LAYOUT"] << 8) | (h["PWM_PER_CONTROL"] << 16)
    assert await drv.read("CAPS") == caps
    assert await drv.read("PWM_HALF") == h["PWM_HALF_PERIOD"]
    assert await drv.read("WDOG_TIMEOUT") == next(r.reset for r in regmap.GLOBAL if r.name == "WDOG_TIMEOUT")
    rng = np.random.default_rng(2026)
    for v in (0xFFFFFFFF, 0x0, int(rng.integers(0, 2**32)), 0xA5A5A5A5):
        await drv.write("SCRATCH", v)
        assert await drv.read("SCRATCH") == v
        assert await drv.read("ID") == regmap.ID_MAGIC          # no SCRATCH bits in another read
    await drv.write("SCRATCH", 0)
    for v in (3, 1, 2):
        await drv.write("IRQ_ENABLE", v | 0xFFFFFFFC)
        assert await drv.read("IRQ_ENABLE") == v
    await drv.write("IRQ_ENABLE", 0)
    t0 = await drv.read("TIME")
    await ClockCycles(dut.clk, 2 * 2 * h["PWM_HALF_PERIOD"])
    assert (await drv.read("TIME") - t0) in (2, 3), "TIME counts PWM periods"
    assert await bus.read(regmap.COEF_BASE) == 0, "the coefficient window is write-only (reads 0)"


async def run_cosim(dut, name: str) -> dict:
    cs = CoSim(dut, name)
    from emc_bfm import EmcBfm
    bus = EmcBfm(dut, pins=dict(cs_n="cpu_cs_n", oe_n="cpu_oe_n", we_n="cpu_we_n", a="cpu_a", d="cpu_d",
                                d_oe="cpu_d_oe", bus="emc_d_seen"))
    drv = driver.Drive(bus)
    dut.rst_n.value = 0
    dut.enc_target.value = 0
    dut.idx_enable.value = 0
    dut.mark.value = 0
    dut.enc_glitch.value = 0
    dut.hall.value = hall_code(0.0)
    off = cs.cfg.sensors.adc_offset
    for i in range(3):
        getattr(dut, f"adc_code{i}").value = off
    bus.idle()
    await ClockCycles(dut.clk, 20)
    dut.rst_n.value = 1
    # decoders settle (HALL debounce), then the first index pulse aligns the angle at count 0
    await ClockCycles(dut.clk, 3000)
    dut.idx_enable.value = 1
    assert await drv.read("ID") == regmap.ID_MAGIC, "bus or bitstream: ID register"
    await check_global_regs(dut, bus, drv)
    wall0 = time.perf_counter()
    cpu0 = time.process_time()
    # lockstep from the first PWM period after alignment: the sequencer's state so far is known
    # (disabled, zero currents: every control period just shifted its counter), take it over
    await RisingEdge(dut.dbg_period_start)
    await ReadOnly()
    cs.seq.per_cnt = int(dut.dbg_per_cnt.value)
    cs.seq.first = False
    await RisingEdge(dut.clk)           # the loop's first period begins one clock after this boundary

    async def w(name, value):
        await drv.write(name, value)

    # configuration, one short burst of CPU writes per PWM period, mirrored in the model
    plan = []
    words = cs.image
    if cs.params != cs.boot:
        chunk = 100
        for a0 in range(0, image.USED, chunk):
            async def up(a0=a0):
                base = regmap.COEF_BASE
                for a in range(a0, min(image.USED, a0 + chunk)):
                    await bus.write(base + a, words[a])
            plan.append([up])

        async def swap():
            await drv.command(coef_swap=1)
        plan.append([swap])

        async def check_swap():
            st = await drv.read("STATUS")
            assert (st >> 7) & 1 == 0, "coefficient swap still pending while the core is idle"
            cs.seq.params = cs.params
        plan.append([check_swap])

    async def ref_setup():
        await drv.command(ref_sync=1)         # head = measured position (0) / speed (0)
        cs.ref.sync(0)
    plan.append([ref_setup])

    async def gov_setup():
        # the reference governor's words for the scenario's task (the bitstream holds the boot
        # task's): SEG_GOV = field 7 of slot SEG_ADDR, read back (the model has them already)
        for slot, word in gov_words(cs.gov["vmax"], cs.gov["a"], cs.gov["ksh"], cs.gov["enable"]).items():
            await w("SEG_ADDR", slot)
            await w("SEG_GOV", word)
            got = await drv.read("SEG_GOV")
            assert got == word == cs.ref.read_field(slot, GOV_FIELD), f"governor word of slot {slot}: {got:#x}"
            cs.reg_checks += 1
    plan.append([gov_setup])

    async def regcheck():
        # RW registers read back in the format of the register map (width mask, sign extension,
        # fields): random words written and read back, then the run's values restored (all
        # before this period's trigger; these registers do not stop the drive)
        rng = np.random.default_rng(cs.period + 17)
        names = ("DEAD_TIME", "KDC", "ID_REF", "IQ_REF", "KACC", "SEG_ADDR")
        keep = {}
        for n in names:
            keep[n] = await drv.read(n)
        for n in names:
            reg = regmap.axis_reg(n)
            for v in [0xFFFFFFFF, 0x0002FF00, int(rng.integers(0, 2**32))]:
                await w(n, v)
                got = await drv.read(n)
                assert got == reg.readback(v), f"{n}: wrote {v:#x}, read {got:#x}, expected {reg.readback(v):#x}"
                cs.reg_checks += 1
            await w(n, keep[n])
            assert await drv.read(n) == keep[n]
        # the co-simulation never writes these three: they still hold their reset values
        assert all(keep[n] == regmap.axis_reg(n).reset for n in ("KDC", "ID_REF", "DEAD_TIME")), keep
    plan.append([regcheck])
    for i, s in enumerate(cs.slots):
        async def wslot(i=i, s=s):
            await w("SEG_ADDR", i)
            for n, v in s.regs().items():
                await w(n, v)
            for n, v in s.regs().items():         # each field reads back from slot SEG_ADDR
                got = await drv.read(n)
                assert got == v, f"slot {i} {n}: read {got:#x}, wrote {v:#x}"
                cs.reg_checks += 1
            cs.ref.write_slot(i, s)
        plan.append([wslot])

    async def kick():
        await drv.kick()

    async def enable():
        await w("SEG_START", 0)
        cs.ref.start(0)
        cs.started = True
        await drv.control(enable=True, run=True, pwm_per_control=cs.M)
    plan.append([kick, enable])
    n_periods = int(round(cs.duration / cs.Tpwm))
    fault_at = n_periods // 3
    fault_seen = None
    for k in range(len(plan) + n_periods + 1):
        if k > 0:                              # one wake-up per PWM period
            await RisingEdge(dut.dbg_period_start)
            cs.end_period()
            if cs.fault and fault_seen is None and int(dut.dbg_trip.value):
                fault_seen = cs.period
                # from here the drive must keep every bridge off
            if fault_seen is not None:
                assert int(dut.pwm_en.value) == 0 and int(dut.pwm_out.value) == 0, \
                    f"outputs not safe {cs.period - fault_seen} periods after the fault"
            assert not int(dut.dbg_unsafe.value), f"period {cs.period}: a bridge or PWM output on after a trip"
            if cs.mismatches and cs.fault is None:
                break
        if k == len(plan) + n_periods:
            break
        acts = list(plan[k]) if k < len(plan) else []
        if k % 100 == 50 and not (cs.fault == "watchdog" and k >= fault_at):
            acts.append(kick)
        if cs.fault == "overcurrent" and k == fault_at:
            cs.inject = True
        if cs.fault == "encoder" and k == fault_at:
            async def glitch():
                for _ in range(5):             # both channels toggle in one sample: illegal transitions
                    dut.enc_glitch.value = 1
                    await ClockCycles(dut.clk, 40)
                    dut.enc_glitch.value = 0
                    await ClockCycles(dut.clk, 40)
            acts.append(glitch)
        await cs.begin_period(acts)
    wall = time.perf_counter() - wall0
    cpu = time.process_time() - cpu0
    if cs.mismatches:
        dut._log.error("first mismatches (period, RTL cmp, model cmp): %s", cs.mismatches[:5])
    # read back status over the bus
    status = {n: await drv.read(n) for n in ("STATUS", "FAULT", "LATENCY", "PERIODS", "SAT_LIMIT", "SAT_EBAR_INC",
                                              "SAT_WN", "SAT_OPERAND", "SAT_TERM", "SAT_ACC", "SAT_DU", "SAT_U",
                                              "SAT_FRONT", "CNT_ADC_MISS", "CNT_ENC_ERR", "CNT_OVERRUN")}
    # status words of the last control period (and the u applied) against the model
    lc = cs.last_control
    m32 = 0xFFFFFFFF
    ref_sh = 32 - (F.TH_FRAC if cs.sc.task == "position" else F.W_FRAC)   # REF: the Q.32 word in the core's unit
    exp = {"I_D": lc["i_d"] & m32, "I_Q": lc["i_q"] & m32, "SPEED": lc["omega"] & m32,
           "U_D": cs.u_applied[0] & m32, "U_Q": cs.u_applied[1] & m32, "REF": (lc["ref_w0"] >> ref_sh) & m32}
    got = {n: await drv.read(n) for n in exp}
    assert got == exp, f"status words {got} model {exp}"
    cs.reg_checks += len(exp)
    # CMD.clear_counters: the counters read 0 at once (and stay 0 once zeroed)
    await drv.command(clear_counters=1)
    for n in ("PERIODS", "SAT_OPERAND", "SAT_EBAR_INC", "SAT_LIMIT"):
        assert await drv.read(n) == 0, f"{n} not cleared"
    await ClockCycles(dut.clk, 4000)
    for n in ("PERIODS", "SAT_OPERAND", "SAT_EBAR_INC", "SAT_LIMIT", "CNT_OVERRUN"):
        assert await drv.read(n) < 2, f"{n} not zeroed"
    cs.reg_checks += 9
    return {"cs": cs, "wall": wall, "cpu": cpu, "status": status, "fault_seen": fault_seen}


def metrics_report(cs: CoSim, res: dict) -> dict:
    rec = {k: np.array(v) for k, v in cs.rec.items()}
    # Control samples lie on the Ts grid of the profile; rounding removes the float error of the
    # accumulated simulation time, which would otherwise decide on which side of a step edge
    # (steps sit on grid points) a sample falls.
    Ts = cs.cfg.control.Ts
    t = np.round((rec["t"] - cs.t_profile0) / Ts) * Ts
    sel = t >= 0
    prof = cs.sc.profile
    ref = np.array([prof(x) for x in t[sel]])
    # The task-output reference is the w_k the RTL's reference generator actually applied: with the
    # governor off it must equal the profile except at step edges (one sample each, by the same
    # rounding); with the governor on, the profile shaped within the governor's limits: increments
    # of at most vmax, changing by at most a per period, the profile's value wherever the profile
    # has held still for 240 periods (60 ms: after the move and the 2^-ksh catch-up).
    applied = rec["ref"][sel]
    off = np.abs(applied - ref[:, 2]) > 1e-6 * max(1.0, float(np.max(np.abs(ref[:, 2]))))
    if not cs.gov["enable"]:
        n_steps = sum(1 for p in scenarios.POINTS[cs.sc.name] if p[2] == "step")
        assert off.sum() <= n_steps, f"applied reference differs from the profile in {off.sum()} samples"
    else:
        unit_q32 = 2.0 ** 32 * cs.ref_unit          # Q.32 words per SI unit
        d = np.diff(applied) * unit_q32
        lsb = 4.0                                    # rounding of the recorded SI values
        assert np.all(np.abs(d) <= cs.gov["vmax"] + lsb), f"governed increment {np.max(np.abs(d))} > vmax"
        assert np.all(np.abs(np.diff(d)) <= cs.gov["a"] + 2 * lsb), "governed increment changed by more than a"
        still = np.array([all(abs(prof(x - k * Ts)[2] - prof(x)[2]) < 1e-12 for k in range(1, 241)) for x in t[sel]])
        # ... and long enough for the distance left when the profile stopped moving, at vmax: a large
        # position step travels at the governor's speed limit for longer than the 240 periods.
        r2 = ref[:, 2]
        moved = np.flatnonzero(np.diff(r2) != 0) + 1
        last = np.maximum.accumulate(np.where(np.isin(np.arange(r2.size), moved), np.arange(r2.size), 0))
        dist = np.abs(r2[last] - applied[last]) * unit_q32
        still &= (np.arange(r2.size) - last) >= 240 + np.ceil(dist / max(cs.gov["vmax"], 1))
        assert not np.any(off & still), (f"governed reference off the held profile in {np.sum(off & still)} samples "
                                         f"(first at t = {t[sel][np.argmax(off & still)]:.4f} s)")
    if not cs.gov["enable"]:
        ref[:, 2] = applied
    # (with the governor the errors are taken against the profile, as the float loop's are)
    tr = cl.Trace(t[sel], ref, rec["i_d"][sel], rec["i_q"][sel], rec["w_e"][sel], rec["theta_e"][sel],
                  rec["u_d"][sel], rec["u_q"][sel], rec["ipk"][sel], np.zeros(sel.sum()), np.zeros(sel.sum()))
    sc = cs.sc
    sc_cut = cl.Scenario(sc.name, sc.task, float(t[sel][-1]) if sel.any() else 0.0, sc.profile, sc.load,
                         sc.description, [s for s in sc.segments if s[2] <= (t[sel][-1] if sel.any() else 0)])
    floor = cs.cfg.rad_s_per_count_ts if sc.task == "speed" else 4 * cs.cfg.rad_per_count
    m = cl.metrics(tr, sc_cut, settle_floor=floor, preview=cs.cfg.control.N * cs.cfg.control.Ts)
    return tr, sc_cut, m


async def closed_loop(dut, name: str):
    res = await run_cosim(dut, name)
    cs = res["cs"]
    sim_ms = cs.period * cs.Tpwm * 1e3
    clocks = cs.period * 2 * cs.P            # fabric clocks of the checked periods
    dut._log.info("%s: %d PWM periods (%.1f ms simulated) in %.1f s wall, %.1f s CPU (%.2f sim ms per CPU s); "
                  "%d compare sets checked, %d mismatches; %d register read-backs checked", name, cs.period, sim_ms,
                  res["wall"], res["cpu"], sim_ms / res["cpu"], cs.checked, len(cs.mismatches), cs.reg_checks)
    report = {"scenario": name, "paper_scenario": cs.sc.name, "fault_injection": cs.fault,
              "pwm_periods": cs.period, "simulated_ms": sim_ms, "wall_s": res["wall"],
              "sim_ms_per_wall_s": sim_ms / res["wall"], "clocks_per_wall_s": clocks / res["wall"],
              # CPU time of the simulator process (Verilator + Python): the speed on an idle core
              "cpu_s": res["cpu"], "sim_ms_per_cpu_s": sim_ms / res["cpu"], "clocks_per_cpu_s": clocks / res["cpu"],
              "latency_last_adc_bit_to_cmp_load_max_cycles": dict(cs.lat_bit),
              "latency_adc_valid_to_cmp_load_max_cycles": dict(cs.lat_valid),
              "python_per_period_cpu_s": cs.py_cpu, "load_avg_1min": os.getloadavg()[0],
              "compare_sets_checked": cs.checked,
              "mismatches_vs_bit_accurate_model": len(cs.mismatches),
              "register_readbacks_checked": cs.reg_checks,
              "first_mismatches": [list(map(list, [[m[0]], m[1], m[2]])) for m in cs.mismatches[:5]],
              "status_registers": res["status"],
              "latency_adc_trigger_to_pwm_update_cycles": res["status"]["LATENCY"],
              "latency_max_cycles": dict(cs.lat_max),
              "fault_seen_period": res["fault_seen"]}
    if cs.lockstep:
        report["lockstep"] = {"clocks_compared": int(dut.dbg_ls_clocks.value),
                              "clocks_core_clock_stopped": int(dut.dbg_ls_gated.value),
                              "clocks_differing": int(dut.dbg_ls_errors.value)}
        dut._log.info("lockstep: %s", report["lockstep"])
        assert report["lockstep"]["clocks_differing"] == 0, report["lockstep"]
    assert 0 < cs.lat_bit["control"] <= LATENCY_MAX, f"last ADC bit -> compare values: {cs.lat_bit} clocks"
    if cs.fault is None:
        assert not cs.mismatches, f"RTL compare values differ from the bit-accurate model: {cs.mismatches[:3]}"
        tr, sc_cut, m = metrics_report(cs, res)
        report["metrics"] = m
        # float loop (fitted gains) on the same profile for the stated tolerance
        from empc.controllers.explicit import ExplicitMPC
        ftr = cl.simulate(cs.cfg, ExplicitMPC(cs.cfg), sc_cut)
        fm = cl.metrics(ftr, sc_cut, settle_floor=cs.cfg.rad_s_per_count_ts if cs.sc.task == "speed"
                        else 4 * cs.cfg.rad_per_count, preview=cs.cfg.control.N * cs.cfg.control.Ts)
        report["float_metrics"] = fm
        report["rms_error_rtl_vs_float_rel"] = abs(m["rms_error"] - fm["rms_error"]) / max(fm["rms_error"], 1e-12)
        assert report["rms_error_rtl_vs_float_rel"] < 0.10, report["rms_error_rtl_vs_float_rel"]
        assert res["status"]["CNT_OVERRUN"] == 0 and res["status"]["FAULT"] == 0, res["status"]
        if not cs.lockstep:
            _plot(cs, tr, ftr, REPORTS / f"closed_loop_{name}.png")
    else:
        assert res["fault_seen"] is not None, f"{cs.fault}: no fault tripped"
        bit = {"overcurrent": 0, "encoder": 2, "watchdog": 3}[cs.fault]
        assert (res["status"]["FAULT"] >> bit) & 1, f"{cs.fault}: FAULT register {res['status']['FAULT']:#x}"
        # cleared only by the CPU: still latched now, clears once the cause has gone
        cs.inject = False
        drv = driver.Drive(__import__("emc_bfm").EmcBfm(dut, pins=dict(cs_n="cpu_cs_n", oe_n="cpu_oe_n",
                           we_n="cpu_we_n", a="cpu_a", d="cpu_d", d_oe="cpu_d_oe", bus="emc_d_seen")))
        await drv.kick()
        cs.drive_plant_pins()
        await ClockCycles(dut.clk, 12000)
        assert await drv.read("FAULT") != 0, "fault cleared without the CPU"
        await drv.kick()
        await drv.command(fault_clear=1)
        await ClockCycles(dut.clk, 100)
        report["fault_after_clear"] = await drv.read("FAULT")
        assert report["fault_after_clear"] == 0, f"fault did not clear: {report['fault_after_clear']:#x}"
        for k, v in res["status"].items():
            assert v < 0xFFFFFFFF, f"counter {k} saturated/wrapped"
    REPORTS.mkdir(parents=True, exist_ok=True)
    tag = "_lockstep" if cs.lockstep else ""
    (REPORTS / f"closed_loop_{name}{tag}.json").write_text(json.dumps(report, indent=1, default=float) + "\n")


def _plot(cs, tr, ftr, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(15, 4))
    y, fy = tr.output(cs.sc.task), ftr.output(cs.sc.task)
    ax[0].plot(tr.t, tr.ref[:, 2], "k--", lw=1, label="reference")
    ax[0].plot(tr.t, y, lw=1, label="RTL co-simulation")
    ax[0].plot(ftr.t, fy, lw=1, label="float model")
    ax[1].plot(tr.t, tr.i_q, lw=1, label="i_q RTL")
    ax[1].plot(tr.t, tr.i_d, lw=1, label="i_d RTL")
    ax[1].plot(ftr.t, ftr.i_q, lw=1, alpha=0.6, label="i_q float")
    ax[2].plot(tr.t, tr.u_q, lw=1, label="u_q RTL")
    ax[2].plot(tr.t, tr.u_d, lw=1, label="u_d RTL")
    for a in ax:
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7)
        a.set_xlabel("t [s]")
    fig.suptitle(f"RTL-in-the-loop: {cs.name} ({cs.sc.description})", fontsize=9)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)   # fresh clone: build/reports may not exist yet
    fig.savefig(path, dpi=90)
    plt.close(fig)


# ---------------------------------------------------------------- cocotb test
@cocotb.test()
async def cosim(dut):
    """The scenarios named in EMPC_COSIM (comma-separated), in sequence, each from its own reset."""
    for name in os.environ["EMPC_COSIM"].split(","):
        await closed_loop(dut, name)


# ---------------------------------------------------------------- pytest entries
# make sim runs every scenario of COSIM except SOAK (make sim-full), one pytest test each, so that
# pytest-xdist spreads them over its workers; all of them share one Verilator build (tb/runner.py).
# The builds stop the MPC core's clock while it is idle (EMPC_SIM_GATE, rtl/mpc_core.v); the
# LOCKSTEP runs prove that against an ungated copy of the core, every output every clock.
SOAK = ("soak", "speed_alg2")
LOCKSTEP = ("short", "overcurrent", "encoder", "watchdog", "speed_steps")   # make sim; the rest: sim-full
VLT = ROOT / "tb" / "hdl" / "cosim_top.vlt"       # the signals Python touches through VPI


def build_and_run(names: str, lockstep: bool = False):
    from runner import run
    defines = {"EMPC_SIM_GATE": 1, **({"COSIM_LOCKSTEP": 1} if lockstep else {})}
    run(toplevel="cosim_top", test_module="test_closed_loop", sim="verilator", name="cosim", public=VLT,
        timing=True, parameters={"CLK_HALF_PS": CLK_PERIOD_NS * 500}, defines=defines,
        run_name=names.replace(",", "+"), extra_env={"EMPC_COSIM": names})


SIM_MS_PER_S = 13.0         # co-simulation speed on one core (build/reports/closed_loop_*.json), for the order


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.cost(5 + COSIM[n][1] * 1e3 / SIM_MS_PER_S))
                                  for n in COSIM if n not in SOAK])
def test_closed_loop(name):
    """RTL in the loop (Verilator): every compare value bit-exact against the model, the trajectory
    against the float loop, or (fault runs) the fault trips, the bridges stay off, the CPU clears it."""
    build_and_run(name)


@pytest.mark.full
@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.cost(5 + COSIM[n][1] * 1e3 / SIM_MS_PER_S))
                                  for n in SOAK])
def test_closed_loop_soak(name):
    """Longer runs for make sim-full (see SOAK)."""
    build_and_run(name)


@pytest.mark.parametrize("name", [
    pytest.param(n, marks=[pytest.mark.cost(5 + COSIM[n][1] * 1e3 / SIM_MS_PER_S * 1.4)]
                 + ([] if n in LOCKSTEP else [pytest.mark.full])) for n in COSIM])
def test_closed_loop_lockstep(name):
    """The scenario with the gated MPC core next to an ungated copy: every output equal every clock
    (the proof of EMPC_SIM_GATE), plus all the checks of test_closed_loop."""
    build_and_run(name, lockstep=True)
