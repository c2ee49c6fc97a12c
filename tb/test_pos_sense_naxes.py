"""pos_sense with NAXES > 1: one shared reducer / alignment engine and one angle DSP.

Four builds: NAXES = 4 with CPR/P 4000/4 and 1000/7 (REALIGN = 1), NAXES = 3 (4096/3),
NAXES = 2 (4000/4, REALIGN = 1); the figures below are NAXES = 4's.

Every output of every axis is compared bit-exact with the stepping model
empc.rtlmodel.pos_sense.PosSenseMx on every clock.  Independently of the model:
  * theta_ok latency: after the last count change / alignment event of an axis,
    theta_ok rises within latency_bound(4)[1] = 168 clocks (any situation), and
    within latency_bound(4)[0] = 136 clocks after four simultaneous 32-bit jumps
    (-2**31, the longest job: 32 bit clocks) from every engine / round-robin phase;
  * while theta_ok = 1 and the axis is index-aligned (cal_offset unchanged for 8
    clocks), theta = angle((true - ref) mod CPR) + cal_offset and pos_mod =
    (true - ref) mod CPR, ref tracked by the test (first index after reset /
    align_clear);
  * isolation: axis b driven by the same stimulus twice, once with the other
    axes still and once with heavy activity on them (jumps, index, HALL,
    align_clear, offsets): b's speed/sample outputs are identical every clock,
    and b's theta/valid/aligned/pos_mod are identical on every clock where
    theta_ok[b] = 1 in both runs (only the time to theta_ok may differ).
The seed is EMPC_SEED (printed).
"""
from __future__ import annotations

import json
import os
import random

import pytest

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from empc.rtlmodel.pos_sense import PosSenseMx, angle, latency_bound

DEFAULT_SEED = 4242
MASK32 = (1 << 32) - 1
NAMES_IN = ("pos", "index_event", "index_pos", "hall_sector", "hall_valid", "hall_change", "cal_offset",
            "hall_offset", "align_clear", "sample")
WIDTH_IN = dict(pos=32, index_event=1, index_pos=32, hall_sector=3, hall_valid=1, hall_change=1, cal_offset=16,
                hall_offset=16, align_clear=1, sample=1)
PULSES = ("index_event", "hall_change", "align_clear", "sample")


