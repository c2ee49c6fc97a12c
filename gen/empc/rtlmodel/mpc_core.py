"""Bit-accurate model of the explicit-MPC core (rtl/mpc_core.v).

The RTL must match :func:`update` bit for bit.  The RTL reads its inputs from an input
buffer of SIG_W-bit signed words (written before ``start``, word map ``IN_*`` below,
:func:`input_words` builds it from :class:`Inputs`); every input is used at the full
SIG_W = 32 bit, so the model below is exact for any field value in the signed 32-bit
range (the writer sign-extends: i_d, i_q 18 bit, u_prev 24 bit in practice).
One update, in this order:

1. Scheduling speed: ``wn = clamp(sat18(rshift_round(omega, WS)), wn_min, wn_max)``
   (Q1.17, |wn| <= 1; the polynomials are never extrapolated beyond Omega_e).
   flag wn_clamp: wn differs from the unsaturated rshift_round(omega, WS), or the limits are
   inverted (wn_min > wn_max: wn = wn_max, the RTL's second clamp step always acts).
2. Algorithm 2 only: ``ebar[o] = satSIG(ebar_prev[o] + clamp(w_k[o] - y[o], +-ebar_lim[o]))`` (eq. 25).
   Anti-windup of the speed integral (speed task, o = 2; issue 15): the increment is 0 in an update with
   aw bit 0 set (|i_q| at the governor's hold current: :func:`aw_bits`, register IQ_HOLD, 0 = off) where
   w_k[2] - y[2] has the sign aw bit 1 (< 0 with i_q < 0, else >= 0): it would drive |i_q| further.
   flag ebar_inc: an increment was clamped or held.
3. Signal vector S (fixed index layout, see ``SIG_*``), all SIG_W-bit saturated
   (horizon m = 1..min(N, N_MAX, len(wref) - 1); all other indices up to 63 read 0):
   W_rel[m,o] = w_{k+m}[o] - (position task and o == 2 ? y[2] : 0)
   E[m,o]     = w_{k+m}[o] - y[o]
   Y[o]       = y[o], except 0 for the angle in the position task
   EBAR[o]    = ebar[o],   DX[n] = dx[n]
   (angles relative to the measured theta_k: the law is invariant to a common shift).
4. Per row i (d, q) and column j in order 0..min(ncols, MAX_COLS)-1
   (flag signal: a column reads a signal that saturated):
   a    = sat18(rshift_round(S[sig_j], c_j))                       operand (c_j >= -1: -1 = 2 S)
   h    = sat18(p1 + rshift_round(p2 * wn, 17))
   k    = sat18(p0 + rshift_round(h * wn, 17))                     gain, eq. 29
   term = sat48((k * a) << s_ij);   acc = sat48(acc + term)
5. ``du = satU(rshift_round(acc, ACC_FRAC - U_FRAC))``, ``u_raw = satU(u_prev + du)`` (eqs. 24/27).
6. Voltage limit (circle, vector scaling, never outside the circle):
   u18 = sat18(rshift_round(u_raw, U_FRAC - V_FRAC)); r = u18_d^2 + u18_q^2
   if r <= umax^2: u = u_raw
   else: normalise r = m 4^-z (m in [2^36, 2^38)), T = RSQRT[m >> 28],
         f = min((umax * T) >> (18 - z), 2^17 - 1)   (Q1.17, f <= umax/|u|)
         u = trunc0(u18 * f / 2^17) << (U_FRAC - V_FRAC)
   RSQRT[i] = floor(2^16 / sqrt((i + 1) / 1024)) uses the upper end of each bin,
   so the scaled vector is inside the circle; its magnitude is >= 0.998 umax - 2 LSB.
   The direction is kept while |u_raw| < 8192 PWM ticks (5.6x the default limit);
   beyond, the 18-bit operands saturate per component (direction error < 0.5 deg).

Saturation events are reported per kind in ``flags`` (bit names in ``FLAG_BITS``).

7. Field-weakening flags (issue 15 item 6), from the limiter's r = u18_d^2 + u18_q^2 of step 6
   (computed in every update): ``fw_hi = (r >> FW_R_SHIFT) > fw_thr[0]``,
   ``fw_lo = (r >> FW_R_SHIFT) < fw_thr[1]`` (thresholds: register FW_R2, 16 bit each).

Image fields are used as the RTL stores them (``effective``): p0, p1, p2 saturated to
18 bit, wn_min / wn_max clamped to +-OP_MAX, u_max to 0..OP_MAX, ebar_lim to 0..EBAR_LIM_MAX, ncols to MAX_COLS.
Generated images are unaffected (they are always inside these ranges).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..formats import (ACC_FRAC, ACCW, OPW, U_FRAC, U_W, V_FRAC, rshift_round, sat, wrap)

SIG_W = 32
N_MAX = 8
SIG_WREL = 0            # + 3*(m-1) + o, m = 1..N
SIG_E = 3 * N_MAX       # 24
SIG_Y = 6 * N_MAX       # 48
SIG_EBAR = SIG_Y + 3    # 51
SIG_DX = SIG_EBAR + 3   # 54
N_SIGNALS = SIG_DX + 5  # 59
N_SIG_INDEX = 64        # col_sig is 6 bit; indices N_SIGNALS..63 read 0
MAX_COLS = 64
RSQRT_BITS = 10
FW_THR_W = 16           # field-weakening thresholds (register FW_R2 hi / lo)
FW_R_SHIFT = 2 * OPW - FW_THR_W   # 20: the flags compare the top 16 bits r[35:20] of r < 2^(2 OPW)
OP_MAX = (1 << (OPW - 1)) - 1
EBAR_LIM_MAX = (1 << (SIG_W - 1)) - 1   # ebar_lim is stored clamped to this (a SIG_W-bit operand)

# input buffer word map of rtl/mpc_core.v (in_we / in_addr / in_wdata; `empc roms` writes EMPC_IN_*)
IN_Y = 0                # y[o] at IN_Y + o (i_d, i_q, speed or angle)
IN_OMEGA = 3            # scheduling speed
IN_DX = 4               # dx[n] at IN_DX + n, n = 0..4
IN_UPREV = 9            # u_prev[i] at IN_UPREV + i
IN_EBAR = 11            # ebar_prev[o] at IN_EBAR + o
IN_WREF = 16            # wref[m][o] at IN_WREF + 3 m + o, m = 0..N (N <= N_MAX: up to word 42)
IN_WORDS = 64           # buffer depth (6-bit address); other words are not read

# timing of rtl/mpc_core.v (not part of the arithmetic): start -> done cycles and boot load
LATENCY_BASE = 38       # latency = LATENCY_BASE + min(ncols, MAX_COLS)
BOOT_CYCLES = 771       # rst released -> ready (768 image words streamed through the write port)


def boot_cycles(naxes: int = 1) -> int:
    """rst released -> ready of a core with ``naxes`` axes: the boot image is streamed into every
    axis, one pass of image.DEPTH clocks each (the words above USED are not written)."""
    from .. import image
    return (naxes - 1) * image.DEPTH + BOOT_CYCLES


def latency(ncols: int) -> int:
    """Clock cycles from ``start`` to ``done`` of rtl/mpc_core.v for a bank of ``ncols`` columns
    (tb/test_mpc_core.py checks the RTL's ``latency`` output and its done cycle against it)."""
    return LATENCY_BASE + min(ncols, MAX_COLS)

FLAG_BITS = {
    "operand": 0, "gain": 1, "term": 2, "acc": 3, "du": 4, "u": 5,
    "ebar": 6, "ebar_inc": 7, "limit": 8, "wn_clamp": 9, "signal": 10,
}


def rsqrt_table() -> list[int]:
    n = 1 << RSQRT_BITS
    return [min(int(math.floor(65536.0 / math.sqrt((i + 1) / n))), OP_MAX) for i in range(n)]


RSQRT = rsqrt_table()


@dataclass
class Params:
    """One coefficient bank (what `empc roms` writes and the CPU can upload)."""
    algorithm: int
    task: str                      # "speed" | "position"
    N: int
    ws: int                        # scheduling speed right shift (image field: ws + SIG_SHIFT_BIAS)
    wn_min: int
    wn_max: int
    u_max: int                     # voltage limit, Q14.4 PWM ticks (V_FRAC)
    ebar_lim: tuple                # 3 raw clamps of the eq. 25 increments
    col_sig: list                  # per column: signal index into S
    col_shift: list                # per column: operand right shift c_j (-1 = left shift; image: c_j + bias)
    coef: list                     # [row][col] -> (p0, p1, p2, s)

    @property
    def ncols(self) -> int:
        return len(self.col_sig)


@dataclass
class Inputs:
    y: tuple                       # 3 raw outputs (i_d, i_q Q.4; w Q16.16 or theta Q32.8)
    omega: int                     # scheduling speed Q16.16 counts/Ts
    dx: tuple                      # 5 raw state increments (dtau = 0)
    wref: tuple                    # (N+1) x 3: w_k, w_{k+1}, ..., w_{k+N}
    u_prev: tuple                  # 2 x Q16.8
    ebar_prev: tuple = (0, 0, 0)
    fw_thr: tuple = (0xFFFF, 0)    # field-weakening thresholds (hi, lo) on r >> FW_R_SHIFT (FW_R2)
    aw: int = 0                    # speed-integral hold: bit 0 |i_q| at the hold current, bit 1 i_q < 0 (aw_bits)


@dataclass
class Outputs:
    u: tuple
    du: tuple
    u_raw: tuple
    ebar: tuple
    wn: int
    flags: int
    counts: dict = field(default_factory=dict)
    fw_hi: bool = False            # |u_raw| above the field-weakening band (step 7)
    fw_lo: bool = False            # |u_raw| below it


def input_words(x: Inputs, N: int | None = None) -> dict[int, int]:
    """Input-buffer words of one update: {address: signed value} (word map ``IN_*``).

    ``N``: references written, w_k .. w_{k+N} (default: all of ``x.wref``, at most N_MAX).
    Every value must fit the signed SIG_W-bit word (the writer sign-extends); the core reads
    the words from ``start`` until ``done``, so they must not change in between.
    """
    nref = len(x.wref) - 1 if N is None else N
    if not 0 <= nref <= min(N_MAX, len(x.wref) - 1):
        raise ValueError(f"N = {nref}: wref has {len(x.wref)} entries, the buffer holds {N_MAX + 1}")
    w = {IN_Y + o: x.y[o] for o in range(3)}
    w[IN_OMEGA] = x.omega
    w.update({IN_DX + n: x.dx[n] for n in range(5)})
    w.update({IN_UPREV + i: x.u_prev[i] for i in range(2)})
    w.update({IN_EBAR + o: x.ebar_prev[o] for o in range(3)})
    for m in range(nref + 1):
        w.update({IN_WREF + 3 * m + o: x.wref[m][o] for o in range(3)})
    lo, hi = -(1 << (SIG_W - 1)), (1 << (SIG_W - 1)) - 1
    for a, v in w.items():
        if not lo <= v <= hi:
            raise ValueError(f"input word {a} = {v} does not fit {SIG_W} bit")
    return w


def _count(counts: dict, name: str, hit: bool) -> None:
    if hit:
        counts[name] = counts.get(name, 0) + 1


def horizon(p: Params, x: Inputs) -> int:
    """Horizon steps the core reads: the image's N, at most N_MAX and the wref ports present."""
    return max(0, min(p.N, N_MAX, len(x.wref) - 1))


def signals(p: Params, x: Inputs, ebar: tuple, saturated: set | None = None) -> list[int]:
    """Signal vector S (64 entries, unused ones 0); indices that saturated go into ``saturated``."""
    S = [0] * N_SIG_INDEX
    pos = p.task == "position"
    y = list(x.y)

    def put(i, v):
        s = sat(v, SIG_W)
        if s != v and saturated is not None:
            saturated.add(i)
        S[i] = s

    for m in range(1, horizon(p, x) + 1):
        for o in range(3):
            w = x.wref[m][o]
            put(SIG_WREL + 3 * (m - 1) + o, w - (y[2] if (pos and o == 2) else 0))
            put(SIG_E + 3 * (m - 1) + o, w - y[o])
    for o in range(3):
        put(SIG_Y + o, 0 if (pos and o == 2) else y[o])
        put(SIG_EBAR + o, ebar[o])
    for n in range(5):
        put(SIG_DX + n, x.dx[n])
    return S


def aw_bits(i_q: int, iq_hold: int) -> int:
    """The core's aw input: bit 0 |i_q| >= 16 iq_hold (i_q Q.4, register IQ_HOLD in ADC LSB, 0 = off; the
    governor's hold comparison, rtlmodel/ctrl_seq.hold_flag, rtl/mpc_axis.v), bit 1 i_q < 0."""
    big = iq_hold > 0 and (i_q >= 16 * iq_hold or i_q < -16 * iq_hold)
    return int(big) | (int(i_q < 0) << 1)


def update(p: Params, x: Inputs) -> Outputs:
    counts: dict = {}
    # 1. scheduling speed
    wr = rshift_round(x.omega, p.ws)
    wn0 = sat(wr, OPW)
    wn0 = max(min(wn0, OP_MAX), -OP_MAX)
    lo, hi = _clamp(p.wn_min, OP_MAX), _clamp(p.wn_max, OP_MAX)
    wn = min(max(wn0, lo), hi)
    _count(counts, "wn_clamp", wn != wr or lo > hi)     # inverted limits: the max step always clamps
    # 2. aggregated error (algorithm 2)
    ebar = tuple(x.ebar_prev)
    if p.algorithm == 2:
        nb = []
        for o in range(3):
            inc = x.wref[0][o] - x.y[o]
            lim = min(p.ebar_lim[o], EBAR_LIM_MAX)
            inc_c = min(max(inc, -lim), lim)
            held = o == 2 and p.task == "speed" and bool(x.aw & 1) and (inc < 0) == bool(x.aw & 2)
            if held:
                inc_c = 0
            _count(counts, "ebar_inc", inc_c != inc or held)
            v = x.ebar_prev[o] + inc_c
            s = sat(v, SIG_W)
            _count(counts, "ebar", s != v)
            nb.append(s)
        ebar = tuple(nb)
    # 3./4. signals and the polynomial-gain MAC
    sat_sig: set = set()
    S = signals(p, x, ebar, sat_sig)
    ncols = min(p.ncols, MAX_COLS)
    du, u_raw = [], []
    for i in range(2):
        acc = 0
        for j in range(ncols):
            if i == 0:
                _count(counts, "signal", p.col_sig[j] in sat_sig)
            a0 = rshift_round(S[p.col_sig[j]], p.col_shift[j])
            a = sat(a0, OPW)
            _count(counts, "operand", a != a0)
            p0, p1, p2, s = p.coef[i][j]
            p0, p1, p2 = sat(p0, OPW), sat(p1, OPW), sat(p2, OPW)
            h0 = p1 + rshift_round(p2 * wn, OPW - 1)
            h = sat(h0, OPW)
            k0 = p0 + rshift_round(h * wn, OPW - 1)
            k = sat(k0, OPW)
            _count(counts, "gain", h != h0 or k != k0)
            t0 = (k * a) << s
            t = sat(t0, ACCW)
            _count(counts, "term", t != t0)
            acc0 = acc + t
            acc = sat(acc0, ACCW)
            _count(counts, "acc", acc != acc0)
        d0 = rshift_round(acc, ACC_FRAC - U_FRAC)
        d = sat(d0, U_W)
        _count(counts, "du", d != d0)
        u0 = x.u_prev[i] + d
        u = sat(u0, U_W)
        _count(counts, "u", u != u0)
        du.append(d)
        u_raw.append(u)
    # 6. voltage limit
    u_out, limited = limit_circle(u_raw, min(max(p.u_max, 0), OP_MAX))
    _count(counts, "limit", limited)
    flags = 0
    for name, n in counts.items():
        if n:
            flags |= 1 << FLAG_BITS[name]
    # 7. field-weakening flags
    rt = voltage_r(u_raw) >> FW_R_SHIFT
    return Outputs(tuple(u_out), tuple(du), tuple(u_raw), ebar, wn, flags, counts,
                   fw_hi=rt > x.fw_thr[0], fw_lo=rt < x.fw_thr[1])


def voltage_r(u_raw) -> int:
    """r = u18_d^2 + u18_q^2 of the limiter (step 6), 0 <= r < 2^36."""
    sh = U_FRAC - V_FRAC
    u18 = [sat(rshift_round(v, sh), OPW) for v in u_raw]
    return u18[0] * u18[0] + u18[1] * u18[1]


def _clamp(v: int, lim: int) -> int:
    return max(min(v, lim), -lim)


def limit_circle(u_raw, u_max: int) -> tuple[list[int], bool]:
    """Circle limiter of step 6; ``u_max`` in 0..OP_MAX (Q14.4)."""
    sh = U_FRAC - V_FRAC
    u18 = [sat(rshift_round(v, sh), OPW) for v in u_raw]
    r = u18[0] * u18[0] + u18[1] * u18[1]
    if r <= u_max * u_max:
        return list(u_raw), False
    z = 0
    m = r
    while m < (1 << 36):
        m <<= 2
        z += 1
    T = RSQRT[m >> (38 - RSQRT_BITS)]
    f = min((u_max * T) >> (18 - z), OP_MAX)
    out = []
    for v in u18:
        prod = v * f
        q = -((-prod) >> (OPW - 1)) if prod < 0 else prod >> (OPW - 1)   # truncate toward zero
        out.append(q << sh)
    return out, True


class MxBanks:
    """The coefficient banks of rtl/mpc_core.v (NAXES axes, a bank pair each) with the image
    checker of rtl/mpc_boot.v.

    Transaction level, events in the order the RTL sees them:
      ``write(addr, word, axis)``   one CPU word into the axis's inactive bank (cfg_we, cfg_addr =
                                    {axis, addr})
      ``request(axis)``             cfg_swap[axis] (ignored before ready, i.e. never here: the model is ready)
      ``boundary(in_flight, axis)`` swap_at[axis] with no update of that axis running: its pending swap
                                    is decided; in_flight = a CPU word for that axis requested or in the
                                    registered write port in that clock (it would land in the bank being
                                    activated)
    Boot: the boot image is written into bank 0 of every axis (axis 0 first), through the checker.
    Checker (one for all axes: one upload at a time; per written word): word 0 restarts (acc = word,
    bad = word != MAGIC); any other word is in sequence iff addr = previous addr + 1 and axis =
    previous axis, header words CFG / USED / FMT must be those of the build (image.check);
    acc += word (the checksum word: -= word); upl_ok[axis] = the word is USED-1, in sequence,
    nothing bad since word 0, acc == 0; the other axes' upl_ok hold.  Any later write to the axis
    clears its upl_ok, and so does an accepted swap of it; the end of the boot clears them all.
    Control period (image CFG[23:16]): ``ppc_v[a]`` is axis a's CTRL.pwm_per_control (the core's input
    pwm_per_control; ``set_ppc``, default the boot image's period, the build's reset value); a swap is
    accepted only if the inactive bank's period is ppc_v[a], and img_ok_v[a] needs the active bank's
    period to be ppc_v[a] (in the same clock).
    State compared with the RTL, per axis a: bank_v[a], pending_v[a], upl_ok_v[a], img_ok_v[a],
    swap_refused_v[a], refused_v[a] (count); boot_ok; ``active(a)``, the Params updates of axis a use.
    """

    def __init__(self, boot_words: list[int], N: int, fmt_id: int, naxes: int = 1, ppc: int | None = None):
        from .. import image
        self._img = image
        self.N, self.fmt, self.naxes = N, fmt_id, naxes
        boot = list(boot_words[:image.USED]) + [0] * (image.DEPTH - image.USED)
        self.raw = [[list(boot), [0] * image.DEPTH] for _ in range(naxes)]
        self.acc, self.bad, self.nexp, self.nax = 0, True, 0, 0
        self.upl_ok_v = [False] * naxes
        for a in range(naxes):
            for w in range(image.USED):
                self._check(a, w, boot[w])
        self.boot_ok = self.upl_ok_v[naxes - 1]
        self.upl_ok_v = [False] * naxes
        self.bank_v = [0] * naxes
        self.pending_v = [False] * naxes
        self.swapped_v = [False] * naxes
        self.swap_refused_v = [False] * naxes
        self.refused_v = [0] * naxes
        p0 = self._params(self.raw[0][0])
        self.params_v = [[p0, None] for _ in range(naxes)]
        self.ppc_v = [image.period(boot) if ppc is None else ppc] * naxes

    def set_ppc(self, axis: int, ppc: int) -> None:
        """CTRL.pwm_per_control of ``axis`` (the core's input; axis_regs changes it only with the bridges off)."""
        self.ppc_v[axis] = ppc

    def period(self, axis: int, bank: int) -> int:
        """Control period of a bank (CFG[23:16] of the last CFG word written into it)."""
        return self._img.period(self.raw[axis][bank])

    @property
    def img_ok_v(self) -> list[bool]:
        return [(self.boot_ok or s) and self.period(a, self.bank_v[a]) == self.ppc_v[a]
                for a, s in enumerate(self.swapped_v)]

    def active(self, axis: int = 0) -> Params:
        return self.params_v[axis][self.bank_v[axis]]

    def _params(self, w: list[int]) -> Params:
        """What an update reads from a bank holding words w (the RTL decodes every word as written;
        a bank's header fields are those of the last write: a valid image wrote them all)."""
        im = self._img
        cfgw = w[im.A_CFG]
        ncols = min(cfgw & 0x7F, MAX_COLS)
        coef = [[], []]
        for i in range(2):
            for j in range(ncols):
                b = im.A_GAINS + 4 * (MAX_COLS * i + j)
                coef[i].append((wrap(w[b], 32), wrap(w[b + 1], 32), wrap(w[b + 2], 32), w[b + 3] & im.PROD_SHIFT_MASK))
        return Params(algorithm=(cfgw >> 13) & 3, task="position" if (cfgw >> 12) & 1 else "speed",
                      N=(cfgw >> 8) & 0xF, ws=im.field_shift(w[im.A_WS]), wn_min=wrap(w[im.A_WNMIN], 32),
                      wn_max=wrap(w[im.A_WNMAX], 32), u_max=w[im.A_UMAX], ebar_lim=tuple(w[im.A_EBAR + o] for o in range(3)),
                      col_sig=[w[im.A_COLS + j] & 0x3F for j in range(ncols)],
                      col_shift=[im.field_shift(w[im.A_COLS + j] >> 8) for j in range(ncols)], coef=coef)

    def _hdr_bad(self, addr: int, v: int) -> bool:
        im = self._img
        if addr == im.A_MAGIC:
            return v != im.MAGIC
        if addr == im.A_USED:
            return v != im.USED
        if addr == im.A_FMT:
            return v != self.fmt
        if addr == im.A_CFG:
            return (v >> 24 != im.LAYOUT or v & im.CFG_RESERVED or (v >> 13) & 3 not in (1, 2)
                    or (v >> 8) & 0xF != self.N or v & 0x7F > MAX_COLS)
        return False

    def _check(self, axis: int, addr: int, v: int) -> None:
        im = self._img
        hb = self._hdr_bad(addr, v)
        if addr == 0:
            self.acc, self.bad = v, hb
            self.upl_ok_v[axis] = False
        else:
            in_seq = addr == self.nexp and axis == self.nax
            acc_n = (self.acc - v if addr == im.A_CSUM else self.acc + v) & 0xFFFFFFFF
            self.upl_ok_v[axis] = in_seq and not self.bad and addr == im.USED - 1 and acc_n == 0
            self.bad = self.bad or hb or not in_seq
            self.acc = acc_n
        self.nexp = (addr + 1) & 0x3FF
        self.nax = axis

    def write(self, addr: int, v: int, axis: int = 0) -> None:
        addr &= 0x3FF
        v &= 0xFFFFFFFF
        self.raw[axis][1 - self.bank_v[axis]][addr] = v
        self._check(axis, addr, v)

    def request(self, axis: int = 0) -> None:
        self.pending_v[axis] = True

    def boundary(self, in_flight: bool = False, axis: int = 0) -> bool | None:
        """Decide axis's pending swap: True accepted, False refused, None nothing pending."""
        if not self.pending_v[axis]:
            return None
        self.pending_v[axis] = False
        if self.upl_ok_v[axis] and not in_flight and self.period(axis, 1 - self.bank_v[axis]) == self.ppc_v[axis]:
            b = self.bank_v[axis] = self.bank_v[axis] ^ 1
            self.params_v[axis][b] = self._params(self.raw[axis][b])
            self.upl_ok_v[axis], self.swapped_v[axis], self.swap_refused_v[axis] = False, True, False
            return True
        self.refused_v[axis] += 1
        self.swap_refused_v[axis] = True
        return False


class Banks(MxBanks):
    """The banks of a one-axis core (NAXES = 1): MxBanks with scalar state (bank, pending, upl_ok,
    img_ok, swap_refused, refused) for axis 0."""

    def __init__(self, boot_words: list[int], N: int, fmt_id: int, ppc: int | None = None):
        super().__init__(boot_words, N, fmt_id, 1, ppc)

    bank = property(lambda self: self.bank_v[0])
    pending = property(lambda self: self.pending_v[0])
    upl_ok = property(lambda self: self.upl_ok_v[0])
    img_ok = property(lambda self: self.img_ok_v[0])
    swap_refused = property(lambda self: self.swap_refused_v[0])
    refused = property(lambda self: self.refused_v[0])
    swapped = property(lambda self: self.swapped_v[0])
    params = property(lambda self: self.params_v[0])


def inputs_from_words(words: dict[int, int], N: int) -> Inputs:
    """The Inputs an update reads from input-buffer words (the inverse of :func:`input_words`;
    missing words read 0)."""
    g = lambda a: words.get(a, 0)
    return Inputs(y=tuple(g(IN_Y + o) for o in range(3)), omega=g(IN_OMEGA), dx=tuple(g(IN_DX + n) for n in range(5)),
                  wref=tuple(tuple(g(IN_WREF + 3 * m + o) for o in range(3)) for m in range(min(N, N_MAX) + 1)),
                  u_prev=tuple(g(IN_UPREV + i) for i in range(2)), ebar_prev=tuple(g(IN_EBAR + o) for o in range(3)))


class MxCore:
    """rtl/mpc_core.v with NAXES axes, at transaction level: per axis an input buffer (64 words,
    in_addr = {axis, word}) and a bank pair (:class:`MxBanks`); ``start(axis)`` runs :func:`update`
    on that axis's words with its active bank.  Axes share nothing else: an upload, a swap or
    input words of one axis never change another axis's outputs."""

    def __init__(self, boot_words: list[int], N: int, fmt_id: int, naxes: int, ppc: int | None = None):
        self.N, self.naxes = N, naxes
        self.banks = MxBanks(boot_words, N, fmt_id, naxes, ppc)
        self.words = [dict() for _ in range(naxes)]

    def write_input(self, axis: int, word: int, value: int) -> None:
        self.words[axis][word] = wrap(value, SIG_W)

    def start(self, axis: int, fw_thr: tuple = (0xFFFF, 0), aw: int = 0) -> Outputs:
        x = inputs_from_words(self.words[axis], self.N)
        x = Inputs(x.y, x.omega, x.dx, x.wref, x.u_prev, x.ebar_prev, fw_thr=fw_thr, aw=aw)
        return update(self.banks.active(axis), x)
