"""Tests of pos_sense (electrical angle, HALL/index alignment, speed eq. 37).

Model-only (pytest): the bit-exact angle function of empc.rtlmodel.pos_sense is
checked for every m in [0, CPR) against the exact 2**16*frac(P*m/CPR) within
the stated bound, for the default and non-multiple CPR/P pairs.

cocotb (five builds: CPR/P = 4000/4 default, 4096/3, 1000/7, and 4000/4, 1000/7 with
ANGLE_DSP = 0, the multiplier-free angle): every clock all outputs are compared
bit-exact with the stepping model PosSense; on top of that,
independently of the model:
  * theta after settling equals round-half-up angle of the true position
    relative to the index, within the stated bound of round(2**16*frac(P*x/CPR))
    + cal_offset, while stepping +-1 over more than one revolution in each
    direction and after random multi-count jumps (up to +-2**30, across the
    +-2**31 counter wrap);
  * after N whole mechanical turns (N up to ~10**5, both directions) theta and
    pos_mod return to exactly the same value (no drift);
  * HALL alignment: sector centre at power-up, sector edges at forward /
    backward HALL transitions, centre after a jump, hand-over to the index
    (aligned), HALL ignored afterwards, align_clear without a jump;
  * speed = position difference between sample strobes (also across the wrap),
    speed_q = speed * 2**16 saturated with speed_sat, pos/theta_at_sample.
"""
from __future__ import annotations

import json
import os
import random
from fractions import Fraction

import pytest

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from empc.rtlmodel.pos_sense import (PosSense, angle, angle_error, angle_error_bound, angle_params)

DEFAULT_SEED = 31337
MASK32 = (1 << 32) - 1
CONFIGS = [(4000, 4), (4096, 3), (1000, 7)]
PULSES = ("index_event", "hall_change", "align_clear", "sample")


