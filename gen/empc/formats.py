"""The one source of truth for the datapath's number formats.

Everything the RTL and the bit-accurate models agree on lives here: word
widths, fractional bits and raw units.  Every upper-case int here is a row of
the constant table in ``header.py``, from which ``empc roms`` writes the Verilog
header ``empc_formats.vh`` (macros ``EMPC_*``) and ``manifest.json``; RTL
modules take their parameter defaults from the header and the Python models
import this module, so the two cannot disagree.

Raw units (so the datapath converts nothing):
  current   ADC LSB (``adc_amps_per_lsb`` A)              Q14.4  in 18 bit
  angle     electrical, unsigned, 2**16 = 2 pi           16 bit
  sin/cos   1.0 = 2**16                                   Q2.16  in 18 bit
  voltage   PWM ticks at the nominal DC link              Q14.4  in 18 bit (transforms)
            (1 tick = Udc_nom / PWM_HALF_PERIOD volts)    Q16.8  in 24 bit (MPC u state)
  speed     encoder counts per control period Ts          Q16.16 in 32 bit
  position  encoder counts (multi-turn)                   Q32.8  in 40 bit
"""
from __future__ import annotations

# DSP48A1 operands and accumulator
OPW = 18            # signed multiplier operand width
PRODW = 2 * OPW     # full product width
ACCW = 48           # accumulator width

ADC_BITS = 12
I_FRAC = 4          # fractional bits of currents (ADC LSB)
I_W = 18
TRIG_FRAC = 16      # sin/cos: 1.0 = 2**16
TRIG_W = 18
ANGLE_BITS = 16
V_FRAC = 4          # voltages in the transform chain (PWM ticks)
V_W = 18
U_FRAC = 8          # MPC control u and du (PWM ticks)
U_W = 24
W_FRAC = 16         # speed, counts per Ts
W_W = 32
TH_FRAC = 8         # position, counts
TH_W = 40
POS_W = 32          # integer multi-turn encoder counter
KDC_FRAC = 16       # DC-link compensation factor Udc_nom/Udc, 1.0 = 2**16, 18 bit unsigned
KDC_W = 18

# MPC core (see rtlmodel/mpc_core.py)
COEF_W = OPW        # polynomial coefficient mantissa
WN_FRAC = OPW - 1   # normalised scheduling speed, Q1.17
SIG_SHIFT_BITS = 4  # per-column signal shift field 0..15 (enough for any 32-bit signal)
SIG_SHIFT_BIAS = 1  # signal shifts are stored biased, field = shift + 1: shift -1..14, where -1 is a
                    # left shift (a column operand a = 2 S lets a large gain keep its 18-bit mantissa
                    # one product shift lower: the 50 us designs of the BLWR233D need it; issue 16)
PROD_SHIFT_BITS = 4 # per-gain product left shift 0..15
ACC_FRAC = 32         # accumulator LSB = 2**-32 PWM ticks: small gains keep 18-bit mantissas; range +-2**15 ticks

# Speed window (control.speed_window M = 2^m; the per-axis field KACC.win = m, rtl/mx_seq.v): the sequencer
# keeps the counts of the last WIN_DEPTH control samples per axis, so m = 0..WIN_LOG2_MAX (larger KACC.win
# values act as WIN_LOG2_MAX).  The one source of the largest window: config.SPEED_WINDOWS, the sequencer
# model (rtlmodel/ctrl_seq.py) and the RTL (`EMPC_WIN_LOG2_MAX, `EMPC_WIN_DEPTH) take it from here.
# 1..7: the 3-bit field KACC.win, and the sequencer's spd = sat32(((dpos_M << 8) >>> m) << 8) is exact for m < 8.
WIN_LOG2_MAX = 4
WIN_DEPTH = 1 << WIN_LOG2_MAX   # position history per axis (rtl/mx_seq.v: one SRL16 per count bit at 16)


def sat(x: int, width: int) -> int:
    """Saturate a Python int to a signed ``width``-bit range."""
    hi = (1 << (width - 1)) - 1
    lo = -(1 << (width - 1))
    return hi if x > hi else lo if x < lo else x


def sat_flag(x: int, width: int) -> tuple[int, bool]:
    """:func:`sat` and whether it saturated."""
    y = sat(x, width)
    return y, y != x


def wrap(x, width: int):
    """Signed value of the low ``width`` bits of ``x`` (two's complement: what a ``width``-bit register
    holds, e.g. a counter difference).  Also for numpy integer arrays (``width`` < 64)."""
    half = 1 << (width - 1)
    return ((x + half) & ((1 << width) - 1)) - half


def rshift_round(x: int, n: int) -> int:
    """Arithmetic right shift with round-half-up (add 2**(n-1), then floor)."""
    if n <= 0:
        return x << (-n)
    return (x + (1 << (n - 1))) >> n

