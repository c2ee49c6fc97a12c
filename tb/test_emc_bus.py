"""cocotb tests of emc_bus.

Toplevel ``emc_bus`` (clocked logic, pins changed at the falling clock edge):

* logic_vs_model: random cycle-level pin waveforms (writes and reads with
  0..10-clock strobes, glitches of 1-2 clocks, CS kept low or toggling,
  address/data changing inside and outside the strobes, random reg_rdata)
  compared bit-exact with empc.rtlmodel.emc_bus.EmcBus every clock.

Toplevel ``emc_regs_tb`` (tb/hdl/emc_regs_tb.v: 64 RW registers behind the port,
the data bus a resolved tristate net) driven by the LPC4088 bus-functional
model tb/emc_bfm.py with timing in ns independent of the clock:

* bfm_random: random writes/reads with random timing within spec (every
  access its own timing, CS kept low or toggling, back-to-back), checked
  against a shadow register file; every reg_wr pulse matches a BFM write
  (address, data, order); no bus contention; measured OE-fall-to-data and
  WE-rise-to-reg_wr latencies within the bounds of timing_spec();
* bfm_all_regs: every register written with random data and read back, plus
  reads of out-of-range addresses covering every address bit, with the
  LPC4088 preset timing (60 MHz EMC, recommended wait states);
* bfm_below_spec (negative): WE pulses and noise shorter than the
  synchroniser (< 20 ns) never write; 20..30 ns WE pulses either write the
  right data or raise err_wr_short, never a wrong write; reads with OE low
  below spec (15..80 ns) return either the right data or an undriven bus
  (EmcBusError), never wrong data; err_rd_short is raised for every read
  below timing_spec().rd_err_always, never above rd_err_never, and every
  unflagged read returned the right data; CS noise while idle does nothing.
"""
from __future__ import annotations

import json
import math
import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, First, RisingEdge, Timer
from cocotb.utils import get_sim_time

from emc_bfm import EmcBfm, EmcBusError, EmcTiming
from empc.rtlmodel.emc_bus import EmcBus, timing_spec

DEFAULT_SEED = 40880
PARAMS = dict(AW=14, RD_LAT=1, WR_MIN_LOW=3, RD_MIN_LOW=2, OE_PIN_GATE=1)
NREG = 64


def _params():
    return json.loads(os.environ.get("TB_PARAMS", json.dumps(PARAMS)))


def _seed(dut):
    seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
    dut._log.info("params %s seed %d (EMPC_SEED)", _params(), seed)
    return seed


# ---------------------------------------------------------------- clocked logic vs model
def waveform(rng, aw, n):
    """Yield n per-clock pin tuples (cs_n, oe_n, we_n, a, d) of random bus activity."""
    cs, oe, we = 1, 1, 1
    a, d = rng.getrandbits(aw), rng.getrandbits(32)
    out = []
    while len(out) < n:
        kind = rng.random()
        keep_cs = rng.random() < 0.3
        a, d = rng.getrandbits(aw), rng.getrandbits(32)
        if kind < 0.4:          # write
            pre = rng.randrange(0, 3)
            low = rng.choice([0, 1, 2, 3, 3, 4, 5, 7, rng.randrange(1, 11)])
            post = rng.randrange(0, 3)
            for _ in range(pre):
                out.append((0, 1, 1, a, d))
            for k in range(low):
                if rng.random() < 0.1:
                    d = rng.getrandbits(32)        # data changing during the strobe
                out.append((0, 1, 0, a, d))
            for _ in range(post):
                out.append((0, 1, 1, a, d))
        elif kind < 0.8:        # read
            pre = rng.randrange(0, 3)
            low = rng.choice([0, 1, 2, 3, 4, 5, 6, 8, rng.randrange(1, 12)])
            for _ in range(pre):
                out.append((0, 1, 1, a, d))
            for _ in range(low):
                out.append((0, 0, 1, a, rng.getrandbits(32)))
            for _ in range(rng.randrange(0, 2)):
                out.append((0, 1, 1, a, d))
        else:                   # noise on every pin
            for _ in range(rng.randrange(1, 6)):
                out.append((rng.getrandbits(1), rng.getrandbits(1), rng.getrandbits(1),
                            rng.getrandbits(aw), rng.getrandbits(32)))
        gap = rng.randrange(0, 4)
        for _ in range(gap):
            out.append((0 if keep_cs else 1, 1, 1, rng.getrandbits(aw), rng.getrandbits(32)))
    return out[:n]


