"""Bus-functional model of the LPC4088 EMC static-memory master (CS0, 32 bit).

Used by tb/test_emc_bus.py and by the top-level co-simulation.  It wiggles the
pins with configurable LPC4088-like timing in ns, independent of the fabric
clock (cocotb Timers in ps, no clock edges involved):

write(addr, data)::

    CS low, address and data driven
    +t_cs_we          WE low
    +t_we             WE high
    +t_wr_hold        address/data replaced by garbage (hold ends)
    +t_cs_hold        CS high (after WE high)       then idle t_gap

read(addr) -> int::

    CS low, address driven, data released
    +t_cs_oe          OE low
    +t_oe - t_su      data sampled (must be a resolved 0/1 value)
    +t_su             OE high
    +t_rd_hold        address replaced by garbage
    +t_cs_hold        CS high (after OE high)       then idle t_gap

Between accesses the address and (while the master drives it) the data carry
random garbage, so the DUT cannot depend on values outside the hold windows.
``keep_cs`` keeps CS low between accesses (only the strobes toggle).

Pins are looked up by name on the DUT handle (defaults match tb/hdl/emc_regs_tb.v);
the data bus is modelled as master output + output enable (``d``, ``d_oe``) and
the resolved bus (``bus``) that the master samples on reads.  A read that samples
X or Z raises :class:`EmcBusError`.
"""
from __future__ import annotations

import random
from dataclasses import dataclass, replace

from cocotb.triggers import Timer


class EmcBusError(Exception):
    """A read sampled an unresolved (X/Z) data bus."""


@dataclass(frozen=True)
class EmcTiming:
    """Access timing in ns (see the module docstring for the sequence)."""
    t_cs_we: float = 16.7       # CS low -> WE low
    t_we: float = 50.0          # WE low width
    t_wr_hold: float = 16.7     # WE high -> address/data change
    t_cs_oe: float = 0.0        # CS low -> OE low
    t_oe: float = 83.3          # OE low width
    t_su: float = 5.0           # read data sampled this long before OE rises
    t_rd_hold: float = 5.0      # OE high -> address change
    t_cs_hold: float = 0.0      # strobe high -> CS high
    t_gap: float = 33.3         # idle after the access (CS high or, with keep_cs, strobes high)
    keep_cs: bool = False

    @classmethod
    def lpc(cls, emc_hz: float = 60e6, waitwen: int = 0, waitwr: int = 2, waitoen: int = 0,
            waitrd: int = 4, waitturn: int = 1, t_su: float = 5.0, **kw) -> "EmcTiming":
        """Timing from LPC408x EMCStaticWait* register values (UM10562 register descriptions):
        CS->WE = (WAITWEN+1) Tcy, write access = (WAITWR+2) Tcy with WE rising one Tcy before
        the end (WE low = (WAITWR-WAITWEN+1) Tcy), CS->OE = WAITOEN Tcy, read access =
        (WAITRD+1) Tcy ending with OE and CS high, turnaround (WAITTURN+1) Tcy; address and
        data held one Tcy after WE/OE high.  Check against the LPC408x datasheet figures
        before relying on the exact edges."""
        tcy = 1e9 / emc_hz
        return cls(t_cs_we=(waitwen + 1) * tcy, t_we=(waitwr - waitwen + 1) * tcy, t_wr_hold=tcy,
                   t_cs_oe=waitoen * tcy, t_oe=(waitrd + 1 - waitoen) * tcy, t_su=t_su, t_rd_hold=tcy,
                   t_cs_hold=0.0, t_gap=(waitturn + 1) * tcy, **kw)

    def but(self, **kw) -> "EmcTiming":
        return replace(self, **kw)


DEFAULT_PINS = dict(cs_n="cpu_cs_n", oe_n="cpu_oe_n", we_n="cpu_we_n", a="cpu_a", d="cpu_d",
                    d_oe="cpu_d_oe", bus="emc_d", driven="bus_driven")


