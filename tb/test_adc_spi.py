"""cocotb tests of adc_spi (back-to-back SPI frames, per-frame checks, centred window) against
empc.rtlmodel.adc_spi.AdcSpiCycle.

Toplevel is tb/hdl/adc_spi_tb.v: the master wired pin-to-pin to tb/hdl/adc_spi_slave.v (three ADC
models with a configurable output delay / invalid window, so a wrong sample instant reads 'x'
and fails).  Every clock cycle, EVERY output of the block (cs_n, sclk, busy, per-frame codes and
flags, the controller sample, the period sums, offsets, calibration and refusal flags, the miss
counter) is compared with the cycle-exact model, which is fed the same inputs.  On top of that
each test asserts what it is about without the model (latencies from the formulas, a fault on
the frame it must come on, frozen after exactly FROZEN_PERIODS periods ...).  Seed: EMPC_SEED.
"""
from __future__ import annotations

import json
import os
import random

import pytest

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ReadOnly, RisingEdge

from empc.rtlmodel.adc_spi import AdcInputs, AdcSpiCycle, AdcSpiParams, cal_mean

T_CLK_PS = 10_000
DEFAULT_SEED = 20240611


def mon_fields(p: AdcSpiParams):
    """(name, width, signed) of tb/hdl/adc_spi_tb.v's `mon`, LSB first."""
    b, psw = p.adc_bits, p.psw()
    return [("cs_n", 1, 0), ("busy", 1, 0), ("trig_miss", 1, 0), ("miss_cnt", p.miss_w, 0), ("fvalid", 1, 0),
            ("code0", b, 0), ("code1", b, 0), ("code2", b, 0), ("frame_err", 1, 0), ("oc", 1, 0), ("oc_ch", 3, 0),
            ("sum_err", 1, 0), ("stuck", 1, 0), ("frozen", 1, 0), ("valid", 1, 0), ("cur0", p.cur_w, 1),
            ("cur1", p.cur_w, 1), ("cur2", p.cur_w, 1), ("sat", 1, 0), ("psum0", psw, 1), ("psum1", psw, 1),
            ("psum2", psw, 1), ("pcount", p.pcnt_w, 0), ("offset0", b, 0), ("offset1", b, 0), ("offset2", b, 0),
            ("cal_busy", 1, 0), ("cal_done", 1, 0), ("refused", 1, 0), ("sclk", 1, 0)]


