"""Unified 5-state PMSM model for control design (paper 000, eqs. 4-8).

State x = [i_d, i_q, w_e, theta_e, tau_L], input u = [u_d, u_q] (SI units).
The cross-coupling terms w_e*i_q and w_e*i_d use the scheduling speed w_e as a
parameter (eq. 5); the back-EMF psi*w_e and the torque are linear in the state.
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import expm

NX, NU, NY = 5, 2, 3
STATE_NAMES = ("i_d", "i_q", "w_e", "theta_e", "tau_L")

C_SPEED = np.array([[1, 0, 0, 0, 0], [0, 1, 0, 0, 0], [0, 0, 1, 0, 0]], dtype=float)     # C_s, eq. 7
C_POSITION = np.array([[1, 0, 0, 0, 0], [0, 1, 0, 0, 0], [0, 0, 0, 1, 0]], dtype=float)  # C_p, eq. 7


def output_matrix(task: str) -> np.ndarray:
    if task == "speed":
        return C_SPEED
    if task == "position":
        return C_POSITION
    raise ValueError(f"task must be 'speed' or 'position', got {task!r}")


def continuous(motor, omega_e: float) -> tuple[np.ndarray, np.ndarray]:
    """A_c(w_e), B_c of eq. 5 (L_d != L_q allowed)."""
    R, Ld, Lq, psi, p, J, B = motor.R, motor.Ld, motor.Lq, motor.psi, motor.p, motor.J, motor.B
    A = np.zeros((NX, NX))
    A[0, 0] = -R / Ld
    A[0, 1] = Lq / Ld * omega_e
    A[1, 0] = -Ld / Lq * omega_e
    A[1, 1] = -R / Lq
    A[1, 2] = -psi / Lq
    A[2, 1] = 1.5 * p * p / J * psi
    A[2, 2] = -B / J
    A[2, 4] = -p / J
    A[3, 2] = 1.0
    Bc = np.zeros((NX, NU))
    Bc[0, 0] = 1.0 / Ld
    Bc[1, 1] = 1.0 / Lq
    return A, Bc


def discrete(motor, omega_e: float, Ts: float) -> tuple[np.ndarray, np.ndarray]:
    """Exact zero-order-hold A_d, B_d (eq. 8).

    A_c is singular (theta and tau_L rows), so B_d = A_c^-1 (e^{A_c Ts} - I) B_c
    cannot be used as written; the augmented matrix exponential
    expm([[A_c, B_c], [0, 0]] Ts) = [[A_d, B_d], [0, I]] gives the same result.
    """
    A, Bc = continuous(motor, omega_e)
    M = np.zeros((NX + NU, NX + NU))
    M[:NX, :NX] = A
    M[:NX, NX:] = Bc
    E = expm(M * Ts)
    return E[:NX, :NX], E[:NX, NX:]
