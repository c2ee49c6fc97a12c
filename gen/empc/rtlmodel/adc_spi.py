"""Bit-accurate model of ``rtl/adc_spi.v`` (3-channel SPI current-ADC master).

Used by ``tb/test_adc_spi.py`` and by the bit-accurate closed loop.  Pure Python.

Pieces:
  * :class:`AdcSpiParams`  - the RTL parameters and the timing they imply
    (:meth:`~AdcSpiParams.valid_latency`, :meth:`~AdcSpiParams.cs_rise`,
    :meth:`~AdcSpiParams.min_trig_period`), all in clk cycles.
  * :func:`frame_bits` / :func:`decode_frame` - the SPI frame on one MISO line.
  * :func:`correct`, :func:`overcurrent`, :func:`cal_mean` - the arithmetic.
  * :class:`AdcSpiMaster` - the register state (offsets, calibration) and one
    conversion per :meth:`~AdcSpiMaster.convert` call, in the RTL's order.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from empc import formats

N_CH = 3


@dataclass(frozen=True)
class AdcSpiParams:
    """Parameters of ``adc_spi`` (same names, lower case) and the timing they imply."""

    adc_bits: int = formats.ADC_BITS
    frame_bits: int = 16
    lead_zeros: int = 4
    sclk_div: int = 2
    sample_delay: int = 5
    cs_quiet: int = 5
    cal_log2: int = 6
    cur_w: int = formats.ADC_BITS + 1
    miss_w: int = 8
    offset_reset: int = 2048   # RTL default: `EMPC_ADC_OFFSET (config sensors.adc_offset)

    def __post_init__(self):
        if self.lead_zeros < 1 or self.lead_zeros + self.adc_bits > self.frame_bits:
            raise ValueError("need 1 <= lead_zeros and lead_zeros + adc_bits <= frame_bits")
        if self.sclk_div < 1 or self.sample_delay < 3 or self.cs_quiet < 1 or self.cal_log2 < 1 or self.cur_w < 2:
            raise ValueError("need sclk_div >= 1, sample_delay >= 3, cs_quiet >= 1, cal_log2 >= 1, cur_w >= 2")

    # ---- timing, clk edges after the edge E0 that accepts trig ------------------
    def launch_edge(self, k: int) -> int:
        """Edge at which frame bit ``k`` is launched (k = 0: CS falls; else SCLK falling edge k)."""
        return 2 * k * self.sclk_div

    def capture_edge(self, k: int) -> int:
        """Edge at which the master latches bit ``k`` from the synchronised MISO."""
        return self.launch_edge(k) + self.sample_delay

    def cs_rise(self) -> int:
        """Edge at which CS rises again."""
        h = self.sclk_div
        return max((2 * self.frame_bits + 2) * h, 2 * (self.frame_bits - 1) * h + self.sample_delay + 1)

    def valid_latency(self) -> int:
        """``valid`` is high in the cycle after edge E0 + valid_latency (trig high in cycle 0 -> valid in cycle L)."""
        return 2 * (self.frame_bits - 1) * self.sclk_div + self.sample_delay + 2

    def min_trig_period(self) -> int:
        """Smallest distance (clk) between two accepted triggers (trig held high)."""
        return max(self.cs_rise() + self.cs_quiet, self.valid_latency() + 1)

    def sample_window_ns(self, t_clk_ns: float = 10.0) -> tuple[float, float]:
        """Allowed (round-trip-max, hold-min) pair: the pin is sampled at launch + (sample_delay-2) clk.

        Valid iff t_roundtrip_max + t_setup < (sample_delay - 2) * t_clk < 2 * sclk_div * t_clk + t_hold_min.
        Returns ((sample_delay-2)*t_clk, (sample_delay-2-2*sclk_div)*t_clk): the upper bound for the
        maximum round trip and the lower bound for the minimum hold/round trip.
        """
        ts = (self.sample_delay - 2) * t_clk_ns
        return ts, ts - 2 * self.sclk_div * t_clk_ns

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


@dataclass
class AdcResult:
    codes: tuple[int, int, int]
    cur: tuple[int, int, int]
    sat: bool
    oc_ch: tuple[bool, bool, bool]
    oc: bool
    frame_err: bool
    offsets_used: tuple[int, int, int]


@dataclass
class AdcSpiMaster:
    """Register-level state of ``adc_spi`` between conversions.

    Call in the order the events happen in the RTL: :meth:`write_offset` (CPU),
    :meth:`cal_start`, :meth:`convert` (one accepted trigger, returns what appears at
    ``valid``).  ``counted=False`` in ``convert`` marks a frame that was already in
    flight when ``cal_start`` arrived (RTL: not counted for calibration).

    Calibration averages one channel after the other (``cal_ch`` 0, 1, 2), each over
    2**cal_log2 counted conversions; a channel's offset is loaded when its last sample
    is in, ``cal_done`` after channel 2.  CPU offset writes are ignored while
    ``cal_busy``.
    """

    p: AdcSpiParams = field(default_factory=AdcSpiParams)
    offsets: list[int] = field(default_factory=list)
    cal_busy: bool = False
    cal_done: bool = False
    cal_n: int = 0
    cal_ch: int = 0
    cal_acc: int = 0

    def __post_init__(self):
        if not self.offsets:
            self.offsets = [self.p.offset_reset] * N_CH

    def write_offset(self, ch: int, value: int) -> bool:
        """CPU write; returns False (ignored) while a calibration runs."""
        if self.cal_busy:
            return False
        self.offsets[ch] = value & self.p.code_max
        return True

    def cal_start(self) -> None:
        self.cal_busy, self.cal_done, self.cal_n, self.cal_ch, self.cal_acc = True, False, 0, 0, 0

    def convert(self, codes, thr: int, lead=(0, 0, 0), counted: bool = True) -> AdcResult:
        """One conversion of ``codes`` (3 ints), overcurrent threshold ``thr``."""
        p = self.p
        decoded = [decode_frame(frame_bits(c, p, l), p) for c, l in zip(codes, lead)]
        codes = tuple(d[0] for d in decoded)
        ferr = any(d[1] for d in decoded)
        used = tuple(self.offsets)
        cs = [correct(c, o, p.cur_w) for c, o in zip(codes, used)]
        oc_ch = tuple(overcurrent(c, o, thr) for c, o in zip(codes, used))
        if self.cal_busy and counted:
            self.cal_acc += codes[self.cal_ch]
            self.cal_n += 1
            if self.cal_n == 1 << p.cal_log2:
                self.offsets[self.cal_ch] = cal_mean(self.cal_acc, p.cal_log2)
                self.cal_ch, self.cal_n, self.cal_acc = self.cal_ch + 1, 0, 0
                if self.cal_ch == N_CH:
                    self.cal_busy, self.cal_done = False, True
        return AdcResult(codes, tuple(c for c, _ in cs), any(s for _, s in cs), oc_ch, any(oc_ch), ferr, used)
