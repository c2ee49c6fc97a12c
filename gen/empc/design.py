"""Gain design: the explicit-MPC gains of a configuration, fitted, checked and quantised.

``design(cfg, algorithm, task)`` returns the coefficient parameters of one
(algorithm, task) with its fit and quantisation report and stability margins;
``check_stability`` is the design check; ``designs_of`` lists what a
configuration asks for.  Writing files is ``roms.py``'s job.
"""
from __future__ import annotations

import numpy as np

from . import config as config_mod, fit as fit_mod, mpc, quantise


class DesignError(config_mod.ConfigError):
    pass


def check_stability(cfg, algorithm: int, task: str, gf=None, points: int = 25) -> dict:
    """Spectral radius of the frozen-speed loop on a grid over Omega_e, exact and fitted gains."""
    c = cfg.control
    grid = np.linspace(c.omega_min, c.omega_max, points)
    worst = {"exact": 0.0, "fitted": 0.0}
    for w in grid:
        rho = mpc.spectral_radius(cfg.motor, c, float(w), algorithm, task)
        worst["exact"] = max(worst["exact"], rho)
        if rho >= 1.0:
            raise DesignError(
                f"algorithm {algorithm} / {task}: closed loop unstable at omega_e={w:.1f} rad/s "
                f"(spectral radius {rho:.4f} >= 1) with weights.alg{algorithm}.{task} = "
                f"{c.weights_for(algorithm, task)}")
        if gf is not None:
            g = gf.evaluate(float(w))
            rho_f = mpc.spectral_radius(cfg.motor, c, float(w), algorithm, task, g=g)
            worst["fitted"] = max(worst["fitted"], rho_f)
            if rho_f >= 1.0:
                raise DesignError(
                    f"algorithm {algorithm} / {task}: loop with the fitted polynomial gains unstable at "
                    f"omega_e={w:.1f} rad/s (spectral radius {rho_f:.4f})")
    worst["grid_points"] = points
    return worst


def design(cfg, algorithm: int, task: str) -> dict:
    ws = quantise.ws_for(cfg)
    gf = fit_mod.fit(cfg, algorithm, task, w_norm=quantise.w_norm_rtl(cfg, ws))
    stab = check_stability(cfg, algorithm, task, gf)
    params, rep, gf = quantise.build(cfg, algorithm, task, gain_fit=gf)
    return {"params": params, "report": rep, "fit": gf, "stability": stab}


def designs_of(cfg, all_designs: bool) -> list[tuple[int, str]]:
    boot = (cfg.control.algorithm, cfg.control.task)
    out = [boot]
    if all_designs:
        out += [k for k in sorted(cfg.control.weights) if k != boot]
    return out
