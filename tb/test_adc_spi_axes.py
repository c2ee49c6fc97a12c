"""cocotb tests of adc_spi with NAXES > 1 (one frame engine, one SCLK / CS, per-axis checks, windows
and sums) against empc.rtlmodel.adc_spi.AdcSpiAxes (one AdcSpiCycle per axis on the shared grid).

Toplevel tb/hdl/adc_spi_axes_tb.v: the master wired pin-to-pin to NAXES adc_spi_slave models (three
ADCs each).  Every clock EVERY output of every axis (codes, flags, window mean, sums, offsets,
calibration, centre check) and the shared ones (cs_n, sclk, busy, fvalid) are compared with the
model fed the same inputs.  Independently of the model each test asserts:
  * windows at the stagger offsets: every `valid` of axis a comes valid_delay() after a centre of
    axis a's own timing plan (its boundary + P), from 2^K window frames accepted at exactly
    window_taus() around that centre; for the default period (P = 2500, NAXES = 4) the window
    frames sit at the cycles of docs/four_axes.md 3.1 (2389.., 3647.., 4905.., 1163..);
  * the re-phase point: every irregular gap between two frame starts ends G0 (or G0 + TF, a
    skipped grid point) after a re-phase cycle ps0 + R + k*2P, R = AdcSpiAxes.rephase (1473 at
    NAXES = 4, P = 2500), and no window frame of any axis straddles it;
  * isolation: a victim axis gets overcurrent frames, frame errors, rails, sum errors, frozen codes,
    bridges toggling, calibration, offset writes, displaced triggers and a sync restart of its own
    carrier; every other axis's outputs are identical, clock by clock, to a run in which the victim
    is quiet (the other axes' stimuli come from their own random streams).
Random codes per channel per frame; the seed is EMPC_SEED (printed).
"""
from __future__ import annotations

import json
import operator
import os
import random

import pytest

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ReadOnly, RisingEdge

from empc.rtlmodel.adc_spi import AdcInputs, AdcSpiAxes, AdcSpiParams

DEFAULT_SEED = 20261127
SHARED = (("cs_n", 1, 0), ("busy", 1, 0), ("fvalid", 1, 0), ("sclk", 1, 0))


def axis_fields(p: AdcSpiParams):
    """(name, width, signed) of one axis's slice of tb/hdl/adc_spi_axes_tb.v's `mon`, LSB first."""
    b, psw = p.adc_bits, p.psw()
    return [("trig_miss", 1, 0), ("miss_cnt", p.miss_w, 0), ("code0", b, 0), ("code1", b, 0), ("code2", b, 0),
            ("frame_err", 1, 0), ("oc", 1, 0), ("oc_ch", 3, 0), ("sum_err", 1, 0), ("stuck", 1, 0),
            ("frozen", 1, 0), ("valid", 1, 0), ("cur0", p.cur_w, 1), ("cur1", p.cur_w, 1), ("cur2", p.cur_w, 1),
            ("sat", 1, 0), ("psum0", psw, 1), ("psum1", psw, 1), ("psum2", psw, 1), ("pcount", p.pcnt_w, 0),
            ("offset0", b, 0), ("offset1", b, 0), ("offset2", b, 0), ("cal_busy", 1, 0), ("cal_done", 1, 0),
            ("refused", 1, 0)]


def _field(v, sh, w, sg):
    x = (v >> sh) & ((1 << w) - 1)
    return x - (1 << w) if sg and x >> (w - 1) else x