def exact_round(x: Fraction) -> int:
    return int((x + Fraction(1, 2)) // 1)


def hall_ref(k: int) -> int:
    """Independent: round(k * 2**16 / 12) mod 2**16."""
    return exact_round(Fraction(k * 65536, 12)) % 65536


class Env:
    def __init__(self, dut):
        self.dut = dut
        cfg = json.loads(os.environ["TB_PARAMS"])
        self.cpr, self.p = cfg["CPR"], cfg["POLE_PAIRS"]
        self.realign = bool(cfg.get("REALIGN", 0))
        self.seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
        self.rng = random.Random(self.seed ^ self.cpr)
        self.model = PosSense(self.cpr, self.p, realign=self.realign)
        self.bound = angle_error_bound(self.cpr, self.p)
        self.inp = dict(pos=0, index_event=0, index_pos=0, hall_sector=0, hall_valid=0, hall_change=0,
                        cal_offset=0, hall_offset=0, align_clear=0, sample=0)
        self.true = 0              # unwrapped position (pos = true mod 2**32)
        self.n = 0
        self.n_exact = 0
        dut._log.info("CPR %d P %d REALIGN %d: ANGLE_MUL %d, S %d, bound %.3f LSB; seed %d (EMPC_SEED)",
                      self.cpr, self.p, self.realign, *angle_params(self.cpr, self.p), self.bound, self.seed)

    async def start(self):
        d = self.dut
        Clock(d.clk, 10, unit="ns").start()
        self.hin = {k: getattr(d, k) for k in self.inp}
        self.hout = {k: getattr(d, k) for k in PosSense.OUTPUTS}
        self.written = {}
        for k, v in self.inp.items():
            self.hin[k].value = v
            self.written[k] = v
        d.rst.value = 1
        for _ in range(3):
            await FallingEdge(d.clk)
        d.rst.value = 0
        self.model.reset()

    async def cycle(self, **pulses):
        d = self.dut
        inp = dict(self.inp)
        inp.update(pulses)
        inp["pos"] = self.true & MASK32
        for k, v in inp.items():
            v = int(v)
            if self.written.get(k) != v:
                self.hin[k].value = v
                self.written[k] = v
        self.model.step(**inp)
        await FallingEdge(d.clk)
        self.n += 1
        mo = self.model.outputs()
        for k, v in mo.items():
            got = int(self.hout[k].value)
            assert got == v, f"cycle {self.n}: {k}={got:#x} model={v:#x}"
        return mo

    async def wait(self, n):
        for _ in range(n):
            await self.cycle()

    async def goto(self, target):
        """Move to target in jumps below 2**30 (a real axis never moves 2**31 counts between clocks)."""
        while self.true != target:
            rest = target - self.true
            self.true += max(min(rest, 1 << 30), -(1 << 30))
            await self.settle()

    async def settle(self):
        """Enough clocks for a jump of any size to reach theta (<= 32 + 4)."""
        await self.wait(38)

    def theta(self):
        return int(self.dut.theta.value)

    async def align_index(self, index_true, lag=0):
        """index_event with index_pos = index_true (mod 2**32); pos may already be lag counts further."""
        self.ref = index_true
        self.inp["index_pos"] = index_true & MASK32
        self.true = index_true + lag
        await self.cycle(index_event=1)

    def check_exact(self, what):
        """Settled theta vs the angle of the true position (bit-exact function and exact bound)."""
        m = (self.true - self.ref) % self.cpr
        th = self.theta()
        assert int(self.dut.pos_mod.value) == m, f"{what}: pos_mod {int(self.dut.pos_mod.value)} expected {m}"
        assert th == angle(m, self.cpr, self.p, self.inp["cal_offset"]), f"{what}: theta {th} vs angle()"
        err = angle_error(th, m, self.cpr, self.p, self.inp["cal_offset"])
        assert abs(err) <= self.bound, f"{what}: theta {th} error {err:.3f} > {self.bound:.3f} LSB"
        exact_r = exact_round(Fraction(65536 * ((self.p * m) % self.cpr), self.cpr) + self.inp["cal_offset"]) % 65536
        dr = (th - exact_r + 32768) % 65536 - 32768
        assert abs(dr) <= int(self.bound + 0.5), f"{what}: theta {th} vs round(exact) {exact_r}"
        self.n_exact += 1
        return th


@cocotb.test()
async def step_revolutions(dut):
    """Index alignment, then +-1 steps (2..5 clocks apart) over > 1 revolution each way."""
    env = Env(dut)
    await env.start()
    rng = env.rng
    env.inp["cal_offset"] = rng.randrange(65536)
    env.true = rng.randrange(-(1 << 31), 1 << 31)
    await env.wait(40)
    assert int(dut.valid.value) == 0
    await env.align_index(env.true, lag=0)
    await env.wait(4)
    assert int(dut.aligned.value) == 1 and int(dut.valid.value) == 1
    th0 = env.check_exact("at index")
    assert th0 == env.inp["cal_offset"], "angle at the index must be cal_offset"
    for direction, n in ((+1, env.cpr + 37), (-1, env.cpr + 37)):
        for k in range(n):
            env.true += direction
            dw = rng.choice((2, 2, 2, 5))
            await env.wait(dw)
            if dw >= 5:
                env.check_exact(f"step {k}")
        await env.settle()
        env.check_exact("turn end")
        if direction > 0:
            # one full turn ahead of the index: same angle as at the index
            assert (env.true - env.ref) == env.cpr + 37
    assert env.true == env.ref
    assert env.theta() == th0 and int(dut.pos_mod.value) == 0, "no return to the same angle"
    dut._log.info("steps: %d counts forward then back (> 1 revolution each way), %d exact checks, %d clocks "
                  "bit-exact vs model", env.cpr + 37, env.n_exact, env.n)


@cocotb.test()
async def many_turns_jumps(dut):
    """Random multi-count jumps (also across the 2**31 wrap), whole-turn returns without drift."""
    env = Env(dut)
    await env.start()
    rng = env.rng
    env.inp["cal_offset"] = rng.randrange(65536)
    env.true = (1 << 31) - 5 * env.cpr       # close to the wrap
    await env.wait(5)
    await env.align_index(env.true - 3, lag=3)    # index latched 3 counts ago
    await env.settle()
    th0 = env.check_exact("aligned")
    n_turn_checks = 0
    for rep in range(60):
        kind = rng.random()
        if kind < 0.4:
            # whole turns (either direction, up to ~1e5) in several pieces, then back at the start angle
            start_true, start_theta = env.true, env.theta()
            turns = rng.choice((1, 2, 7, 1000, 99991)) * rng.choice((1, -1))
            target = env.true + turns * env.cpr
            while env.true != target:
                rest = target - env.true
                piece = rest if abs(rest) < 3 * env.cpr else rng.randint(1, abs(rest)) * (1 if rest > 0 else -1)
                env.true += piece
                await env.wait(rng.randint(1, 40))
            await env.settle()
            assert env.theta() == start_theta, f"{turns} turns: theta {env.theta()} != {start_theta} (drift)"
            env.check_exact(f"{turns} turns")
            n_turn_checks += 1
        elif kind < 0.7:
            env.true += rng.randint(-(1 << 30), 1 << 30)
            await env.settle()
            env.check_exact("big jump")
        else:
            for _ in range(rng.randint(1, 20)):
                env.true += rng.randint(-3, 3)
                await env.wait(1)
            await env.settle()
            env.check_exact("small jumps")
    await env.goto(env.ref + 3 + 12345 * env.cpr)      # th0 was taken 3 counts past the index
    assert env.theta() == th0
    dut._log.info("jumps: %d whole-turn returns (up to 99991 turns, incl. the 2**31 wrap), %d exact checks, "
                  "%d clocks bit-exact vs model", n_turn_checks, env.n_exact, env.n)


@cocotb.test()
async def hall_then_index(dut):
    """HALL rough alignment (centre, edges, jump), hand-over to the index, align_clear."""
    env = Env(dut)
    await env.start()
    rng = env.rng
    ho = rng.randrange(65536)
    env.inp["hall_offset"] = ho
    env.inp["cal_offset"] = rng.randrange(65536)
    env.true = rng.randrange(1 << 20)
    await env.wait(40)
    f = lambda counts: angle(counts, env.cpr, env.p)     # noqa: E731  f(m) part of the angle
    s = rng.randint(1, 6)
    env.inp.update(hall_sector=s, hall_valid=1)
    await env.wait(4)
    assert int(dut.valid.value) == 1 and int(dut.aligned.value) == 0
    assert env.theta() == (hall_ref(2 * s - 1) + ho) % 65536, "power-up: sector centre"
    base_true = env.true
    n_hall = 0
    for _ in range(30):
        env.true += rng.randint(-40, 40)
        await env.settle()
        exp = ((hall_ref(2 * s - 1) if n_hall == 0 else env.hall_base) + ho + f(env.true - base_true)) % 65536
        assert env.theta() == exp, f"HALL + counts: theta {env.theta()} expected {exp}"
        r = rng.random()
        new = s % 6 + 1 if r < 0.45 else (s - 2) % 6 + 1 if r < 0.9 else (s + 2) % 6 + 1
        if new == s % 6 + 1:
            env.hall_base = hall_ref(2 * new - 2)           # entering the sector at its start
        elif new == (s - 2) % 6 + 1:
            env.hall_base = hall_ref((2 * new) % 12)        # entering it at its end
        else:
            env.hall_base = hall_ref(2 * new - 1)           # implausible jump: centre
        s = new
        env.inp["hall_sector"] = s
        await env.cycle(hall_change=1)
        base_true = env.true
        n_hall += 1
        await env.wait(4)
        assert env.theta() == (env.hall_base + ho) % 65536, "theta at the HALL edge"
    # index takes over
    env.true += 17
    await env.align_index(env.true - 2, lag=2)
    await env.settle()
    assert int(dut.aligned.value) == 1
    env.check_exact("index after HALL")
    # a second index with a different latched count: ignored (REALIGN=0) or re-aligns (REALIGN=1)
    old_ref = env.ref
    env.true += 3
    await env.align_index(env.true - 3 - 2, lag=5)
    if not env.realign:
        env.ref = old_ref
    await env.settle()
    env.check_exact("second index")
    # HALL edges are ignored while aligned
    env.inp["hall_sector"] = s % 6 + 1
    await env.cycle(hall_change=1)
    env.true += 5
    await env.settle()
    env.check_exact("HALL ignored")
    assert int(dut.aligned.value) == 1
    # cal_offset is live
    env.inp["cal_offset"] = (env.inp["cal_offset"] + 1234) % 65536
    await env.wait(3)
    env.check_exact("cal_offset changed")
    # align_clear: back to HALL mode without a jump
    th = env.theta()
    await env.cycle(align_clear=1)
    await env.wait(4)
    assert int(dut.aligned.value) == 0 and env.theta() == th, "align_clear must not move theta"
    # until the next HALL edge the angle stays on the index calibration: cal_offset live, hall_offset not
    env.inp["hall_offset"] = (env.inp["hall_offset"] + 777) % 65536
    await env.wait(4)
    assert env.theta() == th, "after align_clear, hall_offset must not move theta before a HALL edge"
    env.inp["cal_offset"] = (env.inp["cal_offset"] + 4321) % 65536
    await env.wait(4)
    assert env.theta() == (th + 4321) % 65536, "after align_clear, cal_offset stays live until a HALL edge"
    prev_sector = env.inp["hall_sector"]          # last sector the DUT saw (HALL is tracked while aligned)
    new = s % 6 + 1 if s % 6 + 1 != prev_sector else (s + 1) % 6 + 1
    env.inp["hall_sector"] = new
    await env.cycle(hall_change=1)
    await env.wait(4)
    assert int(dut.aligned.value) == 0
    assert new == prev_sector % 6 + 1, "test setup: a forward HALL edge"
    exp = (hall_ref(2 * new - 2) + env.inp["hall_offset"]) % 65536
    assert env.theta() == exp, f"HALL edge after align_clear: theta {env.theta()} expected {exp} (start + hall_offset)"
    await env.align_index(env.true, lag=0)
    await env.wait(4)
    assert int(dut.aligned.value) == 1 and env.theta() == env.inp["cal_offset"]
    dut._log.info("HALL: %d HALL transitions (fwd/bwd/jump), index hand-over, align_clear; %d clocks "
                  "bit-exact vs model", n_hall, env.n)


@cocotb.test()
async def speed_sampling(dut):
    """sample strobes: speed, speed_q (saturating), pos/theta_at_sample; across the wrap."""
    env = Env(dut)
    await env.start()
    rng = env.rng
    env.true = (1 << 31) - 2000
    await env.align_index(env.true)
    await env.wait(5)
    ts = 25
    last_true = None
    n_samples = n_sat = 0
    for k in range(100):
        v = rng.choice((0, 1, -1, 7, -13, 200, -5000, 40000, -(1 << 15), (1 << 15) - 1, 1 << 20))
        for t in range(ts - 1):
            if t < abs(v) and abs(v) < ts:
                env.true += 1 if v > 0 else -1
            elif t == 0 and abs(v) >= ts:
                env.true += v
            await env.cycle()
        theta_before = env.theta()          # theta output during the sample clock
        await env.cycle(sample=1)
        sample_true = env.true
        assert int(dut.sample_valid.value) == 1
        assert int(dut.theta_at_sample.value) == theta_before
        await env.cycle()
        assert int(dut.sample_valid.value) == 0
        sp = dut.speed.value.to_signed()
        spq = dut.speed_q.value.to_signed()
        exp = 0 if last_true is None else sample_true - last_true
        assert sp == exp, f"sample {k}: speed {sp} expected {exp}"
        q = exp * 65536
        sat = not (-(1 << 31) <= q < (1 << 31))
        q = max(min(q, (1 << 31) - 1), -(1 << 31))
        assert spq == q and int(dut.speed_sat.value) == int(sat), f"sample {k}: speed_q {spq} expected {q}"
        assert int(dut.pos_at_sample.value) == sample_true & MASK32
        n_samples += 1
        n_sat += sat
        last_true = sample_true
    dut._log.info("speed: %d samples (%d saturated in Q16.16), across the 2**31 wrap; %d clocks bit-exact",
                  n_samples, n_sat, env.n)


@cocotb.test()
async def random_fuzz(dut):
    """All inputs random (pulses, jumps, offsets) for a few thousand clocks, bit-exact vs model."""
    env = Env(dut)
    await env.start()
    rng = env.rng
    for _ in range(3000):
        r = rng.random()
        if r < 0.3:
            env.true += rng.choice((1, -1))
        elif r < 0.33:
            env.true += rng.randint(-(1 << 31), 1 << 31)
        if rng.random() < 0.01:
            env.inp["cal_offset"] = rng.randrange(65536)
        if rng.random() < 0.01:
            env.inp["hall_offset"] = rng.randrange(65536)
        if rng.random() < 0.02:
            env.inp["hall_valid"] = rng.random() < 0.8
            env.inp["hall_sector"] = rng.randint(1, 6)
        pulses = {k: int(rng.random() < 0.01) for k in PULSES}
        if pulses["index_event"]:
            env.inp["index_pos"] = (env.true - rng.randint(-3, 3)) & MASK32
        await env.cycle(**pulses)
    dut._log.info("fuzz: %d clocks bit-exact vs model", env.n)


# ----------------------------------------------------------------------------- model-only checks
@pytest.mark.parametrize("cpr,p", CONFIGS + [(2048, 1), (5000, 7), (65536, 5), (100000, 50)])
def test_angle_function_bound(cpr, p):
    """angle(m) for every m in [0, CPR): within the stated bound of the exact angle, and of round()."""
    bound = angle_error_bound(cpr, p)
    mul, s = angle_params(cpr, p)
    assert mul < (1 << 17), "ANGLE_MUL must fit one DSP48A1 operand"
    worst = 0.0
    for m in range(cpr):
        a = angle(m, cpr, p)
        e = abs(angle_error(a, m, cpr, p))
        worst = max(worst, e)
        assert e <= bound, (m, a, e, bound)
    assert angle(cpr, cpr, p) == angle(0, cpr, p) == 0
    print(f"CPR {cpr} P {p}: S {s} MUL {mul} worst {worst:.3f} <= bound {bound:.3f} LSB over {cpr} positions")


@pytest.mark.parametrize("cpr,p,realign,dsp", [(4000, 4, 0, 1), (4096, 3, 0, 1), (1000, 7, 1, 1), (4000, 4, 0, 0),
                                               (1000, 7, 1, 0)])
def test_pos_sense(cpr, p, realign, dsp):
    """ANGLE_DSP = 0 (angle tracked without the multiplier) must give the same bit-exact outputs."""
    from runner import run
    params = dict(CPR=cpr, POLE_PAIRS=p, REALIGN=realign, ANGLE_DSP=dsp)
    run(toplevel="pos_sense", test_module="test_pos_sense", parameters=params,
        name=f"test_pos_sense_{cpr}_{p}" + ("" if dsp else "_nodsp"), extra_env={"TB_PARAMS": json.dumps(params)})
