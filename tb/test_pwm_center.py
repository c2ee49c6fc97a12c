"""cocotb tests for rtl/pwm_center.v: every output bit compared on every clock
against the cycle-accurate model empc.rtlmodel.pwm_center, plus model-independent
checks of the safety rules (no overlap, dead time, fault off/latched, enable off)
and of the waveform (2*cmp clocks high per period, adc_trig in the centre of the
off-window, double-buffered compare).

Builds (pytest entries at the bottom):
  main     NCH=3 P=13 DEAD_W=4 SYNC_STAGES=0 SYNC_LEAD=2: random + directed corners
  small    NCH=1 P=2  DEAD_W=2 SYNC_STAGES=2 SYNC_LEAD=0: random (smallest period)
  default  header defaults (P=EMPC_PWM_HALF_PERIOD=2500, NCH=3, DEAD_W=8): duty corners
  sync2    tb/hdl/pwm_center_sync2.v, master -> slave (SYNC_STAGES=2, lead 4): phase lock
Seed: EMPC_SEED (default below), printed by every test.
"""
from __future__ import annotations

import os
import random
from dataclasses import replace

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from empc.rtlmodel.pwm_center import MODE_COMPL, MODE_PWM_EN, PwmCenter, PwmInputs

SEED = int(os.environ.get("EMPC_SEED", "31415"))
SUITE = os.environ.get("PWM_SUITE", "")
NCH = int(os.environ.get("PWM_NCH", "3"))
P = int(os.environ.get("PWM_P", "13"))
DEAD_W = int(os.environ.get("PWM_DEAD_W", "4"))
SYNC_STAGES = int(os.environ.get("PWM_SYNC_STAGES", "0"))
SYNC_LEAD = int(os.environ.get("PWM_SYNC_LEAD", "2"))
CW = P.bit_length()          # clog2(P + 1)
OUT_FIELDS = ("period_start", "adc_trig", "sync_out", "fault_latched", "mode_eff", "cmp_clip", "on")


# ----------------------------------------------------------------------------- helpers
def pack(vals, width):
    v = 0
    for i, x in enumerate(vals):
        v |= (x & ((1 << width) - 1)) << (i * width)
    return v


def bits(v, n):
    return [(v >> i) & 1 for i in range(n)]


class Props:
    """Model-independent checks on the DUT outputs of one instance (per clock)."""

    def __init__(self, nch, name=""):
        self.nch, self.name = nch, name
        self.off = [0] * nch          # consecutive clocks with hi = lo = 0, ending at the last cycle
        self.prev = None
        self.n = dict(cycles=0, turn_on=0, turn_on_dead=0, fault_off=0, latched_off=0, enable_off=0)

    def check(self, inp: PwmInputs, out: dict, t: int):
        """``inp``: inputs of the cycle before the edge that produced ``out``."""
        tag = f"{self.name} cycle {t}"
        self.n["cycles"] += 1
        if inp.rst:
            assert out["hi"] == [0] * self.nch and out["lo"] == [0] * self.nch, f"{tag}: outputs on after reset"
            assert out["fault_latched"] == 0, f"{tag}: fault latch not cleared by reset"
        else:
            if inp.fault:
                assert out["fault_latched"] == 1, f"{tag}: fault not latched"
                assert not any(out["hi"]) and not any(out["lo"]), f"{tag}: output on the clock after fault"
                self.n["fault_off"] += 1
            elif self.prev is not None and self.prev["fault_latched"] and not inp.fault_clear:
                assert out["fault_latched"] == 1, f"{tag}: fault latch dropped without fault_clear"
            elif self.prev is not None and self.prev["fault_latched"] and inp.fault_clear:
                assert out["fault_latched"] == 0, f"{tag}: fault_clear with fault low did not clear"
            if out["fault_latched"]:
                assert not any(out["hi"]) and not any(out["lo"]), f"{tag}: output on while fault latched"
                self.n["latched_off"] += 1
            if not inp.enable:
                assert not any(out["hi"]) and not any(out["lo"]), f"{tag}: output on the clock after enable low"
                self.n["enable_off"] += 1
        for i in range(self.nch):
            h, lo = out["hi"][i], out["lo"][i]
            if out["mode_eff"] == MODE_COMPL and self.prev is not None:
                assert not (h and lo), f"{tag}: ch{i} hi and lo both on"
                ph, pl = self.prev["hi"][i], self.prev["lo"][i]
                if (h and not ph) or (lo and not pl):
                    self.n["turn_on"] += 1
                    if inp.dead > 0:
                        self.n["turn_on_dead"] += 1
                    assert self.off[i] >= inp.dead, (
                        f"{tag}: ch{i} turned on after {self.off[i]} off clocks, dead = {inp.dead}")
            self.off[i] = self.off[i] + 1 if not (h or lo) else 0
        self.prev = out