class Bench:
    """Clock loop: inputs per cycle -> DUT and model; every output compared every cycle.

    Period timing: period_start every 2P cycles from ``ps0`` and trig P cycles after it, unless
    ``ps_extra`` (sync restarts: an early boundary, the period continues from there) or
    ``trig_shift`` (trig moved by n cycles in the period starting at a given boundary) say
    otherwise.  Frame codes: ``gen(k, a, tau, slot)`` returns ((c0, c1, c2), (l0, l1, l2)) for
    frame k, predicted to be accepted in cycle a, tau = a - (centre cycle of its period),
    slot = its grid index in the period (None before the first boundary).
    """

    def __init__(self, dut):
        self.dut = dut
        cfg = json.loads(os.environ["ADC_SPI_PARAMS"])
        self.p = AdcSpiParams(**cfg["rtl"])
        self.seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
        self.rng = random.Random(self.seed)
        self.m = AdcSpiCycle(self.p)
        self.fields = mon_fields(self.p)
        self.inp = AdcInputs(oc_thr=self.p.code_max, sum_thr=self.p.code_max)
        self.once = {}                         # one-cycle inputs of the next cycle
        self.ps0 = 5
        self.ps_extra = set()
        self.trig_shift = {}
        self.no_ps = False
        self.gen = lambda k, a, tau, slot: ((2048, 2048, 2048), (0, 0, 0))
        self.k = 0
        self.t = 0
        self.cache = {}
        self.hist = []                         # (cycle, outputs) of interesting cycles
        self.n_checked = 0
        dut._log.info("params %s, seed %d (EMPC_SEED)", self.p, self.seed)

    # ---------------------------------------------------------------- timing plan
    def ps_at(self, c: int) -> bool:
        if self.no_ps or c < self.ps0:
            return False
        last = self.last_ps(c - 1)
        nxt = (last + 2 * self.p.half_period) if last is not None else self.ps0
        return c == nxt or c in self.ps_extra

    def last_ps(self, c: int):
        """Cycle of the last period_start at or before c (None if none)."""
        if self.no_ps or c < self.ps0:
            return None
        cache = self.cache.setdefault("ps", {})
        if c in cache:
            return cache[c]
        hi = self.cache.get("ps_hi")                  # cycles are computed in order from ps0
        last = cache[hi] if hi is not None else None
        cc = hi + 1 if hi is not None else self.ps0
        while cc <= c:
            nxt = (last + 2 * self.p.half_period) if last is not None else self.ps0
            if cc == nxt or cc in self.ps_extra:
                last = cc
            cache[cc] = last
            cc += 1
        self.cache["ps_hi"] = c
        return last

    def trig_at(self, c: int) -> bool:
        last = self.last_ps(c)
        if last is None:
            return False
        return c == last + self.p.half_period + self.trig_shift.get(last, 0)

    def centre(self, c: int):
        last = self.last_ps(c)
        return None if last is None else last + self.p.half_period

    def predict_accept(self):
        """(cycle, grid slot) of the next frame start after the current cycle, from the model's
        grid state and the timing plan."""
        p, m = self.p, self.m
        gc, gp = m.gc, m.gp
        busy_to = m.last_accept + p.idle_after() if m.last_accept is not None else -1
        c = self.t
        while True:
            ps = self.ps_at(c)
            if gc == 0 and c > busy_to:
                return c, (None if gp >= p.gp_max else gp)
            gc, gp = (p.g0 - 1, 0) if ps else (p.tf - 1 if gc == 0 else gc - 1,
                                                  gp + 1 if gc == 0 and gp != p.gp_max else gp)
            c += 1

    def next_codes(self):
        a, slot = self.predict_accept()
        cen = self.centre(a)
        tau = None if cen is None else a - cen
        codes, lead = self.gen(self.k, a, tau, slot)
        self.inp.codes = tuple(min(max(int(x), 0), self.p.code_max) for x in codes)
        self.inp.lead = tuple(lead)

    # ---------------------------------------------------------------- clock loop
    async def start(self):
        d = self.dut
        Clock(d.clk, 10, unit="ns").start()
        for s in (d.period_start, d.trig, d.bridges_on, d.off_we, d.off_wdata, d.cal_start, d.refused_clear,
                  d.s_code0, d.s_code1, d.s_code2, d.s_lead):
            s.value = 0
        d.oc_thr.value = self.inp.oc_thr
        d.sum_thr.value = self.inp.sum_thr
        d.rst.value = 1
        for _ in range(3):
            await RisingEdge(d.clk)
        await ReadOnly()
        # the slave is not reset: count from here (the reset may have cut a frame of the last test)
        self.slave0 = {n: int(getattr(d.u_slave, n).value) for n in ("frames", "proto_err")}
        self.first = True
        self.next_codes()

    def set_gen(self, fn):
        """New code generator, also for the frame not yet started."""
        self.gen = fn
        self.next_codes()

    def _w(self, name, v):
        if self.cache.get(("w", name)) != v:
            getattr(self.dut, name).value = v
            self.cache[("w", name)] = v

    def decode(self, v: int) -> dict:
        out, sh = {}, 0
        for name, w, sg in self.fields:
            x = (v >> sh) & ((1 << w) - 1)
            if sg and x >> (w - 1):
                x -= 1 << w
            out[name] = x
            sh += w
        return out

    async def run(self, n: int, hook=None):
        """n cycles.  hook(bench, out) is called in every cycle after the comparison (out = the
        outputs of that cycle) and may set inputs (self.inp persistent, self.once for the next
        cycle only)."""
        d, p = self.dut, self.p
        for _ in range(n):
            await RisingEdge(d.clk)
            if self.first:
                d.rst.value = 0
                self.first = False
            c = self.t
            i = self.inp
            once = self.once
            self.once = {}
            cyc = AdcInputs(period_start=int(self.ps_at(c)), trig=int(self.trig_at(c)), bridges_on=i.bridges_on,
                            off_we=once.get("off_we", 0), off_wdata=once.get("off_wdata", i.off_wdata),
                            cal_start=once.get("cal_start", 0), refused_clear=once.get("refused_clear", 0),
                            oc_thr=i.oc_thr, sum_thr=i.sum_thr, codes=i.codes, lead=i.lead)
            self._w("period_start", cyc.period_start)
            self._w("trig", cyc.trig)
            self._w("bridges_on", cyc.bridges_on)
            self._w("off_we", cyc.off_we)
            self._w("off_wdata", cyc.off_wdata)
            self._w("cal_start", cyc.cal_start)
            self._w("refused_clear", cyc.refused_clear)
            self._w("oc_thr", cyc.oc_thr)
            self._w("sum_thr", cyc.sum_thr)
            self._w("s_code0", cyc.codes[0])
            self._w("s_code1", cyc.codes[1])
            self._w("s_code2", cyc.codes[2])
            lz = p.lead_zeros
            self._w("s_lead", cyc.lead[0] | (cyc.lead[1] << lz) | (cyc.lead[2] << 2 * lz))
            await ReadOnly()
            got = self.decode(int(d.mon.value))
            exp = self.m.outputs()
            if got != exp:
                diff = {k: (got[k], exp[k]) for k in got if got[k] != exp[k]}
                raise AssertionError(f"cycle {c}: DUT != model (field: (dut, model)) {diff}; last frames "
                                     f"{[(f.a, f.codes) for f in self.m.frames[-2:]]}; inputs {cyc}")
            self.n_checked += 1
            self.m.step(cyc)
            self.t += 1
            if self.m.last_accept == c:
                self.k += 1
                self.next_codes()
            if hook is not None:
                hook(self, got)

    def check_slave(self):
        d, p = self.dut, self.p
        assert int(d.u_slave.proto_err.value) == self.slave0["proto_err"], "SPI protocol error seen by the slave"
        for name, lo in (("cs_high_min_ps", p.cs_quiet * T_CLK_PS), ("sclk_low_min_ps", p.sclk_div * T_CLK_PS),
                         ("sclk_high_min_ps", p.sclk_div * T_CLK_PS)):
            v = int(getattr(d.u_slave, name).value)
            assert v == 0 or v >= lo, f"{name} = {v} ps < {lo}"
        # (a frame accepted in the last cycle run has its CS fall at the edge still to come)
        assert int(d.u_slave.frames.value) - self.slave0["frames"] == \
            len([f for f in self.m.frames if f.a < self.t - 1]), "slave saw a different number of frames"
        d._log.info("slave: %d frames, proto_err 0, min CS high %d ps, SCLK low/high %d/%d ps; %d cycles checked",
                    int(d.u_slave.frames.value), int(d.u_slave.cs_high_min_ps.value),
                    int(d.u_slave.sclk_low_min_ps.value), int(d.u_slave.sclk_high_min_ps.value), self.n_checked)


