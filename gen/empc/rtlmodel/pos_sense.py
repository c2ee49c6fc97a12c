"""Bit-exact model of ``rtl/pos_sense.v``: electrical angle, alignment, speed (eq. 37).

Angle of a mechanical position ``m = (pos - ref) mod cpr``::

    theta = ((m * mul + 2**(s-1)) >> s) + base      (mod 2**angle_bits)
    mul   = round(p * 2**(angle_bits + s) / cpr)    (round half up)

:func:`angle_params` picks ``s`` like the RTL (largest ``s <= 24`` with
``mul < 2**mul_w``, ``mul_w = 17`` = one DSP48A1), :func:`angle` is the
bit-exact function, :func:`angle_error_bound` the bound in LSB against the exact
``2**angle_bits * frac(p * m / cpr)``.  :class:`PosSense` is the cycle-exact
stepping model (bit-serial modular tracking, HALL/index alignment, sampling).
"""
from __future__ import annotations

from fractions import Fraction

from .. import formats as F

ANGLE_BITS = F.ANGLE_BITS
MAX_SHIFT = 24


def _mul(cpr: int, p: int, angle_bits: int, s: int) -> int:
    num = p << (angle_bits + s)
    return (2 * num + cpr) // (2 * cpr)


def angle_params(cpr: int, p: int, angle_bits: int = ANGLE_BITS, mul_w: int = 17,
                 shift: int | None = None) -> tuple[int, int]:
    """(mul, s) as the RTL computes them; ``shift=None`` is the RTL's automatic choice."""
    if shift is None or shift < 0:
        shift = 0
        for s in range(MAX_SHIFT + 1):
            if _mul(cpr, p, angle_bits, s) < (1 << mul_w):
                shift = s
    return _mul(cpr, p, angle_bits, shift), shift


def angle(m: int, cpr: int, p: int, base: int = 0, angle_bits: int = ANGLE_BITS,
          mul_w: int = 17, shift: int | None = None) -> int:
    """Bit-exact electrical angle of mechanical position ``m`` (any int, reduced mod cpr)."""
    mul, s = angle_params(cpr, p, angle_bits, mul_w, shift)
    m %= cpr
    half = (1 << (s - 1)) if s > 0 else 0
    return (((m * mul + half) >> s) + base) & ((1 << angle_bits) - 1)


def angle_exact(m: int, cpr: int, p: int, base: int = 0, angle_bits: int = ANGLE_BITS) -> Fraction:
    """Exact angle 2**angle_bits * frac(p*m/cpr) + base, as a Fraction in [0, 2**angle_bits)."""
    full = 1 << angle_bits
    x = Fraction(full * ((p * m) % cpr), cpr) + base
    return x % full


def angle_error_bound(cpr: int, p: int, angle_bits: int = ANGLE_BITS, mul_w: int = 17,
                      shift: int | None = None) -> float:
    """Bound on |angle - angle_exact| in LSB: 0.5 + (cpr-1)*|mul - p*2**(ab+s)/cpr| / 2**s."""
    mul, s = angle_params(cpr, p, angle_bits, mul_w, shift)
    eps = abs(Fraction(mul) - Fraction(p << (angle_bits + s), cpr))
    return float((Fraction(1, 2) if s > 0 else 1) + (cpr - 1) * eps / (1 << s))


def angle_error(a: int, m: int, cpr: int, p: int, base: int = 0, angle_bits: int = ANGLE_BITS) -> float:
    """Signed circular difference a - angle_exact(m) in LSB."""
    full = 1 << angle_bits
    d = (Fraction(a) - angle_exact(m, cpr, p, base, angle_bits)) % full
    if d >= full // 2:
        d -= full
    return float(d)


def hall_angle(k: int, angle_bits: int = ANGLE_BITS) -> int:
    """round(k * 2**angle_bits / 12) mod 2**angle_bits (k = 0..11: sector edges and centres)."""
    return ((k << angle_bits) + 6) // 12 & ((1 << angle_bits) - 1)


def sector_start(s: int, angle_bits: int = ANGLE_BITS) -> int:
    return hall_angle(2 * s - 2, angle_bits)


def sector_centre(s: int, angle_bits: int = ANGLE_BITS) -> int:
    return hall_angle(2 * s - 1, angle_bits)


def sector_end(s: int, angle_bits: int = ANGLE_BITS) -> int:
    return hall_angle((2 * s) % 12, angle_bits)


def _next_sector(s: int) -> int:
    return 1 if s == 6 else s + 1


