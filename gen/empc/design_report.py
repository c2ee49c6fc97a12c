"""`empc check`: the design check of every design of a configuration, at its own Ts and at the
Ts variants of the drive (250 us and 50 us at 20 kHz PWM: issue 16 item 5), optionally with the
five scenarios, into ``build/reports/design_<motor>.json``.

Per design: passed or not and why, worst spectral radius and worst damping with where they
occur (speed, plant corner, gain set, mode frequency), the margins (radius bound, damping
minimum), the nominal radius, the quantisation chatter, the worst polynomial-fit and
quantisation errors (gain element, speed) and the weights (per unit and SI).
"""
from __future__ import annotations

import json
import time
from pathlib import Path

from . import config as config_mod, design as design_mod

TS_VARIANTS = (("Ts_250us", {"control.Ts": 250e-6, "inverter.f_pwm": 20000.0}),
               ("Ts_50us", {"control.Ts": 50e-6, "inverter.f_pwm": 20000.0}))


def _worst_fit(rep: dict) -> dict:
    best = {"fit_rel": 0.0}
    for q in rep["quantisation"]:
        if not q["unused"] and q["fit_rel"] >= best["fit_rel"]:
            best = {"gain": f"{q['gain']}[{q['row']},{q['col']}]", "fit_rel": q["fit_rel"],
                    "omega_e": q["fit_worst_omega"], "fit_du_ticks": q["fit_du_ticks"]}
    return best


def design_summary(cfg, alg: int, task: str) -> dict:
    d = design_mod.design(cfg, alg, task, force=True)
    st, rep = d["stability"], d["report"]
    wpu = cfg.weights_pu(alg, task)
    wsi = cfg.control.weights_for(alg, task)
    return {
        "passed": st["passed"], "reason": st["reason"],
        "worst_radius": st["worst_radius"], "worst_damping": st["worst_damping"],
        "nominal_radius": st["nominal_radius"], "nominal_damping": st["nominal_damping"],
        "radius_bound": st["radius_bound"], "margin": st["margin"], "radius_margin_left": st["radius_margin_left"],
        "damping_min": st["damping_min"], "per_gain_set": st["per_gain_set"],
        "quantisation_noise_rms": st["quantisation_noise_rms"],
        "fit_gate": st["fit_gate"], "fit_worst": _worst_fit(rep),
        "fit_worst_rel": rep["fit_worst_rel"], "fit_worst_du_ticks": rep["fit_worst_du_ticks"],
        "quant_worst_du_ticks": rep["quant_worst_du_ticks"],
        "weights_pu": {"Q_yw": list(wpu.Q_yw), "Q_dy": list(wpu.Q_dy), "Q_du": list(wpu.Q_du),
                       "ebar_step_max": list(wpu.ebar_step_max), "integrate": list(wpu.integrate)},
        "weights_si": {"Q_yw": list(wsi.Q_yw), "Q_dy": list(wsi.Q_dy), "Q_du": list(wsi.Q_du),
                       "ebar_step_max": list(wsi.ebar_step_max)},
    }


def scenario_figures(cfg, fixed: bool = True) -> dict:
    from . import report, scenarios
    out = {}
    for name in ("speed_steps", "speed_alg2", "position_alg1", "position_alg2", "load_step"):
        sc, alg = scenarios.get(name, cfg)
        if (alg, sc.task) not in cfg.control.weights:
            out[name] = {"skipped": f"no weights.alg{alg}.{sc.task} design in the configuration"}
            continue
        r = report.run_scenario(cfg, name, fixed=fixed, out=Path("build/reports") / "motors" /
                                Path(cfg.source).stem)
        out[name] = {k: {m: v.get(m) for m in ("rms_error", "overshoot_pct_max", "settling_time_max",
                                                "unsettled_steps", "ramp_error_mean_abs", "peak_phase_current",
                                                "saturations")}
                     for k, v in r["runs"].items()}
        out[name]["description"] = r["description"]
    return out


def run(path, out_dir: Path = Path("build/reports"), variants: bool = True, scenarios: bool = False,
        overrides: dict | None = None) -> dict:
    t0 = time.perf_counter()
    cfg = config_mod.load(path, overrides)
    stem = Path(cfg.source).stem
    res = {"motor": cfg.motor.name, "config": config_mod.display_path(cfg.source),
           "ratings": {"current_A": cfg.ratings.current, "voltage_V": cfg.ratings.voltage,
                       "speed_rad_s_electrical": cfg.ratings.speed, "position_rad_electrical": cfg.ratings.position,
                       "power_W": cfg.ratings.power, "derived": list(cfg.ratings.derived)},
           "time_constants": {"tau_i_s": cfg.bases("speed").tau_i, "T_m_s": cfg.bases("speed").T_m},
           "i_max_A": cfg.control.i_max, "Udc_V": cfg.inverter.Udc, "J_kg_m2": cfg.motor.J,
           "robustness": {k: getattr(cfg.robustness, k) for k in ("L", "R", "J", "psi", "decay_min", "damping_min",
                                                                   "speed_points", "fit_max")},
           "weight_units": cfg.control.weight_units, "variants": {}}
    runs = [("configured", {})]
    if variants:
        runs += list(TS_VARIANTS)
    for label, ov in runs:
        try:
            c = config_mod.load(path, {**(overrides or {}), **ov})
        except config_mod.ConfigError as e:
            res["variants"][label] = {"error": str(e)}
            continue
        v = {"Ts": c.control.Ts, "f_pwm": c.inverter.f_pwm, "designs": {}}
        for alg, task in sorted(c.control.weights):
            try:
                v["designs"][f"alg{alg}_{task}"] = design_summary(c, alg, task)
            except config_mod.ConfigError as e:
                v["designs"][f"alg{alg}_{task}"] = {"passed": False, "reason": str(e)}
        v["all_passed"] = all(dd["passed"] for dd in v["designs"].values())
        res["variants"][label] = v
    if scenarios:
        res["scenarios"] = scenario_figures(cfg)
    res["wall_s"] = time.perf_counter() - t0
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    (out_dir / f"design_{stem}.json").write_text(json.dumps(res, indent=1, default=float) + "\n")
    return res


def summary_line(res: dict) -> list[str]:
    lines = []
    for label, v in res["variants"].items():
        if "error" in v:
            lines.append(f"{res['motor']} [{label}]: {v['error']}")
            continue
        for name, d in v["designs"].items():
            if "worst_radius" not in d:
                lines.append(f"{res['motor']} [{label}] {name}: FAIL {d['reason']}")
                continue
            wr, wz = d["worst_radius"], d["worst_damping"]
            lines.append(f"{res['motor']} [{label}, Ts {1e6 * v['Ts']:.0f} us] {name}: "
                         f"{'pass' if d['passed'] else 'FAIL'}  radius {wr['value']:.4f} (bound {d['radius_bound']:.5f}; "
                         f"{wr['plant']}, {wr['omega_e']:.0f} rad/s)  damping {wz['value']:.3f} ({wz['plant']}, "
                         f"{wz['omega_e']:.0f} rad/s, {wz['freq_hz']:.0f} Hz)  fit {100 * d['fit_worst'].get('fit_rel', 0):.1f} %"
                         + ("" if d["passed"] else f"  -- {d['reason']}"))
    return lines