class Bench:
    """Drives one DUT (or one prefixed instance group), steps the model, compares per clock."""

    def __init__(self, dut, nch=NCH, p=P, dead_w=DEAD_W, sync_stages=SYNC_STAGES, sync_lead=SYNC_LEAD):
        self.dut = dut
        self.nch, self.p, self.cw = nch, p, p.bit_length()
        self.model = PwmCenter(nch=nch, half_period=p, dead_w=dead_w,
                               sync_stages=sync_stages, sync_lead=sync_lead)
        self.props = Props(nch)
        self.t = 0
        self.compared = 0
        self.inp = PwmInputs(rst=1, cmp_in=[0] * nch)

    async def start(self):
        cocotb.start_soon(Clock(self.dut.clk, 10, unit="ns").start())
        self.drive(self.inp)
        await FallingEdge(self.dut.clk)

    def drive(self, inp: PwmInputs):
        d = self.dut
        d.rst.value = inp.rst
        d.enable.value = inp.enable
        d.mode.value = inp.mode
        d.dead.value = inp.dead
        d.cmp_in.value = pack(inp.cmp_in, self.cw)
        d.cmp_load.value = inp.cmp_load
        d.sync_in.value = inp.sync_in
        d.fault.value = inp.fault
        d.fault_clear.value = inp.fault_clear

    def read(self, prefix=""):
        d = self.dut
        out = {"hi": bits(int(getattr(d, prefix + "hi").value), self.nch),
               "lo": bits(int(getattr(d, prefix + "lo").value), self.nch)}
        for f in OUT_FIELDS:
            out[f] = int(getattr(d, prefix + f).value)
        return out

    async def cycle(self, inp: PwmInputs) -> dict:
        """Apply ``inp`` for one clock; returns the DUT outputs after the edge (checked)."""
        self.inp = inp
        self.drive(inp)
        exp = self.model.step(inp)
        await FallingEdge(self.dut.clk)
        self.t += 1
        got = self.read()
        assert got == exp, f"cycle {self.t}: DUT {got} != model {exp} (inputs {inp})"
        self.compared += 1
        self.props.check(inp, got, self.t)
        return got

    def report(self, log, what):
        log.info("%s: %d clocks compared bit-exact (%d output bits each) with the model; props %s",
                 what, self.compared, 2 * self.nch + len(OUT_FIELDS), self.props.n)


class RandomStimulus:
    """Per-clock random inputs with realistic persistence (episodes), incl. rare events."""

    def __init__(self, rng: random.Random, nch, p, dead_w, allow_rst=True):
        self.rng, self.nch, self.p, self.dead_w = rng, nch, p, dead_w
        self.cw = p.bit_length()
        self.enable = 1
        self.mode = MODE_COMPL
        self.dead = 0
        self.fault_left = 0
        self.sync_left = 0
        self.allow_rst = allow_rst

    def cmp_value(self):
        r = self.rng
        p = self.p
        pick = r.random()
        if pick < 0.35:
            return r.choice([0, 1, p - 1, p, max(0, p - 2), 2])
        if pick < 0.45:
            return r.randint(p, (1 << self.cw) - 1)         # clip to P (when > P)
        return r.randint(0, p)

    def next(self) -> PwmInputs:
        r = self.rng
        p = self.p
        if r.random() < 1.0 / (20 * p):
            self.mode ^= 1
        if r.random() < 1.0 / (8 * p):
            self.dead = r.choice([0, 1, r.randint(0, (1 << self.dead_w) - 1), (1 << self.dead_w) - 1])
        if r.random() < (1.0 / (15 * p) if self.enable else 1.0 / p):
            self.enable ^= 1
        fault = 0
        if self.fault_left:
            self.fault_left -= 1
            fault = 1
        elif r.random() < 1.0 / (25 * p):
            self.fault_left = r.randint(0, 4)
            fault = 1
        sync = 0
        if self.sync_left:
            self.sync_left -= 1
            sync = 1
        elif r.random() < 1.0 / (30 * p):
            self.sync_left = r.randint(0, 3)
            sync = 1
        rst = int(self.allow_rst and r.random() < 1.0 / (400 * p))
        return PwmInputs(
            rst=rst, enable=self.enable, mode=self.mode, dead=self.dead,
            cmp_in=[self.cmp_value() for _ in range(self.nch)],
            cmp_load=int(r.random() < 1.5 / p), sync_in=sync, fault=fault,
            fault_clear=int(r.random() < 1.0 / (3 * p)))


async def reset(bench: Bench, n=3):
    for _ in range(n):
        await bench.cycle(PwmInputs(rst=1, cmp_in=[0] * bench.nch))


def base(nch, **kw) -> PwmInputs:
    d = dict(enable=1, mode=MODE_PWM_EN, dead=0, cmp_in=[0] * nch)
    d.update(kw)
    return PwmInputs(**d)


async def run_to_period_start(bench: Bench, inp: PwmInputs, limit: int):
    """Clock with ``inp`` until the output cycle that shows period_start."""
    for _ in range(limit):
        out = await bench.cycle(inp)
        if out["period_start"]:
            return out
    raise AssertionError("no period_start")


