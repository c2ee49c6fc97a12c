"""Bit-exact model of ``rtl/pos_sense.v``: electrical angle, alignment, speed (eq. 37).

Angle of a mechanical position ``m = (pos - ref) mod cpr``::

    theta = ((m * mul + 2**(s-1)) >> s) + base      (mod 2**angle_bits)
    mul   = round(p * 2**(angle_bits + s) / cpr)    (round half up)

:func:`angle_params` picks ``s`` like the RTL (largest ``s <= 24`` with
``mul < 2**mul_w``, ``mul_w = 17`` = one DSP48A1), :func:`angle` is the
bit-exact function, :func:`angle_error_bound` the bound in LSB against the exact
``2**angle_bits * frac(p * m / cpr)``.  :class:`PosSense` is the cycle-exact
stepping model (bit-serial modular tracking, HALL/index alignment, sampling).
"""
from __future__ import annotations

from fractions import Fraction

from .. import formats as F

ANGLE_BITS = F.ANGLE_BITS
MAX_SHIFT = 24


def _mul(cpr: int, p: int, angle_bits: int, s: int) -> int:
    num = p << (angle_bits + s)
    return (2 * num + cpr) // (2 * cpr)


def angle_params(cpr: int, p: int, angle_bits: int = ANGLE_BITS, mul_w: int = 17,
                 shift: int | None = None) -> tuple[int, int]:
    """(mul, s) as the RTL computes them; ``shift=None`` is the RTL's automatic choice."""
    if shift is None or shift < 0:
        shift = 0
        for s in range(MAX_SHIFT + 1):
            if _mul(cpr, p, angle_bits, s) < (1 << mul_w):
                shift = s
    return _mul(cpr, p, angle_bits, shift), shift


def angle(m: int, cpr: int, p: int, base: int = 0, angle_bits: int = ANGLE_BITS,
          mul_w: int = 17, shift: int | None = None) -> int:
    """Bit-exact electrical angle of mechanical position ``m`` (any int, reduced mod cpr)."""
    mul, s = angle_params(cpr, p, angle_bits, mul_w, shift)
    m %= cpr
    half = (1 << (s - 1)) if s > 0 else 0
    return (((m * mul + half) >> s) + base) & ((1 << angle_bits) - 1)


def angle_exact(m: int, cpr: int, p: int, base: int = 0, angle_bits: int = ANGLE_BITS) -> Fraction:
    """Exact angle 2**angle_bits * frac(p*m/cpr) + base, as a Fraction in [0, 2**angle_bits)."""
    full = 1 << angle_bits
    x = Fraction(full * ((p * m) % cpr), cpr) + base
    return x % full


def angle_error_bound(cpr: int, p: int, angle_bits: int = ANGLE_BITS, mul_w: int = 17,
                      shift: int | None = None) -> float:
    """Bound on |angle - angle_exact| in LSB: 0.5 + (cpr-1)*|mul - p*2**(ab+s)/cpr| / 2**s."""
    mul, s = angle_params(cpr, p, angle_bits, mul_w, shift)
    eps = abs(Fraction(mul) - Fraction(p << (angle_bits + s), cpr))
    return float((Fraction(1, 2) if s > 0 else 1) + (cpr - 1) * eps / (1 << s))


def angle_error(a: int, m: int, cpr: int, p: int, base: int = 0, angle_bits: int = ANGLE_BITS) -> float:
    """Signed circular difference a - angle_exact(m) in LSB."""
    full = 1 << angle_bits
    d = (Fraction(a) - angle_exact(m, cpr, p, base, angle_bits)) % full
    if d >= full // 2:
        d -= full
    return float(d)


def hall_angle(k: int, angle_bits: int = ANGLE_BITS) -> int:
    """round(k * 2**angle_bits / 12) mod 2**angle_bits (k = 0..11: sector edges and centres)."""
    return ((k << angle_bits) + 6) // 12 & ((1 << angle_bits) - 1)


def sector_start(s: int, angle_bits: int = ANGLE_BITS) -> int:
    return hall_angle(2 * s - 2, angle_bits)


def sector_centre(s: int, angle_bits: int = ANGLE_BITS) -> int:
    return hall_angle(2 * s - 1, angle_bits)


def sector_end(s: int, angle_bits: int = ANGLE_BITS) -> int:
    return hall_angle((2 * s) % 12, angle_bits)


def _next_sector(s: int) -> int:
    return 1 if s == 6 else s + 1


