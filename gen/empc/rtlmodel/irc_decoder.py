"""Cycle-exact model of ``rtl/irc_decoder.v`` (incremental encoder interface, one axis).

Pipeline per clock: pins -> ``sync_stages``-deep synchroniser -> 4-bit glitch
filter ({mark, index, B, A}) -> x4 decoder.  Gray phase ``g = {B, A^B}``; the
step ``(g - g_prev) mod 4`` is +1 (count up: A leads B), 3 (-1), 2 (illegal:
both A and B changed in one sample; count unchanged, error reported) or 0.
The position is a ``pos_w``-bit modular counter (use differences).

Start-up: ``init_cnt`` counts; at ``init_cnt == sync_stages`` the filter loads the
synchronised levels, one clock later ``ready`` rises, and from then on steps,
index and mark edges are evaluated (levels present at start-up are not edges).
"""
from __future__ import annotations

from ..formats import wrap
from .glitch_filter import GlitchFilter


def gray_phase(a: int, b: int) -> int:
    """Quadrature phase 0..3 of the levels (a, b): 00->0, 10->1, 11->2, 01->3."""
    return (b << 1) | (a ^ b)


class IrcDecoder:
    """One ``irc_decoder``; :meth:`step` is one rising clock edge.

    Output attributes (registered values after the edge): ``pos`` (unsigned
    pos_w-bit pattern; :meth:`pos_signed` for the signed value), ``dir`` (1 =
    up), ``index_pos``, ``index_seen``, ``index_event``, ``index_dir``,
    ``mark_pos``, ``mark_seen``, ``mark_event``, ``err_pulse``, ``err_flag``,
    ``err_cnt``, ``in_state`` (filtered {mark,index,B,A}), ``ready``.
    """

    OUTPUTS = ("pos", "dir", "index_pos", "index_seen", "index_event", "index_dir",
               "mark_pos", "mark_seen", "mark_event", "err_pulse", "err_flag", "err_cnt",
               "in_state", "ready")

    def __init__(self, pos_w: int = 32, filter_len: int = 8, len_w: int = 8, err_w: int = 16,
                 sync_stages: int = 2):
        self.pos_w = pos_w
        self.err_w = err_w
        self.sync_stages = sync_stages
        self.filt = GlitchFilter(width=4, filter_len=filter_len, len_w=len_w)
        self.reset()

    def reset(self) -> None:
        self.sync = [0] * self.sync_stages
        self.filt.reset()
        self.init_cnt = 0
        self.ready = 0
        self.prev = 0
        self.pos = 0
        self.dir = 0
        self.index_pos = 0
        self.index_seen = 0
        self.index_event = 0
        self.index_dir = 0
        self.mark_pos = 0
        self.mark_seen = 0
        self.mark_event = 0
        self.err_pulse = 0
        self.err_flag = 0
        self.err_cnt = 0

    @property
    def in_state(self) -> int:
        return self.filt.q

    def pos_signed(self) -> int:
        return wrap(self.pos, self.pos_w)

    def outputs(self) -> dict:
        return {k: getattr(self, k) for k in self.OUTPUTS}

    def step(self, a: int, b: int, index: int = 0, mark: int = 0, filt_len: int = 0,
             err_clear: int = 0, index_clear: int = 0, mark_clear: int = 0) -> "IrcDecoder":
        """One clock edge with the given pin levels and control inputs."""
        mask = (1 << self.pos_w) - 1
        synced = self.sync[-1]
        filt = self.filt.q
        prev = self.prev
        ready = self.ready
        # decoder (uses the pre-edge register values)
        g_step = (gray_phase(filt & 1, (filt >> 1) & 1) - gray_phase(prev & 1, (prev >> 1) & 1)) & 3
        up = ready and g_step == 1
        dn = ready and g_step == 3
        bad = ready and g_step == 2
        index_edge = ready and (filt >> 2) & 1 and not (prev >> 2) & 1
        mark_edge = ready and (filt >> 3) & 1 and not (prev >> 3) & 1
        pos_next = (self.pos + 1) & mask if up else (self.pos - 1) & mask if dn else self.pos
        dir_next = 1 if up else 0 if dn else self.dir
        # start-up sequencer
        load = (not ready) and self.init_cnt == self.sync_stages
        if not ready:
            if self.init_cnt == self.sync_stages + 1:
                self.ready = 1
            self.init_cnt += 1
        # registers
        self.filt.step(synced, filt_len, load)
        pins = ((mark & 1) << 3) | ((index & 1) << 2) | ((b & 1) << 1) | (a & 1)
        self.sync = [pins] + self.sync[:-1]
        self.prev = filt
        self.pos = pos_next
        self.dir = dir_next
        self.index_event = int(bool(index_edge))
        if index_edge:
            self.index_pos = pos_next
            self.index_dir = dir_next
        self.index_seen = int(bool(index_edge) or (self.index_seen and not index_clear))
        self.mark_event = int(bool(mark_edge))
        if mark_edge:
            self.mark_pos = pos_next
        self.mark_seen = int(bool(mark_edge) or (self.mark_seen and not mark_clear))
        self.err_pulse = int(bool(bad))
        self.err_flag = int(bool(bad) or (self.err_flag and not err_clear))
        if err_clear:
            self.err_cnt = int(bool(bad))
        elif bad and self.err_cnt != (1 << self.err_w) - 1:
            self.err_cnt += 1
        return self
