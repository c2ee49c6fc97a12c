"""cocotb tests of ref_gen against empc.rtlmodel.ref_gen.

The RTL is a bit-serial engine: every operation (advance, sync) takes tens to
hundreds of clocks.  The delay line w_k..w_{k+N} is observed inside the DUT (the
shift register ``dl``) whenever the engine reports ``w_ok``, and through the
readout port (rd_age, rd_bit -> rd_q).

* closed_form (model-independent): quadratic segments run for 3000
  periods (1000 in the N = 1 run) equals r0 + p d1 + p(p-1)/2 d2 mod 2**64 every period; its
  delay line equals the head of N..1 periods before; a `last` segment holds
  at r(L); len = 0 never ends; slot 15 -> 0 wraps; the position integer part
  wraps through 2**32 (and the 64-bit word through 2**64) exactly;
* (in closed_form) sync: head and delay line = the sync value, differences 0;
  an advance and a start in the sync clock run right after it;
* readout (in closed_form and random): random rd_age / rd_bit reads equal the
  model's w bits; every slot field read back (seg_re) equals what was written;
* profile (model-independent): slots from segments_from_points (steps and
  exact ramps, SI units) written field by field hit every breakpoint value
  exactly (Q.32 of the SI value) at the right period;
* random_vs_model: random segment programs (lengths 0..20 and long, random
  64-bit r0/d1, signed d2, relative/last flags), advances every 1-300 clocks
  (so they also arrive while the engine runs), starts and syncs in the middle
  of segments and of running operations, field writes while running (never to
  the slot an advance in progress is loading), the same-clock combinations
  start+advance, sync+advance, sync+start, a write of the slot that an advance
  beginning in that clock loads; busy / w_ok and (when w_ok) the whole delay
  line compared bit-exact with the clock-level model every clock.  With
  EMPC_REFGEN_GOV=1 (test_ref_gen_governed) the same with the governor enabled and
  re-programmed at random (vmax, a incl. 0 and 2^63-1, ksh 0..31), hold and task_pos
  random every clock, the gov_ev pulses counted against the model's clamps.
* governor (model-independent parts and vs model): the boot words (header) read back
  through field 7; a 64-bit target step is shaped into a trajectory whose increment
  never exceeds vmax and changes by at most a per period (speed and position task, with
  and without hold), ending exactly on the target; the extreme words (a step of 2^63,
  vmax = a = 2^63 - 1, ksh = 31) bit-exact against gov_step.
* braking (position task, the braking distance): target steps from rest and interrupting a motion, small
  shifts (where the proportional catch-up alone overshoots by 100-1500 a), holds; bit-exact vs the model
  after every advance, no step from rest passes its target by more than a, every zone / V step exercised.

Cost: test_ref_gen and test_ref_gen_governed share one Verilator build (the clock-level checks of 1.3 M
clocks ran 3-4 minutes on Icarus); test_ref_gen_n1 and the hold mutant stay on Icarus.  The clock is cocotb's
C clock (inputs change at falling edges, so its write timing does not matter), and wait_idle lets the clocks of
an operation pass under one timer (nothing is driven then; gov_ev_monitor counts the gov_ev pulses).
"""
from __future__ import annotations

import json
import os
import random

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from empc.formats import wrap
from empc.rtlmodel.ref_gen import (FIELDS, GOV_FIELD, GOV_SLOTS, M32, M63, M64, NSLOT, RefGen, Slot, gov_words,
                                   q32, segments_from_points, slot_field)

DEFAULT_SEED = 20240
CLK_NS = 10             # clock period
FRESH = True            # the simulation has just started: the RAM holds its configuration contents
PARAMS = {"N": 4}


def _header() -> dict:
    from pathlib import Path
    from empc import header
    roms = Path(os.environ.get("EMPC_ROMS", Path(__file__).resolve().parents[1] / "build" / "roms" / "default"))
    return header.read(roms / "empc_formats.vh")


