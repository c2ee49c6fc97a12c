"""Cycle-exact model of ``rtl/glitch_filter.v``: per-bit digital glitch filter.

Per bit: while the input equals the output the counter is 0; while it differs
the counter counts consecutive samples, and on the L-th differing sample the
output takes the input.  ``L = length if length != 0 else filter_len``.  A pulse
of L-1 clocks is rejected, a pulse of L clocks passes (delayed by L clocks).
"""
from __future__ import annotations


class GlitchFilter:
    """One ``glitch_filter`` instance; :meth:`step` is one rising clock edge.

    Attributes after a step (the registered outputs): ``q`` (int, WIDTH bits).
    """

    def __init__(self, width: int = 1, filter_len: int = 4, len_w: int = 8, reset_value: int = 0):
        if not 1 <= filter_len < (1 << len_w):
            raise ValueError(f"filter_len {filter_len} out of range 1..{(1 << len_w) - 1}")
        self.width = width
        self.filter_len = filter_len
        self.len_w = len_w
        self.reset_value = reset_value
        self.reset()

    def reset(self) -> None:
        self.q = self.reset_value
        self.cnt = [0] * self.width

    def effective_len(self, length: int = 0) -> int:
        length &= (1 << self.len_w) - 1
        return length if length else self.filter_len

    def step(self, d: int, length: int = 0, load: bool = False) -> int:
        """Clock edge with input ``d`` (WIDTH bits), run-time ``length`` (0 = default), ``load``.

        Returns the new ``q``.
        """
        if load:
            self.q = d & ((1 << self.width) - 1)
            self.cnt = [0] * self.width
            return self.q
        L = self.effective_len(length)
        q = self.q
        for i in range(self.width):
            di = (d >> i) & 1
            qi = (self.q >> i) & 1
            if di == qi:
                self.cnt[i] = 0
            elif self.cnt[i] + 1 >= L:
                q ^= 1 << i
                self.cnt[i] = 0
            else:
                self.cnt[i] += 1
        self.q = q
        return q
