"""Deadbeat model predictive current control of paper 001 (sec. 4 and 5).

Two forms of the deadbeat law, both from the Euler model 001 eq. (8) with the
deadbeat condition i_{k+1} = i*_{k+1} (001 eq. 9):

``form="eq10"`` - the law printed in 001 as eq. (10): the difference of two
consecutive predictions, so Psi_pm cancels:
    u_d,k = u_d,k-1 + L_d/Ts (i*_d,k+1 + i_d,k-1) - L_q (w_k i_q,k - w_k-1 i_q,k-1)
            - 2 L_d/Ts i_d,k + R_s (i_d,k - i_d,k-1)                              (10a)
    u_q,k = u_q,k-1 + L_q/Ts (i*_q,k+1 + i_q,k-1) + L_d (w_k i_d,k - w_k-1 i_d,k-1)
            - 2 L_q/Ts i_q,k + R_s (i_q,k - i_q,k-1)                              (10b)
  u_{k-1} is the voltage applied in the previous period (after the circle limit).
  Note (analysis, see the report): in a steady state (constant i, w, u) (10)
  reduces to 0 = L/Ts (i* - i), so this law is incremental and has NO
  steady-state offset whatever the parameter error or a constant voltage error.

``form="eq9"`` - the direct inversion of (8) at (9) (the classical absolute deadbeat):
    u_d,k = L_d/Ts (i*_d,k+1 - i_d,k) + R_s i_d,k - w_k L_q i_q,k
    u_q,k = L_q/Ts (i*_q,k+1 - i_q,k) + R_s i_q,k + w_k (L_d i_d,k + Psi_pm)
  A mismatch of R, L or Psi, or an inverter voltage error, leaves a steady-state
  offset (the proportional gain is only L/Ts).

DB-MPCC-I (001 sec. 5, eq. 11): the deadbeat output plus a discrete integrator
of the current error,  u^err_{k+1} = K_i sum_{i=0..k} (i*_i - i_i)  (applied from
the next period on).  001 prints the error as (i_meas - i_ref); added to the
voltage that would be positive feedback, so the sign is taken as reference minus
measurement.  K_i is not given in 001: chosen K_i = k_i L / Ts per axis with
k_i = 0.1 (integrator time constant ~10 samples against the deadbeat's unit gain).
Delay compensation (common.py): the state i_k in the laws is the measured
current moved to the instant the new voltage takes effect (``delay_comp``).
``i*_{k+1}``: from the reference window W[0] (001: "computed using linear
extrapolation"; our references are known one step ahead).
"""
from __future__ import annotations

import numpy as np

from .common import CurrentLoop


class DeadbeatMPCC(CurrentLoop):
    def __init__(self, cfg, motor=None, form: str = "eq10", integrator: bool = False, k_i: float = 0.1,
                 delay_comp: bool = True):
        super().__init__(cfg, motor)
        self.delay_comp = delay_comp
        if form not in ("eq10", "eq9"):
            raise ValueError(f"form must be 'eq10' or 'eq9', got {form!r}")
        self.form = form
        self.integrator = integrator
        m = self.motor
        self.L = np.array([m.Ld, m.Lq])
        self.Ki = k_i * self.L / self.Ts if integrator else np.zeros(2)
        self.name = ("DB-MPCC-I" if integrator else "DB-MPCC") + f" ({'eq.10' if form == 'eq10' else 'eq.8-9 abs.'})"
        self.reset()

    def reset(self) -> None:
        super().reset()
        self.i_prev = None
        self.w_prev = 0.0
        self.u_prev = np.zeros(2)
        self.err_sum = np.zeros(2)

    def step(self, meas) -> np.ndarray:
        self.begin()
        m = self.motor
        Ts = self.Ts
        w = self.speed(meas)
        r, r1 = self.refs(meas)
        i_meas = np.array([meas.i_d, meas.i_q])
        i = self.compensate(i_meas) if self.delay_comp else i_meas
        Ld, Lq, R = m.Ld, m.Lq, m.R
        if self.form == "eq10":
            ip = i if self.i_prev is None else self.i_prev
            wp = self.w_prev if self.i_prev is not None else w
            up = self.u_prev
            ud = up[0] + Ld / Ts * (r1[0] + ip[0]) - Lq * (w * i[1] - wp * ip[1]) - 2 * Ld / Ts * i[0] + R * (i[0] - ip[0])
            uq = up[1] + Lq / Ts * (r1[1] + ip[1]) + Ld * (w * i[0] - wp * ip[0]) - 2 * Lq / Ts * i[1] + R * (i[1] - ip[1])
            # constants L/Ts, 2L/Ts precomputed: per axis 5 mul, 7 add
            self.ops.mul += 10; self.ops.add += 14
        else:
            ud = Ld / Ts * (r1[0] - i[0]) + R * i[0] - w * Lq * i[1]
            uq = Lq / Ts * (r1[1] - i[1]) + R * i[1] + w * (Ld * i[0] + m.psi)
            self.ops.mul += 7; self.ops.add += 6
        u_db = np.array([ud, uq])
        u = u_db
        if self.integrator:
            u = u_db + self.Ki * self.err_sum          # u^err_k = K_i sum_{i<k} e_i   (11)
            self.err_sum = self.err_sum + (r - i_meas)
            self.ops.mul += 2; self.ops.add += 6
        ul, sat = self.limit(u)
        if sat and self.integrator:
            # conditional integration (anti-windup): undo this period's accumulation
            self.err_sum = self.err_sum - (r - i_meas)
            self.ops.add += 2
        self.i_prev = i
        self.w_prev = w
        self.u_prev = ul
        self.applied(ul)
        self.u_dq = ul
        self.end()
        return ul
