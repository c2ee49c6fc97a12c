"""Coefficient image: the 32-bit word layout of one coefficient bank.

The same image is the boot ROM ($readmemh, loaded into the core at reset) and
what the CPU uploads through the register bus to swap tunings at run time.
Addresses (words):
  0x000 magic 'EMPC'
  0x001 {layout[31:24], algorithm[14:13], task[12] (1 = position), N[11:8], ncols[6:0]}
  0x002 ws (scheduling speed shift, < 2^SIG_SHIFT_BITS)   0x003 wn_min    0x004 wn_max
  0x005 u_max (Q14.4 PWM ticks)          0x006..0x008 ebar_lim[0..2]
  0x009 number of used words             0x00a checksum (sum of words 0..0x2ff except 0x00a, mod 2^32)
  0x040 + j            column j: {shift[11:8], sig[5:0]}  (shift < 2^SIG_SHIFT_BITS; higher bits ignored)
  0x100 + 4(64 i + j)  gain (row i, column j): p0, p1, p2 (sign-extended 18 bit), product shift
"""
from __future__ import annotations

from pathlib import Path

from . import formats as F
from .rtlmodel import mpc_core as core

MAGIC = 0x454D5043
LAYOUT = 1
DEPTH = 1024
A_MAGIC, A_CFG, A_WS, A_WNMIN, A_WNMAX, A_UMAX, A_EBAR, A_USED, A_CSUM = 0, 1, 2, 3, 4, 5, 6, 9, 10
A_COLS = 0x040
A_GAINS = 0x100
USED = A_GAINS + 4 * 2 * core.MAX_COLS    # 0x300


def _u32(v: int) -> int:
    return v & 0xFFFFFFFF


def encode(p: core.Params) -> list[int]:
    if p.ncols > core.MAX_COLS:
        raise ValueError(f"{p.ncols} columns exceed the core's {core.MAX_COLS}")
    w = [0] * DEPTH
    w[A_MAGIC] = MAGIC
    w[A_CFG] = (LAYOUT << 24) | (p.algorithm << 13) | ((1 if p.task == "position" else 0) << 12) | (p.N << 8) | p.ncols
    if not 0 <= p.ws < (1 << F.SIG_SHIFT_BITS):
        raise ValueError(f"ws={p.ws} does not fit {F.SIG_SHIFT_BITS} bits")
    w[A_WS] = p.ws
    w[A_WNMIN] = _u32(p.wn_min)
    w[A_WNMAX] = _u32(p.wn_max)
    w[A_UMAX] = p.u_max
    for o in range(3):
        if not 0 <= p.ebar_lim[o] < (1 << 31):
            raise ValueError(f"ebar_lim[{o}]={p.ebar_lim[o]} does not fit 31 bits")
        w[A_EBAR + o] = p.ebar_lim[o]
    w[A_USED] = USED
    for j in range(p.ncols):
        if not 0 <= p.col_shift[j] < (1 << F.SIG_SHIFT_BITS):
            raise ValueError(f"column {j}: operand shift {p.col_shift[j]} does not fit {F.SIG_SHIFT_BITS} bits")
        w[A_COLS + j] = (p.col_shift[j] << 8) | p.col_sig[j]
        for i in range(2):
            p0, p1, p2, s = p.coef[i][j]
            base = A_GAINS + 4 * (core.MAX_COLS * i + j)
            w[base:base + 4] = [_u32(p0), _u32(p1), _u32(p2), s]
    w[A_CSUM] = checksum(w)
    return w


def checksum(w: list[int]) -> int:
    return sum(v for a, v in enumerate(w[:USED]) if a != A_CSUM) & 0xFFFFFFFF


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
            coef[i].append((F.wrap(w[base], 32), F.wrap(w[base + 1], 32), F.wrap(w[base + 2], 32), w[base + 3] & 0xF))
    return core.Params(
        algorithm=(cfgw >> 13) & 3, task="position" if (cfgw >> 12) & 1 else "speed", N=(cfgw >> 8) & 0xF,
        ws=w[A_WS] & ((1 << F.SIG_SHIFT_BITS) - 1), wn_min=F.wrap(w[A_WNMIN], 32), wn_max=F.wrap(w[A_WNMAX], 32), u_max=w[A_UMAX],
        ebar_lim=tuple(w[A_EBAR + o] for o in range(3)),
        col_sig=[w[A_COLS + j] & 0x3F for j in range(ncols)],
        col_shift=[(w[A_COLS + j] >> 8) & ((1 << F.SIG_SHIFT_BITS) - 1) for j in range(ncols)], coef=coef)


def write_hex(words: list[int], path: Path, digits: int = 8) -> None:
    Path(path).write_text("".join(f"{v:0{digits}x}\n" for v in words))


def read_hex(path: Path) -> list[int]:
    return [int(l, 16) for l in Path(path).read_text().split()]
