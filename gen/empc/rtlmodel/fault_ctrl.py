"""Cycle-exact model of ``rtl/fault_ctrl.v``: sticky fault latch with a combinational trip.

``trip = |((latched | cause) & mask)`` is combinational (same clock as the
cause); at the clock edge ``latched <= cause if clear else latched | cause``,
so ``clear`` only removes bits whose cause has gone and masked causes are
recorded too.
"""
from __future__ import annotations

from empc import regmap

# bit order of the AXIS FAULT register (gen/empc/regmap.py)
CAUSES = tuple(f.name for f in sorted(regmap.axis_reg("FAULT").fields, key=lambda f: f.lsb))


class FaultCtrl:
    """One ``fault_ctrl`` instance.  ``latched`` is the registered state."""

    def __init__(self, ncause: int = len(CAUSES)):
        self.ncause = ncause
        self.all = (1 << ncause) - 1
        self.reset()

    def reset(self) -> None:
        self.latched = 0

    def trip(self, cause: int, mask: int) -> bool:
        """Combinational trip output for the current inputs (before the clock edge)."""
        return bool(((self.latched | cause) & mask) & self.all)

    def step(self, cause: int, mask: int, clear: bool = False) -> bool:
        """One clock: returns the combinational ``trip`` seen in this clock, then updates ``latched``."""
        t = self.trip(cause, mask)
        cause &= self.all
        self.latched = cause if clear else (self.latched | cause)
        return t