async def capture_period(bench: Bench, inp: PwmInputs, first: dict):
    """``first`` = outputs of the period_start cycle; returns 2P output dicts (one period)."""
    outs = [first]
    for _ in range(2 * bench.p - 1):
        outs.append(await bench.cycle(inp))
    return outs


def expect_compl_counts(c, p, dead):
    """(hi, lo) clocks per period when the dead time is shorter than both ideal runs."""
    return 2 * c - dead, 2 * p - 2 * c - dead


# ----------------------------------------------------------------------------- tests
@cocotb.test(skip=SUITE not in ("main", "small"))
async def test_random(dut):
    """Random inputs every clock (loads mid-period, mode/dead/enable changes, faults, sync, reset)."""
    seed = SEED + P
    rng = random.Random(seed)
    dut._log.info("seed %d (EMPC_SEED=%d), NCH=%d P=%d DEAD_W=%d SYNC_STAGES=%d SYNC_LEAD=%d",
                  seed, SEED, NCH, P, DEAD_W, SYNC_STAGES, SYNC_LEAD)
    b = Bench(dut)
    await b.start()
    await reset(b)
    stim = RandomStimulus(rng, NCH, P, DEAD_W)
    n = int(os.environ.get("PWM_RANDOM_CYCLES", "24000"))
    counts = dict(hi_on=0, lo_on=0, period_start=0, adc_trig=0, sync_out=0, clip=0, mode1=0)
    for _ in range(n):
        out = await b.cycle(stim.next())
        counts["hi_on"] += sum(out["hi"])
        counts["lo_on"] += sum(out["lo"])
        counts["period_start"] += out["period_start"]
        counts["adc_trig"] += out["adc_trig"]
        counts["sync_out"] += out["sync_out"]
        counts["clip"] += out["cmp_clip"]
        counts["mode1"] += out["mode_eff"]
    b.report(dut._log, "random")
    dut._log.info("activity: %s", counts)
    # the stimulus must have exercised what the checks are about
    assert counts["hi_on"] > 0 and counts["lo_on"] > 0 and counts["mode1"] > 0
    assert b.props.n["turn_on_dead"] > 0 and b.props.n["fault_off"] > 0 and b.props.n["latched_off"] > 0
    if P.bit_length() and (1 << CW) - 1 > P:
        assert counts["clip"] > 0


@cocotb.test(skip=SUITE not in ("main", "default"))
async def test_duty_corners(dut):
    """Duty 0, 1, P-1, P and random in both modes: clocks on per period, symmetry, adc_trig centre."""
    rng = random.Random(SEED + 1)
    dut._log.info("seed %d, NCH=%d P=%d", SEED + 1, NCH, P)
    b = Bench(dut)
    await b.start()
    await reset(b)
    corner = [0, 1, P - 1, P]
    if P < 100:
        sets = [corner[:NCH] + [rng.randint(0, P)] * max(0, NCH - 4)]
        sets += [[rng.choice(corner + [rng.randint(1, P - 1)]) for _ in range(NCH)] for _ in range(3)]
        sets += [[c] * NCH for c in corner]
        combos = [(s, m) for s in sets for m in (MODE_PWM_EN, MODE_COMPL)]
    else:   # long period (default P): every corner once, each mode once (~3 periods per combination)
        combos = [((corner + [rng.randint(1, P - 1)] * NCH)[:NCH], MODE_PWM_EN),
                  ((corner[::-1] + [rng.randint(1, P - 1)] * NCH)[:NCH], MODE_COMPL)]
    periods = 0
    dmax = (1 << DEAD_W) - 1
    for cmps, mode in combos:
        if True:
            dead = 0 if mode == MODE_PWM_EN else rng.randint(0, min(dmax, 3))
            inp = base(NCH, mode=mode, dead=dead, cmp_in=cmps, cmp_load=1)
            hold = base(NCH, mode=mode, dead=dead, cmp_in=cmps)
            await b.cycle(inp)
            first = await run_to_period_start(b, hold, 2 * P + 2)   # new cmp + mode active here
            # one more period so that the mode change / dead-time settling is over
            first = await run_to_period_start(b, hold, 2 * P + 2)
            outs = await capture_period(b, hold, first)
            nxt = await b.cycle(hold)
            assert nxt["period_start"] == 1, "period is not 2P clocks"
            assert [o["adc_trig"] for o in outs].index(1) == P and sum(o["adc_trig"] for o in outs) == 1, \
                "adc_trig not exactly P clocks after period_start"
            for i, c in enumerate(cmps):
                hi = [o["hi"][i] for o in outs]
                lo = [o["lo"][i] for o in outs]
                if mode == MODE_PWM_EN:
                    assert sum(hi) == 2 * c, f"ch{i} cmp {c}: {sum(hi)} clocks high, expected {2 * c}"
                    assert all(lo), f"ch{i}: enable not on all period"
                    # pulse at the period edges, symmetric about the centre (adc_trig at position P)
                    assert hi == ideal_wave(c, P), f"ch{i}: waveform {hi}"
                    if 0 < c < P:
                        assert hi[P] == 0 and hi[P - 1] == 0, f"ch{i}: high side on at the centre"
                else:
                    if c == 0:
                        assert sum(hi) == 0 and sum(lo) == 2 * P
                    elif c == P:
                        assert sum(hi) == 2 * P and sum(lo) == 0
                    elif dead < min(2 * c, 2 * P - 2 * c):
                        assert (sum(hi), sum(lo)) == expect_compl_counts(c, P, dead), \
                            f"ch{i} cmp {c} dead {dead}: hi {sum(hi)} lo {sum(lo)}"
                    assert not any(h and l for h, l in zip(hi, lo))
            periods += 1
            dut._log.info("mode %d dead %d cmp %s: on-times checked", mode, dead, cmps)
    b.report(dut._log, f"duty corners ({periods} periods of 2P={2 * P} clocks)")


