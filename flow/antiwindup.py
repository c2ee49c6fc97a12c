#!/usr/bin/env python3
"""Study (issue 15): anti-windup of algorithm 2's speed integral, load_speed at corner_a.

The rated-current load step of ``load_speed`` is a disturbance the reference governor does not see; at
corner_a (psi -20 %) the algorithm-2 speed loop's integral action overshot the load current 1.65-1.8 x
(docs/design.md "Current limit at the box corners").  The model and the RTL now hold the speed error's
increment of eq. 25 (ebar[2], speed task) in a control period where |i_q| >= hold_current x i_max (the
governor's hold current, register IQ_HOLD) and the increment has the sign of i_q (it would drive |i_q|
further): the standard conditional integration of a drive's speed controller, offset-free for every
load below hold_current x i_max (rtlmodel/mpc_core.update step 2, rtl/mpc_operand.v, ExplicitMPC).

This script measures it against other thresholds ``--thr`` (x i_max; 0 = no hold, the model before) and
the position task (``--tasks speed,position``: the angle error held the same way, through the core's
inputs, w_k[2] := y[2]), installed around the models for the time of a run (ExplicitMPC.ebar_increment,
mpc_core.update as FixedMPC and the sequencer model, ctrl_seq / bitloop, call it):

    PYTHONPATH=$PWD/gen .venv/bin/python flow/antiwindup.py [--thr 0.7] [--cases motor:scenario:plant,...]
        [--forms float,fixed,bit] [--tasks speed] [--offsets] [--sweep] [--json build/reports/antiwindup.json]

``--cases`` (default: the load_speed / corner_a cases and the EC 45 flat's corner_b ones) prints the
peak |i| / i_max without the hold (thr 0) and with each thr, and the number of periods it held;
``--offsets`` test_alg2_load's load_speed metric (speed offset under the rated load in % of the rated
speed, i_d and i_q means / I_rated, peak) for the four algorithm-2 speed designs at nominal and corner_a;
``--sweep`` every scenario of every motor at its own Ts, three plants, the given forms.
"""
from __future__ import annotations

import argparse
import contextlib
import dataclasses
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from files import REPORTS, ROOT  # noqa: E402

sys.path.insert(0, str(ROOT / "gen"))
from empc import corners  # noqa: E402
from empc import formats as F  # noqa: E402
from empc.controllers.explicit import ExplicitMPC  # noqa: E402
from empc.rtlmodel import mpc_core  # noqa: E402

CASES = ("ipmsm_001:load_speed:corner_a", "blwr233d:load_speed:corner_a",
         "ec45flat_24v:load_speed:corner_b", "ec45flat_24v:speed_alg2:corner_b")
HELD = {"n": 0}          # periods the prototype held the integral (what a status counter would count)


@contextlib.contextmanager
def conditional_integration(cfg, thr: float, tasks=("speed",)):
    """Runs of ``cfg`` with the hold at ``thr`` x i_max in the designs of ``tasks`` (thr = 0: no hold, the
    model before issue 15's anti-windup; the model: thr = governor.hold_current, speed task)."""
    i_max = cfg.control.i_max
    thr_raw = int(round(thr * i_max / cfg.amps_per_lsb))       # as governor.hold_current_raw (IQ_HOLD)
    orig_inc, orig_update = ExplicitMPC.ebar_increment, mpc_core.update

    def ebar_increment(self, inc, meas):
        if self.task in tasks and thr > 0 and abs(meas.i_q) >= thr * i_max and (inc[2] < 0) == (meas.i_q < 0):
            HELD["n"] += 1
            inc = inc.copy()
            inc[2] = 0.0
        return inc

    def update(p, x):
        iq = x.y[1]
        aw = mpc_core.aw_bits(iq, thr_raw)
        held = (p.algorithm == 2 and p.task in tasks and bool(aw & 1)
                and ((x.wref[0][2] - x.y[2]) < 0) == (iq < 0))
        HELD["n"] += int(held)
        if p.task == "position":
            # the model holds the speed task only: the angle error through the inputs, w_k[2] := y[2]
            x = dataclasses.replace(x, aw=0)
            if held:
                w0 = x.wref[0]
                x = dataclasses.replace(x, wref=((w0[0], w0[1], x.y[2]),) + tuple(x.wref[1:]))
        else:
            x = dataclasses.replace(x, aw=aw if p.task in tasks else 0)
        return orig_update(p, x)

    ExplicitMPC.ebar_increment = ebar_increment
    mpc_core.update = update
    try:
        yield
    finally:
        ExplicitMPC.ebar_increment, mpc_core.update = orig_inc, orig_update