class PosSense:
    """Cycle-exact model of one ``pos_sense``; :meth:`step` is one rising clock edge.

    Inputs of :meth:`step` are the values present before the edge; afterwards
    the attributes hold the registered outputs: ``theta``, ``valid``,
    ``aligned``, ``pos_mod``, ``speed`` (unsigned pos_w pattern), ``speed_q``
    (unsigned w_w pattern), ``speed_sat``, ``pos_at_sample``,
    ``theta_at_sample``, ``sample_valid``; ``theta_ok`` is combinational (theta is the final
    angle of the count of the inputs of the last step: not dirty before the last two edges nor
    now; dirty = pos != last_pos, the reducer busy, or an alignment event).
    """

    OUTPUTS = ("theta", "valid", "aligned", "theta_ok", "pos_mod", "speed", "speed_q", "speed_sat",
               "pos_at_sample", "theta_at_sample", "sample_valid")

    def __init__(self, cpr: int, p: int, pos_w: int = F.POS_W, angle_bits: int = ANGLE_BITS,
                 mul_w: int = 17, shift: int | None = None, w_w: int = F.W_W, w_frac: int = F.W_FRAC,
                 realign: bool = False):
        self.cpr, self.p, self.pos_w, self.ab = cpr, p, pos_w, angle_bits
        self.realign = bool(realign)
        self.w_w, self.w_frac = w_w, w_frac
        self.mul, self.s = angle_params(cpr, p, angle_bits, mul_w, shift)
        self.reset()

    def reset(self) -> None:
        self.last_pos = 0
        self.r = 0          # signed
        self.k = 0          # weight 2**k of r's bit 0
        self.m = 0
        self.busy = 0
        self.al = 0
        self.rel_cal = 0    # not aligned, base_rel relative to cal_offset (after align_clear)
        self.hall_init = 0
        self.last_sector = 0
        self.base_rel = 0
        self.prod = 0
        self.base_d = 0
        self.v1 = 0
        self.al1 = 0
        self.theta = 0
        self.valid = 0
        self.aligned = 0
        self.speed = 0
        self.speed_q = 0
        self.speed_sat = 0
        self.pos_at_sample = 0
        self.theta_at_sample = 0
        self.sample_valid = 0
        self.have_prev = 0
        self.ok1 = 0
        self.okq = 0
        self._inp = {}

    def _events(self, index_event, hall_valid, hall_change, align_clear):
        ev_hall_init = (not self.al) and (not self.hall_init) and hall_valid
        ev_hall_chg = (not self.al) and self.hall_init and hall_valid and hall_change
        ev_index = index_event and ((not self.al) or align_clear or self.realign)
        return bool(ev_hall_init), bool(ev_hall_chg), bool(ev_index)

    def _dirty(self, pos=0, index_event=0, index_pos=0, hall_valid=0, hall_change=0, align_clear=0,
               **_unused) -> bool:
        """Counts not yet in m (pos != last_pos or the reducer busy) or an alignment event now."""
        pmask = (1 << self.pos_w) - 1
        hi, hc, ix = self._events(index_event, hall_valid, hall_change, align_clear)
        d = (pos - (index_pos if ix else self.last_pos)) & pmask
        return bool(d != 0 or self.busy or hi or hc or ix)

    @property
    def theta_ok(self) -> int:
        """Combinational: theta is the final angle of the count present now (inputs of the last step)."""
        return int(bool(self.okq) and not self._dirty(**self._inp))

    @property
    def pos_mod(self) -> int:
        return self.m

    def outputs(self) -> dict:
        return {k: getattr(self, k) for k in self.OUTPUTS}

    def step(self, pos: int, index_event: int = 0, index_pos: int = 0, hall_sector: int = 0,
             hall_valid: int = 0, hall_change: int = 0, cal_offset: int = 0, hall_offset: int = 0,
             align_clear: int = 0, sample: int = 0) -> "PosSense":
        pw, amask = self.pos_w, (1 << self.ab) - 1
        pmask = (1 << pw) - 1
        pos &= pmask
        index_pos &= pmask
        cpr = self.cpr
        inp = dict(pos=pos, index_event=index_event, index_pos=index_pos, hall_valid=hall_valid,
                   hall_change=hall_change, align_clear=align_clear)
        dirty = self._dirty(**inp)
        ok1, okq = int(not dirty), int(bool(self.ok1) and not dirty)
        # ---- next state of the tracker / alignment (from pre-edge values) ----
        ev_hall_init, ev_hall_chg, ev_index = self._events(index_event, hall_valid, hall_change, align_clear)
        ev_hall = ev_hall_init or ev_hall_chg
        ev_any = ev_index or ev_hall
        m, last_pos, r, k, busy = self.m, self.last_pos, self.r, self.k, self.busy
        # d: new counts, or at an index event the lag pos - index_pos (m restarts at the index)
        d = (pos - (index_pos if ev_index else self.last_pos)) & pmask
        load = (not self.busy) or ev_any
        if load:
            last_pos, r, k = pos, F.wrap(d, pw), 0
        else:
            r, k = self.r >> 1, self.k + 1
        if ev_any:
            m = 0
        elif self.busy and (self.r & 1):
            step = -(1 << self.k) if self.r == -1 else (1 << self.k)
            m = (self.m + step) % cpr
        if ev_hall and not ev_index:
            busy = 0
        elif load:
            busy = int(d != 0)
        elif self.r in (0, 1, -1):          # r >> 1 == 0, or remainder -1: last bit
            busy = 0
        al, base_rel, rel_cal = self.al, self.base_rel, self.rel_cal
        if ev_index:
            al, base_rel = 1, 0
        elif align_clear and self.al:
            al, rel_cal, base_rel = 0, 1, 0
        elif ev_hall:
            rel_cal = 0
            # the RTL's HALL ROM (one rule for both models; 0 for the invalid sectors 0 and 7)
            base_rel = hall_rom(self.hall_init, self.last_sector, hall_sector, self.ab)
        hall_init, last_sector = self.hall_init, self.last_sector
        if hall_valid and ((not self.hall_init) or hall_change):
            hall_init, last_sector = 1, hall_sector
        # ---- angle pipeline ----
        half = (1 << (self.s - 1)) if self.s > 0 else 0
        theta = ((self.prod >> self.s) + self.base_d) & amask
        prod = self.m * self.mul + half
        base_d = (self.base_rel + (cal_offset if (self.al or self.rel_cal) else hall_offset)) & amask
        v1 = int(bool(self.al or self.hall_init))
        valid, aligned, al1 = self.v1, self.al1, self.al
        # ---- sampling ----
        sample_valid = int(bool(sample))
        if sample:
            diff = (pos - self.pos_at_sample) & pmask
            if self.have_prev:
                ds = F.wrap(diff, pw)
                q, sat = F.sat_flag(ds << self.w_frac, self.w_w)
                self.speed_sat = int(sat)
                self.speed_q = q & ((1 << self.w_w) - 1)
                self.speed = diff
            else:
                self.speed, self.speed_q, self.speed_sat = 0, 0, 0
            self.have_prev = 1
            self.pos_at_sample = pos
            self.theta_at_sample = self.theta
        self.sample_valid = sample_valid
        # ---- commit ----
        self.m, self.last_pos, self.r, self.k, self.busy = m, last_pos, r, k, busy
        self.al, self.base_rel, self.rel_cal = al, base_rel, rel_cal
        self.hall_init, self.last_sector = hall_init, last_sector
        self.prod, self.base_d, self.v1, self.al1 = prod, base_d, v1, al1
        self.theta, self.valid, self.aligned = theta, valid, aligned
        self.ok1, self.okq, self._inp = ok1, okq, inp
        return self


