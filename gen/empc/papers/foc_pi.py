"""FOC with PI current controllers, decoupling feed-forward and anti-windup (paper 001, sec. 3, Fig. 2a).

    u_d = PI_d(i_d* - i_d) - w_e L_q i_q                (decoupling of 001 eq. 7a)
    u_q = PI_q(i_q* - i_q) + w_e (L_d i_d + Psi_pm)     (decoupling and back-EMF of 001 eq. 7b)
    u   = circle limit |u| <= Udc/sqrt(3) (vector scaling)

Tuning rule (stated): technical optimum (modulus optimum) with pole-zero
cancellation.  The PI zero cancels the stator pole, T_i = L/R; the remaining
open loop K_p / (L s (1 + T_sigma s)) with the small time constant T_sigma = Ts
(half a period from sampling to the duty update plus half a period of PWM
averaging: the timing of closedloop.simulate) is set to K_p T_sigma / L = 1/2,
i.e. K_p = L / (2 T_sigma): a current-loop bandwidth of about 1/(2 T_sigma) =
a / Ts with a = 0.5 and ~4 % overshoot.  Discrete
PI: integrator by forward Euler, I += K_p Ts / T_i * e.
Anti-windup: back-calculation with full tracking: after limiting, the
integrator is corrected by (u_limited - u_unlimited), so the PI output sits on
the limit and recovers without windup.
"""
from __future__ import annotations

import numpy as np

from .common import CurrentLoop


def technical_optimum(L: float, R: float, T_sigma: float) -> tuple[float, float]:
    """(K_p, K_i) with T_i = L/R and K_p = L/(2 T_sigma); K_i = K_p / T_i (V/A, V/(A s))."""
    kp = L / (2.0 * T_sigma)
    return kp, kp * R / L


class FocPI(CurrentLoop):
    name = "FOC-PI"

    def __init__(self, cfg, motor=None, T_sigma: float | None = None, decouple: bool = True):
        super().__init__(cfg, motor)
        m = self.motor
        self.T_sigma = T_sigma or self.Ts
        self.kp = np.zeros(2)
        self.ki = np.zeros(2)
        for j, L in enumerate((m.Ld, m.Lq)):
            self.kp[j], self.ki[j] = technical_optimum(L, m.R, self.T_sigma)
        self.decouple = decouple
        self.reset()

    def reset(self) -> None:
        super().reset()
        self.integ = np.zeros(2)

    def step(self, meas) -> np.ndarray:
        self.begin()
        m = self.motor
        w = self.speed(meas)
        r, _ = self.refs(meas)
        i = np.array([meas.i_d, meas.i_q])
        e = r - i
        self.integ += self.ki * self.Ts * e
        u = self.kp * e + self.integ
        self.ops.add += 2; self.ops.mul += 4; self.ops.add += 2; self.ops.mul += 2; self.ops.add += 2
        if self.decouple:
            ff = np.array([-w * m.Lq * i[1], w * (m.Ld * i[0] + m.psi)])
            u = u + ff
            self.ops.mul += 4; self.ops.add += 3
        ul, sat = self.limit(u)
        if sat:
            self.integ += ul - u                 # back-calculation anti-windup
            self.ops.add += 4
        self.u_dq = ul
        self.end()
        return ul