class PosSense:
    """Cycle-exact model of one ``pos_sense``; :meth:`step` is one rising clock edge.

    Inputs of :meth:`step` are the values present before the edge; afterwards
    the attributes hold the registered outputs: ``theta``, ``valid``,
    ``aligned``, ``pos_mod``, ``speed`` (unsigned pos_w pattern), ``speed_q``
    (unsigned w_w pattern), ``speed_sat``, ``pos_at_sample``,
    ``theta_at_sample``, ``sample_valid``.
    """

    OUTPUTS = ("theta", "valid", "aligned", "pos_mod", "speed", "speed_q", "speed_sat",
               "pos_at_sample", "theta_at_sample", "sample_valid")

    def __init__(self, cpr: int, p: int, pos_w: int = F.POS_W, angle_bits: int = ANGLE_BITS,
                 mul_w: int = 17, shift: int | None = None, w_w: int = F.W_W, w_frac: int = F.W_FRAC,
                 realign: bool = False):
        self.cpr, self.p, self.pos_w, self.ab = cpr, p, pos_w, angle_bits
        self.realign = bool(realign)
        self.w_w, self.w_frac = w_w, w_frac
        self.mul, self.s = angle_params(cpr, p, angle_bits, mul_w, shift)
        self.reset()

    def reset(self) -> None:
        self.last_pos = 0
        self.r = 0          # signed
        self.k = 0          # weight 2**k of r's bit 0
        self.m = 0
        self.busy = 0
        self.al = 0
        self.rel_cal = 0    # not aligned, base_rel relative to cal_offset (after align_clear)
        self.hall_init = 0
        self.last_sector = 0
        self.base_rel = 0
        self.prod = 0
        self.base_d = 0
        self.v1 = 0
        self.al1 = 0
        self.theta = 0
        self.valid = 0
        self.aligned = 0
        self.speed = 0
        self.speed_q = 0
        self.speed_sat = 0
        self.pos_at_sample = 0
        self.theta_at_sample = 0
        self.sample_valid = 0
        self.have_prev = 0

    @property
    def pos_mod(self) -> int:
        return self.m

    def outputs(self) -> dict:
        return {k: getattr(self, k) for k in self.OUTPUTS}

    def step(self, pos: int, index_event: int = 0, index_pos: int = 0, hall_sector: int = 0,
             hall_valid: int = 0, hall_change: int = 0, cal_offset: int = 0, hall_offset: int = 0,
             align_clear: int = 0, sample: int = 0) -> "PosSense":
        pw, amask = self.pos_w, (1 << self.ab) - 1
        pmask = (1 << pw) - 1
        pos &= pmask
        index_pos &= pmask
        cpr = self.cpr
        # ---- next state of the tracker / alignment (from pre-edge values) ----
        ev_hall_init = (not self.al) and (not self.hall_init) and hall_valid
        ev_hall_chg = (not self.al) and self.hall_init and hall_valid and hall_change
        ev_index = index_event and ((not self.al) or align_clear or self.realign)
        ev_hall = ev_hall_init or ev_hall_chg
        ev_any = ev_index or ev_hall
        m, last_pos, r, k, busy = self.m, self.last_pos, self.r, self.k, self.busy
        # d: new counts, or at an index event the lag pos - index_pos (m restarts at the index)
        d = (pos - (index_pos if ev_index else self.last_pos)) & pmask
        load = (not self.busy) or ev_any
        if load:
            last_pos, r, k = pos, F.wrap(d, pw), 0
        else:
            r, k = self.r >> 1, self.k + 1
        if ev_any:
            m = 0
        elif self.busy and (self.r & 1):
            step = -(1 << self.k) if self.r == -1 else (1 << self.k)
            m = (self.m + step) % cpr
        if ev_hall and not ev_index:
            busy = 0
        elif load:
            busy = int(d != 0)
        elif self.r in (0, 1, -1):          # r >> 1 == 0, or remainder -1: last bit
            busy = 0
        al, base_rel, rel_cal = self.al, self.base_rel, self.rel_cal
        if ev_index:
            al, base_rel = 1, 0
        elif align_clear and self.al:
            al, rel_cal, base_rel = 0, 1, 0
        elif ev_hall:
            s = hall_sector
            rel_cal = 0
            if ev_hall_init:
                base_rel = sector_centre(s, self.ab)
            elif s == _next_sector(self.last_sector):
                base_rel = sector_start(s, self.ab)
            elif self.last_sector == _next_sector(s):
                base_rel = sector_end(s, self.ab)
            else:
                base_rel = sector_centre(s, self.ab)
        hall_init, last_sector = self.hall_init, self.last_sector
        if hall_valid and ((not self.hall_init) or hall_change):
            hall_init, last_sector = 1, hall_sector
        # ---- angle pipeline ----
        half = (1 << (self.s - 1)) if self.s > 0 else 0
        theta = ((self.prod >> self.s) + self.base_d) & amask
        prod = self.m * self.mul + half
        base_d = (self.base_rel + (cal_offset if (self.al or self.rel_cal) else hall_offset)) & amask
        v1 = int(bool(self.al or self.hall_init))
        valid, aligned, al1 = self.v1, self.al1, self.al
        # ---- sampling ----
        sample_valid = int(bool(sample))
        if sample:
            diff = (pos - self.pos_at_sample) & pmask
            if self.have_prev:
                ds = F.wrap(diff, pw)
                q, sat = F.sat_flag(ds << self.w_frac, self.w_w)
                self.speed_sat = int(sat)
                self.speed_q = q & ((1 << self.w_w) - 1)
                self.speed = diff
            else:
                self.speed, self.speed_q, self.speed_sat = 0, 0, 0
            self.have_prev = 1
            self.pos_at_sample = pos
            self.theta_at_sample = self.theta
        self.sample_valid = sample_valid
        # ---- commit ----
        self.m, self.last_pos, self.r, self.k, self.busy = m, last_pos, r, k, busy
        self.al, self.base_rel, self.rel_cal = al, base_rel, rel_cal
        self.hall_init, self.last_sector = hall_init, last_sector
        self.prod, self.base_d, self.v1, self.al1 = prod, base_d, v1, al1
        self.theta, self.valid, self.aligned = theta, valid, aligned
        return self