class Env:
    def __init__(self, dut):
        self.dut = dut
        cfg = json.loads(os.environ["TB_PARAMS"])
        self.n = cfg["NAXES"]
        self.cpr, self.p = cfg["CPR"], cfg["POLE_PAIRS"]
        self.realign = bool(cfg.get("REALIGN", 0))
        self.seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
        self.rng = random.Random(self.seed)
        self.model = PosSenseMx(self.n, self.cpr, self.p, realign=self.realign)
        self.bound_sim, self.bound_any = latency_bound(self.n)
        self.mw = len(dut.pos_mod) // self.n
        self.wout = dict(theta=16, valid=1, aligned=1, theta_ok=1, pos_mod=self.mw, speed=32, speed_q=32,
                         speed_sat=1, pos_at_sample=32, theta_at_sample=16, sample_valid=1)
        self.hin = {k: getattr(dut, k) for k in NAMES_IN}
        self.hout = {k: getattr(dut, k) for k in PosSenseMx.OUTPUTS}
        self.n_clk = 0
        self.n_lat = 0
        self.n_exact = 0
        self.max_lat = 0
        dut._log.info("NAXES %d CPR %d P %d REALIGN %d: theta_ok bounds %d (simultaneous 32-bit jumps) / %d (any); "
                      "seed %d (EMPC_SEED)", self.n, self.cpr, self.p, self.realign, self.bound_sim, self.bound_any,
                      self.seed)

    def fresh(self):
        n = self.n
        self.inp = {k: [0] * n for k in NAMES_IN}
        self.true = [0] * n
        self.last = [0] * n           # clock of the last count change / alignment input per axis
        self.ref = [None] * n         # true count of the index alignment (None: not aligned)
        self.cal_age = [0] * n
        self.trace = []               # per clock: outputs dict (lists)
        self.written = {}
        self._prev_pos = None
        self._prev_hv = [0] * n
        self._prev_cal = None
        self._index_true = [0] * n

    async def start(self):
        d = self.dut
        if not hasattr(self, "clk_started"):
            Clock(d.clk, 10, unit="ns").start()
            self.clk_started = True
        self.fresh()
        for k in NAMES_IN:
            self._write(k, self.inp[k])
        d.rst.value = 1
        for _ in range(3):
            await FallingEdge(d.clk)
        d.rst.value = 0
        self.model.reset()
        self.n_clk0 = self.n_clk

    def _write(self, k, vals):
        w = WIDTH_IN[k]
        v = 0
        for a, x in enumerate(vals):
            v |= (int(x) & ((1 << w) - 1)) << (w * a)
        if self.written.get(k) != v:
            self.hin[k].value = v
            self.written[k] = v

    async def cycle(self, pulses=None):
        """One clock; pulses: {name: [per-axis]} for this clock only."""
        n = self.n
        inp = {k: list(v) for k, v in self.inp.items()}
        if pulses:
            for k, v in pulses.items():
                inp[k] = list(v)
        inp["pos"] = [t & MASK32 for t in self.true]
        c = self.n_clk - self.n_clk0
        for a in range(n):
            prev = self._prev_pos
            if (prev is not None and prev[a] != inp["pos"][a]) or inp["index_event"][a] or inp["hall_change"][a] \
                    or (inp["hall_valid"][a] and not self._prev_hv[a]):
                self.last[a] = c
            # the test's own alignment state
            if inp["index_event"][a] and (self.ref[a] is None or inp["align_clear"][a] or self.realign):
                self.ref[a] = self._index_true[a]
            elif inp["align_clear"][a]:
                self.ref[a] = None
            self.cal_age[a] = 0 if (self._prev_cal is not None and self._prev_cal[a] != inp["cal_offset"][a]) \
                else self.cal_age[a] + 1
        self._prev_pos = list(inp["pos"])
        self._prev_hv = list(inp["hall_valid"])
        self._prev_cal = list(inp["cal_offset"])
        for k in NAMES_IN:
            self._write(k, inp[k])
        self.model.step(**inp)
        await FallingEdge(self.dut.clk)
        self.n_clk += 1
        c += 1
        mo = self.model.outputs()
        got = {}
        for k in PosSenseMx.OUTPUTS:
            raw = int(self.hout[k].value)
            w = self.wout[k]
            got[k] = [(raw >> (w * a)) & ((1 << w) - 1) for a in range(n)]
            assert got[k] == mo[k], f"clock {c}: {k} = {got[k]} model {mo[k]}"
        self.trace.append(got)
        for a in range(n):
            lat = c - self.last[a]
            if got["theta_ok"][a]:
                if self.ref[a] is not None and self.cal_age[a] >= 8 and got["aligned"][a]:
                    mm = (self.true[a] - self.ref[a]) % self.cpr
                    assert got["pos_mod"][a] == mm, f"clock {c} axis {a}: pos_mod {got['pos_mod'][a]} expected {mm}"
                    exp = angle(mm, self.cpr, self.p, inp["cal_offset"][a])
                    assert got["theta"][a] == exp, f"clock {c} axis {a}: theta {got['theta'][a]} expected {exp}"
                    self.n_exact += 1
            else:
                assert lat <= self.bound_any, f"clock {c} axis {a}: theta_ok still 0 {lat} clocks after the last change"
                self.max_lat = max(self.max_lat, lat)
                self.n_lat += 1
        return got

    async def wait(self, k):
        for _ in range(k):
            await self.cycle()

    def index_at(self, a, true_idx):
        self._index_true[a] = true_idx
        self.inp["index_pos"][a] = true_idx & MASK32

    def ok_all(self):
        return all(self.trace[-1]["theta_ok"])


def pulse(n, **axes):
    """{name: [0..]} with 1 for the axes listed, e.g. pulse(4, index_event=(0, 2))."""
    return {k: [int(a in v) for a in range(n)] for k, v in axes.items()}


async def random_activity(env, clocks, axes, rng, big_gap=200, hall=True, events=True):
    """Random motion / events on the given axes for `clocks` clocks (other axes untouched)."""
    n = env.n
    last_big = {a: -big_gap for a in axes}
    rate = {a: 0.3 for a in axes}
    for t in range(clocks):
        pulses = {k: [0] * n for k in PULSES}
        for a in axes:
            if rng.random() < 1 / 300:      # per-axis activity: fast, slow or still phases
                rate[a] = rng.choice((0.3, 0.02, 0.0))
            r = rng.random()
            if r >= rate[a] * 1.15:
                pass
            elif r < rate[a]:
                env.true[a] += rng.choice((1, -1))
            elif r < rate[a] * 1.1:
                env.true[a] += rng.randint(-40, 40)
            elif t - last_big[a] >= big_gap:
                env.true[a] += rng.randint(-(1 << 30), 1 << 30)
                last_big[a] = t
            if rng.random() < 0.003:
                env.inp["cal_offset"][a] = rng.randrange(65536)
            if rng.random() < 0.003:
                env.inp["hall_offset"][a] = rng.randrange(65536)
            if hall and rng.random() < 0.01:
                env.inp["hall_valid"][a] = int(rng.random() < 0.9)
                s = env.inp["hall_sector"][a] or 1
                env.inp["hall_sector"][a] = rng.choice((s % 6 + 1, (s - 2) % 6 + 1, rng.randint(1, 6)))
                pulses["hall_change"][a] = 1
            if events:
                if rng.random() < 0.004:
                    env.index_at(a, env.true[a] - rng.randint(-3, 3))
                    pulses["index_event"][a] = 1
                if rng.random() < 0.002:
                    pulses["align_clear"][a] = 1
            if rng.random() < 0.01:
                pulses["sample"][a] = 1
        await env.cycle(pulses)


