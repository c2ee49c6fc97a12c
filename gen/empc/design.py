"""Gain design: the explicit-MPC gains of a configuration, fitted, checked and quantised.

``design(cfg, algorithm, task)`` returns the coefficient parameters of one
(algorithm, task) with its fit and quantisation report and its robustness report;
``check_stability`` is the design check (robust.py: the loop as built over the
robustness box and Omega_e, with the exact and the fitted/quantised gains, plus the
fit-quality gate); ``designs_of`` lists what a configuration asks for.  Writing files
is ``roms.py``'s job.
"""
from __future__ import annotations

import numpy as np

from . import config as config_mod, fit as fit_mod, loop as loop_mod, mpc, quantise, robust


class DesignError(config_mod.ConfigError):
    pass


def _name(algorithm: int, task: str) -> str:
    return f"weights.alg{algorithm}.{task}"


def _blame(cfg, algorithm: int, task: str, worst: robust.Worst, exact: dict, applied: dict) -> tuple[str, float]:
    """The gain element whose applied (fitted/quantised) value, put back to the exact one, improves
    the failing loop most: (name, improved radius)."""
    m = robust.perturbed(cfg.motor, worst.point)
    best = ("", np.inf)
    for n, K in applied.items():
        if n not in exact:
            continue
        for i in range(K.shape[0]):
            for j in range(K.shape[1]):
                if K[i, j] == exact[n][i, j]:
                    continue
                g = {k: v.copy() for k, v in applied.items()}
                g[n][i, j] = exact[n][i, j]
                r, _ = loop_mod.radius(loop_mod.loop(cfg, m, worst.omega, algorithm, task, g))
                if r < best[1]:
                    best = (f"{n}[{i},{j}]", r)
    return best


def fit_gate(cfg, rep: dict) -> tuple[bool, str, dict]:
    """Fit fidelity (a warning, not a refusal: the refusal is the loop check with the fitted and
    quantised gains, which is the bound that keeps the loop inside its margin): the relative fit
    error (of the gain's peak over Omega_e) of every gain element that matters (its error moves u
    by more than 1 % of the voltage limit at the operand's range) within ``robustness.fit_max``.
    Returns (passed, reason, worst)."""
    u_ticks = cfg.u_max / cfg.volts_per_tick
    worst = {"gain": None, "fit_rel": 0.0, "fit_du_pct_of_umax": 0.0}
    for q in rep["quantisation"]:
        if q["unused"]:
            continue
        du_pct = 100.0 * q["fit_du_ticks"] / u_ticks
        if du_pct < 1.0:
            continue
        if q["fit_rel"] > worst["fit_rel"]:
            worst = {"gain": f"{q['gain']}[{q['row']},{q['col']}]", "fit_rel": q["fit_rel"],
                     "fit_du_pct_of_umax": du_pct, "omega_e": q.get("fit_worst_omega")}
    lim = cfg.robustness.fit_max
    if worst["gain"] and worst["fit_rel"] > lim:
        at = f" at omega_e = {worst['omega_e']:.0f} rad/s" if worst.get("omega_e") is not None else ""
        return False, (f"polynomial fit of {worst['gain']} is off by {100 * worst['fit_rel']:.0f} % of its peak{at} "
                       f"(robustness.fit_max = {100 * lim:.0f} %; the loop check with the fitted gains passes): "
                       f"narrowing Omega_e (control.omega_min/omega_max) improves it"), worst
    return True, "ok", worst


