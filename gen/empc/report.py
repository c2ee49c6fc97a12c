"""Scenario runs -> CSV, PNG plots and JSON reports under build/reports/."""
from __future__ import annotations

import csv
import json
import time
from pathlib import Path

import numpy as np

from . import closedloop as cl
from . import scenarios as scen
from .controllers.explicit import ExplicitMPC
from .controllers.fixed import FixedMPC

REPORTS = Path("build/reports")


def run_scenario(cfg, name: str, fixed: bool = False, out: Path = REPORTS) -> dict:
    sc, alg = scen.get(name, cfg)
    cfg = cfg.with_control(algorithm=alg, task=sc.task)
    runs = {"float": ExplicitMPC(cfg, gains="poly"), "exact": ExplicitMPC(cfg, gains="exact")}
    if fixed:
        runs["fixed"] = FixedMPC(cfg)
    traces, result = {}, {"scenario": name, "description": sc.description, "algorithm": alg, "task": sc.task,
                          "duration_s": sc.duration, "Ts": cfg.control.Ts, "config": cfg.source, "runs": {}}
    for key, ctl in runs.items():
        t0 = time.perf_counter()
        tr = cl.simulate(cfg, ctl, sc)
        wall = time.perf_counter() - t0
        traces[key] = tr
        m = cl.metrics(tr, sc, settle_floor=_band(cfg, sc), preview=cfg.control.N * cfg.control.Ts)
        m["wall_s"] = wall
        m["sim_ms_per_wall_s"] = sc.duration * 1e3 / wall
        if key == "fixed":
            m["saturation_counts"] = ctl.flag_counts
        result["runs"][key] = m
    y = {k: tr.output(sc.task) for k, tr in traces.items()}
    result["fit_effect"] = _diff(traces["float"], traces["exact"], sc.task)
    if fixed:
        result["fixed_vs_float"] = _diff(traces["fixed"], traces["float"], sc.task)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    write_csv(traces, out / f"sim_{name}.csv")
    plot(traces, sc, out / f"sim_{name}.png", cfg)
    (out / f"sim_{name}.json").write_text(json.dumps(result, indent=1) + "\n")
    return result


def _band(cfg, sc) -> float:
    """Settling-band floor: the sensor resolution (1 count per Ts of speed, 4 counts of angle)."""
    return cfg.rad_s_per_count_ts if sc.task == "speed" else 4 * cfg.rad_per_count


def _diff(a: cl.Trace, b: cl.Trace, task: str) -> dict:
    ya, yb = a.output(task), b.output(task)
    return {"output_max_abs": float(np.max(np.abs(ya - yb))), "output_rms": float(np.sqrt(np.mean((ya - yb) ** 2))),
            "i_q_max_abs": float(np.max(np.abs(a.i_q - b.i_q))), "i_q_rms": float(np.sqrt(np.mean((a.i_q - b.i_q) ** 2))),
            "i_d_max_abs": float(np.max(np.abs(a.i_d - b.i_d)))}


def write_csv(traces: dict, path: Path) -> None:
    keys = list(traces)
    t = traces[keys[0]].t
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        cols = ["t", "ref_i_d", "ref_i_q", "ref_3"]
        for k in keys:
            cols += [f"{k}_{n}" for n in ("i_d", "i_q", "w_e", "theta_e", "u_d", "u_q")]
        w.writerow(cols)
        ref = traces[keys[0]].ref
        for n in range(len(t)):
            row = [f"{t[n]:.6f}", f"{ref[n, 0]:.6g}", f"{ref[n, 1]:.6g}", f"{ref[n, 2]:.6g}"]
            for k in keys:
                tr = traces[k]
                row += [f"{v:.6g}" for v in (tr.i_d[n], tr.i_q[n], tr.w_e[n], tr.theta_e[n], tr.u_d[n], tr.u_q[n])]
            w.writerow(row)


def plot(traces: dict, sc, path: Path, cfg) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 3, figsize=(15, 7), sharex=True)
    label3 = "w_e [rad/s]" if sc.task == "speed" else "theta_e [rad]"
    first = next(iter(traces.values()))
    ax[0, 0].plot(first.t, first.ref[:, 2], "k--", lw=1, label="reference")
    for k, tr in traces.items():
        y = tr.output(sc.task)
        ax[0, 0].plot(tr.t, y, lw=1, label=k)
        ax[1, 0].plot(tr.t, tr.ref[:, 2] - y, lw=1, label=k)
        ax[0, 1].plot(tr.t, tr.i_d, lw=1, label=f"{k} i_d")
        ax[1, 1].plot(tr.t, tr.i_q, lw=1, label=f"{k} i_q")
        ax[0, 2].plot(tr.t, tr.u_d, lw=1, label=f"{k} u_d")
        ax[1, 2].plot(tr.t, tr.u_q, lw=1, label=f"{k} u_q")
    ax[0, 0].set_ylabel(label3)
    ax[1, 0].set_ylabel("error e_3")
    ax[0, 1].set_ylabel("i_d [A]")
    ax[1, 1].set_ylabel("i_q [A]")
    ax[0, 2].set_ylabel("u_d [V]")
    ax[1, 2].set_ylabel("u_q [V]")
    for a in ax.flat:
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7)
    for a in ax[1]:
        a.set_xlabel("t [s]")
    fig.suptitle(f"{sc.name}: {sc.description}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
