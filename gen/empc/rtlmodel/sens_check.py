"""Cycle-exact model of ``rtl/sens_check.v``: HALL-vs-encoder plausibility, encoder line break.

1. Angle: j = sector of the encoder angle, floor(6 * ((theta_hi - hall_off_hi) mod 64) / 64)
   with the RTL's integer boundaries 11, 22, 32, 43, 54 (6-bit angles), registered together
   with the HALL sector and (theta_valid and hall_valid); hall_enc one clock later when the
   circular distance of (j + 1) and the HALL sector is 2 or 3.
2. HALL edges (hall_change, hall_valid, a reference taken): dq = pos[DW-1:QS] - pos_ref
   ((DW-QS)-bit, signed, units of 2^QS counts), step = (sector - s_last) mod 6:
     step not 1 or 5                                  -> hall_enc
     +1 with dq < -S_LO, or -1 with dq >= S_LO         -> hall_enc
     same direction as the previous step (+1/+1, -1/-1):
       +1: dq < S_LO  (-1: dq >= -S_LO)               -> enc_break
       +1: dq >= S_HI  (-1: dq < -S_HI)               -> hall_enc
   S_LO, S_HI: powers of two at or below / above half and 1.5 sector widths, in units of
   2^QS counts (default 8 and 32 units = 64 and 256 counts; a sector is 166.7 counts).
Both outputs are registered: :meth:`step` returns their values after the clock edge.
"""
from __future__ import annotations

J_BOUNDS = (11, 22, 32, 43, 54)
ANGLE_BITS = 6


def thresholds(cpr: int, p: int, qs: int = 3) -> tuple[int, int]:
    """(S_LO, S_HI) in units of 2^qs encoder counts: powers of two at or below half and at or
    above 1.5 sector widths (S = cpr / (6 p) counts), as the RTL computes them."""
    d = 12 * p * (1 << qs)
    lo_v, hi_v = cpr // d, -(-3 * cpr // d)
    lo = 1
    while lo * 2 <= lo_v:
        lo *= 2
    hi = 1
    while hi < hi_v:
        hi *= 2
    return lo, hi


def enc_sector(theta_hi: int, hall_off_hi: int) -> int:
    """0..5: the sector index of the encoder angle relative to the HALL reference (6-bit angles)."""
    rel = (theta_hi - hall_off_hi) & 0x3F
    return sum(rel >= b for b in J_BOUNDS)


def far(sector: int, j: int) -> bool:
    if not 1 <= sector <= 6:
        return False
    return ((sector - 1 - j) % 6) in (2, 3, 4)


class SensCheck:
    def __init__(self, cpr: int, p: int, dw: int = 12, qs: int = 3):
        self.s_lo, self.s_hi = thresholds(cpr, p, qs)
        self.dw, self.qs, self.uw = dw, qs, dw - qs
        assert self.s_lo >= 2 and self.s_hi < (1 << (self.uw - 2))
        self.reset()

    def reset(self) -> None:
        self.have = False
        self.s_last = 0
        self.pos_ref = 0
        self.lst_fwd = self.lst_bwd = False
        self.hall_enc = 0
        self.enc_break = 0
        self.j_r = self.s_r = self.v_r = 0

    def _signed(self, v: int) -> int:
        v &= (1 << self.uw) - 1
        return v - (1 << self.uw) if v >> (self.uw - 1) else v

    def step(self, theta_hi: int, theta_valid: int, hall_off_hi: int, sector: int, hall_valid: int,
             hall_change: int, pos_q: int) -> tuple[int, int]:
        f = self.v_r and far(self.s_r, self.j_r)
        legal = 1 <= self.s_last <= 6 and 1 <= sector <= 6
        dstep = (sector - self.s_last) % 6
        fwd, bwd = legal and dstep == 1, legal and dstep == 5
        pq = pos_q & ((1 << self.uw) - 1)        # the count bits DW-1 .. QS
        dq = self._signed(pq - self.pos_ref)
        against = (fwd and dq < -self.s_lo) or (bwd and dq >= self.s_lo)
        same = (fwd and self.lst_fwd) or (bwd and self.lst_bwd)
        short = same and (dq < self.s_lo if fwd else dq >= -self.s_lo)
        long_ = same and (dq >= self.s_hi if fwd else dq < -self.s_hi)
        ev = hall_change and hall_valid and self.have
        self.hall_enc = int(bool(f or (ev and (not (fwd or bwd) or against or long_))))
        self.j_r, self.s_r, self.v_r = enc_sector(theta_hi, hall_off_hi), sector, int(bool(theta_valid and hall_valid))
        self.enc_break = int(bool(ev and short))
        if hall_valid and (not self.have or hall_change):
            self.lst_fwd = self.have and fwd
            self.lst_bwd = self.have and bwd
            self.have = True
            self.s_last = sector
            self.pos_ref = pq
        return self.hall_enc, self.enc_break
