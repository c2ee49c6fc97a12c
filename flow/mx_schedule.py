"""Schedule of the four-axis drive's shared control engine (issue 16 items 2, 3; docs/four_axes.md).

A planning model, not the bit-accurate model of the RTL: it places every job of every axis on the
shared units of the planned engine (word ALU, xform, MPC core, the bit-serial reference engine, the
status port) clock by clock and checks, for NAXES = 1..4 and every combination of per-axis control
periods Ts (in PWM periods) and their phases, that

  * no unit is double-booked (the simulator is non-preemptive: a unit runs one segment at a time),
  * every axis loads its compare values at least 2 clocks before its own next PWM boundary
    (pwm_center's rule), i.e. no overrun,
  * the latency from the last ADC bit of the axis's sample to its compare values stays within the
    issue's 300 clocks, and equals the single-axis figure when the carriers are staggered,

and reports, per axis, the sample-to-applied-voltage delays.  Two checks cover all combinations: an
event simulation of every combination of Ts in 1..4 with every phase (1..3 with --quick) plus a random
sample of Ts up to 12, and an interval argument (each axis's work lies in a fixed window after its
own sample; the windows of different axes are disjoint modulo the PWM period), which holds for any Ts.

Every duration is either measured on the RTL (the bit-serial ctrl_seq's timeline, seq_timeline, retired with
ctrl_seq at the mx_seq merge; the xform and mpc_core models, issue 14's adc_spi) or a design figure of docs/four_axes.md (the word-ALU programs below); the table
TIMING says which.

    .venv/bin/python flow/mx_schedule.py [--json build/reports/mx_schedule.json] [--quick]
"""
from __future__ import annotations

import argparse
import heapq
import itertools
import json
import math
import random
import sys
from dataclasses import dataclass, field, replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from files import REPORTS  # noqa: E402

# ---------------------------------------------------------------------------------------------
# Timing (clocks at 100 MHz).  m = measured on main / issue 14's branch, d = design figure.
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Timing:
    half: int = 2500            # m: EMPC_PWM_HALF_PERIOD (20 kHz carrier)
    tf: int = 74                # m: issue 14 adc_spi frame grid (K = 2: shortest even frame period)
    adc_last_bit: int = 177     # m: trig -> last SCLK rising edge of the last window frame (2611 + 66 - 2500)
    adc_valid: int = 195        # m: trig -> window mean valid (adc_spi valid_delay, K = 2)
    win_lo: int = -111          # m: first window frame's CS fall relative to the centre
    win_hi: int = 199           # m: last window frame's serial pass ends (2611 + 68 + 20 - 2500)
    theta_lat: int = 16         # d: trig -> theta of the count at the trigger (shared pos engine, small moves)
    theta_lat_max: int = 134    # d: same, four simultaneous 32-bit jumps (4 x 33 + 2)
    xf_front: int = 23          # m: xform.latency("front")
    xf_mod: int = 84            # m: xform.latency("mod")
    core_base: int = 38         # m: mpc_core.LATENCY_BASE (latency = 38 + ncols)
    alu_lat: int = 4            # d: word ALU: operand RAM read, DSP A/B/C, P, saturate + write
    kshift: int = 31            # d: worst serial right shift of kacc * i_q (KACC.shift 0..31, 1 bit / clock)
    ref_adv: int = 199          # m: ref_gen advance with a segment load (busy), 66 without
    ref_gov: int = 4 * 65       # d: issue 15 governor passes G1..G4 after the head pass (64 + 1 each)
    ref_sync: int = 5 * 65      # m: ref_gen sync, (N + 1) x 65
    stat_words: int = 6 + 15 + 2  # d: status words + word-parallel counter update (15 words, 2 pipeline)
    load_lead: int = 2          # m: pwm_center: cmp_load >= 2 clocks before period_start


TIMING = Timing()
# double update: a second window centred on the PWM boundary needs the boundary mid-grid too, i.e. a
# frame period dividing P: TF = 100 (25 frames per half period; window frames at +-50, +-150)
DUAL_TIMING = replace(TIMING, tf=100, win_lo=-150, win_hi=150 + 68 + 20, adc_last_bit=150 + 66,
                      adc_valid=150 + 84)


