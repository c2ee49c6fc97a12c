"""cocotb tests of ref_gen with NAXES = 4 axes on its one shared engine, against
empc.rtlmodel.ref_gen.RefGenAxes (NAXES per-axis RefGen models on a clock-exact engine schedule).

* random_axes: random segment programs per axis (CPU field writes to {axis, slot}), random
  per-axis advance strobes (each axis its own spacing, often several axes in one clock, many
  while another axis's operation runs), starts, syncs (a sync on one axis while others advance
  or wait), the governor enabled and re-programmed on axes 0 and 2 (hold / task random per
  axis), field read-backs.  Every clock: busy, w_ok, gov_ev of every axis, seg_rdata, a random
  readout bit (rd_age = {axis, age}) and the whole delay line of every axis with w_ok compared
  bit-exact with the model.
* isolation (model-independent): the same stimulus twice from reset, once with random syncs on
  axis 0 and once without: the delay-line words of axes 1..3 after each of their advances, and
  their gov_ev pulses, are identical (the engine time a sync of axis 0 takes only moves the
  other axes' operations later).
* braking_axes: the position task's braking distance on all four axes (V, B in the state RAM),
  bit-exact vs the model after every period, each axis's brake / no-speed-up zones exercised.
* test_ref_gen_axes_mutant: an engine that shifts every axis's target word rt (not only the
  running axis's) must fail random_axes.
"""
from __future__ import annotations

import json
import os
import random

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, Timer

from empc.rtlmodel.ref_gen import FIELDS, GOV_FIELD, M32, M64, NSLOT, RefGenAxes, Slot, gov_words, slot_field

DEFAULT_SEED = 20261126
CLOCK = False
PARAMS = {"N": 4, "NAXES": 4}


def rand_slot(rng):
    from test_ref_gen import rand_slot as rs
    return rs(rng)


def rand_gov(rng):
    from test_ref_gen import rand_gov as rg
    return rg(rng, False)


