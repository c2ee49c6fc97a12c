"""Explicit MPC gains of paper 000 (section III) for one scheduling speed.

Incremental prediction over the horizon N (control horizon N as well):
    dY = F dx_k + G dU,          F = [CA; CA^2; ...],  G_ji = C A^(j-i) B  (i <= j)
    Y  = 1 (x) y_k + S dY,       S = tril(1_N) (x) I_3
Algorithm 1 (cost 21):  du_k = K_e (W - 1 (x) y_k) - K_dx dx_k                 (23)
Algorithm 2 (cost 22):  ebar_k = ebar_{k-1} + w_k - y_k                         (25)
                        du_k = K_ebar ebar_k + K_WL W - K_y y_k - K_dx dx_k     (26)
with E_hat = 1 (x) ebar_k + L (W - Y), L = tril(1_N, -1) (x) I_3, K_WL = K_W (I + L) (28).
Generalisation: ``integrate`` selects which outputs carry the second integrator
(L = tril(1_N, -1) (x) D, D = diag(integrate)); the paper integrates all three.
The weights are block diagonals of Q_*^T Q_* (eq. 19).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import model

GAIN_NAMES = {1: ("K_e", "K_dx"), 2: ("K_ebar", "K_WL", "K_y", "K_dx")}


@dataclass
class Prediction:
    F: np.ndarray   # (3N, 5)
    G: np.ndarray   # (3N, 2N)
    S: np.ndarray   # (3N, 3N) cumulative sum
    L: np.ndarray   # (3N, 3N) strictly lower cumulative sum


def prediction(Ad: np.ndarray, Bd: np.ndarray, C: np.ndarray, N: int) -> Prediction:
    ny, nu = C.shape[0], Bd.shape[1]
    F = np.zeros((ny * N, Ad.shape[0]))
    G = np.zeros((ny * N, nu * N))
    Ap = np.eye(Ad.shape[0])
    powers = []
    for j in range(N):
        powers.append(Ap.copy())   # A^j
        Ap = Ap @ Ad
        F[j * ny:(j + 1) * ny] = C @ Ap
    for j in range(N):
        for i in range(j + 1):
            G[j * ny:(j + 1) * ny, i * nu:(i + 1) * nu] = C @ powers[j - i] @ Bd
    S = np.kron(np.tril(np.ones((N, N))), np.eye(ny))
    L = np.kron(np.tril(np.ones((N, N)), -1), np.eye(ny))
    return Prediction(F, G, S, L)


def weight_blocks(q_diag, N: int) -> np.ndarray:
    q = np.asarray(q_diag, dtype=float)
    return np.kron(np.eye(N), np.diag(q * q))


def gains(motor, ctrl, omega_e: float, algorithm: int | None = None, task: str | None = None,
          weights=None) -> dict[str, np.ndarray]:
    """Gains at the scheduling speed ``omega_e`` (rad/s) in SI units and the paper's signs."""
    algorithm = algorithm or ctrl.algorithm
    task = task or ctrl.task
    w = weights or ctrl.weights_for(algorithm, task)
    N = ctrl.N
    C = model.output_matrix(task)
    Ad, Bd = model.discrete(motor, omega_e, ctrl.Ts)
    P = prediction(Ad, Bd, C, N)
    Qyw = weight_blocks(w.Q_yw, N)
    Qdy = weight_blocks(w.Q_dy, N)
    Qdu = weight_blocks(w.Q_du, N)
    first = np.zeros((model.NU, model.NU * N))
    first[:, :model.NU] = np.eye(model.NU)
    ones = np.kron(np.ones((N, 1)), np.eye(model.NY))
    if algorithm == 1:
        SG, SF = P.S @ P.G, P.S @ P.F
        H = SG.T @ Qyw @ SG + P.G.T @ Qdy @ P.G + Qdu
        Hinv_first = first @ np.linalg.inv(H)
        K_e = Hinv_first @ SG.T @ Qyw
        K_dx = Hinv_first @ (SG.T @ Qyw @ SF + P.G.T @ Qdy @ P.F)
        return {"K_e": K_e, "K_dx": K_dx}
    if algorithm == 2:
        # integrated outputs (eq. 25): D selects them; the paper integrates all three
        D = np.diag(np.asarray(w.integrate, dtype=float))
        L = np.kron(np.tril(np.ones((N, N)), -1), D)
        M = np.eye(model.NY * N) + L
        MSG, MSF = M @ P.S @ P.G, M @ P.S @ P.F
        H = MSG.T @ Qyw @ MSG + P.G.T @ Qdy @ P.G + Qdu
        Hinv_first = first @ np.linalg.inv(H)
        K_W = Hinv_first @ MSG.T @ Qyw
        K_WL = K_W @ M
        return {
            "K_ebar": K_W @ ones @ D,
            "K_WL": K_WL,
            "K_y": K_WL @ ones,
            "K_dx": Hinv_first @ (MSG.T @ Qyw @ MSF + P.G.T @ Qdy @ P.F),
        }
    raise ValueError(f"algorithm must be 1 or 2, got {algorithm!r}")