# ---------------------------------------------------------------------------------------------
# Word-ALU programs (docs/four_axes.md, section 3.4): (name, deps, kind) with kind "op" (one issue
# slot, result alu_lat later), "wr" (a buffer / state write of a ready value: one issue slot, no
# result), "shift" (the serial shifter: kshift clocks after its operand).  The segment durations
# below come from a list schedule of these tables.
# ---------------------------------------------------------------------------------------------
def trig_program(n: int, task_pos: bool) -> list[tuple]:
    """After the trigger (count and angle at the trigger, registers, references advanced at the
    preceding PWM boundary), before the ADC sample: every core input word that does not depend on
    the currents, and theta_mod for the modulation."""
    prog = [("dpos", (), "op"), ("spd", ("dpos",), "op"), ("dx3", ("dpos",), "op"), ("dx4", (), "wr"),
            ("thm", ("theta",), "op")]
    for m in range(n + 1):
        prog += [(f"idr{m}", (), "wr"), (f"iqr{m}", (), "wr")]
        if task_pos:                                      # w3 = sat32(wrap40((w_hi - pos) << 8) + round(w_lo >> 24))
            prog += [(f"rel{m}", (), "op"), (f"w3_{m}", (f"rel{m}",), "op")]
        else:                                             # w3 = sat32(round(w >> 16))
            prog.append((f"w3_{m}", (), "op"))
    return prog


def dep_program(load_est: bool) -> list[tuple]:
    """After the front (i_d, i_q): the core's ADC-dependent input words, then core start."""
    prog = [("y0", ("front",), "wr"), ("dx0", ("front",), "op"), ("y1", ("front",), "wr"),
            ("dx1", ("front",), "op"), ("kap", ("front",), "op"), ("ka", ("kap",), "shift")]
    if load_est:                                          # issue 15: omega = spd + (ka - D)
        prog += [("u1", ("ka",), "op"), ("om", ("u1",), "op")]
    else:
        prog += [("om", ("ka",), "op")]
    prog += [("omw", ("om",), "wr"), ("y2", ("om",), "wr"), ("dx2", ("om",), "op")]
    return prog


POST_PROGRAM = [("u_prev0", (), "wr"), ("u_prev1", (), "wr"), ("ebar0", (), "wr"), ("ebar1", (), "wr"),
                ("ebar2", (), "wr"), ("u_held", (), "wr"),                   # write-back of the core outputs
                ("t2a", (), "op"), ("t2", ("t2a",), "op"), ("dsh", ("t2",), "shift"), ("d", ("dsh",), "op")]


def alu_span(prog: list[tuple], t: Timing, ready: dict[str, int] | None = None) -> tuple[int, dict[str, int]]:
    """List schedule of a program on the word ALU (one issue per clock, in program order unless an
    operand is not ready: the first ready op issues).  Returns (clocks until the last write lands,
    ready time of every value).  ``ready`` gives external values (front, theta) relative to 0."""
    ready = dict(ready or {})
    todo = list(prog)
    clk, last = 0, 0
    while todo:
        for i, (name, deps, kind) in enumerate(todo):
            if all(ready.get(d, math.inf) <= clk for d in deps):
                break
        else:
            clk = min(max(ready.get(d, math.inf) for d in deps) for _, deps, _ in todo)
            continue
        name, deps, kind = todo.pop(i)
        if kind == "shift":
            ready[name] = clk + 1 + t.kshift
        else:
            ready[name] = clk + (t.alu_lat if kind == "op" else 1)
        last = max(last, ready[name])
        clk += 1
    return last, ready


# ---------------------------------------------------------------------------------------------
# Axis configuration and derived job shape
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class AxisCfg:
    ts: int = 1                 # control period in PWM periods
    phase: int = 0              # control periods at PWM periods k with k % ts == phase
    n: int = 4                  # horizon
    ncols: int = 23             # core columns (alg2 N = 4: 23; alg1: 17; maximum 64)
    task_pos: bool = True
    load_est: bool = True       # issue 15 speed estimate (u1 = ka - D) and governor