def _rev64(x: int) -> int:
    return int(f"{x:064b}"[::-1], 2)


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
        self.n_w = 0          # delay-line comparisons
        self.n_rd = 0         # readout-port checks
        self.n_seg = 0        # field read-backs
        self.gov_ev = 0       # gov_ev pulses (clocks with gov_ev = 1), counted by gov_ev_monitor
        dut._log.info("params %s seed %d (EMPC_SEED)", self.p, self.seed)

    async def sync_driver(self):
        """The value source: sync_bit = bit sync_idx of the current sync value, every clock
        while a sync is pending or running (started with each sync)."""
        d = self.dut
        self.driving = True
        while True:
            await FallingEdge(d.clk)
            d.sync_bit.value = (getattr(self, "sync_value", 0) >> int(d.sync_idx.value)) & 1
            if not int(d.busy.value):                      # (the sync has run)
                self.driving = False
                return

    async def gov_ev_monitor(self):
        """Counts the clocks with gov_ev = 1 (as sampled at the falling edge), waking only on a pulse:
        wait_idle lets the clocks of an operation pass without Python."""
        d = self.dut
        while True:
            await RisingEdge(d.gov_ev)              # set by the clock edge just passed
            self.gov_ev += 1                        # its falling-edge sample
            await FallingEdge(d.clk)
            while True:                             # a pulse longer than one clock counts every clock
                await FallingEdge(d.clk)
                if not int(d.gov_ev.value):
                    break
                self.gov_ev += 1

    def drive_sync(self):
        if not getattr(self, "driving", False):
            cocotb.start_soon(self.sync_driver())

    async def start(self, governor=False):
        d = self.dut
        Clock(d.clk, CLK_NS, unit="ns", impl="gpi").start()   # C clock: no Python per edge (inputs change at falling edges)
        cocotb.start_soon(self.gov_ev_monitor())
        d.sync_bit.value = 0
        d.rst.value = 1
        self._idle()
        for _ in range(3):
            await FallingEdge(d.clk)
        d.rst.value = 0
        self.model.reset()                 # the RTL clears its delay line after rst (sync to 0)
        await self.wait_idle()
        self.check()
        # governor words (field 7 of slots 0..4; block RAM and the enable / ksh register keep them
        # over rst): after configuration the header's, afterwards what the last test wrote
        global FRESH
        h = _header()
        boot = {GOV_SLOTS["vmax_lo"]: h["GOV_VMAX_LO"], GOV_SLOTS["vmax_hi"]: h["GOV_VMAX_HI"],
                GOV_SLOTS["a_lo"]: h["GOV_A_LO"], GOV_SLOTS["a_hi"]: h["GOV_A_HI"],
                GOV_SLOTS["cfg"]: (h["GOV_EN"] & 1) | (h["GOV_KSH"] << 8)}
        for slot, word in boot.items():
            d.seg_re.value, d.seg_slot.value, d.seg_field.value = 1, slot, GOV_FIELD
            await FallingEdge(d.clk)
            got = int(d.seg_rdata.value)
            if FRESH:
                assert got == word, f"governor word of slot {slot} after configuration {got:#x} != header {word:#x}"
            self.model.write_field(slot, GOV_FIELD, got)
        FRESH = False
        self._idle()
        self.check()
        if not governor:
            await self.set_gov(0, 0, 0, False)

    async def set_gov(self, vmax, a, ksh, enable):
        for slot, word in gov_words(vmax, a, ksh, enable).items():
            await self.cycle(seg=(slot, GOV_FIELD, word))

    def _idle(self):
        d = self.dut
        for s in ("seg_we", "seg_re", "start", "sync", "advance"):
            getattr(d, s).value = 0
        d.hold.value = getattr(self, "hold", 0)
        d.task_pos.value = getattr(self, "task_pos", 0)
        d.seg_slot.value = 0
        d.seg_field.value = 0
        d.seg_wdata.value = 0
        d.start_slot.value = 0
        d.rd_age.value = 0
        d.rd_bit.value = 0

    def w(self) -> list[int]:
        """w_k .. w_{k+N} from the DUT's delay line (bit 64*age + 63 - b = bit b of w_{k+N-age})."""
        v = int(self.dut.dl.value)
        return [_rev64((v >> (64 * (self.N - m))) & M64) for m in range(self.N + 1)]

    def check(self):
        d, m = self.dut, self.model
        assert int(d.busy.value) == m.busy and int(d.w_ok.value) == m.w_ok, \
            (f"clock {self.n}: busy/w_ok rtl {int(d.busy.value)}/{int(d.w_ok.value)} model {m.busy}/{m.w_ok} "
             f"(rtl run {d.run.value} kind {d.kind.value} adv_pend {d.adv_pend.value}; model op {m._op and {k: v for k, v in m._op.items() if k != 'result'}} adv_pend {m.adv_pend})")
        if m.w_ok:
            got, exp = self.w(), m.w
            assert got == exp, (f"clock {self.n} (advance {self.n_adv}): w mismatch\n"
                                f"  rtl   {[hex(x) for x in got]}\n  model {[hex(x) for x in exp]}")
            self.n_w += 1

    async def cycle(self, seg=None, seg_read=None, start_slot=None, sync_value=None, advance=False,
                    sync_hold=None, check=True):
        """One clock with the given inputs (None = not asserted), then compare with the model.
        seg = (slot, field, value) writes a field; seg_read = (slot, field) reads one back."""
        d = self.dut
        self._idle()
        if seg is not None:
            d.seg_we.value = 1
            d.seg_slot.value, d.seg_field.value, d.seg_wdata.value = seg[0], seg[1], seg[2] & M32
        if seg_read is not None:
            d.seg_re.value = 1
            d.seg_slot.value, d.seg_field.value = seg_read
            exp_rd = self.model.read_field(*seg_read)
        if start_slot is not None:
            d.start.value = 1
            d.start_slot.value = start_slot
        if sync_value is not None:
            d.sync.value = 1
            self.sync_value = sync_value & M64
            self.drive_sync()
        d.advance.value = int(advance)
        was_op = self.model._op is not None and self.model._op["kind"] == "advance"
        self.model.step(seg_we=seg is not None, seg_slot=seg[0] if seg else 0, seg_field=seg[1] if seg else 0,
                        seg_wdata=seg[2] if seg else 0, start=start_slot is not None, start_slot=start_slot or 0,
                        sync=sync_value is not None, sync_value=getattr(self, "sync_value", 0),
                        advance=advance, hold=bool(getattr(self, "hold", 0)),
                        task_pos=bool(getattr(self, "task_pos", 0)))
        await FallingEdge(d.clk)
        self.n += 1
        self.n_adv += int(advance)
        if was_op and self.model._op is None:
            self.model_ev = getattr(self, "model_ev", 0) + int(self.model.clamped)
        if seg_read is not None:
            got = int(d.seg_rdata.value)
            assert got == exp_rd, f"clock {self.n}: slot {seg_read[0]} field {seg_read[1]} read {got:#x} " \
                                  f"expected {exp_rd:#x}"
            self.n_seg += 1
        elif int(d.seg_rdata.value) != 0:
            raise AssertionError(f"clock {self.n}: seg_rdata {int(d.seg_rdata.value):#x} without a read")
        if check:
            self.check()

    async def wait_idle(self, limit=10000):
        """Clocks without inputs until the engine is idle (model and RTL), checked at the end.  Python
        sleeps through them (one timer): nothing is driven, and gov_ev_monitor counts any gov_ev pulse."""
        n = 0
        while self.model.busy:
            was_op = self.model._op is not None and self.model._op["kind"] == "advance"
            self.model.step(hold=bool(getattr(self, "hold", 0)), task_pos=bool(getattr(self, "task_pos", 0)))
            if was_op and self.model._op is None:
                self.model_ev = getattr(self, "model_ev", 0) + int(self.model.clamped)
            n += 1
            assert n < limit, "engine does not finish"
        self._idle()
        if n:                                   # we are at (or 10 ps after) a falling edge
            await Timer(n * CLK_NS - 2, unit="ns")  # past the n-th rising edge, before the n-th falling one
            await FallingEdge(self.dut.clk)
        self.n += n
        self.check()

    async def readout(self, count):
        """Random readout-port reads (the delay line must be current); no clock edge passes."""
        d, m = self.dut, self.model
        assert m.w_ok
        w = m.w
        for _ in range(count):
            age, b = self.rng.randrange(self.N + 1), self.rng.randrange(64)
            d.rd_age.value, d.rd_bit.value = age, b
            await Timer(10, unit="ps")          # stays inside the low clock phase
            exp = (w[self.N - age] >> b) & 1
            assert int(d.rd_q.value) == exp, f"readout age {age} bit {b}: {int(d.rd_q.value)} != {exp}"
            self.n_rd += 1

    async def program(self, slots, base=0, readback=True):
        for i, s in enumerate(slots):
            s = s.normalised()
            idx = (base + i) % NSLOT
            for f in range(len(FIELDS)):
                await self.cycle(seg=(idx, f, slot_field(s, f)))
            if readback:
                for f in range(len(FIELDS)):
                    await self.cycle(seg_read=(idx, f))

    async def advance(self, gap=0):
        await self.cycle(advance=True)
        await self.wait_idle()
        for _ in range(gap):
            await self.cycle()
        return self.w()


