"""Cycle-exact model of ``rtl/watchdog.v``: PWM-period watchdog.

Per clock: kick, timeout = 0 or reset clear the count and ``expired``;
otherwise a tick increments the count (only while not expired, so it never
overflows) and ``expired`` is set (sticky until kick) when the new count is
>= timeout.
"""
from __future__ import annotations


class Watchdog:
    """One ``watchdog`` instance; :meth:`step` is one rising clock edge."""

    def __init__(self, tw: int = 16):
        self.tw = tw
        self.max = (1 << tw) - 1
        self.reset()

    def reset(self) -> None:
        self.count = 0
        self.expired = False

    def step(self, tick: bool, kick: bool, timeout: int) -> bool:
        """Clock edge; returns the new (registered) ``expired``."""
        timeout &= self.max
        if kick or timeout == 0:
            self.count = 0
            self.expired = False
        else:
            if tick and not self.expired:
                self.count += 1
            if self.count >= timeout:
                self.expired = True
        return self.expired
