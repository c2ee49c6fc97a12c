"""Shared parts of the reference current controllers (issue 7, papers 001/002).

A current controller reads the current references (i_d*, i_q*) from
``meas.w_k[0:2]`` (and i*_{k+1} from ``meas.W[0]`` where a law wants the next
reference), the measured currents ``meas.i_d, meas.i_q`` and the electrical
speed from the encoder by the backward difference (paper 000 eq. 37), and
returns u_dq in volts.

Output delay: closedloop.simulate samples at the centre of the last PWM period
of a control period and the new duties start at the next period boundary, i.e.
u_k acts from t_k + t_d (t_d = half a PWM period) to t_k+1 + t_d.  The
model-based laws of 001/002 assume u_k acts from t_k.  ``compensate()`` moves
the measured state to t_k + t_d with the psi-free incremental predictor
    x^ = x_k + beta dx_k + beta^2 Ts B_c (u_k-1 - u_k-2),   beta = t_d / Ts,
(first order in Ts; exact in a steady state, so it adds no offset of its own),
the standard delay compensation of predictive current control; without it the
incremental laws of 001 oscillate at 10 kHz with one PWM period per sample
(see the report).  Outer loops (papers/cascade.py) overwrite the
references.  Every controller counts its arithmetic per step in ``self.ops``
(an :class:`~empc.papers.qp.opcount.OpCount`), summarised in ``op_stats()``.
"""
from __future__ import annotations

import math

import numpy as np

from .qp.opcount import OpCount
from ..controllers.base import Controller


class CurrentLoop(Controller):
    name = "current-loop"

    def __init__(self, cfg, motor=None):
        super().__init__(cfg)
        self.motor = motor or cfg.motor          # design parameters (may differ from the plant)
        self.Ts = cfg.control.Ts
        self.u_max = cfg.u_max                   # circle Udc / sqrt(3)
        self.i_max = cfg.control.i_max
        self.ops = OpCount()
        self.op_hist: list[int] = []
        self.op_max = OpCount()

    def reset(self) -> None:
        super().reset()
        self.x_meas_prev = None
        self.u_hist = [np.zeros(2), np.zeros(2)]     # u_k-1, u_k-2
        self.theta_prev = None
        self.w = 0.0
        self.saturations = 0
        self.op_hist = []
        self.op_max = OpCount()

    # --- helpers ---
    def speed(self, meas) -> float:
        """Electrical speed by the backward difference of the encoder angle (000 eq. 37)."""
        th = meas.theta_e
        w = 0.0 if self.theta_prev is None else (th - self.theta_prev) / self.Ts
        self.theta_prev = th
        self.w = w
        self.ops.add += 1; self.ops.mul += 1
        return w

    @property
    def beta(self) -> float:
        """Output delay as a fraction of Ts (closedloop timing: half a PWM period)."""
        return 0.5 / self.cfg.inverter.f_pwm / self.Ts

    def compensate(self, x: np.ndarray) -> np.ndarray:
        """State at the instant u_k takes effect (see module doc); x = measured [i_d, i_q]."""
        b = self.beta
        dx = np.zeros(2) if self.x_meas_prev is None else x - self.x_meas_prev
        self.x_meas_prev = x
        du = self.u_hist[0] - self.u_hist[1]
        Bc = np.array([1.0 / self.motor.Ld, 1.0 / self.motor.Lq])
        self.ops.mul += 6; self.ops.add += 6
        return x + b * dx + b * b * self.Ts * Bc * du

    def applied(self, u: np.ndarray) -> None:
        """Record the voltage applied this period (for ``compensate``)."""
        self.u_hist = [np.asarray(u, float).copy(), self.u_hist[0]]

    def refs(self, meas) -> tuple[np.ndarray, np.ndarray]:
        """(i*_k, i*_{k+1}) as 2-vectors."""
        r = np.asarray(meas.w_k, float)[:2]
        W = np.asarray(meas.W, float)
        r1 = W[0, :2] if W.size else r
        return r, r1

    def limit(self, u: np.ndarray) -> tuple[np.ndarray, bool]:
        """Circle limit |u| <= Udc/sqrt(3) by vector scaling (counted)."""
        n2 = float(u[0] * u[0] + u[1] * u[1])
        self.ops.mul += 2; self.ops.add += 1; self.ops.cmp += 1
        if n2 > self.u_max * self.u_max:
            k = self.u_max / math.sqrt(n2)
            self.ops.sqrt += 1; self.ops.div += 1; self.ops.mul += 2
            self.saturations += 1
            return u * k, True
        return u, False

    def begin(self) -> None:
        self.ops = OpCount()

    def end(self) -> None:
        self.op_hist.append(self.ops.flops)
        if self.ops.flops > self.op_max.flops:
            self.op_max = self.ops

    def op_stats(self) -> dict:
        h = np.asarray(self.op_hist) if self.op_hist else np.zeros(1)
        return {"flops_mean": float(np.mean(h)), "flops_max": int(np.max(h)), "worst_step": self.op_max.as_dict()}
