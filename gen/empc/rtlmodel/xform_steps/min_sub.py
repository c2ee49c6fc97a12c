"""Step of ``xform`` (``rtl/xform.v``, mod): min-subtraction of the phase voltages (paper 000 eq. 36), bit-exact.

    u_min = min(u_A, u_B, u_C);  w_X = u_X - u_min   (X = A, B, C)

Voltages signed ``V_W`` = 18 bit Q.4 (PWM ticks).  The differences are exact and >= 0; they
exceed the signed 18-bit range only if the inputs span more than 2**17 - 1, in which case
they saturate to 2**17 - 1 and ``sat`` is True.
"""
from __future__ import annotations

from ...formats import V_W

_HI = (1 << (V_W - 1)) - 1


def min_sub(u_a: int, u_b: int, u_c: int) -> tuple[int, int, int, bool]:
    """(w_A, w_B, w_C, sat) exactly as ``xform`` computes them."""
    m = min(u_a, u_b, u_c)
    a, b, c = u_a - m, u_b - m, u_c - m
    sat = a > _HI or b > _HI or c > _HI
    return min(a, _HI), min(b, _HI), min(c, _HI), sat


def min_sub_np(u_a, u_b, u_c):
    """Vectorised :func:`min_sub` (numpy int64 arrays)."""
    import numpy as np

    u = np.stack([np.asarray(x, dtype=np.int64) for x in (u_a, u_b, u_c)])
    w = u - u.min(axis=0)
    wc = np.minimum(w, _HI)
    return wc[0], wc[1], wc[2], (w > _HI).any(axis=0)
