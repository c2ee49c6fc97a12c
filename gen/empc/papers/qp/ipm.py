"""Slack primal-dual interior-point method of paper 001, Algorithm 1.

Problem (001 eq. 18 in the notation of Algorithm 1):

    min_xi  J(xi) = 1/2 xi' H xi + f' xi
    s.t.    g(xi) = A_eq xi - b_eq = 0                      (n_e rows)
            h_i(xi) = 1/2 xi' P_i xi + c_i' xi + d_i <= 0    (n_i rows, P_i >= 0)

The quadratic h_i carry the circular voltage and current limits of 001 eqs.
18h/18i directly (the paper's KKT matrix uses the Hessian of the Lagrangian
H(xi, mu, lambda) = H + sum mu_i P_i, i.e. the circles are *not* polygonised).
Linear rows have P_i = 0.

Algorithm 1 (001): slack formulation h(xi) + s = 0, s >= 0, mu >= 0, with
    mu = 1, s = 1, lambda = 1 at the start (001: "Set tau = 0.5, mu = 1(n_i,1), ..."),
    fixed barrier tau (001: 0.5, after Wang & Boyd 2010), at most ``max_iter`` (001: 4)
    Newton steps on the perturbed KKT conditions
        r_T = [grad J + grad g lambda + grad h mu;  g;  h + s;  mu .* s - tau] = 0,
    a backtracking line search alpha = 1, alpha <- 0.9 alpha (at most 12 times) until
    mu + alpha dmu > 0 and s + alpha ds > 0, and the stop test ||r_T||_2 <= threshold.
The Newton system of Algorithm 1 (the 4 x 4 block KKT matrix) is solved here in
its condensed form: ds and dmu are eliminated (ds = -(h + s) - Dh dxi,
dmu = (mu/s)(Dh dxi + h + s) - (mu s - tau)/s), leaving the n_v x n_v system
    (H_L + Dh' diag(mu/s) Dh) dxi = -(r_d + Dh' [(mu/s)(h + s) - (mu s - tau)/s])
(plus the equality rows when n_e > 0).  The Newton direction is identical to the
full system's; the condensed form is what an embedded implementation solves.

Deviation from the literal Algorithm 1, stated: if 12 line-search reductions do
not restore mu, s > 0 the literal algorithm would take a step that leaves the
positive orthant and the method breaks down; we then fall back to the
fraction-to-boundary step 0.99 * alpha_max and count it (``ls_fallbacks``).

With a fixed tau the result is the point of the central path with mu_i s_i = tau,
not the exact optimum: its distance to the optimum scales with tau / (cost
scale) (quantified in the tests and the report).  ``solve(..., tau=..., max_iter=...)``
with a decreasing barrier (``tau_decrease``) converges to the exact solution and
is used to validate the implementation against reference solvers.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .opcount import OpCount


@dataclass
class QuadConstraints:
    """h(xi) = 1/2 xi' P_i xi + C xi + d  (P: list or None per row; None = linear row)."""
    C: np.ndarray                    # (n_i, n_v)
    d: np.ndarray                    # (n_i,)
    P: list = field(default_factory=list)   # per row: (n_v, n_v) or None

    def __post_init__(self):
        self.C = np.atleast_2d(np.asarray(self.C, float))
        self.d = np.asarray(self.d, float)
        if not self.P:
            self.P = [None] * self.d.shape[0]
        self.quad = [i for i, p in enumerate(self.P) if p is not None]

    @property
    def m(self) -> int:
        return self.d.shape[0]

    def value(self, xi: np.ndarray, ops: OpCount) -> np.ndarray:
        h = self.C @ xi + self.d
        ops.matvec(self.m, xi.shape[0]); ops.vadd(self.m)
        for i in self.quad:
            h[i] += 0.5 * xi @ self.P[i] @ xi
            ops.matvec(xi.shape[0], xi.shape[0]); ops.dot(xi.shape[0]); ops.mul += 1; ops.add += 1
        return h

    def jacobian(self, xi: np.ndarray, ops: OpCount) -> np.ndarray:
        D = self.C.copy()
        for i in self.quad:
            D[i] += self.P[i] @ xi
            ops.matvec(xi.shape[0], xi.shape[0]); ops.vadd(xi.shape[0])
        return D


