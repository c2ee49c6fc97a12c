"""Step of ``xform`` (``rtl/xform.v``): sin and cos of the 16-bit electrical angle, bit-exact.

Method (identical in RTL and model):

* angle ``a`` (unsigned ``ANGLE_BITS`` = 16, 2**16 = 2 pi), quadrant ``q = a >> 14``,
  position in the quadrant ``r = a & 0x3fff``;
* mirrored first-quadrant argument ``x = r`` (q even) or ``x = 2**14 - r`` (q odd),
  so ``x`` is 0..2**14 and |sin| = S(x) with S(x) = sin(x * pi/2 / 2**14);
* quarter-wave table of ``2**LUT_BITS`` = 512 nodes ``T[k] = round(2**16 sin(k pi / 1024))``
  (k = 0..512), with the differences ``D[k] = T[k+1] - T[k]`` (8 bit) for k = 0..511
  (``rtl/xform.v`` keeps the 513 nodes T[k] in its block RAM and interpolates with its MAC);
* linear interpolation ``S(x) = T[k] + ((D[k] * f + 16) >> 5)`` with ``k = x >> 5``,
  ``f = x & 31`` (round half up); ``x = 2**14`` (only possible in odd quadrants with
  r = 0) is the exact value 2**16;
* sign: negative in quadrants 2 and 3;
* cos(a) = sin(a + 2**14 mod 2**16).

Outputs are signed, 1.0 = 2**TRIG_FRAC = 2**16, range -65536..65536 (fits TRIG_W = 18),
so there is nothing to saturate.  Error bound (checked exhaustively by
``tb/test_xform.py``): |out - round(2**16 sin)| <= 1 for every angle, and
|out - 2**16 sin| < 1.0 (analytic bound 1.08 = 0.5 node rounding + 0.08 interpolation
+ 0.5 final rounding; measured maximum 0.9802); see :data:`ERR_BOUND_FLOAT`.
"""
from __future__ import annotations

import math

from ... import formats as F

ANGLE_BITS = F.ANGLE_BITS            # 16: 2**16 = 2 pi
TRIG_FRAC = F.TRIG_FRAC              # 16: 1.0 = 2**16
TRIG_W = F.TRIG_W                    # 18
QUARTER_BITS = ANGLE_BITS - 2        # 14: angle LSBs inside one quadrant
LUT_BITS = 9                         # 512 table nodes per quadrant
INTERP_BITS = QUARTER_BITS - LUT_BITS  # 5 fractional bits of the table index
DELTA_BITS = 8                       # node difference, max 201
LUT_SIZE = 1 << LUT_BITS
ONE = 1 << TRIG_FRAC

ERR_BOUND_ROUNDED = 1    # |sin_rtl - round(2**16 sin)| <= 1 LSB (all 65536 angles)
ERR_BOUND_FLOAT = 1.0    # |sin_rtl - 2**16 sin| < 1.0 LSB (all 65536 angles; measured 0.9802)


def _round_half_up(x: float) -> int:
    return int(math.floor(x + 0.5))


def node_values() -> list[int]:
    """T[k] = round(2**16 sin(k pi/2 / 512)), k = 0..512 (513 nodes, T[512] = 2**16)."""
    return [_round_half_up(ONE * math.sin(k * (math.pi / 2) / LUT_SIZE)) for k in range(LUT_SIZE + 1)]


_T = node_values()
_D = [_T[k + 1] - _T[k] for k in range(LUT_SIZE)]
assert all(0 <= d < (1 << DELTA_BITS) for d in _D) and _T[-1] == ONE


def _quarter_sin(x: int) -> int:
    """|sin| for the mirrored first-quadrant argument x = 0..2**14."""
    if x == 1 << QUARTER_BITS:
        return ONE
    k = x >> INTERP_BITS
    f = x & ((1 << INTERP_BITS) - 1)
    return _T[k] + ((_D[k] * f + (1 << (INTERP_BITS - 1))) >> INTERP_BITS)


def sin_q(angle: int) -> int:
    """sin of the 16-bit angle (taken modulo 2**16), 1.0 = 2**16."""
    a = angle & ((1 << ANGLE_BITS) - 1)
    q = a >> QUARTER_BITS
    r = a & ((1 << QUARTER_BITS) - 1)
    x = (1 << QUARTER_BITS) - r if q & 1 else r
    m = _quarter_sin(x)
    return -m if q & 2 else m


def sincos(angle: int) -> tuple[int, int]:
    """(sin, cos) of the 16-bit angle exactly as ``xform`` computes them."""
    return sin_q(angle), sin_q(angle + (1 << QUARTER_BITS))


def sincos_np(angles):
    """Vectorised :func:`sincos` for a numpy integer array: returns (sin, cos) int64 arrays."""
    import numpy as np

    t = np.asarray(_T, dtype=np.int64)
    d = np.asarray(_D + [0], dtype=np.int64)

    def s(a):
        a = np.asarray(a, dtype=np.int64) & ((1 << ANGLE_BITS) - 1)
        q = a >> QUARTER_BITS
        r = a & ((1 << QUARTER_BITS) - 1)
        x = np.where(q & 1, (1 << QUARTER_BITS) - r, r)
        k = x >> INTERP_BITS
        f = x & ((1 << INTERP_BITS) - 1)
        m = t[k] + ((d[k] * f + (1 << (INTERP_BITS - 1))) >> INTERP_BITS)
        return np.where(q & 2, -m, m)

    angles = np.asarray(angles, dtype=np.int64)
    return s(angles), s(angles + (1 << QUARTER_BITS))
