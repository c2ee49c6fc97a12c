"""Goldfarb-Idnani dual active-set QP solver (paper 002, sec. III-C, Algorithm 1).

Problem (002 eq. 11):   min_z  1/2 z' H z + z' g    s.t.   W z <= b,   H SPD.

Algorithm (Goldfarb & Idnani 1983, as summarised in 002 Algorithm 1):
  1. start at the unconstrained minimum z = -H^-1 g with an empty active set A
     (dual feasible), J = Z^-T (Cholesky H = Z Z', 002 eq. 16), R empty;
  2. pick a violated constraint p (W_p z - b_p > 0; we take the most violated);
     none -> optimal (step 3 of 002's Algorithm 1);
  4. step directions from the factors (002 eqs. 17-19): with d = J' n_p,
     primal dz = J2 J2' n_p (= G n_p, eq. 15/18), dual r = R^-1 J1' n_p (= K n_p, eq. 14/18);
  5. step lengths: full (primal) step t2 that makes constraint p active,
     partial (dual) step t1 = min over active j with r_j > 0 of u_j / r_j;
  6. t = min(t1, t2): if t2 is infinite, a dual-only step and the blocking
     constraint is dropped; if t = t2, p is added to A; else the blocking
     constraint is dropped and step 4 repeats for the same p.
Factor updates: adding a constraint uses ONE Householder reflection on the last
n - q columns of J (002 eqs. 20-22: the new column of Z^-1 W_A' enters at the end,
so one reflection restores R's triangular form); dropping one uses Givens
rotations on the upper-Hessenberg R (002 text after eq. 22; 002 Table 1 compares
both choices).  Internally constraints are written in the >= form n' z >= c with
n = -W_i, c = -b_i (the form of the original paper).

The solver counts floating-point operations (``ops``) as it goes and returns
the active set, the multipliers and the iteration count.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .opcount import OpCount


@dataclass
class GIResult:
    z: np.ndarray
    lam: np.ndarray              # multipliers, one per row of W (0 for inactive)
    active: list                 # indices of active constraints (order of entry)
    iterations: int              # number of add + drop steps
    status: str                  # "optimal", "infeasible", "max_iter"
    adds: int = 0
    drops: int = 0
    ops: OpCount = field(default_factory=OpCount)

    @property
    def optimal(self) -> bool:
        return self.status == "optimal"


class GIFactor:
    """Offline part: Cholesky factor of H and J0 = Z^-T (reused when H is constant)."""

    def __init__(self, H: np.ndarray):
        H = np.asarray(H, dtype=float)
        self.n = H.shape[0]
        self.Z = np.linalg.cholesky(H)                       # H = Z Z' (002 eq. 16)
        self.J0 = np.linalg.inv(self.Z).T                    # J = Z^-T (Q = I initially)
        self.H = H


def solve(H: np.ndarray, g: np.ndarray, W: np.ndarray, b: np.ndarray, factor: GIFactor | None = None,
          max_iter: int = 200, tol: float = 1e-10, ops: OpCount | None = None) -> GIResult:
    """Solve min 1/2 z'Hz + g'z s.t. W z <= b.

    ``factor`` reuses a precomputed Cholesky factor (and its operation count is
    then not charged: it is an offline computation when H is constant).
    ``tol``: a constraint counts as violated when W_i z - b_i > tol * (1 + |b_i|).
    """
    ops = ops if ops is not None else OpCount()
    g = np.asarray(g, dtype=float)
    W = np.atleast_2d(np.asarray(W, dtype=float))
    b = np.asarray(b, dtype=float)
    n = g.shape[0]
    m = b.shape[0]
    if factor is None:
        factor = GIFactor(H)
        ops.cholesky(n)
        for _ in range(n):                                   # Z^-1 by n triangular solves
            ops.trisolve(n)
    J = factor.J0.copy()
    R = np.zeros((n, n))
    q = 0                                                    # active constraints
    active: list[int] = []
    u = np.zeros(n)                                          # multipliers of the active set
    # unconstrained minimum z = -H^-1 g = -J J' g
    z = -(J @ (J.T @ g))
    ops.matvec(n, n); ops.matvec(n, n)
    N = -W                                                   # >= form normals (rows)
    c = -b
    scale = 1.0 + np.abs(b)
    it = adds = drops = 0
    lam_full = np.zeros(m)
    while True:
        # --- step 2: most violated constraint (s_i = n_i'z - c_i < 0 is violated) ---
        s = N @ z - c
        ops.matvec(m, n); ops.vadd(m)
        ops.cmp += m
        viol = s / scale
        if active:
            viol[active] = np.inf
        p = int(np.argmin(viol))
        if viol[p] >= -tol:
            lam_full[active] = u[:q]
            return GIResult(z, lam_full, list(active), it, "optimal", adds, drops, ops)
        np_ = N[p]
        u_plus = 0.0
        # --- steps 4-6 for this p ---
        while True:
            if it >= max_iter:
                lam_full[active] = u[:q]
                return GIResult(z, lam_full, list(active), it, "max_iter", adds, drops, ops)
            d = J.T @ np_
            ops.matvec(n, n)
            dz = J[:, q:] @ d[q:]                            # primal direction G n_p
            ops.matvec(n, n - q)
            if q:
                r = _back_substitute(R[:q, :q], d[:q])       # dual direction K n_p
                ops.trisolve(q)
            else:
                r = np.zeros(0)
            # partial step t1 (dual): blocking active constraint
            t1, l = math.inf, -1
            for j in range(q):
                ops.cmp += 1
                if r[j] > 0.0:
                    tj = u[j] / r[j]
                    ops.div += 1
                    if tj < t1:
                        t1, l = tj, j
            # full step t2 (primal)
            dz_norm2 = float(dz @ dz)
            ops.dot(n)
            if dz_norm2 > 1e-28 * (1.0 + float(np_ @ np_)):
                sp = float(np_ @ z - c[p])
                den = float(dz @ np_)
                ops.dot(n); ops.dot(n); ops.add += 1; ops.div += 1
                t2 = -sp / den
            else:
                t2 = math.inf
            t = min(t1, t2)
            it += 1
            if math.isinf(t):
                lam_full[active] = u[:q]
                return GIResult(z, lam_full, list(active), it, "infeasible", adds, drops, ops)
            if math.isinf(t2):                               # dual step only, drop the blocking constraint
                u[:q] -= t * r
                u_plus += t
                ops.axpy(q); ops.add += 1
                q = _drop(J, R, u, active, l, q, ops)
                drops += 1
                continue
            z = z + t * dz
            ops.axpy(n)
            u[:q] -= t * r
            u_plus += t
            ops.axpy(q); ops.add += 1
            if t == t2:                                      # full step: add p
                q = _add(J, R, d, q, ops)
                active.append(p)
                u[q - 1] = u_plus
                adds += 1
                break
            q = _drop(J, R, u, active, l, q, ops)            # partial step: drop l, same p
            drops += 1


def _back_substitute(R: np.ndarray, y: np.ndarray) -> np.ndarray:
    q = R.shape[0]
    x = np.zeros(q)
    for i in range(q - 1, -1, -1):
        x[i] = (y[i] - R[i, i + 1:] @ x[i + 1:]) / R[i, i]
    return x


def _add(J: np.ndarray, R: np.ndarray, d: np.ndarray, q: int, ops: OpCount) -> int:
    """Append the constraint with d = J' n to the factors by one Householder reflection (002 eqs. 20-22)."""
    n = J.shape[0]
    v = d[q:].copy()
    norm = math.sqrt(float(v @ v))
    ops.dot(n - q); ops.sqrt += 1
    if n - q > 1 and norm > 0.0:
        sigma = -norm if v[0] >= 0 else norm                 # reflection maps v to sigma e1
        v[0] -= sigma                                        # v'v = 2 norm (norm + |v0|) > 0
        ops.add += 1
        vtv = float(v @ v)
        ops.dot(n - q)
        # J2 <- J2 (I - 2 v v' / v'v)
        w = J[:, q:] @ v
        ops.matvec(n, n - q)
        beta = 2.0 / vtv
        ops.div += 1
        J[:, q:] -= np.outer(w * beta, v)
        ops.vmul(n); ops.mul += n * (n - q); ops.add += n * (n - q)
    else:
        sigma = v[0]                                         # last free column: nothing to rotate
    R[:q, q] = d[:q]
    R[q, q] = sigma
    return q + 1