class Env:
    def __init__(self, dut, seed=None):
        self.dut = dut
        self.p = json.loads(os.environ.get("TB_PARAMS", json.dumps(PARAMS)))
        self.N, self.A = self.p["N"], self.p["NAXES"]
        self.AW = 1 if self.N < 2 else (self.N).bit_length()
        self.seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED)) if seed is None else seed
        self.rng = random.Random(self.seed)
        self.m = RefGenAxes(self.N, self.A)
        self.n = 0
        self.cnt = dict(w=0, rd=0, seg=0, gov_ev=0)
        self.sync_val = [0] * self.A
        self.hold = [0] * self.A
        self.task_pos = [0] * self.A
        self.trace = {a: [] for a in range(self.A)}     # per axis: (w after each advance / sync, gov_ev)
        self._w_prev = [None] * self.A
        self._in = [getattr(dut, n) for n in self.INPUTS]
        self._last = [None] * len(self.INPUTS)          # nothing written yet by this Env
        self.h_sync_idx, self.h_dl, self.h_rd_q = dut.sync_idx, dut.dl, dut.rd_q
        self.h_busy, self.h_w_ok, self.h_gov_ev, self.h_seg_rdata = dut.busy, dut.w_ok, dut.gov_ev, dut.seg_rdata
        dut._log.info("params %s seed %d (EMPC_SEED)", self.p, self.seed)

    # the inputs _drive sets, in this order; a write goes to the simulator only when the value changes
    # (an unchanged input written again is no event in the simulator: the same stimulus, 3-4 instead of
    # 14 handle writes a clock)
    INPUTS = ("seg_we", "seg_re", "seg_slot", "seg_field", "seg_wdata", "start", "start_slot", "sync", "advance",
              "hold", "task_pos", "sync_bit", "rd_age", "rd_bit")

    def _drive(self, seg=None, seg_read=None, start=None, sync=None, advance=None, rd=None):
        A = self.A
        if seg is not None:
            a, s, f, v = seg
            slot, field, wdata = (a << 4) | s, f, v & M32
        elif seg_read is not None:
            a, s, f = seg_read
            slot, field, wdata = (a << 4) | s, f, 0
        else:
            slot, field, wdata = 0, 0, 0
        start = start or [None] * A
        sv = self.h_sync_idx.value
        idx = sv.to_unsigned() if sv.is_resolvable else 0
        ra, age, b = rd if rd is not None else (0, 0, 0)
        vals = (int(seg is not None), int(seg_read is not None), slot, field, wdata,
                sum(1 << a for a in range(A) if start[a] is not None),
                sum((start[a] or 0) << (4 * a) for a in range(A)),
                sum(1 << a for a in range(A) if sync and sync[a]),
                sum(1 << a for a in range(A) if advance and advance[a]),
                sum(h << a for a, h in enumerate(self.hold)),
                sum(h << a for a, h in enumerate(self.task_pos)),
                sum(((self.sync_val[a] >> idx) & 1) << a for a in range(A)),
                (ra << self.AW) | age, b)
        last, hs = self._last, self._in
        for i, v in enumerate(vals):
            if last[i] != v:
                last[i] = v
                hs[i].value = v

    def w(self, a, bits=None):
        """Axis ``a``'s delay line w_k .. w_{k+N} from ``bits`` (``str`` of dl, MSB first; read now if None;
        other axes may still be X after reset)."""
        if bits is None:
            bits = str(self.h_dl.value)
        DL = (self.N + 1) * 64
        s = bits[len(bits) - (a + 1) * DL:len(bits) - a * DL]
        return [int(s[64 * m:64 * m + 64][::-1], 2) for m in range(self.N + 1)]     # each word bit-reversed

    async def cycle(self, seg=None, seg_read=None, start=None, sync=None, advance=None, check=True):
        """One clock with these inputs (per-axis lists), then compare every output with the model."""
        d, m, A, rng = self.dut, self.m, self.A, self.rng
        sync = sync or [None] * A
        for a in range(A):
            if sync[a] is not None:
                self.sync_val[a] = sync[a] & M64
        rd = (rng.randrange(A), rng.randrange(self.N + 1), rng.randrange(64))
        exp_rd = None
        if m[rd[0]].w_ok:                                   # readout of the present clock (combinational)
            exp_rd = (m[rd[0]].w[self.N - rd[1]] >> rd[2]) & 1
        self._drive(seg, seg_read, start, [s is not None for s in sync], advance, rd)
        if exp_rd is not None:
            await Timer(10, unit="ps")
            assert int(self.h_rd_q.value) == exp_rd, f"clock {self.n}: readout axis {rd[0]} age {rd[1]} bit {rd[2]}"
            self.cnt["rd"] += 1
        exp_seg = m[seg_read[0]].read_field(seg_read[1], seg_read[2]) if seg_read else None
        m.step(seg=seg, start=start, sync=[s is not None for s in sync], sync_value=[s or 0 for s in sync],
               advance=advance, hold=self.hold, task_pos=self.task_pos)
        await FallingEdge(d.clk)
        self.n += 1
        if check:
            self.check(exp_seg)

    def check(self, exp_seg=None):
        m, A = self.m, self.A
        busy, w_ok, gev = int(self.h_busy.value), int(self.h_w_ok.value), int(self.h_gov_ev.value)
        bits = None                                     # dl, read once per clock
        for a in range(A):
            g = m[a]
            assert (busy >> a) & 1 == g.busy and (w_ok >> a) & 1 == g.w_ok and (gev >> a) & 1 == g.gov_ev, (
                f"clock {self.n} axis {a}: busy/w_ok/gov_ev rtl {(busy >> a) & 1}/{(w_ok >> a) & 1}/{(gev >> a) & 1} "
                f"model {g.busy}/{g.w_ok}/{g.gov_ev} (engine axis {m.engine_axis})")
            self.cnt["gov_ev"] += int(g.gov_ev)
            if g.w_ok:
                if bits is None:
                    bits = str(self.h_dl.value)
                got = self.w(a, bits)
                assert got == g.w, (f"clock {self.n} axis {a}: w mismatch\n  rtl   {[hex(x) for x in got]}\n"
                                    f"  model {[hex(x) for x in g.w]}")
                self.cnt["w"] += 1
                if got != self._w_prev[a]:
                    self.trace[a].append(tuple(got))
                    self._w_prev[a] = got
            if (gev >> a) & 1:
                self.trace[a].append("gov_ev")
        rd = int(self.h_seg_rdata.value)
        if exp_seg is not None:
            assert rd == exp_seg, f"clock {self.n}: seg_rdata {rd:#x} != {exp_seg:#x}"
            self.cnt["seg"] += 1
        else:
            assert rd == 0, f"clock {self.n}: seg_rdata {rd:#x} without a read"

    async def start(self):
        global CLOCK
        d = self.dut
        if not CLOCK:
            Clock(d.clk, 10, unit="ns", impl="gpi").start()   # C clock: no Python per edge (inputs change at falling edges)
            CLOCK = True
        d.rst.value = 1
        self._drive()
        for _ in range(3):
            await FallingEdge(d.clk)
        d.rst.value = 0
        self.m.reset()
        # the header's governor words are in field 7 of slots 0..4 of every axis after configuration
        for a in range(self.A):
            for slot in range(5):
                await self.cycle(seg_read=(a, slot, GOV_FIELD), check=False)
                got = int(d.seg_rdata.value)
                self.m[a].write_field(slot, GOV_FIELD, got)
                self.check(exp_seg=got)
        while any(g.busy for g in self.m.axes):
            await self.cycle()

    async def program(self, a, slots):
        for i, s in enumerate(slots):
            s = s.normalised()
            for f in range(len(FIELDS)):
                await self.cycle(seg=(a, i % NSLOT, f, slot_field(s, f)))


