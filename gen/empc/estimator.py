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
form serves the float controller; :func:`state_space` gives the estimator as a linear block,
the one the robust design check puts in the loop (loop.py ``ESTIMATORS``).
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

    Inputs v_k = [dtheta_k (rad: theta_k - theta_{k-1}, the encoder's count difference),
    i_q,k (A)], output w_k (rad/s), state z_k = [w37_{k-1}, D_{k-1}]:

        z_{k+1} = A z_k + B v_k,      w_k = C z_k + D v_k

    ("eq37": kc = 0 and no states; "accel": no states: w_k = D v_k).  The angle enters only as its
    difference, so a loop with this block has no structural eigenvalue 1 from theta; the
    encoder quantisation (eq. 38) acts on dtheta before the block.  The design check's loop
    model (loop.py, :func:`empc.loop.from_state_space`) puts this block in the loop as built
    (the law then sees w_k instead of the plant's speed).
    Returns {"A", "B", "C", "D", "states", "inputs"}.
    """
    Ts = cfg.control.Ts
    kc = cfg.speed_correction
    g = 2.0 ** -cfg.speed_load_shift if cfg.speed_load_shift else 0.0
    # w37 = dtheta / Ts;  u1 = kc i - z1;  w = w37 + u1
    # z0' = w37;  z1' = z1 + g (u1 - (w37 - z0) / 2)
    A = np.array([[0.0, 0.0],
                  [g * 0.5, 1.0 - g]])
    B = np.array([[1.0 / Ts, 0.0],
                  [-g * 0.5 / Ts, g * kc]])
    C = np.array([[0.0, -1.0]])
    D = np.array([[1.0 / Ts, kc]])
    if not g:       # no states: w37_prev is read only by the load update, D would be a constant
        return {"A": A[:0, :0], "B": B[:0], "C": C[:, :0], "D": D, "states": (), "inputs": ("dtheta", "i_q")}
    return {"A": A, "B": B, "C": C, "D": D, "states": ("w37_prev", "D_load"), "inputs": ("dtheta", "i_q")}
