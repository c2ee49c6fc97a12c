"""Bit-accurate, cycle-exact model of ``rtl/adc_spi.v`` (3-channel SPI current-ADC master,
back-to-back frames, per-frame checks, centred window mean for the controller).

Used by ``tb/test_adc_spi.py`` (every output, every clock) and by the RTL co-simulation
(``tb/test_closed_loop.py``: the controller's sample of a PWM period).  Pure Python.

Pieces:
  * :class:`AdcSpiParams`  - the RTL parameters and the schedule they imply, in clk cycles
    (frame grid, window, latencies).
  * :func:`frame_bits` / :func:`decode_frame` - the SPI frame on one MISO line.
  * :func:`correct`, :func:`overcurrent`, :func:`cal_mean`, :func:`window_mean`,
    :func:`sum_bad`, :func:`at_rail` - the arithmetic.
  * :class:`AdcSpiCycle` - the registers of the block, one :meth:`~AdcSpiCycle.step` per
    clock cycle (inputs of the cycle -> registers after its closing edge).

Cycle convention: inputs "in cycle c" are sampled at the edge that ends cycle c; a register
written at that edge is visible in cycle c + 1.  A frame is *accepted* in cycle a (grid point,
engine idle): CS falls at the edge ending cycle a (E0); with VL = ``valid_latency()`` the
frame's stage A (codes, differences) is computed in cycle a + VL - 1, stage B in a + VL
(``fvalid`` visible in a + VL + 1), and its serial pass runs in cycles a + VL + 1 + j,
j = 0 .. pass_len - 1.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from empc import formats, regmap

N_CH = 3


@dataclass(frozen=True)
class AdcSpiParams:
    """Parameters of ``adc_spi`` (same names, lower case) and the schedule they imply."""

    adc_bits: int = formats.ADC_BITS
    frame_bits: int = 16
    lead_zeros: int = 4
    sclk_div: int = 2
    sample_delay: int = 5
    cs_quiet: int = 5
    half_period: int = 0           # 0 = the default configuration's P (EMPC_PWM_HALF_PERIOD)
    avg_log2: int = 2
    frame_period: int = 0          # 0 = shortest (even when avg_log2 > 0)
    cal_log2: int = 10
    cur_w: int = formats.ADC_BITS + 1
    miss_w: int = 8
    offset_reset: int = 2048       # RTL default: `EMPC_ADC_OFFSET (config sensors.adc_offset)
    pcnt_w: int = 7
    sum_persist: int = regmap.ADC_SUM_FRAMES
    stuck_persist: int = regmap.ADC_STUCK_FRAMES
    frozen_periods: int = regmap.ADC_FROZEN_PERIODS

    def __post_init__(self):
        if not self.half_period:
            from .pwm_center import default_half_period
            object.__setattr__(self, "half_period", default_half_period())
        if self.lead_zeros < 1 or self.lead_zeros + self.adc_bits > self.frame_bits:
            raise ValueError("need 1 <= lead_zeros and lead_zeros + adc_bits <= frame_bits")
        if self.sclk_div < 1 or self.sample_delay < 3 or self.cs_quiet < 1 or self.cal_log2 < 1 or self.cur_w < 2:
            raise ValueError("need sclk_div >= 1, sample_delay >= 3, cs_quiet >= 1, cal_log2 >= 1, cur_w >= 2")
        if min(self.sum_persist, self.stuck_persist, self.frozen_periods) < 1 or self.avg_log2 < 0:
            raise ValueError("need sum_persist, stuck_persist, frozen_periods >= 1 and avg_log2 >= 0")
        tf = self.tf
        if tf < self.min_frame_period() or (self.avg_log2 > 0 and tf % 2):
            raise ValueError(f"frame_period {tf}: need >= {self.min_frame_period()} (and even when avg_log2 > 0)")
        if self.m0 < 1 or self.pass_len() + 2 > tf:
            raise ValueError("window too early in the period (M0 < 1) or frame period shorter than the serial pass")
        if self.t0 + self.n_window * tf + self.valid_latency() + self.pass_len() + 2 > 2 * self.half_period:
            raise ValueError("window (and its pass) does not end inside the PWM period")
        if (1 << self.pcnt_w) - 1 < (2 * self.half_period - 1) // tf + 1:
            raise ValueError("pcnt_w too small for the frames of one PWM period")

    # ---- frame timing, clk edges after the edge E0 that starts a frame ------------------
    def launch_edge(self, k: int) -> int:
        """Edge at which frame bit ``k`` is launched (k = 0: CS falls; else SCLK falling edge k)."""
        return 2 * k * self.sclk_div

    def capture_edge(self, k: int) -> int:
        """Edge at which the master latches bit ``k`` from the synchronised MISO."""
        return self.launch_edge(k) + self.sample_delay

    def last_sclk_rise(self) -> int:
        """Edge of the frame's last SCLK rising edge."""
        return (2 * self.frame_bits + 1) * self.sclk_div

    def cs_rise(self) -> int:
        """Edge at which CS rises again."""
        h = self.sclk_div
        return max((2 * self.frame_bits + 2) * h, 2 * (self.frame_bits - 1) * h + self.sample_delay + 1)

    def valid_latency(self) -> int:
        """VL: per-frame outputs are registered at edge E0 + VL (frame accepted in cycle a ->
        ``fvalid`` high in cycle a + 1 + VL)."""
        return 2 * (self.frame_bits - 1) * self.sclk_div + self.sample_delay + 2

    def oc_to_pins(self) -> int:
        """Clocks from the frame's last SCLK rising edge to the bridge outputs off: ``oc`` is
        registered at E0 + VL, the trip is combinational and pwm_center's output registers
        switch off at the next edge."""
        return self.valid_latency() + 1 - self.last_sclk_rise()

    def idle_after(self) -> int:
        """``busy`` is high in cycles a+1 .. a+idle_after() of a frame accepted in cycle a."""
        return max(self.cs_rise() + self.cs_quiet - 1, self.valid_latency())

    def min_frame_period(self) -> int:
        """Shortest distance (clk) between two frame starts."""
        return max(self.cs_rise() + self.cs_quiet, self.valid_latency() + 1)

    def sample_window_ns(self, t_clk_ns: float = 10.0) -> tuple[float, float]:
        """Allowed (round-trip-max, hold-min) pair: the pin is sampled at launch + (sample_delay-2) clk.

        Valid iff t_roundtrip_max + t_setup < (sample_delay - 2) * t_clk < 2 * sclk_div * t_clk + t_hold_min.
        """
        ts = (self.sample_delay - 2) * t_clk_ns
        return ts, ts - 2 * self.sclk_div * t_clk_ns

    # ---- grid and window, cycles after the period_start cycle ----------------------------
    @property
    def tf(self) -> int:
        """Frame period (clk)."""
        if self.frame_period:
            return self.frame_period
        m = self.min_frame_period()
        return m + (m % 2) if self.avg_log2 > 0 else m

    @property
    def n_window(self) -> int:
        return 1 << self.avg_log2

    @property
    def w_lead(self) -> int:
        """First window frame starts this many clk before the centre."""
        return (self.n_window - 1) * self.tf // 2

    @property
    def t0(self) -> int:
        return self.half_period - self.w_lead

    @property
    def g0(self) -> int:
        """First grid point, cycles after the period_start cycle (1 .. tf)."""
        return self.t0 % self.tf or self.tf

    @property
    def m0(self) -> int:
        """Grid index of the first window frame."""
        return (self.t0 - self.g0) // self.tf

    @property
    def gp_max(self) -> int:
        return 2 * self.half_period // self.tf + 2

    def window_taus(self) -> list[int]:
        """Accept cycles of the window frames relative to the centre (cycle half_period):
        symmetric, -(2^K - 1) TF / 2 .. +(2^K - 1) TF / 2."""
        return [-self.w_lead + j * self.tf for j in range(self.n_window)]

    def frames_per_period(self) -> int:
        """Frames whose stage B falls in a PWM period of 2 * half_period clocks (steady state):
        the value of ``pcount``."""
        tf, p2, vl = self.tf, 2 * self.half_period, self.valid_latency()
        starts = list(range(self.g0, p2, tf))
        if starts[0] <= starts[-1] - p2 + self.idle_after():    # the previous period's last frame is busy
            starts = starts[1:]
        allst = [a - p2 for a in starts] + starts
        return sum(1 for a in allst if 0 <= a + vl < p2)

    def aw(self) -> int:
        return self.adc_bits + 1 + self.avg_log2

    def sw(self) -> int:
        return self.adc_bits + 3

    def psw(self) -> int:
        return self.adc_bits + 1 + self.pcnt_w

    def pass_len(self) -> int:
        return max(self.aw() + 1 if self.avg_log2 else 0, self.sw(), self.psw())

    def valid_delay(self) -> int:
        """Cycles from the centre (``trig`` cycle) to ``valid`` of the controller sample."""
        if self.avg_log2 == 0:
            return self.valid_latency() + 1
        return self.w_lead + self.valid_latency() + self.aw() + 2

    def valid_after_last_bit(self) -> int:
        """Clocks from the last SCLK rising edge of the controller sample's last frame (the window's
        last, or the centre frame with avg_log2 = 0) to ``valid``: valid is registered at edge
        E0 + VL (+ AW + 1 after the serial mean pass), the rising edge at E0 + last_sclk_rise()."""
        return self.valid_latency() + (self.aw() + 1 if self.avg_log2 else 0) - self.last_sclk_rise()

    def sum_delay(self) -> int:
        """``sum_err`` of a frame changes this many cycles after its ``fvalid`` cycle."""
        return self.sw()

    @property
    def code_max(self) -> int:
        return (1 << self.adc_bits) - 1