@cocotb.test()
async def logic_vs_model(dut):
    p = _params()
    seed = _seed(dut)
    rng = random.Random(seed)
    m = EmcBus(p["AW"], p["RD_LAT"], p["WR_MIN_LOW"], p["RD_MIN_LOW"], bool(p["OE_PIN_GATE"]))
    Clock(dut.clk, 10, unit="ns").start()
    dut.rst.value = 1
    dut.emc_cs_n.value = 1
    dut.emc_oe_n.value = 1
    dut.emc_we_n.value = 1
    dut.emc_a.value = 0
    dut.emc_d_in.value = 0
    dut.reg_rdata.value = 0
    for _ in range(3):
        await FallingEdge(dut.clk)
    dut.rst.value = 0
    names = ("reg_wr", "reg_rd", "reg_addr", "reg_wdata", "emc_d_out", "err_wr_short", "err_rd_short")
    n = 24000
    stats = dict(wr=0, rd=0, drive=0, err_wr=0, err_rd=0)
    for k, (cs, oe, we, a, d) in enumerate(waveform(rng, p["AW"], n)):
        rdata = rng.getrandbits(32)
        dut.emc_cs_n.value = cs
        dut.emc_oe_n.value = oe
        dut.emc_we_n.value = we
        dut.emc_a.value = a
        dut.emc_d_in.value = d
        dut.reg_rdata.value = rdata
        m.step(cs, oe, we, a, d, rdata)
        await FallingEdge(dut.clk)
        got = {s: int(getattr(dut, s).value) for s in names}
        exp = {s: getattr(m, s) for s in names}
        assert got == exp, f"clock {k}: rtl {got} model {exp}"
        oe_pin = int(dut.emc_d_oe.value)
        assert oe_pin == m.d_oe(cs, oe), f"clock {k}: emc_d_oe {oe_pin} model {m.d_oe(cs, oe)}"
        stats["wr"] += got["reg_wr"]
        stats["rd"] += got["reg_rd"]
        stats["drive"] += oe_pin
        stats["err_wr"] += got["err_wr_short"]
        stats["err_rd"] += got["err_rd_short"]
    dut._log.info("logic: %d clocks bit-exact vs model (seed %d): %s", n, seed, stats)
    assert min(stats.values()) > 0, "stimulus must exercise writes, reads, drive and both errors"


# ---------------------------------------------------------------- BFM level
def spec_ns(p, board=True):
    """Spec (rounded up to 5 ns, board delays) or exact simulation bounds (no delays)."""
    kw = dict(clk_hz=100e6, rd_lat=p["RD_LAT"], wr_min_low=p["WR_MIN_LOW"], rd_min_low=p["RD_MIN_LOW"],
              oe_pin_gate=bool(p["OE_PIN_GATE"]))
    if not board:
        return timing_spec(t_unc=0.0, t_co=0.0, t_su_cpu=0.0, t_pad_in=0.0, **kw)
    s = timing_spec(**kw)
    up = lambda x: 5.0 * math.ceil(x / 5.0 - 1e-9)
    return dict(we_low=up(s.we_low_min), wr_hold=up(s.wr_hold_min), we_high=up(s.we_high_min),
                oe_low=up(s.oe_low_min), oe_high=up(s.oe_high_min), release=up(s.release_max))


