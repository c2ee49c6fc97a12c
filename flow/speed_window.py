#!/usr/bin/env python3
"""Speed window sweep at Ts = 50 us (issues 15/16): control.speed_window M = 1, 2, 4, 8 per motor and design,
every design at the same M (the Ts_50us tables' own speed_window, e.g. the BLWR233D's M = 8, set aside; the
sweep's tables are the bundled ones, so the BLWR233D's algorithm-2 speed table is the one tuned for M = 8).

Per (motor, design, M): the robust design check (design.check_stability: box, margins, loaded points,
with the window's delay and its quantisation in the loop, estimator.state_space), the linear quantisation
chatter (robust.noise_box at omega 0: worst i_q / |u| RMS over the box, and x u_max), and the closed-loop
step of test_motors.py's 50 us cases (the test's own _step_50us: float = ExplicitMPC, fixed = FixedMPC, the
nominal plant) against the test's bounds (peak, overshoot, settling / half way, u_q tail RMS, fixed-float
agreement).  Writes build/reports/speed_window_50us.json.

    PYTHONPATH=$PWD/gen .venv/bin/python flow/speed_window.py [--motors blwr233d ...] [--windows 1 2 4 8] [--no-steps]
"""
from __future__ import annotations

import argparse
import json
import sys
import time

from files import REPORTS, ROOT

sys.path.insert(0, str(ROOT / "gen" / "tests"))

import numpy as np  # noqa: E402

from empc import corners, design, robust  # noqa: E402

MOTORS = ("blwr233d", "premo_320v", "ec45flat_24v")


def step_case(tm, cfg, key) -> dict:
    """The test's 50 us step, float and fixed, and which of its bounds fail."""
    res = cfg.rad_per_count if key[1] == "position" else cfg.rad_s_per_count_ts
    figs, fails = {}, []
    for fixed in (False, True):
        _, _, fig = tm._step_50us(cfg, key, "nominal", fixed)
        what = "fixed" if fixed else "float"
        figs[what] = {k: (float(v) if v is not None else None) for k, v in fig.items()}
        if not np.isfinite(fig["rms_error"]):
            fails.append(f"{what}: not finite")
        if fig["peak/i_max"] > tm.PEAK_50US:
            fails.append(f"{what}: peak {fig['peak/i_max']:.3f} i_max")
        if fig["overshoot_pct"] > tm.OV_50US:
            fails.append(f"{what}: overshoot {fig['overshoot_pct']:.1f} %")
        if not fig["governed"] and fig["settling_time"] is None:
            fails.append(f"{what}: not settled (final error {100 * fig['final_error/step']:.0f} % of the step)")
        if fig["governed"] and fig["final_error/step"] > 1.0 - 0.5 * fig["reach/step"]:
            fails.append(f"{what}: not half way")
        if fig["u_q_tail_rms/u_max"] > tm.UQ_50US:
            fails.append(f"{what}: u_q tail RMS {fig['u_q_tail_rms/u_max']:.2f} u_max")
    f, x = figs["float"]["rms_error"], figs["fixed"]["rms_error"]
    if not abs(f - x) <= tm.AGREE_50US * f + res:
        fails.append(f"fixed/float RMS error {x:.4g} / {f:.4g}")
    return {"passed": not fails, "fails": fails, **figs}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--motors", nargs="*", default=list(MOTORS))
    ap.add_argument("--windows", nargs="*", type=int, default=[1, 2, 4, 8])
    ap.add_argument("--no-steps", action="store_true")
    ap.add_argument("--out", default=str(REPORTS / "speed_window_50us.json"))
    a = ap.parse_args(argv)
    import test_motors as tm
    out = {"Ts": 50e-6, "f_pwm": corners.TS_PWM, "windows": a.windows, "motors": {},
           "command": "PYTHONPATH=$PWD/gen .venv/bin/python flow/speed_window.py", "bounds": {
               "peak/i_max": tm.PEAK_50US, "overshoot_pct": tm.OV_50US, "u_q_tail_rms/u_max": tm.UQ_50US,
               "agree": tm.AGREE_50US}}
    t0 = time.time()
    for name in a.motors:
        mo = out["motors"][name] = {}
        bundled = corners.load(name, **tm.TS_50US)
        # every design at M (with_control drops the design tables' own speed_window), then as bundled
        for label, cfg in [(f"M{M}", bundled.with_control(speed_window=M)) for M in a.windows] + [("bundled", bundled)]:
            row = mo[label] = {"designs": {}}
            for key in sorted(cfg.control.weights):
                d = f"alg{key[0]}.{key[1]}"
                M = cfg.control.window_of(*key)
                st = design.design(cfg, *key, force=True)["stability"]
                g = robust.exact_gains(cfg, *key)(0.0)
                nb = robust.noise_box(cfg, *key, g, 0.0)
                r = {"check_passed": st["passed"], "reason": st["reason"],
                     "worst_radius": st["worst_radius"]["value"], "radius_bound": st["radius_bound"],
                     "worst_damping": st["worst_damping"]["value"],
                     "noise_u_rms/u_max": nb["u_rms"] / cfg.u_max, "noise_i_q_rms/i_max": nb["i_q_rms"] / cfg.control.i_max,
                     "noise_u_rms_nominal/u_max": nb["u_rms_nominal"] / cfg.u_max, "speed_window": M,
                     "rad_s_per_count": cfg.rad_s_per_count_ts / M}
                if not a.no_steps:
                    r["step"] = step_case(tm, cfg, key)
                row["designs"][d] = r
                print(name, label, f"M={M}", d, "check", st["passed"], f"radius {r['worst_radius']:.5f}",
                      f"damping {r['worst_damping']:.3f}", f"noise u {r['noise_u_rms/u_max']:.2f} u_max",
                      "step", (r["step"]["passed"], r["step"]["fails"]) if "step" in r else "-",
                      f"{time.time() - t0:.0f} s", flush=True)
            ds = row["designs"].values()
            row["check_pass"] = f"{sum(d['check_passed'] for d in ds)}/{len(ds)}"
            row["step_pass"] = (f"{sum(d['step']['passed'] for d in ds)}/{len(ds)}" if not a.no_steps else None)
            row["both_pass"] = (f"{sum(d['check_passed'] and d['step']['passed'] for d in ds)}/{len(ds)}"
                                if not a.no_steps else None)
    out["wall_s"] = time.time() - t0
    from pathlib import Path
    p = Path(a.out)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(json.dumps(out, indent=1) + "\n")
    print("wrote", p)
    return 0


if __name__ == "__main__":
    sys.exit(main())