# ---- frame -------------------------------------------------------------------------
def frame_bits(code: int, p: AdcSpiParams = AdcSpiParams(), lead: int = 0) -> list[int]:
    """Bits on one MISO line, in transmission order (bit 0 first)."""
    trail = p.frame_bits - p.lead_zeros - p.adc_bits
    word = (((lead << p.adc_bits) | code) << trail)
    return [(word >> (p.frame_bits - 1 - k)) & 1 for k in range(p.frame_bits)]


def decode_frame(bits: list[int], p: AdcSpiParams = AdcSpiParams()) -> tuple[int, bool]:
    """(code, lead_error) from a received frame."""
    word = 0
    for b in bits:
        word = (word << 1) | (b & 1)
    trail = p.frame_bits - p.lead_zeros - p.adc_bits
    code = (word >> trail) & p.code_max
    lead = word >> (p.frame_bits - p.lead_zeros)
    return code, lead != 0


# ---- arithmetic --------------------------------------------------------------------
def correct(code: int, offset: int, cur_w: int) -> tuple[int, bool]:
    """Offset-corrected current ``sat(code - offset, cur_w)`` and its saturation flag."""
    return formats.sat_flag(code - offset, cur_w)


def overcurrent(code: int, offset: int, thr: int) -> bool:
    """``|code - offset| > thr`` on the unsaturated difference."""
    return abs(code - offset) > thr