class BusEnv:
    def __init__(self, dut):
        self.dut = dut
        self.p = _params()
        self.seed = _seed(dut)
        self.rng = random.Random(self.seed)
        self.bfm = EmcBfm(dut, aw=self.p["AW"], rng=random.Random(self.seed + 1))
        self.shadow = [0] * NREG
        self.wlog = []          # reg_wr pulses seen: (addr, data)
        self.expect_w = []      # BFM writes that must have landed
        self.contention = 0
        self.lat_rd = []
        self.lat_wr = []
        self.spec = spec_ns(self.p)
        self.sim = spec_ns(self.p, board=False)

    async def start(self):
        d = self.dut
        Clock(d.clk, 10, unit="ns").start()
        self.bfm.idle()
        d.rst.value = 1
        for _ in range(3):
            await RisingEdge(d.clk)
        d.rst.value = 0
        await RisingEdge(d.clk)
        cocotb.start_soon(self._mon_wr())
        cocotb.start_soon(self._mon_contention())
        cocotb.start_soon(self._mon_oe())
        cocotb.start_soon(self._mon_we())

    async def _mon_wr(self):
        d = self.dut
        while True:
            await RisingEdge(d.clk)
            if int(d.reg_wr.value):
                self.wlog.append((int(d.reg_addr.value), int(d.reg_wdata.value)))

    async def _mon_contention(self):
        while True:
            await RisingEdge(self.dut.contention)
            self.contention += 1
            self.dut._log.error("bus contention at %.3f ns", get_sim_time("ns"))

    async def _mon_oe(self):
        """OE fall -> the last change of the bus to a resolved value before OE rises."""
        d = self.dut
        while True:
            await FallingEdge(d.cpu_oe_n)
            t0 = get_sim_time("ps")
            last_good = None
            while True:
                await First(d.emc_d.value_change, RisingEdge(d.cpu_oe_n))
                if int(d.cpu_oe_n.value):
                    break
                if d.emc_d.value.is_resolvable and int(d.fpga_d_oe.value):
                    last_good = get_sim_time("ps")
            if last_good is not None:
                self.lat_rd.append((last_good - t0) / 1000.0)

    async def _mon_we(self):
        d = self.dut
        while True:
            await RisingEdge(d.cpu_we_n)
            t0 = get_sim_time("ps")
            r = await First(RisingEdge(d.reg_wr), FallingEdge(d.cpu_we_n), Timer(100, unit="ns"))
            if int(d.reg_wr.value):
                self.lat_wr.append((get_sim_time("ps") - t0) / 1000.0)
            del r

    def random_timing(self, rng):
        s = self.spec
        gap_min = max(s["we_high"], s["oe_high"], s["release"])
        return EmcTiming(t_cs_we=rng.uniform(0, 30), t_we=rng.uniform(s["we_low"], s["we_low"] + 40),
                         t_wr_hold=rng.uniform(s["wr_hold"], 20), t_cs_oe=rng.uniform(0, 30),
                         t_oe=rng.uniform(s["oe_low"], s["oe_low"] + 40), t_su=5.0,
                         t_rd_hold=rng.uniform(0, 20), t_cs_hold=rng.uniform(0, 10),
                         t_gap=rng.uniform(gap_min, gap_min + 40), keep_cs=rng.random() < 0.3)

    async def write(self, addr, data):
        await self.bfm.write(addr, data)
        self.expect_w.append((addr, data))
        if addr < NREG:
            self.shadow[addr] = data

    def expected(self, addr):
        return self.shadow[addr] if addr < NREG else (0xDEAD0000 | addr)

    async def read_check(self, addr):
        v = await self.bfm.read(addr)
        assert v == self.expected(addr), f"read {addr:#x}: {v:#010x} expected {self.expected(addr):#010x}"
        return v

    async def settle(self):
        await Timer(100, unit="ns")

    def final_checks(self, what):
        d = self.dut
        assert self.contention == 0, f"{self.contention} bus contentions"
        assert self.wlog == self.expect_w, (f"reg_wr log ({len(self.wlog)}) differs from the BFM writes "
                                            f"({len(self.expect_w)})")
        if self.lat_rd:
            assert max(self.lat_rd) <= self.sim.oe_to_data_max + 1e-6, \
                f"OE fall -> data {max(self.lat_rd)} ns > bound {self.sim.oe_to_data_max}"
        if self.lat_wr:
            assert max(self.lat_wr) <= self.sim.wr_latency_max + 1e-6, \
                f"WE rise -> reg_wr {max(self.lat_wr)} ns > bound {self.sim.wr_latency_max}"
        d._log.info("%s: %d writes, %d reads; OE->data %.2f..%.2f ns (bound %.1f), WE->reg_wr %.2f..%.2f ns "
                    "(bound %.1f); err_wr %d err_rd %d; contention 0",
                    what, self.bfm.n_wr, self.bfm.n_rd, min(self.lat_rd or [0]), max(self.lat_rd or [0]),
                    self.sim.oe_to_data_max, min(self.lat_wr or [0]), max(self.lat_wr or [0]),
                    self.sim.wr_latency_max, int(d.n_err_wr.value), int(d.n_err_rd.value))


