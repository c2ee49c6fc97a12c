"""Cycle-exact model of ``rtl/sens_check.v``: HALL-vs-encoder plausibility, encoder line break.

1. Angle (every clock, theta_valid and hall_valid): j = sector of the encoder angle,
   floor(6 * ((theta_hi - hall_off_hi) mod 256) / 256) with the RTL's integer boundaries
   43, 86, 128, 171, 214; hall_enc when the circular distance of (j + 1) and the HALL sector
   is 2 or 3.
2. HALL edges (hall_change, hall_valid, a reference taken): dpos = pos - pos_ref (DW-bit,
   signed), step = (sector - s_last) mod 6:
     step not 1 or 5                                  -> hall_enc
     +1 with dpos < -S_LO, or -1 with dpos > S_LO      -> hall_enc
     same direction as the previous step (+1/+1, -1/-1):
       +1: dpos < S_LO  (-1: dpos > -S_LO)            -> enc_break
       +1: dpos > S_HI  (-1: dpos < -S_HI)            -> hall_enc
   S_LO = round(CPR / (12 P)), S_HI = round(3 CPR / (12 P)) (half and 1.5 sector widths in counts).
Both outputs are registered: :meth:`step` returns their values after the clock edge.
"""
from __future__ import annotations

J_BOUNDS = (43, 86, 128, 171, 214)


def thresholds(cpr: int, p: int) -> tuple[int, int]:
    """(S_LO, S_HI) in encoder counts, rounded as the RTL does."""
    return (cpr + 6 * p) // (12 * p), (3 * cpr + 6 * p) // (12 * p)


def enc_sector(theta_hi: int, hall_off_hi: int) -> int:
    """0..5: the sector index of the encoder angle relative to the HALL reference."""
    rel = (theta_hi - hall_off_hi) & 0xFF
    return sum(rel >= b for b in J_BOUNDS)


def far(sector: int, j: int) -> bool:
    if not 1 <= sector <= 6:
        return False
    return ((sector - 1 - j) % 6) in (2, 3, 4)


class SensCheck:
    def __init__(self, cpr: int, p: int, dw: int = 16):
        self.s_lo, self.s_hi = thresholds(cpr, p)
        self.dw = dw
        assert self.s_lo >= 1 and self.s_hi < (1 << (dw - 1))
        self.reset()

    def reset(self) -> None:
        self.have = False
        self.s_last = 0
        self.pos_ref = 0
        self.lst_fwd = self.lst_bwd = False
        self.hall_enc = 0
        self.enc_break = 0

    def _signed(self, v: int) -> int:
        v &= (1 << self.dw) - 1
        return v - (1 << self.dw) if v >> (self.dw - 1) else v

    def step(self, theta_hi: int, theta_valid: int, hall_off_hi: int, sector: int, hall_valid: int,
             hall_change: int, pos: int) -> tuple[int, int]:
        j = enc_sector(theta_hi, hall_off_hi)
        f = far(sector, j)
        dstep = ((sector + 6 - self.s_last) & 15) % 6          # 4-bit arithmetic, as the RTL
        fwd, bwd = dstep == 1, dstep == 5
        dpos = self._signed(pos - self.pos_ref)
        against = (fwd and dpos < -self.s_lo) or (bwd and dpos > self.s_lo)
        same = (fwd and self.lst_fwd) or (bwd and self.lst_bwd)
        short = same and (dpos < self.s_lo if fwd else dpos > -self.s_lo)
        long_ = same and (dpos > self.s_hi if fwd else dpos < -self.s_hi)
        ev = hall_change and hall_valid and self.have
        self.hall_enc = int(bool((theta_valid and hall_valid and f) or (ev and (not (fwd or bwd) or against or long_))))
        self.enc_break = int(bool(ev and short))
        if hall_valid and (not self.have or hall_change):
            self.lst_fwd = self.have and fwd
            self.lst_bwd = self.have and bwd
            self.have = True
            self.s_last = sector
            self.pos_ref = pos & ((1 << self.dw) - 1)
        return self.hall_enc, self.enc_break