@cocotb.test()
async def fuzz_all_axes(dut):
    """Random per-axis motion, jumps (< 2**30, across the wrap), index / HALL / align_clear, offsets."""
    env = Env(dut)
    await env.start()
    rng = env.rng
    n = env.n
    for a in range(n):
        env.true[a] = (1 << 31) - rng.randrange(1 << 16)        # near the 2**31 wrap
        env.index_at(a, env.true[a])
        env.inp["cal_offset"][a] = rng.randrange(65536)
        env.inp["hall_offset"][a] = rng.randrange(65536)
    await env.wait(20)
    await env.cycle(pulse(n, index_event=range(n)))           # simultaneous index on all axes
    await random_activity(env, 6000, range(n), rng)
    # simultaneous events on all axes in one clock
    for kind in ("index_event", "align_clear", "hall_change", "sample"):
        for a in range(n):
            env.true[a] += rng.randint(-1000, 1000)
            env.index_at(a, env.true[a] - 1)
            env.inp["hall_valid"][a] = 1
            env.inp["hall_sector"][a] = rng.randint(1, 6)
        await env.cycle(pulse(n, **{kind: range(n)}))
        await env.wait(env.bound_any + 2)
        assert env.ok_all(), f"after simultaneous {kind}: theta_ok {env.trace[-1]['theta_ok']}"
    await random_activity(env, 6000, range(n), rng)
    await env.wait(env.bound_any + 2)
    assert env.ok_all()
    dut._log.info("fuzz: %d clocks x %d axes bit-exact vs PosSenseMx; %d theta checks vs the true angle; "
                  "theta_ok latency max %d <= %d clocks (%d not-ok samples)",
                  env.n_clk, n, env.n_exact, env.max_lat, env.bound_any, env.n_lat)
    assert env.n_exact > 1000


@cocotb.test()
async def latency_bound_jumps(dut):
    """NAXES simultaneous -2**31 jumps from every phase: theta_ok within bound_sim (136 at NAXES = 4); stale
    jobs within bound_any (168)."""
    env = Env(dut)
    await env.start()
    rng = env.rng
    n = env.n
    for a in range(n):
        env.true[a] = rng.randrange(1 << 31)
        env.index_at(a, env.true[a])
    await env.cycle(pulse(n, index_event=range(n)))
    await env.wait(env.bound_any)
    worst_sim = 0
    for phase in range(2 * n + 3):
        await env.wait(phase)
        assert env.ok_all()
        for a in range(n):
            env.true[a] -= 1 << 31
        lat = [None] * n
        for c in range(1, env.bound_any + 2):
            got = await env.cycle()
            for a in range(n):
                if lat[a] is None and got["theta_ok"][a]:
                    lat[a] = c
        assert None not in lat, f"phase {phase}: theta_ok never rose {lat}"
        assert max(lat) <= env.bound_sim, f"phase {phase}: latencies {lat} > {env.bound_sim}"
        worst_sim = max(worst_sim, max(lat))
    # worst case of any kind: axis a0's previous count was just captured when it moves again
    worst_any = 0
    for a0 in range(n):
        for dt in range(n):
            await env.wait(dt)
            for a in range(n):
                env.true[a] -= 1 << 31
            seen_busy = False
            for c in range(4 * 32):
                await env.cycle()
                busy_a0 = env.model.busy and env.model.cur == a0
                if busy_a0:
                    seen_busy = True
                    break
            assert seen_busy
            env.true[a0] -= 1 << 31
            lat = None
            for c in range(1, env.bound_any + 2):
                got = await env.cycle()
                if got["theta_ok"][a0]:
                    lat = c
                    break
            assert lat is not None and lat <= env.bound_any, f"axis {a0}: stale-job latency {lat}"
            worst_any = max(worst_any, lat)
            await env.wait(env.bound_any)
    dut._log.info("latency: %d simultaneous 32-bit jumps, %d phases: worst %d <= %d clocks; new count right "
                  "after the capture of the old one (stale job + the others' jobs + own): worst %d <= %d clocks",
                  n, 2 * n + 3, worst_sim, env.bound_sim, worst_any, env.bound_any)