@cocotb.test()
async def bfm_random(dut):
    env = BusEnv(dut)
    await env.start()
    rng = env.rng
    dut._log.info("spec used (ns): %s; simulation bounds: %s", env.spec, env.sim)
    n_acc = 1500
    for k in range(n_acc):
        env.bfm.timing = env.random_timing(rng)
        addr = rng.randrange(NREG) if rng.random() < 0.9 else rng.getrandbits(env.p["AW"])
        if rng.random() < 0.5:
            await env.write(addr, rng.getrandbits(32))
        else:
            await env.read_check(addr)
    await env.settle()
    assert int(dut.n_err_wr.value) == 0 and int(dut.n_err_rd.value) == 0, "timing errors flagged within spec"
    env.final_checks(f"random within spec ({n_acc} accesses, seed {env.seed})")


@cocotb.test()
async def bfm_all_regs(dut):
    env = BusEnv(dut)
    await env.start()
    rng = env.rng
    aw = env.p["AW"]
    presets = [("LPC 60 MHz WAITWEN=0 WAITWR=2 WAITOEN=0 WAITRD=4 WAITTURN=1", EmcTiming.lpc()),
               ("LPC 60 MHz, CS kept low", EmcTiming.lpc(keep_cs=True)),
               ("exact spec minima", EmcTiming(t_cs_we=0.0, t_we=env.spec["we_low"], t_wr_hold=env.spec["wr_hold"],
                                               t_cs_oe=0.0, t_oe=env.spec["oe_low"], t_su=5.0, t_rd_hold=0.0,
                                               t_gap=max(env.spec["we_high"], env.spec["oe_high"],
                                                         env.spec["release"])))]
    if env.p["OE_PIN_GATE"]:
        presets[0] = (presets[0][0], presets[0][1])
    else:   # no pin gate: the turnaround must cover the release time
        presets = [(n, t.but(t_gap=max(t.t_gap, env.spec["release"]))) for n, t in presets]
    for name, tim in presets:
        env.bfm.timing = tim
        vals = [rng.getrandbits(32) for _ in range(NREG)]
        for i in rng.sample(range(NREG), NREG):
            await env.write(i, vals[i])
        for i in range(NREG):
            await env.read_check(i)
        for b in range(aw):                       # every address bit, outside the register file
            await env.read_check(1 << b if (1 << b) >= NREG else (1 << b) | NREG)
        await env.read_check((1 << aw) - 1)
        dut._log.info("%s: %d registers written and read back, %d out-of-range reads", name, NREG, aw + 1)
    await env.settle()
    assert int(dut.n_err_wr.value) == 0 and int(dut.n_err_rd.value) == 0
    env.final_checks("all registers")