@dataclass
class JobShape:
    trig: int                   # ALU clocks of the trigger program (released trig + 1; theta at theta_lat)
    thm: int                    # theta_mod ready, relative to the trigger
    dep_alu: int                # ALU clocks from front done to core start
    core: int
    post_alu: int               # write-back, issue 15 load-estimate update (off the critical path)
    ref: int                    # reference engine: advance (+ governor)


def job_shape(c: AxisCfg, t: Timing) -> JobShape:
    trg, rdy = alu_span(trig_program(c.n, c.task_pos), t, {"theta": t.theta_lat})
    dep, _ = alu_span(dep_program(c.load_est), t, {"front": 0})
    post, _ = alu_span(POST_PROGRAM if c.load_est else POST_PROGRAM[:6], t)
    return JobShape(trig=trg + 1, thm=rdy["thm"] + 1, dep_alu=dep + 1, core=t.core_base + c.ncols,
                    post_alu=post, ref=t.ref_adv + (t.ref_gov if c.load_est else 0))


def stagger(naxes: int, t: Timing, dual: bool = False) -> list[int]:
    """Carrier offsets: axis n is delayed by n x TF x round(S / (NAXES TF)) clocks, S = the spacing of
    one axis's samples (2P; dual: P), a whole number of ADC frames so that one frame grid serves
    every axis's centred window (2P = 5000, TF = 74, NAXES = 4: 17 frames = 1258 clocks)."""
    spacing = t.half if dual else 2 * t.half
    step = t.tf * round(spacing / (naxes * t.tf))
    return [a * step for a in range(naxes)]


# ---------------------------------------------------------------------------------------------
# Event simulation: units, segments (non-preemptive, first come first served per unit, ties by
# deadline)
# ---------------------------------------------------------------------------------------------
UNITS = ("alu", "xf", "core", "ref", "stat")


@dataclass(order=True)
class Seg:
    release: int
    prio: int                   # deadline (earliest first among equal releases)
    seq: int
    axis: int = field(compare=False)
    trig: int = field(compare=False)
    unit: str = field(compare=False)
    dur: int = field(compare=False)
    name: str = field(compare=False)
    after: int = field(compare=False, default=0)              # not before this clock either
    then: list = field(compare=False, default_factory=list)   # [(Seg, offset from this end)]


@dataclass
class Result:
    latency_last_bit: dict      # axis -> max clocks last ADC bit -> cmp_load (control periods)
    latency_trig: dict          # axis -> max clocks trigger -> cmp_load (control periods)
    mod_latency: dict           # axis -> max trigger -> cmp_load in modulation-only periods
    slack: dict                 # axis -> min clocks cmp_load -> boundary - load_lead
    overruns: int
    ref_late: int               # trigger programs that found their references not yet advanced
    busy: dict                  # unit -> busy clocks per PWM period (mean)
    conflicts: int              # segments that had to wait for a unit held by another axis
    spans: dict                 # (axis, unit) -> [(start - trig, end - trig)]
    events: list                # (axis, segment, unit, start, end), absolute clocks


