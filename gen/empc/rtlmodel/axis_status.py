"""Model of ``rtl/axis_status.v``: the status words and event counters of one axis, clock by clock.

:meth:`AxisStatus.clock` takes one clock's inputs (the RTL's port names) and returns the registered
read data after the edge (``rdata``); :attr:`mem` is the block RAM.  The behaviour (docs/blocks/
axis_status.md): port A serves a CPU read first, then a deferred word write (one that met a read;
it takes ``st_addr`` / ``st_wdata`` of the next clock, which the sequencer holds: the model checks
that contract), then the sequencer's word write, then a sweep write; port B reads the sweep's counter.  Events are
held until a counting sweep takes them (``sweep`` pulse, this clock's events included); the sweep
adds each counter's event, one counter per clock in which port A is free, saturating at 2**32 - 1
(PERIODS wraps).  Zero sweeps (after rst: all 64 words; after cnt_clear: the counters) write 0 and
keep the words hidden (reads 0) until they end.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .. import regmap
from .ctrl_seq import COUNTERS, STATUS_WORDS

MASK32 = (1 << 32) - 1
ADDR = {n: regmap.axis_reg(n).offset for n in STATUS_WORDS + COUNTERS}
STATUS_ADDR = frozenset(ADDR[n] for n in STATUS_WORDS)
COUNTER_ADDR = frozenset(ADDR[n] for n in COUNTERS)
CNT_ADDR = [ADDR[n] for n in COUNTERS]          # sweep word k -> offset (event k: core flags 0..10, then EVENTS)
EVENTS = ("front_sat", "overrun", "period", "gov")   # event indices 11..14 (the RTL port names)
PERIODS = ADDR["PERIODS"]
NCNT = len(COUNTERS)
assert CNT_ADDR[:13] == list(range(CNT_ADDR[0], CNT_ADDR[0] + 13))


@dataclass
class AxisStatus:
    mem: list = field(default_factory=lambda: [0] * 64)
    ev: int = 0
    act: bool = False
    zact: bool = True
    zall: bool = True
    k: int = 0
    sev: int = 0
    hide_st: bool = True
    hide_cnt: bool = True
    q: int = 0
    q_ok: bool = False
    w_def: bool = False
    w_held: tuple = (0, 0)      # (st_addr, st_wdata) of the last st_we: held in the next clock (contract)
    rdata: int = 0

    def _addr(self, k: int, zall: bool) -> int:
        return k if zall else CNT_ADDR[k] if k < NCNT else CNT_ADDR[-1]

    @property
    def busy(self) -> bool:
        return self.act or self.zact

    def clock(self, rst=0, reg_rd=0, reg_addr=0, cnt_re=0, stat_re=0, cnt_clear=0, core_done=0, core_flags=0,
              front_sat=0, overrun=0, period=0, gov=0, st_we=0, st_addr=0, st_wdata=0, sweep=0) -> int:
        ev_now = (core_flags & 0x7FF if core_done else self.ev & 0x7FF) | (self.ev & ~0x7FF)
        ev_now |= (front_sat << 11) | (overrun << 12) | (period << 13) | (gov << 14)
        take = bool(sweep and not self.act and not self.zact)
        # port A
        if self.w_def and (st_addr, st_wdata) != self.w_held:
            raise AssertionError(f"axis_status: st_addr / st_wdata {(st_addr, st_wdata)} not held in the clock "
                                 f"after st_we {self.w_held} (a deferred write takes them)")
        w_now = st_we and not reg_rd
        w_st = self.w_def or w_now
        a_free = not reg_rd and not self.w_def and not st_we
        cnt_ev = (self.sev >> self.k) & 1 if self.k < NCNT else 0
        go_c = self.act and self.q_ok and a_free
        go_z = self.zact and a_free
        go = go_c or go_z
        sw_a = self._addr(self.k, self.zall)
        c_full = self.q == MASK32
        sw_wr = go_z or (go_c and not (cnt_ev and c_full and sw_a != PERIODS))
        sw_d = 0 if go_z else (self.q + cnt_ev) & MASK32
        b_k = self.k + 1 if go else self.k
        b_addr = CNT_ADDR[b_k] if b_k < NCNT else CNT_ADDR[-1]
        s_rd = (cnt_re and not self.hide_cnt) or (stat_re and not self.hide_st)
        pa = (reg_addr & 63) if reg_rd else st_addr if w_st else sw_a
        pa_we = not reg_rd and (w_st or (go and sw_wr))
        pa_d = st_wdata if w_st else sw_d
        # edge
        new_rdata = self.mem[pa] if (reg_rd and s_rd) else 0
        new_q = self.mem[b_addr]
        if pa_we:
            self.mem[pa] = pa_d & MASK32
        self.rdata = new_rdata
        self.q = new_q
        self.w_def = bool(st_we and reg_rd and not rst)
        if st_we:
            self.w_held = (st_addr, st_wdata)
        self.ev = 0 if (rst or take) else ev_now
        if rst:
            self.act, self.zact, self.zall, self.k, self.q_ok, self.sev = False, True, True, 0, False, 0
            self.hide_st = self.hide_cnt = True
        elif cnt_clear:
            keep = self.zall and self.zact
            self.act, self.zact, self.zall = False, True, keep
            if not keep:
                self.k = 0
            self.hide_cnt = True
        else:
            q_ok = self.act and not take
            if take:
                self.act, self.k, self.sev = True, 0, ev_now
            elif go:
                last = 63 if self.zall else NCNT - 1
                if self.k == last:
                    if self.zact:
                        self.hide_cnt = False
                        if self.zall:
                            self.hide_st = False
                    self.act = self.zact = self.zall = False
                self.k += 1
            self.q_ok = q_ok
        return self.rdata

    def read(self, addr: int) -> int:
        """What a CPU read of ``addr`` would return now (hidden words and other offsets: 0)."""
        if (addr in COUNTER_ADDR and not self.hide_cnt) or (addr in STATUS_ADDR and not self.hide_st):
            return self.mem[addr]
        return 0
