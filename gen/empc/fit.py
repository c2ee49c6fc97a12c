"""Gain profiles over Omega_e and their 2nd-order polynomial fits (paper 000 eqs. 29-31).

Every gain element k_ij(w) is sampled on a grid over Omega_e and fitted by
least squares (numpy.polyfit, eq. 31) in the normalised speed s = w / w_norm, so
k_ij(w) ~= p0 + s (p1 + p2 s).  The fit-error report gives per gain the maximum
absolute error and the error relative to the gain's peak magnitude over Omega_e.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import mpc


@dataclass
class GainFit:
    algorithm: int
    task: str
    N: int
    omega_grid: np.ndarray
    w_norm: float                      # scheduling variable s = w / w_norm
    order: int
    profiles: dict = field(default_factory=dict)   # name -> (n_grid, rows, cols)
    coeffs: dict = field(default_factory=dict)     # name -> (order+1, rows, cols), ascending powers of s
    report: dict = field(default_factory=dict)

    @property
    def names(self) -> tuple:
        return mpc.GAIN_NAMES[self.algorithm]

    @property
    def n_polynomials(self) -> int:
        return sum(int(np.prod(self.coeffs[n].shape[1:])) for n in self.names)

    @property
    def n_coefficients(self) -> int:
        return self.n_polynomials * (self.order + 1)

    def evaluate(self, omega: float, clamp: bool = True) -> dict:
        """Fitted gains at ``omega`` (clamped to Omega_e: the polynomials are never extrapolated)."""
        if clamp:
            omega = float(np.clip(omega, self.omega_grid[0], self.omega_grid[-1]))
        s = omega / self.w_norm
        out = {}
        for n in self.names:
            c = self.coeffs[n]
            acc = c[-1]
            for k in range(c.shape[0] - 2, -1, -1):
                acc = c[k] + s * acc
            out[n] = acc
        return out


def w_norm_for(omega_min: float, omega_max: float) -> float:
    return max(abs(omega_min), abs(omega_max))


def profiles(cfg, algorithm: int | None = None, task: str | None = None, grid: np.ndarray | None = None) -> tuple[np.ndarray, dict]:
    c = cfg.control
    grid = grid if grid is not None else np.linspace(c.omega_min, c.omega_max, c.omega_points)
    prof = {}
    for w in grid:
        g = mpc.gains(cfg.motor, c, float(w), algorithm, task)
        for n, k in g.items():
            prof.setdefault(n, []).append(k)
    return grid, {n: np.array(v) for n, v in prof.items()}


def fit(cfg, algorithm: int | None = None, task: str | None = None, order: int = 2,
        w_norm: float | None = None) -> GainFit:
    c = cfg.control
    algorithm = algorithm or c.algorithm
    task = task or c.task
    grid, prof = profiles(cfg, algorithm, task)
    w_norm = w_norm or w_norm_for(c.omega_min, c.omega_max)
    s = grid / w_norm
    gf = GainFit(algorithm, task, c.N, grid, w_norm, order, profiles=prof)
    for n, k in prof.items():
        flat = k.reshape(len(grid), -1)
        p = np.polynomial.polynomial.polyfit(s, flat, order)      # (order+1, rows*cols), ascending
        gf.coeffs[n] = p.reshape((order + 1,) + k.shape[1:])
    gf.report = fit_report(gf)
    return gf


def fit_report(gf: GainFit) -> dict:
    """Per gain element: max |fit - exact| over Omega_e, and relative to max |exact|."""
    rep = {}
    fitted = [gf.evaluate(float(w), clamp=False) for w in gf.omega_grid]
    worst_rel = 0.0
    for n in gf.names:
        exact = gf.profiles[n]
        approx = np.array([f[n] for f in fitted])
        err = np.abs(approx - exact).max(axis=0)
        peak = np.abs(exact).max(axis=0)
        rel = np.where(peak > 0, err / np.where(peak > 0, peak, 1), 0.0)
        rep[n] = {"max_abs": err.tolist(), "max_rel": rel.tolist(), "peak": peak.tolist()}
        worst_rel = max(worst_rel, float(rel.max()))
    rep["worst_rel"] = worst_rel
    return rep
