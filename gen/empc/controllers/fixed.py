"""Explicit MPC through the bit-accurate model of the RTL core (rtlmodel/mpc_core.py).

Measurements are converted into the core's raw integer units exactly as the
FPGA front end delivers them (currents in ADC LSB Q.4, encoder counts, speed as
counts per Ts: rtlmodel/ctrl_seq.speed_estimate), the law runs in the core model,
and u (PWM ticks Q16.8) is converted back to volts for modulation.  Field weakening
runs in raw units as in the sequencer (ctrl_seq.fw_update, flags from the core); the
reference governor in SI units as in the float controller (governor.ReferencePath;
the bit-accurate loop, bitloop.py, runs the generator's integer governor).
"""
from __future__ import annotations

import math

import numpy as np

from .. import formats as F
from .. import design as design_mod, governor as gov_mod, header
from ..rtlmodel import ctrl_seq as seq_mod
from ..rtlmodel import mpc_core as core
from .base import Controller


class FixedMPC(Controller):
    def __init__(self, cfg, algorithm: int | None = None, task: str | None = None, params: core.Params | None = None):
        cfg = cfg.for_design(algorithm or cfg.control.algorithm, task or cfg.control.task)   # its speed window
        super().__init__(cfg)
        c = cfg.control
        self.algorithm = algorithm or c.algorithm
        self.task = task or c.task
        self.N = c.N
        self.params = params or design_mod.design(cfg, self.algorithm, self.task, force=True)["params"]   # simulate any design
        self.name = f"fixed-mpc-alg{self.algorithm}-{self.task}"
        self.kacc, self.kacc_shift = header.speed_correction_raw(cfg)
        fw = header.field_weakening_raw(cfg)
        self.regs = seq_mod.Regs(pwm_per_control=cfg.pwm_per_control, kacc=self.kacc, kacc_shift=self.kacc_shift,
                                 load_shift=cfg.speed_load_shift, fw_shift=fw["FW_SHIFT"], fw_nmax=fw["FW_NMAX"],
                                 fw_thr=(fw["FW_R2_HI"], fw["FW_R2_LO"]),
                                 iq_hold=header.governor_raw(cfg, self.task)["IQ_HOLD"],
                                 win_shift=c.speed_window.bit_length() - 1)
        self.M = c.speed_window
        self.refpath = gov_mod.ReferencePath(cfg, self.task)
        self.reset()

    # --- raw unit conversions (the RTL front end) ---
    def i_raw(self, amps: float) -> int:
        return F.sat(int(round(amps / self.cfg.amps_per_lsb * (1 << F.I_FRAC))), F.I_W)

    def out3_raw(self, v: float) -> int:
        """Speed (rad/s) -> Q16.16 counts/Ts, or angle (rad) -> Q32.8 counts."""
        if self.task == "speed":
            return int(round(v / self.cfg.rad_s_per_count_ts * (1 << F.W_FRAC)))
        return int(round(v / self.cfg.rad_per_count * (1 << F.TH_FRAC)))

    def reset(self) -> None:
        super().reset()
        self.u_raw = (0, 0)
        self.ebar = (0, 0, 0)
        self.prev = None
        self.counts_prev = None
        self.counts_hist: list = []          # speed_window > 1: counts_{k-M} .. counts_{k-1}
        self.saturations = 0
        self.flag_counts: dict = {}
        self.est = {"D": 0, "spd_prev": 0}
        self.fw_n = 0
        self.fw_flags = (False, False)
        self.hold = False
        self.refpath.reset()
        self.gov_clamps = 0

    def step(self, meas) -> np.ndarray:
        counts = meas.counts
        if self.M == 1:
            speed_counts = 0 if self.counts_prev is None else counts - self.counts_prev   # eq. 37, counts per Ts
        else:                                    # counts per M Ts (the window reaches back to the first sample)
            if not self.counts_hist:
                self.counts_hist = [counts] * self.M
            speed_counts = counts - self.counts_hist[0]
            self.counts_hist = self.counts_hist[1:] + [counts]
        self.counts_prev = counts
        i_d, i_q = self.i_raw(meas.i_d), self.i_raw(meas.i_q)
        omega, _ = seq_mod.speed_estimate(speed_counts, i_q, self.regs, self.est)
        y2 = omega if self.task == "speed" else counts << F.TH_FRAC
        state = (i_d, i_q, omega, counts << F.TH_FRAC, 0)
        dx = (0, 0, 0, 0, 0) if self.prev is None else tuple(a - b for a, b in zip(state, self.prev))
        self.prev = state
        g0, gW = self.refpath.window(float(meas.w_k[2]), [float(r[2]) for r in meas.W], self.hold)
        self.gov_clamps = self.refpath.clamps
        refs = [(meas.w_k[0], meas.w_k[1], g0)] + [(r[0], r[1], g) for r, g in zip(meas.W, gW)]
        self.fw_n = seq_mod.fw_update(self.fw_n, *self.fw_flags, self.regs)
        i_fw = seq_mod.fw_offset(self.fw_n, self.regs)
        wref = tuple((F.sat(self.i_raw(r[0]) + i_fw, F.I_W), self.i_raw(r[1]), self.out3_raw(r[2]))
                     for r in refs)
        out = core.update(self.params, core.Inputs(y=(i_d, i_q, y2), omega=omega, dx=dx, wref=wref,
                                                   u_prev=self.u_raw, ebar_prev=self.ebar, fw_thr=self.regs.fw_thr,
                                                   aw=core.aw_bits(i_q, self.regs.iq_hold)))
        self.u_raw = out.u
        self.ebar = out.ebar
        self.fw_flags = (out.fw_hi, out.fw_lo)
        self.hold = seq_mod.hold_flag(i_q, bool(out.flags >> core.FLAG_BITS["limit"] & 1), self.regs)
        self.saturations += int(out.flags & (1 << core.FLAG_BITS["limit"]) != 0)
        for k, v in out.counts.items():
            self.flag_counts[k] = self.flag_counts.get(k, 0) + v
        vpt = self.cfg.volts_per_tick / (1 << F.U_FRAC)
        self.u_dq = np.array([out.u[0] * vpt, out.u[1] * vpt])
        return self.u_dq
