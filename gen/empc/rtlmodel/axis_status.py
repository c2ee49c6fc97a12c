"""Model of ``rtl/axis_status.v``: the status words and event counters of NAXES axes, clock by clock.

:meth:`AxisStatus.clock` takes one clock's inputs (the RTL's port names) and returns the registered
read data after the edge (``rdata``); :attr:`mem` is the block RAM, word ``{axis, word}`` at
``axis * 64 + word``.  Per-axis inputs and outputs (``cnt_clear``, ``core_done``, the events,
``sweep``, ``busy``) are bit masks (bit a: axis a), ``core_flags`` packs 11 bits per axis (axis a at
bit 11 a), ``reg_addr`` is ``{axis, offset}`` (axis at bit 8), ``st_addr`` ``{axis, word}`` (axis at
bit 6); with ``naxes = 1`` they are the one-axis block's scalars.

The behaviour (docs/blocks/axis_status.md): port A serves a CPU read first, then a deferred word
write (one that met a read; it takes ``st_addr`` / ``st_wdata`` of the next clock, which the
sequencer holds: the model checks that contract), then the sequencer's word write, then a sweep
write; port B reads the sweep's counter.  Events are held per axis until a counting sweep of that
axis takes them (``sweep`` pulse, this clock's events included, into the axis's snapshot); the sweep
adds each counter's event, one counter per clock in which port A is free, saturating at 2**32 - 1
(PERIODS wraps).  Zero sweeps (after rst: all words of every axis; after cnt_clear of axis a: a's
counters) write 0 and keep the words hidden (reads 0) until they end.  One engine serves every
axis: a pulse taken or a clear of an axis the engine is not serving waits (``cp`` / ``zp``), an
idle engine starts the request of the first axis after the last one served (round robin), a clear
of the engine's axis restarts it.
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
NFLAGS = 11                                     # core flag bits per axis (events 0..10)
assert CNT_ADDR[:13] == list(range(CNT_ADDR[0], CNT_ADDR[0] + 13))


def axis_bits(naxes: int) -> int:
    """clog2(naxes): the axis bits of the addresses (0 for one axis)."""
    return (naxes - 1).bit_length()


def _cnt_a(kw: int) -> int:
    """Offset of sweep word kw (6 bits): the counters in event order, SAT_GOV beyond them (as the RTL)."""
    kw &= 63
    return CNT_ADDR[kw] if kw < NCNT else CNT_ADDR[-1]


@dataclass
class AxisStatus:
    naxes: int = 1
    mem: list = field(default=None)
    ev: list = field(default=None)      # held events per axis (15 bits)
    sq: list = field(default=None)      # snapshot per axis: the events its taken sweep pulse adds
    cp: int = 0                         # counting sweep of axis a waits (bit mask)
    zp: int = 0                         # zero sweep of axis a waits
    act: bool = False
    zact: bool = True
    zall: bool = True
    ax: int = 0
    k: int = 0
    hide_st: bool = True
    hide_cnt: int = 0                   # bit a: axis a's counters read 0
    q: int = 0
    q_ok: bool = False
    w_def: bool = False
    w_held: tuple = (0, 0)      # (st_addr, st_wdata) of the last st_we: held in the next clock (contract)
    rdata: int = 0

    def __post_init__(self):
        if not 1 <= self.naxes <= 8:
            raise ValueError(f"axis_status: NAXES {self.naxes} not in 1..8")
        self.axb = axis_bits(self.naxes)
        self.nw = 64 << self.axb
        self.full = (1 << self.naxes) - 1
        if self.mem is None:
            self.mem = [0] * self.nw
        self.ev = [0] * self.naxes if self.ev is None else self.ev
        self.sq = [0] * self.naxes if self.sq is None else self.sq
        self.hide_cnt = self.full

    @property
    def sev(self) -> int:
        """The running counting sweep's events (axis ``ax``'s snapshot)."""
        return self.sq[self.ax]

    def eng_on(self) -> int:
        if not (self.act or self.zact):
            return 0
        return self.full if self.zall else 1 << self.ax

    @property
    def busy(self) -> int:
        """Bit mask: a sweep of axis a runs or waits (every axis during the zero sweep after rst)."""
        return self.eng_on() | self.cp | self.zp

    def clock(self, rst=0, reg_rd=0, reg_addr=0, cnt_re=0, stat_re=0, cnt_clear=0, core_done=0, core_flags=0,
              front_sat=0, overrun=0, period=0, gov=0, st_we=0, st_addr=0, st_wdata=0, sweep=0) -> int:
        n, full = self.naxes, self.full
        ev_now = []
        for a in range(n):
            e = self.ev[a]
            core = (core_flags >> (NFLAGS * a)) & 0x7FF if (core_done >> a) & 1 else e & 0x7FF
            e = core | (e & ~0x7FF)
            e |= (((front_sat >> a) & 1) << 11) | (((overrun >> a) & 1) << 12) | \
                 (((period >> a) & 1) << 13) | (((gov >> a) & 1) << 14)
            ev_now.append(e)
        eng_on = self.eng_on()
        busy = eng_on | self.cp | self.zp
        take = sweep & ~busy & full
        # port A
        if self.w_def and (st_addr, st_wdata) != self.w_held:
            raise AssertionError(f"axis_status: st_addr / st_wdata {(st_addr, st_wdata)} not held in the clock "
                                 f"after st_we {self.w_held} (a deferred write takes them)")
        w_now = st_we and not reg_rd
        w_st = self.w_def or w_now
        a_free = not reg_rd and not self.w_def and not st_we
        cnt_ev = (self.sq[self.ax] >> (self.k & 15)) & 1
        go_c = self.act and self.q_ok and a_free
        go_z = self.zact and a_free
        go = go_c or go_z
        kw = self.k & 63
        cnt_a = _cnt_a(kw)
        sw_a = self.k if self.zall else (self.ax << 6) | cnt_a
        c_full = self.q == MASK32
        sw_wr = go_z or (go_c and not (cnt_ev and c_full and cnt_a != PERIODS))
        sw_d = 0 if go_z else (self.q + cnt_ev) & MASK32
        b_addr = (self.ax << 6) | _cnt_a(kw + 1 if go else kw)
        r_ax = reg_addr >> 8
        ra = (r_ax << 6) | (reg_addr & 63)
        r_ok = r_ax < n
        s_rd = r_ok and ((cnt_re and not (self.hide_cnt >> r_ax) & 1) or (stat_re and not self.hide_st))
        pa = ra if reg_rd else st_addr if w_st else sw_a
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
        for a in range(n):
            if (take >> a) & 1:
                self.sq[a] = ev_now[a]
            self.ev[a] = 0 if (rst or (take >> a) & 1) else ev_now[a]
        # the sweep engine
        idle = not self.act and not self.zact
        zrun = self.zact and self.zall
        rz = (cnt_clear | self.zp) & full
        rq = rz | self.cp | (sweep & full)
        pick = 0                            # round robin: the first request after axis ax
        for i in range(n):
            a = (self.ax + 1 + i) % n
            if (rq >> a) & 1:
                pick = a
                break
        start = idle and rq != 0
        restart = not zrun and not idle and bool((cnt_clear >> self.ax) & 1)
        served = (1 << pick) if start else 0
        if rst:
            self.act, self.zact, self.zall, self.ax, self.k, self.q_ok = False, True, True, 0, 0, False
            self.hide_st, self.hide_cnt, self.cp, self.zp = True, full, 0, 0
            return self.rdata
        q_ok = self.act
        self.hide_cnt |= cnt_clear & full
        if n > 1:
            self.cp = (self.cp | take) & ~cnt_clear & ~served & full
            on_ax = 0 if idle else 1 << self.ax     # the engine runs a sweep of axis ax
            self.zp = (self.zp | (cnt_clear & ~on_ax & (0 if zrun else full))) & ~served & full
        if zrun and cnt_clear & full:
            pass                            # a clear holds the zero sweep after rst one clock
        elif restart:
            self.act, self.zact, self.k = False, True, 0
        elif start:
            self.ax, self.k = pick, 0
            self.zact = bool((rz >> pick) & 1)
            self.act = not self.zact
        elif go:
            last = self.nw - 1 if self.zall else NCNT - 1
            if self.k == last:
                if self.zact:
                    if self.zall:
                        self.hide_st, self.hide_cnt = False, 0
                    else:
                        self.hide_cnt &= ~(1 << self.ax)
                self.act = self.zact = self.zall = False
            self.k = (self.k + 1) & (self.nw - 1)
        self.q_ok = q_ok
        return self.rdata

    def read(self, addr: int, axis: int = 0) -> int:
        """What a CPU read of ``addr`` of ``axis`` would return now (hidden words and other offsets: 0)."""
        base = axis << 6
        if (addr in COUNTER_ADDR and not (self.hide_cnt >> axis) & 1) or (addr in STATUS_ADDR and not self.hide_st):
            return self.mem[base + addr]
        return 0