@dataclass
class IPMResult:
    xi: np.ndarray
    mu: np.ndarray
    s: np.ndarray
    lam: np.ndarray
    iterations: int
    residual: float                  # ||r_T||_2 at the returned point (tau-perturbed KKT)
    ls_steps: int = 0                # total line-search reductions
    ls_fallbacks: int = 0            # fraction-to-boundary fallbacks (see module doc)
    ops: OpCount = field(default_factory=OpCount)


def solve(H: np.ndarray, f: np.ndarray, cons: QuadConstraints, xi0: np.ndarray | None = None,
          A_eq: np.ndarray | None = None, b_eq: np.ndarray | None = None,
          tau: float = 0.5, max_iter: int = 4, ls_factor: float = 0.9, ls_max: int = 12,
          threshold: float = 1e-6, tau_decrease: float = 1.0, tau_min: float = 1e-13,
          ops: OpCount | None = None) -> IPMResult:
    """Algorithm 1 of paper 001.  Defaults are the paper's: tau = 0.5 fixed, 4 iterations,
    line search factor 0.9 with at most 12 reductions.  ``tau_decrease`` < 1 multiplies tau
    after every iteration down to ``tau_min`` (validation mode, not the paper's setting)."""
    ops = ops if ops is not None else OpCount()
    H = np.asarray(H, float)
    f = np.asarray(f, float)
    n = f.shape[0]
    mi = cons.m
    ne = 0 if A_eq is None else np.atleast_2d(A_eq).shape[0]
    xi = np.zeros(n) if xi0 is None else np.asarray(xi0, float).copy()
    mu = np.ones(mi)
    s = np.ones(mi)
    lam = np.ones(ne)
    A_eq = None if ne == 0 else np.atleast_2d(np.asarray(A_eq, float))
    b_eq = None if ne == 0 else np.asarray(b_eq, float)
    ls_total = fallbacks = 0
    it = 0
    res_norm = math.inf
    for it in range(1, max_iter + 1):
        # --- evaluate H_L, g, h, grad g, grad h, grad J and r_T ---
        h = cons.value(xi, ops)
        Dh = cons.jacobian(xi, ops)
        gradJ = H @ xi + f
        ops.matvec(n, n); ops.vadd(n)
        r_d = gradJ + Dh.T @ mu
        ops.matvec(n, mi); ops.vadd(n)
        if ne:
            r_d = r_d + A_eq.T @ lam
            ops.matvec(n, ne); ops.vadd(n)
            r_e = A_eq @ xi - b_eq
            ops.matvec(ne, n); ops.vadd(ne)
        r_i = h + s
        r_c = mu * s - tau
        ops.vadd(mi); ops.vmul(mi); ops.vadd(mi)
        res_norm = math.sqrt(float(r_d @ r_d + r_i @ r_i + r_c @ r_c + (r_e @ r_e if ne else 0.0)))
        ops.dot(n + 2 * mi + ne); ops.sqrt += 1
        if res_norm <= threshold:
            it -= 1
            break
        # --- condensed Newton system (same direction as Algorithm 1's KKT matrix) ---
        HL = H.copy()
        for i in cons.quad:
            HL += mu[i] * cons.P[i]
            ops.mul += n * n; ops.add += n * n
        w = mu / s
        ops.vdiv(mi)
        if not np.all(np.isfinite(w)):
            # validation mode only (tau -> 1e-13): a slack underflowed to 0, the iterate is converged
            it -= 1
            break
        K = HL + Dh.T @ (w[:, None] * Dh)
        ops.mul += mi * n; ops.matmul(n, mi, n); ops.add += n * n
        rhs_i = w * r_i - r_c / s
        ops.vmul(mi); ops.vdiv(mi); ops.vadd(mi)
        rhs = -(r_d + Dh.T @ rhs_i)
        ops.matvec(n, mi); ops.vadd(n)
        if ne:
            KKT = np.block([[K, A_eq.T], [A_eq, np.zeros((ne, ne))]])
            sol = np.linalg.solve(KKT, np.concatenate([rhs, -r_e]))
            _lu_ops(ops, n + ne)
            dxi, dlam = sol[:n], sol[n:]
        else:
            try:
                Lc = np.linalg.cholesky(K)
                dxi = np.linalg.solve(Lc.T, np.linalg.solve(Lc, rhs))
                ops.cholesky(n); ops.chol_solve(n)
            except np.linalg.LinAlgError:
                try:
                    dxi = np.linalg.solve(K, rhs)
                except np.linalg.LinAlgError:   # K numerically singular (tau -> 0): keep the iterate
                    it -= 1
                    break
                _lu_ops(ops, n)
            dlam = np.zeros(0)
        Ddx = Dh @ dxi
        ops.matvec(mi, n)
        ds = -r_i - Ddx
        dmu = w * (Ddx + r_i) - r_c / s
        ops.vadd(mi); ops.vadd(mi); ops.vmul(mi); ops.vdiv(mi); ops.vadd(mi)
        # --- line search (factor 0.9, at most 12 reductions) ---
        alpha = 1.0
        ok = False
        for _ in range(ls_max):
            mt = mu + alpha * dmu
            st = s + alpha * ds
            ops.axpy(2 * mi); ops.cmp += 2 * mi
            if np.all(mt > 0) and np.all(st > 0):
                ok = True
                break
            alpha *= ls_factor
            ops.mul += 1
            ls_total += 1
        if not ok:
            amax = 1.0
            for v, dv in ((mu, dmu), (s, ds)):
                neg = dv < 0
                if np.any(neg):
                    amax = min(amax, float(np.min(-v[neg] / dv[neg])))
                    ops.vdiv(int(np.sum(neg)))
            alpha = 0.99 * amax
            fallbacks += 1
        # --- Newton step ---
        xi = xi + alpha * dxi
        mu = mu + alpha * dmu
        s = s + alpha * ds
        ops.axpy(n + 2 * mi)
        if ne:
            lam = lam + alpha * dlam
            ops.axpy(ne)
        if tau_decrease < 1.0:
            # validation mode: shrink the barrier only once near its central point (a step cut by
            # the line search means the iterate is not yet centred), so no slack collapses early
            if alpha >= 0.5:
                tau = max(tau * tau_decrease, tau_min)
    return IPMResult(xi, mu, s, lam, it, res_norm, ls_total, fallbacks, ops)