def simulate(cfgs: list[AxisCfg], t: Timing = TIMING, periods: int | None = None, offsets=None,
             sync_axis: int | None = None, dual: bool = False) -> Result:
    """Run ``periods`` PWM periods (default: lcm of the Ts + 2) of every axis.  ``dual``: the
    double-update variant (a sample and a control job at the centre and at the boundary, compare
    values loaded at the next half-period point; Ts counts half periods)."""
    na = len(cfgs)
    offs = offsets if offsets is not None else stagger(na, t, dual)
    T = 2 * t.half
    per = periods or (math.lcm(*[c.ts for c in cfgs]) + 2)
    shapes = [job_shape(c, t) for c in cfgs]
    heap: list[Seg] = []
    seq = itertools.count()
    lat_bit = {a: 0 for a in range(na)}
    lat_trig = {a: 0 for a in range(na)}
    mod_lat = {a: 0 for a in range(na)}
    slack = {a: math.inf for a in range(na)}
    overruns = ref_late = conflicts = 0
    busy = {u: 0 for u in UNITS}
    free = {u: 0 for u in UNITS}
    owner = {u: None for u in UNITS}
    spans: dict = {}
    step = t.half if dual else T                    # sample spacing of one axis
    for k in range(per * (2 if dual else 1)):
        for a, c in enumerate(cfgs):
            trig = offs[a] + t.half + k * step + T     # first sample one period in (the advance before it)
            deadline = trig + t.half - t.load_lead     # next boundary (dual: next half-period point)
            s = shapes[a]
            if (k % c.ts) != c.phase:
                thm = Seg(trig + s.thm, deadline, next(seq), a, trig, "alu", 1, "thm")
                thm.then.append((Seg(0, deadline, next(seq), a, trig, "xf", t.xf_mod + 1, "mod_only"), 0))
                heapq.heappush(heap, thm)
                continue
            radv = s.ref + (t.ref_sync if (sync_axis == a and k == 1) else 0)
            # the references advance at the PWM boundary before the sample (dual: the previous sample)
            ref = Seg(trig - t.half, deadline, next(seq), a, trig, "ref", radv, "ref")
            trg = Seg(trig + 1, deadline, next(seq), a, trig, "alu", s.trig, "trig")
            front = Seg(trig + t.adc_valid + 1, deadline, next(seq), a, trig, "xf", t.xf_front, "front")
            dep = Seg(0, deadline, next(seq), a, trig, "alu", s.dep_alu, "dep")
            core = Seg(0, deadline, next(seq), a, trig, "core", s.core, "core")
            mod = Seg(0, deadline, next(seq), a, trig, "xf", t.xf_mod + 1, "mod", after=trig + s.thm)
            post = Seg(0, deadline + T, next(seq), a, trig, "alu", s.post_alu, "post")
            stat = Seg(0, deadline + T, next(seq), a, trig, "stat", t.stat_words, "stat")
            front.then.append((dep, 0))
            dep.then.append((core, 1))
            core.then += [(mod, 1), (post, 0), (stat, 0)]
            for x in (ref, trg, front):
                heapq.heappush(heap, x)
    ref_end: dict = {}
    events: list = []
    while heap:
        s = heapq.heappop(heap)
        start = max(s.release, s.after, free[s.unit])
        if start > max(s.release, s.after) and owner[s.unit] not in (None, s.axis):
            conflicts += 1
        end = start + s.dur
        free[s.unit], owner[s.unit] = end, s.axis
        busy[s.unit] += s.dur
        spans.setdefault((s.axis, s.unit), []).append((start - s.trig, end - s.trig))
        events.append((s.axis, s.name, s.unit, start, end))
        if s.name == "ref":
            ref_end[(s.axis, s.trig)] = end
        if s.name == "trig" and ref_end.get((s.axis, s.trig), math.inf) > start:
            ref_late += 1
        for nxt, off in s.then:
            nxt.release = end + off
            heapq.heappush(heap, nxt)
        if s.name in ("mod", "mod_only"):
            a = s.axis
            load = end                                       # cmp_load: the clock after xform done
            if load > s.trig + t.half - t.load_lead:
                overruns += 1
            slack[a] = min(slack[a], s.trig + t.half - t.load_lead - load)
            if s.name == "mod":
                lat_bit[a] = max(lat_bit[a], load - (s.trig + t.adc_last_bit))
                lat_trig[a] = max(lat_trig[a], load - s.trig)
            else:
                mod_lat[a] = max(mod_lat[a], load - s.trig)
    return Result(lat_bit, lat_trig, mod_lat, slack, overruns, ref_late,
                  {u: busy[u] / per for u in UNITS}, conflicts, spans, events)


