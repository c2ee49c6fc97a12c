"""cocotb tests of ref_gen against empc.rtlmodel.ref_gen.

* closed_form (model-independent): one quadratic segment run for 3000
  periods equals r0 + p d1 + p(p-1)/2 d2 mod 2**64 every period; its
  delay line equals the head of N..1 periods before; a `last` segment holds
  at r(L); len = 0 never ends; the position integer part wraps through
  2**32 (and the 64-bit word through 2**64) exactly;
* profile (model-independent): slots from segments_from_points (steps and
  exact ramps, SI units) loaded through the ports hit every breakpoint value
  exactly (Q.32 of the SI value) at the right period;
* (in closed_form) sync: head at once, delay line refilled in N clocks, an
  advance (and start) in the sync clock executed right after the fill;
* random_vs_model: random segment programs (lengths 0..20 and long, random
  64-bit r0/d1, signed d2, relative/last flags), advances every 1-4 clocks,
  start/sync in the middle of segments, slot writes while running and all
  same-clock combinations (start+advance, sync+advance, sync+start, write of
  the slot being loaded) compared bit-exact with the model every clock.
"""
from __future__ import annotations

import json
import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from empc.rtlmodel.ref_gen import M64, NSLOT, RefGen, Slot, q32, s64, segments_from_points

DEFAULT_SEED = 20240
PARAMS = {"N": 4}


class Env:
    def __init__(self, dut):
        self.dut = dut
        self.p = json.loads(os.environ.get("TB_PARAMS", json.dumps(PARAMS)))
        self.N = self.p["N"]
        self.seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
        self.rng = random.Random(self.seed)
        self.model = RefGen(self.N)
        self.n = 0
        self.n_adv = 0
        dut._log.info("params %s seed %d (EMPC_SEED)", self.p, self.seed)

    async def start(self):
        d = self.dut
        Clock(d.clk, 10, unit="ns").start()
        d.rst.value = 1
        self._idle()
        for _ in range(3):
            await FallingEdge(d.clk)
        d.rst.value = 0
        self.model.reset()
        self.check()

    def _idle(self):
        d = self.dut
        for s in ("seg_we", "start", "sync", "advance", "seg_relative", "seg_last"):
            getattr(d, s).value = 0
        d.seg_addr.value = 0
        d.seg_len.value = 0
        d.seg_r0.value = 0
        d.seg_d1.value = 0
        d.seg_d2.value = 0
        d.start_slot.value = 0
        d.sync_value.value = 0

    def w(self) -> list[int]:
        v = int(self.dut.w.value)
        return [(v >> (64 * j)) & M64 for j in range(self.N + 1)]

    def check(self):
        got = self.w()
        exp = self.model.w
        assert got == exp, (f"clock {self.n} (advance {self.n_adv}): w mismatch\n"
                            f"  rtl   {[hex(x) for x in got]}\n  model {[hex(x) for x in exp]}")

    async def cycle(self, seg_addr=None, seg=None, start_slot=None, sync_value=None, advance=False):
        """One clock with the given inputs (None = not asserted), then compare with the model."""
        d = self.dut
        self._idle()
        if seg is not None:
            s = seg.normalised()
            d.seg_we.value = 1
            d.seg_addr.value = seg_addr
            d.seg_len.value = s.length
            d.seg_r0.value = s.r0
            d.seg_d1.value = s.d1
            d.seg_d2.value = s.d2 & 0xFFFFFFFF
            d.seg_relative.value = int(s.relative)
            d.seg_last.value = int(s.last)
        if start_slot is not None:
            d.start.value = 1
            d.start_slot.value = start_slot
        if sync_value is not None:
            d.sync.value = 1
            d.sync_value.value = sync_value & M64
        d.advance.value = int(advance)
        self.model.step(seg_we=seg is not None, seg_addr=seg_addr or 0, seg=seg,
                        start=start_slot is not None, start_slot=start_slot or 0,
                        sync=sync_value is not None, sync_value=sync_value or 0, advance=advance)
        await FallingEdge(d.clk)
        self.n += 1
        self.n_adv += int(advance)
        self.check()
        return self.w()

    async def program(self, slots, base=0):
        for i, s in enumerate(slots):
            await self.cycle(seg_addr=(base + i) % NSLOT, seg=s)

    async def advance(self, gap=0):
        w = await self.cycle(advance=True)
        for _ in range(gap):
            await self.cycle()
        return w