def cal_mean(total: int, cal_log2: int) -> int:
    """Round-half-up mean of 2**cal_log2 samples summing to ``total``."""
    return formats.rshift_round(total, cal_log2)


def window_mean(diffs, avg_log2: int) -> int:
    """Round-half-up mean of 2**avg_log2 differences (code - offset): (sum + 2^(K-1)) >> K."""
    assert len(diffs) == 1 << avg_log2
    return formats.rshift_round(sum(diffs), avg_log2) if avg_log2 else diffs[0]


def window_cur(codes_per_frame, offsets, p: AdcSpiParams = AdcSpiParams()) -> tuple[int, int, int]:
    """The controller's sample from the window frames' codes (list of 3-tuples, in order)."""
    return tuple(formats.sat_flag(window_mean([c[i] - offsets[i] for c in codes_per_frame], p.avg_log2),
                                  p.cur_w)[0] for i in range(N_CH))


def sum_bad(diffs, thr: int) -> bool:
    """Sum-of-currents check of one frame: |d0 + d1 + d2| > thr."""
    return abs(sum(diffs)) > thr


def at_rail(code: int, p: AdcSpiParams = AdcSpiParams()) -> bool:
    return code in (0, p.code_max)


# ---- cycle-exact register model -----------------------------------------------------
@dataclass
class _Frame:
    a: int                      # accept cycle
    codes: tuple
    lead_bad: bool
    bits: tuple                 # per channel, transmission order
    win: bool
    first: bool
    last: bool


