"""Step of ``xform`` (``rtl/xform.v``, mod): inverse Park transform (paper 000 eq. 34), bit-exact.

    u_alpha = cos * u_d - sin * u_q
    u_beta  = sin * u_d + cos * u_q

Voltages signed ``V_W`` = 18 bit Q.4 in PWM ticks, sin/cos 1.0 = 2**16; one rounding
(half up) of the exact two-product sum by 16 bits, then saturation to 18 bit (``sat``).
Same arithmetic as :func:`empc.rtlmodel.xform_steps.park.rotate` with ``inverse=True``.
"""
from __future__ import annotations

from .park import rotate, rotate_np


def inv_park(u_d: int, u_q: int, sin: int, cos: int) -> tuple[int, int, bool]:
    """(u_alpha, u_beta, sat) exactly as ``xform`` computes them."""
    return rotate(u_d, u_q, sin, cos, True)


def inv_park_np(u_d, u_q, sin, cos):
    return rotate_np(u_d, u_q, sin, cos, True)