async def random_run(dut, seed, n_clocks, sync_axis0=True, gov_axes=(0, 2)):
    env = Env(dut, seed)
    gov_axes = tuple(a for a in gov_axes if a < env.A)
    await env.start()
    A, m = env.A, env.m
    srng = random.Random(seed + 1)          # axis 0's syncs: their own stream (isolation runs)
    rng = env.rng
    for a in range(A):
        await env.program(a, [rand_slot(rng) for _ in range(NSLOT)])
        words = gov_words(*rand_gov(rng)) if a in gov_axes else gov_words(0, 0, 0, False)
        if a in gov_axes:
            words[4] |= 1
        for slot, word in words.items():
            await env.cycle(seg=(a, slot, GOV_FIELD, word))
    await env.cycle(start=[rng.randrange(NSLOT) for _ in range(A)])
    st = dict(adv=0, multi_adv=0, adv_wait=0, start=0, sync=0, sync_other_busy=0, write=0, read=0, gov_write=0)
    next_adv = [rng.randrange(400) for _ in range(A)]
    while env.n < n_clocks:
        adv = [env.n >= next_adv[a] for a in range(A)]
        if rng.random() < 0.0008:                             # several axes in one clock
            adv = [x or rng.random() < 0.7 for x in adv]
        for a in range(A):
            if adv[a]:
                next_adv[a] = env.n + rng.choice([1, 40, 1000, 2000, 3000, 4000])
                st["adv_wait"] += int(m.engine_axis not in (None, a))
        st["adv"] += sum(adv)
        st["multi_adv"] += int(sum(adv) > 1)
        start = [None] * A
        sync = [None] * A
        for a in range(A):
            if rng.random() < 0.001:
                start[a] = rng.randrange(NSLOT)
                st["start"] += 1
        for a in range(A):
            g = m[a]
            r = (srng if a == 0 else rng).random()
            if a == 0 and not sync_axis0:
                continue
            if r < 0.00012 and not g.sync_pend and not (g._op is not None and g._op["kind"] == "sync"):
                sync[a] = (srng if a == 0 else rng).getrandbits(64)
                st["sync"] += 1
                st["sync_other_busy"] += int(any(m[b].busy for b in range(A) if b != a))
        seg = seg_read = None
        r = rng.random()
        if r < 0.03:
            a = rng.randrange(A)
            g = m[a]
            s = rng.randrange(NSLOT)
            if s != g.loading_slot:
                f = rng.randrange(len(FIELDS))
                seg = (a, s, f, slot_field(rand_slot(rng).normalised(), f))
                st["write"] += 1
        elif r < 0.045:
            seg_read = (rng.randrange(A), rng.randrange(NSLOT), rng.randrange(len(FIELDS) + 1))
            st["read"] += 1
        elif r < 0.06:
            a = rng.choice(gov_axes)
            if not m[a].busy:
                words = gov_words(*rand_gov(rng))
                words[4] |= 1
                slot = rng.choice(list(words))
                seg = (a, slot, GOV_FIELD, words[slot])
                st["gov_write"] += 1
        for a in range(A):
            if rng.random() < 0.01:
                env.hold[a] = int(rng.random() < 0.5)
                env.task_pos[a] = int(rng.random() < 0.5)
        await env.cycle(seg=seg, seg_read=seg_read, start=start, sync=sync, advance=adv)
    while any(g.busy for g in m.axes):
        await env.cycle()
    dut._log.info("seed %d: %d clocks, %s; compared: %s", seed, env.n, st, env.cnt)
    return env, st