@cocotb.test()
async def bfm_below_spec(dut):
    env = BusEnv(dut)
    await env.start()
    rng = env.rng
    bfm = env.bfm
    good = EmcTiming.lpc() if env.p["OE_PIN_GATE"] else EmcTiming.lpc(waitturn=2)
    bfm.timing = good
    for i in range(NREG):
        await env.write(i, rng.getrandbits(32))
    # 1. WE pulses shorter than the synchroniser depth (< 20 ns) never write
    n_wr0 = int(dut.n_wr.value)
    for _ in range(200):
        bfm.timing = good.but(t_we=rng.uniform(0.1, 19.9), t_cs_we=rng.uniform(0, 20), keep_cs=rng.random() < 0.3)
        await bfm.write(rng.randrange(NREG), rng.getrandbits(32))
    await env.settle()
    assert int(dut.n_wr.value) == n_wr0, "a WE pulse shorter than 20 ns wrote"
    n_short = int(dut.n_err_wr.value)
    # 2. 20..30 ns: either a correct write or a flagged drop, never wrong data
    n_ok = 0
    for _ in range(200):
        bfm.timing = good.but(t_we=rng.uniform(20, 30))
        a, v = rng.randrange(NREG), rng.getrandbits(32)
        n0, e0 = int(dut.n_wr.value), int(dut.n_err_wr.value)
        await bfm.write(a, v)
        await Timer(40, unit="ns")
        if int(dut.n_wr.value) != n0:
            assert env.wlog[-1] == (a, v), "marginal write landed with wrong address/data"
            env.expect_w.append((a, v))
            env.shadow[a] = v
            n_ok += 1
        else:
            assert int(dut.n_err_wr.value) == e0 + 1, "a dropped marginal write must raise err_wr_short"
    n_short2 = int(dut.n_err_wr.value) - n_short
    # 3. noise on WE / OE / CS (pulses < 20 ns, random address/data) never writes
    n_wr1 = int(dut.n_wr.value)
    for _ in range(300):
        pin = rng.choice([dut.cpu_we_n, dut.cpu_oe_n, dut.cpu_cs_n])
        dut.cpu_cs_n.value = rng.getrandbits(1)
        dut.cpu_a.value = rng.getrandbits(env.p["AW"])
        await Timer(int(rng.uniform(1, 30) * 1000), unit="ps")
        pin.value = 0
        await Timer(int(rng.uniform(0.1, 19.9) * 1000), unit="ps")
        pin.value = 1
        await Timer(int(rng.uniform(20, 40) * 1000), unit="ps")
    dut.cpu_cs_n.value = 1
    await env.settle()
    assert int(dut.n_wr.value) == n_wr1, "noise shorter than the synchroniser wrote"
    # 4. reads below spec: err_rd_short always below rd_err_always, never above rd_err_never,
    #    never an unflagged wrong read, never a wrong value (either right or an undriven bus)
    sim = env.sim
    data_min = (env.p["RD_MIN_LOW"] + 2 + env.p["RD_LAT"]) * 10.0     # earliest data after OE fall
    n_flag = n_z = n_right = 0
    for _ in range(150):
        t_oe = rng.uniform(15, 80)
        bfm.timing = good.but(t_oe=t_oe)
        a = rng.randrange(NREG)
        e0 = int(dut.n_err_rd.value)
        try:
            v = await bfm.read(a)
            assert v == env.expected(a), f"short read t_oe={t_oe:.2f} returned wrong data {v:#x}"
            ok = True
        except EmcBusError:
            ok = False
        await Timer(40, unit="ns")
        flagged = int(dut.n_err_rd.value) - e0
        assert flagged in (0, 1)
        if t_oe <= sim.rd_err_always:
            assert flagged, f"read with OE low {t_oe:.2f} ns not flagged"
        if t_oe >= sim.rd_err_never:
            assert not flagged and ok, f"read with OE low {t_oe:.2f} ns flagged or failed"
        if not flagged:
            assert ok, f"unflagged read with OE low {t_oe:.2f} ns failed"
        if t_oe - bfm.timing.t_su < data_min:
            assert not ok, f"OE low {t_oe:.2f} ns cannot have valid data"
        n_flag += flagged
        n_z += not ok
        n_right += ok
    # all registers still hold what was written with good timing
    bfm.timing = good
    for i in range(NREG):
        await env.read_check(i)
    await env.settle()
    env.final_checks(f"below spec: 200 WE<20ns (0 writes, {n_short} flagged), 200 WE 20-30ns "
                     f"({n_ok} written ok, {n_short2} flagged), 300 noise pulses (0 writes), "
                     f"150 reads with OE low 15..80 ns ({n_flag} flagged, {n_z} undriven, {n_right} right; "
                     f"flag always <= {env.sim.rd_err_always} ns, never >= {env.sim.rd_err_never} ns)")


def _run(params, toplevel, tests, name):
    from runner import run
    run(toplevel=toplevel, test_module="test_emc_bus", parameters=params, testcase=tests, name=name,
        extra_env={"TB_PARAMS": json.dumps(params)})


def test_emc_bus_logic():
    _run(PARAMS, "emc_bus", ["logic_vs_model"], "test_emc_bus_logic")


def test_emc_bus_logic_alt():
    p = dict(AW=10, RD_LAT=3, WR_MIN_LOW=2, RD_MIN_LOW=1, OE_PIN_GATE=0)
    _run(p, "emc_bus", ["logic_vs_model"], "test_emc_bus_logic_alt")


def test_emc_bus_bfm():
    _run(PARAMS, "emc_regs_tb", ["bfm_random", "bfm_all_regs", "bfm_below_spec"], "test_emc_bus_bfm")


def test_emc_bus_bfm_alt():
    p = dict(PARAMS, RD_LAT=2, OE_PIN_GATE=0)
    _run(p, "emc_regs_tb", ["bfm_random", "bfm_all_regs"], "test_emc_bus_bfm_alt")
