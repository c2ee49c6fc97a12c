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
timing clock by clock, the other methods act at once.  :class:`RefGenAxes` is the RTL's
NAXES parameter: NAXES of these generators on the one shared engine, clock by clock.  Slots are written one
32-bit field at a time (:meth:`RefGen.write_field`, fields :data:`FIELDS`).

:func:`segments_from_points` turns a step/ramp profile in SI units into slots.

Reference governor (issue 15 item 4, gen/empc/governor.py for the float form): with the
governor enabled the profile above runs on the *target* r, and the head w_{k+N} is the
governed g.  Per advance, r_old -> r_new (the profile's advance), and in 64-bit two's
complement Q.32 (exact integers where stated; s64 = the signed value of a 64-bit word):

    vd  = s64(r_new - r_old) + (s64(r_old - g) >> ksh)              (exact, 65 bit)
    vd  = vmax if vd > vmax, -vmax if vd < -vmax
    speed task, hold, and not (s64(g) != 0 and sign(vd) != sign(s64(g))): vd = 0
                                   (one-sided: vd passes only towards lower |g|; sign of the exact vd)
    position task, brake (below): vd = 0
    dv  = vd - s64(v)                                                (exact)
    dv  = a if dv > a, -a if dv < -a
    position task, hold or slow, dv != 0, v != 0 and sign(dv) = sign(v): dv = 0
    v   = s64(v + dv);  g = g + v (mod 2^64)

Braking distance (position task, :func:`brake_zone`, :func:`brake_update`): the state V (a
multiple n of a, tracked one step per advance so that V - a < |v| <= V) and B = a n (n + 1) / 2,
the distance a reference at a speed <= V travels while braking at a (this period's step included).
With the target holding (r_new = r_old), v != 0 moving towards it (sign(v) = sign(e), e = r_old - g)
and |e| (mod 2^64): brake = s64(|e| - B) < 0, slow = s64(|e| - (B + 2V)) < 0 (no speed-up; B + 2V >=
B of n + 1).  After the step, w = |v| by the sign of the old v (of the exact dv when v was 0):
s64(w - V - 1) >= 0 -> V += a, B += V;  else s64(w + a - V - 1) < 0 -> B -= V, V -= a (mod 2^64).
Adds and compares only: the RTL computes the zones in G1, the compares in G4 and the update in G5.

vmax and a are 63-bit unsigned (bit 63 of each reads as 0); they sit with ksh and enable in
field 7 of slots 0..4 (:data:`GOV_SLOTS`, register SEG_GOV).  ``hold`` and the task come from
the axis (``advance(hold=..., task_pos=...)``).  Disabled: g = r, v = 0 (the plain generator).
A sync sets r, g and the delay line to the sync value and v, V, B to 0.  ``clamped`` tells whether
the last advance changed the reference (hold or a clamp: the SAT_GOV event).  A held target is
reached to within 2^ksh LSB of Q.32 (where e >> ksh becomes 0): 2^-29 counts for ksh = 3.
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
GOV_FIELD = 7                                                          # register SEG_GOV
GOV_SLOTS = {"vmax_lo": 0, "vmax_hi": 1, "a_lo": 2, "a_hi": 3, "cfg": 4}  # field 7 of these slots
GOV_KSH_LSB = 8                                                        # cfg word: bit 0 enable, ksh [12:8]
M63 = (1 << 63) - 1


def speed_hold_passes(vd: int, g: int) -> bool:
    """Speed-task hold: does the (exact, signed) demand ``vd`` pass, i.e. point towards lower |g|
    (``g`` the governed reference, a 64-bit word)?  g = 0: never (any vd raises |g|)."""
    gs = wrap(g, 64)
    return gs != 0 and (vd < 0) != (gs < 0)


def speed_hold_case(gp: dict, r_old: int, r_new: int, g: int) -> tuple[bool, bool]:
    """(g < 0, vd passes) of a speed-task hold with these operands (the block test counts the cases)."""
    vd0 = wrap(r_new - r_old, 64) + (wrap(r_old - g, 64) >> gp["ksh"])
    return wrap(g, 64) < 0, speed_hold_passes(vd0, g)


def brake_zone(gp: dict, v: int, vq: int, bq: int, x1: int, e: int, task_pos: bool) -> tuple[bool, bool]:
    """Position task, braking distance (module docstring): (brake, no speed-up) of an advance with the
    target step x1 = r_new - r_old, e = r_old - g and the braking state vq, bq (64-bit words)."""
    vs, es = wrap(v, 64), wrap(e, 64)
    if not (task_pos and x1 & M64 == 0 and vs != 0 and (vs < 0) == (es < 0)):
        return False, False
    ae = -es & M64 if es < 0 else es                    # |e| (mod 2^64)
    lt0 = wrap(ae - bq, 64) < 0 and bq > vq             # |e| < B, and n >= 2 (B > V: |v| <= a stops in time)
    lt1 = wrap(ae - (bq + 2 * vq), 64) < 0              # |e| < B + 2 V
    return lt0, lt1


def brake_update(a: int, v_old: int, dv0: int, v_new: int, vq: int, bq: int) -> tuple[int, int]:
    """The braking state after an advance (pass G4 compares, G5 updates): V = n a tracks |v| from above
    (up by a when |v| > V, down when |v| + a <= V), B = a n (n + 1) / 2 (B += V' up, B -= V down); the
    sign of |v| is that of the old v, or of the exact dv0 when v was 0 (64-bit words, mod 2^64)."""
    vs = wrap(v_old, 64)
    s = vs < 0 if vs != 0 else dv0 < 0
    w = -v_new & M64 if s else v_new & M64
    up = wrap(w - vq - 1, 64) >= 0                      # |v'| > V
    dn = wrap(w + a - vq - 1, 64) < 0                   # |v'| + a <= V
    if up:
        vq = (vq + a) & M64
        bq = (bq + vq) & M64
    elif dn:
        bq = (bq - vq) & M64
        vq = (vq - a) & M64
    return vq, bq


def gov_step(gp: dict, v: int, r_old: int, r_new: int, g: int, hold: bool, task_pos: bool,
             vb: tuple[int, int] = (0, 0)) -> tuple[int, int, bool, tuple[int, int]]:
    """One governor step (module docstring): returns (g_new, v_new, clamped, (V, B)), 64-bit words; ``vb``
    is the braking state (V, B) before the step."""
    if not gp["enable"]:
        return r_new & M64, 0, False, (0, 0)
    vmax, a = gp["vmax"], gp["a"]
    vq, bq = vb
    x1 = wrap(r_new - r_old, 64)
    vd0 = x1 + (wrap(r_old - g, 64) >> gp["ksh"])
    vd = vmax if vd0 > vmax else -vmax if vd0 < -vmax else vd0
    brake, slow = brake_zone(gp, v, vq, bq, x1, r_old - g, task_pos)
    if (hold and not task_pos and not speed_hold_passes(vd0, g)) or brake:
        vd = 0
    vs = wrap(v, 64)
    dv0 = vd - vs
    dv = a if dv0 > a else -a if dv0 < -a else dv0
    if (hold or slow) and task_pos and dv != 0 and vs != 0 and (dv > 0) == (vs > 0):
        dv = 0
    clamped = bool(hold or vd0 > vmax or vd0 < -vmax or dv0 > a or dv0 < -a)
    v_new = (vs + dv) & M64
    return (g + v_new) & M64, v_new, clamped, brake_update(a, v, dv0, v_new, vq, bq)


def gov_words(vmax: int, a: int, ksh: int, enable: bool) -> dict[int, int]:
    """Field-7 words {slot: word} that program the governor (see governor.raw_params)."""
    if not (0 <= vmax <= M63 and 0 <= a <= M63 and 0 <= ksh < 32):
        raise ValueError(f"governor parameters out of range: vmax={vmax} a={a} ksh={ksh}")
    return {GOV_SLOTS["vmax_lo"]: vmax & M32, GOV_SLOTS["vmax_hi"]: vmax >> 32,
            GOV_SLOTS["a_lo"]: a & M32, GOV_SLOTS["a_hi"]: a >> 32,
            GOV_SLOTS["cfg"]: int(bool(enable)) | (ksh << GOV_KSH_LSB)}


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
PASS_CLOCKS = {"flags": 3, "head": 65, "d1": 65, "d2": 33, "len": 33, "sync": 65, "gov": 65}
GOV_PASSES = 5                  # governor passes after the head pass (G1..G5)
GOV_W_PASSES = 4                # the 4th (G4) shifts the delay line; G5 updates the braking state


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
        self.gmem = [0] * NSLOT            # field 7 of each slot (governor words), block RAM too
        self.gcfg = 0                      # enable / ksh register (loaded by the field-7 write of slot 4)
        # statistics for the tests (not state): speed-task holds by (g < 0, vd passes), counted when the
        # advance is computed (clock level: when it begins; the snapshot shares this dict)
        self.hold_cases = {(n, p): 0 for n in (False, True) for p in (False, True)}
        self.brake_cases = {"brake": 0, "slow": 0, "up": 0, "down": 0, "vq_max": 0}    # braking zones and V steps
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
        self.r = 0                         # target (the profile); = head when the governor is off
        self.v = 0                         # governed increment per period
        self.vb = (0, 0)                   # braking state (V, B) of the position task
        self.clamped = False
        self._op = None                    # running operation: dict(kind, clocks left, ...)
        self._sync_value = 0
        self._hold = False
        self._task_pos = False
        self.gov_ev = False                # RTL gov_ev in this clock (clock level)
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
        if field == GOV_FIELD:
            self.gmem[idx % NSLOT] = value & M32
            if idx % NSLOT == GOV_SLOTS["cfg"]:
                self.gcfg = value & (1 | (31 << GOV_KSH_LSB))
            return
        self.mem[idx % NSLOT] = with_field(self.mem[idx % NSLOT], field, value)

    def read_field(self, idx: int, field: int) -> int:
        if field == GOV_FIELD:
            return self.gmem[idx % NSLOT]
        return slot_field(self.mem[idx % NSLOT], field)

    def write_gov(self, vmax: int, a: int, ksh: int, enable: bool) -> None:
        for slot, word in gov_words(vmax, a, ksh, enable).items():
            self.write_field(slot, GOV_FIELD, word)

    @property
    def gov(self) -> dict:
        g = self.gmem
        return {"enable": bool(self.gcfg & 1), "ksh": (self.gcfg >> GOV_KSH_LSB) & 31,
                "vmax": (g[GOV_SLOTS["vmax_lo"]] | g[GOV_SLOTS["vmax_hi"]] << 32) & M63,
                "a": (g[GOV_SLOTS["a_lo"]] | g[GOV_SLOTS["a_hi"]] << 32) & M63}

    def start(self, slot: int) -> None:
        self.pend, self.pend_slot = True, slot % NSLOT

    def sync(self, value: int) -> None:
        """Head and the whole delay line = ``value``, differences 0, hold (a pending start survives)."""
        v = value & M64
        self.head = self.r = v
        self.dl = [v] * self.N
        self.d1 = self.d2 = self.rem = self.v = 0
        self.vb = (0, 0)
        self.ends = self.last = False

    def advance(self, hold: bool = False, task_pos: bool = False) -> list[int]:
        self._hold, self._task_pos = bool(hold), bool(task_pos)
        self._advance()
        return self.w

    def load_program(self, slots, base: int = 0) -> None:
        for i, s in enumerate(slots):
            self.write_slot(base + i, s)

    def _advance(self) -> None:
        old_head = self.head
        r_old = self.r
        h1 = (r_old + self.d1) & M64
        d1n = (self.d1 + self.d2) & M64
        seg_end = self.ends and self.rem == 1
        do_start = self.pend
        ld = self.pend_slot if self.pend else (self.slot + 1) % NSLOT
        self.pend = False
        if do_start or (seg_end and not self.last):
            s = self.mem[ld]
            self.r = h1 if s.relative else s.r0
            self.d1, self.d2, self.rem = s.d1, s.d2, s.length
            self.ends, self.last, self.slot = s.length != 0, s.last, ld
        elif seg_end:                       # last: hold
            self.r = h1
            self.d1 = self.d2 = self.rem = 0
            self.ends = False
        else:
            self.r = h1
            self.d1 = d1n
            if self.ends:
                self.rem -= 1
        self.head = self._govern(r_old, self.r, old_head)
        self.dl = self.dl[1:] + [old_head]

    def _govern(self, r_old: int, r_new: int, g: int) -> int:
        """The governed head after an advance of the target from r_old to r_new (g: the old head)."""
        if self._hold and not self._task_pos and self.gov["enable"]:
            self.hold_cases[speed_hold_case(self.gov, r_old, r_new, g)] += 1
        gp = self.gov
        if gp["enable"]:
            br = brake_zone(gp, self.v, *self.vb, wrap(r_new - r_old, 64), r_old - g, self._task_pos)
            for k, z in zip(("brake", "slow"), br):
                self.brake_cases[k] += int(z)
        g_new, self.v, self.clamped, vb = gov_step(gp, self.v, r_old, r_new, g, self._hold, self._task_pos, self.vb)
        if gp["enable"]:
            self.brake_cases["up"] += int(vb[0] > self.vb[0])
            self.brake_cases["down"] += int(vb[0] < self.vb[0])
            self.brake_cases["vq_max"] = max(self.brake_cases["vq_max"], vb[0] // max(1, gp["a"]))
        self.vb = vb
        return g_new

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
        snap.gmem = list(self.gmem)
        snap._hold, snap._task_pos = self._hold_in, self._task_pos_in
        snap._advance()
        gov = self.gov["enable"]
        w_left = PASS_CLOCKS["head"] + (GOV_W_PASSES * PASS_CLOCKS["gov"] if gov else 0)
        clocks = PASS_CLOCKS["head"] + (GOV_PASSES * PASS_CLOCKS["gov"] if gov else 0)
        if load:
            clocks += sum(PASS_CLOCKS[k] for k in ("flags", "d1", "d2", "len"))
            w_left += PASS_CLOCKS["flags"]
        self.pend = False                          # consumed (a start in this clock re-pends)
        self._op = {"kind": "advance", "left": clocks, "w_left": w_left, "w_done": False,
                    "load": load, "slot": ld, "result": snap, "gov": gov}

    def step(self, seg_we: bool = False, seg_slot: int = 0, seg_field: int = 0, seg_wdata: int = 0,
             start: bool = False, start_slot: int = 0, sync: bool = False, sync_value: int = 0,
             advance: bool = False, hold: bool = False, task_pos: bool = False) -> None:
        """One rising clock edge with the given inputs (RTL priorities and timing).
        ``sync_value`` is sampled when the sync's first pass runs: keep it constant from the
        strobe until the sync has run (as the RTL requires); here it is taken at the strobe.  A field write
        lands before an advance that begins in the same clock reads the slot; the CPU must not
        write :attr:`loading_slot` while that advance runs (undefined in the RTL)."""
        if seg_we:                                 # port A write: seen by an advance beginning now
            self.write_field(seg_slot, seg_field, seg_wdata)
        self._hold_in, self._task_pos_in = bool(hold), bool(task_pos)   # sampled when an advance begins
        self.gov_ev = False
        if self._op is not None:                   # the running operation advances one clock
            self._tick()
        elif self.sync_pend:                       # idle: begin an operation
            self._begin_pending()
        elif self.adv_pend:
            self._begin_pending()
        self._strobes(start, start_slot, sync, sync_value, advance)

    def _tick(self) -> None:
        """One clock of the running operation (RTL engine timing)."""
        op = self._op
        op["left"] -= 1
        if op["w_left"] is not None and not op["w_done"]:
            op["w_left"] -= 1
            if op["w_left"] == 0:
                r = op["result"]
                self.head, self.dl = r.head, list(r.dl)
                op["w_done"] = True
                self.gov_ev = op.get("gov", False) and r.clamped   # RTL gov_ev: the clock after G4
        if op["left"] == 0:
            if op["kind"] == "sync":
                v = op["value"]
                self.head, self.dl, self.r, self.v, self.vb = v, [v] * self.N, v, 0, (0, 0)
            else:
                r = op["result"]
                for k in ("d1", "d2", "rem", "ends", "last", "slot", "r", "v", "vb", "clamped"):
                    setattr(self, k, getattr(r, k))
            self._op = None

    def _begin_pending(self) -> None:
        """The engine begins this generator's pending operation: a sync first, else an advance."""
        if self.sync_pend:
            self.sync_pend = False
            self._begin_sync(self._sync_value)
        else:
            self.adv_pend = False
            self._begin_advance()

    def _strobes(self, start: bool, start_slot: int, sync: bool, sync_value: int, advance: bool) -> None:
        if advance:
            self.adv_pend = True
        if sync:
            self.sync_pend = True
            self._sync_value = sync_value & M64
        if start:
            self.pend, self.pend_slot = True, start_slot % NSLOT


class RefGenAxes:
    """``ref_gen`` with NAXES axes on its one shared engine (``rtl/ref_gen.v``, parameter NAXES).

    Each axis is a :class:`RefGen` (its slots, state, delay line, pending flags), unchanged; the
    engine runs one operation at a time for all of them, so an axis's operation may wait for
    another's.  Clock-level schedule (:meth:`step`): an engine that is idle at a clock begins the
    pending sync of the lowest-numbered axis, else the pending advance of the lowest-numbered
    axis; the operation then takes the single-axis clocks of :data:`PASS_CLOCKS` and touches only
    that axis.  After ``rst`` axis 0 runs its clearing sync at once and axes 1.. queue theirs
    (value 0; a CPU sync strobe on the axis before it runs supplies the value instead).
    At NAXES = 1 this is exactly :class:`RefGen`."""

    def __init__(self, N: int = 4, naxes: int = 1):
        if not 1 <= naxes <= 4:
            raise ValueError("naxes must be 1..4")
        self.N = N
        self.naxes = naxes
        self.axes = [RefGen(N) for _ in range(naxes)]

    def __getitem__(self, a: int) -> RefGen:
        return self.axes[a]

    def reset(self, settled: bool = False) -> None:
        for a, g in enumerate(self.axes):
            g.reset(settled=settled or a > 0)
            g.gov_ev = False
            if not settled and a > 0:
                g.sync_pend, g._sync_value = True, 0

    @property
    def engine_axis(self):
        """Axis whose operation the engine runs (None: idle)."""
        for a, g in enumerate(self.axes):
            if g._op is not None:
                return a
        return None

    def next_axis(self):
        """Axis whose operation an idle engine begins in this clock (None: nothing pending)."""
        for a, g in enumerate(self.axes):
            if g.sync_pend:
                return a
        for a, g in enumerate(self.axes):
            if g.adv_pend:
                return a
        return None

    def step(self, seg=None, start=None, sync=None, sync_value=None, advance=None, hold=None,
             task_pos=None) -> None:
        """One clock.  ``seg`` = (axis, slot, field, value) is a CPU field write; the others are
        per-axis lists (None: all 0) of the strobes and inputs of :meth:`RefGen.step`
        (``start`` holds the start slot or None)."""
        n = self.naxes
        start = start or [None] * n
        sync = sync or [False] * n
        sync_value = sync_value or [0] * n
        advance = advance or [False] * n
        hold = hold or [False] * n
        task_pos = task_pos or [False] * n
        if seg is not None:
            self.axes[seg[0]].write_field(seg[1], seg[2], seg[3])
        for a, g in enumerate(self.axes):
            g._hold_in, g._task_pos_in = bool(hold[a]), bool(task_pos[a])
            g.gov_ev = False
        run = self.engine_axis
        if run is not None:
            self.axes[run]._tick()
        else:
            nx = self.next_axis()
            if nx is not None:
                self.axes[nx]._begin_pending()
        for a, g in enumerate(self.axes):
            g._strobes(start[a] is not None, start[a] or 0, bool(sync[a]), sync_value[a], bool(advance[a]))


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
