"""Cycle-exact model of ``rtl/hall_decoder.v`` (three HALL sensors -> sector 1..6).

Code = filtered {C, B, A}; sector = ``sector_map[code]`` (1..6 legal, 0/7
illegal).  Default map: codes 5,1,3,2,6,4 are sectors 1..6 (sector s spans
[(s-1)*60, s*60) deg electrical from the HALL reference); 0 and 7 are illegal.
"""
from __future__ import annotations

from .glitch_filter import GlitchFilter

#: default table, index = code {C,B,A}, value = sector (0 = illegal)
DEFAULT_MAP = (0, 2, 4, 3, 6, 1, 5, 0)
#: the code of each sector 1..6 under DEFAULT_MAP (forward = increasing angle)
DEFAULT_SEQUENCE = (5, 1, 3, 2, 6, 4)


def map_to_param(table) -> int:
    """8-entry table -> the 24-bit Verilog ``SECTOR_MAP`` parameter value."""
    return sum((int(s) & 7) << (3 * c) for c, s in enumerate(table))


def clog2(v: int) -> int:
    return max(0, (v - 1).bit_length())


class HallDecoder:
    """One ``hall_decoder``; :meth:`step` is one rising clock edge.

    Output attributes: ``sector``, ``valid``, ``change``, ``fault_pulse``,
    ``fault``, ``code`` (filtered raw code), ``ready``.
    """

    OUTPUTS = ("sector", "valid", "change", "fault_pulse", "fault", "code", "ready")

    def __init__(self, debounce: int = 1000, sector_map=DEFAULT_MAP, sync_stages: int = 2):
        self.sector_map = tuple(sector_map)
        self.sync_stages = sync_stages
        len_w = max(1, clog2(debounce + 1))
        self.filt = GlitchFilter(width=3, filter_len=debounce, len_w=len_w)
        self.reset()

    def reset(self) -> None:
        self.sync = [0] * self.sync_stages
        self.filt.reset()
        self.init_cnt = 0
        self.ready = 0
        self.sector = 0
        self.valid = 0
        self.change = 0
        self.fault_pulse = 0
        self.fault = 0
        self.bad = 0

    @property
    def code(self) -> int:
        return self.filt.q

    def outputs(self) -> dict:
        return {k: getattr(self, k) for k in self.OUTPUTS}

    def step(self, hall: int, fault_clear: int = 0) -> "HallDecoder":
        synced = self.sync[-1]
        code = self.filt.q
        load = (not self.ready) and self.init_cnt == self.sync_stages
        if not self.ready:
            if self.init_cnt == self.sync_stages + 1:
                self.ready = 1
            self.init_cnt += 1
        else:
            s_new = self.sector_map[code] & 7
            legal = s_new not in (0, 7)
            self.valid = int(legal)
            self.change = int(legal and self.sector != 0 and s_new != self.sector)
            if legal:
                self.sector = s_new
            self.fault_pulse = int((not legal) and not self.bad)
            self.bad = int(not legal)
            self.fault = int((not legal) or (self.fault and not fault_clear))
        self.filt.step(synced, 0, load)
        self.sync = [hall & 7] + self.sync[:-1]
        return self
