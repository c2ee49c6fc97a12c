#!/usr/bin/env python3
"""Study (issue 15): conditional integration of algorithm 2's task-output error, load_speed at corner_a.

The rated-current load step of ``load_speed`` is a disturbance the reference governor does not see; at
corner_a (psi -20 %) the algorithm-2 speed loop's integral action overshoots the load current 1.65-1.8 x
(docs/design.md "Current limit at the box corners").  The prototype here is the standard conditional
integration of a drive's speed controller: the task output's increment of eq. 25 (speed or angle,
ebar[2]) is not added in a control period where the measured |i_q| > ``thr`` x i_max and the increment
has the sign of i_q (it would drive |i_q| further); the clamped increment is used otherwise, so the
loop stays offset-free for every load below thr x i_max.  The current increments (not integrated in the
bundled designs) are untouched.

NOT in the model nor in the RTL: the study installs it around the existing code for the time of a run,

  * float: ExplicitMPC.ebar_increment (the hook is the identity in the model);
  * fixed and bit: the core model's inputs, w_k[2] := y[2] (the increment is then 0, every other
    word unchanged) in mpc_core.update as FixedMPC and the sequencer model (ctrl_seq, bitloop) call it,
    i.e. what the sequencer would write into the core's input buffer (IN_WREF + 2); the RTL would need a
    condition the 36-bit microword has no code for (``cond`` is full) or a freeze input of the core's
    EBA item (rtl/mpc_operand.v), a threshold word and a status counter: not done.

    PYTHONPATH=$PWD/gen .venv/bin/python flow/antiwindup.py [--thr 0.8] [--cases motor:scenario:plant,...]
        [--forms float,fixed,bit] [--offsets] [--sweep] [--json build/reports/antiwindup.json (default)]

``--cases`` (default: the load_speed / corner_a xfails and the EC 45 flat's corner_b ones) prints the
peak |i| / i_max with and without the prototype and the number of periods it held the integral;
``--offsets`` test_alg2_load's load_speed metric (speed offset under the rated load / rated speed, i_d
mean / I_rated, peak) for the four algorithm-2 speed designs at nominal and corner_a; ``--sweep`` every
scenario of every motor at its own Ts, three plants, the given forms (only the runs where it acted
differ from the model's).
"""
from __future__ import annotations

import argparse
import contextlib
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
    """Install the prototype for runs of ``cfg`` in the designs of ``tasks`` (thr <= 0: the model as it is)."""
    i_max = cfg.control.i_max
    thr_raw = int(round(thr * i_max / cfg.amps_per_lsb)) << F.I_FRAC       # i_q in ADC LSB Q.4
    orig_inc, orig_update = ExplicitMPC.ebar_increment, mpc_core.update

    def ebar_increment(self, inc, meas):
        if self.task in tasks and thr > 0 and abs(meas.i_q) > thr * i_max and inc[2] * meas.i_q > 0:
            HELD["n"] += 1
            inc = inc.copy()
            inc[2] = 0.0
        return inc

    def update(p, x):
        iq = x.y[1]
        if p.algorithm == 2 and p.task in tasks and thr > 0 and abs(iq) > thr_raw and (x.wref[0][2] - x.y[2]) * iq > 0:
            HELD["n"] += 1
            w0 = x.wref[0]
            x = mpc_core.Inputs(y=x.y, omega=x.omega, dx=x.dx, wref=((w0[0], w0[1], x.y[2]),) + tuple(x.wref[1:]),
                                u_prev=x.u_prev, ebar_prev=x.ebar_prev, fw_thr=x.fw_thr)
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
    ap.add_argument("--thr", default="0.8", help="thresholds x i_max, comma separated (0: the model)")
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