@cocotb.test(skip=SUITE != "main")
async def test_dead_longer_than_pulse(dut):
    """dead > pulse: the short pulse disappears, the complementary switch keeps `dead` off-clocks."""
    rng = random.Random(SEED + 2)
    dut._log.info("seed %d", SEED + 2)
    b = Bench(dut)
    await b.start()
    await reset(b)
    dmax = (1 << DEAD_W) - 1
    cases = 0
    for c in [1, 2, 3, P - 1, P - 2] + [rng.randint(1, P - 1) for _ in range(4)]:
        for dead in sorted({2 * c, 2 * c + 1, dmax, 2 * (P - c), 2 * (P - c) + 1}):
            if dead > dmax:
                continue
            hold = base(NCH, mode=MODE_COMPL, dead=dead, cmp_in=[c] * NCH)
            await b.cycle(base(NCH, mode=MODE_COMPL, dead=dead, cmp_in=[c] * NCH, cmp_load=1))
            first = await run_to_period_start(b, hold, 2 * P + 2)
            first = await run_to_period_start(b, hold, 2 * P + 2)
            outs = await capture_period(b, hold, first)
            for i in range(NCH):
                hi = [o["hi"][i] for o in outs]
                lo = [o["lo"][i] for o in outs]
                assert not any(h and l for h, l in zip(hi, lo))
                if dead >= 2 * c and dead < 2 * P - 2 * c:
                    assert sum(hi) == 0, f"cmp {c} dead {dead}: high pulse of {sum(hi)} should have vanished"
                if dead >= 2 * (P - c) and dead < 2 * c:
                    assert sum(lo) == 0, f"cmp {c} dead {dead}: low pulse of {sum(lo)} should have vanished"
            cases += 1
    b.report(dut._log, f"dead >= pulse ({cases} cmp/dead cases)")


def ideal_wave(c, p):
    """High-side command over one period (positions from period_start), spec: 2c clocks centred on the boundary."""
    return [1] * c + [0] * (2 * p - 2 * c) + [1] * c


@cocotb.test(skip=SUITE != "main")
async def test_cmp_mid_period(dut):
    """cmp_load at any position of a period changes nothing before the next period_start; cmp_in
    without cmp_load is ignored.  A load sampled at output position 2P-1 (the edge that also
    starts the next period in stage A) misses that boundary and applies one period later."""
    rng = random.Random(SEED + 3)
    dut._log.info("seed %d", SEED + 3)
    b = Bench(dut)
    await b.start()
    await reset(b)
    cur = [rng.randint(0, P) for _ in range(NCH)]
    await b.cycle(base(NCH, cmp_in=cur, cmp_load=1))
    first = await run_to_period_start(b, base(NCH, cmp_in=cur), 2 * P + 2)
    first = await run_to_period_start(b, base(NCH, cmp_in=cur), 2 * P + 2)   # past the mode switch
    n = 0
    positions = [1, 2, P - 1, P, P + 1, 2 * P - 2, 2 * P - 1] + [rng.randint(1, 2 * P - 1) for _ in range(8)]
    for pos in positions:
        new = [rng.randint(0, P) for _ in range(NCH)]
        outs = [first]
        for k in range(1, 2 * P):
            ld = int(k == pos)
            junk = [rng.randint(0, (1 << CW) - 1) for _ in range(NCH)]
            outs.append(await b.cycle(base(NCH, cmp_in=new if ld else junk, cmp_load=ld)))
        for i in range(NCH):
            assert [o["hi"][i] for o in outs] == ideal_wave(cur[i], P), \
                f"ch{i}: load at position {pos} leaked into the running period"
        hold = base(NCH, cmp_in=[rng.randint(0, (1 << CW) - 1) for _ in range(NCH)])   # no load
        late = pos == 2 * P - 1
        for per in range(2 if late else 1):
            first = await b.cycle(hold)
            assert first["period_start"], "period is not 2P clocks"
            outs = await capture_period(b, hold, first)
            exp = cur if (late and per == 0) else new
            for i in range(NCH):
                assert [o["hi"][i] for o in outs] == ideal_wave(exp[i], P), \
                    f"ch{i}: load at position {pos}: period {per} after the load is not cmp {exp[i]}"
        cur = new
        first = await b.cycle(hold)
        assert first["period_start"]
        n += 1
    b.report(dut._log, f"mid-period loads ({n} loads at positions {positions})")