@dataclass
class AdcInputs:
    """Inputs of one clock cycle (the slave's codes/lead are what a frame accepted now sends)."""
    period_start: int = 0
    trig: int = 0
    bridges_on: int = 0
    off_we: int = 0
    off_wdata: int = 0
    cal_start: int = 0
    refused_clear: int = 0
    oc_thr: int = 4095
    sum_thr: int = 4095
    codes: tuple = (2048, 2048, 2048)
    lead: tuple = (0, 0, 0)


@dataclass
class AdcSpiCycle:
    """Registers of ``adc_spi`` (outputs under their port names), one :meth:`step` per clock.

    Besides the outputs, ``frames`` lists every accepted frame and ``events`` the frames'
    per-frame results (dicts) for tests that want to look at a frame rather than a cycle.
    """

    p: AdcSpiParams = field(default_factory=AdcSpiParams)
    t: int = 0

    def __post_init__(self):
        p = self.p
        # schedule constants (the params' properties recompute them)
        self.TF, self.G0, self.M0, self.NW, self.GPMAX = p.tf, p.g0, p.m0, p.n_window, p.gp_max
        self.VL, self.IDLE, self.TCS = p.valid_latency(), p.idle_after(), p.cs_rise()
        self.PL, self.SW, self.AW = p.pass_len(), p.sw(), p.aw()
        self.GC_C = (p.g0 - p.half_period) % p.tf
        self.GP_C = (p.half_period - 1 - p.g0) // p.tf + 1 if p.half_period > p.g0 else 0
        self.gc, self.gp = p.tf - 1, p.gp_max
        self.grid = None                      # AdcSpiAxes: the shared grid (gc, gp, jump of this cycle)
        self.win_open = False
        self.f = (False, False, False)
        self.trig_miss, self.miss_cnt = 0, 0
        self.last_accept = None
        self.frame = None                     # frame in the SPI engine / stages
        self.prev_bits = tuple((0,) * p.frame_bits for _ in range(N_CH))
        self.capdone = self.st_a = 0
        self.code = [0, 0, 0]
        self.diff = [0, 0, 0]
        self.lead_bad_a = self.rail_a = False
        self.fchg = (False, False, False)
        self.fvalid = self.frame_err = self.oc = 0
        self.oc_ch = (False, False, False)
        self.kcnt = 0
        self.stuck = 0
        self.valid, self.sat = 0, 0
        self.cur = [0, 0, 0]
        # calibration, offsets
        self.offsets = [p.offset_reset] * N_CH
        self.frame_cal = False
        self.cal_busy = self.cal_done = False
        self.cal_ch, self.cal_cnt, self.cal_last = 0, 0, False
        self.cal_acc = 1 << (p.cal_log2 - 1)
        self.refused = 0
        # serial pass
        self.pbusy, self.pj = False, 0
        self.p_flags = None
        self.pass_t0 = None
        self.pass_sbad = False
        self.scnt, self.sum_err = 0, 0
        self.pcnt, self.pfresh, self.snap_req = 0, True, False
        self.pacc = [0, 0, 0]
        self.psum = [0, 0, 0]
        self.pcount = 0
        self.accw = [0, 0, 0]
        self.pending_cur = None
        # frozen
        self.chg = [False, False, False]
        self.on_all = False
        self.fzc, self.frozen = 0, 0
        self.frames: list[_Frame] = []
        self.events: list[dict] = []

    # ---- helpers
    def busy(self, c: int) -> bool:
        a = self.last_accept
        return a is not None and a < c <= a + self.IDLE

    def cs_n(self) -> int:
        """cs_n in the current cycle ``t``."""
        a = self.last_accept
        return 0 if a is not None and a + 1 <= self.t <= a + self.TCS else 1

    def sclk(self) -> int:
        """sclk in the current cycle: high except in the even half-bits 2..2*frame_bits of a frame."""
        a, p = self.last_accept, self.p
        if a is None or not a + 1 <= self.t <= a + self.TCS:
            return 1
        hb = (self.t - a - 1) // p.sclk_div
        return int(hb < 2 or hb % 2 == 1 or hb > 2 * p.frame_bits)

    def _sat(self, v):
        return formats.sat_flag(v, self.p.cur_w)

    # ---- one clock cycle: inputs of cycle self.t -> registers visible in cycle self.t + 1
    def step(self, i: AdcInputs) -> None:
        p, c = self.p, self.t
        ps = bool(i.period_start)
        bon = bool(i.bridges_on)
        nx = {}                                  # next-state values, committed at the end

        # grid (period_start reloads it at its edge: first new grid point G0 >= 1 cycles later),
        # window flags, centre check
        g = self.grid
        if g is None:                            # own grid (NAXES = 1)
            gc_e, gp_e, jump = self.gc, self.gp, False
            go = gc_e == 0
            nx["gc"] = self.G0 - 1 if ps else self.TF - 1 if go else gc_e - 1
            nx["gp"] = 0 if ps else gp_e + 1 if go and gp_e != self.GPMAX else gp_e
        else:                                    # the shared grid of AdcSpiAxes (stepped by it)
            gc_e, gp_e, jump = g.gc, g.gp, g.jump
            go = gc_e == 0
        accept = go and not self.busy(c)
        w_in = self.M0 <= gp_e <= self.M0 + self.NW - 1
        w_first, w_last = gp_e == self.M0, gp_e == self.M0 + self.NW - 1
        w_ok = g is None or w_first or self.win_open   # NAXES > 1: only a window that started counts
        trig_ok = gc_e == self.GC_C and gp_e == self.GP_C
        miss = (i.trig and not trig_ok) or ((ps or jump) and self.win_open)
        nx["trig_miss"] = int(bool(miss))
        nx["miss_cnt"] = min(self.miss_cnt + 1, (1 << p.miss_w) - 1) if miss else self.miss_cnt
        win_open = False if ps or jump else self.win_open
        if accept:
            if w_first:
                win_open = True
            if w_last:
                win_open = False
            w_in, w_last = w_in and w_ok, w_last and w_ok
            nx["f"] = (w_in, w_first, w_last)
        nx["win_open"] = win_open

        # SPI engine: a new frame, stage A (capdone), stage B (st_a)
        fr = self.frame
        capdone = fr is not None and c == fr.a + self.VL - 1
        st_a = fr is not None and c == fr.a + self.VL
        if accept:
            bits, codes, lb = [], [], False
            for ch in range(N_CH):
                b = frame_bits(i.codes[ch] & p.code_max, p, i.lead[ch])
                code, bad = decode_frame(b, p)
                bits.append(tuple(b))
                codes.append(code)
                lb |= bad
            nx["frame"] = _Frame(c, tuple(codes), lb, tuple(bits), w_in, w_first, w_last)
            nx["last_accept"] = c
            self.frames.append(nx["frame"])
        if capdone:
            nx["code"] = list(fr.codes)
            nx["diff"] = [fr.codes[ch] - self.offsets[ch] for ch in range(N_CH)]
            nx["lead_bad_a"] = fr.lead_bad
            nx["rail_a"] = any(at_rail(x, p) for x in fr.codes)
            nx["fchg"] = tuple(fr.bits[ch] != self.prev_bits[ch] for ch in range(N_CH))
            nx["prev_bits"] = fr.bits

        # calibration and offsets
        cpu_ok = not self.cal_busy and not bon
        cal_go = bool(i.cal_start) and not bon
        cal_abort = self.cal_busy and bon
        refuse = (i.cal_start and bon) or (i.off_we and not cpu_ok) or cal_abort
        nx["refused"] = int(bool(refuse) or (self.refused and not i.refused_clear))
        offsets = list(self.offsets)
        off_d = (self.cal_acc >> p.cal_log2) if self.cal_last else i.off_wdata & p.code_max
        for ch in range(N_CH):
            if (self.cal_last and self.cal_ch == ch) or ((i.off_we >> ch) & 1 and cpu_ok):
                offsets[ch] = off_d
        nx["offsets"] = offsets
        frame_cal = self.cal_busy if accept else self.frame_cal
        cal_acc, cal_cnt, cal_last = self.cal_acc, self.cal_cnt, False
        cal_ch, cal_busy, cal_done = self.cal_ch, self.cal_busy, self.cal_done
        if capdone and self.frame_cal:
            cal_acc += fr.codes[self.cal_ch]
            cal_cnt = (cal_cnt + 1) % (1 << p.cal_log2)
            cal_last = self.cal_cnt == (1 << p.cal_log2) - 1
            frame_cal = False
        if self.cal_last:
            cal_acc = 1 << (p.cal_log2 - 1)
            cal_ch = (self.cal_ch + 1) % 4
            if self.cal_ch == 2:
                cal_busy, cal_done = False, True
        if cal_abort:
            cal_busy, frame_cal = False, False
        if cal_go:
            cal_busy, cal_done, cal_ch, cal_cnt, cal_last, frame_cal = True, False, 0, 0, False, False
            cal_acc = 1 << (p.cal_log2 - 1)
        nx.update(frame_cal=frame_cal, cal_acc=cal_acc, cal_cnt=cal_cnt, cal_last=cal_last, cal_ch=cal_ch,
                  cal_busy=cal_busy, cal_done=cal_done)

        # stage B: every frame
        nx["fvalid"] = int(st_a)
        nx["frame_err"] = int(st_a and self.lead_bad_a)
        oc_now = tuple(abs(d) > i.oc_thr for d in self.diff)
        nx["oc"] = int(st_a and any(oc_now))
        if st_a:
            nx["oc_ch"] = oc_now
            nx["stuck"] = int(self.rail_a and self.kcnt >= p.stuck_persist - 1)
            nx["kcnt"] = 0 if not self.rail_a else min(self.kcnt + 1, p.stuck_persist - 1)
            self.events.append(dict(a=fr.a, codes=tuple(self.code), diff=tuple(self.diff), oc_ch=oc_now,
                                    frame_err=self.lead_bad_a, rail=self.rail_a, win=fr.win, first=fr.first,
                                    last=fr.last, fvalid_cycle=c + 1))
        # controller sample, AVG_LOG2 = 0: at stage B
        if p.avg_log2 == 0:
            hit = st_a and fr.last
            nx["valid"] = int(hit)
            if hit:
                sc = [self._sat(d) for d in self.diff]
                nx["cur"] = [v for v, _ in sc]
                nx["sat"] = int(any(s for _, s in sc))
            else:
                nx["sat"] = 0

        # serial pass
        snap_now = (ps or self.snap_req) and not self.pbusy
        nx["snap_req"] = (ps or self.snap_req) and self.pbusy
        if snap_now:
            nx["psum"], nx["pcount"] = list(self.pacc), self.pcnt
        if p.avg_log2 > 0:
            w_end = self.pbusy and self.p_flags["win"] and self.p_flags["last"] and self.pj == self.AW
            nx["valid"] = int(w_end)
            nx["sat"] = 0
            if w_end:
                sc = [self._sat(a >> p.avg_log2) for a in self.accw]
                nx["cur"] = [v for v, _ in sc]
                nx["sat"] = int(any(s for _, s in sc))
        if st_a:
            fresh = self.pfresh or snap_now
            padd = fresh or self.pcnt != (1 << p.pcnt_w) - 1
            nx["pbusy"], nx["pj"], nx["pfresh"] = True, 0, False
            nx["pcnt"] = 1 if fresh else min(self.pcnt + 1, (1 << p.pcnt_w) - 1)
            nx["p_flags"] = dict(win=fr.win, first=fr.first, last=fr.last)
            nx["pass_sbad"] = sum_bad(self.diff, i.sum_thr)
            # accumulators: exact sums (no overflow by construction), visible only after the pass
            nx["pacc"] = [(0 if fresh else self.pacc[ch]) + (self.diff[ch] if padd else 0) for ch in range(N_CH)]
            if p.avg_log2 > 0 and fr.win:
                half = 1 << (p.avg_log2 - 1)
                nx["accw"] = [(half if fr.first else self.accw[ch]) + self.diff[ch] for ch in range(N_CH)]
        else:
            if snap_now:
                nx["pcnt"], nx["pfresh"] = 0, True
            if self.pbusy:
                nx["pj"] = self.pj + 1
                if self.pj == self.PL - 1:
                    nx["pbusy"] = False
                if self.pj == self.SW - 1:
                    sb = self.pass_sbad
                    nx["sum_err"] = int(sb and self.scnt >= p.sum_persist - 1)
                    nx["scnt"] = 0 if not sb else min(self.scnt + 1, p.sum_persist - 1)

        # frozen
        nx["on_all"] = bon if ps else (self.on_all and bon)
        if ps:
            frz = self.on_all and bon and self.pcnt > 1 and not all(self.chg)
            nx["chg"] = list(self.fchg) if st_a else [False] * 3
            nx["frozen"] = int(frz and self.fzc >= p.frozen_periods - 1)
            nx["fzc"] = 0 if not frz else min(self.fzc + 1, p.frozen_periods - 1)
        elif st_a:
            nx["chg"] = [a or b for a, b in zip(self.chg, self.fchg)]

        nx["capdone"], nx["st_a"] = int(capdone), int(st_a)
        for k, v in nx.items():
            setattr(self, k, v)
        self.t = c + 1

    def outputs(self) -> dict:
        """Port values in the current cycle (after the last step)."""
        return dict(cs_n=self.cs_n(), busy=int(self.busy(self.t)), trig_miss=self.trig_miss, miss_cnt=self.miss_cnt,
                    fvalid=self.fvalid, code0=self.code[0], code1=self.code[1], code2=self.code[2],
                    frame_err=self.frame_err, oc=self.oc, oc_ch=sum(int(b) << k for k, b in enumerate(self.oc_ch)),
                    sum_err=self.sum_err, stuck=self.stuck, frozen=self.frozen, valid=self.valid,
                    cur0=self.cur[0], cur1=self.cur[1], cur2=self.cur[2], sat=self.sat,
                    psum0=self.psum[0], psum1=self.psum[1], psum2=self.psum[2], pcount=self.pcount,
                    offset0=self.offsets[0], offset1=self.offsets[1], offset2=self.offsets[2],
                    cal_busy=int(self.cal_busy), cal_done=int(self.cal_done), refused=self.refused, sclk=self.sclk())


