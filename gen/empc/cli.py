"""`empc` command line: roms, tune, gains, fit, simulate, compare (see README)."""
from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

from . import config as config_mod


def _load(args):
    overrides = {}
    for item in getattr(args, "set", None) or []:
        key, sep, val = item.partition("=")
        if not sep or not key:
            raise config_mod.ConfigError(f"--set {item!r}: expected KEY=VALUE (e.g. --set control.Ts=5e-5)")
        overrides[key.strip()] = config_mod.parse_value(val.strip())
    return config_mod.load(args.config, overrides)


def cmd_roms(args) -> int:
    from . import roms
    cfg = _load(args)
    man = roms.generate(cfg, Path(args.out), all_designs=not args.boot_only, force=args.force)
    for name, d in man["designs"].items():
        st = d["stability"]
        if not st["passed"]:
            print(f"empc: warning: {st['design']} fails the design check (written because of --force): "
                  f"{st['reason']}", file=sys.stderr)
        if st.get("fit_gate", {}).get("warning"):
            print(f"empc: warning: {st['design']}: {st['fit_gate']['warning']}", file=sys.stderr)
    print(f"wrote coefficient ROMs, empc_formats.vh, empc_designs.h and manifest.json to {args.out}")
    return 0


def cmd_check(args) -> int:
    from . import design_report
    overrides = {}
    for item in args.set or []:
        key, _, val = item.partition("=")
        overrides[key.strip()] = config_mod.parse_value(val.strip())
    res = design_report.run(args.config, Path(args.out), variants=not args.no_variants, scenarios=args.scenarios,
                            overrides=overrides or None)
    for line in design_report.summary_line(res):
        print(line)
    stem = Path(res["config"]).stem
    print(f"wrote {args.out}/design_{stem}.json")
    ok = all(v.get("all_passed", False) for v in res["variants"].values())
    return 0 if ok else 2


def cmd_tune(args) -> int:
    from . import tune
    cfg = _load(args)
    specs = tune.Specs.from_args(args)
    designs = [(args.algorithm, args.task)] if args.algorithm and args.task else \
        [k for k in sorted(cfg.control.weights) if (not args.algorithm or k[0] == args.algorithm)
         and (not args.task or k[1] == args.task)]
    results = []
    for alg, task in designs:
        r = tune.tune(cfg, alg, task, specs)
        if args.refine:            # the refined weights when the grid finds none or settle faster
            r2 = tune.refine(cfg, alg, task, specs)
            if r2.passed and (not r.passed or r2.chosen.m["settling"] < r.chosen.m["settling"]):
                r = r2
        results.append(r)
    if args.json:
        print(json.dumps([r.as_dict() for r in results], indent=1))
    else:
        for r in results:
            print(r.explain())
        print(tune.toml_tables(results, ts=cfg.control.Ts if args.ts_table else None))
    return 0 if all(r.passed for r in results) else 2


def _jsonable(g: dict) -> dict:
    return {k: v.tolist() for k, v in g.items()}


def cmd_gains(args) -> int:
    from . import mpc
    cfg = _load(args)
    g = mpc.gains(cfg.motor, cfg.control, args.omega, args.algorithm, args.task)
    if args.json:
        print(json.dumps(_jsonable(g)))
    else:
        import numpy as np
        np.set_printoptions(precision=6, suppress=True, linewidth=160)
        print(f"algorithm {args.algorithm}, task {args.task}, omega_e = {args.omega} rad/s (SI units, paper signs)")
        for k, v in g.items():
            print(f"{k} ({v.shape[0]} x {v.shape[1]}):\n{v}")
    return 0


