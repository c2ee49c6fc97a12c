"""Explicit MPC of paper 000 (float): laws (23)-(24) and (25)-(27) with polynomial gains.

``gains="poly"`` evaluates the fitted 2nd-order polynomials (29) (what the FPGA
does), ``gains="exact"`` the exact gains (eqs. 23-28) at each speed, taken from a
dense table over Omega_e (``EXACT_POINTS``) with linear interpolation, whose error
is far below the polynomial fit's (tests check both).
Online stage (sec. V-A): the error increments of (25) are clamped per output
and u is limited to the circle |u| <= Udc/sqrt(3) by vector scaling; u_{k-1}
keeps the limited value (incremental-form anti-windup).

Position task: the law is invariant to a common shift of all angle signals
(sum of the K_WL angle columns = K_y angle column, exactly), so angles are
taken relative to the measured theta_k; this keeps the arithmetic small on a
multi-turn axis and matches the RTL.
"""
from __future__ import annotations

import numpy as np

from .. import fit as fit_mod
from .. import model, mpc
from .base import Controller, limit_circle


class ExplicitMPC(Controller):
    def __init__(self, cfg, algorithm: int | None = None, task: str | None = None,
                 gains: str = "poly", gain_fit: "fit_mod.GainFit | None" = None):
        super().__init__(cfg)
        c = cfg.control
        self.algorithm = algorithm or c.algorithm
        self.task = task or c.task
        self.N = c.N
        self.C = model.output_matrix(self.task)
        self.mode = gains
        self.name = f"explicit-mpc-alg{self.algorithm}-{self.task}-{gains}"
        if gains == "poly":
            self.fit = gain_fit or fit_mod.fit(cfg, self.algorithm, self.task)
        elif gains == "exact":
            self.table = exact_table(cfg, self.algorithm, self.task)
        else:
            raise ValueError(f"gains must be 'poly' or 'exact', got {gains!r}")
        self.ebar_max = self._ebar_clamp()
        self.reset()

    def _ebar_clamp(self) -> np.ndarray:
        c = self.cfg.control
        return mpc.ebar_step_limits(self.cfg, self.task)

    def reset(self) -> None:
        super().reset()
        self.x_prev = None
        self.theta_prev = None
        self.ebar = np.zeros(3)
        self.saturations = 0
        self.last = {}

    def gains_at(self, w: float) -> dict:
        c = self.cfg.control
        w = float(np.clip(w, c.omega_min, c.omega_max))
        if self.mode == "poly":
            return self.fit.evaluate(w)
        grid, tab = self.table
        x = (w - grid[0]) / (grid[1] - grid[0])
        i = min(max(int(x), 0), len(grid) - 2)
        f = x - i
        return {n: (1 - f) * v[i] + f * v[i + 1] for n, v in tab.items()}

    def step(self, meas) -> np.ndarray:
        Ts = self.cfg.control.Ts
        theta = meas.theta_e
        w = 0.0 if self.theta_prev is None else (theta - self.theta_prev) / Ts   # eq. 37
        w += self.cfg.speed_correction * meas.i_q
        self.theta_prev = theta
        x = np.array([meas.i_d, meas.i_q, w, theta, 0.0])
        dx = np.zeros(5) if self.x_prev is None else x - self.x_prev
        self.x_prev = x
        y = self.C @ x
        W = np.array(meas.W, dtype=float)          # (N, 3): w_{k+1..k+N}
        w_k = np.array(meas.w_k, dtype=float)
        if self.task == "position":                # relative angles (exact by invariance)
            W[:, 2] -= y[2]
            w_k = w_k.copy(); w_k[2] -= y[2]
            y = y.copy(); y[2] = 0.0
        g = self.gains_at(w)
        Wv = W.reshape(-1)
        if self.algorithm == 1:
            du = g["K_e"] @ (Wv - np.tile(y, self.N)) - g["K_dx"] @ dx
        else:
            self.ebar = self.ebar + np.clip(w_k - y, -self.ebar_max, self.ebar_max)   # (25), clamped
            du = g["K_ebar"] @ self.ebar + g["K_WL"] @ Wv - g["K_y"] @ y - g["K_dx"] @ dx
        u, sat = limit_circle(self.u_dq + du, self.cfg.u_max)
        self.saturations += int(sat)
        self.u_dq = u
        self.last = {"w_sched": w, "du": du}
        return u


EXACT_POINTS = 1201
_TABLES: dict = {}


def exact_table(cfg, algorithm: int, task: str):
    key = (id(cfg), cfg.motor, cfg.control.Ts, cfg.control.N, cfg.control.omega_min, cfg.control.omega_max,
           algorithm, task, cfg.control.weights_for(algorithm, task))
    if key not in _TABLES:
        grid = np.linspace(cfg.control.omega_min, cfg.control.omega_max, EXACT_POINTS)
        _TABLES[key] = fit_mod.profiles(cfg, algorithm, task, grid=grid)
    return _TABLES[key]