@cocotb.test()
async def closed_form(dut):
    env = Env(dut)
    await env.start()
    N = env.N
    rng = env.rng
    checks = 0
    # quadratic segment through the 64-bit wrap and the 2**32 integer wrap
    for r0, d1, d2 in ((0xFFFFFFF0_00000000, 0x0000_0001_2345_6789, -0x1234_5678),
                       (0x7FFF_FFFF_8000_0000, -0x0000_0003_0000_0001, 0x7FFF_FFFF),
                       (rng.getrandbits(64), rng.getrandbits(40), rng.randrange(-2**31, 2**31))):
        await env.program([Slot(0, r0, d1, d2)], base=5)
        await env.cycle(start_slot=5)
        heads = []
        wrapped32 = wrapped64 = False
        for p in range(3000):
            w = await env.advance()
            exp = (r0 + p * d1 + p * (p - 1) // 2 * d2) & M64
            assert w[N] == exp, f"period {p}: head {w[N]:#x} closed form {exp:#x}"
            heads.append(w[N])
            for j in range(N):
                if p - (N - j) >= 0:
                    assert w[j] == heads[p - (N - j)], f"delay line w[{j}] at period {p}"
            if p:
                wrapped32 |= (heads[p] >> 32) < (heads[p - 1] >> 32) if d1 > 0 else (heads[p] >> 32) > (heads[p - 1] >> 32)
                wrapped64 |= abs(s64(heads[p]) - s64(heads[p - 1])) > (1 << 62)
            checks += 1
        dut._log.info("closed form r0=%#x d1=%#x d2=%d: 3000 periods ok (integer part wrapped mod 2**32: %s, "
                      "signed 64-bit overflow: %s)", r0, d1 & M64, d2, wrapped32, wrapped64)
    # last: hold at r(L); then nothing changes
    L = 37
    r0, d1, d2 = 0x1_0000_0000, 0x2345_6789, -0x1111
    await env.program([Slot(L, r0, d1, d2, last=True), Slot(0, 0x4242 << 32, 0, 0)], base=15)
    await env.cycle(start_slot=15)
    for p in range(L + 20):
        w = await env.advance(gap=1)
        pp = min(p, L)
        exp = (r0 + pp * d1 + pp * (pp - 1) // 2 * d2) & M64
        assert w[N] == exp, f"last segment period {p}: {w[N]:#x} != {exp:#x} (must hold at r(L) from period L)"
        checks += 1
    # a non-last segment of length L moves on to slot + 1 (mod 16: 15 -> 0) after L periods
    await env.program([Slot(3, 0x10 << 32, 1 << 32, 0)], base=15)
    await env.program([Slot(0, 0x99 << 32, 0, 0)], base=0)
    await env.cycle(start_slot=15)
    vals = [(await env.advance())[N] >> 32 for _ in range(6)]
    assert vals == [0x10, 0x11, 0x12, 0x99, 0x99, 0x99], f"slot 15 -> 0 sequence {vals}"
    checks += 1
    # sync: head at once, delay line filled in N clocks; an advance in the sync clock (with a
    # start in the same clock) is executed in the clock after the fill
    sv, r0, d1 = 0xABCD_0000_1234_5678, 0x0000_0042_8000_0000, 0x1_0000_0000
    await env.program([Slot(0, r0, d1, 0)], base=3)
    old = env.w()
    w = await env.cycle(sync_value=sv, start_slot=3, advance=True)
    assert w[N] == sv and w[:N] == old[:N], "sync clock: head only"
    for k in range(1, N + 1):
        w = await env.cycle()
        assert w[N] == sv and w[N - k:N] == [sv] * k and w[:N - k] == old[k:N], f"fill clock {k}: {w}"
    w = await env.cycle()
    assert w[N] == r0 and w[:N] == [sv] * N, "deferred advance must run right after the fill"
    w = await env.advance()
    assert w[N] == (r0 + d1) & M64 and w[N - 1] == r0 and w[:N - 1] == [sv] * (N - 1)
    checks += N + 3
    dut._log.info("closed_form: %d period checks, %d clocks", checks, env.n)


@cocotb.test()
async def profile(dut):
    """segments_from_points -> slots -> RTL: breakpoints hit exactly."""
    env = Env(dut)
    await env.start()
    N = env.N
    Ts = 250e-6
    unit = 4000 / (2 * 3.141592653589793)          # counts per rad
    pts = [(0.005, 0.0, "step"), (0.0173, 12.345, "ramp"), (0.03, 12.345, "step"), (0.031, -7.5, "step"),
           (0.05, 100.0 / 3.0, "ramp"), (0.06, -1.0, "ramp")]
    slots = segments_from_points(pts, unit, Ts, v0=1.5)
    await env.program(slots)
    await env.cycle(sync_value=0x1234_5678_9ABC_DEF0)
    for _ in range(N):                              # delay-line fill
        await env.cycle()
    await env.cycle(start_slot=0)
    n = int(round(0.07 / Ts))
    heads = [(await env.advance(gap=env.rng.randrange(3)))[N] for _ in range(n)]
    checks = 0
    prev = (0.0, 1.5)
    for t, v, kind in pts:
        p = int(round(t / Ts))
        assert heads[p] == q32(v * unit) & M64, f"breakpoint t={t}: {s64(heads[p]) / 2**32} != {v * unit}"
        if kind == "step":      # the value before the step is the previous one
            assert heads[p - 1] == q32(prev[1] * unit) & M64, f"value before step at t={t}"
        else:                   # ramp midpoint within 1 count of the straight line
            # (breakpoint times are rounded to whole periods)
            p0 = int(round(prev[0] / Ts))
            pm = (p0 + p) // 2
            vm = prev[1] + (v - prev[1]) * (pm - p0) / (p - p0)
            assert abs(s64(heads[pm]) / 2**32 - vm * unit) < 2**-20, f"ramp midpoint period {pm}"
        prev = (t, v)
        checks += 1
    assert all(h == heads[-1] for h in heads[int(round(0.06 / Ts)):]), "final hold"
    dut._log.info("profile: %d slots, %d periods, %d breakpoint checks exact", len(slots), n, checks)


def rand_slot(rng):
    length = rng.choice([0, 1, 1, 2, 3, 5, 8, 13, 20, rng.randrange(1, 40)]) if rng.random() < 0.95 \
        else rng.choice([0xFFFFFFFF, rng.getrandbits(32)])
    mag = rng.choice([8, 24, 36, 48, 64])
    d1 = rng.getrandbits(mag) * rng.choice([1, -1])
    d2 = rng.randrange(-2**31, 2**31) if rng.random() < 0.5 else rng.randrange(-100, 100)
    return Slot(length, rng.getrandbits(64), d1, d2, relative=rng.random() < 0.4, last=rng.random() < 0.15)


@cocotb.test()
async def random_vs_model(dut):
    env = Env(dut)
    await env.start()
    rng = env.rng
    await env.program([rand_slot(rng) for _ in range(NSLOT)])
    await env.cycle(start_slot=rng.randrange(NSLOT))
    n_clocks = 24000
    stats = dict(start=0, sync=0, write=0, start_adv=0, sync_adv=0, write_load=0, deferred=0)
    while env.n < n_clocks:
        adv = rng.random() < 0.35
        kw = {"advance": adv}
        r = rng.random()
        if r < 0.01:
            kw["start_slot"] = rng.randrange(NSLOT)
            stats["start"] += 1
            stats["start_adv"] += adv
        elif r < 0.016:
            kw["sync_value"] = rng.getrandbits(64)
            stats["sync"] += 1
            stats["sync_adv"] += adv
            if rng.random() < 0.3:
                kw["start_slot"] = rng.randrange(NSLOT)
        if rng.random() < 0.02:
            # often hit the slot that this advance would load
            m = env.model
            nxt = kw.get("start_slot", m.pend_slot if m.pend else (m.slot + 1) % NSLOT)
            a = nxt if rng.random() < 0.5 else rng.randrange(NSLOT)
            kw["seg_addr"], kw["seg"] = a, rand_slot(rng)
            stats["write"] += 1
            stats["write_load"] += int(adv and a == nxt)
        stats["deferred"] += int(adv and (env.model.fill != 0 or "sync_value" in kw))
        await env.cycle(**kw)
    assert stats["deferred"] > 10 and stats["write_load"] > 10 and stats["start_adv"] > 10
    dut._log.info("random: %d clocks, %d advances bit-exact vs model (seed %d); %s",
                  env.n, env.n_adv, env.seed, stats)


def test_ref_gen():
    from runner import run
    run(toplevel="ref_gen", test_module="test_ref_gen", parameters=PARAMS,
        extra_env={"TB_PARAMS": json.dumps(PARAMS)})


def test_ref_gen_n1():
    from runner import run
    p = {"N": 1}
    run(toplevel="ref_gen", test_module="test_ref_gen", parameters=p, extra_env={"TB_PARAMS": json.dumps(p)},
        testcase=["closed_form", "random_vs_model"], name="test_ref_gen_n1")
