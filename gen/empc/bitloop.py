"""Bit-accurate closed loop: the plant driven by the Python models of the whole RTL axis.

Per PWM period: the plant runs half a period with the current duties; at the
period centre the ADC codes and the encoder count are sampled (the ADC
trigger), the sequencer model (rtlmodel/ctrl_seq.py: front end, MPC core,
modulation) computes the compare values, and they take effect at the next
period boundary, half a period later - exactly the RTL's timing.  The RTL
co-simulation (tb/test_closed_loop.py) is compared against this loop.
The task references pass through the reference generator's integer governor
(rtlmodel/ref_gen.gov_step) with the hold flag of the sequencer model, as in the RTL.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import closedloop as cl
from . import formats as F
from . import design as design_mod, header, pmsm
from .rtlmodel import pos_sense
from .rtlmodel.ctrl_seq import CtrlSeq, Regs
from .rtlmodel.ref_gen import M64, gov_step


def ref_q32(cfg, task: str, value_si: float) -> int:
    """Task-output reference in the ref_gen's Q.32 unit (counts, or counts per Ts), modulo 2^64."""
    unit = cfg.rad_per_count if task == "position" else cfg.rad_s_per_count_ts
    return int(round(value_si / unit * (1 << 32))) & ((1 << 64) - 1)


def regs_for(cfg, task: str, **kw) -> Regs:
    """Sequencer registers as the generator's header sets them after reset (``kw`` overrides)."""
    kacc, kacc_shift = header.speed_correction_raw(cfg)
    fw = header.field_weakening_raw(cfg)
    gov = header.governor_raw(cfg, task)
    base = dict(pwm_per_control=cfg.pwm_per_control, kacc=kacc, kacc_shift=kacc_shift,
                half_period=cfg.pwm_half_period, load_shift=cfg.speed_load_shift, fw_shift=fw["FW_SHIFT"],
                fw_nmax=fw["FW_NMAX"], fw_thr=(fw["FW_R2_HI"], fw["FW_R2_LO"]), iq_hold=gov["IQ_HOLD"])
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
    c = cfg.control
    alg_task = (c.algorithm, scenario.task)
    params = params or design_mod.design(cfg.with_control(task=scenario.task), *alg_task)["params"]
    M = cfg.pwm_per_control
    P = cfg.pwm_half_period
    Tpwm = 1.0 / cfg.inverter.f_pwm
    plant = pmsm.Plant(plant_motor or cfg.motor, cfg.inverter.Udc, cfg.inverter.f_pwm, substeps=substeps)
    plant.state = pmsm.PlantState(*scenario.x0)
    sensors = pmsm.Sensors(cfg, rng=np.random.default_rng(seed))
    regs = regs or regs_for(cfg, scenario.task)
    gp = gov if gov is not None else gov_params(cfg, scenario.task)
    task_pos = scenario.task == "position"
    gdl, r_prev, v_gov, gov_clamps = None, 0, 0, 0
    seq = CtrlSeq(params=params, N=c.N)
    cpr, p = cfg.sensors.encoder_cpr, cfg.motor.p
    n = int(round(scenario.duration / c.Ts))
    rec = {k: [] for k in ("t", "i_d", "i_q", "w_e", "theta_e", "u_d", "u_q", "ipk", "sat", "w_meas")}
    ref_rec, cmp_rec, counts_rec, records = [], [], [], []
    duties = np.zeros(3)
    t = 0.0
    k = 0
    off = cfg.sensors.adc_offset
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
        theta16 = pos_sense.angle(count, cpr, p, base=cal_offset)
        cur = tuple(code - off for code in codes)
        control = seq.per_cnt + 1 >= regs.pwm_per_control
        ref_w = None
        if control:
            if refs is not None:
                target = refs(k)
            else:
                target = [ref_q32(cfg, scenario.task, scenario.profile(t + j * c.Ts)[2]) for j in range(c.N + 1)]
            if gdl is None:                  # bumpless start: the target window
                gdl = [x & M64 for x in target]
            else:
                g_new, v_gov, clamped = gov_step(gp, v_gov, r_prev, target[-1] & M64, gdl[-1], seq.hold, task_pos)
                gdl = gdl[1:] + [g_new]
                gov_clamps += int(clamped)
            r_prev = target[-1] & M64
            ref_w = list(gdl)
        out = seq.period(theta16, count & 0xFFFFFFFF, cur, regs, ref_w)
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
            rec["u_d"].append(seq.u[0] * vpu)
            rec["u_q"].append(seq.u[1] * vpu)
            r = out.get("core")
            rec["sat"].append(1 if r is not None and r.counts.get("limit") else 0)
            rec["w_meas"].append(out["omega"] / (1 << F.W_FRAC) * cfg.rad_s_per_count_ts)
            rec["ipk"].append(ipk)
            ipk = 0.0
            records.append({"omega": out["omega"], "i_d": out["i_d"], "i_q": out["i_q"], "u": seq.u,
                            "flags": r.flags if r is not None else 0, "w_k": ref_w[0], "i_fw": out["i_fw"],
                            "hold": out["hold"], "gov_clamps": gov_clamps})
            k += 1
    a = {kk: np.array(v) for kk, v in rec.items()}
    tr = cl.Trace(a["t"], np.array(ref_rec), a["i_d"], a["i_q"], a["w_e"], a["theta_e"], a["u_d"], a["u_q"],
                  a["ipk"], a["sat"], a["w_meas"])
    return BitLoopResult(tr, np.array(cmp_rec), counts_rec, records)
