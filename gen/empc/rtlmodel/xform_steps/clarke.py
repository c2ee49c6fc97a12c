"""Step of ``xform`` (``rtl/xform.v``, front): forward Clarke transform (paper 000 eq. 32), bit-exact.

    i_alpha = i_A
    i_beta  = (i_B - i_C) / sqrt(3)

Inputs are offset-corrected ADC currents (signed integers in ADC LSB, ``IN_W`` = 13 bit
from ``adc_spi``); outputs are Q.4 in ADC LSB (``I_FRAC`` = 4), signed ``I_W`` = 18 bit:

    i_alpha = sat(i_A << I_FRAC)
    i_beta  = sat(((i_B - i_C) * K_BETA + 2**(K_SHIFT - I_FRAC - 1)) >> (K_SHIFT - I_FRAC))
    K_BETA  = round(2**K_SHIFT / sqrt(3)) = 151349, K_SHIFT = 18

(round half up, then saturate; ``sat`` is True if either output saturated, which cannot
happen for 13- or 14-bit inputs).  Error: |i_beta - 16 (i_B - i_C)/sqrt(3)| <= 0.5 + 0.05 LSB
(constant error 0.091 / 2**18 relative); i_alpha is exact.
"""
from __future__ import annotations

import math

from ...formats import I_FRAC, I_W, sat_flag

K_SHIFT = 18
K_BETA = int(math.floor((1 << K_SHIFT) / math.sqrt(3.0) + 0.5))   # 151349, 18 bit unsigned
_SH = K_SHIFT - I_FRAC
_RND = 1 << (_SH - 1)
_HI = (1 << (I_W - 1)) - 1
_LO = -(1 << (I_W - 1))


def clarke(i_a: int, i_b: int, i_c: int) -> tuple[int, int, bool]:
    """(i_alpha, i_beta, sat) exactly as ``xform`` computes them."""
    a = i_a << I_FRAC
    b = ((i_b - i_c) * K_BETA + _RND) >> _SH
    a, sat_a = sat_flag(a, I_W)
    b, sat_b = sat_flag(b, I_W)
    return a, b, sat_a or sat_b


def clarke_np(i_a, i_b, i_c):
    """Vectorised :func:`clarke` (numpy int64 arrays): returns (i_alpha, i_beta, sat)."""
    import numpy as np

    i_a, i_b, i_c = (np.asarray(x, dtype=np.int64) for x in (i_a, i_b, i_c))
    a = i_a << I_FRAC
    b = ((i_b - i_c) * K_BETA + _RND) >> _SH
    ac, bc = np.clip(a, _LO, _HI), np.clip(b, _LO, _HI)
    return ac, bc, (ac != a) | (bc != b)