def cmd_fit(args) -> int:
    from . import design as design_mod
    cfg = _load(args)
    alg = args.algorithm or cfg.control.algorithm
    task = args.task or cfg.control.task
    d = design_mod.design(cfg, alg, task, force=True)
    gf, rep = d["fit"], d["report"]
    out = {"algorithm": alg, "task": task, "N": gf.N, "omega_range": [float(gf.omega_grid[0]), float(gf.omega_grid[-1])],
           "variable": f"s = omega_e / {gf.w_norm:.6g} rad/s; k(s) = p0 + s (p1 + p2 s)",
           "n_polynomials": gf.n_polynomials, "n_coefficients": gf.n_coefficients,
           "coefficients": {n: gf.coeffs[n].tolist() for n in gf.names},
           "fit_error": gf.report, "stability": d["stability"],
           "quantisation": {"worst_du_ticks": rep["quant_worst_du_ticks"], "worst_rel_of_peak": rep["quant_worst_rel_of_peak"]}}
    if args.json:
        print(json.dumps(out))
        return 0
    print(f"algorithm {alg}, task {task}, N = {gf.N}: {gf.n_polynomials} polynomials, {gf.n_coefficients} coefficients")
    print(out["variable"])
    for n in gf.names:
        c = gf.coeffs[n]
        r = gf.report[n]
        for i in range(c.shape[1]):
            for j in range(c.shape[2]):
                print(f"  {n}[{i},{j}]  p0={c[0, i, j]: .6e} p1={c[1, i, j]: .6e} p2={c[2, i, j]: .6e}"
                      f"  fit err max {r['max_abs'][i][j]:.3e} ({100 * r['max_rel'][i][j]:.2f} % of peak {r['peak'][i][j]:.3e})")
    print(f"worst relative fit error {100 * gf.report['worst_rel']:.2f} %; spectral radius exact {d['stability']['exact']:.5f}, "
          f"fitted {d['stability']['fitted']:.5f}")
    return 0


def cmd_simulate(args) -> int:
    from . import report
    cfg = _load(args)
    res = report.run_scenario(cfg, args.scenario, fixed=args.fixed, out=Path(args.out))
    print(json.dumps({k: {m: v[m] for m in ("rms_error", "overshoot_pct_max", "settling_time_max",
                                             "ramp_error_mean_abs", "peak_phase_current", "saturations",
                                             "sim_ms_per_wall_s")}
                      for k, v in res["runs"].items()}, indent=1))
    print(f"wrote {args.out}/sim_{args.scenario}.{{json,csv,png}}")
    return 0