def hall_rom(hall_init: int, last_sector: int, sector: int, angle_bits: int = ANGLE_BITS) -> int:
    """The HALL angle word of the RTL's ROM at {hall_init, last_sector, sector} (0 for sectors 0, 7)."""
    if not 1 <= sector <= 6:
        return 0
    if not hall_init:
        return sector_centre(sector, angle_bits)
    if sector == (last_sector + 1) % 8 or (last_sector == 6 and sector == 1):
        return sector_start(sector, angle_bits)
    if last_sector == _next_sector(sector):
        return sector_end(sector, angle_bits)
    return sector_centre(sector, angle_bits)


class PosSenseMx:
    """Cycle-exact model of ``pos_sense`` with ``NAXES > 1``: one shared engine.

    :meth:`step` takes every input as a list of NAXES values (``pos``, ``index_event``,
    ``index_pos``, ``hall_sector``, ``hall_valid``, ``hall_change``, ``cal_offset``,
    ``hall_offset``, ``align_clear``, ``sample``); :meth:`outputs` gives, per output name of
    :attr:`OUTPUTS`, the list over the axes after the edge.

    Engine: the reducer visits the axes in the fixed order 0, 1, ..., NAXES-1, 0, ...  A visit
    captures d = pos - last_pos of that axis (pos - index_pos after an index alignment); a visit
    without work (pos = last_pos, no index alignment pending) costs one clock, else the job takes
    one clock per bit of d (POS_W at most; 1 for d = 0 after an index) and the next visit is
    captured in the clock of the last bit.  An alignment event of an axis restarts its m at once (its job,
    if running, ends).  The angle pipeline samples one axis per clock, round robin, and writes
    its theta / valid / aligned 3 clocks later; theta_ok tags the sample.
    """

    OUTPUTS = PosSense.OUTPUTS

    def __init__(self, naxes: int, cpr: int, p: int, pos_w: int = F.POS_W, angle_bits: int = ANGLE_BITS,
                 mul_w: int = 17, shift: int | None = None, w_w: int = F.W_W, w_frac: int = F.W_FRAC,
                 realign: bool = False):
        assert naxes >= 2
        self.n = naxes
        self.cpr, self.p, self.pos_w, self.ab = cpr, p, pos_w, angle_bits
        self.realign = bool(realign)
        self.w_w, self.w_frac = w_w, w_frac
        self.mul, self.s = angle_params(cpr, p, angle_bits, mul_w, shift)
        self.reset()

    def reset(self) -> None:
        n = self.n
        z = lambda: [0] * n  # noqa: E731
        self.lp, self.ip, self.ipend, self.m = z(), z(), z(), z()
        self.al, self.rel_cal, self.hall_init, self.last_sector = z(), z(), z(), z()
        self.ha = [None] * n            # (hall_init, last_sector, sector) of the last HALL event, None = base 0
        self.cur, self.busy, self.r, self.k = n - 1, 0, 0, 0
        self.ap = 0
        self.st1 = dict(a=0, m=0, hq=0, off=0, c=0, v=0, l=0)
        self.st2 = dict(a=0, prod=0, base=0, c=0, v=0, l=0)
        self.st3 = dict(a=0, th=0, c=0, v=0, l=0)
        self.theta, self.valid, self.aligned, self.okq = z(), z(), z(), z()
        self.speed, self.speed_q, self.speed_sat = z(), z(), z()
        self.pos_at_sample, self.theta_at_sample, self.sample_valid, self.have_prev = z(), z(), z(), z()
        self._inp = None

    # ---- combinational helpers (from the current state and the inputs of this clock) ----
    def _events(self, a, inp):
        ev_hall = bool((not self.al[a]) and inp["hall_valid"][a] and ((not self.hall_init[a]) or inp["hall_change"][a]))
        ev_index = bool(inp["index_event"][a] and ((not self.al[a]) or inp["align_clear"][a] or self.realign))
        return ev_hall, ev_index

    def _dirty(self, a, inp) -> bool:
        ev_hall, ev_index = self._events(a, inp)
        return bool(self.ipend[a] or inp["pos"][a] != self.lp[a] or (self.busy and self.cur == a)
                    or ev_hall or ev_index)

    @property
    def pos_mod(self):
        return list(self.m)

    @property
    def theta_ok(self):
        if self._inp is None:
            return [0] * self.n
        return [int(bool(self.okq[a]) and not self._dirty(a, self._inp)) for a in range(self.n)]

    def outputs(self) -> dict:
        return {k: list(getattr(self, k)) for k in self.OUTPUTS}

    def step(self, **inp) -> "PosSenseMx":
        n, pw, ab = self.n, self.pos_w, self.ab
        pmask, amask = (1 << pw) - 1, (1 << ab) - 1
        inp = {k: list(v) for k, v in inp.items()}
        inp["pos"] = [x & pmask for x in inp["pos"]]
        inp["index_pos"] = [x & pmask for x in inp["index_pos"]]
        ev = [self._events(a, inp) for a in range(n)]
        ev_any = [h or i for h, i in ev]
        dirty = [self._dirty(a, inp) for a in range(n)]
        # ---- engine ----
        cur, busy, r, k = self.cur, self.busy, self.r, self.k
        nxt = (cur + 1) % n
        ref = self.ip[nxt] if self.ipend[nxt] else self.lp[nxt]
        d = (inp["pos"][nxt] - ref) & pmask
        fin = busy and (r in (0, 1, -1) or ev_any[cur])
        load = (not busy) or fin
        m_new = None
        if busy and (r & 1) and not ev_any[cur]:
            step = -(1 << k) if r == -1 else (1 << k)
            m_new = (self.m[cur] + step) % self.cpr
        if load:
            work = inp["pos"][nxt] != self.lp[nxt] or self.ipend[nxt]
            n_cur, n_r, n_k, n_busy = nxt, F.wrap(d, pw), 0, int(bool(work) and not ev_any[nxt])
        else:
            n_cur, n_r, n_k, n_busy = cur, r >> 1, k + 1, busy
        # ---- angle pipeline (pre-edge values) ----
        ap = self.ap
        half = (1 << (self.s - 1)) if self.s > 0 else 0
        ha = self.ha[ap]
        s1 = dict(a=ap, m=self.m[ap], hq=0 if ha is None else hall_rom(*ha, angle_bits=ab),
                  off=inp["cal_offset"][ap] if (self.al[ap] or self.rel_cal[ap]) else inp["hall_offset"][ap],
                  c=int(not dirty[ap]), v=int(bool(self.al[ap] or self.hall_init[ap])), l=self.al[ap])
        o1, o2, o3 = self.st1, self.st2, self.st3
        s2 = dict(a=o1["a"], prod=o1["m"] * self.mul, base=(o1["hq"] + o1["off"]) & amask,
                  c=int(o1["c"] and not dirty[o1["a"]]), v=o1["v"], l=o1["l"])
        s3 = dict(a=o2["a"], th=(((o2["prod"] + half) >> self.s) + o2["base"]) & amask,
                  c=int(o2["c"] and not dirty[o2["a"]]), v=o2["v"], l=o2["l"])
        theta_pre = list(self.theta)
        for a in range(n):
            if o3["a"] == a:
                self.theta[a], self.valid[a], self.aligned[a] = o3["th"], o3["v"], o3["l"]
                self.okq[a] = int(o3["c"] and not dirty[a])
            else:
                self.okq[a] = int(self.okq[a] and not dirty[a])
        self.st1, self.st2, self.st3, self.ap = s1, s2, s3, (ap + 1) % n
        # ---- per-axis state ----
        for a in range(n):
            ev_hall, ev_index = ev[a]
            pos_a, ac = inp["pos"][a], inp["align_clear"][a]
            eng_ld = load and nxt == a
            hi, ls, al = self.hall_init[a], self.last_sector[a], self.al[a]
            sec = inp["hall_sector"][a]
            if ev_hall or eng_ld:
                self.lp[a] = pos_a
            if ev_index:
                self.ip[a] = inp["index_pos"][a]
                self.ipend[a] = 1
            elif ev_hall or eng_ld:
                self.ipend[a] = 0
            if ev_any[a]:
                self.m[a] = 0
            elif m_new is not None and cur == a:
                self.m[a] = m_new
            if ev_index:
                self.al[a] = 1
            elif ac and al:
                self.al[a], self.rel_cal[a] = 0, 1
            elif ev_hall:
                self.rel_cal[a] = 0
            if inp["hall_valid"][a] and ((not hi) or inp["hall_change"][a]):
                self.hall_init[a], self.last_sector[a] = 1, sec
            if ev_index or (ac and al):
                self.ha[a] = None
            elif ev_hall:
                self.ha[a] = (hi, ls, sec)
            # sampling
            self.sample_valid[a] = int(bool(inp["sample"][a]))
            if inp["sample"][a]:
                diff = (pos_a - self.pos_at_sample[a]) & pmask
                if self.have_prev[a]:
                    q, sat = F.sat_flag(F.wrap(diff, pw) << self.w_frac, self.w_w)
                    self.speed[a], self.speed_q[a], self.speed_sat[a] = diff, q & ((1 << self.w_w) - 1), int(sat)
                else:
                    self.speed[a], self.speed_q[a], self.speed_sat[a] = 0, 0, 0
                self.have_prev[a] = 1
                self.pos_at_sample[a] = pos_a
                self.theta_at_sample[a] = theta_pre[a]
        self.cur, self.busy, self.r, self.k = n_cur, n_busy, n_r, n_k
        self._inp = inp
        return self


def latency_bound(naxes: int, pos_w: int = F.POS_W) -> tuple[int, int]:
    """Clocks from a count change of one axis to its theta_ok (shared engine, NAXES > 1).

    Returns (simultaneous, any): ``simultaneous`` bounds every axis when all axes change their
    count in the same clock from an idle engine (one job per axis, at most pos_w bit clocks
    each); ``any`` bounds the last change of an axis in any situation (the engine may have just
    captured that axis's previous count: its stale job, the other axes' jobs, then its own).
    Both include the wait for the angle pipeline's round robin (naxes - 1) and its 4 stages.
    """
    pipe = (naxes - 1) + 4
    return naxes * pos_w + 1 + pipe, (naxes + 1) * pos_w + 1 + pipe