@cocotb.test()
async def isolation(dut):
    """Axis b: same stimulus with and without activity on the other axes."""
    env = Env(dut)
    n = env.n
    runs = []
    for b in (1, n - 1):
        seed_b = env.seed * 7 + b
        for busy_others in (False, True):
            await env.start()
            rng_b = random.Random(seed_b)
            rng_o = random.Random(seed_b + 1)
            for a in range(n):
                env.true[a] = 1000 + 77 * a
                env.index_at(a, env.true[a])
                env.inp["cal_offset"][a] = 1234 * (a + 1)
            await env.cycle(pulse(n, index_event=range(n)))
            others = [a for a in range(n) if a != b]
            # b: random motion, a still period, an index re-alignment attempt, HALL (ignored, aligned)
            for t in range(3000):
                pulses = {k: [0] * n for k in PULSES}
                phase = (t // 500) % 2           # b still in odd 500-clock windows
                if phase == 0:
                    r = rng_b.random()
                    if r < 0.3:
                        env.true[b] += rng_b.choice((1, -1))
                    elif r < 0.31:
                        env.true[b] += rng_b.randint(-(1 << 29), 1 << 29)
                if rng_b.random() < 0.01:
                    pulses["sample"][b] = 1
                if busy_others:
                    for a in others:
                        r = rng_o.random()
                        if r < 0.4:
                            env.true[a] += rng_o.choice((1, -1, 5))
                        elif r < 0.45:
                            env.true[a] -= rng_o.randrange(1 << 30)
                        if rng_o.random() < 0.01:
                            env.index_at(a, env.true[a])
                            pulses["index_event"][a] = 1
                        if rng_o.random() < 0.005:
                            pulses["align_clear"][a] = 1
                        if rng_o.random() < 0.01:
                            env.inp["hall_valid"][a] = 1
                            env.inp["hall_sector"][a] = rng_o.randint(1, 6)
                            pulses["hall_change"][a] = 1
                        if rng_o.random() < 0.005:
                            env.inp["cal_offset"][a] = rng_o.randrange(65536)
                            env.inp["hall_offset"][a] = rng_o.randrange(65536)
                        if rng_o.random() < 0.01:
                            pulses["sample"][a] = 1
                await env.cycle(pulses)
            runs.append((b, busy_others, [dict((k, v[b]) for k, v in tr.items()) for tr in env.trace]))
    n_cmp = n_ok = 0
    for i in range(0, len(runs), 2):
        b, _, quiet = runs[i]
        _, _, loud = runs[i + 1]
        assert len(quiet) == len(loud)
        for c, (q, l) in enumerate(zip(quiet, loud)):
            for k in ("speed", "speed_q", "speed_sat", "pos_at_sample", "sample_valid"):
                assert q[k] == l[k], f"axis {b} clock {c}: {k} {q[k]} vs {l[k]} with the other axes busy"
            if q["theta_ok"] and l["theta_ok"]:
                for k in ("theta", "valid", "aligned", "pos_mod"):
                    assert q[k] == l[k], f"axis {b} clock {c}: {k} {q[k]} vs {l[k]} with the other axes busy"
                n_ok += 1
            n_cmp += 1
        still = sum(1 for q in quiet if q["theta_ok"])
        assert still > 1000
    dut._log.info("isolation: axes 1 and %d, %d clocks compared, %d with theta_ok in both runs identical", n - 1,
                  n_cmp, n_ok)


@pytest.mark.parametrize("naxes,cpr,p,realign", [(4, 4000, 4, 0), (4, 1000, 7, 1), (3, 4096, 3, 0), (2, 4000, 4, 1)])
def test_pos_sense_naxes(naxes, cpr, p, realign):
    from runner import run
    params = dict(CPR=cpr, POLE_PAIRS=p, NAXES=naxes, REALIGN=realign)
    run(toplevel="pos_sense", test_module="test_pos_sense_naxes", parameters=params,
        name=f"test_pos_sense_naxes{naxes}_{cpr}_{p}_{realign}", extra_env={"TB_PARAMS": json.dumps(params)})
