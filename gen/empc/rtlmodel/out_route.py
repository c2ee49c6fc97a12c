"""Cycle-exact model of ``rtl/out_route.v``: output and input routing (issue 16 item 4).

Selects (as the register fields of gen/empc/regmap.py, one integer per field):
  osel[k]      OUT_SEL code of output k: 0 = off, 1 + 3 a + p = axis a, phase p
  asel[3a+p]   ADC channel (MISO line) of axis a, phase p
  esel[a]      IRC input of axis a;  hsel[a]  HALL set of axis a
Per clock (:meth:`comb` for the combinational outputs of this clock, :meth:`step` for the edge):
  pin_hi[k], pin_lo[k] <= pair of osel[k], 0 if the code is 0 or names an axis the build lacks,
                          or the owning axis trips, or rst
  ax_miso / ax_irc_* / ax_hall: the selected line; a select beyond the build's lines reads the
                          fail-safe value (MISO 1, IRC 0, HALL 000)
  mapped               a scan of osel, one output per clock, restarted (mapped = 0) by osel_wr or rst
  bad_sel <= an input select of an axis of this build names a line the build lacks (0 in rst); an
                          OUT_SEL code naming a missing axis is just off (the reset map names every axis)
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .. import regmap

PHASES = regmap.ROUTE_PHASES


@dataclass
class Selects:
    """The routing fields (reset: gen/empc/regmap.py, today's single-axis pinout)."""
    osel: list = field(default_factory=list)
    asel: list = field(default_factory=list)
    esel: list = field(default_factory=list)
    hsel: list = field(default_factory=list)

    @classmethod
    def from_regs(cls, words: dict, naxes: int) -> "Selects":
        """From register words {name: 32-bit value} of OUT_SEL0/1, ADC_SEL0/1, IN_SEL."""
        regs = {r.name: r for r in regmap.GLOBAL}

        def fld(reg, name):
            f = next(x for x in regs[reg].fields if x.name == name)
            return (words[reg] >> f.lsb) & ((1 << f.width) - 1)
        per = regmap.ROUTE_PER_WORD
        osel = [fld(f"OUT_SEL{k // per}", f"out{k}") for k in range(regmap.ROUTE_OUTPUTS)]
        apw = 32 // (regmap.ROUTE_NIB * PHASES)
        asel = [fld(f"ADC_SEL{a // apw}", f"ax{a}_{'abc'[p]}") for a in range(naxes) for p in range(PHASES)]
        esel = [fld("IN_SEL", f"enc{a}") for a in range(naxes)]
        hsel = [fld("IN_SEL", f"hall{a}") for a in range(naxes)]
        return cls(osel, asel, esel, hsel)


class OutRoute:
    """One ``out_route`` instance."""

    def __init__(self, naxes: int = regmap.ROUTE_AXES, nout: int = regmap.ROUTE_OUTPUTS,
                 nenc: int = regmap.ROUTE_ENC, nhall: int = regmap.ROUTE_HALL, nadc: int = regmap.ROUTE_ADC):
        if not 1 <= naxes <= regmap.ROUTE_AXES:
            raise ValueError(f"out_route: NAXES = {naxes} outside 1..{regmap.ROUTE_AXES}")
        self.naxes, self.nout, self.nenc, self.nhall, self.nadc = naxes, nout, nenc, nhall, nadc
        self.np = PHASES * naxes
        self.reset()

    def reset(self) -> None:
        self.pin_hi = 0
        self.pin_lo = 0
        self.mapped = 0
        self.bad_sel = 0
        self.scan_k = 0
        self.acc = 0

    def pair(self, code: int) -> int | None:
        """Pair index of an OUT_SEL code, None for off / an axis the build lacks."""
        return code - 1 if 1 <= code <= self.np else None

    def comb(self, s: Selects, miso: int, irc: tuple, hall: int) -> dict:
        """Input multiplexers (combinational).  irc = (a, b, idx, mark) bit vectors over the
        NENC inputs, hall = 3 bits per set, miso one bit per channel."""
        out = {"ax_miso": 0, "ax_hall": 0, "ax_irc_a": 0, "ax_irc_b": 0, "ax_irc_idx": 0, "ax_irc_mark": 0}
        for j, ch in enumerate(s.asel[:self.np]):
            bit = (miso >> ch) & 1 if ch < self.nadc else 1
            out["ax_miso"] |= bit << j
        for a in range(self.naxes):
            e, h = s.esel[a], s.hsel[a]
            for name, vec in zip(("ax_irc_a", "ax_irc_b", "ax_irc_idx", "ax_irc_mark"), irc):
                out[name] |= (((vec >> e) & 1) if e < self.nenc else 0) << a
            bits = (hall >> (PHASES * h)) & 0b111 if h < self.nhall else 0
            out["ax_hall"] |= bits << (PHASES * a)
        return out

    def bad(self, s: Selects) -> bool:
        return (any(c >= self.nadc for c in s.asel[:self.np])
                or any(e >= self.nenc for e in s.esel[:self.naxes])
                or any(h >= self.nhall for h in s.hsel[:self.naxes]))

    def step(self, rst: bool, s: Selects, osel_wr: bool, hi: int, lo: int, trip: int) -> None:
        """Rising edge with this clock's inputs (the selects as they are before the edge)."""
        tp = sum(((trip >> (j // PHASES)) & 1) << j for j in range(self.np))
        hv, lv = hi & ~tp, lo & ~tp
        ph, pl = 0, 0
        for k in range(self.nout):
            j = self.pair(s.osel[k])
            if j is not None and not rst:
                ph |= ((hv >> j) & 1) << k
                pl |= ((lv >> j) & 1) << k
        self.pin_hi, self.pin_lo = ph, pl
        cur = self.pair(s.osel[self.scan_k])
        dec = 0 if cur is None else 1 << cur
        if rst or osel_wr:
            self.scan_k, self.acc, self.mapped = 0, 0, 0
        elif self.scan_k == self.nout - 1:
            self.scan_k, self.mapped, self.acc = 0, self.acc | dec, 0
        else:
            self.scan_k += 1
            self.acc |= dec
        self.bad_sel = int(not rst and self.bad(s))
