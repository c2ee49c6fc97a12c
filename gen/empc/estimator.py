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

``control.speed_window`` = M > 1 (a power of two) takes the difference over M periods,
w37_k = (theta_k - theta_{k-M}) / (M Ts): the mean speed over the window, i.e. the speed M/2
periods ago, with 1/M of eq. 37's quantisation step (one count is rad_per_count / (M Ts)).  The
correction covers the window's lag, kc = (M Ts/2) 1.5 p^2 psi / J (Config.speed_correction), and
the load estimate compares it with the encoder's speed change over that lag, (M/2) (w37_k - w37_{k-1}):

      D_k = D_{k-1} + 2^-s (u1 - M (w37_k - w37_{k-1}) / 2)

(M = 1: the formulas above).  Before M angles are known the window reaches back to the first one.
Float, fixed-point FixedMPC, the robust check and the RTL (KACC.win = log2 M in rtl/mx_seq.v: a count history
formats.WIN_DEPTH = 16 deep; the RTL's first M speeds after reset take the counts before it as 0, FixedMPC's this
first angle).

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
        self.M = cfg.control.speed_window
        self.reset()

    def reset(self) -> None:
        self.theta_prev = None
        self.w37_prev = 0.0
        self.D = 0.0
        self.hist: list = []            # speed_window > 1: theta_{k-M} .. theta_{k-1}

    def step(self, theta: float, i_q: float) -> float:
        if self.M != 1:
            return self._step_window(theta, i_q)
        w37 = 0.0 if self.theta_prev is None else (theta - self.theta_prev) / self.Ts   # eq. 37
        self.theta_prev = theta
        u1 = self.kc * i_q - self.D
        w = w37 + u1
        if self.g:
            self.D += self.g * (u1 - 0.5 * (w37 - self.w37_prev))
        self.w37_prev = w37
        return w

    def _step_window(self, theta: float, i_q: float) -> float:
        M = self.M
        if not self.hist:
            self.hist = [theta] * M
        w37 = (theta - self.hist[0]) / (M * self.Ts)          # mean speed over the last M periods
        self.hist = self.hist[1:] + [theta]
        u1 = self.kc * i_q - self.D
        w = w37 + u1
        if self.g:
            self.D += self.g * (u1 - 0.5 * M * (w37 - self.w37_prev))
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
    if cfg.control.speed_window != 1:
        return _state_space_window(cfg.control.speed_window, Ts, kc, g)
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


def _state_space_window(M: int, Ts: float, kc: float, g: float) -> dict:
    """:func:`state_space` for ``control.speed_window`` = M > 1: states s_j = dtheta_{k-j} / (M Ts),
    j = 1..M, and D_{k-1}:

        w37_k = dtheta_k / (M Ts) + s_1 + .. + s_{M-1},   w37_k - w37_{k-1} = dtheta_k / (M Ts) - s_M
        u1 = kc i_q - D;  w_k = w37_k + u1;  D' = D + g (u1 - (M/2) (w37_k - w37_{k-1}));  s_1' = dtheta_k / (M Ts)
    """
    n = M + 1
    A = np.zeros((n, n)); B = np.zeros((n, 2)); C = np.zeros((1, n)); D = np.zeros((1, 2))
    for j in range(1, M):
        A[j, j - 1] = 1.0                       # s_{j+1}' = s_j
    B[0, 0] = 1.0 / (M * Ts)
    C[0, :M - 1] = 1.0
    C[0, M] = -1.0
    D[0, 0], D[0, 1] = 1.0 / (M * Ts), kc
    A[M, M] = 1.0 - g
    A[M, M - 1] = g * 0.5 * M
    B[M, 0] = -g * 0.5 / Ts
    B[M, 1] = g * kc
    states = tuple(f"dtheta_{j}/(M Ts)" for j in range(1, M + 1)) + ("D_load",)
    if not g:       # no load estimate: D stays 0 (no state; s_M is read only by its update)
        return {"A": A[:M, :M], "B": B[:M], "C": C[:, :M], "D": D, "states": states[:M], "inputs": ("dtheta", "i_q")}
    return {"A": A, "B": B, "C": C, "D": D, "states": states, "inputs": ("dtheta", "i_q")}