@cocotb.test()
async def random_axes(dut):
    global CLOCK
    CLOCK = False
    seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
    env, st = await random_run(dut, seed, int(os.environ.get("EMPC_REFGEN_CLOCKS", 80000)))
    assert st["multi_adv"] > 5 and st["adv_wait"] > 50 and st["sync"] > 10 and st["sync_other_busy"] > 5
    assert st["gov_write"] > 5 and env.cnt["w"] > env.n, "too few governor writes / delay-line compares"
    assert env.cnt["gov_ev"] > 10, "the governor never clamped"
    hc = {k: sum(m.hold_cases[k] for m in env.m.axes) for k in env.m[0].hold_cases}   # one-sided speed hold
    dut._log.info("speed-task holds (g < 0, vd passes): %s", hc)
    assert min(hc.values()) >= 2, f"speed-task hold cases not all exercised: {hc}"
    dut._log.info("random_axes: every output of every axis bit- and clock-exact vs RefGenAxes")


async def iso_run(dut, seed, n_clocks, sync_axis0):
    """Stimulus whose effect on axes 1..3 does not depend on the engine's timing: every axis's
    strobes come >= 3000 clocks apart (longer than any wait for the engine), a start, a sync and a
    hold / task change of axis b only in the clock of b's advance strobe, no CPU traffic after the
    programs.  Axis 0 is synced at random (its own random stream) or never."""
    env = Env(dut, seed)
    await env.start()
    A, m, rng = env.A, env.m, env.rng
    srng = random.Random(seed + 1)
    for a in range(A):
        await env.program(a, [rand_slot(rng) for _ in range(NSLOT)])
        words = gov_words(*rand_gov(rng))
        words[4] |= int(a % 2 == 0)
        for slot, word in words.items():
            await env.cycle(seg=(a, slot, GOV_FIELD, word))
    await env.cycle(start=[rng.randrange(NSLOT) for _ in range(A)])
    next_adv = [rng.randrange(3000) for _ in range(A)]
    n_sync0 = 0
    while env.n < n_clocks:
        adv = [env.n >= next_adv[a] for a in range(A)]
        start, sync = [None] * A, [None] * A
        for a in range(A):
            if adv[a]:
                # the premise: the axis's previous advance has run (no strobe merges into a pending one)
                assert a == 0 or not m[a].busy, f"clock {env.n}: axis {a} still busy at its next advance"
                next_adv[a] = env.n + rng.choice([3000, 3100, 3500])
                if a > 0 or True:
                    env.hold[a] = int(rng.random() < 0.3)
                    env.task_pos[a] = int(rng.random() < 0.5)
                    if rng.random() < 0.1:
                        start[a] = rng.randrange(NSLOT)
                    v = rng.getrandbits(64)
                    if rng.random() < 0.05 and a > 0:
                        sync[a] = v
        g = m[0]
        if sync_axis0 and srng.random() < 0.0004 and not g.sync_pend and not (g._op is not None and g._op["kind"] == "sync"):
            sync[0] = srng.getrandbits(64)
            n_sync0 += 1
        await env.cycle(start=start, sync=sync, advance=adv)
    while any(g.busy for g in m.axes):
        await env.cycle()
    return env, n_sync0


@cocotb.test()
async def isolation(dut):
    global CLOCK
    CLOCK = False
    seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED)) + 7
    n = int(os.environ.get("EMPC_REFGEN_ISO_CLOCKS", 72000))
    env1, n1 = await iso_run(dut, seed, n, sync_axis0=True)
    env2, n2 = await iso_run(dut, seed, n, sync_axis0=False)
    assert n1 > n / 6000 and n2 == 0, "axis 0 was never synced"
    for b in range(1, env1.A):
        t1, t2 = env1.trace[b], env2.trace[b]
        assert len(t1) > 20 and t1 == t2, f"axis {b} differs when axis 0 is synced"
    dut._log.info("isolation: axes 1..3 identical (%s delay-line states / gov_ev pulses) with and without %d "
                  "syncs of axis 0 (both runs also bit-exact vs the model every clock)", [len(env1.trace[b]) for b in range(1, env1.A)], n1)