@cocotb.test(skip=SUITE != "main")
async def test_fault(dut):
    """Fault at random clocks: all off on the next clock, latched, fault_clear only while fault low,
    outputs restart at a period boundary."""
    rng = random.Random(SEED + 4)
    dut._log.info("seed %d", SEED + 4)
    b = Bench(dut)
    await b.start()
    await reset(b)
    n = 0
    for _ in range(25):
        mode = rng.choice([MODE_COMPL, MODE_PWM_EN])
        hold = base(NCH, mode=mode, dead=rng.randint(0, 3), cmp_in=[rng.randint(1, P - 1) for _ in range(NCH)])
        await b.cycle(replace(hold, cmp_load=1))
        for _ in range(rng.randint(2 * P, 6 * P)):
            await b.cycle(hold)
        out = await b.cycle(replace(hold, fault=1))
        assert out["fault_latched"] == 1 and not any(out["hi"] + out["lo"]), "not off after fault"
        # fault_clear while fault is still high: must stay latched
        for _ in range(rng.randint(0, 3)):
            out = await b.cycle(replace(hold, fault=1, fault_clear=rng.randint(0, 1)))
            assert out["fault_latched"] == 1
        for _ in range(rng.randint(1, 3 * P)):
            out = await b.cycle(hold)
            assert out["fault_latched"] == 1 and not any(out["hi"] + out["lo"]), "latch lost without clear"
        out = await b.cycle(replace(hold, fault_clear=1))
        assert out["fault_latched"] == 0, "fault_clear did not clear"
        assert not any(out["hi"] + out["lo"])
        # restart only at a period boundary: the first clock with any output on shows period_start
        for _ in range(4 * P + 2):
            out = await b.cycle(hold)
            if any(out["hi"] + out["lo"]):
                break
        assert any(out["hi"] + out["lo"]), "outputs did not restart after fault_clear"
        assert out["period_start"], "outputs restarted elsewhere than at a period boundary"
        n += 1
    b.report(dut._log, f"faults ({n} fault episodes)")


@cocotb.test(skip=SUITE != "sync2")
async def test_sync_two(dut):
    """Master sync_out -> slave sync_in: after linking, the slave runs in phase (bit-identical)."""
    rng = random.Random(SEED + 5)
    dut._log.info("seed %d, NCH=%d P=%d slave SYNC_STAGES=2 master SYNC_LEAD=4", SEED + 5, NCH, P)
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    m = PwmCenter(nch=NCH, half_period=P, dead_w=DEAD_W, sync_stages=0, sync_lead=4)
    s = PwmCenter(nch=NCH, half_period=P, dead_w=DEAD_W, sync_stages=2, sync_lead=4)
    pm, ps = Props(NCH, "master"), Props(NCH, "slave")
    cw = P.bit_length()
    stats = dict(compared=0, locked=0, trials=0)

    async def clk(rst_m, rst_s, link, inp: PwmInputs):
        dut.rst_m.value = rst_m
        dut.rst_s.value = rst_s
        dut.link.value = link
        dut.enable.value = inp.enable
        dut.mode.value = inp.mode
        dut.dead.value = inp.dead
        dut.cmp_in.value = pack(inp.cmp_in, cw)
        dut.cmp_load.value = inp.cmp_load
        dut.sync_ext.value = inp.sync_in
        dut.fault.value = inp.fault
        dut.fault_clear.value = inp.fault_clear
        s_sync = int(link and m.sync_out)
        ein_m = replace(inp, rst=rst_m)
        ein_s = replace(inp, rst=rst_s, sync_in=s_sync)
        em, es = m.step(ein_m), s.step(ein_s)
        await FallingEdge(dut.clk)
        got = {}
        for pre, exp, pr, ein in (("m_", em, pm, ein_m), ("s_", es, ps, ein_s)):
            o = {"hi": bits(int(getattr(dut, pre + "hi").value), NCH),
                 "lo": bits(int(getattr(dut, pre + "lo").value), NCH)}
            for f in OUT_FIELDS:
                o[f] = int(getattr(dut, pre + f).value)
            assert o == exp, f"{pre}: DUT {o} != model {exp}"
            pr.check(ein, o, stats["compared"])
            got[pre] = o
        stats["compared"] += 1
        return got

    for trial in range(6):
        mode = rng.choice([MODE_COMPL, MODE_PWM_EN])
        cm = [rng.randint(0, P) for _ in range(NCH)]
        hold = PwmInputs(enable=1, mode=mode, dead=rng.randint(0, 3), cmp_in=cm)
        # both in reset, master released first, slave after a random offset, not linked
        for _ in range(2):
            await clk(1, 1, 0, hold)
        await clk(0, 1, 0, replace(hold, cmp_load=1))
        off = rng.randint(1, 2 * P - 1)
        for _ in range(off):
            await clk(0, 1, 0, hold)
        await clk(0, 0, 0, replace(hold, cmp_load=1))
        diff = 0
        for _ in range(4 * P):
            g = await clk(0, 0, 0, hold)
            diff += g["m_"]["period_start"] != g["s_"]["period_start"]
        assert diff > 0, "instances in phase before linking (test setup)"
        # link: within one period + latency the slave restarts; afterwards identical outputs
        for _ in range(2 * P + 8):
            await clk(0, 0, 1, hold)
        for _ in range(6 * P):
            g = await clk(0, 0, 1, hold)
            assert g["m_"]["hi"] == g["s_"]["hi"] and g["m_"]["lo"] == g["s_"]["lo"], "slave not in phase"
            assert g["m_"]["period_start"] == g["s_"]["period_start"]
            assert g["m_"]["adc_trig"] == g["s_"]["adc_trig"]
            stats["locked"] += 1
        stats["trials"] += 1
    dut._log.info("sync2: %s (every clock both instances bit-exact vs model; locked clocks compared m == s); "
                  "props master %s slave %s", stats, pm.n, ps.n)