def timeline(cfgs: list[AxisCfg], t: Timing = TIMING) -> list[tuple]:
    """One steady-state PWM period of axis 0 (clock 0 = its boundary, 2P = 5000 clocks): every
    segment of every axis that starts in it, sorted by start (axis, segment, unit, start, end)."""
    T = 2 * t.half
    r = simulate(cfgs, t, periods=4)
    lo = 2 * T                                         # the third period (after the first advances)
    out = [(a, n, u, s - lo, e - lo) for a, n, u, s, e in r.events if lo <= s < lo + T]
    return sorted(out, key=lambda x: x[3])


# ---------------------------------------------------------------------------------------------
# Interval argument: the window of clocks (relative to the axis's own trigger) in which any job of
# the axis can hold any unit; disjoint windows modulo T for all axes => no combination can conflict.
# ---------------------------------------------------------------------------------------------
JOB_TYPES = [AxisCfg(task_pos=tp, ncols=nc, load_est=le) for tp in (False, True) for nc in (17, 23, 64)
             for le in (False, True)]


def unit_spans(t: Timing = TIMING, dual: bool = False) -> dict:
    """Per unit, the clocks relative to an axis's own sample at which any job of that axis (any task,
    core size, speed estimate, control or modulation-only, with or without a reference sync) holds the
    unit, from single-axis runs: [(lo, hi)] merged."""
    out: dict = {}
    for c in JOB_TYPES:
        for ts, sync in ((1, None), (1, 0), (2, None)):
            r = simulate([replace(c, ts=ts)], t, periods=4, offsets=[0], sync_axis=sync, dual=dual)
            for (_, u), sp in r.spans.items():
                out.setdefault(u, []).extend(sp)
    for u, sp in out.items():
        sp.sort()
        merged = [list(sp[0])]
        for lo, hi in sp[1:]:
            if lo <= merged[-1][1]:
                merged[-1][1] = max(merged[-1][1], hi)
            else:
                merged.append([lo, hi])
        out[u] = [tuple(x) for x in merged]
    return out


def windows_disjoint(naxes: int, t: Timing = TIMING, dual: bool = False) -> tuple[bool, dict]:
    """Interval argument for every combination of Ts and phases: shifted by the carrier offsets, the
    per-unit spans of different axes never overlap modulo the sample spacing of the unit's use (one
    PWM period; dual: half a period).  A job of an axis then never waits for another axis's job, so
    its timing is the single-axis timing whatever the other axes do."""
    sp = unit_spans(t, dual)
    offs = stagger(naxes, t, dual)
    period = t.half if dual else 2 * t.half
    gaps = {}
    ok = True
    for u, spans in sp.items():
        worst = math.inf
        for a, b in itertools.combinations(range(naxes), 2):
            d = (offs[b] - offs[a]) % period
            for lo1, hi1 in spans:
                for lo2, hi2 in spans:
                    # axis b's span [lo2, hi2) + d against axis a's [lo1, hi1), modulo the period
                    for shift in (-period, 0, period):
                        lo_b, hi_b = lo2 + d + shift, hi2 + d + shift
                        gap = max(lo_b - hi1, lo1 - hi_b)
                        worst = min(worst, gap)
        gaps[u] = worst if worst != math.inf else None
        if worst != math.inf and worst < 0:
            ok = False
    return ok, {"spans": sp, "min_gap": gaps}


def adc_grid_check(naxes: int, t: Timing = TIMING, dual: bool = False) -> dict:
    """The shared frame grid.  Unwrapped, the sample points (centres; dual: and boundaries) of all axes
    are whole numbers of frames apart, so each is mid-grid when the first is (window frames symmetric
    about every one).  The grid is re-phased once per PWM period (2P = 67 x 74 + 42: one irregular
    gap) at a point R outside every window; with TF dividing 2P (dual: TF = 100) it needs none."""
    T = 2 * t.half
    offs = stagger(naxes, t, dual)
    pts = sorted(o + t.half + s for o in offs for s in ((0, -t.half) if dual else (0,)))
    mid_grid = all((c - pts[0]) % t.tf == 0 for c in pts)
    lo = pts[0] + t.win_lo - t.tf                      # one frame of margin before the first window frame
    hi = pts[-1] + t.win_hi
    periodic = T % t.tf == 0
    return {"offsets": offs, "sample_points": [p % T for p in pts], "mid_grid": mid_grid,
            "grid_periodic": periodic, "windows_span": hi - lo,
            "rephase_ok": periodic or (hi - lo) <= T - 2 * t.tf,
            "rephase_point": None if periodic else hi % T}


