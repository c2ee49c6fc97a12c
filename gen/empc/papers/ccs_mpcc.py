"""Offset-free CCS-MPCC of paper 001 (sec. 6): incremental MPC, horizon 2, interior-point solver.

Model (001 eqs. 12-13, explicit Euler of eq. 7): x = [i_d, i_q],
    A = [[1 - Ts R/L_d,  Ts w L_q/L_d], [-Ts w L_d/L_q, 1 - Ts R/L_q]],  B = diag(Ts/L_d, Ts/L_q).
Incremental prediction (001 eqs. 14-15, 18b-18c), disturbance d_k (back-EMF) eliminated:
    x_{k+1} = x_k + A dx_k + B du_k,          dx_k = x_k - x_{k-1} (measured)
    x_{k+2} = x_{k+1} + A dx_{k+1} + B du_{k+1},  dx_{k+1} = A dx_k + B du_k
    u_k = u_{k-1} + du_k (001 eq. 16),  u_{k+1} = u_k + du_{k+1}
Cost (001 eq. 17), N = 2, decision xi = [du_k; du_{k+1}]:
    J = 1/2 sum_{i=0,1} (x_{k+1+i} - r_k)' Q (x_{k+1+i} - r_k) + du_{k+i}' R du_{k+i}
Constraints (001 eq. 18e-18i), all written h(xi) <= 0 and normalised to be dimensionless:
    18e  x_min <= x_{k+2} <= x_max           box on the predicted currents, +-I_max    (4 rows)
    18f/g du_min <= du_{k+j} <= du_max        +-du_max per axis                           (8 rows)
    18h  |u_{k+j}|^2 <= (u_dc/sqrt3)^2, j = 0, 1: |u|^2/U^2 - 1 <= 0 (quadratic rows)   (2 rows)
    18i  |i_{k+j+1}|^2 <= I_max^2, j = 0, 1:    |i|^2/I^2 - 1 <= 0 (quadratic rows)     (2 rows)
The circles are kept as convex quadratic constraints, as in 001 (the IPM's KKT
matrix carries the Hessian of the Lagrangian): no polygonisation.
Solver: qp/ipm.py, 001 Algorithm 1 (tau = 0.5 fixed, 4 iterations, line search
0.9 x at most 12), warm-started with the shifted previous solution [du_{k+1}; 0].
Delay compensation (common.py): x_k is the measured current moved to the
instant u_k takes effect, dx_k the increment of those compensated states.
The returned u_k is finally projected on the circle (guards the approximate
solution of the 4-iteration IPM; counted in ``projections``).
Weights are not given in 001: Q = q I (A^-2), R = r I (V^-2), chosen q = 100,
r = 10 (fast response without ringing at Ts = 100 us; the cost scale is large
against tau = 0.5 so the fixed-barrier bias stays in the mA range, see tests).
"""
from __future__ import annotations

import numpy as np

from .qp import ipm
from .qp.opcount import OpCount
from .common import CurrentLoop


