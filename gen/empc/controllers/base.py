"""Controller base class: float modulation of a held dq voltage."""
from __future__ import annotations

import math

import numpy as np

from .. import pmsm


class Controller:
    name = "controller"
    uses_reference_window = True

    def __init__(self, cfg):
        self.cfg = cfg
        self.u_dq = np.zeros(2)

    def reset(self) -> None:
        self.u_dq = np.zeros(2)

    def step(self, meas) -> np.ndarray:
        raise NotImplementedError

    def modulate(self, theta_e: float, w_e: float) -> np.ndarray:
        """Phase duties for one PWM period from the held u_dq at angle ``theta_e``.

        The angle is advanced by half a PWM period (the average angle over the
        period the duties are held), inverse Park (34), inverse Clarke (35),
        min-subtraction (36), duty = u / Udc.
        """
        th = theta_e + w_e * 0.5 / self.cfg.inverter.f_pwm
        a, b = pmsm.inv_park(self.u_dq[0], self.u_dq[1], th)
        v = pmsm.min_subtract(*pmsm.inv_clarke(a, b))
        return np.clip(np.array(v) / self.cfg.inverter.Udc, 0.0, 1.0)


def limit_circle(u: np.ndarray, u_max: float) -> tuple[np.ndarray, bool]:
    """Scale the vector back onto the circle |u| <= u_max (direction kept)."""
    n = math.hypot(u[0], u[1])
    if n > u_max:
        return u * (u_max / n), True
    return u, False
