"""Model of ``rtl/axis_status.v``: the status words and event counters of one axis.

At the level of its protocol with ctrl_seq's engine and the CPU, one call per event:

* :meth:`AxisStatus.write` - a word written (at the end of its stream: st_wr);
* :meth:`AxisStatus.sweep_start` / :meth:`sweep_word` / :meth:`sweep_end` - a sweep; the word a
  sweep step writes is counter + event (saturating at 2**32 - 1: not written; PERIODS wraps), or
  0 in a zero sweep (one started while the counters are hidden);
* :meth:`control_start` - a control period starts: a sweep in progress is abandoned, the next is due;
* :meth:`core_update`, :meth:`event` - the events of the control period (held until a sweep ends);
* :meth:`clear_counters` (CMD.clear_counters), :meth:`reset` (rst: the memory keeps its contents);
* :meth:`read` - what a CPU read returns: 0 for hidden words and other offsets.

:attr:`sweep_request` / :attr:`sweep_all` are the RTL's ``sw_req`` / ``sw_all``.
Timing, per clock: a read sees the words written in earlier clocks (not one written in the same
clock); a sweep step's word is formed from the counter and the events as they are in the clock
the step starts (ctrl_seq's E_OP clock; an event arriving in that clock counts in the next
sweep) and written 33 clocks later; an event in the clock of sweep_end is lost (the events are
cleared); start, end and control_start take the hide flags before a clear of the same clock.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .. import regmap
from .ctrl_seq import COUNTERS, STATUS_WORDS

MASK32 = (1 << 32) - 1
ADDR = {n: regmap.axis_reg(n).offset for n in STATUS_WORDS + COUNTERS}
STATUS_ADDR = frozenset(ADDR[n] for n in STATUS_WORDS)
COUNTER_ADDR = frozenset(ADDR[n] for n in COUNTERS)
# the event of each counter: core flag bits 0..10 (SAT_OPERAND .. SAT_SIGNAL), then EVENTS
EVENT_OF = {ADDR[n]: i for i, n in enumerate(COUNTERS)}
EVENTS = ("front_sat", "overrun", "period", "gov")   # event indices 11, 12, 13, 14 (the RTL port names)
WRAPS = frozenset({ADDR["PERIODS"]})


@dataclass
class AxisStatus:
    mem: dict = field(default_factory=dict)      # word offset -> value (unwritten words: 0, as the RAM's init)
    hide_st: bool = True
    hide_cnt: bool = True
    pend: bool = False
    sweeping: bool = False
    zero: bool = False
    events: int = 0                              # bit i: the event of counter COUNTERS[i]

    def reset(self) -> None:
        self.hide_st = self.hide_cnt = True
        self.pend = self.sweeping = self.zero = False
        self.events = 0

    @property
    def sweep_request(self) -> bool:
        return self.hide_st or self.hide_cnt or self.pend

    @property
    def sweep_all(self) -> bool:
        return self.hide_st

    # ---- events ----
    def core_update(self, flags: int) -> None:
        self.events = (self.events & ~0x7FF) | (flags & 0x7FF)

    def event(self, name: str) -> None:
        self.events |= 1 << (11 + EVENTS.index(name))

    # ---- words ----
    def write(self, addr: int, value: int) -> None:
        self.mem[addr] = value & MASK32

    def sweep_start(self) -> None:
        self.sweeping, self.zero, self.pend = True, self.hide_cnt, False

    def sweep_word(self, addr: int) -> int | None:
        """The word the sweep step of ``addr`` writes (None: a saturated counter, not written)."""
        assert self.sweeping
        if self.zero:
            return 0
        ev = (self.events >> EVENT_OF[addr]) & 1 if addr in EVENT_OF else 0
        new = self.mem.get(addr, 0) + ev
        if new > MASK32:
            return 0 if addr in WRAPS else None
        return new

    def sweep_end(self) -> None:
        if self.zero:
            self.hide_st = self.hide_cnt = False
        self.sweeping = False
        self.events = 0

    def control_start(self) -> None:
        self.sweeping, self.zero, self.pend = False, False, True

    def clear_counters(self) -> None:
        self.hide_cnt = True

    def read(self, addr: int) -> int:
        if (addr in COUNTER_ADDR and not self.hide_cnt) or (addr in STATUS_ADDR and not self.hide_st):
            return self.mem.get(addr, 0)
        return 0