def closed_loop_matrix(motor, ctrl, omega_e: float, algorithm: int | None = None, task: str | None = None,
                       g: dict | None = None) -> np.ndarray:
    """Transition matrix of the linear loop (model + law) frozen at one speed, zero references.

    The load torque (an unmeasured constant) and, in the speed task, the angle (not fed
    back) are left out: they give structural unit eigenvalues, not instability.
    Loop state z = [x_k, x_{k-1}, u_{k-1}] over the kept states, plus for algorithm 2 the
    aggregated errors the law can see (see below).
    """
    algorithm = algorithm or ctrl.algorithm
    task = task or ctrl.task
    g = g if g is not None else gains(motor, ctrl, omega_e, algorithm, task)
    keep = [0, 1, 2] if task == "speed" else [0, 1, 2, 3]
    C = model.output_matrix(task)[:, keep]
    Ad, Bd = model.discrete(motor, omega_e, ctrl.Ts)
    Ad, Bd = Ad[np.ix_(keep, keep)], Bd[keep]
    K_dx = g["K_dx"][:, keep]
    nx, nu, ny, N = len(keep), model.NU, model.NY, ctrl.N
    ones = np.kron(np.ones((N, 1)), np.eye(ny))
    # u_k = u_{k-1} + Kx x_k + Kxm x_{k-1} (+ Ke ebar_{k-1});  x_{k+1} = Ad x_k + Bd u_k
    if algorithm == 1:
        Kx = -g["K_e"] @ ones @ C - K_dx
        E_out = np.zeros((0, ny))           # no aggregated-error states
        Ke = np.zeros((nu, 0))
    else:
        # du = K_ebar ebar_k - K_y C x_k - K_dx (x_k - x_{k-1}), ebar_k = ebar_{k-1} - D C x_k.
        # Minimal ebar states: the integrated outputs themselves if at most two, otherwise
        # zeta = K_ebar ebar (2 states): the third direction is a neutral mode that changes nothing.
        Kx = -g["K_ebar"] @ C - g["K_y"] @ C - K_dx
        integ = [o for o in range(ny) if np.any(g["K_ebar"][:, o] != 0)]
        if len(integ) <= nu:
            E_out = np.eye(ny)[integ]                  # ebar_I = E_out ebar
            Ke = g["K_ebar"][:, integ]
        else:
            E_out = g["K_ebar"]                        # zeta = K_ebar ebar
            Ke = np.eye(nu)
    ne = E_out.shape[0]
    Kxm = K_dx
    n = 2 * nx + nu + ne
    sx, sxm, su, se = slice(0, nx), slice(nx, 2 * nx), slice(2 * nx, 2 * nx + nu), slice(2 * nx + nu, n)
    T = np.zeros((n, n))
    T[sx, sx] = Ad + Bd @ Kx
    T[sx, sxm] = Bd @ Kxm
    T[sx, su] = Bd
    T[sxm, sx] = np.eye(nx)
    T[su, sx] = Kx
    T[su, sxm] = Kxm
    T[su, su] = np.eye(nu)
    if ne:
        T[sx, se] = Bd @ Ke
        T[su, se] = Ke
        T[se, sx] = -E_out @ C
        T[se, se] = np.eye(ne)
    return T


def spectral_radius(motor, ctrl, omega_e: float, algorithm: int | None = None, task: str | None = None,
                    g: dict | None = None) -> float:
    T = closed_loop_matrix(motor, ctrl, omega_e, algorithm, task, g)
    return float(np.max(np.abs(np.linalg.eigvals(T))))


def ebar_step_limits(cfg, task: str) -> np.ndarray:
    """Clamp of the error increments of eq. 25 per output (SI units).

    Configured values > 0 are used as given; 0 selects the default: i_max for the
    currents, 5 % of max|Omega_e| for the speed, and the angle covered in one
    period at max|Omega_e| for the position.  Outputs that are not integrated
    (``integrate``) get 0, so their ebar stays 0 (the RTL needs nothing else).
    """
    c = cfg.control
    w_top = max(abs(c.omega_min), abs(c.omega_max))
    defaults = np.array([c.i_max, c.i_max, 0.05 * w_top if task == "speed" else w_top * c.Ts])
    w = c.weights[(2, task)] if (2, task) in c.weights else None
    clamp = np.array(w.ebar_step_max if w else (0, 0, 0), dtype=float)
    lim = np.where(clamp > 0, clamp, defaults)
    if w is not None:
        lim = lim * np.asarray(w.integrate, dtype=float)   # outputs without the integrator: ebar stays 0
    return lim