def _lu_ops(ops: OpCount, n: int) -> None:
    """LU factorisation and solve of an n x n system (2/3 n^3 + 2 n^2 flops)."""
    ops.mul += n ** 3 // 3 + n * n
    ops.add += n ** 3 // 3 + n * n
    ops.div += n * (n + 1) // 2


def linear(C: np.ndarray, d: np.ndarray) -> QuadConstraints:
    """Linear inequality rows C xi + d <= 0."""
    return QuadConstraints(C, d)


def kkt_error(H, f, cons: QuadConstraints, xi, mu, A_eq=None, b_eq=None, lam=None) -> dict:
    """Unperturbed KKT residuals (tau = 0) of (xi, mu[, lam]) and the complementarity mu' (-h)."""
    ops = OpCount()
    h = cons.value(np.asarray(xi, float), ops)
    Dh = cons.jacobian(np.asarray(xi, float), ops)
    st = H @ xi + f + Dh.T @ mu
    if A_eq is not None and lam is not None:
        st = st + np.atleast_2d(A_eq).T @ lam
    return {"stationarity": float(np.max(np.abs(st))), "primal": float(max(0.0, np.max(h))) if h.size else 0.0,
            "complementarity": float(np.max(np.abs(mu * h))) if h.size else 0.0,
            "eq": 0.0 if A_eq is None else float(np.max(np.abs(np.atleast_2d(A_eq) @ xi - b_eq)))}
