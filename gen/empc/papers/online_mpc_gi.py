"""Online MPC current controller of paper 002 (sec. II-III) with the Goldfarb-Idnani QP solver.

Model (002 eq. 2, forward Euler, after Bolognani et al.): the bilinear terms
w i_d and w i_q are extra states held constant over the horizon, the speed is a
measured exogenous input held constant:
    x = [i_d, i_q, w i_d, w i_q],  u = [V_d, V_q],  x_k+1 = A x_k + B u_k + G w_k,  y = [i_d, i_q]
    A = [[1 - Ts R/L_d, 0, 0, Ts L_q/L_d], [0, 1 - Ts R/L_q, -Ts L_d/L_q, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    B = [[Ts/L_d, 0], [0, Ts/L_q], 0, 0],  G = [0, -Ts lambda_m/L_q, 0, 0]'
  (002 eq. 2b is garbled in the text: the lower-right block must be the identity
  for "constant over the prediction horizon", and A[1,1] uses L_q.)
  A and B do not depend on w, so the QP Hessian is constant: its Cholesky factor
  and J0 = Z^-T are computed once (offline), as an embedded implementation would.
MPC (002 eq. 7): N_p prediction, N_u control steps, decision dU = [du_k .. du_k+Nu-1],
    min sum_{i=1..Np} |Q^1/2 (y_k+i - r_k)|^2 + sum_{j<Nu} |R^1/2 du_k+j|^2,
    u_k+j = u_k+j-1 + du_k+j, du = 0 beyond N_u (7f),
    voltage polygon (002 eq. 9) on u_k .. u_k+Nu-1, current polygon (002 eq. 10) on y_k+1 .. y_k+Np.
  002's Table 2 (N_p, N_u, Q, R) is missing from the text; 002 sec. III-C gives the
  solution-space dimension 4, so N_u = 2.  Chosen: N_p = 4, Q = I, R = r I (r below).
Constraint polygons (002 eqs. 9-10; the extracted matrices are garbled, this is
the reading consistent with the text, m = sqrt(2) + 1):
  voltage, 6 rows: +-sqrt(2) V_d <= V_max (the two octagon edges around the d axis
  merged into one vertical edge at 0.707 V_max, "70 % of the maximum voltage for the
  d axis"), and +-V_d/m +- V_q <= V_max (octagon edges through the q-axis vertices);
  current, 3 rows: -I_d/m + I_q <= I_max, -sqrt(2) I_d <= I_max, -I_d/m - I_q <= I_max
  (left half of the same polygon; the right half-plane is cropped, i_d < 0 only).
Steady-state Kalman filter (002 sec. II) on the current measurements, for the
2-state current model with the speed as known input; gain from the discrete
Riccati equation at w = 0 (process noise sigma_w, measurement noise sigma_v),
used at every speed (steady-state filter).  The filtered state is then moved to
the instant the new voltage acts (output delay, see common.py) with the model.
Solver: qp/goldfarb_idnani.py (002 Algorithm 1).  If the QP is infeasible (the
current polygon cannot be reached within the horizon under the voltage polygon),
it is solved again with the voltage rows only (counted in ``status_bad``).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.linalg import solve_discrete_are

from .qp import goldfarb_idnani as gi
from .common import CurrentLoop

M_OCT = math.sqrt(2.0) + 1.0


def voltage_polygon() -> np.ndarray:
    """Rows P with P [V_d, V_q] <= V_max (002 eq. 9)."""
    m = M_OCT
    return np.array([[-1 / m, 1.0], [math.sqrt(2.0), 0.0], [-1 / m, -1.0],
                     [1 / m, -1.0], [-math.sqrt(2.0), 0.0], [1 / m, 1.0]])


def current_polygon() -> np.ndarray:
    """Rows P with P [I_d, I_q] <= I_max (002 eq. 10, right half-plane cropped)."""
    m = M_OCT
    return np.array([[-1 / m, 1.0], [-math.sqrt(2.0), 0.0], [-1 / m, -1.0]])


class OnlineMPC(CurrentLoop):
    name = "online MPC (GI)"

    def __init__(self, cfg, motor=None, Np: int = 4, Nu: int = 2, q: float = 1.0, r: float = 0.02,
                 sigma_w: float = 0.1, sigma_v: float | None = None, kalman: bool = True,
                 delay_comp: bool = True):
        super().__init__(cfg, motor)
        m = self.motor
        Ts = self.Ts
        self.Np, self.Nu = Np, Nu
        A = np.eye(4)
        A[0, 0] = 1 - Ts * m.R / m.Ld
        A[0, 3] = Ts * m.Lq / m.Ld
        A[1, 1] = 1 - Ts * m.R / m.Lq
        A[1, 2] = -Ts * m.Ld / m.Lq
        B = np.zeros((4, 2))
        B[0, 0] = Ts / m.Ld
        B[1, 1] = Ts / m.Lq
        G = np.array([0.0, -Ts * m.psi / m.Lq, 0.0, 0.0])
        C = np.hstack([np.eye(2), np.zeros((2, 2))])
        self.A, self.B, self.G, self.C = A, B, G, C
        # prediction  Y = Phi x + Gu u_prev + Gw w + Theta dU
        ny, nu = 2, 2
        Phi = np.zeros((ny * Np, 4))
        Gu = np.zeros((ny * Np, nu))
        Gw = np.zeros(ny * Np)
        Theta = np.zeros((ny * Np, nu * Nu))
        Apows = [np.eye(4)]
        for i in range(1, Np + 1):
            Apows.append(Apows[-1] @ A)
        for i in range(1, Np + 1):
            Phi[(i - 1) * ny:i * ny] = C @ Apows[i]
            sB = sum(Apows[l] @ B for l in range(i))
            sG = sum(Apows[l] @ G for l in range(i))
            Gu[(i - 1) * ny:i * ny] = C @ sB
            Gw[(i - 1) * ny:i * ny] = C @ sG
            # u_{k+j} for j = 0..i-1 contains du_{k+l} for l <= min(j, Nu-1)
            for l in range(Nu):
                blk = np.zeros((4, 2))
                for j in range(l, i):
                    blk += Apows[i - 1 - j] @ B
                Theta[(i - 1) * ny:i * ny, l * nu:(l + 1) * nu] = C @ blk
        self.Phi, self.Gu, self.Gw, self.Theta = Phi, Gu, Gw, Theta
        self.Qb = np.kron(np.eye(Np), q * np.eye(ny))
        self.Rb = np.kron(np.eye(Nu), r * np.eye(nu))
        self.H = Theta.T @ self.Qb @ Theta + self.Rb      # 1/2 z'Hz + g'z with the 1/2 folded into both
        self.factor = gi.GIFactor(self.H)                  # offline Cholesky + J0
        # constraint rows in dU
        Pv, Pi = voltage_polygon(), current_polygon()
        self.Pv, self.Pi = Pv, Pi
        rows_v = []                                        # u_k+j = u_prev + T_j dU
        for j in range(Nu):
            Tj = np.hstack([np.eye(2) if l <= j else np.zeros((2, 2)) for l in range(Nu)])
            rows_v.append(Pv @ Tj)
        self.Wv = np.vstack(rows_v)                        # (6 Nu, 2 Nu)
        self.Wi = np.vstack([Pi @ Theta[(i - 1) * 2:i * 2] for i in range(1, Np + 1)])   # (3 Np, 2 Nu)
        self.W = np.vstack([self.Wv, self.Wi])
        # steady-state Kalman filter for [i_d, i_q] (A at w = 0)
        sv = sigma_v if sigma_v is not None else max(2.0, cfg.sensors.adc_noise_lsb) * cfg.sensors.adc_amps_per_lsb
        A2 = A[:2, :2]
        P = solve_discrete_are(A2.T, np.eye(2), sigma_w ** 2 * np.eye(2), sv ** 2 * np.eye(2))
        self.K_kf = P @ np.linalg.inv(P + sv ** 2 * np.eye(2))
        self.kalman = kalman
        self.delay_comp = delay_comp
        self.reset()

    def reset(self) -> None:
        super().reset()
        self.xhat = None
        self.iters = []
        self.active_max = 0
        self.status_bad = 0

    def _kf(self, y: np.ndarray, w: float) -> np.ndarray:
        """Steady-state Kalman filter on the currents (predict with the voltage that acted over the period)."""
        if self.xhat is None or not self.kalman:
            self.xhat = y.copy()
            return self.xhat
        m = self.motor
        Ts, b = self.Ts, self.beta
        u_eff = b * self.u_hist[1] + (1 - b) * self.u_hist[0]   # u_k-2 acted for beta Ts, u_k-1 for the rest
        x = self.xhat
        xp = np.array([x[0] + Ts / m.Ld * (u_eff[0] - m.R * x[0] + w * m.Lq * x[1]),
                       x[1] + Ts / m.Lq * (u_eff[1] - m.R * x[1] - w * (m.Ld * x[0] + m.psi))])
        self.xhat = xp + self.K_kf @ (y - xp)
        self.ops.mul += 12 + 4; self.ops.add += 10 + 6
        return self.xhat

    def _advance(self, x: np.ndarray, w: float) -> np.ndarray:
        """Move the state estimate by the output delay (half a PWM period) with u_k-1 (model-based)."""
        m = self.motor
        td = self.beta * self.Ts
        u = self.u_hist[0]
        self.ops.mul += 10; self.ops.add += 8
        return np.array([x[0] + td / m.Ld * (u[0] - m.R * x[0] + w * m.Lq * x[1]),
                         x[1] + td / m.Lq * (u[1] - m.R * x[1] - w * (m.Ld * x[0] + m.psi))])

    def qp(self, x2: np.ndarray, w: float, r: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """g and b of 002 eq. 11 for the current state (H, W constant)."""
        x = np.array([x2[0], x2[1], w * x2[0], w * x2[1]])
        free = self.Phi @ x + self.Gu @ self.u_dq + self.Gw * w           # prediction with dU = 0
        Rr = np.tile(r, self.Np)
        g = self.Theta.T @ (self.Qb @ (free - Rr))
        n, ny = self.H.shape[0], 2 * self.Np
        self.ops.mul += 2
        self.ops.matvec(ny, 4); self.ops.matvec(ny, 2); self.ops.axpy(ny); self.ops.vadd(ny)
        self.ops.vadd(ny); self.ops.vmul(ny); self.ops.matvec(n, ny)
        Vmax, Imax = self.u_max, self.i_max
        bv = np.tile(Vmax - self.Pv @ self.u_dq, self.Nu)
        fi = free.reshape(self.Np, 2)
        bi = (Imax - fi @ self.Pi.T).reshape(-1)
        self.ops.matvec(6, 2); self.ops.vadd(6); self.ops.matvec(3 * self.Np, 2); self.ops.vadd(3 * self.Np)
        return g, np.concatenate([bv, bi]), free

    def step(self, meas) -> np.ndarray:
        self.begin()
        w = self.speed(meas)
        r, _ = self.refs(meas)
        y = np.array([meas.i_d, meas.i_q])
        x = self._kf(y, w)
        if self.delay_comp:
            x = self._advance(x, w)
        g, b, _ = self.qp(x, w, r)
        res = gi.solve(self.H, g, self.W, b, factor=self.factor, ops=self.ops)
        W_used, b_used = self.W, b
        if not res.optimal:
            # current polygon unreachable within the horizon: keep the voltage polygon only
            self.status_bad += 1
            nv = self.Wv.shape[0]
            W_used, b_used = self.Wv, b[:nv]
            res = gi.solve(self.H, g, W_used, b_used, factor=self.factor, ops=self.ops)
        self.iters.append(res.iterations)
        self.active_max = max(self.active_max, len(res.active))
        du = res.z[:2]
        u = self.u_dq + du
        self.ops.vadd(2)
        ul, sat = self.limit(u)        # never active when the QP is solved (polygon inside the circle)
        self.applied(ul)
        self.u_dq = ul
        self.last_qp = (g, b_used, res, W_used)     # the QP actually solved (for the solver tests)
        self.end()
        return ul
