"""Coefficient image: the 32-bit word layout of one coefficient bank.

The same image is the boot ROM ($readmemh, loaded into the core at reset) and
what the CPU uploads through the register bus to swap tunings at run time.
Addresses (words):
  0x000 magic 'EMPC'
  0x001 {layout[31:24], control period[23:16] (PWM periods per control period Ts the gains were designed
        for, 1..255: CTRL.pwm_per_control of the axis that runs it), algorithm[14:13], task[12] (1 =
        position), N[11:8], ncols[6:0]}  (bits 15 and 7 reserved, 0)
  0x002 ws field (scheduling speed shift ws + SIG_SHIFT_BIAS, < 2^SIG_SHIFT_BITS)   0x003 wn_min    0x004 wn_max
  0x005 u_max (Q14.4 PWM ticks)          0x006..0x008 ebar_lim[0..2]
  0x009 number of used words             0x00a checksum (sum of words 0..0x2ff except 0x00a, mod 2^32)
  0x00b format fingerprint of the build (format_id: the constants that fix what a word means, without Ts:
        the control period is the CFG field above, so one build accepts the designs of every Ts)
  (all other words below 0x300 are 0 in a generated image and count in the checksum)
  0x040 + j            column j: {shift field[11:8], sig[5:0]}  (field = operand shift c_j + SIG_SHIFT_BIAS
                       < 2^SIG_SHIFT_BITS; higher bits ignored)
  0x100 + 4(64 i + j)  gain (row i, column j): p0, p1, p2 (sign-extended 18 bit), product shift
                       (< 2^PROD_SHIFT_BITS; higher bits ignored)
Signal shifts (ws, c_j) are stored biased: field f means rshift_round(x, f - SIG_SHIFT_BIAS), so
f = 0 is a left shift by one (SIG_SHIFT_BIAS = 1; the model's Params hold the shifts themselves).

The RTL accepts an upload (or the boot image) only as a whole: words 0..USED-1 written in
ascending order starting at word 0, with the magic, this LAYOUT, the build's N, algorithm 1
or 2, ncols <= 64, reserved CFG bits 0, USED, the build's format fingerprint and a matching
checksum (:func:`check` is the same rule in Python; rtl/mpc_boot.v the checker).  The control
period is not the checker's: it belongs to the axis (CTRL.pwm_per_control); the drivers refuse an
image whose period differs from the axis's (``check(..., pwm_per_control=)``), see docs/blocks/mpc_core.md.
"""
from __future__ import annotations

import zlib
from pathlib import Path

from . import formats as F
from .rtlmodel import mpc_core as core

MAGIC = 0x454D5043
LAYOUT = 4              # 4: control period CFG[23:16], Ts out of the fingerprint (3: biased signal shift
                        # fields; 2: format fingerprint word A_FMT; 1 had none)
DEPTH = 1024
A_MAGIC, A_CFG, A_WS, A_WNMIN, A_WNMAX, A_UMAX, A_EBAR, A_USED, A_CSUM, A_FMT = 0, 1, 2, 3, 4, 5, 6, 9, 10, 11
A_COLS = 0x040
A_GAINS = 0x100
USED = A_GAINS + 4 * 2 * core.MAX_COLS    # 0x300
CFG_PERIOD_LSB, CFG_PERIOD_BITS = 16, 8   # control period field of word A_CFG (CTRL.pwm_per_control's width)
CFG_RESERVED = (1 << 15) | (1 << 7)       # reserved CFG bits (0 in a valid image)


def _u32(v: int) -> int:
    return v & 0xFFFFFFFF


SHIFT_MIN = -F.SIG_SHIFT_BIAS                                  # signal shifts an image can hold
SHIFT_MAX = (1 << F.SIG_SHIFT_BITS) - 1 - F.SIG_SHIFT_BIAS


def shift_field(shift: int) -> int:
    """Stored field of a signal shift (ws or a column's c_j)."""
    return shift + F.SIG_SHIFT_BIAS


def field_shift(word: int) -> int:
    """Signal shift of a stored field (the low SIG_SHIFT_BITS of ``word``)."""
    return (word & ((1 << F.SIG_SHIFT_BITS) - 1)) - F.SIG_SHIFT_BIAS


PROD_SHIFT_MASK = (1 << F.PROD_SHIFT_BITS) - 1