def measure(motor, scen, plant, form, thr, duration=1.0, tasks=("speed",)) -> dict:
    cfg = corners.load(motor)
    HELD["n"] = 0
    with conditional_integration(cfg, thr, tasks):
        r = corners.measure(cfg, scen, plant, form, duration=duration)
    return {"motor": motor, "scenario": scen, "plant": plant, "form": form, "thr": thr,
            "peak": round(r["peak"], 4), "t": round(r["t"], 5), "held": HELD["n"]}


def offsets(motor, plant, form, thr) -> dict:
    """test_alg2_load.test_alg2_load_speed_offsets's metric on load_speed (window 0.18-0.25 s)."""
    cfg = corners.load(motor)
    HELD["n"] = 0
    with conditional_integration(cfg, thr):
        sc, c, tr, _ = corners.simulate(cfg, "load_speed", plant, form)
    s = (tr.t >= 0.18) & (tr.t < 0.25)
    I, w_b = c.ratings.current, c.ratings.speed
    return {"motor": motor, "plant": plant, "form": form, "thr": thr,
            "speed_offset_pct": round(100 * float(np.mean(tr.w_e[s] - tr.ref[s, 2])) / w_b, 4),
            "i_d_mean_pu": round(float(np.mean(tr.i_d[s])) / I, 4), "i_q_mean_pu": round(float(np.mean(tr.i_q[s])) / I, 4),
            "peak": round(float(np.max(tr.i_phase_peak)) / c.control.i_max, 4), "held": HELD["n"]}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--thr", default="0.7", help="thresholds x i_max, comma separated (0: no hold)")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--forms", default="float,fixed,bit")
    ap.add_argument("--tasks", default="speed", help="designs with the prototype: speed (default), position")
    ap.add_argument("--offsets", action="store_true")
    ap.add_argument("--sweep", action="store_true")
    ap.add_argument("--json", type=Path, default=REPORTS / "antiwindup.json")
    a = ap.parse_args(argv)
    thrs = [float(t) for t in a.thr.split(",")]
    forms = a.forms.split(",")
    out = {"command": "flow/antiwindup.py " + " ".join(argv if argv is not None else sys.argv[1:]),
           "cases": [], "offsets": [], "sweep": []}
    t0 = time.process_time()
    if a.sweep:
        for m in corners.MOTORS:
            for scen, alg, task in corners.scenario_list(corners.load(m)):
                for plant in corners.PLANTS:
                    for form in forms:
                        for thr in thrs:
                            r = measure(m, scen, plant, form, thr, tasks=tuple(a.tasks.split(",")))
                            out["sweep"].append(r)
                            print(*r.values(), flush=True)
    elif a.offsets:
        for m in ("blwr233d", "premo_320v", "ec45flat_24v", "ipmsm_001"):
            for plant in ("nominal", "corner_a"):
                for form in forms:
                    for thr in [0.0] + [t for t in thrs if t > 0]:
                        r = offsets(m, plant, form, thr)
                        out["offsets"].append(r)
                        print(*r.values(), flush=True)
    else:
        for case in a.cases.split(","):
            m, scen, plant = case.split(":")
            for form in forms:
                for thr in [0.0] + [t for t in thrs if t > 0]:
                    r = measure(m, scen, plant, form, thr, tasks=tuple(a.tasks.split(",")))
                    out["cases"].append(r)
                    print(*r.values(), flush=True)
    out["cpu_s"] = round(time.process_time() - t0, 1)
    if a.json:
        a.json.parent.mkdir(parents=True, exist_ok=True)
        a.json.write_text(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
