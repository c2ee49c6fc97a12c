"""Speed estimate fed to the control law (paper 000 eq. 37 and its corrections), float form.

``control.speed_estimate`` selects it:

- ``"eq37"``: w_k = (theta_k - theta_{k-1}) / Ts, the mean speed over the last period, i.e. the
  speed half a period ago (a half-period lag: a 250 Hz limit cycle at standstill).
- ``"accel"``: eq. 37 + kc i_q, kc = (Ts/2) 1.5 p^2 psi / J (Config.speed_correction): the missing
  half period of acceleration from the torque.  Under a constant load the rotor does not
  accelerate while i_q holds the load, so the estimate is kc i_load too high and the speed
  settles kc i_load low (5 rad/s per A on the BLWR233D).
- ``"accel_load"`` (default): the same, less a load estimate D that converges to the part of
  kc i_q that does not accelerate the rotor:

      u1  = kc i_q,k - D_{k-1}
      w_k = w37_k + u1
      D_k = D_{k-1} + 2^-s (u1 - (w37_k - w37_{k-1}) / 2)

  (w37_k - w37_{k-1}) / 2 is the half-period speed change measured by the encoder, so D is a
  low-pass estimate (time constant 2^s periods) of (Ts/2) x the load's deceleration, and w_k
  is offset-free under a constant load (D = kc i_load).  It keeps the half-period
  correction at every frequency, also along a sustained acceleration.  s =
  ``control.speed_load_shift`` (6: 16 ms at Ts = 250 us).

The RTL computes the same in raw units (rtlmodel/ctrl_seq.py ``speed_estimate``); this float
form serves the float controller and the design check.  :func:`state_space` gives the
estimator as a linear block for the robustness check (design.py).
"""
from __future__ import annotations

import numpy as np


class SpeedEstimator:
    """Float speed estimate (rad/s electrical) from the measured angle and i_q, once per period."""

    def __init__(self, cfg):
        self.kind = cfg.control.speed_estimate
        self.Ts = cfg.control.Ts
        self.kc = cfg.speed_correction
        self.g = 2.0 ** -cfg.speed_load_shift if cfg.speed_load_shift else 0.0
        self.reset()

    def reset(self) -> None:
        self.theta_prev = None
        self.w37_prev = 0.0
        self.D = 0.0

    def step(self, theta: float, i_q: float) -> float:
        w37 = 0.0 if self.theta_prev is None else (theta - self.theta_prev) / self.Ts   # eq. 37
        self.theta_prev = theta
        u1 = self.kc * i_q - self.D
        w = w37 + u1
        if self.g:
            self.D += self.g * (u1 - 0.5 * (w37 - self.w37_prev))
        self.w37_prev = w37
        return w


def state_space(cfg) -> dict:
    """The estimator as a discrete linear block, one step per control period.

    Inputs v_k = [theta_k (rad, the measured angle), i_q,k (A)], output w_k (rad/s),
    state z_k = [theta_{k-1}, w37_{k-1}, D_{k-1}]:

        z_{k+1} = A z_k + B v_k,      w_k = C z_k + D v_k

    (eq. 37 alone: the D state stays 0; "eq37": kc = 0 as well).  The encoder quantisation
    (eq. 38) acts on theta_k before this block.  Returns {"A", "B", "C", "D", "states", "inputs"}.
    """
    Ts = cfg.control.Ts
    kc = cfg.speed_correction
    g = 2.0 ** -cfg.speed_load_shift if cfg.speed_load_shift else 0.0
    # w37_k = (theta_k - z0) / Ts;  u1 = kc i - z2;  w = w37_k + u1
    # z0' = theta_k;  z1' = w37_k;  z2' = z2 + g (u1 - (w37_k - z1) / 2)
    A = np.array([[0.0, 0.0, 0.0],
                  [-1.0 / Ts, 0.0, 0.0],
                  [g * 0.5 / Ts, g * 0.5, 1.0 - g]])
    B = np.array([[1.0, 0.0],
                  [1.0 / Ts, 0.0],
                  [-g * 0.5 / Ts, g * kc]])
    C = np.array([[-1.0 / Ts, 0.0, -1.0]])
    D = np.array([[1.0 / Ts, kc]])
    return {"A": A, "B": B, "C": C, "D": D, "states": ("theta_prev", "w37_prev", "D_load"),
            "inputs": ("theta", "i_q")}