def check_stability(cfg, algorithm: int, task: str, gf=None, params=None, points: int | None = None) -> dict:
    """The design check: robust.survey over the box and Omega_e with the exact gains and, if given,
    the fitted (``gf``) and the quantised (``params``) gains; the verdict against the margins.

    Returns a report dict (``passed``, ``reason``, worst radius / damping and where, margins)."""
    cfg = cfg.for_design(algorithm, task)
    c = cfg.control
    rob = cfg.robustness
    sets = {"exact": robust.exact_gains(cfg, algorithm, task)}
    if gf is not None:
        sets["fitted"] = lambda w: gf.evaluate(float(w))
    if params is not None:
        sets["quantised"] = lambda w: quantise.gains_si(cfg, params, float(w))
    grid = robust.speeds(cfg, points or rob.speed_points)
    res = robust.survey(cfg, algorithm, task, sets, grid=grid)
    passed, reason = robust.verdict(cfg, res)
    wr, wz = res["worst_radius"], res["worst_damping"]
    blame = None
    if not passed and wr.gains != "exact":
        exact_only = robust.survey(cfg, algorithm, task, {"exact": sets["exact"]}, grid=grid)
        if robust.verdict(cfg, exact_only)[0]:
            w = wr if wr.value > robust.radius_bound(cfg) else wz
            blame = _blame(cfg, algorithm, task, w, sets["exact"](w.omega), sets[w.gains](w.omega))
            reason += (f"; the exact gains pass: the fit/quantisation of {blame[0]} at omega_e = {w.omega:.0f} rad/s "
                       f"moves the loop out (radius {blame[1]:.4f} with it exact)")
    noise = {}
    for w in (0.0, max(abs(c.omega_min), abs(c.omega_max))):
        if c.omega_min <= w <= c.omega_max:
            noise[f"{w:.0f}"] = robust.noise_rms(cfg, algorithm, task, sets["exact"](w), w)
    return {
        "passed": passed, "reason": reason,
        "design": f"algorithm {algorithm} / {task} ({_name(algorithm, task)})",
        "worst_radius": wr.as_dict(), "worst_damping": wz.as_dict(),
        "nominal_radius": res["nominal_radius"], "nominal_damping": res["nominal_damping"],
        "per_gain_set": {k: v.as_dict() for k, v in res["per_gain_set"].items()},
        "radius_bound": robust.radius_bound(cfg), "margin": 1.0 - robust.radius_bound(cfg),
        "radius_margin_left": robust.radius_bound(cfg) - wr.value,
        "damping_min": rob.damping_min, "decay_min": robust.decay_min(cfg),
        "box": {k: getattr(rob, k) for k in robust.FACTORS}, "box_points": res["box_points"],
        "speeds": res["speeds"], "estimator": loop_mod.estimator_for(cfg).name,
        "quantisation_noise_rms": noise, "blame": blame,
        # loaded operating points (robust.survey): the law's steady state i_d0 per A of load current
        "load": {"i_q0": res["load_current"], "worst_id_per_iq": res["worst_load_id"].value,
                 "where": res["worst_load_id"].as_dict(), "load_id_max": rob.load_id_max},
        # older manifest keys
        "exact": res["per_gain_set"]["exact"].value,
        "fitted": res["per_gain_set"].get("fitted", res["per_gain_set"]["exact"]).value,
        "grid_points": res["speeds"],
    }


_CACHE: dict = {}


def design(cfg, algorithm: int, task: str, force: bool = False) -> dict:
    """Fit, quantise and check one design.  Raises :class:`DesignError` (one line: the design, the
    failing criterion, speed, plant corner and value) unless ``force``; the report is under
    ``stability`` (``passed`` False when forced through)."""
    cfg = cfg.for_design(algorithm, task)
    key = (repr(cfg.motor), repr(cfg.inverter), repr(cfg.sensors), cfg.f_clk, repr(cfg.control),
           repr(cfg.ratings), repr(cfg.robustness), algorithm, task)
    if key not in _CACHE:
        ws = quantise.ws_for(cfg)
        gf = fit_mod.fit(cfg, algorithm, task, w_norm=quantise.w_norm_rtl(cfg, ws))
        try:
            params, rep, gf = quantise.build(cfg, algorithm, task, gain_fit=gf)
        except quantise.QuantisationError as e:
            raise DesignError(f"algorithm {algorithm} / {task} ({_name(algorithm, task)}) cannot be quantised: {e}; "
                              f"change {_name(algorithm, task)} or sensors.adc_amps_per_lsb / "
                              f"sensors.encoder_cpr") from None
        stab = check_stability(cfg, algorithm, task, gf, params)
        ok, why, worst = fit_gate(cfg, rep)
        stab["fit_gate"] = {"passed": ok, "warning": None if ok else why, "worst": worst,
                            "fit_max": cfg.robustness.fit_max}
        _CACHE[key] = {"params": params, "report": rep, "fit": gf, "stability": stab}
    d = _CACHE[key]
    if not d["stability"]["passed"] and not force:
        raise DesignError(f"{d['stability']['design']} fails the design check: {d['stability']['reason']} "
                          f"(empc roms --force writes it anyway)")
    return d


def designs_of(cfg, all_designs: bool) -> list[tuple[int, str]]:
    boot = (cfg.control.algorithm, cfg.control.task)
    out = [boot]
    if all_designs:
        out += [k for k in sorted(cfg.control.weights) if k != boot]
    return out
