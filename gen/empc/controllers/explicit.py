"""Explicit MPC of paper 000 (float): laws (23)-(24) and (25)-(27) with polynomial gains.

``gains="poly"`` evaluates the fitted 2nd-order polynomials (29) (what the FPGA
does), ``gains="exact"`` the exact gains (eqs. 23-28) at each speed, taken from a
dense table over Omega_e (``EXACT_POINTS``) with linear interpolation, whose error
is far below the polynomial fit's (tests check both).
Online stage (sec. V-A): the error increments of (25) are clamped per output
and u is limited to the circle |u| <= Udc/sqrt(3) by vector scaling; u_{k-1}
keeps the limited value (incremental-form anti-windup); the speed task's speed increment is held while
|i_q| is at the governor's hold current and it would drive |i_q| further (``ebar_increment``, issue 15).

Position task: the law is invariant to a common shift of all angle signals
(sum of the K_WL angle columns = K_y angle column, exactly), so angles are
taken relative to the measured theta_k; this keeps the arithmetic small on a
multi-turn axis and matches the RTL.

Around the law, as in the RTL (issue 15): the speed estimate of ``control.speed_estimate``
(estimator.py), the reference governor on the task reference (governor.py: the current
limit; ``hold`` after a period with |i_q| above the hold current or the voltage limit
active) and field weakening, a d-current reference from the voltage margin:
i_fw moves by about fw.step x i_max per period (2^FW_SHIFT Q.4 ADC LSB, as the RTL's
counter) toward about -fw.i_max_frac x i_max while the last |u_raw| > fw.u_hi x u_max,
back toward 0 while it is < fw.u_lo x u_max, and is added to the i_d references.
"""
from __future__ import annotations

import numpy as np

from .. import estimator as est_mod
from .. import fit as fit_mod
from .. import governor as gov_mod
from .. import header, model, mpc
from .base import Controller, limit_circle


class ExplicitMPC(Controller):
    def __init__(self, cfg, algorithm: int | None = None, task: str | None = None,
                 gains: str = "poly", gain_fit: "fit_mod.GainFit | None" = None):
        cfg = cfg.for_design(algorithm or cfg.control.algorithm, task or cfg.control.task)   # its speed window
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
        self.estimator = est_mod.SpeedEstimator(cfg)
        self.fw_step, self.fw_max = header.field_weakening_si(cfg)     # the RTL's counter steps
        self.refpath = gov_mod.ReferencePath(cfg, self.task)
        self.reset()

    def _ebar_clamp(self) -> np.ndarray:
        c = self.cfg.control
        return mpc.ebar_step_limits(self.cfg, self.task)

    def reset(self) -> None:
        super().reset()
        self.x_prev = None
        self.ebar = np.zeros(3)
        self.saturations = 0
        self.last = {}
        self.estimator.reset()
        self.refpath.reset()
        self.hold = False
        self.i_fw = 0.0
        self.u_raw_mag = 0.0
        self.gov_clamps = 0
        self.aw_holds = 0

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

    def ebar_increment(self, inc: np.ndarray, meas) -> np.ndarray:
        """The clamped increments of eq. 25 as added to ebar.  Anti-windup of the speed integral (issue 15,
        as the RTL core, rtlmodel/mpc_core.update step 2): in the speed task the speed increment is 0 while
        |i_q| >= hold_current x i_max (the governor's hold current, register IQ_HOLD; off with the governor)
        and it has the sign of i_q (it would drive |i_q| further).  flow/antiwindup.py studies it."""
        g = self.cfg.control.governor
        if (self.task == "speed" and g.enable and abs(meas.i_q) >= g.hold_current * self.cfg.control.i_max
                and (inc[2] < 0) == (meas.i_q < 0)):
            self.aw_holds += 1
            inc = inc.copy()
            inc[2] = 0.0
        return inc

    def references(self, meas) -> tuple[np.ndarray, np.ndarray]:
        """w_k and W = w_{k+1..k+N} after the governor (task output) and field weakening (i_d)."""
        c = self.cfg.control
        W = np.array(meas.W, dtype=float)          # (N, 3): w_{k+1..k+N}
        w_k = np.array(meas.w_k, dtype=float)
        g0, gW = self.refpath.window(w_k[2], list(W[:, 2]), self.hold)
        self.gov_clamps = self.refpath.clamps
        w_k[2], W[:, 2] = g0, gW
        fw = c.field_weakening
        if fw.enable:
            if self.u_raw_mag > fw.u_hi * self.cfg.u_max:
                self.i_fw -= self.fw_step
            elif self.u_raw_mag < fw.u_lo * self.cfg.u_max:
                self.i_fw += self.fw_step
            self.i_fw = min(max(self.i_fw, -self.fw_max), 0.0)
        w_k[0] += self.i_fw
        W[:, 0] += self.i_fw
        return w_k, W

    def step(self, meas) -> np.ndarray:
        theta = meas.theta_e
        w = self.estimator.step(theta, meas.i_q)
        x = np.array([meas.i_d, meas.i_q, w, theta, 0.0])
        dx = np.zeros(5) if self.x_prev is None else x - self.x_prev
        self.x_prev = x
        y = self.C @ x
        w_k, W = self.references(meas)
        if self.task == "position":                # relative angles (exact by invariance)
            W[:, 2] -= y[2]
            w_k = w_k.copy(); w_k[2] -= y[2]
            y = y.copy(); y[2] = 0.0
        g = self.gains_at(w)
        Wv = W.reshape(-1)
        if self.algorithm == 1:
            du = g["K_e"] @ (Wv - np.tile(y, self.N)) - g["K_dx"] @ dx
        else:
            self.ebar = self.ebar + self.ebar_increment(np.clip(w_k - y, -self.ebar_max, self.ebar_max), meas)  # (25)
            du = g["K_ebar"] @ self.ebar + g["K_WL"] @ Wv - g["K_y"] @ y - g["K_dx"] @ dx
        u_raw = self.u_dq + du
        u, sat = limit_circle(u_raw, self.cfg.u_max)
        self.saturations += int(sat)
        self.u_dq = u
        self.u_raw_mag = float(np.hypot(u_raw[0], u_raw[1]))
        self.hold = sat or abs(meas.i_q) > self.cfg.control.governor.hold_current * self.cfg.control.i_max
        self.last = {"w_sched": w, "du": du, "i_fw": self.i_fw}
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