async def run_idle(env):
    """Clocks without inputs until every axis is idle (model and RTL), compared at the end: Python sleeps
    through them (one timer; no sync may run, its value is read bit by bit)."""
    m, n = env.m, 0
    env._drive()
    while any(g.busy for g in m.axes):
        assert not any(g._op is not None and g._op["kind"] == "sync" for g in m.axes)
        m.step(hold=env.hold, task_pos=env.task_pos)
        n += 1
    if n:
        await Timer(n * 10 - 2, unit="ns")          # past the n-th rising edge, before the n-th falling one
        await FallingEdge(env.dut.clk)
        env.n += n
    env.check()


@cocotb.test()
async def braking_axes(dut):
    """Position task, braking distance (V, B of every axis in the state RAM): every axis governed with its
    own vmax, a and ksh (a small shift: the proportional catch-up alone would overshoot), target steps
    of 5..40 vmax, staggered between the axes, advances of all four axes in one clock (the engine
    serialises them), holds at random; the delay lines of all axes bit-exact vs RefGenAxes after every
    period, and the brake / no-speed-up zones seen on every axis."""
    global CLOCK
    CLOCK = False
    env = Env(dut, int(os.environ.get("EMPC_SEED", DEFAULT_SEED)) + 11)
    await env.start()
    A, m, rng = env.A, env.m, env.rng
    env.task_pos = [1] * A
    vm = []
    for a in range(A):
        vmax = rng.getrandbits(33) | (1 << 33)                  # 2..4 counts per period
        vm.append(vmax >> 32)
        k = rng.randrange(4, 8)
        for slot, word in gov_words(vmax, max(1, vmax >> k), rng.randrange(0, k - 2), True).items():
            await env.cycle(seg=(a, slot, GOV_FIELD, word))
    await env.cycle(sync=[0] * A)
    while any(g.busy for g in m.axes):
        await env.cycle()
    tgt = [0] * A
    periods = int(os.environ.get("EMPC_REFGEN_BRAKE_PERIODS", 120))
    for p in range(periods):
        start = [None] * A
        for a in range(A):
            if p % 60 == a * 7:
                tgt[a] += rng.choice([1, -1]) * vm[a] * rng.randrange(5, 40)
                await env.program(a, [Slot(0, (tgt[a] << 32) & M64, 0, 0, last=True)])
                start[a] = 0
            env.hold[a] = int(rng.random() < 0.03)
        await env.cycle(start=start, advance=[True] * A)
        await run_idle(env)
    bc = [g.brake_cases for g in m.axes]
    dut._log.info("braking_axes: %d periods x %d axes bit-exact vs RefGenAxes, %d clocks; cases per axis %s",
                  periods, A, env.n, bc)
    assert all(c["brake"] >= 10 and c["slow"] >= 10 and c["down"] >= 10 for c in bc), bc


@pytest.mark.cost(85)          # seconds on an idle core (make sim starts the costliest first)
def test_ref_gen_axes():
    from runner import run
    run(toplevel="ref_gen", test_module="test_ref_gen_axes", parameters=PARAMS,
        extra_env={"TB_PARAMS": json.dumps(PARAMS)}, name="test_ref_gen_axes")


def test_ref_gen_axes_mutant(tmp_path):
    """The test must fail on an engine that reads the wrong axis's state (the state RAM's read port
    without the axis bits: every axis sees axis 0's d1, d2, remaining, rt and v)."""
    import pytest
    import runner
    from files import ROOT, rtl_sources
    src = (ROOT / "rtl" / "ref_gen.v").read_text()
    good = "st_q <= st_m[{ax, t}];"
    assert src.count(good) == 1, "the mutant no longer matches rtl/ref_gen.v"
    lines = src.replace(good, "st_q <= st_m[{{AXW{1'b0}}, t}];")
    mut = tmp_path / "ref_gen.v"
    mut.write_text(lines)
    orig = runner.rtl_sources
    runner.rtl_sources = lambda: [mut if p.name == "ref_gen.v" else p for p in rtl_sources()]
    try:
        with pytest.raises((AssertionError, SystemExit)):  # cocotb's runner exits on a failed test
            runner.run(toplevel="ref_gen", test_module="test_ref_gen_axes", parameters=PARAMS,
                       extra_env={"TB_PARAMS": json.dumps(PARAMS), "EMPC_REFGEN_CLOCKS": "20000"},
                       testcase="random_axes", name="test_ref_gen_axes_mutant")
    finally:
        runner.rtl_sources = orig
    # (a build error of the mutant raises RuntimeError from the runner: not caught, the test fails)