def rand_code(rng, p, near=None, spread=8):
    if near is None:
        return rng.randrange(1 << p.adc_bits)
    return min(max(near + rng.randint(-spread, spread), 0), p.code_max)


def frames_with(b: Bench, **kw):
    """Per-frame results (model events) whose fields equal kw."""
    return [e for e in b.m.events if all(e[k] == v for k, v in kw.items())]


# ----------------------------------------------------------------------------- tests
@cocotb.test()
async def test_reset_schedule(dut):
    """Reset values; frames run back to back on the grid from reset; no window before the first
    boundary; then the window frames sit symmetrically about the centre and valid comes at the
    stated delay after trig."""
    b = Bench(dut)
    p = b.p
    b.ps0 = 3 * p.tf + 7
    await b.start()
    outs = []
    await b.run(1, hook=lambda bb, o: outs.append(o))
    o = outs[0]
    assert o["cs_n"] == 1 and o["sclk"] == 1 and o["valid"] == 0 and o["fvalid"] == 0 and o["miss_cnt"] == 0
    assert [o[f"offset{i}"] for i in range(3)] == [p.offset_reset] * 3 and o["refused"] == 0
    valids, trigs = [], []
    n_per = 4

    def hook(bb, out):
        if out["valid"]:
            valids.append(bb.t - 1)
        if bb.trig_at(bb.t - 1):
            trigs.append(bb.t - 1)
    await b.run(b.ps0 + n_per * 2 * p.half_period + 10, hook=hook)
    starts = [f.a for f in b.m.frames]
    gaps = [y - x for x, y in zip(starts, starts[1:])]
    # before the first boundary: the reset grid, every TF cycles
    pre = [a for a in starts if a < b.ps0]
    assert pre and all(y - x == p.tf for x, y in zip(pre, pre[1:])), pre
    assert min(gaps) >= p.min_frame_period() and max(gaps) < 2 * p.tf, gaps
    # window frames: accepted at centre + (j - (2^K-1)/2) TF
    for k in range(n_per):
        cen = b.ps0 + k * 2 * p.half_period + p.half_period
        win = [f.a - cen for f in b.m.frames if f.win and abs(f.a - cen) < p.half_period]
        assert win == p.window_taus(), (k, win, p.window_taus())
        assert sum(win) == 0, "window not symmetric about the centre"
    assert len(valids) == n_per and [v - t for v, t in zip(valids, trigs)] == [p.valid_delay()] * n_per, \
        (valids, trigs, p.valid_delay())
    b.check_slave()
    dut._log.info("schedule: %d frames, gaps %d..%d clk (TF %d), window taus %s, valid %d clk after trig",
                  len(starts), min(gaps), max(gaps), p.tf, p.window_taus(), p.valid_delay())


