"""`empc` command line: gains, fit, roms, simulate (see README)."""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from . import config as config_mod


def _load(args):
    return config_mod.load(args.config)


def cmd_roms(args) -> int:
    from . import roms
    cfg = _load(args)
    roms.generate(cfg, Path(args.out), all_designs=not args.boot_only)
    print(f"wrote coefficient ROMs, empc_formats.vh and manifest.json to {args.out}")
    return 0


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
    d = design_mod.design(cfg, alg, task)
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
    c = sub.add_parser("compare", help="explicit MPC vs the reference controllers of papers 001/002: compare.{json,md}, plots")
    c.add_argument("--quick", action="store_true", help="short version (the regression runs it)")
    c.add_argument("--out", default="build/reports")
    c.add_argument("--only", nargs="*", help="run only these case keys (e.g. s2_iq_step fw_002)")
    c.set_defaults(func=cmd_compare)
    args = ap.parse_args(argv)
    try:
        return args.func(args)
    except (config_mod.ConfigError, ValueError, KeyError) as e:
        print(f"empc: error: {e.args[0] if e.args else e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