@cocotb.test(skip=SUITE != "default")
async def test_default_sync_adc(dut):
    """Default P: period_start every 2P clocks, adc_trig P clocks after it, sync_out SYNC_LEAD before."""
    b = Bench(dut)
    await b.start()
    await reset(b)
    hold = base(NCH, cmp_in=[P // 3] * NCH)
    await b.cycle(base(NCH, cmp_in=[P // 3] * NCH, cmp_load=1))
    t_ps, t_adc, t_so = [], [], []
    for t in range(4 * P + 5):
        out = await b.cycle(hold)
        if out["period_start"]:
            t_ps.append(t)
        if out["adc_trig"]:
            t_adc.append(t)
        if out["sync_out"]:
            t_so.append(t)
    assert len(t_ps) >= 2 and all(y - x == 2 * P for x, y in zip(t_ps, t_ps[1:])), t_ps
    t_adc = [a for a in t_adc if a > t_ps[0]]
    assert len(t_adc) >= 1 and all(any(a - s == P for s in t_ps) for a in t_adc), (t_ps, t_adc)
    t_so = [o for o in t_so if o < t_ps[-1]]
    assert len(t_so) >= 1 and all(any(s - o == SYNC_LEAD for s in t_ps) for o in t_so), (t_ps, t_so)
    b.report(dut._log, "default-P timing")


# ----------------------------------------------------------------------------- pytest entries
def _run(suite, toplevel="pwm_center", env=None, **p):
    from runner import run
    params = dict(p)
    e = {"PWM_SUITE": suite}
    for k, name in (("NCH", "PWM_NCH"), ("PWM_HALF_PERIOD", "PWM_P"), ("DEAD_W", "PWM_DEAD_W"),
                    ("SYNC_STAGES", "PWM_SYNC_STAGES"), ("SYNC_LEAD", "PWM_SYNC_LEAD")):
        if k in params:
            e[name] = str(params[k])
    e.update(env or {})
    run(toplevel=toplevel, test_module="test_pwm_center", parameters=params, extra_env=e,
        name=f"test_pwm_center_{suite}")


def test_pwm_center():
    _run("main", NCH=3, PWM_HALF_PERIOD=13, DEAD_W=4, SYNC_STAGES=0, SYNC_LEAD=2)


def test_pwm_center_small():
    _run("small", NCH=1, PWM_HALF_PERIOD=2, DEAD_W=2, SYNC_STAGES=2, SYNC_LEAD=0)


def test_pwm_center_default():
    """RTL parameter defaults (P from the generated header); the bench gets the same values."""
    from empc.rtlmodel.pwm_center import default_half_period
    _run("default", env={"PWM_P": str(default_half_period()), "PWM_NCH": "3", "PWM_DEAD_W": "8",
                         "PWM_SYNC_STAGES": "0", "PWM_SYNC_LEAD": "2"})


def test_pwm_center_sync2():
    _run("sync2", toplevel="pwm_center_sync2", NCH=2, PWM_HALF_PERIOD=11, DEAD_W=4)


# ----------------------------------------------------------------------------- carrier stagger (PHASE)
PHASE = int(os.environ.get("PWM_PHASE", "0"))
STROBES = ("period_start", "adc_trig", "sync_out")


class PhaseBench:
    """tb/hdl/pwm_center_phase.v: u_a (PHASE = 0) and u_b (PHASE), the same inputs; both against their
    models every clock; records the counters (state after each edge), the strobes, and the restart
    edges (rst, or a sync rise) for the shift check."""

    def __init__(self, dut):
        self.dut = dut
        kw = dict(nch=NCH, half_period=P, dead_w=DEAD_W, sync_stages=SYNC_STAGES, sync_lead=SYNC_LEAD)
        self.ma, self.mb = PwmCenter(**kw), PwmCenter(**kw, phase=PHASE)
        self.pa, self.pb = Props(NCH, "a"), Props(NCH, "b")
        self.rec = {"a": [], "b": []}           # per clock: (cnt, dir, outputs)
        self.restart = []                      # clock indices of restart edges
        self.kinds = {}                        # restart clock -> "rst" / "sync"
        self.t = -1

    async def start(self):
        cocotb.start_soon(Clock(self.dut.clk, 10, unit="ns").start())
        await FallingEdge(self.dut.clk)

    async def cycle(self, inp: PwmInputs):
        d = self.dut
        d.rst.value = inp.rst
        d.enable.value = inp.enable
        d.mode.value = inp.mode
        d.dead.value = inp.dead
        d.cmp_in.value = pack(inp.cmp_in, CW)
        d.cmp_load.value = inp.cmp_load
        d.sync_in.value = inp.sync_in
        d.fault.value = inp.fault
        d.fault_clear.value = inp.fault_clear
        m = self.ma
        sync_s = m.sync_pipe[-1] if m.sync_stages else (inp.sync_in & 1)
        rise = sync_s & (1 - m.sync_prev)
        self.t += 1
        if inp.rst or rise:
            self.restart.append(self.t)
            self.kinds[self.t] = "rst" if inp.rst else "sync"
        exp = {"a": self.ma.step(inp), "b": self.mb.step(inp)}
        await FallingEdge(d.clk)
        for x, pr in (("a", self.pa), ("b", self.pb)):
            o = {"hi": bits(int(getattr(d, x + "_hi").value), NCH), "lo": bits(int(getattr(d, x + "_lo").value), NCH)}
            for f in OUT_FIELDS:
                o[f] = int(getattr(d, f"{x}_{f}").value)
            assert o == exp[x], f"{x} (PHASE {PHASE if x == 'b' else 0}) cycle {self.t}: DUT {o} != model {exp[x]}"
            pr.check(inp, o, self.t)
            u = getattr(d, "u_" + x)
            cnt, dr = int(u.cnt.value), int(u.dir.value)
            mm = self.ma if x == "a" else self.mb
            assert (cnt, dr) == (mm.cnt, mm.dir), f"{x} cycle {self.t}: counter {(cnt, dr)} model {(mm.cnt, mm.dir)}"
            self.rec[x].append((cnt, dr, o))

    def check_shift(self, fields=STROBES):
        """Within each segment between restart edges: u_b's counter after edge t equals u_a's after
        t - PHASE (or t - PHASE + 2P before u_b's first boundary, the periodic waveform), u_b's
        ``fields`` at output clock t those of u_a at t - PHASE (+ 2P).  Returns counts."""
        n = dict(counter=0, strobes=0, first_period=0, after_rst=0, after_sync=0, ps=0, adc=0)
        ends = self.restart[1:] + [self.t + 1]
        for e, e_end in zip(self.restart, ends):
            kind = self.kinds[e]
            for t in range(e, e_end):
                for lo, what in ((e, "counter"), (e + 1, "strobes")):
                    if t < lo:
                        continue
                    s = t - PHASE
                    if s < lo:
                        s += 2 * P
                        if s >= e_end:
                            continue
                        n["first_period"] += 1
                    ra, rb = self.rec["a"][s], self.rec["b"][t]
                    if what == "counter":
                        assert rb[:2] == ra[:2], \
                            f"counter of u_b after edge {t} {rb[:2]} != u_a's after {s} {ra[:2]} (segment from {kind} {e})"
                    else:
                        for f in fields:
                            ga, gb = ra[2][f], rb[2][f]
                            assert gb == ga, f"{f} of u_b at {t} = {gb}, u_a at {s} = {ga} (segment from {kind} {e})"
                        n["ps"] += rb[2]["period_start"]
                        n["adc"] += rb[2]["adc_trig"]
                    n[what] += 1
                    n["after_" + kind] += 1
        return n


@cocotb.test(skip=SUITE != "phase")
async def test_phase_random(dut):
    """PHASE build: random inputs (resets, sync rises, loads, faults), u_a (PHASE 0) and u_b (PHASE)
    bit-exact against their models every clock; u_b's counter and strobes are u_a's delayed by PHASE
    in every segment between restarts, including the clocks before u_b's first boundary."""
    ncyc = int(os.environ.get("PWM_RANDOM_CYCLES", "24000"))
    if ncyc == 0:
        import pytest
        pytest.skip("PWM_RANDOM_CYCLES = 0 (the default-P build runs the steady test only)")
    seed = SEED + P + PHASE
    rng = random.Random(seed)
    dut._log.info("seed %d (EMPC_SEED=%d), NCH=%d P=%d PHASE=%d SYNC_STAGES=%d", seed, SEED, NCH, P, PHASE,
                  SYNC_STAGES)
    b = PhaseBench(dut)
    await b.start()
    for _ in range(3):
        await b.cycle(PwmInputs(rst=1, cmp_in=[0] * NCH))
    stim = RandomStimulus(rng, NCH, P, DEAD_W)
    for _ in range(ncyc):
        await b.cycle(stim.next())
    n = b.check_shift()
    kinds = list(b.kinds.values())
    dut._log.info("PHASE %d: %d clocks, both instances bit-exact with their models; restarts %d rst, %d sync; "
                  "shift checks %s; props a %s b %s", PHASE, b.t + 1, kinds.count("rst"), kinds.count("sync"), n,
                  b.pa.n, b.pb.n)
    assert kinds.count("rst") >= 2 and kinds.count("sync") >= 5, "too few restarts"
    assert n["first_period"] > 0 and n["after_rst"] > 0 and n["after_sync"] > 0 and n["ps"] > 0 and n["adc"] > 0
    assert b.pb.n["turn_on_dead"] > 0 and b.pb.n["fault_off"] > 0


@cocotb.test(skip=SUITE != "phase")
async def test_phase_steady(dut):
    """Constant inputs from reset, then a sync rise: the strobes of u_b are u_a's delayed by PHASE from
    the first clock after reset and after the sync; once both run, hi / lo / on of u_b are u_a's
    delayed by PHASE (also across u_a's boundary loads of a new compare)."""
    rng = random.Random(SEED + 7)
    b = PhaseBench(dut)
    await b.start()
    cm = [rng.randint(1, P - 1) for _ in range(NCH)]
    mode = MODE_COMPL
    hold = PwmInputs(enable=1, mode=mode, dead=1, cmp_in=cm)
    await b.cycle(replace(hold, rst=1))
    await b.cycle(replace(hold, cmp_load=1))
    for _ in range(6 * P):
        await b.cycle(hold)
    t_sync = b.t + 1
    for _ in range(max(1, SYNC_STAGES)):         # a sync pulse (held for the synchroniser)
        await b.cycle(replace(hold, sync_in=1))
    for _ in range(8 * P + PHASE):
        await b.cycle(hold)
    n = b.check_shift()
    # outputs: both running from u_a's second boundary after each restart and u_b's first one, so
    # u_b(t) == u_a(t - PHASE) from 2P + PHASE + 1 clocks after the restart on
    cmpd = 0
    for e, e_end in zip(b.restart, b.restart[1:] + [b.t + 1]):
        for t in range(e + 2 * P + PHASE + 2, e_end):
            oa, ob = b.rec["a"][t - PHASE][2], b.rec["b"][t][2]
            for f in ("hi", "lo", "on"):
                assert ob[f] == oa[f], f"{f} of u_b at {t} {ob[f]} != u_a at {t - PHASE} {oa[f]} (restart at {e})"
            cmpd += 1
    assert cmpd > 4 * P and b.kinds.get(t_sync + SYNC_STAGES) == "sync", (cmpd, b.kinds, t_sync)
    dut._log.info("PHASE %d steady: shift checks %s; %d clocks of hi/lo/on shifted; cmp %s", PHASE, n, cmpd, cm)


@pytest.mark.cost(12)          # seconds on an idle core (make sim starts the costliest first)
def test_pwm_center_phase():
    """The carrier stagger at P = 13: PHASE < P, = P, > P (one with SYNC_STAGES = 2)."""
    for ph, ss in ((5, 0), (13, 0), (20, 2)):
        _run("phase", toplevel="pwm_center_phase", env={"PWM_PHASE": str(ph)}, NCH=3, PWM_HALF_PERIOD=13,
             DEAD_W=4, SYNC_STAGES=ss, SYNC_LEAD=2, PHASE=ph)


@pytest.mark.cost(11)          # seconds on an idle core (make sim starts the costliest first)
def test_pwm_center_phase_default():
    """Default P (2500) with axis 1 and axis 3 of the four-axis stagger (header PWM_STAGGER_4)."""
    from empc.rtlmodel.pwm_center import default_half_period
    from runner import roms_dir
    from empc import header
    import mx_schedule
    h = header.read(roms_dir() / "empc_formats.vh")
    for n in (2, 3, 4):                 # the header's stagger is the schedule's (flow/mx_schedule.py)
        assert h[f"PWM_STAGGER_{n}"] == mx_schedule.stagger(n, mx_schedule.TIMING)[1], (n, h)
    step = h["PWM_STAGGER_4"]
    assert step == 1258, step
    p = default_half_period()
    for ph in (step, 3 * step):
        _run("phase", toplevel="pwm_center_phase", env={"PWM_PHASE": str(ph), "PWM_RANDOM_CYCLES": "0"},
             NCH=3, PWM_HALF_PERIOD=p, DEAD_W=8, SYNC_STAGES=0, SYNC_LEAD=2, PHASE=ph)