@cocotb.test()
async def test_random(dut):
    """Random codes (anywhere / near the offsets / symmetric ripple + noise about the centre),
    offsets, thresholds, bridges on/off, CPU writes, sync restarts and trigger jitter; every
    output bit-exact every cycle."""
    b = Bench(dut)
    p, rng = b.p, b.rng
    n_per = int(os.environ.get("ADC_SPI_PERIODS", "40"))
    P2 = 2 * p.half_period
    # timing plan: a few sync restarts and displaced triggers
    for k in range(1, n_per, 7):
        b.ps_extra.add(b.ps0 + k * P2 + rng.randrange(P2 // 4, P2))     # roughly: relative to the plan
    b.trig_shift[b.ps0] = 1                    # at least one displaced trigger
    base = [rng.randrange(1 << p.adc_bits) for _ in range(3)]
    mode = {"m": 0}

    def gen(k, a, tau, slot):
        m = mode["m"]
        if m == 0:
            return [rand_code(rng, p) for _ in range(3)], (0, 0, 0)
        if m == 1:
            return [rand_code(rng, p, b.m.offsets[i], 300) for i in range(3)], (0, 0, 0)
        # odd-symmetric ripple about the centre plus noise: the window mean is the centre value +- noise
        t = tau or 0
        return [base[i] + (t * (i + 1)) // 16 + rng.randint(-2, 2) for i in range(3)], \
            ((rng.randrange(1 << p.lead_zeros), 0, 0) if rng.random() < 0.01 else (0, 0, 0))
    b.gen = gen
    await b.start()
    stats = dict(writes=0, refused=0)

    def hook(bb, out):
        c = bb.t
        if rng.random() < 0.002:
            mode["m"] = rng.randrange(3)
        if rng.random() < 0.003:
            bb.inp.bridges_on = int(not bb.inp.bridges_on)
        if rng.random() < 0.004:
            bb.once = dict(off_we=1 << rng.randrange(3), off_wdata=rand_code(rng, p, 2048, 200))
            stats["writes"] += 1
        if rng.random() < 0.003:
            diffs = [abs(x - o) for x, o in zip(bb.m.code, bb.m.offsets)]
            bb.inp.oc_thr = max(0, min(p.code_max, rng.choice(diffs) + rng.randint(-2, 2)))
        if rng.random() < 0.003:
            s = abs(sum(x - o for x, o in zip(bb.m.code, bb.m.offsets)))
            bb.inp.sum_thr = max(0, min(p.code_max, s + rng.randint(-3, 3)))
        if rng.random() < 0.0005:
            bb.trig_shift[bb.last_ps(c) or 0] = rng.choice([-1, 1, -p.tf, 3])
        if rng.random() < 0.0003:
            bb.once = dict(refused_clear=1)
        stats["refused"] = out["refused"]
    await b.run(b.ps0 + n_per * P2, hook=hook)
    ev = b.m.events
    n_oc = sum(any(e["oc_ch"]) for e in ev)
    n_valid = sum(1 for f in b.m.frames if f.last)
    b.check_slave()
    assert n_oc > 0 and b.m.miss_cnt > 0 and n_valid > n_per // 2
    dut._log.info("random: %d frames x 3 channels, %d overcurrent frames, %d windows, %d offset writes, "
                  "miss_cnt %d, %d cycles bit-exact", len(ev), n_oc, n_valid, stats["writes"], b.m.miss_cnt,
                  b.n_checked)


@cocotb.test()
async def test_overcurrent(dut):
    """OC on one frame between two good ones, on each phase, positive and negative, exactly at
    the threshold (no trip) and one above (trip); offsets near the rails; the pulse comes in the
    frame's own fvalid cycle, oc_to_pins() - 1 clocks after its last SCLK rising edge."""
    b = Bench(dut)
    p = b.p
    m = p.code_max
    thr = 500
    b.inp.oc_thr = thr
    plan = {}                                   # frame index -> codes
    cases = []
    k0 = 3
    for off in (2048, 0, m, 1, m - 1):
        for ch in range(3):
            for d, trips in ((thr, False), (thr + 1, True), (-thr, False), (-(thr + 1), True)):
                code = off + d
                if not 0 <= code <= m:
                    continue
                cases.append((off, ch, d, trips))
    # each case: 2 good frames, the test frame, 2 good frames, all at offset `off`
    k = k0
    for off, ch, d, trips in cases:
        good = (off, off, off)
        for _ in range(2):
            plan[k] = good
            k += 1
        bad = list(good)
        bad[ch] = off + d
        plan[k] = tuple(bad)
        k += 1
        for _ in range(2):
            plan[k] = good
            k += 1
    offs_at = {}
    kk = k0
    for off, *_ in cases:
        offs_at[kk] = off
        kk += 5
    last_off = cases[-1][0]                     # frames after the plan: zero current at the last offset
    b.gen = lambda k, a, tau, slot: (plan.get(k, (p.offset_reset,) * 3 if k < k0 else (last_off,) * 3), (0, 0, 0))
    await b.start()
    oc_cycles, sclk_rise = [], []

    def hook(bb, out):
        if out["oc"]:
            oc_cycles.append(bb.t - 1)
        if out["sclk"] and not hook.prev_sclk:
            sclk_rise.append(bb.t - 1)
        hook.prev_sclk = out["sclk"]
        # offsets for the next case: after the previous frame's stage B (its difference is taken),
        # before the case's first stage A
        nk = len(bb.m.events)
        if nk in offs_at and not hook.done.get(nk):
            hook.done[nk] = True
            bb.once = dict(off_we=0b111, off_wdata=offs_at[nk])
    hook.prev_sclk = 1
    hook.done = {}
    b.no_ps = True                              # no windows needed; frames on the reset grid
    await b.run((k + 2) * p.tf + 200, hook=hook)
    n_trip = 0
    for idx, (off, ch, d, trips) in enumerate(cases):
        f = b.m.frames[k0 + 5 * idx + 2]
        ev = frames_with(b, a=f.a)[0]
        assert ev["diff"][ch] == d and ev["oc_ch"] == tuple(trips and i == ch for i in range(3)), (off, ch, d, ev)
        fv = ev["fvalid_cycle"]
        assert (fv in oc_cycles) == trips, (off, ch, d)
        if trips:
            n_trip += 1
            last_rise = max(r for r in sclk_rise if r <= fv)
            assert fv - last_rise == p.oc_to_pins() - 1, (fv, last_rise)
            # the good frames around it did not trip
            for j in (-1, 1):
                g = frames_with(b, a=b.m.frames[k0 + 5 * idx + 2 + j].a)[0]
                assert g["fvalid_cycle"] not in oc_cycles
    extra = [(e["a"], e["codes"], e["diff"]) for e in b.m.events if e["fvalid_cycle"] in oc_cycles
             and not any(e["a"] == b.m.frames[k0 + 5 * i + 2].a for i in range(len(cases)))]
    assert len(oc_cycles) == n_trip, f"overcurrent on frames that are not test frames: {extra}"
    b.check_slave()
    dut._log.info("overcurrent: %d cases (offsets 0/1/mid/max-1/max, 3 phases, +-thr, +-(thr+1)), %d trips, each "
                  "in its own frame's fvalid cycle, %d clk after the last SCLK rise (pins off %d clk after it)",
                  len(cases), n_trip, p.oc_to_pins() - 1, p.oc_to_pins())


@cocotb.test()
async def test_sum_stuck(dut):
    """Sum of the currents just at / above the threshold for SUM_PERSIST - 1 and SUM_PERSIST
    frames, positive and negative; codes at the rails for STUCK_PERSIST - 1 / STUCK_PERSIST
    frames; stuck-low MISO (also after a calibration to offset 0: OC silent, stuck trips);
    stuck-high MISO (frame error every frame, stuck)."""
    b = Bench(dut)
    p = b.p
    m = p.code_max
    S, K = p.sum_persist, p.stuck_persist
    thr = 40
    b.inp.sum_thr = thr
    b.inp.oc_thr = m
    o = p.offset_reset
    seq = []                                    # (codes, lead, tag)
    good = lambda: ((o + 7, o - 3, o - 4), (0, 0, 0), "good")
    for sgn in (1, -1):
        for n_bad in (S - 1, S):
            for s in (thr, thr + 1):
                seq += [good()] * 2
                seq += [((o + sgn * s, o, o), (0, 0, 0), f"sum{sgn * s}x{n_bad}")] * n_bad
                seq += [good()] * 2
    for ch in range(3):
        for rail in (0, m):
            for n_bad in (K - 1, K):
                seq += [good()] * 2
                c = [o, o, o]
                c[ch] = rail
                seq += [(tuple(c), (0, 0, 0), f"rail{rail}ch{ch}x{n_bad}")] * n_bad
                seq += [good()] * 2
    # one bit away from a rail (LSB or MSB alone differs): never stuck
    for c in (1, m - 1, 1 << (p.adc_bits - 1), (1 << (p.adc_bits - 1)) - 1, 2, m - 2):
        seq += [good()] * 2 + [((c, c, c), (0, 0, 0), f"near{c}")] * (K + 1) + [good()] * 2
    seq += [((0, 0, 0), (0, 0, 0), "stucklow")] * (K + 2) + [good()] * 2
    seq += [((m, m, m), ((1 << p.lead_zeros) - 1,) * 3, "stuckhigh")] * (K + 2) + [good()] * 2
    k0 = 2
    b.gen = lambda k, a, tau, slot: (seq[k - k0][0], seq[k - k0][1]) if 0 <= k - k0 < len(seq) else good()[:2]
    b.no_ps = True
    await b.start()
    sum_hi, stuck_hi, ferr = [], [], []

    def hook(bb, out):
        sum_hi.append(out["sum_err"])
        stuck_hi.append(out["stuck"])
        if out["frame_err"]:
            ferr.append(bb.t - 1)
    await b.run((len(seq) + k0 + 3) * p.tf, hook=hook)
    # expectations without the model: the flag is set by the S-th (K-th) consecutive bad frame
    # and cleared by the next good one
    fr = b.m.frames
    tags = {}
    for i, (_, _, tag) in enumerate(seq):
        tags.setdefault(tag, []).append(i + k0)

    def flag_after(hist, frame_k, delay):
        ev = frames_with(b, a=fr[frame_k].a)[0]
        return hist[ev["fvalid_cycle"] + delay]
    n = 0
    for tag, ks in tags.items():
        if tag.startswith("sum"):
            s = abs(int(tag[3:].split("x")[0]))
            nb = int(tag.split("x")[1])
            want = s > thr and nb >= S
            got = flag_after(sum_hi, ks[-1], p.sum_delay())
            assert bool(got) == want, (tag, got)
            assert not flag_after(sum_hi, ks[-1] + 1, p.sum_delay()), f"{tag}: not cleared by a good frame"
            n += 1
        elif tag.startswith("near"):
            assert not any(flag_after(stuck_hi, k, 0) for k in ks), f"{tag}: stuck one bit away from a rail"
            n += 1
        elif tag.startswith("rail") or tag in ("stucklow", "stuckhigh"):
            nb = len(ks) if tag in ("stucklow", "stuckhigh") else int(tag.split("x")[1])
            want = nb >= K
            assert bool(flag_after(stuck_hi, ks[-1], 0)) == want, tag
            if want:
                assert not flag_after(stuck_hi, ks[K - 2], 0) if K > 1 else True, f"{tag}: stuck too early"
                assert flag_after(stuck_hi, ks[K - 1], 0), f"{tag}: stuck not at frame {K}"
            assert not flag_after(stuck_hi, ks[-1] + 1, 0), f"{tag}: not cleared by a good frame"
            n += 1
    assert len(ferr) == len(tags["stuckhigh"]), "stuck-high MISO: frame error on every frame"
    # stuck-low with offsets calibrated onto the stuck channel: no OC possible, stuck still trips
    b.inp.oc_thr = 100
    b.inp.bridges_on = 0
    b.once = dict(cal_start=1)
    b.set_gen(lambda k, a, tau, slot: ((0, o, o), (0, 0, 0)))
    await b.run(1)
    while b.m.cal_busy:
        await b.run(p.tf)
    assert b.m.offsets[0] == 0 and b.m.stuck
    assert not any(b.m.events[-1]["oc_ch"]) and b.m.events[-1]["codes"][0] == 0
    b.check_slave()
    dut._log.info("sum/stuck: %d directed cases (thr %d, persistence %d / %d frames), stuck-low, stuck-high "
                  "(%d frame errors), calibrated-onto-stuck: OC silent, stuck set", n, thr, S, K, len(ferr))


@cocotb.test()
async def test_frozen(dut):
    """One channel bit-identical in every frame: bridges off -> never frozen; bridges on -> frozen
    at the boundary ending the FROZEN_PERIODS-th period, not one earlier; one bridges-off clock
    resets the count; a varying channel clears it at the next boundary."""
    b = Bench(dut)
    p, rng = b.p, b.rng
    P2 = 2 * p.half_period
    F = p.frozen_periods
    state = {"frozen_ch": 1}
    b.gen = lambda k, a, tau, slot: (tuple(2000 if i == state["frozen_ch"] else rand_code(rng, p, 2048, 30)
                                           for i in range(3)), (0, 0, 0))
    await b.start()
    fz = []
    b.inp.bridges_on = 0
    await b.run(b.ps0 + (F + 3) * P2 + 2, hook=lambda bb, o: fz.append(o["frozen"]))
    assert not any(fz), "frozen with the bridges off"
    # bridges on from a few clocks before a boundary N: the period starting at N is the first
    # with the bridges on in every cycle (both boundary cycles count)
    nxt = b.last_ps(b.t) + P2
    await b.run(nxt - 5 - b.t)
    b.inp.bridges_on = 1
    bnds = [nxt + k * P2 for k in range(1, F + 3)]
    fz = {}
    await b.run(bnds[-1] + 3 - b.t, hook=lambda bb, o: fz.__setitem__(bb.t - 1, o["frozen"]))
    # boundary bnds[j] ends on-period j+1; frozen visible the cycle after the F-th, not the (F-1)-th
    assert (F == 1 or not fz[bnds[F - 2] + 1]) and fz[bnds[F - 1] + 1], (F, [fz[x + 1] for x in bnds])
    assert not fz[bnds[F - 1]], "frozen before the boundary"
    # a single bridges-off clock in a period: not frozen at its end
    t_off = b.t + 50
    while b.t < t_off:
        await b.run(1)
    b.inp.bridges_on = 0
    await b.run(1)
    b.inp.bridges_on = 1
    nb = b.last_ps(b.t) + P2
    await b.run(nb + 2 - b.t)
    assert b.m.frozen == 0 and b.m.fzc == 0
    # channel varies again: no frozen period
    state["frozen_ch"] = None
    await b.run((F + 1) * P2)
    assert b.m.frozen == 0
    b.check_slave()
    dut._log.info("frozen: channel 1 constant, %d periods bridges off: never; bridges on: set after exactly %d "
                  "periods; one off clock resets; varying channel: never", F + 3, F)


@cocotb.test()
async def test_period_edges(dut):
    """Sync restarts at every place of the period (before / inside / after the window, on a grid
    point, on a frame's stage B and inside its serial pass), trig off the centre by -1/+1/-TF:
    misses counted, cut windows give no valid, period sums taken once the pass has ended."""
    b = Bench(dut)
    p = b.p
    P2 = 2 * p.half_period
    vl = p.valid_latency()
    n_cases = 0
    # places relative to the window's first frame start t0 (period cycles)
    rel = [p.t0 - p.tf // 2, p.t0 + 1, p.t0 + p.tf, p.half_period + 1, p.half_period + p.w_lead + vl + 3,
           p.t0 + vl, p.t0 + vl + 1, p.t0 + vl + 5, p.t0 + vl + p.pass_len(), p.g0, 1, P2 - 1]
    t = b.ps0 + P2
    for r in rel:
        t += P2                                  # one normal period in between
        b.ps_extra.add(t + r)
        t = t + r
        n_cases += 1
    t += 2 * P2
    shifts = {}
    for s in (-1, 1, -p.tf, p.tf // 2):
        t += P2
        shifts[t] = s
    b.trig_shift = dict(shifts)
    await b.start()
    valids = []
    await b.run(t + 3 * P2, hook=lambda bb, o: valids.append(bb.t - 1) if o["valid"] else None)
    assert b.m.miss_cnt >= len(shifts), b.m.miss_cnt
    b.check_slave()
    dut._log.info("period edges: %d sync restarts, %d displaced triggers -> miss_cnt %d, %d valid samples",
                  n_cases, len(shifts), b.m.miss_cnt, len(valids))


@cocotb.test()
async def test_period_sums(dut):
    """Period sums and count against a sum of the test's own codes over the frames whose stage B
    (fvalid - 1) fell in the period, also across sync restarts on a stage B and inside a pass
    (the snapshot then waits for the pass)."""
    b = Bench(dut)
    p, rng = b.p, b.rng
    P2 = 2 * p.half_period
    vl = p.valid_latency()
    # restarts: on a frame's stage B (window frame 0 accepted at t0: stage B at t0 + vl) and 5 clocks into its pass
    e1 = b.ps0 + 2 * P2 + p.t0 + vl
    b.ps_extra = {e1, e1 + 2 * P2 + p.t0 + vl + 6}
    b.gen = lambda k, a, tau, slot: ([rand_code(rng, p) for _ in range(3)], (0, 0, 0))
    await b.start()
    seen = {}

    def hook(bb, o):
        seen[bb.t - 1] = ([o["psum0"], o["psum1"], o["psum2"]], o["pcount"])
    await b.run(b.ps0 + 8 * P2, hook=hook)
    bnd = sorted({b.last_ps(c) for c in range(b.ps0, b.t) if b.last_ps(c) is not None})
    off = p.offset_reset
    n = 0
    for x, y, z in zip(bnd, bnd[1:], bnd[2:] + [b.t]):
        if z <= y + p.pass_len() + 2:
            continue
        fr = [f for f in b.m.frames if x <= f.a + vl < y]
        exp = ([sum(f.codes[i] - off for f in fr) for i in range(3)], len(fr))
        assert seen[y + p.pass_len() + 2] == exp, (x, y, seen[y + p.pass_len() + 2], exp)
        n += 1
    b.check_slave()
    assert n >= 6
    dut._log.info("period sums: %d periods checked against the codes sent (count %d), incl. restarts on a "
                  "stage B and inside a pass", n, exp[1])


@cocotb.test()
async def test_calibration(dut):
    """Calibration: per-channel round-half-up mean of 2^CAL_LOG2 frames accepted after cal_start;
    refused while the bridges are on (refused flag, nothing changes); aborted when the bridges
    come on (finished channels keep their new offsets); CPU offset writes refused while
    calibrating and while the bridges are on; refused_clear."""
    b = Bench(dut)
    p, rng = b.p, b.rng
    n_cal = 1 << p.cal_log2
    true = [2048, 2040, 2061]
    b.gen = lambda k, a, tau, slot: ([rand_code(rng, p, true[i], 3) for i in range(3)], (0, 0, 0))
    b.no_ps = True
    await b.start()
    await b.run(3)
    # refused while the bridges are on
    b.inp.bridges_on = 1
    b.once = dict(cal_start=1)
    await b.run(3)
    assert b.m.cal_busy is False and b.m.refused == 1
    b.once = dict(off_we=0b001, off_wdata=1234)
    await b.run(3)
    assert b.m.offsets[0] == p.offset_reset, "offset write accepted with the bridges on"
    b.once = dict(refused_clear=1)
    await b.run(2)
    assert b.m.refused == 0
    b.inp.bridges_on = 0
    # a full calibration with CPU writes tried while it runs
    b.once = dict(cal_start=1)
    await b.run(2)
    assert b.m.cal_busy
    b.once = dict(off_we=0b111, off_wdata=77)
    await b.run(2)
    assert b.m.refused == 1 and b.m.offsets != [77] * 3
    while b.m.cal_busy:
        await b.run(p.tf)
    got = list(b.m.offsets)
    assert b.m.cal_done and all(abs(g - t) <= 3 for g, t in zip(got, true)), (got, true)
    dut._log.info("calibration: offsets %s (true %s +- 3 LSB noise), %d frames per channel", got, true, n_cal)
    # abort: bridges on after channel 0 finished
    true[:] = [1500, 1600, 1700]
    b.next_codes()
    b.once = dict(cal_start=1)
    await b.run(2)
    while b.m.cal_ch == 0:
        await b.run(1)
    await b.run(5)
    b.inp.bridges_on = 1
    await b.run(2)
    assert not b.m.cal_busy and not b.m.cal_done and b.m.refused
    assert abs(b.m.offsets[0] - 1500) <= 3 and b.m.offsets[1] == got[1] and b.m.offsets[2] == got[2]
    b.inp.bridges_on = 0
    # a CPU write is accepted again once idle and the bridges are off
    b.once = dict(off_we=0b010, off_wdata=2222)
    await b.run(2)
    assert b.m.offsets[1] == 2222
    # rounding: channel 0 half the frames base+1 -> rounds up
    base = 1000
    cnt = {"i": 0}

    def gen(k, a, tau, slot):
        j = cnt["i"] % n_cal
        cnt["i"] += 1
        return (base + (j < n_cal // 2), base + (j < n_cal // 2 - 1), base + (j > 0)), (0, 0, 0)
    b.gen = gen
    b.once = dict(cal_start=1)
    await b.run(1)
    cnt["i"] = 0
    b.next_codes()
    while b.m.cal_busy:
        await b.run(p.tf)
    exp = [cal_mean(base * n_cal + n_cal // 2, p.cal_log2), cal_mean(base * n_cal + n_cal // 2 - 1, p.cal_log2),
           cal_mean((base + 1) * n_cal - 1, p.cal_log2)]
    assert b.m.offsets == exp, (b.m.offsets, exp)
    assert exp[0] == base + 1 and exp[1] == base and exp[2] == base + 1
    dut._log.info("rounding: offsets %s (half -> up)", exp)
    b.check_slave()
    dut._log.info("calibration: refused with bridges on, CPU writes refused while calibrating / bridges on, "
                  "abort keeps finished channels, refused_clear; %d cycles bit-exact", b.n_checked)


# ----------------------------------------------------------------------------- pytest
CONFIGS = {
    # defaults except a short PWM period (800 clk, 10 frames) and calibration (16 frames) to keep the run short
    "default": ({"half_period": 400, "cal_log2": 4}, {"T_HOLD_PS": 3000, "T_OUT_PS": 15000}),
    # the real default period (2 x 2500 clk) and every default parameter
    "p2500": ({}, {"T_HOLD_PS": 3000, "T_OUT_PS": 15000}),
    # single centre sample (AVG_LOG2 = 0, the former behaviour), narrow current word (saturation),
    # 3 clk SCLK half period, trailing bits, minimum CS quiet time, short calibration, persistence 1/2/2
    "narrow": ({"cur_w": 12, "sclk_div": 3, "sample_delay": 7, "frame_bits": 18, "cs_quiet": 1, "cal_log2": 3,
                "miss_w": 6, "offset_reset": 100, "avg_log2": 0, "half_period": 500, "sum_persist": 1,
                "stuck_persist": 2, "frozen_periods": 2},
               {"T_HOLD_PS": 5000, "T_OUT_PS": 35000}),
    # isolated link: round trip 80 ns > one SCLK period; 8-frame window, longer frame period
    "isolated": ({"sclk_div": 3, "sample_delay": 12, "lead_zeros": 2, "frame_bits": 14, "cal_log2": 2,
                  "cs_quiet": 2, "avg_log2": 3, "half_period": 600, "frame_period": 98, "pcnt_w": 5},
                 {"T_HOLD_PS": 45000, "T_OUT_PS": 80000}),
}

RTL_NAMES = {"adc_bits": "ADC_BITS", "frame_bits": "FRAME_BITS", "lead_zeros": "LEAD_ZEROS", "sclk_div": "SCLK_DIV",
             "sample_delay": "SAMPLE_DELAY", "cs_quiet": "CS_QUIET", "half_period": "HALF_PERIOD",
             "avg_log2": "AVG_LOG2", "frame_period": "FRAME_PERIOD", "cal_log2": "CAL_LOG2", "cur_w": "CUR_W",
             "miss_w": "MISS_W", "offset_reset": "OFFSET_RESET", "pcnt_w": "PCNT_W", "sum_persist": "SUM_PERSIST",
             "stuck_persist": "STUCK_PERSIST", "frozen_periods": "FROZEN_PERIODS"}


@pytest.mark.parametrize("cfg", list(CONFIGS))
def test_adc_spi(cfg):
    from runner import default_sim, run
    if cfg == "isolated" and default_sim() == "verilator":
        pytest.skip("needs the slave's 80 ns output delay; the slave is zero-delay under Verilator (no --timing)")
    rtl, slave = CONFIGS[cfg]
    p = AdcSpiParams(**rtl)
    params = {RTL_NAMES[k]: getattr(p, k) for k in RTL_NAMES}
    params.update(slave)
    env = {"ADC_SPI_PARAMS": json.dumps({"rtl": {k: getattr(p, k) for k in RTL_NAMES}, "slave": slave}),
           "ADC_SPI_PERIODS": {"default": "24", "p2500": "4"}.get(cfg, "12")}
    testcase = "test_reset_schedule,test_random,test_overcurrent" if cfg == "p2500" else None
    run(toplevel="adc_spi_tb", test_module="test_adc_spi", parameters=params, extra_env=env, name=f"adc_spi_{cfg}",
        testcase=testcase)