def delays(c: AxisCfg, t: Timing, dual: bool = False) -> dict:
    """Sample -> applied voltage (clocks): the compare values load at the next boundary (P after the
    centre sample; dual: P/2 after each sample, at the next half-period point), and the voltage of
    one control decision lasts Ts PWM periods (dual: Ts half periods); centroid = first + span / 2."""
    T = 2 * t.half
    if dual:
        first, span = t.half, c.ts * t.half
    else:
        first, span = t.half, c.ts * T
    return {"first_applied": first, "centroid": first + span // 2,
            "first_us": first / 100, "centroid_us": (first + span / 2) / 100}


# ---------------------------------------------------------------------------------------------
def run_all(quick: bool = False, seed: int = 1) -> dict:
    t = TIMING
    rep: dict = {"timing": t.__dict__, "stagger": {}, "adc_grid": {}, "job_shape": {}, "worst": {}, "sweep": {}}
    for task_pos in (False, True):
        for load in (False, True):
            s = job_shape(AxisCfg(task_pos=task_pos, load_est=load), t)
            rep["job_shape"][f"{'position' if task_pos else 'speed'}{'_load' if load else ''}"] = s.__dict__
    rep["windows"] = {}
    for na in range(1, 5):
        rep["stagger"][na] = stagger(na, t)
        rep["adc_grid"][na] = adc_grid_check(na, t)
        rep["adc_grid"][f"dual_{na}"] = adc_grid_check(na, DUAL_TIMING, dual=True)
        ok, w = windows_disjoint(na, t)
        okd, wd = windows_disjoint(na, DUAL_TIMING, dual=True)
        rep["windows"][na] = {"disjoint": ok, "min_gap": w["min_gap"], "dual_disjoint": okd,
                              "dual_min_gap": wd["min_gap"]}
    rep["unit_spans"] = {u: sp for u, sp in unit_spans(t).items()}
    rep["timeline_4"] = timeline([AxisCfg() for _ in range(4)], t)
    # the single-axis reference figures
    single = simulate([AxisCfg()], t)
    mod_only = simulate([AxisCfg(ts=2)], t)
    rep["single_axis"] = {"latency_last_bit": single.latency_last_bit[0], "latency_trig": single.latency_trig[0],
                          "mod_only": mod_only.mod_latency[0], "slack": single.slack[0]}
    # worst case: every axis a control period every PWM period, per NAXES; largest core (64 columns) too
    for na in range(1, 5):
        for ncols in (23, 64):
            r = simulate([AxisCfg(ncols=ncols) for _ in range(na)], t)
            rep["worst"][f"{na}_ncols{ncols}"] = {
                "latency_last_bit": r.latency_last_bit, "latency_trig": r.latency_trig, "slack": r.slack,
                "overruns": r.overruns, "conflicts": r.conflicts,
                "busy_per_period": {u: round(v) for u, v in r.busy.items()},
                "ref_late": r.ref_late}
    # without staggering (all carriers in phase): what the stagger buys
    r = simulate([AxisCfg() for _ in range(4)], t, offsets=[0, 0, 0, 0])
    rep["no_stagger_4"] = {"latency_last_bit": r.latency_last_bit, "slack": r.slack, "overruns": r.overruns,
                           "conflicts": r.conflicts}
    # a CPU sync of one axis's references on top of the worst case
    r = simulate([AxisCfg() for _ in range(4)], t, sync_axis=2)
    rep["sync_4"] = {"latency_last_bit": r.latency_last_bit, "overruns": r.overruns, "conflicts": r.conflicts,
                     "ref_late": r.ref_late}
    # double update (sample at the centre and the boundary, update at both)
    r = simulate([AxisCfg() for _ in range(4)], DUAL_TIMING, dual=True)
    rep["dual_4"] = {"latency_last_bit": r.latency_last_bit, "slack": r.slack, "overruns": r.overruns,
                     "conflicts": r.conflicts, "ref_late": r.ref_late,
                     "busy_per_period": {u: round(v) for u, v in r.busy.items()}}
    r = simulate([AxisCfg() for _ in range(4)], DUAL_TIMING, dual=True, sync_axis=1)
    rep["dual_sync_4"] = {"latency_last_bit": r.latency_last_bit, "overruns": r.overruns, "conflicts": r.conflicts,
                          "ref_late": r.ref_late}
    # every combination of Ts in 1..TSX with every phase, every NAXES; tasks mixed
    tsx = 3 if quick else 4
    rng = random.Random(seed)
    n_sim = 0
    worst_bit = 0
    worst_over = 0
    worst_conf = 0
    for na in range(1, 5):
        choices = [(ts, ph) for ts in range(1, tsx + 1) for ph in range(ts)]
        for combo in itertools.product(choices, repeat=na):
            cfgs = [AxisCfg(ts=ts, phase=ph, task_pos=bool(i % 2), ncols=(23 if i % 2 else 17))
                    for i, (ts, ph) in enumerate(combo)]
            r = simulate(cfgs, t)
            n_sim += 1
            worst_bit = max([worst_bit] + list(r.latency_last_bit.values()))
            worst_over += r.overruns + r.ref_late
            worst_conf += r.conflicts
    # random longer control periods
    n_rand = 50 if quick else 400
    for _ in range(n_rand):
        na = rng.randint(1, 4)
        cfgs = []
        for i in range(na):
            ts = rng.randint(1, 12)
            cfgs.append(AxisCfg(ts=ts, phase=rng.randrange(ts), task_pos=rng.random() < 0.5,
                                ncols=rng.choice((17, 23, 64)), load_est=rng.random() < 0.5))
        r = simulate(cfgs, t, periods=min(math.lcm(*[c.ts for c in cfgs]) + 2, 200))
        n_sim += 1
        worst_bit = max([worst_bit] + list(r.latency_last_bit.values()))
        worst_over += r.overruns + r.ref_late
        worst_conf += r.conflicts
    rep["sweep"] = {"combinations": n_sim, "ts_exhaustive": tsx, "random": n_rand, "seed": seed,
                    "worst_latency_last_bit": worst_bit, "overruns": worst_over, "conflicts": worst_conf}
    rep["delays"] = {f"ts{ts}": delays(AxisCfg(ts=ts), t) for ts in (1, 2, 5)}
    rep["delays"]["dual_ts1"] = delays(AxisCfg(ts=1), DUAL_TIMING, dual=True)
    return rep


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", default=str(REPORTS / "mx_schedule.json"))
    ap.add_argument("--quick", action="store_true", help="Ts 1..3 exhaustive and 50 random combinations")
    a = ap.parse_args(argv)
    rep = run_all(quick=a.quick)
    Path(a.json).parent.mkdir(parents=True, exist_ok=True)
    Path(a.json).write_text(json.dumps(rep, indent=1, default=str) + "\n")
    print(f"job shapes: {rep['job_shape']}")
    print(f"single axis: {rep['single_axis']}")
    for k, v in rep["worst"].items():
        print(f"worst {k}: {v}")
    print(f"no stagger, 4 axes: {rep['no_stagger_4']}")
    print(f"sync on axis 2, 4 axes: {rep['sync_4']}")
    print(f"double update, 4 axes: {rep['dual_4']}; with a sync: {rep['dual_sync_4']}")
    print(f"sweep: {rep['sweep']}")
    print(f"adc grid: {rep['adc_grid']}")
    print(f"delays: {rep['delays']}")
    bad = rep["sweep"]["overruns"] or rep["sweep"]["conflicts"] or rep["sweep"]["worst_latency_last_bit"] > 300
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
