"""Cycle-exact model of ``rtl/emc_bus.v`` and the bus timing it requires.

:class:`EmcBus` models the clocked logic given the pin values present at each
rising clock edge (no metastability: a pin changing exactly at an edge is
sampled as in an event simulator, with its old value).  :func:`timing_spec`
gives the LPC4088 EMC timing requirements (ns) that follow from the
parameters; docs/blocks/emc_bus.md derives them.
"""
from __future__ import annotations

from dataclasses import dataclass


class EmcBus:
    """One ``emc_bus`` instance.  :meth:`step` is one rising clock edge; the
    attributes after it are the registered outputs (``reg_wr``, ``reg_rd``,
    ``reg_addr``, ``reg_wdata``, ``emc_d_out``, ``drive``, ``err_wr_short``,
    ``err_rd_short``); :meth:`d_oe` is the (combinational) output enable.
    ``reg_addr`` / ``reg_wdata`` follow the synchronised pins while WE and CS are
    low (they are the write's hold registers) and take the read address at a
    read; they are meaningful in the ``reg_wr`` / ``reg_rd`` clock."""

    def __init__(self, aw: int = 14, rd_lat: int = 1, wr_min_low: int = 3, rd_min_low: int = 2,
                 oe_pin_gate: bool = True):
        if min(rd_lat, wr_min_low, rd_min_low) < 1:
            raise ValueError("rd_lat, wr_min_low and rd_min_low must be >= 1")
        self.aw, self.rd_lat = aw, rd_lat
        self.wr_min_low, self.rd_min_low = wr_min_low, rd_min_low
        self.oe_pin_gate = oe_pin_gate
        self.rd_ok = rd_min_low + rd_lat + 4      # low samples of a read that is in time
        self.reset()

    def reset(self) -> None:
        self.s_strobe = [(1, 1, 1), (1, 1, 1)]    # (cs_n, oe_n, we_n) stage 0, 1
        self.s_a = [0, 0]
        self.s_d = [0, 0]
        self.we_n_d = 1
        self.wcnt = 0
        self.reg_wr = self.reg_rd = 0
        self.reg_addr = self.reg_wdata = 0
        self.err_wr_short = self.err_rd_short = 0
        self.rcnt = 0
        self.rd_act = 0
        self.rd_pipe = [0] * self.rd_lat
        self.drive = 0
        self.emc_d_out = 0

    def d_oe(self, cs_n: int, oe_n: int) -> int:
        """Output enable for the current raw pin values."""
        if self.oe_pin_gate:
            return int(self.drive and not oe_n and not cs_n)
        return int(self.drive)

    def step(self, cs_n: int, oe_n: int, we_n: int, a: int, d: int, reg_rdata: int) -> None:
        cs_q, oe_q, we_q = self.s_strobe[1]
        a_q, d_q = self.s_a[1], self.s_d[1]
        # write side
        w_low = not we_q and not cs_q
        we_rise = we_q and not self.we_n_d
        n_reg_wr, n_err_wr = 0, 0
        n_reg_addr, n_reg_wdata = self.reg_addr, self.reg_wdata
        if we_rise:
            if self.wcnt == self.wr_min_low:
                n_reg_wr = 1          # reg_addr / reg_wdata hold the last WE-low sample
            elif self.wcnt:
                n_err_wr = 1
        if we_q:
            self.wcnt = 0
        elif not cs_q and self.wcnt != self.wr_min_low:
            self.wcnt += 1
        if w_low:                     # reg_addr / reg_wdata follow the pins while WE and CS are low
            n_reg_addr, n_reg_wdata = a_q, d_q
        # read side
        r_low = not oe_q and not cs_q and we_q and self.we_n_d
        n_reg_rd, n_err_rd = 0, 0
        if not r_low:
            if self.rcnt and self.rcnt != self.rd_ok:
                n_err_rd = 1
            self.rcnt = 0
            self.rd_act = 0
            self.rd_pipe = [0] * self.rd_lat
            self.drive = 0
        else:
            fire = self.rcnt == self.rd_min_low - 1
            cap = self.rd_act and self.rd_pipe[-1]
            if self.rcnt != self.rd_ok:
                self.rcnt += 1
            self.rd_pipe = [self.reg_rd] + self.rd_pipe[:-1]
            if fire:
                n_reg_rd, n_reg_addr = 1, a_q
                self.rd_act = 1
            if cap:
                self.emc_d_out = reg_rdata & 0xFFFFFFFF
                self.drive = 1
        self.we_n_d = we_q
        self.reg_wr, self.reg_rd = n_reg_wr, n_reg_rd
        self.reg_addr, self.reg_wdata = n_reg_addr, n_reg_wdata
        self.err_wr_short, self.err_rd_short = n_err_wr, n_err_rd
        # synchronisers
        self.s_strobe = [(cs_n & 1, oe_n & 1, we_n & 1), self.s_strobe[0]]
        self.s_a = [a & ((1 << self.aw) - 1), self.s_a[0]]
        self.s_d = [d & 0xFFFFFFFF, self.s_d[0]]


@dataclass(frozen=True)
class TimingSpec:
    """EMC timing requirements (ns) for the FPGA side; see :func:`timing_spec`."""
    we_low_min: float          # WE (and CS) low
    wr_setup_min: float        # address/data valid before WE rises
    wr_hold_min: float         # address/data held after WE rises
    we_high_min: float         # WE high between writes
    wr_latency_max: float      # WE rise -> reg_wr (fabric)
    oe_to_data_max: float      # OE fall -> data valid at the FPGA pin
    oe_low_min: float          # OE (and CS) low for a read
    oe_high_min: float         # OE high between reads
    release_max: float         # OE/CS rise -> FPGA data driver off (bus turnaround)
    glitch_reject: float       # strobe pulses shorter than this never write
    rd_err_always: float       # err_rd_short always raised for OE low <= this
    rd_err_never: float        # ... and never for OE low >= this


def timing_spec(clk_hz: float = 100e6, rd_lat: int = 1, wr_min_low: int = 3, rd_min_low: int = 2,
                oe_pin_gate: bool = True, t_unc: float = 2.5, t_co: float = 7.0,
                t_su_cpu: float = 5.0, t_pad_in: float = 3.0) -> TimingSpec:
    """Timing requirements from the design parameters.

    ``t_unc``: sampling uncertainty per edge (FF aperture + pin-to-pin skew);
    ``t_co``: clock to data valid at the pin (output flop + OBUFT);
    ``t_su_cpu``: LPC4088 read-data setup before the end of the read strobe;
    ``t_pad_in``: input pad to the OE/CS gate (release path with oe_pin_gate).
    With all of them 0 the numbers are the exact bounds seen in RTL simulation.
    """
    T = 1e9 / clk_hz
    oe_to_data = T + t_unc + (rd_min_low + 2 + rd_lat) * T + t_co
    return TimingSpec(
        we_low_min=wr_min_low * T + 2 * t_unc,
        wr_setup_min=T + 2 * t_unc,
        wr_hold_min=2 * t_unc,
        we_high_min=T + 2 * t_unc,
        wr_latency_max=3 * T + t_unc,
        oe_to_data_max=oe_to_data,
        oe_low_min=oe_to_data + t_su_cpu,
        oe_high_min=T + 2 * t_unc,
        release_max=(t_pad_in + t_co) if oe_pin_gate else (3 * T + t_unc + t_co),
        glitch_reject=(wr_min_low - 1) * T,
        rd_err_always=(rd_min_low + rd_lat + 3) * T,
        rd_err_never=(rd_min_low + rd_lat + 4) * T + 2 * t_unc,
    )