# ---- NAXES > 1: one frame engine, per-axis instances of the cycle model on a common grid ----------
class AdcSpiAxes:
    """Cycle model of ``adc_spi`` with ``NAXES`` > 1: one :class:`AdcSpiCycle` per axis (its own
    MISO codes, offsets, checks, sums, window), all on one frame grid (the RTL's one SCLK / CS).

    Axis a's carrier is axis 0's delayed by a * ``stagger`` clk (pwm_center PHASE), a whole number
    of frames, so its window frames are grid points centred on its own centre.  Grid coordinates:
    cycle 0 reloads the grid (first point ``g0`` cycles later); it is cycle ``rephase`` (R) of axis
    0's period, the first clock after the last axis's last window pass.  The terminal state (grid
    cycle 2P) reloads the grid; axis 0's ``period_start`` loads the state of the cycle after it only
    if the grid is out of phase (``jump``: every axis's open window is cut, counted as a miss).

    :meth:`step` takes one :class:`AdcInputs` per axis (``period_start`` etc. of that axis; the
    codes are what that axis's three converters send in a frame accepted now).
    """

    def __init__(self, p: AdcSpiParams, naxes: int, stagger: int | None = None):
        from .pwm_center import stagger_step
        if not 2 <= naxes <= 4:
            raise ValueError("AdcSpiAxes: 2 <= naxes <= 4 (NAXES = 1 is AdcSpiCycle)")
        self.p, self.n = p, naxes
        tf, p2 = p.tf, 2 * p.half_period
        self.stagger = stagger_step(naxes, p.half_period, tf) if stagger is None else stagger
        s = self.stagger
        if s < tf or s % tf:
            raise ValueError(f"stagger {s}: a positive multiple of the frame period {tf}")
        tail = (naxes - 1) * s + p.w_lead + p.valid_latency() + p.pass_len() + 1
        self.rephase = (p.half_period + tail) % p2
        self.c0 = p2 - tail                   # axis 0's centre, grid cycle
        t0 = self.c0 - p.w_lead
        if t0 <= 0:
            raise ValueError("the windows of all axes do not fit in one PWM period")
        self.g0 = t0 % tf or tf
        self.m0 = (t0 - self.g0) // tf
        if self.m0 < 1:
            raise ValueError("axis 0's window less than one frame after the grid's re-phase point")
        self.gp_max = p.gp_max
        y0 = p2 - self.rephase
        y1 = 1 if y0 == p2 else y0 + 1
        self.T, self.J, self.L = self.state(p2), self.state(y0), self.state(y1)
        self.gc, self.gp, self.jump = tf - 1, p.gp_max, False
        self.t = 0
        self.axes = []
        for a in range(naxes):
            m = AdcSpiCycle(p)
            m.grid = self
            cn = self.c0 + a * s
            m.M0 = self.m0 + a * s // tf
            m.GC_C, m.GP_C = self.state(cn)
            self.axes.append(m)

    def state(self, x: int) -> tuple[int, int]:
        """(gc, gp) in grid cycle x >= 1 after a reload."""
        g0, tf = self.g0, self.p.tf
        return (g0 - x) % tf, 0 if x <= g0 else (x - g0 - 1) // tf + 1

    def centre_cycle(self, a: int) -> int:
        """Axis a's centre in axis 0's period (cycles after axis 0's period_start), mod 2P."""
        return (self.p.half_period + a * self.stagger) % (2 * self.p.half_period)

    def window_frames(self, a: int) -> list[int]:
        """Accept cycles of axis a's window frames in axis 0's period (mod 2P)."""
        return [(self.centre_cycle(a) + t) % (2 * self.p.half_period) for t in self.p.window_taus()]

    def step(self, inputs) -> None:
        assert len(inputs) == self.n
        gc, gp, tf = self.gc, self.gp, self.p.tf
        self.jump = bool(inputs[0].period_start) and (gc, gp) != self.J
        for m, i in zip(self.axes, inputs):
            m.step(i)
        go = gc == 0
        if self.jump:
            self.gc, self.gp = self.L
        elif (gc, gp) == self.T:
            self.gc, self.gp = self.g0 - 1, 0
        else:
            self.gc = tf - 1 if go else gc - 1
            self.gp = gp + 1 if go and gp != self.gp_max else gp
        self.t += 1

    def outputs(self) -> list[dict]:
        """Per axis the port values of its slice (cs_n, sclk, busy, fvalid are shared: the same in every dict)."""
        return [m.outputs() for m in self.axes]