# header constants that do not change what an image word means (the boot-image choice, the
# register reset values of the speed correction, the ADC offset and the reference governor), the
# control period (PWM_PER_CONTROL: it is the image's CFG field, checked against the axis's
# CTRL.pwm_per_control) and the fingerprint itself.  Every Ts-dependent header constant is here
# (gen/tests/test_header.py::test_format_id_ts_independent): KACC / KACC_SHIFT and the GOV_* words
# are register reset values for the build's Ts, and PWM_PER_CONTROL is Ts / PWM period.
FMT_EXCLUDE = ("BOOT_ALGORITHM", "BOOT_TASK_POSITION", "KACC", "KACC_SHIFT", "KACC_WIN", "ADC_OFFSET", "IMG_FMT_ID",
               "PWM_STAGGER_2", "PWM_STAGGER_3", "PWM_STAGGER_4",      # the carrier stagger: not the image format
               "PWM_PER_CONTROL", "GOV_EN", "GOV_KSH", "GOV_VMAX_LO", "GOV_VMAX_HI", "GOV_A_LO", "GOV_A_HI")
# units that depend on Ts (rad/s per count per Ts = rad per count / Ts: rad per count is in the
# fingerprint, Ts is the image's control period times the PWM period, both covered)
FMT_EXCLUDE_UNITS = ("rad_s_per_count_per_ts",)


def format_id(constants: dict, units: dict) -> int:
    """Format fingerprint of a build (image word A_FMT, header EMPC_IMG_FMT_ID): CRC-32 (31 bits)
    of the header constants (formats, scalings, layout, N; without FMT_EXCLUDE) and the raw-unit
    scalings (volts per PWM tick, amperes per ADC LSB, radians per count; not FMT_EXCLUDE_UNITS).
    Another weight tuning or another control period Ts of the same build keeps it (the period is
    the image's CFG field); another motor, encoder, inverter, PWM or format gives another one."""
    text = ";".join(f"{k}={int(v)}" for k, v in sorted(constants.items()) if k not in FMT_EXCLUDE)
    text += "|" + ";".join(f"{k}={float(v)!r}" for k, v in sorted(units.items()) if k not in FMT_EXCLUDE_UNITS)
    return zlib.crc32(text.encode()) & 0x7FFFFFFF


def encode(p: core.Params, fmt_id: int = 0, *, period: int) -> list[int]:
    """Image words of ``p`` for a build with format fingerprint ``fmt_id``, designed for a control
    period of ``period`` PWM periods (Config.pwm_per_control of the design)."""
    if not 1 <= period < (1 << CFG_PERIOD_BITS):
        raise ValueError(f"control period {period} PWM periods outside 1..{(1 << CFG_PERIOD_BITS) - 1}")
    if p.ncols > core.MAX_COLS:
        raise ValueError(f"{p.ncols} columns exceed the core's {core.MAX_COLS}")
    w = [0] * DEPTH
    w[A_MAGIC] = MAGIC
    w[A_CFG] = (LAYOUT << 24) | (period << CFG_PERIOD_LSB) | (p.algorithm << 13) | ((1 if p.task == "position" else 0) << 12) | (p.N << 8) | p.ncols
    if not SHIFT_MIN <= p.ws <= SHIFT_MAX:
        raise ValueError(f"ws={p.ws} outside {SHIFT_MIN}..{SHIFT_MAX}")
    w[A_WS] = shift_field(p.ws)
    w[A_WNMIN] = _u32(p.wn_min)
    w[A_WNMAX] = _u32(p.wn_max)
    w[A_UMAX] = p.u_max
    for o in range(3):
        if not 0 <= p.ebar_lim[o] < (1 << 31):
            raise ValueError(f"ebar_lim[{o}]={p.ebar_lim[o]} does not fit 31 bits")
        w[A_EBAR + o] = p.ebar_lim[o]
    w[A_USED] = USED
    w[A_FMT] = fmt_id & 0xFFFFFFFF
    for j in range(p.ncols):
        if not SHIFT_MIN <= p.col_shift[j] <= SHIFT_MAX:
            raise ValueError(f"column {j}: operand shift {p.col_shift[j]} outside {SHIFT_MIN}..{SHIFT_MAX}")
        w[A_COLS + j] = (shift_field(p.col_shift[j]) << 8) | p.col_sig[j]
        for i in range(2):
            p0, p1, p2, s = p.coef[i][j]
            if not 0 <= s <= PROD_SHIFT_MASK:
                raise ValueError(f"gain ({i}, {j}): product shift {s} outside 0..{PROD_SHIFT_MASK}")
            base = A_GAINS + 4 * (core.MAX_COLS * i + j)
            w[base:base + 4] = [_u32(p0), _u32(p1), _u32(p2), s]
    w[A_CSUM] = checksum(w)
    return w


def checksum(w: list[int]) -> int:
    return sum(v for a, v in enumerate(w[:USED]) if a != A_CSUM) & 0xFFFFFFFF