class AxBench:
    """Clock loop for NAXES axes.  Timing plan: ``starts`` = [(cycle r, axis, phase)]: from cycle r
    on, axis a's boundaries are r + phase + k*2P and its centres r + phase - P + k*2P (those >= r),
    until the axis's next start; ``trig_moves`` {(axis, centre cycle): new cycle}.  The plan is fixed
    before :meth:`start`.  Codes: ``gen[a](k)`` gives ((c0, c1, c2), (l0, l1, l2)) for frame k of
    axis a (called once per frame, in frame order, after the previous frame was accepted)."""

    def __init__(self, dut, seed_offset: int = 0):
        self.dut = dut
        cfg = json.loads(os.environ["ADC_AXES_PARAMS"])
        self.p = AdcSpiParams(**cfg["rtl"])
        self.n, self.stagger = cfg["naxes"], cfg["stagger"]
        self.seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED)) + seed_offset
        self.m = AdcSpiAxes(self.p, self.n, self.stagger)
        self.afields = axis_fields(self.p)
        self.axw = sum(w for _, w, _ in self.afields)
        self.P2 = 2 * self.p.half_period
        self.ps0 = 7
        self.starts = [(self.ps0, a, a * self.stagger) for a in range(self.n)]
        self.trig_moves = {}
        cm = self.p.code_max
        self.inp = [AdcInputs(oc_thr=cm, sum_thr=cm) for _ in range(self.n)]
        self.once = [dict() for _ in range(self.n)]
        self.gen = [lambda k: ((2048, 2048, 2048), (0, 0, 0)) for _ in range(self.n)]
        self.k = 0
        self.t = 0
        self.cache = {}
        self.n_checked = 0
        self.trace = [[] for _ in range(self.n)]       # per axis: outputs of every cycle (if record)
        self.record = False
        self._dec_last = [None] * self.n                # per axis: (mon slice, its fields, their values)

    # ---------------------------------------------------------------- timing plan
    def make_plan(self, horizon: int):
        P, P2 = self.p.half_period, self.P2
        self.ps_set = [set() for _ in range(self.n)]
        self.trig_set = [set() for _ in range(self.n)]
        self.centres = [set() for _ in range(self.n)]     # nominal centres (window checks)
        for a in range(self.n):
            st = sorted((r, ph) for r, ax, ph in self.starts if ax == a)
            for idx, (r, ph) in enumerate(st):
                end = st[idx + 1][0] if idx + 1 < len(st) else horizon
                c = r + ph - P
                while c - P2 >= r:
                    c -= P2
                while c < end:
                    if c >= r:
                        self.trig_set[a].add(self.trig_moves.get((a, c), c))
                        self.centres[a].add(c)
                    if r <= c + P < end:
                        self.ps_set[a].add(c + P)
                    c += P2

    def next_codes(self):
        for a in range(self.n):
            codes, lead = self.gen[a](self.k)
            self.inp[a].codes = tuple(min(max(int(x), 0), self.p.code_max) for x in codes)
            self.inp[a].lead = tuple(lead)

    # ---------------------------------------------------------------- clock loop
    async def start(self, horizon: int, first: bool = True):
        d = self.dut
        self.make_plan(horizon)
        if first:
            Clock(d.clk, 10, unit="ns", impl="gpi").start()   # C clock: no Python per edge
        else:
            await RisingEdge(d.clk)             # out of the last run's ReadOnly phase
        for s in (d.period_start, d.trig, d.bridges_on, d.off_we, d.off_wdata, d.cal_start, d.refused_clear,
                  d.s_code, d.s_lead):
            s.value = 0
        d.rst.value = 1
        self.cache = {}
        for _ in range(3):
            await RisingEdge(d.clk)
        await ReadOnly()
        self.slave0 = [int(d.g_sl[a].u_slave.proto_err.value) for a in range(self.n)]
        self.first = True
        self.next_codes()

    def _w(self, name, v):
        if self.cache.get(name) != v:
            getattr(self.dut, name).value = v
            self.cache[name] = v

    def _decode_fields(self, v: int, fields):
        d, o = {}, 0
        for name, w, sg in fields:
            d[name] = _field(v, o, w, sg)
            o += w
        return d

    def decode(self, v: int):
        """``mon`` -> (shared fields, [per-axis fields]).  An axis's slice that equals its previous clock's
        gives the previous clock's dict (the same fields from the same bits; the dicts are read only)."""
        shw = sum(w for _, w, _ in SHARED)
        sh = self._decode_fields(v & ((1 << shw) - 1), SHARED)
        axes, m, last = [], (1 << self.axw) - 1, self._dec_last
        for a in range(self.n):
            x = (v >> (shw + a * self.axw)) & m
            if last[a] is None or last[a][0] != x:
                d = self._decode_fields(x, self.afields)
                last[a] = (x, d, tuple(d.values()))
            axes.append(last[a][1])
        return sh, axes

    async def run(self, n: int, hook=None):
        d, p, B, LZ = self.dut, self.p, self.p.adc_bits, self.p.lead_zeros
        mon = d.mon
        akeys = [k for k, _, _ in self.afields]
        exp_vals = operator.itemgetter(*akeys)          # the model's values of the axis fields, in mon's order
        for _ in range(n):
            await RisingEdge(d.clk)
            if self.first:
                d.rst.value = 0
                self.first = False
            c = self.t
            cyc = []
            # the packed input words (sums as before: field a of each), one pass over the axes
            ps = tr = bo = owe = owd = cs = rc = oct_ = sut = sc = sl = 0
            for a in range(self.n):
                i, once = self.inp[a], self.once[a]
                self.once[a] = {}
                x = AdcInputs(period_start=int(c in self.ps_set[a]), trig=int(c in self.trig_set[a]),
                              bridges_on=i.bridges_on, off_we=once.get("off_we", 0),
                              off_wdata=once.get("off_wdata", i.off_wdata), cal_start=once.get("cal_start", 0),
                              refused_clear=once.get("refused_clear", 0), oc_thr=i.oc_thr, sum_thr=i.sum_thr,
                              codes=i.codes, lead=i.lead)
                cyc.append(x)
                ps += x.period_start << a
                tr += x.trig << a
                bo += int(x.bridges_on) << a
                owe += x.off_we << (3 * a)
                owd += x.off_wdata << (B * a)
                cs += x.cal_start << a
                rc += x.refused_clear << a
                oct_ += x.oc_thr << (B * a)
                sut += x.sum_thr << (B * a)
                sc += (x.codes[0] | (x.codes[1] << B) | (x.codes[2] << 2 * B)) << (3 * B * a)
                sl += (x.lead[0] | (x.lead[1] << LZ) | (x.lead[2] << 2 * LZ)) << (3 * LZ * a)
            self._w("period_start", ps)
            self._w("trig", tr)
            self._w("bridges_on", bo)
            self._w("off_we", owe)
            self._w("off_wdata", owd)
            self._w("cal_start", cs)
            self._w("refused_clear", rc)
            self._w("oc_thr", oct_)
            self._w("sum_thr", sut)
            self._w("s_code", sc)
            self._w("s_lead", sl)
            await ReadOnly()
            sh, got = self.decode(int(mon.value))
            exp = self.m.outputs()
            for name, _, _ in SHARED:
                if sh[name] != exp[0][name]:
                    raise AssertionError(f"cycle {c}: shared {name} DUT {sh[name]} != model {exp[0][name]}")
            for a in range(self.n):
                if self._dec_last[a][2] != exp_vals(exp[a]):     # every field of the axis, in one tuple compare
                    e = {k: exp[a][k] for k in got[a]}
                    diff = {k: (got[a][k], e[k]) for k in e if got[a][k] != e[k]}
                    raise AssertionError(f"cycle {c}: axis {a}: DUT != model (field: (dut, model)) {diff}; "
                                         f"inputs {cyc[a]}")
                if self.record:
                    self.trace[a].append(self._dec_last[a][2])
            self.n_checked += 1
            self.m.step(cyc)
            self.t += 1
            if self.m.axes[0].last_accept == c:
                self.k += 1
                self.next_codes()
            if hook is not None:
                hook(self, sh, got)

    # ---------------------------------------------------------------- independent checks
    def check_windows(self, valids, exclude=()):  # exclude: (axis, lo, hi) cycles not checked
        """Every valid of axis a: the 2^K window frames before it are at window_taus() about a centre
        of axis a's plan, and valid comes valid_delay() after that centre.  Returns windows checked."""
        p = self.p
        n = 0
        for a in range(self.n):
            win = [f.a for f in self.m.axes[a].frames if f.win]
            for v in valids[a]:
                if any(ax == a and lo <= v <= hi for ax, lo, hi in exclude):
                    continue
                last = [x for x in win if x < v][-p.n_window:]
                cen = v - p.valid_delay()
                assert cen in self.centres[a], (a, v, cen)
                assert [x - cen for x in last] == p.window_taus(), (a, v, last, cen)
                n += 1
        return n

    def check_rephase(self, t_lo, t_hi):
        """Irregular frame gaps only right after a re-phase cycle (axis 0's plan without restarts in
        [t_lo, t_hi)); no window frame of any axis on both sides of one."""
        p, m = self.p, self.m
        starts = [f.a for f in m.axes[0].frames if t_lo <= f.a < t_hi]
        rp = [b + m.rephase for b in sorted(self.ps_set[0]) if t_lo <= b + m.rephase < t_hi]
        n_irr = 0
        for x, y in zip(starts, starts[1:]):
            if y - x == p.tf:
                continue
            n_irr += 1
            ok = [r for r in rp if x < r <= y and y - r - m.g0 in (0, p.tf)]
            assert ok, f"irregular frame gap {x} -> {y} not at a re-phase point {rp}"
        for a in range(self.n):
            fr = [f for f in m.axes[a].frames if f.win and t_lo <= f.a < t_hi]
            for i, f in enumerate(fr):
                if f.first and len(fr[i:i + p.n_window]) == p.n_window and fr[i + p.n_window - 1].last:
                    w = [x.a for x in fr[i:i + p.n_window]]      # a complete window
                    assert not any(w[0] < r <= w[-1] for r in rp), f"axis {a}: window {w} across a re-phase {rp}"
        return len(rp), n_irr

    def check_slaves(self):
        for a in range(self.n):
            assert int(self.dut.g_sl[a].u_slave.proto_err.value) == self.slave0[a], f"slave {a}: SPI protocol error"


