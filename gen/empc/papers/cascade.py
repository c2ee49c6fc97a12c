"""Outer loops for the reference current controllers: speed PI, position P, field weakening.

``Cascade(inner, cfg, ...)`` turns any current controller of this package
(FOC-PI, DB-MPCC, CCS-MPCC, online MPC of 002) into a speed or position
controller, as in the cascaded structure of 001 Fig. 2a and 002 Fig. 2:

  position task:  w* = K_th (theta* - theta) + d theta*/dt          (P + speed feed-forward)
  speed loop:     i_q* = PI(w*_f - w_f), every ``T_slow``            (002: T_slow = 1 ms)
  field weakening i_d* from the voltage circle (002 eqs. 3-6), or 0
  inner loop:     u = inner.step(meas with the references replaced by (i_d*, i_q*))

Tuning rule (stated): symmetric optimum.  With the current loop closed
(equivalent lag 2 T_sigma for a technical-optimum loop; used for all inner
loops), the speed filter T_f and half a slow period, T_sw = 2 T_sigma + T_f +
T_slow/2; plant i_q -> w_e is K_m / s with K_m = p * 1.5 p psi / J.  Then
K_p = 1 / (2 K_m T_sw), T_i = 4 T_sw, and the speed reference passes a
prefilter 1/(1 + T_i s) (removes the symmetric optimum's 43 % overshoot).
Anti-windup: the PI output is clamped to the current limit and the integrator
is stopped while clamped (conditional integration).  Position task: no speed
prefilter (it would lag inside the position loop), P gain K_th = 1 / (6 T_sw)
plus the reference derivative as speed feed-forward (K_th chosen on the
BLWR233D position step: the fastest setting without overshoot; 1/(4 T_sw)
overshoots 4 %, 1/(8 T_sw) is slower).
The speed is the backward difference of the encoder angle (000 eq. 37) through
a first-order filter T_f.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from .qp.opcount import OpCount
from ..controllers.base import Controller


@dataclasses.dataclass
class FieldWeakening:
    """d-axis reference from the steady-state voltage circle (002 eqs. 3-6).

    Voltage circle in the (i_d, i_q) plane at the electrical speed w (derived from
    the steady state of 002 eq. 1 with L = L_d = L_q; 002 eq. 6 prints V^2 where
    the radius is V):
        centre = (-L w^2 lambda / (R^2 + L^2 w^2), -R w lambda / (R^2 + L^2 w^2))   (5)
        radius = V / sqrt(R^2 + L^2 w^2)                                           (6)
    i_d* = 0 while (0, i_q*) is inside the circle (MTPA of a surface PMSM), else the
    point of the circle at i_q*: i_d* = c_d + sqrt(rho^2 - (i_q* - c_q)^2); if i_q*
    is outside the circle's i_q range, i_d* = c_d and i_q* is cut to the circle.
    Then i_d* >= -i_d_min_abs (the current polygon's left edge, 002 eq. 10) and
    |i_q*| <= sqrt(I_max^2 - i_d*^2) (current circle, 002 eq. 3).
    ``v_margin``: V = v_margin * V_max.  With ``polygon`` (the voltage polygon of
    002 eq. 9, which the MPC enforces instead of the circle) V is further scaled to
    the polygon's radius in the direction of the steady-state voltage of the
    operating point (two passes), so the reference stays reachable by the MPC.
    """
    R: float
    L: float
    psi: float
    v_max: float
    i_max: float
    v_margin: float = 0.98
    i_d_min_abs: float | None = None

    polygon: np.ndarray | None = None     # rows P with P u <= V_max (002 eq. 9); None: circle

    def _circle(self, w: float, i_q_ref: float, V: float) -> tuple[float, float]:
        Z2 = self.R ** 2 + (self.L * w) ** 2
        cd = -self.L * w * w * self.psi / Z2                 # (5)
        cq = -self.R * w * self.psi / Z2
        rho = V / math.sqrt(Z2)                              # (6)
        iq = i_q_ref
        if (0.0 - cd) ** 2 + (iq - cq) ** 2 <= rho ** 2:
            return 0.0, iq
        t = rho ** 2 - (iq - cq) ** 2
        if t >= 0.0:
            return min(0.0, cd + math.sqrt(t)), iq
        return min(0.0, cd), (cq + math.copysign(rho, iq - cq))

    def __call__(self, w: float, i_q_ref: float, ops: OpCount | None = None) -> tuple[float, float]:
        if ops is not None:
            ops.mul += 12; ops.add += 8; ops.div += 2; ops.sqrt += 2; ops.cmp += 4
        V = self.v_margin * self.v_max
        if self.polygon is None:
            i_d, iq = self._circle(w, i_q_ref, V)
        else:
            # start from the edge distance next to the q axis (cos 22.5 deg of V_max), then
            # two passes with the polygon's radius in the direction of the steady-state
            # voltage at the operating point just found
            rho = math.cos(math.pi / 8)
            for _ in range(3):
                i_d, iq = self._circle(w, i_q_ref, V * rho)
                ud = self.R * i_d - w * self.L * iq
                uq = self.R * iq + w * (self.L * i_d + self.psi)
                n = math.hypot(ud, uq)
                if n <= 0:
                    break
                proj = self.polygon @ np.array([ud, uq]) / n
                rho = min(float(np.min(1.0 / proj[proj > 0])) if np.any(proj > 0) else 1.0, 1.0)
            if ops is not None:
                ops.mul += 36; ops.add += 24; ops.div += 16; ops.sqrt += 6; ops.cmp += 14
        dmin = self.i_d_min_abs if self.i_d_min_abs is not None else self.i_max
        i_d = max(i_d, -dmin)
        lim = math.sqrt(max(self.i_max ** 2 - i_d ** 2, 0.0))
        iq = min(max(iq, -lim), lim)
        return i_d, iq


class SpeedPI:
    """Speed PI (symmetric optimum) with reference prefilter and conditional-integration anti-windup."""

    def __init__(self, cfg, T_slow: float, T_f: float, T_sigma_inner: float, i_limit: float, motor=None,
                 prefilter: bool = True):
        m = motor or cfg.motor
        self.prefilter = prefilter
        self.K_m = m.p * 1.5 * m.p * m.psi / m.J            # d w_e / dt per A of i_q
        self.T_sw = 2.0 * T_sigma_inner + T_f + 0.5 * T_slow
        self.kp = 1.0 / (2.0 * self.K_m * self.T_sw)
        self.Ti = 4.0 * self.T_sw
        self.T_slow = T_slow
        self.i_limit = i_limit
        self.reset()

    def reset(self) -> None:
        self.integ = 0.0
        self.ref_f = None

    def __call__(self, w_ref: float, w: float, limit: float | None = None, ops: OpCount | None = None) -> float:
        lim = self.i_limit if limit is None else limit
        if self.ref_f is None:
            self.ref_f = w_ref
        if self.prefilter:
            a = self.T_slow / (self.Ti + self.T_slow)        # prefilter 1/(1 + Ti s), backward Euler
            self.ref_f += a * (w_ref - self.ref_f)
        else:
            self.ref_f = w_ref
        e = self.ref_f - w
        u = self.kp * e + self.integ
        u_new_int = self.integ + self.kp * self.T_slow / self.Ti * e
        if ops is not None:
            ops.add += 4; ops.mul += 4; ops.cmp += 2
        if abs(u) < lim or (u >= lim and e < 0) or (u <= -lim and e > 0):
            self.integ = u_new_int                           # conditional integration
        return float(min(max(u, -lim), lim))


class Cascade(Controller):
    """Speed (and position) loops around a current controller; optional field weakening."""

    def __init__(self, inner, cfg, task: str = "speed", T_slow: float | None = None, T_f: float = 1e-3,
                 field_weakening: FieldWeakening | None = None, motor=None, name: str | None = None,
                 T_sigma_inner: float | None = None, k_th: float | None = None):
        super().__init__(cfg)
        self.inner = inner
        self.task = task
        Ts = cfg.control.Ts
        self.Ts = Ts
        self.T_slow = T_slow or Ts
        self.n_slow = max(1, int(round(self.T_slow / Ts)))
        self.T_f = T_f
        self.fw = field_weakening
        self.speed_pi = SpeedPI(cfg, self.n_slow * Ts, T_f, T_sigma_inner or Ts, cfg.control.i_max, motor,
                                prefilter=(task != "position"))
        self.k_th = k_th if k_th is not None else 1.0 / (6.0 * self.speed_pi.T_sw)
        self.name = name or f"{inner.name} + {'P/' if task == 'position' else ''}PI cascade"
        self.reset()

    @property
    def ops(self) -> OpCount:
        return self.inner.ops

    def op_stats(self) -> dict:
        return self.inner.op_stats()

    @property
    def saturations(self) -> int:
        return getattr(self.inner, "saturations", 0)

    def reset(self) -> None:
        super().reset()
        self.inner.reset()
        self.k = 0
        self.theta_prev = None
        self.w_f = 0.0
        self.i_q_ref = 0.0
        self.speed_pi.reset()
        self.log = []

    def step(self, meas) -> np.ndarray:
        th = meas.theta_e
        w_raw = 0.0 if self.theta_prev is None else (th - self.theta_prev) / self.Ts
        self.theta_prev = th
        a = self.Ts / (self.T_f + self.Ts)
        self.w_f += a * (w_raw - self.w_f)
        extra = OpCount()
        extra.add += 3; extra.mul += 2
        if self.k % self.n_slow == 0:
            r = np.asarray(meas.w_k, float)
            if self.task == "position":
                W = np.asarray(meas.W, float)
                ff = (W[0, 2] - r[2]) / self.Ts if W.size else 0.0
                w_ref = self.k_th * (r[2] - th) + ff
                extra.add += 3; extra.mul += 1; extra.div += 1
            else:
                w_ref = r[2]
            self.i_q_ref = self.speed_pi(w_ref, self.w_f, ops=extra)
        self.k += 1
        i_d_ref, i_q_ref = 0.0, self.i_q_ref
        if self.fw is not None:
            i_d_ref, i_q_ref = self.fw(self.w_f, self.i_q_ref, ops=extra)
        ref = np.array([i_d_ref, i_q_ref, meas.w_k[2]])
        m2 = dataclasses.replace(meas, w_k=ref, W=np.tile(ref, (max(1, len(meas.W)), 1)))
        u = self.inner.step(m2)
        self.inner.ops += extra
        if self.inner.op_hist:
            self.inner.op_hist[-1] += extra.flops
        self.u_dq = np.asarray(u, float)
        self.log.append((i_d_ref, i_q_ref))
        return self.u_dq

    def modulate(self, theta_e: float, w_e: float) -> np.ndarray:
        self.inner.u_dq = self.u_dq
        return self.inner.modulate(theta_e, w_e)


class FWReference(Controller):
    """Feeds a controller that takes (i_d*, i_q*, w*) references with i_d* from field weakening.

    For our explicit MPC in the speed task (paper 000: the 'Position/Speed' block
    provides field weakening): i_d* = FieldWeakening(w_f, i_q_f) with the filtered
    speed and the filtered measured i_q (the MPC computes i_q itself).
    """

    def __init__(self, inner, cfg, field_weakening: FieldWeakening, T_f: float = 1e-3, name: str | None = None):
        super().__init__(cfg)
        self.inner = inner
        self.fw = field_weakening
        self.Ts = cfg.control.Ts
        self.T_f = T_f
        self.name = name or f"{inner.name} + FW"
        self.reset()

    @property
    def saturations(self) -> int:
        return getattr(self.inner, "saturations", 0)

    def reset(self) -> None:
        super().reset()
        self.inner.reset()
        self.theta_prev = None
        self.w_f = 0.0
        self.iq_f = 0.0

    def step(self, meas) -> np.ndarray:
        th = meas.theta_e
        w_raw = 0.0 if self.theta_prev is None else (th - self.theta_prev) / self.Ts
        self.theta_prev = th
        a = self.Ts / (self.T_f + self.Ts)
        self.w_f += a * (w_raw - self.w_f)
        self.iq_f += a * (meas.i_q - self.iq_f)
        i_d, _ = self.fw(self.w_f, self.iq_f)
        wk = np.array(meas.w_k, float)
        W = np.array(meas.W, float)
        wk[0] = i_d
        W[:, 0] = i_d
        u = self.inner.step(dataclasses.replace(meas, w_k=wk, W=W))
        self.u_dq = np.asarray(u, float)
        return self.u_dq

    def modulate(self, theta_e: float, w_e: float) -> np.ndarray:
        return self.inner.modulate(theta_e, w_e)


class RampReference(Controller):
    """Rate limiter on the third reference (speed) before a controller that reads w_k / W.

    Plays the role of paper 000's reference generator (time-parameterised profiles)
    when a scenario gives steps: w* moves towards the scenario's reference at most
    ``rate`` (rad/s per s, electrical); the preview window W is the limiter's own
    extrapolation over the horizon.
    """

    def __init__(self, inner, cfg, rate: float, name: str | None = None):
        super().__init__(cfg)
        self.inner = inner
        self.rate = rate
        self.Ts = cfg.control.Ts
        self.name = name or f"{inner.name} + ramp"
        self.reset()

    @property
    def saturations(self) -> int:
        return getattr(self.inner, "saturations", 0)

    def reset(self) -> None:
        super().reset()
        self.inner.reset()
        self.r = None

    def step(self, meas) -> np.ndarray:
        target = float(meas.w_k[2])
        if self.r is None:
            self.r = target
        dmax = self.rate * self.Ts
        self.r += min(max(target - self.r, -dmax), dmax)
        wk = np.array(meas.w_k, float)
        W = np.array(meas.W, float)
        wk[2] = self.r
        r = self.r
        for j in range(W.shape[0]):
            r += min(max(W[j, 2] - r, -dmax), dmax)
            W[j, 2] = r
        u = self.inner.step(dataclasses.replace(meas, w_k=wk, W=W))
        self.u_dq = np.asarray(u, float)
        return self.u_dq

    def modulate(self, theta_e: float, w_e: float) -> np.ndarray:
        return self.inner.modulate(theta_e, w_e)
