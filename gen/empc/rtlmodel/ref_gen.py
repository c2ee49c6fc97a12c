"""Bit-exact model of ``rtl/ref_gen.v`` plus the profile-to-slot helper.

The reference generator (paper 000 sec. V-A) evaluates time-parameterised
polynomial segments by exact integer forward differences once per control
period.  Values are Q.32 of the task output unit (encoder counts for
position, counts per Ts for speed), held modulo 2**64: the position integer
part wraps modulo 2**32 like the encoder counter (consumers take differences);
for speed the CPU keeps the profile within +-2**31 counts/Ts.

Per advance (see the RTL header for the exact rules)::

    h1 = head + d1; d1' = d1 + d2; remaining' = remaining - 1 (if the segment ends)
    start pending       -> load(start slot)
    remaining' == 0     -> last ? hold (d1 = d2 = 0) : load(slot + 1 mod 16)
    otherwise           -> head = h1, d1 = d1', remaining = remaining'
    load(s): head = h1 if relative[s] else r0[s]; d1, d2, remaining = d1[s], d2[s], len[s]

``w`` is the delay line w_k .. w_{k+N} (``w[N]`` = head).  A sync sets the head
and the whole delay line.  The RTL is a bit-serial engine that executes one
queued operation at a time (sync before advance); :meth:`RefGen.step` models its
timing clock by clock, the other methods act at once.  Slots are written one
32-bit field at a time (:meth:`RefGen.write_field`, fields :data:`FIELDS`).

:func:`segments_from_points` turns a step/ramp profile in SI units into slots.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..formats import wrap

NSLOT = 16
M64 = (1 << 64) - 1
M32 = (1 << 32) - 1
Q = 32                  # fractional bits of the generator values


@dataclass(frozen=True)
class Slot:
    """One segment slot.  ``r0``/``d1`` are Q.32 (any int, stored modulo 2**64),
    ``d2`` a signed 32-bit Q.32 second difference, ``length`` in control periods
    (0 = the segment never ends)."""
    length: int = 0
    r0: int = 0
    d1: int = 0
    d2: int = 0
    relative: bool = False
    last: bool = False

    def normalised(self) -> "Slot":
        if not -(1 << 31) <= self.d2 < (1 << 31) and not 0 <= self.d2 <= M32:
            raise ValueError(f"d2 {self.d2} does not fit 32 bits")
        if not 0 <= self.length <= M32:
            raise ValueError(f"length {self.length} out of 0..2**32-1")
        return Slot(self.length, self.r0 & M64, self.d1 & M64, wrap(self.d2, 32), bool(self.relative), bool(self.last))

    def regs(self) -> dict:
        """Register words (gen/empc/regmap.py AXIS SEG_*) that program this slot (each write goes
        straight into slot SEG_ADDR; the order does not matter)."""
        s = self.normalised()
        return {"SEG_LEN": s.length, "SEG_R0_LO": s.r0 & M32, "SEG_R0_HI": s.r0 >> 32,
                "SEG_D1_LO": s.d1 & M32, "SEG_D1_HI": s.d1 >> 32, "SEG_D2": s.d2 & M32,
                "SEG_FLAGS": int(s.relative) | (int(s.last) << 1)}


FIELDS = ("len", "r0_lo", "r0_hi", "d1_lo", "d1_hi", "d2", "flags")   # seg_field 0..6 (SEG_LEN .. SEG_FLAGS)


def slot_field(s: Slot, field: int) -> int:
    """32-bit word of field ``field`` (0..6, see :data:`FIELDS`) of a normalised slot, as read back."""
    return [s.length, s.r0 & M32, s.r0 >> 32, s.d1 & M32, s.d1 >> 32, s.d2 & M32,
            int(s.relative) | (int(s.last) << 1)][field]


def with_field(s: Slot, field: int, value: int) -> Slot:
    """``s`` with field ``field`` replaced by the 32-bit word ``value`` (a CPU field write)."""
    v = value & M32
    if field == 0:
        return Slot(v, s.r0, s.d1, s.d2, s.relative, s.last)
    if field in (1, 2):
        r0 = (s.r0 & ~M32 | v) if field == 1 else (s.r0 & M32 | v << 32)
        return Slot(s.length, r0, s.d1, s.d2, s.relative, s.last)
    if field in (3, 4):
        d1 = (s.d1 & ~M32 | v) if field == 3 else (s.d1 & M32 | v << 32)
        return Slot(s.length, s.r0, d1, s.d2, s.relative, s.last)
    if field == 5:
        return Slot(s.length, s.r0, s.d1, wrap(v, 32), s.relative, s.last)
    if field == 6:
        return Slot(s.length, s.r0, s.d1, s.d2, bool(v & 1), bool(v & 2))
    raise ValueError(f"field {field} out of 0..6")


# engine timing of rtl/ref_gen.v (clocks per pass include the lead clock of the block RAM read)
PASS_CLOCKS = {"flags": 3, "head": 65, "d1": 65, "d2": 33, "len": 33, "sync": 65}


class RefGen:
    """One ``ref_gen`` instance.

    Operation-level API: :meth:`write_slot` / :meth:`write_field`, :meth:`start`,
    :meth:`sync`, :meth:`advance` (each as if the engine ran it to completion at once).
    Clock-level API: :meth:`step` (the inputs of one clock) with the RTL engine's
    timing: strobes set pending flags; an idle engine begins a pending sync first,
    then a pending advance; an operation's effect on the delay line (``w``) shows at
    the end of its head / last sync pass (``w_ok``), on the differences at its end
    (``busy`` falls).  The slot memory is read when an advance begins: the RTL reads
    the slot fields during the operation, so the CPU must not write the slot being
    loaded (:attr:`loading_slot`) while the operation runs.
    """

    def __init__(self, N: int = 4):
        if N < 1:
            raise ValueError("N must be >= 1")
        self.N = N
        self.mem = [Slot()] * NSLOT        # not cleared by reset (block RAM)
        self.reset(settled=True)

    def reset(self, settled: bool = False) -> None:
        """rst: state cleared; the RTL clears its delay line with a sync to 0 that runs
        (N+1) passes after rst (``settled=True`` skips that wait: the state after it)."""
        self.head = 0
        self.d1 = 0
        self.d2 = 0
        self.rem = 0
        self.ends = False
        self.last = False
        self.slot = 0
        self.pend = False
        self.pend_slot = 0
        self.adv_pend = False
        self.sync_pend = False
        self.dl = [0] * self.N
        self._op = None                    # running operation: dict(kind, clocks left, ...)
        self._sync_value = 0
        if not settled:
            self._begin_sync(0)

    @property
    def w(self) -> list[int]:
        """w_k .. w_{k+N} (unsigned 64-bit words)."""
        return self.dl + [self.head]

    # ---- operation level ----
    def write_slot(self, idx: int, slot: Slot) -> None:
        self.mem[idx % NSLOT] = slot.normalised()

    def write_field(self, idx: int, field: int, value: int) -> None:
        self.mem[idx % NSLOT] = with_field(self.mem[idx % NSLOT], field, value)

    def read_field(self, idx: int, field: int) -> int:
        return slot_field(self.mem[idx % NSLOT], field)

    def start(self, slot: int) -> None:
        self.pend, self.pend_slot = True, slot % NSLOT

    def sync(self, value: int) -> None:
        """Head and the whole delay line = ``value``, differences 0, hold (a pending start survives)."""
        v = value & M64
        self.head = v
        self.dl = [v] * self.N
        self.d1 = self.d2 = self.rem = 0
        self.ends = self.last = False

    def advance(self) -> list[int]:
        self._advance()
        return self.w

    def load_program(self, slots, base: int = 0) -> None:
        for i, s in enumerate(slots):
            self.write_slot(base + i, s)

    def _advance(self) -> None:
        old_head = self.head
        h1 = (self.head + self.d1) & M64
        d1n = (self.d1 + self.d2) & M64
        seg_end = self.ends and self.rem == 1
        do_start = self.pend
        ld = self.pend_slot if self.pend else (self.slot + 1) % NSLOT
        self.pend = False
        if do_start or (seg_end and not self.last):
            s = self.mem[ld]
            self.head = h1 if s.relative else s.r0
            self.d1, self.d2, self.rem = s.d1, s.d2, s.length
            self.ends, self.last, self.slot = s.length != 0, s.last, ld
        elif seg_end:                       # last: hold
            self.head = h1
            self.d1 = self.d2 = self.rem = 0
            self.ends = False
        else:
            self.head = h1
            self.d1 = d1n
            if self.ends:
                self.rem -= 1
        self.dl = self.dl[1:] + [old_head]

    # ---- clock level (RTL engine timing) ----
    @property
    def busy(self) -> bool:
        return self._op is not None or self.adv_pend or self.sync_pend

    @property
    def w_ok(self) -> bool:
        """The delay line is current (RTL ``w_ok``): nothing pending, no head / sync pass running."""
        return not self.adv_pend and not self.sync_pend and (self._op is None or self._op["w_done"])

    @property
    def loading_slot(self):
        """Slot an advance in progress loads (None if none)."""
        return self._op["slot"] if self._op is not None and self._op.get("load") else None

    def _begin_sync(self, value: int) -> None:
        self._op = {"kind": "sync", "left": (self.N + 1) * PASS_CLOCKS["sync"], "w_left": None,
                    "w_done": False, "value": value & M64}
        self.d1 = self.d2 = self.rem = 0          # cleared when the sync begins
        self.ends = self.last = False

    def _begin_advance(self) -> None:
        seg_end = self.ends and self.rem == 1
        load = self.pend or (seg_end and not self.last)
        ld = self.pend_slot if self.pend else (self.slot + 1) % NSLOT
        snap = RefGen.__new__(RefGen)              # the result, applied in two steps
        snap.__dict__.update({k: v for k, v in self.__dict__.items() if k != "_op"})
        snap.dl = list(self.dl)
        snap._advance()
        if load:
            clocks = sum(PASS_CLOCKS[k] for k in ("flags", "head", "d1", "d2", "len"))
            w_left = PASS_CLOCKS["flags"] + PASS_CLOCKS["head"]
        else:
            clocks = w_left = PASS_CLOCKS["head"]
        self.pend = False                          # consumed (a start in this clock re-pends)
        self._op = {"kind": "advance", "left": clocks, "w_left": w_left, "w_done": False,
                    "load": load, "slot": ld, "result": snap}

    def step(self, seg_we: bool = False, seg_slot: int = 0, seg_field: int = 0, seg_wdata: int = 0,
             start: bool = False, start_slot: int = 0, sync: bool = False, sync_value: int = 0,
             advance: bool = False) -> None:
        """One rising clock edge with the given inputs (RTL priorities and timing).
        ``sync_value`` is sampled when the sync's first pass runs: keep it constant from the
        strobe until the sync has run (as the RTL requires); here it is taken at the strobe.  A field write
        lands before an advance that begins in the same clock reads the slot; the CPU must not
        write :attr:`loading_slot` while that advance runs (undefined in the RTL)."""
        if seg_we:                                 # port A write: seen by an advance beginning now
            self.write_field(seg_slot, seg_field, seg_wdata)
        op = self._op
        if op is not None:                         # the running operation advances one clock
            op["left"] -= 1
            if op["w_left"] is not None and not op["w_done"]:
                op["w_left"] -= 1
                if op["w_left"] == 0:
                    r = op["result"]
                    self.head, self.dl = r.head, list(r.dl)
                    op["w_done"] = True
            if op["left"] == 0:
                if op["kind"] == "sync":
                    v = op["value"]
                    self.head, self.dl = v, [v] * self.N
                else:
                    r = op["result"]
                    for k in ("d1", "d2", "rem", "ends", "last", "slot"):
                        setattr(self, k, getattr(r, k))
                self._op = None
        elif self.sync_pend:                       # idle: begin an operation
            self.sync_pend = False
            self._begin_sync(self._sync_value)
        elif self.adv_pend:
            self.adv_pend = False
            self._begin_advance()
        # strobes of this clock
        if advance:
            self.adv_pend = True
        if sync:
            self.sync_pend = True
            self._sync_value = sync_value & M64
        if start:
            self.pend, self.pend_slot = True, start_slot % NSLOT


def q32(value: float) -> int:
    """Round a value in the output unit to Q.32 (round half up)."""
    import math
    return int(math.floor(value * (1 << Q) + 0.5))


def segments_from_points(points, unit_per_si: float, Ts: float, v0: float = 0.0,
                         relative_start: bool = False, exact_ramps: bool = True) -> list[Slot]:
    """Slots for a profile of steps and ramps given in SI units.

    ``points``: (t, value, kind) in time order, as in :func:`empc.reference.steps_and_ramps`:
    kind ``"step"`` holds the previous value on [t_prev, t) and jumps to ``value`` at t;
    ``"ramp"`` moves linearly from the previous value to reach ``value`` at t.  The profile
    starts at t = 0 with ``v0`` and holds the last value forever (final slot len = 0).
    ``unit_per_si`` converts SI to the generator unit (counts per rad, or counts/Ts per rad/s);
    times are rounded to whole control periods ``Ts``; period 0 is the advance that takes
    the start (the head, w_{k+N}).

    Steps become absolute segments (r0 = the value); ramps relative segments with
    d1 = slope per period; holds d1 = 0.  With ``relative_start`` the first segment is
    relative (keeps the generator's present value, e.g. after CMD.ref_sync) and the profile
    is offset by (start value - v0) until the first step.  Ramp ends: with ``exact_ramps`` a
    ramp of L periods and Q.32 increment D is split into r = D mod L periods of
    floor(D/L) + 1 and L - r periods of floor(D/L), so it ends exactly on the Q.32 value
    (one extra slot when r != 0); without, one slot with d1 = round(D/L), ending within
    L/2 LSB of Q.32.  Raises ValueError if more than 16 slots are needed.
    """
    segs: list[Slot] = []
    cur = q32(v0 * unit_per_si)           # tracked (nominal) generator value, Q.32
    p_prev = 0
    # the open hold segment: (absolute r0 or None for relative)
    open_r0 = None if relative_start else cur
    for t, v, kind in points:
        p = int(round(t / Ts))
        L = p - p_prev
        if L < 0:
            raise ValueError(f"breakpoint at t={t} is before the previous one")
        target = q32(v * unit_per_si)
        if kind == "step":
            if L > 0:
                segs.append(_hold(L, open_r0))
            elif not segs and p == 0:
                pass                                    # step at t = 0 replaces the start value
            open_r0 = target
            cur = target
        elif kind == "ramp":
            if L == 0:
                raise ValueError(f"ramp to {v} at t={t} has zero duration")
            if open_r0 is not None:
                # the ramp starts at an absolute value (after a step / absolute start):
                # a zero-length hold is not possible, so the ramp segment itself is absolute
                first_abs = open_r0
            else:
                first_abs = None
            D = target - cur
            if exact_ramps:
                qd, r = divmod(D, L)
                parts = [(r, qd + 1), (L - r, qd)] if r else [(L, qd)]
            else:
                parts = [(L, (2 * D + L) // (2 * L))]
            for i, (n, d1) in enumerate(parts):
                if i == 0 and first_abs is not None:
                    segs.append(Slot(n, first_abs & M64, d1 & M64, 0, relative=False))
                else:
                    segs.append(Slot(n, 0, d1 & M64, 0, relative=True))
                cur += n * d1
            open_r0 = None
        else:
            raise ValueError(f"unknown breakpoint kind {kind!r}")
        p_prev = p
    segs.append(_hold(0, open_r0))
    if len(segs) > NSLOT:
        raise ValueError(f"profile needs {len(segs)} slots, the generator has {NSLOT}")
    return segs


def _hold(length: int, r0) -> Slot:
    if r0 is None:
        return Slot(length, 0, 0, 0, relative=True)
    return Slot(length, r0 & M64, 0, 0, relative=False)


def profile_values(slots, n: int, init: int = 0, N: int = 4, start_slot: int = 0) -> list[int]:
    """Head values (period 0 .. n-1 after the start) of ``slots`` run on a fresh generator
    synced to ``init``: the sequence w_{k+N} that the RTL produces."""
    g = RefGen(N)
    g.load_program(slots, start_slot)
    g.sync(init)
    g.start(start_slot)
    return [g.advance()[-1] for _ in range(n)]
