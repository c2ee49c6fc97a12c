"""Step of ``xform`` (``rtl/xform.v``, mod): inverse Clarke transform (paper 000 eq. 35), bit-exact.

    u_A = u_alpha
    u_B = -u_alpha/2 + sqrt(3)/2 u_beta
    u_C = -u_alpha/2 - sqrt(3)/2 u_beta

Voltages signed ``V_W`` = 18 bit Q.4 (PWM ticks) in and out.  With
p = u_beta * K_SQ3 (K_SQ3 = round(2**K_SHIFT sqrt(3)/2) = 1816187, K_SHIFT = 21) and
h = u_alpha * 2**(K_SHIFT-1):

    u_B = sat((-h + p + 2**(K_SHIFT-1)) >> K_SHIFT)
    u_C = sat((-h - p + 2**(K_SHIFT-1)) >> K_SHIFT)

(one round-half-up each, then saturation to ``V_W``; ``sat`` if either saturated - possible
for |u| beyond the linear range, e.g. u_alpha = -2**17 with u_beta = 0).  Error against
float: <= 0.5 + 0.006 LSB.
"""
from __future__ import annotations

import math

from ...formats import V_W, sat_flag

K_SHIFT = 21
K_SQ3 = int(math.floor((1 << K_SHIFT) * math.sqrt(3.0) / 2 + 0.5))   # 1816187, 21 bit unsigned
_RND = 1 << (K_SHIFT - 1)
_HI = (1 << (V_W - 1)) - 1
_LO = -(1 << (V_W - 1))


def inv_clarke(u_alpha: int, u_beta: int) -> tuple[int, int, int, bool]:
    """(u_A, u_B, u_C, sat) exactly as ``xform`` computes them."""
    p = u_beta * K_SQ3
    h = u_alpha << (K_SHIFT - 1)
    b = (p - h + _RND) >> K_SHIFT
    c = (-p - h + _RND) >> K_SHIFT
    b, sat_b = sat_flag(b, V_W)
    c, sat_c = sat_flag(c, V_W)
    return u_alpha, b, c, sat_b or sat_c


def inv_clarke_np(u_alpha, u_beta):
    """Vectorised :func:`inv_clarke` (numpy int64 arrays)."""
    import numpy as np

    a, be = np.asarray(u_alpha, dtype=np.int64), np.asarray(u_beta, dtype=np.int64)
    p = be * K_SQ3
    h = a << (K_SHIFT - 1)
    b = (p - h + _RND) >> K_SHIFT
    c = (-p - h + _RND) >> K_SHIFT
    bc, cc = np.clip(b, _LO, _HI), np.clip(c, _LO, _HI)
    return a, bc, cc, (bc != b) | (cc != c)