def with_period(w: list[int], period: int) -> list[int]:
    """A copy of image ``w`` marked for control period ``period`` (CFG field, checksum updated), the same
    gains: for tests that run one design at another period."""
    if not 1 <= period < (1 << CFG_PERIOD_BITS):
        raise ValueError(f"control period {period} PWM periods outside 1..{(1 << CFG_PERIOD_BITS) - 1}")
    mask = ((1 << CFG_PERIOD_BITS) - 1) << CFG_PERIOD_LSB
    out = list(w)
    out[A_CFG] = (w[A_CFG] & ~mask) | (period << CFG_PERIOD_LSB)
    out[A_CSUM] = checksum(out)
    return out


def period(w: list[int]) -> int:
    """Control period of image ``w`` in PWM periods (CFG field)."""
    return (w[A_CFG] >> CFG_PERIOD_LSB) & ((1 << CFG_PERIOD_BITS) - 1)


def check(w: list[int], N: int, fmt_id: int, pwm_per_control: int | None = None) -> list[str]:
    """Why the RTL would refuse image ``w`` uploaded in order (empty list: accepted).  The same
    rule as rtl/mpc_boot.v (header words and checksum of words 0..USED-1).  ``pwm_per_control``
    (the axis's CTRL.pwm_per_control): also refuse an image designed for another control period
    (the drivers' rule: gen/empc/driver.py, fw/empc_drv.c)."""
    out = []
    if len(w) < USED:
        out.append(f"{len(w)} words, an image has {USED}")
        return out
    cfgw = w[A_CFG]
    if w[A_MAGIC] != MAGIC:
        out.append(f"magic {w[A_MAGIC]:#x} != {MAGIC:#x}")
    if cfgw >> 24 != LAYOUT:
        out.append(f"layout {cfgw >> 24} != {LAYOUT}")
    if cfgw & CFG_RESERVED:
        out.append(f"reserved CFG bits set ({cfgw:#x})")
    if (cfgw >> 13) & 3 not in (1, 2):
        out.append(f"algorithm {(cfgw >> 13) & 3} not 1 or 2")
    if (cfgw >> 8) & 0xF != N:
        out.append(f"N {(cfgw >> 8) & 0xF} != the build's {N}")
    if cfgw & 0x7F > core.MAX_COLS:
        out.append(f"ncols {cfgw & 0x7F} > {core.MAX_COLS}")
    if w[A_USED] != USED:
        out.append(f"used words {w[A_USED]} != {USED}")
    if w[A_FMT] != fmt_id:
        out.append(f"format fingerprint {w[A_FMT]:#x} != the build's {fmt_id:#x}")
    if checksum(w) != w[A_CSUM]:
        out.append(f"checksum {w[A_CSUM]:#x} != {checksum(w):#x}")
    if pwm_per_control is not None and period(w) != pwm_per_control:
        out.append(f"control period {period(w)} PWM periods (the image's design) != the axis's "
                   f"CTRL.pwm_per_control {pwm_per_control}: gains for another Ts")
    return out


def decode(w: list[int]) -> core.Params:
    if w[A_MAGIC] != MAGIC:
        raise ValueError(f"bad magic {w[A_MAGIC]:#x}")
    cfgw = w[A_CFG]
    if cfgw >> 24 != LAYOUT:
        raise ValueError(f"image layout {cfgw >> 24} != {LAYOUT}")
    if checksum(w) != w[A_CSUM]:
        raise ValueError("image checksum mismatch")
    ncols = cfgw & 0x7F
    coef = [[], []]
    for i in range(2):
        for j in range(ncols):
            base = A_GAINS + 4 * (core.MAX_COLS * i + j)
            coef[i].append((F.wrap(w[base], 32), F.wrap(w[base + 1], 32), F.wrap(w[base + 2], 32),
                            w[base + 3] & PROD_SHIFT_MASK))
    return core.Params(
        algorithm=(cfgw >> 13) & 3, task="position" if (cfgw >> 12) & 1 else "speed", N=(cfgw >> 8) & 0xF,
        ws=field_shift(w[A_WS]), wn_min=F.wrap(w[A_WNMIN], 32), wn_max=F.wrap(w[A_WNMAX], 32), u_max=w[A_UMAX],
        ebar_lim=tuple(w[A_EBAR + o] for o in range(3)),
        col_sig=[w[A_COLS + j] & 0x3F for j in range(ncols)],
        col_shift=[field_shift(w[A_COLS + j] >> 8) for j in range(ncols)], coef=coef)


def write_hex(words: list[int], path: Path, digits: int = 8) -> None:
    Path(path).write_text("".join(f"{v:0{digits}x}\n" for v in words))


def read_hex(path: Path) -> list[int]:
    return [int(l, 16) for l in Path(path).read_text().split()]