def rand_code(rng, p, near=None, spread=8):
    if near is None:
        return rng.randrange(1 << p.adc_bits)
    return min(max(near + rng.randint(-spread, spread), 0), p.code_max)


# ----------------------------------------------------------------------------- tests
@cocotb.test()
async def test_random_axes(dut):
    """Random codes per channel and axis, per-axis offsets, thresholds, bridges, CPU writes,
    calibration, displaced triggers and single-axis restarts; one common restart (a grid jump);
    every output of every axis bit-exact every clock; windows at the stagger offsets; re-phase."""
    b = AxBench(dut)
    p, n = b.p, b.n
    rng = random.Random(b.seed)
    dut._log.info("NAXES %d, stagger %d, params %s, seed %d (EMPC_SEED); rephase R = %d, G0 %d, window frames "
                  "(axis 0's period) %s", n, b.stagger, p, b.seed, b.m.rephase, b.m.g0,
                  [b.m.window_frames(a) for a in range(n)])
    P2 = b.P2
    n_per = int(os.environ.get("ADC_AXES_PERIODS", "16"))
    horizon = b.ps0 + n_per * P2 + 50
    # timing plan: single-axis restarts on axes >= 1 (axis 0 anchors the grid), one common restart
    # in the second half, a few displaced triggers
    r_common = b.ps0 + (n_per * 2 // 3) * P2 + rng.randrange(P2)
    for a in range(n):
        b.starts.append((r_common, a, a * b.stagger))
    single = []
    for _ in range(max(1, n_per // 6)):
        a = rng.randrange(1, n)
        r = b.ps0 + rng.randrange(2 * P2, (n_per * 2 // 3 - 1) * P2)
        b.starts.append((r, a, 0))
        single.append((r, a))
    b.make_plan(horizon)
    for _ in range(max(1, n_per // 4)):
        a = rng.randrange(n)
        c = rng.choice(sorted(b.centres[a]))
        b.trig_moves[(a, c)] = c + rng.choice([-1, 1, -p.tf, 3])
    rngs = [random.Random(b.seed * 7 + a) for a in range(n)]
    mode = [0] * n
    base = [[r.randrange(1 << p.adc_bits) for _ in range(3)] for r in rngs]

    def mkgen(a):
        r = rngs[a]

        def gen(k):
            md = mode[a]
            if md == 0:
                return [rand_code(r, p) for _ in range(3)], (0, 0, 0)
            if md == 1:
                return [rand_code(r, p, b.m.axes[a].offsets[i], 300) for i in range(3)], (0, 0, 0)
            return [base[a][i] + r.randint(-2, 2) for i in range(3)], \
                ((r.randrange(1 << p.lead_zeros), 0, 0) if r.random() < 0.01 else (0, 0, 0))
        return gen
    b.gen = [mkgen(a) for a in range(n)]
    await b.start(horizon)
    valids = [[] for _ in range(n)]
    stats = dict(writes=0, cal=0)

    def hook(bb, sh, out):
        for a in range(n):
            r = rngs[a]
            m = bb.m.axes[a]
            if out[a]["valid"]:
                valids[a].append(bb.t - 1)
            if r.random() < 0.002:
                mode[a] = r.randrange(3)
            if r.random() < 0.002:
                bb.inp[a].bridges_on = int(not bb.inp[a].bridges_on)
            if r.random() < 0.003:
                bb.once[a] = dict(off_we=1 << r.randrange(3), off_wdata=rand_code(r, p, 2048, 200))
                stats["writes"] += 1
            if r.random() < 0.0003:
                bb.once[a] = dict(cal_start=1)
                stats["cal"] += 1
            if r.random() < 0.003:
                diffs = [abs(x - o) for x, o in zip(m.code, m.offsets)]
                bb.inp[a].oc_thr = max(0, min(p.code_max, r.choice(diffs) + r.randint(-2, 2)))
            if r.random() < 0.003:
                s = abs(sum(x - o for x, o in zip(m.code, m.offsets)))
                bb.inp[a].sum_thr = max(0, min(p.code_max, s + r.randint(-3, 3)))
            if r.random() < 0.0003:
                bb.once[a] = dict(refused_clear=1)
    await b.run(horizon, hook=hook)
    b.check_slaves()
    ms = b.m.axes
    n_oc = [sum(any(e["oc_ch"]) for e in m.events) for m in ms]
    miss = [m.miss_cnt for m in ms]
    # windows: all valids (those whose window a restart cut give no valid at all)
    # (an axis restarted alone is out of phase with the grid until the common restart: its windows stay
    # on the grid, its trigs miss; not checked there)
    nw = b.check_windows(valids, exclude=[(a, r, r_common + P2) for r, a in single])
    assert all(len(v) >= n_per // 2 for v in valids), [len(v) for v in valids]
    # re-phase: periods before the first restart of axis 0's plan (single restarts do not move the grid)
    nr, nirr = b.check_rephase(b.ps0 + P2, r_common)
    assert nr >= n_per // 2 and nirr >= nr - 1, (nr, nirr)
    moved = {a for (a, c), c2 in b.trig_moves.items() if c2 < horizon - 10}
    assert all(x > 0 for x in n_oc) and all(miss[a] > 0 for a in moved) and moved, (n_oc, miss, moved)
    dut._log.info("random: %d frames x %d axes x 3 channels, overcurrent frames %s, valids %s (all %d windows "
                  "at window_taus() about the axis's own centre, valid %d clk after it), miss_cnt %s "
                  "(%d single-axis restarts, 1 common at %d, %d displaced trigs), %d re-phase points (R = %d) "
                  "with %d irregular gaps, all right after one; %d offset writes, %d calibrations; "
                  "%d cycles bit-exact (every output of every axis)", len(ms[0].frames), n, n_oc,
                  [len(v) for v in valids], nw, p.valid_delay(), miss, len(single), r_common, len(b.trig_moves),
                  nr, b.m.rephase, nirr, stats["writes"], stats["cal"], b.n_checked)
    want = os.environ.get("ADC_AXES_WINDOW_TABLE")
    if want:
        got = [b.m.window_frames(a) for a in range(n)]
        assert got == json.loads(want), (got, want)
        assert b.m.rephase == int(os.environ["ADC_AXES_REPHASE"])
        # and the frames the RTL marked as window frames, in axis 0's period
        for a in range(n):
            wf = sorted({(f.a - b.ps0) % P2 for f in ms[a].frames if f.win and b.ps0 + P2 <= f.a < r_common})
            assert wf == sorted(got[a]), (a, wf, got[a])
        dut._log.info("default period: window frames per axis %s (axis 0's period), re-phase at %d", got,
                      b.m.rephase)


async def _iso_run(dut, victim: int, faults: bool, first: bool, n_per: int):
    b = AxBench(dut, seed_offset=1)
    p, n, P2 = b.p, b.n, b.P2
    horizon = b.ps0 + n_per * P2 + 50
    vr = random.Random(b.seed * 13 + 99)
    if faults:
        b.starts.append((b.ps0 + (n_per // 2) * P2 + vr.randrange(P2), victim, 0))   # victim's carrier restarted
    b.make_plan(horizon)
    if faults:
        for c in sorted(b.centres[victim])[2:n_per:3]:
            b.trig_moves[(victim, c)] = c + vr.choice([-1, 1, -p.tf])
        b.make_plan(horizon)
    rngs = [random.Random(b.seed * 7 + a) for a in range(n)]
    m_ = p.code_max
    plan = {}                                   # victim's fault frames: k -> (codes, lead)
    if faults:
        k = 20
        n_fr = n_per * P2 // p.tf
        kinds = [0, 1, 2, 3]
        while k < n_fr // 2:
            if not kinds:                       # every kind once per round, in random order
                kinds = [0, 1, 2, 3]
            kind = kinds.pop(vr.randrange(len(kinds)))
            if kind == 0:                       # overcurrent frame (offset 2048, thr 500)
                plan[k] = ((2048 + vr.choice([-1, 1]) * 900, 2048, 2048), (0, 0, 0))
            elif kind == 1:                     # frame error
                plan[k] = ((2048, 2048, 2048), (0, 1, 0))
            elif kind == 2:                     # stuck at a rail, 6 frames
                for j in range(6):
                    plan[k + j] = ((2048, 0, 2048), (0, 0, 0))
            else:                               # sum error, 6 frames
                for j in range(6):
                    plan[k + j] = ((2048 + 400, 2048 + 100, 2048), (0, 0, 0))
            k += vr.randrange(4, 12) + 6
        for j in range(k, n_fr + 10):           # then frozen: identical frames to the end
            plan[j] = ((2050, 2047, 2049), (0, 0, 0))

    def mkgen(a):
        r = rngs[a]

        def gen(k):
            cs = [rand_code(r, p, 2048, 40) for _ in range(3)]
            if a == victim:
                if not faults:                  # healthy: noise about the offsets (not frozen)
                    return [rand_code(vr, p, 2048, 40) for _ in range(3)], (0, 0, 0)
                return plan.get(k, (cs, (0, 0, 0)))
            return cs, (0, 0, 0)
        return gen
    b.gen = [mkgen(a) for a in range(n)]
    for a in range(n):
        b.inp[a].oc_thr = 500
        b.inp[a].sum_thr = 300
        b.inp[a].bridges_on = 1
    await b.start(horizon, first=first)
    b.record = True
    seen = dict(oc=0, frame_err=0, stuck=0, sum_err=0, frozen=0, trig_miss=0)

    def hook(bb, sh, out):
        for a in range(n):
            r = rngs[a]
            if a != victim:                      # the others: their own events, the same in both runs
                if r.random() < 0.001:
                    bb.once[a] = dict(off_we=1 << r.randrange(3), off_wdata=rand_code(r, p, 2048, 3))
                continue
            for k in seen:
                seen[k] += out[a][k]
            if faults:
                if bb.t < horizon // 3 and vr.random() < 0.001:
                    bb.inp[a].bridges_on = int(not bb.inp[a].bridges_on)
                elif bb.t >= horizon // 3:
                    bb.inp[a].bridges_on = 1
                if vr.random() < 0.0005:
                    bb.once[a] = dict(cal_start=1)
                if vr.random() < 0.001:
                    bb.once[a] = dict(off_we=1 << vr.randrange(3), off_wdata=rand_code(vr, p, 2048, 5))
                if vr.random() < 0.0005:
                    bb.inp[a].oc_thr = vr.choice([500, 300, m_])
    await b.run(horizon, hook=hook)
    b.check_slaves()
    return b, seen


@cocotb.test()
async def test_isolation(dut):
    """A victim axis with every fault the block detects, its own bridges / calibration / offset
    writes, displaced triggers and a restart of its carrier: every other axis's outputs are
    identical clock by clock to a run with the victim quiet (both runs also bit-exact vs the model)."""
    cfg = json.loads(os.environ["ADC_AXES_PARAMS"])
    n = cfg["naxes"]
    victim = n // 2
    n_per = int(os.environ.get("ADC_AXES_ISO_PERIODS", "16"))
    b1, seen1 = await _iso_run(dut, victim, True, True, n_per)
    b2, seen2 = await _iso_run(dut, victim, False, False, n_per)
    assert all(seen1[k] > 0 for k in seen1), seen1
    assert seen2["oc"] == seen2["frame_err"] == seen2["stuck"] == seen2["sum_err"] == seen2["frozen"] == 0, seen2
    n_cmp = 0
    for a in range(n):
        if a == victim:
            continue
        t1, t2 = b1.trace[a], b2.trace[a]
        assert len(t1) == len(t2) > 0
        for c, (x, y) in enumerate(zip(t1, t2)):
            assert x == y, f"axis {a} differs at cycle {c} when axis {victim} is faulted: {x} vs {y}"
        n_cmp += len(t1)
        assert sum(1 for x in t1 if x[11]) >= n_per - 2, f"axis {a}: too few valids"   # field 11 = valid
    b1.dut._log.info("isolation: victim axis %d events %s (quiet run: %s); axes %s identical in %d axis-cycles "
                     "(%d cycles per run, both runs bit-exact vs the model)", victim, seen1, seen2,
                     [a for a in range(n) if a != victim], n_cmp, b1.n_checked)


# ----------------------------------------------------------------------------- pytest
CONFIGS = {
    # two axes, short period (2P = 800 clk, 10 frames): stagger 370 (5 frames), re-phase at 169
    "n2": (2, {"half_period": 400, "cal_log2": 4}, {"T_HOLD_PS": 3000, "T_OUT_PS": 15000},
           {"ADC_AXES_PERIODS": "40", "ADC_AXES_ISO_PERIODS": "24"}),
    # four axes, 2P = 2000 clk: stagger 518 (7 frames), re-phase at 753
    "n4": (4, {"half_period": 1000, "cal_log2": 4}, {"T_HOLD_PS": 3000, "T_OUT_PS": 15000}, {}),
    # three axes, single centre sample (K = 0: odd TF = 73), persistence 1 / 2 / 2
    "n3_k0": (3, {"half_period": 600, "cal_log2": 3, "avg_log2": 0, "sum_persist": 1, "stuck_persist": 2,
                  "frozen_periods": 2}, {"T_HOLD_PS": 3000, "T_OUT_PS": 15000}, {}),
    # two axes 2 frames apart (stagger < 2^K frames): the windows overlap, so each axis keeps its own window
    # accumulators (the per-axis window path, not g_wsh); a board might stagger its carriers this little
    "n2_s2": (2, {"half_period": 400, "cal_log2": 4}, {"T_HOLD_PS": 3000, "T_OUT_PS": 15000},
              {"ADC_AXES_PERIODS": "40", "STAGGER_FRAMES": "2"}),
    # four axes at every default (P = 2500, stagger 1258 = `EMPC_PWM_STAGGER_4): docs/four_axes.md 3.1
    "n4_p2500": (4, {}, {"T_HOLD_PS": 3000, "T_OUT_PS": 15000},
                 {"ADC_AXES_PERIODS": "6", "ADC_AXES_REPHASE": "1473",
                  "ADC_AXES_WINDOW_TABLE": json.dumps([[2389, 2463, 2537, 2611], [3647, 3721, 3795, 3869],
                                                       [4905, 4979, 53, 127], [1163, 1237, 1311, 1385]])}),
}

RTL_NAMES = {"adc_bits": "ADC_BITS", "frame_bits": "FRAME_BITS", "lead_zeros": "LEAD_ZEROS", "sclk_div": "SCLK_DIV",
             "sample_delay": "SAMPLE_DELAY", "cs_quiet": "CS_QUIET", "half_period": "HALF_PERIOD",
             "avg_log2": "AVG_LOG2", "frame_period": "FRAME_PERIOD", "cal_log2": "CAL_LOG2", "cur_w": "CUR_W",
             "miss_w": "MISS_W", "offset_reset": "OFFSET_RESET", "pcnt_w": "PCNT_W", "sum_persist": "SUM_PERSIST",
             "stuck_persist": "STUCK_PERSIST", "frozen_periods": "FROZEN_PERIODS"}


def _build_args(cfg):
    from empc.rtlmodel.pwm_center import stagger_step
    n, rtl, slave, env = CONFIGS[cfg]
    p = AdcSpiParams(**rtl)
    env = dict(env)
    frames = env.pop("STAGGER_FRAMES", None)
    stagger = stagger_step(n, p.half_period, p.tf) if frames is None else int(frames) * p.tf
    params = {RTL_NAMES[k]: getattr(p, k) for k in RTL_NAMES}
    params.update(slave, NAXES=n, STAGGER=stagger)
    e = {"ADC_AXES_PARAMS": json.dumps({"rtl": {k: getattr(p, k) for k in RTL_NAMES}, "naxes": n,
                                        "stagger": stagger})}
    e.update(env)
    return params, e


@pytest.mark.parametrize("cfg", list(CONFIGS))
def test_adc_spi_axes(cfg):
    from runner import run
    params, env = _build_args(cfg)
    testcase = "test_random_axes" if cfg == "n4_p2500" else None
    run(toplevel="adc_spi_axes_tb", test_module="test_adc_spi_axes", parameters=params, extra_env=env,
        name=f"adc_spi_axes_{cfg}", testcase=testcase)


MUTANTS = {
    # every axis takes axis 0's window (grid indices): wrong-axis window
    "window": ("            localparam integer MN   = M0 + (ax * STAGGER) / TF;\n",
               "            localparam integer MN   = M0;\n"),
    # the next axis's overcurrent ORed into every axis's flag: a shared fault flag
    "shared_oc": ("                    r_oc        <= st_a & (|oc_now);\n",
                  "                    r_oc        <= st_a & ((|oc_now) | (|g_ax[(ax + 1) % NAXES].oc_now));\n"),
}


@pytest.mark.parametrize("mutant", list(MUTANTS))
def test_adc_spi_axes_mutant(mutant, tmp_path):
    """The tests must fail on a wrong-axis window and on a shared overcurrent flag (config n2)."""
    import runner
    from files import ROOT, rtl_sources
    good, bad = MUTANTS[mutant]
    src = (ROOT / "rtl" / "adc_spi.v").read_text()
    assert src.count(good) == 1, "the mutant no longer matches rtl/adc_spi.v"
    mut = tmp_path / "adc_spi.v"
    mut.write_text(src.replace(good, bad))
    params, env = _build_args("n2")
    orig = runner.rtl_sources
    runner.rtl_sources = lambda: [mut if p.name == "adc_spi.v" else p for p in rtl_sources()]
    try:
        with pytest.raises((AssertionError, SystemExit)):  # cocotb's runner exits on a failed test
            runner.run(toplevel="adc_spi_axes_tb", test_module="test_adc_spi_axes", parameters=params,
                       extra_env=env, name=f"adc_spi_axes_mutant_{mutant}",
                       testcase="test_isolation" if mutant == "shared_oc" else "test_random_axes")
    finally:
        runner.rtl_sources = orig
    # it failed for the right reason: a mismatch against the model (or between the isolation runs)
    res = max((runner.BUILD / "sim").glob(f"adc_spi_axes_mutant_{mutant}_adc_spi_axes_tb_*/results.xml"),
              key=lambda f: f.stat().st_mtime).read_text()
    assert "DUT != model" in res or "differs at cycle" in res, res[-2000:]