def cmd_compare(args) -> int:
    from .papers import compare
    rep = compare.run(quick=args.quick, out=Path(args.out), only=args.only or None)
    print(f"wrote {args.out}/compare.json, compare.md and {len(rep['cases'])} plots in {rep['wall_s']:.0f} s")
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="empc", description=__doc__)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("roms", help="write coefficient ROMs, Verilog header and manifest")
    r.add_argument("--config", help="TOML configuration (default: BLWR233D, paper 000)")
    r.add_argument("--out", required=True)
    r.add_argument("--force", action="store_true",
                   help="write designs that fail the robust design check (with a warning)")
    r.set_defaults(func=cmd_roms)
    g = sub.add_parser("gains", help="explicit MPC gains at one electrical speed (SI units)")
    g.add_argument("--algorithm", type=int, choices=(1, 2), required=True)
    g.add_argument("--task", choices=("speed", "position"), required=True)
    g.add_argument("--omega", type=float, required=True, help="electrical speed, rad/s")
    g.add_argument("--config")
    g.add_argument("--json", action="store_true")
    g.set_defaults(func=cmd_gains)
    f = sub.add_parser("fit", help="polynomial gain fit (eq. 29-31) and its error report")
    f.add_argument("--algorithm", type=int, choices=(1, 2))
    f.add_argument("--task", choices=("speed", "position"))
    f.add_argument("--config")
    f.add_argument("--json", action="store_true")
    f.set_defaults(func=cmd_fit)
    s = sub.add_parser("simulate", help="closed-loop scenario: CSV, PNG and build/reports/sim_<scenario>.json")
    s.add_argument("--scenario", required=True)
    s.add_argument("--fixed", action="store_true", help="also run the bit-accurate model of the RTL core")
    s.add_argument("--config")
    s.add_argument("--out", default="build/reports")
    s.set_defaults(func=cmd_simulate)
    r.add_argument("--boot-only", action="store_true", help="only the configuration's own algorithm/task")
    k = sub.add_parser("check", help="design check of every design (configured Ts, 250 us, 50 us): "
                                     "build/reports/design_<motor>.json")
    k.add_argument("--config")
    k.add_argument("--out", default="build/reports")
    k.add_argument("--no-variants", action="store_true", help="only the configured Ts")
    k.add_argument("--scenarios", action="store_true", help="also run the five scenarios (float, exact, fixed)")
    k.set_defaults(func=cmd_check)
    t = sub.add_parser("tune", help="pick per-unit weights that meet specifications; explain which one binds")
    t.add_argument("--config")
    t.add_argument("--algorithm", type=int, choices=(1, 2))
    t.add_argument("--task", choices=("speed", "position"))
    t.add_argument("--settling", type=float, help="task-output step settling time limit, s (default: none)")
    t.add_argument("--current-rise", type=float,
                   help="current-loop settling: i_d step 90 %% rise time limit, s (default 20 Ts)")
    t.add_argument("--overshoot", type=float,
                   help="task step overshoot limit, %% (default 20 for algorithm 1, none for algorithm 2)")
    t.add_argument("--step", type=float, default=0.1,
                   help="task step (per unit of rated speed / position scale) whose peak current must stay "
                        "within control.i_max (default 0.1)")
    t.add_argument("--chatter", type=float, default=0.2,
                   help="RMS i_q from sensor quantisation, per unit of rated current, the worst over the "
                        "robustness box (default 0.2)")
    t.add_argument("--u-chatter", type=float, default=0.5,
                   help="RMS |u| from sensor quantisation, per unit of the voltage limit, the worst over the "
                        "robustness box (default 0.5)")
    t.add_argument("--refine", action="store_true",
                   help="when the two-factor grid finds nothing: search one factor per weight element (and "
                        "algorithm 2's proportional weight Q_yp) until the full design check passes")
    t.add_argument("--ts-table", action="store_true",
                   help="print the weights as control-period tables [weights.<design>.Ts_<us>us] for the "
                        "configured control.Ts (e.g. with --set control.Ts=5e-5)")
    t.add_argument("--json", action="store_true")
    t.set_defaults(func=cmd_tune)
    c = sub.add_parser("compare", help="explicit MPC vs the reference controllers of papers 001/002: compare.{json,md}, plots")
    c.add_argument("--quick", action="store_true", help="short version (the regression runs it)")
    c.add_argument("--out", default="build/reports")
    c.add_argument("--only", nargs="*", help="run only these case keys (e.g. s2_iq_step fw_002)")
    c.set_defaults(func=cmd_compare)
    for p in (r, g, f, s, t, k):
        p.add_argument("--set", action="append", metavar="KEY=VALUE",
                       help="override a configuration value (TOML syntax), e.g. --set control.Ts=5e-5")
    args = ap.parse_args(argv)
    try:
        return args.func(args)
    except (config_mod.ConfigError, ValueError, KeyError) as e:
        msg = e.args[0] if e.args else e
        print(f"empc: error: {str(msg).splitlines()[0] if str(msg) else type(e).__name__}", file=sys.stderr)
        return 2
    except Exception as e:          # no traceback for users; EMPC_DEBUG=1 shows it
        if os.environ.get("EMPC_DEBUG"):
            raise
        print(f"empc: internal error: {type(e).__name__}: {e} (EMPC_DEBUG=1 for the traceback)", file=sys.stderr)
        return 3


if __name__ == "__main__":
    sys.exit(main())