class CcsMPCC(CurrentLoop):
    name = "CCS-MPCC (IPM)"

    def __init__(self, cfg, motor=None, q: float = 100.0, r: float = 10.0, du_max: float | None = None,
                 max_iter: int = 4, tau: float = 0.5, u_limit: float | None = None, delay_comp: bool = True):
        super().__init__(cfg, motor)
        self.delay_comp = delay_comp
        self.Q = q * np.eye(2)
        self.R = r * np.eye(2)
        self.du_max = du_max if du_max is not None else self.u_max
        self.max_iter = max_iter
        self.tau = tau
        self.U = u_limit if u_limit is not None else self.u_max
        self.reset()

    def reset(self) -> None:
        super().reset()
        self.x_prev = None
        self.xi_prev = np.zeros(4)
        self.iters = []
        self.fallbacks = 0
        self.projections = 0

    def model(self, w: float) -> tuple[np.ndarray, np.ndarray]:
        m = self.motor
        Ts = self.Ts
        A = np.array([[1 - Ts * m.R / m.Ld, Ts * w * m.Lq / m.Ld],
                      [-Ts * w * m.Ld / m.Lq, 1 - Ts * m.R / m.Lq]])
        B = np.diag([Ts / m.Ld, Ts / m.Lq])
        return A, B

    def problem(self, x: np.ndarray, dx: np.ndarray, u_prev: np.ndarray, r: np.ndarray, w: float,
                ops: OpCount) -> tuple[np.ndarray, np.ndarray, ipm.QuadConstraints]:
        """QP data of 001 eq. (18) in xi = [du_k; du_k+1]: H, f and the constraint rows."""
        A, B = self.model(w)
        ops.mul += 2; ops.add += 0                      # A(w): two products with w (other terms constant)
        Adx = A @ dx
        ops.matvec(2, 2)
        # x_{k+1} = a1 + M1 xi,  x_{k+2} = a2 + M2 xi
        a1 = x + Adx
        a2 = a1 + A @ Adx
        ops.vadd(2); ops.matvec(2, 2); ops.vadd(2)
        Z = np.zeros((2, 2))
        M1 = np.hstack([B, Z])
        AB = A @ B                                      # B diagonal: 4 multiplies
        ops.mul += 4
        M2 = np.hstack([B + AB, B])
        ops.add += 2
        Q, R = self.Q, self.R
        # J = 1/2 sum (a_i + M_i xi - r)' Q (a_i + M_i xi - r) + 1/2 xi' blkdiag(R, R) xi
        H = M1.T @ Q @ M1 + M2.T @ Q @ M2 + np.kron(np.eye(2), R)
        e1, e2 = a1 - r, a2 - r
        f = M1.T @ Q @ e1 + M2.T @ Q @ e2
        # H: M1'QM1 is diagonal (Q diagonal), M2'QM2 a 4x4 with structure; count dense 4x4 from 2x4 factors
        ops.matmul(4, 2, 4); ops.mul += 8; ops.add += 16 + 4
        ops.vadd(4); ops.matvec(4, 2); ops.matvec(4, 2); ops.vmul(4); ops.vadd(4)
        # --- constraints h(xi) <= 0 ---
        rows_C, rows_d, rows_P = [], [], []
        I, U, dU = self.i_max, self.U, self.du_max
        for sgn in (1.0, -1.0):                          # 18e: +-(x_{k+2}) <= I_max
            for j in range(2):
                rows_C.append(sgn * M2[j] / I)
                rows_d.append(sgn * a2[j] / I - 1.0)
                rows_P.append(None)
        for sgn in (1.0, -1.0):                          # 18f, 18g
            for j in range(4):
                c = np.zeros(4); c[j] = sgn / dU
                rows_C.append(c); rows_d.append(-1.0); rows_P.append(None)
        # 18h: u_{k+j} = u_prev + S_j xi
        S0 = np.hstack([np.eye(2), Z])
        S1 = np.hstack([np.eye(2), np.eye(2)])
        for S in (S0, S1):
            rows_C.append(2.0 * (S.T @ u_prev) / U**2)
            rows_d.append(float(u_prev @ u_prev) / U**2 - 1.0)
            rows_P.append(2.0 * (S.T @ S) / U**2)
        # 18i: |a_j + M_j xi|^2 / I^2 - 1 <= 0
        for a, M in ((a1, M1), (a2, M2)):
            rows_C.append(2.0 * (M.T @ a) / I**2)
            rows_d.append(float(a @ a) / I**2 - 1.0)
            rows_P.append(2.0 * (M.T @ M) / I**2)
        ops.mul += 8 + 4 + 6 + 6 + 8 + 16; ops.add += 8 + 6 + 6 + 4 + 8   # constraint data
        cons = ipm.QuadConstraints(np.array(rows_C), np.array(rows_d), rows_P)
        return H, f, cons

    def step(self, meas) -> np.ndarray:
        self.begin()
        w = self.speed(meas)
        r, _ = self.refs(meas)
        x = np.array([meas.i_d, meas.i_q])
        if self.delay_comp:
            x = self.compensate(x)
        dx = np.zeros(2) if self.x_prev is None else x - self.x_prev
        self.ops.vadd(2)
        self.x_prev = x
        H, f, cons = self.problem(x, dx, self.u_dq, r, w, self.ops)
        xi0 = np.concatenate([self.xi_prev[2:], np.zeros(2)])
        res = ipm.solve(H, f, cons, xi0=xi0, tau=self.tau, max_iter=self.max_iter, ops=self.ops)
        self.iters.append(res.iterations)
        self.fallbacks += res.ls_fallbacks
        self.xi_prev = res.xi
        u = self.u_dq + res.xi[:2]
        self.ops.vadd(2)
        ul, sat = self.limit(u)
        self.projections += int(sat)
        self.applied(ul)
        self.u_dq = ul
        self.end()
        return ul