@cocotb.test()
async def closed_form(dut):
    env = Env(dut)
    await env.start()
    N = env.N
    rng = env.rng
    checks = 0
    n_periods = int(os.environ.get("EMPC_REFGEN_PERIODS", 3000))
    # quadratic segment through the 64-bit wrap and the 2**32 integer wrap
    for r0, d1, d2 in ((0xFFFFFFF0_00000000, 0x0000_0001_2345_6789, -0x1234_5678),
                       (0x7FFF_FFFF_8000_0000, -0x0000_0003_0000_0001, 0x7FFF_FFFF),
                       (rng.getrandbits(64), rng.getrandbits(40), rng.randrange(-2**31, 2**31))):
        await env.program([Slot(0, r0, d1, d2)], base=5)
        await env.cycle(start_slot=5)
        heads = []
        wrapped32 = wrapped64 = False
        for p in range(n_periods):
            w = await env.advance()
            exp = (r0 + p * d1 + p * (p - 1) // 2 * d2) & M64
            assert w[N] == exp, f"period {p}: head {w[N]:#x} closed form {exp:#x}"
            heads.append(w[N])
            for j in range(N):
                if p - (N - j) >= 0:
                    assert w[j] == heads[p - (N - j)], f"delay line w[{j}] at period {p}"
            if p:
                wrapped32 |= (heads[p] >> 32) < (heads[p - 1] >> 32) if d1 > 0 else (heads[p] >> 32) > (heads[p - 1] >> 32)
                wrapped64 |= abs(wrap(heads[p], 64) - wrap(heads[p - 1], 64)) > (1 << 62)
            if p % 500 == 0:
                await env.readout(20)
            checks += 1
        dut._log.info("closed form r0=%#x d1=%#x d2=%d: %d periods ok (integer part wrapped mod 2**32: %s, "
                      "signed 64-bit overflow: %s)", r0, d1 & M64, d2, n_periods, wrapped32, wrapped64)
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
    # sync: head and delay line = the value, differences 0; an advance and a start in the sync
    # clock run right after the sync
    sv, r0, d1 = 0xABCD_0000_1234_5678, 0x0000_0042_8000_0000, 0x1_0000_0000
    await env.program([Slot(0, r0, d1, 0)], base=3)
    await env.cycle(sync_value=sv, start_slot=3, advance=True)
    assert int(dut.busy.value) == 1 and int(dut.w_ok.value) == 0
    n_sync = 0
    while env.model._op is None or env.model._op["kind"] == "sync":
        await env.cycle()
        n_sync += 1
    w = env.model.w
    assert w == [sv] * (N + 1), "sync: every word = the sync value"
    assert env.w() == w
    await env.wait_idle()
    w = env.w()
    assert w[N] == r0 and w[:N] == [sv] * N, "the advance of the sync clock must run right after the sync"
    w = await env.advance()
    assert w[N] == (r0 + d1) & M64 and w[N - 1] == r0 and w[:N - 1] == [sv] * (N - 1)
    await env.readout(200)
    checks += 3
    dut._log.info("closed_form: %d period checks, %d clocks (sync %d clocks), %d delay-line compares, "
                  "%d readout bits, %d field read-backs", checks, env.n, n_sync, env.n_w, env.n_rd, env.n_seg)


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
    await env.wait_idle()
    await env.cycle(start_slot=0)
    n = int(round(0.07 / Ts))
    heads = [(await env.advance(gap=env.rng.randrange(3)))[N] for _ in range(n)]
    checks = 0
    prev = (0.0, 1.5)
    for t, v, kind in pts:
        p = int(round(t / Ts))
        assert heads[p] == q32(v * unit) & M64, f"breakpoint t={t}: {wrap(heads[p], 64) / 2**32} != {v * unit}"
        if kind == "step":      # the value before the step is the previous one
            assert heads[p - 1] == q32(prev[1] * unit) & M64, f"value before step at t={t}"
        else:                   # ramp midpoint within 1 count of the straight line
            # (breakpoint times are rounded to whole periods)
            p0 = int(round(prev[0] / Ts))
            pm = (p0 + p) // 2
            vm = prev[1] + (v - prev[1]) * (pm - p0) / (p - p0)
            assert abs(wrap(heads[pm], 64) / 2**32 - vm * unit) < 2**-20, f"ramp midpoint period {pm}"
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


def rand_gov(rng, task_pos):
    """Random governor words: realistic magnitudes mostly, extremes sometimes."""
    big = rng.random() < 0.15
    vmax = rng.choice([0, 1, M63, rng.getrandbits(63)]) if big else rng.getrandbits(rng.choice([20, 30, 36, 40]))
    a = rng.choice([0, 1, M63, rng.getrandbits(63)]) if big else max(1, vmax >> rng.randrange(0, 12))
    return vmax, a, rng.choice([0, 1, 3, 4, 6, rng.randrange(32)]), rng.random() < 0.9


@cocotb.test()
async def random_vs_model(dut):
    env = Env(dut)
    gov = os.environ.get("EMPC_REFGEN_GOV", "0") == "1"
    await env.start(governor=gov)
    rng = env.rng
    m = env.model
    if gov:
        await env.set_gov(*rand_gov(rng, False))
    await env.program([rand_slot(rng) for _ in range(NSLOT)], readback=False)
    await env.cycle(start_slot=rng.randrange(NSLOT))
    n_clocks = int(os.environ.get("EMPC_REFGEN_CLOCKS", 60000))
    stats = dict(advance=0, start=0, sync=0, write=0, read=0, start_adv=0, sync_adv=0, sync_start=0,
                 write_load=0, adv_busy=0, readouts=0)
    next_adv = 0
    while env.n < n_clocks:
        kw = {}
        if env.n >= next_adv:
            kw["advance"] = True
            stats["advance"] += 1
            stats["adv_busy"] += int(m.busy)
            # governed: an advance takes 326-459 clocks; half the spacings longer, so the delay line is
            # compared (w_ok) and the governor words rewritten (idle) often enough
            next_adv = env.n + rng.choice([1, 2, 3, 30, 70, 150, 200, 300] + ([400, 500, 700, 900] * 2 if gov else []))
        r = rng.random()
        if r < 0.004 or ("advance" in kw and r > 0.985):        # (a start in an advance's clock: 1.5 %)
            kw["start_slot"] = rng.randrange(NSLOT)
            stats["start"] += 1
            stats["start_adv"] += int("advance" in kw)
        elif r < 0.006 and not m.sync_pend and not (m._op is not None and m._op["kind"] == "sync"):
            kw["sync_value"] = rng.getrandbits(64)
            stats["sync"] += 1
            stats["sync_adv"] += int("advance" in kw)
            if rng.random() < 0.3:
                kw["start_slot"] = rng.randrange(NSLOT)
                stats["sync_start"] += 1
        r = rng.random()
        begins = m._op is None and not m.sync_pend and m.adv_pend      # an advance begins in this clock
        if r < 0.03 or (begins and r < 0.4):
            # a field write: often to the slot an advance beginning now loads; never to the
            # slot of an advance in progress
            nxt = m.pend_slot if m.pend else (m.slot + 1) % NSLOT
            a = nxt if rng.random() < 0.5 else rng.randrange(NSLOT)
            if a != m.loading_slot:
                s = rand_slot(rng).normalised()
                f = rng.randrange(len(FIELDS))
                kw["seg"] = (a, f, slot_field(s, f))
                stats["write"] += 1
                stats["write_load"] += int(begins and a == nxt)
        elif r < 0.045:
            kw["seg_read"] = (rng.randrange(NSLOT), rng.randrange(len(FIELDS)))
            stats["read"] += 1
        if gov:
            # hold and task change at random (taken when an advance begins); the governor
            # words are rewritten only while the engine is idle (the passes read them)
            if rng.random() < 0.2:
                env.hold = int(rng.random() < 0.5)
                env.task_pos = int(rng.random() < 0.5)
            if "seg" not in kw and not m.busy and rng.random() < 0.003:
                words = gov_words(*rand_gov(rng, env.task_pos))
                slot = rng.choice(list(words))
                kw["seg"] = (slot, GOV_FIELD, words[slot])
                stats["gov_write"] = stats.get("gov_write", 0) + 1
            elif "seg" not in kw and "seg_read" not in kw and rng.random() < 0.002:
                kw["seg_read"] = (rng.randrange(NSLOT), GOV_FIELD)
        await env.cycle(**kw)
        if m.w_ok and rng.random() < 0.01:
            await env.readout(8)
            stats["readouts"] += 1
    await env.wait_idle()
    assert stats["adv_busy"] > 50 and stats["write_load"] > 3 and stats["start_adv"] > 0 and stats["sync_adv"] >= 0
    assert env.gov_ev == getattr(env, "model_ev", 0), \
        f"gov_ev pulses {env.gov_ev} != model clamps {getattr(env, 'model_ev', 0)}"
    if gov:
        assert env.model_ev > 20, "the governor never clamped"
        # the one-sided speed hold: held advances of the speed task with g > 0 and g < 0, vd passing
        # (towards lower |g|) and blocked, each seen (the model counts them when an advance begins)
        hc = m.hold_cases
        stats["speed_hold"] = {f"g{'<' if n else '>='}0 {'pass' if p else 'block'}": c for (n, p), c in hc.items()}
        assert min(hc.values()) >= 3, f"speed-task hold cases not all exercised: {stats['speed_hold']}"
    dut._log.info("random%s: %d clocks, %d advances, %d delay-line compares, %d readout bits, %d field read-backs "
                  "bit-exact vs model (seed %d), %d governor clamps; %s", " (governor)" if gov else "", env.n,
                  env.n_adv, env.n_w, env.n_rd, env.n_seg, env.seed, getattr(env, "model_ev", 0), stats)


@cocotb.test()
async def governor(dut):
    """Target steps shaped within vmax / a, both tasks, with and without hold; extremes vs gov_step."""
    env = Env(dut)
    await env.start(governor=True)
    N = env.N
    checks = 0
    for task_pos in (0, 1):
        for hold_mode in (0, 1):
            env.task_pos = task_pos
            vmax, a, ksh = 3 << 32, 1 << 30, 3
            await env.set_gov(vmax, a, ksh, True)
            await env.cycle(sync_value=0)
            await env.wait_idle()
            target = 200 << 32
            await env.program([Slot(0, target, 0, 0, last=True)], base=9)
            await env.cycle(start_slot=9)
            heads, vs = [], []
            for p in range(420):
                env.hold = int(hold_mode and 40 <= p < 60)          # a hold while speeding up
                w = await env.advance()
                heads.append(wrap(w[N], 64))
                vs.append(wrap(env.model.v, 64))
            d = [b - a_ for a_, b in zip([0] + heads, heads)]
            assert max(abs(x) for x in d) <= vmax, "governed increment above vmax"
            assert max(abs(y - x) for x, y in zip([0] + d, d)) <= a, "increment changed by more than a"
            # ends on the target to within the catch-up's resolution 2^ksh LSB of Q.32 (e >> ksh = 0)
            assert abs(heads[-1] - target) < (1 << ksh) and d[-1] == 0, f"does not end on the target: {heads[-1]:#x}"
            if hold_mode and task_pos:
                assert all(abs(d[p + 1]) <= abs(d[p]) for p in range(40, 59)), "position hold raised the speed"
            if hold_mode and not task_pos:
                assert all(abs(d[p + 1]) <= abs(d[p]) for p in range(41, 59)), "speed hold did not decay"
            checks += 1
    # extremes: a 2^63 step, vmax = a = 2^63 - 1, ksh 31 and 0 (bit-exact vs the model via check())
    env.hold = 0
    for vmax, a, ksh in ((M63, M63, 0), (M63, 1, 31), (0, M63, 5), (1, 0, 0)):
        await env.set_gov(vmax, a, ksh, True)
        await env.program([Slot(0, 1 << 63, 0, 0, last=True), Slot(0, 0x7FFF_FFFF_FFFF_FFFF, 0, 0, last=True)], base=3)
        for start in (3, 4, 3):
            await env.cycle(start_slot=start)
            for _ in range(5):
                await env.advance()
                checks += 1
    await env.wait_idle()
    assert env.gov_ev == env.model_ev
    dut._log.info("governor: %d checks, %d clamps", checks, env.model_ev)


@cocotb.test()
async def braking(dut):
    """Position task, braking distance: target steps of 1..4000 counts (both signs, from rest and
    interrupting a motion) with realistic vmax / a and ksh 0..8, occasional holds; bit-exact against
    the model after every advance (delay line), and model-independently: a step taken from rest
    (v = 0, no hold) never passes its target by more than a (the proportional catch-up alone passed it
    by far more at ksh 0..3), and the brake, no-speed-up and V up / down cases are all exercised."""
    env = Env(dut)
    await env.start(governor=True)
    rng = env.rng
    m = env.model
    N = env.N
    env.task_pos = 1
    n_adv = int(os.environ.get("EMPC_REFGEN_BRAKE_ADV", 1600))
    worst, steps_rest, k = 0.0, 0, 0
    while k < n_adv:
        vmax = rng.getrandbits(33) | (1 << 33)                  # 2..4 counts per period
        a = max(1, vmax >> rng.randrange(3, 8))
        ksh = rng.choice([0, 1, 3, 5, 8])
        env.hold = 0
        await env.set_gov(vmax, a, ksh, True)
        await env.cycle(sync_value=0)
        await env.wait_idle()
        tgt = 0
        for _ in range(6):
            if rng.random() < 0.5:                              # from rest (else it interrupts the motion)
                env.hold = 0
                await env.cycle(sync_value=(tgt << 32) & M64)
                await env.wait_idle()
            tgt += rng.choice([1, -1]) * rng.choice([rng.randrange(1, 20), rng.randrange(20, 400), rng.randrange(400, 4000)])
            await env.program([Slot(0, (tgt << 32) & M64, 0, 0, last=True)], base=5, readback=False)
            await env.cycle(start_slot=5)
            rest = m.v == 0
            sgn = 1 if tgt << 32 > wrap(m.head, 64) else -1
            held = False
            periods = rng.choice([rng.randrange(5, 60), 300])
            hp = 0.03 if rng.random() < 0.3 else 0.0
            for p in range(periods):
                env.hold = int(rng.random() < hp)
                held |= bool(env.hold)
                w = await env.advance()
                k += 1
                if rest and not held and p > 0:
                    worst = max(worst, sgn * (wrap(w[N], 64) - (tgt << 32)) / a)
            steps_rest += int(rest and not held)
    bc = m.brake_cases
    dut._log.info("braking: %d advances bit-exact vs model (seed %d), %d steps from rest, worst overshoot %.3g a, "
                  "cases %s", k, env.seed, steps_rest, worst, bc)
    assert worst <= 1.0, f"a step from rest passed its target by {worst:.3g} a"
    assert steps_rest >= 3 and min(bc[c] for c in ("brake", "slow", "up", "down")) >= 50, bc


@pytest.mark.cost(45)           # Verilator build (about 28 CPU s, shared with test_ref_gen_governed) + 21 s of tests
def test_ref_gen():
    from runner import run
    run(toplevel="ref_gen", test_module="test_ref_gen", parameters=PARAMS, sim="verilator", name="test_ref_gen",
        run_name="all", extra_env={"TB_PARAMS": json.dumps(PARAMS)})


@pytest.mark.cost(40)           # waits for test_ref_gen's Verilator build (or makes it) + 200,000 clocks (about 16 s)
def test_ref_gen_governed():
    from runner import run
    run(toplevel="ref_gen", test_module="test_ref_gen", parameters=PARAMS, sim="verilator", name="test_ref_gen",
        run_name="governed",
        extra_env={"TB_PARAMS": json.dumps(PARAMS), "EMPC_REFGEN_GOV": "1", "EMPC_REFGEN_CLOCKS": "200000"},
        testcase=["random_vs_model"])


def test_ref_gen_hold_mutant(tmp_path):
    """The governed random test must fail on the old two-sided speed hold (vd = 0 whenever held), by a
    delay-line mismatch against the model (not by a statistics check)."""
    import pytest
    import runner
    from files import rtl_sources
    for old in runner.BUILD.glob("sim/test_ref_gen_hold_mutant_*/results.xml"):
        old.unlink()
    src = next(p for p in rtl_sources() if p.name == "ref_gen.v").read_text()
    good = "wire        vdc  = hblk ? 1'b0 :"
    assert src.count(good) == 1, "the mutant no longer matches rtl/ref_gen.v"
    mut = tmp_path / "ref_gen.v"
    mut.write_text(src.replace(good, "wire        vdc  = (gv_hold && !gv_pos) ? 1'b0 :"))
    orig = runner.rtl_sources
    runner.rtl_sources = lambda: [mut if p.name == "ref_gen.v" else p for p in rtl_sources()]
    try:
        with pytest.raises((AssertionError, SystemExit)):  # cocotb's runner exits on a failed test
            runner.run(toplevel="ref_gen", test_module="test_ref_gen", parameters=PARAMS,
                       extra_env={"TB_PARAMS": json.dumps(PARAMS), "EMPC_REFGEN_GOV": "1",
                                  "EMPC_REFGEN_CLOCKS": "150000"},
                       testcase=["random_vs_model"], name="test_ref_gen_hold_mutant")
    finally:
        runner.rtl_sources = orig
    res = list(runner.BUILD.glob("sim/test_ref_gen_hold_mutant_*/results.xml"))
    assert len(res) == 1 and "w mismatch" in res[0].read_text(), "the mutant failed for another reason"


@pytest.mark.cost(17)          # seconds on an idle core (make sim starts the costliest first)
def test_ref_gen_n1():
    from runner import run
    p = {"N": 1}
    run(toplevel="ref_gen", test_module="test_ref_gen", parameters=p,
        extra_env={"TB_PARAMS": json.dumps(p), "EMPC_REFGEN_PERIODS": "1000", "EMPC_REFGEN_CLOCKS": "30000"},
        testcase=["closed_form", "random_vs_model"], name="test_ref_gen_n1")