class EmcBfm:
    """LPC4088 EMC master.  ``timing`` may be changed between accesses (``bfm.timing = ...``)."""

    def __init__(self, dut, timing: EmcTiming | None = None, aw: int = 14, pins: dict | None = None,
                 rng: random.Random | None = None, garbage: bool = True):
        p = dict(DEFAULT_PINS, **(pins or {}))
        self.cs_n = getattr(dut, p["cs_n"])
        self.oe_n = getattr(dut, p["oe_n"])
        self.we_n = getattr(dut, p["we_n"])
        self.a = getattr(dut, p["a"])
        self.d = getattr(dut, p["d"])
        self.d_oe = getattr(dut, p["d_oe"])
        self.bus = getattr(dut, p["bus"])
        # optional "some driver on the bus" flag: Verilator is 2-state and reads an undriven bus as 0
        self.driven = getattr(dut, p["driven"], None) if p.get("driven") else None
        self.timing = timing or EmcTiming()
        self.aw = aw
        self.rng = rng or random.Random(0)
        self.garbage = garbage
        self.n_wr = self.n_rd = 0

    def idle(self) -> None:
        """Bus idle: strobes high, data released (call once before the first access)."""
        self.cs_n.value = 1
        self.oe_n.value = 1
        self.we_n.value = 1
        self.d_oe.value = 0
        self.a.value = 0
        self.d.value = 0

    def _junk_a(self) -> None:
        if self.garbage:
            self.a.value = self.rng.getrandbits(self.aw)

    def _junk_d(self) -> None:
        if self.garbage:
            self.d.value = self.rng.getrandbits(32)

    def _junk_ad(self) -> None:
        self._junk_a()
        self._junk_d()

    @staticmethod
    async def _wait(ns: float) -> None:
        ps = int(round(ns * 1000))
        if ps > 0:
            await Timer(ps, unit="ps")

    async def _run(self, events) -> dict:
        """Execute (time_ns, action) events in time order; actions returning a value are collected."""
        out = {}
        now = 0.0
        for t, name, fn in sorted(events, key=lambda e: e[0]):
            await self._wait(t - now)
            now = max(now, t)
            r = fn()
            if r is not None:
                out[name] = r
        return out

    async def write(self, addr: int, data: int) -> None:
        t = self.timing
        self.a.value = addr & ((1 << self.aw) - 1)
        self.d.value = data & 0xFFFFFFFF
        self.d_oe.value = 1
        self.cs_n.value = 0
        t_rise = t.t_cs_we + t.t_we
        ev = [(t.t_cs_we, "we0", lambda: setattr(self.we_n, "value", 0)),
              (t_rise, "we1", lambda: setattr(self.we_n, "value", 1)),
              (t_rise + t.t_wr_hold, "hold", self._junk_ad)]
        if not t.keep_cs:
            ev.append((t_rise + t.t_cs_hold, "cs1", lambda: setattr(self.cs_n, "value", 1)))
        end = max(e[0] for e in ev)
        ev.append((end + t.t_gap, "end", lambda: None))
        await self._run(ev)
        self.n_wr += 1

    async def read(self, addr: int) -> int:
        t = self.timing
        self.a.value = addr & ((1 << self.aw) - 1)
        self.d_oe.value = 0
        self.cs_n.value = 0
        t_rise = t.t_cs_oe + t.t_oe
        ev = [(t.t_cs_oe, "oe0", lambda: setattr(self.oe_n, "value", 0)),
              (t_rise - t.t_su, "sample", lambda: (self.bus.value,
                                                   None if self.driven is None else int(self.driven.value))),
              (t_rise, "oe1", lambda: setattr(self.oe_n, "value", 1)),
              (t_rise + t.t_rd_hold, "hold", lambda: self._junk_a())]
        if not t.keep_cs:
            ev.append((t_rise + t.t_cs_hold, "cs1", lambda: setattr(self.cs_n, "value", 1)))
        end = max(e[0] for e in ev)
        ev.append((end + t.t_gap, "end", lambda: None))
        out = await self._run(ev)
        self.n_rd += 1
        v, driven = out["sample"]
        if driven == 0 or not v.is_resolvable:
            raise EmcBusError(f"read {addr:#x}: data bus {v} (driven={driven}) at the sampling point")
        return int(v)