def _drop(J: np.ndarray, R: np.ndarray, u: np.ndarray, active: list, l: int, q: int, ops: OpCount) -> int:
    """Remove active constraint l: delete column l of R, restore triangular form by Givens rotations."""
    n = J.shape[0]
    R[:, l:q - 1] = R[:, l + 1:q]
    R[:, q - 1] = 0.0
    u[l:q - 1] = u[l + 1:q]
    u[q - 1] = 0.0
    del active[l]
    for i in range(l, q - 1):
        a, bb = R[i, i], R[i + 1, i]
        h = math.hypot(a, bb)
        ops.mul += 2; ops.add += 1; ops.sqrt += 1
        if h == 0.0:
            continue
        cs, sn = a / h, bb / h
        ops.div += 2
        # rotate rows i, i+1 of R (columns i..q-2)
        ri = R[i, i:q - 1].copy()
        ri1 = R[i + 1, i:q - 1].copy()
        R[i, i:q - 1] = cs * ri + sn * ri1
        R[i + 1, i:q - 1] = -sn * ri + cs * ri1
        k = q - 1 - i
        ops.mul += 4 * k; ops.add += 2 * k
        R[i + 1, i] = 0.0
        # same rotation on columns i, i+1 of J
        ji = J[:, i].copy()
        ji1 = J[:, i + 1].copy()
        J[:, i] = cs * ji + sn * ji1
        J[:, i + 1] = -sn * ji + cs * ji1
        ops.mul += 4 * n; ops.add += 2 * n
    R[q - 1, :] = 0.0
    return q - 1


def kkt_residual(H, g, W, b, z, lam) -> dict:
    """KKT residuals of a candidate (z, lam) for W z <= b (lam >= 0)."""
    H = np.asarray(H, float)
    W = np.atleast_2d(np.asarray(W, float))
    stat = H @ z + g + W.T @ lam
    slack = W @ z - b
    return {"stationarity": float(np.max(np.abs(stat))) if stat.size else 0.0,
            "primal": float(max(0.0, np.max(slack))) if slack.size else 0.0,
            "dual": float(max(0.0, -np.min(lam))) if lam.size else 0.0,
            "complementarity": float(np.max(np.abs(lam * slack))) if lam.size else 0.0}
