"""Step of ``xform`` (``rtl/xform.v``, front): forward Park transform (paper 000 eq. 33), bit-exact;
the shared rotation is also the inverse Park step (see :mod:`empc.rtlmodel.xform_steps.inv_park`).

    i_d =  cos * i_alpha + sin * i_beta
    i_q = -sin * i_alpha + cos * i_beta

Operands: currents signed ``I_W`` = 18 bit Q.4 (any Q format: the block is format-neutral,
output format = input format), sin/cos signed ``TRIG_W`` = 18 bit with 1.0 = 2**TRIG_FRAC
(from :mod:`empc.rtlmodel.xform_steps.sincos`).  Each output is the exact sum of the two 36-bit
products, rounded once (round half up) by TRIG_FRAC bits and saturated to 18 bit:

    y = sat((p0 +- p1 + 2**15) >> 16)

``sat`` is True if either output saturated (possible only when the input vector length
|(x0, x1)| exceeds about 2**17, e.g. both inputs near full scale at 45 degrees).

Accuracy against float math with the exact angle: |y - y_float| <= 0.5 + e_trig (|x0| + |x1|) / 2**16
LSB with e_trig < 1.0 the sin/cos error of :mod:`sincos`; <= 0.5 LSB against float math with
the same integer sin/cos.
"""
from __future__ import annotations

from ...formats import I_W, TRIG_FRAC, sat_flag

_RND = 1 << (TRIG_FRAC - 1)
_HI = (1 << (I_W - 1)) - 1
_LO = -(1 << (I_W - 1))


def _rounded(x0, x1, sin, cos, inverse: bool):
    """The two outputs before saturation: the exact two-product sums rounded once (ints or numpy int64
    arrays; the products fit easily in int64)."""
    if inverse:
        return (cos * x0 - sin * x1 + _RND) >> TRIG_FRAC, (sin * x0 + cos * x1 + _RND) >> TRIG_FRAC
    return (cos * x0 + sin * x1 + _RND) >> TRIG_FRAC, (cos * x1 - sin * x0 + _RND) >> TRIG_FRAC


def rotate(x0: int, x1: int, sin: int, cos: int, inverse: bool) -> tuple[int, int, bool]:
    """Shared arithmetic of park (inverse=False) and inv_park (inverse=True).

    forward: y0 = c x0 + s x1, y1 = -s x0 + c x1;  inverse: y0 = c x0 - s x1, y1 = s x0 + c x1.
    """
    y0, y1 = _rounded(x0, x1, sin, cos, inverse)
    y0, sat0 = sat_flag(y0, I_W)
    y1, sat1 = sat_flag(y1, I_W)
    return y0, y1, sat0 or sat1


def park(i_alpha: int, i_beta: int, sin: int, cos: int) -> tuple[int, int, bool]:
    """(i_d, i_q, sat) exactly as ``xform`` computes them."""
    return rotate(i_alpha, i_beta, sin, cos, False)


def rotate_np(x0, x1, sin, cos, inverse: bool):
    """Vectorised :func:`rotate` (numpy int64 arrays)."""
    import numpy as np

    y0, y1 = _rounded(*(np.asarray(v, dtype=np.int64) for v in (x0, x1, sin, cos)), inverse)
    a, b = np.clip(y0, _LO, _HI), np.clip(y1, _LO, _HI)
    return a, b, (a != y0) | (b != y1)


def park_np(i_alpha, i_beta, sin, cos):
    return rotate_np(i_alpha, i_beta, sin, cos, False)
