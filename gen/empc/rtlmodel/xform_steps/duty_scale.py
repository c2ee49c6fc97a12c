"""Step of ``xform`` (``rtl/xform.v``, mod): DC-link compensation and PWM compare values, bit-exact.

    cmp_X = clamp(round(v_X * kdc / 2**(KDC_FRAC + V_FRAC)), 0, half_period)

v_X: phase voltage after min-subtraction, signed ``V_W`` = 18 bit Q.4 in PWM ticks at the
nominal DC link; kdc = Udc_nom / Udc_measured, unsigned 18 bit, 1.0 = 2**KDC_FRAC (0 ... 4.0);
half_period = ``PWM_HALF_PERIOD`` (config; ``EMPC_PWM_HALF_PERIOD`` = 2500 by default).
Rounding: half up ((p + 2**19) >> 20), then clamp; ``sat`` is True if any phase was clamped
(rounded value < 0 or > half_period).  Exact: |cmp - float| <= 0.5 unless clamped.
"""
from __future__ import annotations

from ...formats import KDC_FRAC, V_FRAC

SHIFT = KDC_FRAC + V_FRAC
_RND = 1 << (SHIFT - 1)


def duty_scale(v_a: int, v_b: int, v_c: int, kdc: int, half_period: int) -> tuple[int, int, int, bool]:
    """(cmp_A, cmp_B, cmp_C, sat) exactly as ``xform`` computes them."""
    out = []
    sat = False
    for v in (v_a, v_b, v_c):
        r = (v * kdc + _RND) >> SHIFT
        if r < 0:
            r, sat = 0, True
        elif r > half_period:
            r, sat = half_period, True
        out.append(r)
    return out[0], out[1], out[2], sat


def duty_scale_np(v_a, v_b, v_c, kdc, half_period: int):
    """Vectorised :func:`duty_scale` (numpy int64 arrays, kdc scalar or array)."""
    import numpy as np

    v = np.stack([np.asarray(x, dtype=np.int64) for x in (v_a, v_b, v_c)])
    r = (v * np.asarray(kdc, dtype=np.int64) + _RND) >> SHIFT
    rc = np.clip(r, 0, half_period)
    return rc[0], rc[1], rc[2], (rc != r).any(axis=0)
