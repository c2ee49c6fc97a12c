"""Bit-accurate closed loop: the plant driven by the Python models of the whole RTL axis.

Per PWM period: the plant runs half a period with the current duties; at the
period centre the ADC codes and the encoder count are sampled (the ADC
trigger), the axis model (:class:`AxisModel`: sequencer model rtlmodel/ctrl_seq.py
with front end, MPC core and modulation, plus the reference and its governor)
computes the compare values, and they take effect at the next period boundary,
half a period later - exactly the RTL's timing.

:class:`AxisModel` is the one implementation of the axis's per-PWM-period loop: the
closed loop here (:func:`simulate`, plant in Python) and the RTL co-simulation's checker
(tb/test_closed_loop.py, plant on the RTL's pins, every compare value checked against
:meth:`AxisModel.period`) both step it.  The task references pass through the reference
generator's integer governor (rtlmodel/ref_gen.gov_step) with the sequencer model's hold
flag, as in the RTL (issue 15 item 4).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from . import closedloop as cl
from . import formats as F
from . import config as config_mod, design as design_mod, header, pmsm
from .rtlmodel import pos_sense
from .rtlmodel.ctrl_seq import CtrlSeq, Regs
from .rtlmodel.ref_gen import M64, RefGen, gov_step

M32 = (1 << 32) - 1


class AxisModel:
    """One RTL axis, one PWM period at a time (bit-accurate).

    Owns the sequencer model (:class:`CtrlSeq`: front end, MPC core, modulation), its
    register values (:class:`Regs`, default: the header's, :func:`regs_for`) and the
    reference of the control periods: either the reference generator's model (``refgen``,
    a :class:`RefGen` the caller programs as the CPU programs the RTL's, governor words
    included) or a function ``refs(k, t)`` giving the N+1 Q.32 *target* references of
    control period k sampled at time t, which pass through the generator's governor
    (``gov``, default: the header's words for the task of ``params``; the head w_{k+N} is
    governed, a delay line keeps the earlier ones; the start is a sync to the first target w_k, as in
    the RTL, so a change inside the first window is governed too).
    Either way the governor sees the sequencer's hold flag of the previous control period.
    :meth:`period` takes what the ADC trigger samples (encoder count, ADC codes) and
    returns the sequencer's outputs for the period (``cmp``: the compare values the RTL
    loads for the next period).
    """

    def __init__(self, cfg, params, *, regs: Regs | None = None, refgen: RefGen | None = None,
                 refs: Callable[[int, float], list] | None = None, cal_offset: int = 0, gov: dict | None = None):
        if (refgen is None) == (refs is None):
            raise ValueError("AxisModel needs exactly one reference source: refgen or refs")
        self.cfg = cfg
        self.regs = regs if regs is not None else regs_for(cfg, params.task, params.algorithm)
        self.seq = CtrlSeq(params=params, N=cfg.control.N)
        self.ref = refgen
        self.refs = refs
        self.gov = gov if gov is not None else gov_params(cfg, params.task)
        self.cal_offset = cal_offset
        self.periods = 0            # PWM periods evaluated
        self.k = 0                  # control periods evaluated
        self.last_control = None    # outputs of the last control period (+ ref_w0: the w_k it applied)
        self.gov_clamps = 0         # control periods in which the governor shaped the reference (SAT_GOV)
        self._gdl, self._r_prev, self._v_gov, self._vb_gov = None, 0, 0, (0, 0)     # governor of the refs path
        self._boundary_ref = None   # (control, references) decided at boundary(), for the next period()
        self.swap_params = None     # a coefficient swap requested (swap()): decided at the next control boundary

    @property
    def control_next(self) -> bool:
        """True if the next :meth:`period` is a control period (decided at :meth:`boundary` if that
        was called, else the sequencer's period counter now)."""
        if self._boundary_ref is not None:
            return self._boundary_ref[0]
        return self.seq.per_cnt + 1 >= self.regs.pwm_per_control

    def boundary(self, t: float = 0.0) -> bool:
        """The PWM boundary before the next sample (rtl/mx_seq.v, docs/four_axes.md D5): the kind of
        the coming period is decided and, for a control period, the references advance here, so a
        CPU command to the reference generator after this call is taken by the next advance.
        ``t``: the coming trigger's time (for ``refs``).  The next :meth:`period` uses the decision;
        without this call :meth:`period` decides and advances at the trigger (no commands between)."""
        control = self.seq.boundary(self.regs)
        if control and self.swap_params is not None:       # the core's bank flips first: the advance
            self.seq.params, self.swap_params = self.swap_params, None    # and the period use the new task
        self._boundary_ref = (control, self._reference(t) if control else None)
        return control

    def swap(self, params) -> None:
        """CMD.coef_swap after a complete, valid upload of ``params`` (STATUS.coef_valid): the RTL
        decides the swap at the next boundary before a control sample (mx_seq's ctl_boundary, the
        core's swap_at), before that boundary's reference advance, so that control period and all
        later ones run the new image's task, references and coefficients (:meth:`boundary`).  The
        model assumes the swap is accepted (the caller checks STATUS)."""
        self.swap_params = params

    @property
    def u(self) -> tuple:
        """u_dq (Q.8 PWM ticks) the modulation applies (held between control periods)."""
        return self.seq.u

    def ref_sync(self, count: int) -> int:
        """CMD.ref_sync (rtl/axis_periph.v): the reference generator to the measured output, the bumpless
        start.  The RTL latches {count, 32'd0} (position task; ``count`` = the encoder count at the
        command) or {sext(omega), 16'd0} (speed task; omega = the sequencer's speed estimate of the
        last control period, which runs with the law off too: ADC noise gives a few LSB of i_q, the
        KACC term makes them a nonzero omega).  The task is the active image's (the RTL's task_pos
        while the sync runs: a swap requested before the command but not yet decided at a control
        boundary has not changed it).  Returns the Q.32 value the generator was set to."""
        if self.seq.params.task == "position":
            v = (count & M32) << 32
        else:
            v = (self.seq.omega_prev << (32 - F.W_FRAC)) & M64
        self.ref.sync(v)
        return v

    def _reference(self, t: float) -> list:
        task_pos = self.seq.params.task == "position"
        if self.ref is not None:
            w = self.ref.advance(hold=self.seq.hold, task_pos=task_pos)
            self.gov_clamps += int(self.ref.clamped)
            return w
        target = [x & M64 for x in self.refs(self.k, t)]
        if self._gdl is None and not self.gov["enable"]:
            self._gdl = list(target)               # bumpless start: the target window
        else:
            if self._gdl is None:                  # as the RTL after a sync to w_k (governor.ReferencePath)
                self._gdl, self._r_prev = [target[0]] * len(target), target[0]
            g_new, self._v_gov, clamped, self._vb_gov = gov_step(self.gov, self._v_gov, self._r_prev, target[-1],
                                                                 self._gdl[-1], self.seq.hold, task_pos, self._vb_gov)
            self._gdl = self._gdl[1:] + [g_new]
            self.gov_clamps += int(clamped)
        self._r_prev = target[-1]
        return list(self._gdl)

    def period(self, count: int, codes=None, t: float = 0.0, cur=None) -> dict:
        """One PWM period from the ADC trigger's samples: ``count`` (encoder, any int), ``codes``
        (three raw ADC codes) or ``cur`` (the ADC's offset-corrected window means, as adc_spi hands
        them to the sequencer: the co-simulation with back-to-back frames), ``t`` (trigger time, for
        ``refs``).  Returns the sequencer's outputs (:meth:`CtrlSeq.period`) plus ``ref_w`` (the N+1
        references of a control period)."""
        if (codes is None) == (cur is None):
            raise ValueError("AxisModel.period needs exactly one of codes and cur")
        cfg = self.cfg
        if self._boundary_ref is not None:
            control, ref_w = self._boundary_ref
            self._boundary_ref = None
        else:
            control = self.control_next
            if control and self.swap_params is not None:
                self.seq.params, self.swap_params = self.swap_params, None
            ref_w = self._reference(t) if control else None
        theta16 = pos_sense.angle(count, cfg.sensors.encoder_cpr, cfg.motor.p, base=self.cal_offset)
        off = cfg.sensors.adc_offset
        if cur is None:
            cur = tuple(c - off for c in codes)
        out = self.seq.period(theta16, count & M32, tuple(cur), self.regs, ref_w)
        out["ref_w"] = ref_w
        if control:
            self.last_control = dict(out, ref_w0=ref_w[0])
            self.k += 1
        self.periods += 1
        return out


def ref_q32(cfg, task: str, value_si: float) -> int:
    """Task-output reference in the ref_gen's Q.32 unit (counts, or counts per Ts), modulo 2^64."""
    unit = cfg.rad_per_count if task == "position" else cfg.rad_s_per_count_ts
    return int(round(value_si / unit * (1 << 32))) & ((1 << 64) - 1)


def regs_for(cfg, task: str, algorithm: int | None = None, **kw) -> Regs:
    """Sequencer registers of the design (``algorithm``, default control.algorithm; ``task``) as the firmware
    writes them with its image (the header's reset values for the boot design; KACC and KACC.win follow the
    design's speed window, manifest designs.kacc); ``kw`` overrides."""
    cfg = cfg.for_design(algorithm or cfg.control.algorithm, task)
    kacc, kacc_shift = header.speed_correction_raw(cfg)
    fw = header.field_weakening_raw(cfg)
    gov = header.governor_raw(cfg, task)
    base = dict(pwm_per_control=cfg.pwm_per_control, kacc=kacc, kacc_shift=kacc_shift,
                half_period=cfg.pwm_half_period, load_shift=cfg.speed_load_shift, fw_shift=fw["FW_SHIFT"],
                fw_nmax=fw["FW_NMAX"], fw_thr=(fw["FW_R2_HI"], fw["FW_R2_LO"]), iq_hold=gov["IQ_HOLD"],
                win_shift=cfg.control.speed_window.bit_length() - 1)
    base.update(kw)
    return Regs(**base)


def gov_params(cfg, task: str) -> dict:
    """The reference generator's governor words of ``task`` as the engine reads them."""
    g = header.governor_raw(cfg, task)
    return {"enable": bool(g["GOV_EN"]), "ksh": g["GOV_KSH"], "vmax": g["GOV_VMAX_LO"] | g["GOV_VMAX_HI"] << 32,
            "a": g["GOV_A_LO"] | g["GOV_A_HI"] << 32}


@dataclass
class BitLoopResult:
    trace: cl.Trace
    cmp: np.ndarray
    counts: list = field(default_factory=list)
    records: list = field(default_factory=list)


def simulate(cfg, scenario: cl.Scenario, params=None, seed: int = 0, substeps: int = 4,
             refs=None, cal_offset: int = 0, regs: Regs | None = None, plant_motor=None,
             gov: dict | None = None) -> BitLoopResult:
    """Closed loop with the bit-accurate axis model.  ``refs(k)`` may supply the N+1 Q.32
    target references of control period k (default: the scenario profile sampled and rounded);
    they pass through the governor ``gov`` (default: the header's for the task).
    ``plant_motor`` lets the plant differ from the design motor."""
    config_mod.require_rtl_speed_window(cfg)
    cfg = cfg.for_design(cfg.control.algorithm, scenario.task)     # the design's speed window (KACC.win)
    c = cfg.control
    alg_task = (c.algorithm, scenario.task)
    params = params or design_mod.design(cfg.with_control(task=scenario.task), *alg_task, force=True)["params"]
    M = cfg.pwm_per_control
    P = cfg.pwm_half_period
    Tpwm = 1.0 / cfg.inverter.f_pwm
    plant = pmsm.Plant(plant_motor or cfg.motor, cfg.inverter.Udc, cfg.inverter.f_pwm, substeps=substeps)
    plant.state = pmsm.PlantState(*scenario.x0)
    sensors = pmsm.Sensors(cfg, rng=np.random.default_rng(seed))
    if refs is not None:
        ref_fn = lambda k, t: refs(k)                                              # noqa: E731
    else:
        ref_fn = lambda k, t: [ref_q32(cfg, scenario.task, scenario.profile(t + j * c.Ts)[2])  # noqa: E731
                               for j in range(c.N + 1)]
    axis = AxisModel(cfg, params, regs=regs if regs is not None else regs_for(cfg, scenario.task), refs=ref_fn,
                     cal_offset=cal_offset, gov=gov if gov is not None else gov_params(cfg, scenario.task))
    n = int(round(scenario.duration / c.Ts))
    rec = {k: [] for k in ("t", "i_d", "i_q", "w_e", "theta_e", "u_d", "u_q", "ipk", "sat", "w_meas")}
    ref_rec, cmp_rec, counts_rec, records = [], [], [], []
    duties = np.zeros(3)
    t = 0.0
    vpu = cfg.volts_per_tick / (1 << F.U_FRAC)
    ipk = 0.0
    for period in range(n * M):
        if scenario.load is not None:
            plant.tau_load = scenario.load(t)
        plant.step(0.5 * Tpwm, duties)
        t += 0.5 * Tpwm
        ipk = max(ipk, float(np.max(np.abs(plant.phase_currents()))))
        st = plant.state
        codes = sensors.adc_codes(plant.phase_currents())
        count = sensors.encoder_count(st.theta_e)
        out = axis.period(count, codes, t)
        control = out["control"]
        plant.step(0.5 * Tpwm, duties)
        t += 0.5 * Tpwm
        ipk = max(ipk, float(np.max(np.abs(plant.phase_currents()))))
        duties = np.array(out["cmp"], dtype=float) / P
        cmp_rec.append(out["cmp"])
        if control:
            counts_rec.append(count)
            rec["t"].append(t - 0.5 * Tpwm)
            ref_rec.append(scenario.profile(t - 0.5 * Tpwm))
            rec["i_d"].append(st.i_d)
            rec["i_q"].append(st.i_q)
            rec["w_e"].append(st.w_e)
            rec["theta_e"].append(st.theta_e)
            rec["u_d"].append(axis.u[0] * vpu)
            rec["u_q"].append(axis.u[1] * vpu)
            r = out.get("core")
            rec["sat"].append(1 if r is not None and r.counts.get("limit") else 0)
            rec["w_meas"].append(out["omega"] / (1 << F.W_FRAC) * cfg.rad_s_per_count_ts)
            rec["ipk"].append(ipk)
            ipk = 0.0
            records.append({"omega": out["omega"], "i_d": out["i_d"], "i_q": out["i_q"], "u": axis.u,
                            "flags": r.flags if r is not None else 0, "w_k": out["ref_w"][0], "i_fw": out["i_fw"],
                            "hold": out["hold"], "gov_clamps": axis.gov_clamps})
    a = {kk: np.array(v) for kk, v in rec.items()}
    tr = cl.Trace(a["t"], np.array(ref_rec), a["i_d"], a["i_q"], a["w_e"], a["theta_e"], a["u_d"], a["u_q"],
                  a["ipk"], a["sat"], a["w_meas"])
    return BitLoopResult(tr, np.array(cmp_rec), counts_rec, records)
