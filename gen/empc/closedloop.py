"""Closed-loop simulation: controller + averaged inverter + PMSM + sensors.

Timing per PWM period (centre-aligned, period T_pwm): duties are held for the
whole period; the currents and the encoder are sampled at the period centre of
the last PWM period of each control period (the RTL's ADC trigger), the
controller computes u_k, and the new duties take effect at the next period
boundary (half a PWM period later).  Between control updates the held u_dq is
re-modulated every PWM period with the latest encoder angle (the sequencer
does the same), so the applied dq voltage does not drift with the rotor.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import pmsm
from .reference import Profile


@dataclass
class Measurement:
    t: float
    adc: list            # raw ADC codes A, B, C
    counts: int          # encoder count (x4)
    hall: int            # HALL sector 1..6
    i_abc: np.ndarray    # phase currents from the ADC codes, A
    theta_e: float       # electrical angle from the encoder, rad (multi-turn)
    i_d: float           # float Park of the measured currents at theta_e
    i_q: float
    w_k: np.ndarray      # reference at this sample (3)
    W: np.ndarray        # references w_{k+1..k+N} (N x 3)


@dataclass
class Scenario:
    name: str
    task: str
    duration: float
    profile: Profile
    load: callable = None                    # t -> load torque (N m)
    description: str = ""
    segments: list = field(default_factory=list)   # (kind, t0, t1, v0, v1) for the metrics
    speed_imposed: callable = None           # t -> w_e (rad/s): speed held by a load machine
    x0: tuple = (0.0, 0.0, 0.0, 0.0)


@dataclass
class Trace:
    t: np.ndarray
    ref: np.ndarray       # (n, 3) w_k
    i_d: np.ndarray
    i_q: np.ndarray
    w_e: np.ndarray
    theta_e: np.ndarray
    u_d: np.ndarray
    u_q: np.ndarray
    i_phase_peak: np.ndarray
    sat: np.ndarray
    w_meas: np.ndarray
    extra: dict = field(default_factory=dict)

    def output(self, task: str) -> np.ndarray:
        return self.w_e if task == "speed" else self.theta_e


def simulate(cfg, controller, scenario: Scenario, seed: int = 0, substeps: int = 4,
             plant_motor=None, ideal_timing: bool = False, dead_time: float = 0.0) -> Trace:
    """Run ``controller`` on the plant for ``scenario``; returns the per-control-period trace.

    ``plant_motor`` lets the plant differ from the design motor (parameter mismatch).
    ``ideal_timing`` applies u at the sampling instant (no half-period output delay),
    for analysis only: the hardware cannot do it.
    ``dead_time`` (s) enables the plant's inverter dead-time voltage error (default off).
    """
    c = cfg.control
    M = cfg.pwm_per_control
    Tpwm = 1.0 / cfg.inverter.f_pwm
    plant = pmsm.Plant(plant_motor or cfg.motor, cfg.inverter.Udc, cfg.inverter.f_pwm, substeps=substeps,
                       dead_time=dead_time)
    plant.state = pmsm.PlantState(*scenario.x0)
    sensors = pmsm.Sensors(cfg, rng=np.random.default_rng(seed))
    controller.reset()
    n = int(round(scenario.duration / c.Ts))
    rec = {k: np.zeros(n) for k in ("t", "i_d", "i_q", "w_e", "theta_e", "u_d", "u_q", "ipk", "sat", "w_meas")}
    rec_ref = np.zeros((n, 3))
    duties = np.zeros(3)
    lsb = cfg.sensors.adc_amps_per_lsb
    off = cfg.sensors.adc_offset
    rad_per_count = cfg.rad_per_count
    w_est = 0.0
    theta_prev_meas = None
    t = 0.0
    N = c.N
    sat_prev = 0
    for k in range(n):
        ipk = 0.0
        for m in range(M):
            if scenario.load is not None:
                plant.tau_load = scenario.load(t)
            if scenario.speed_imposed is not None:
                plant.state.w_e = scenario.speed_imposed(t)
            plant.step(0.5 * Tpwm, duties)
            t += 0.5 * Tpwm
            if scenario.speed_imposed is not None:
                plant.state.w_e = scenario.speed_imposed(t)
            ipk = max(ipk, float(np.max(np.abs(plant.phase_currents()))))
            if m == M - 1:
                st = plant.state
                i_abc_true = plant.phase_currents()
                adc = sensors.adc_codes(i_abc_true)
                counts = sensors.encoder_count(st.theta_e)
                theta_meas = counts * rad_per_count
                i_abc = (np.array(adc, dtype=float) - off) * lsb
                a, b = pmsm.clarke(*i_abc)
                i_d, i_q = pmsm.park(a, b, theta_meas)
                w_k = scenario.profile(t)
                W = scenario.profile.samples(t, c.Ts, N)
                meas = Measurement(t, adc, counts, sensors.hall_sector(st.theta_e), i_abc, theta_meas,
                                   i_d, i_q, w_k, W)
                u = controller.step(meas)
                if theta_prev_meas is not None:
                    w_est = (theta_meas - theta_prev_meas) / c.Ts
                theta_prev_meas = theta_meas
                rec["t"][k] = t
                rec_ref[k] = w_k
                rec["i_d"][k], rec["i_q"][k] = st.i_d, st.i_q
                rec["w_e"][k], rec["theta_e"][k] = st.w_e, st.theta_e
                rec["u_d"][k], rec["u_q"][k] = u[0], u[1]
                rec["w_meas"][k] = w_est
                sat_now = getattr(controller, "saturations", 0)
                rec["sat"][k] = sat_now - sat_prev
                sat_prev = sat_now
                if ideal_timing:
                    duties = controller.modulate(theta_meas, w_est)
            plant.step(0.5 * Tpwm, duties)
            t += 0.5 * Tpwm
            ipk = max(ipk, float(np.max(np.abs(plant.phase_currents()))))
            # period boundary: new duties from the held u_dq and the encoder angle now
            counts_now = sensors.encoder_count(plant.state.theta_e)
            duties = controller.modulate(counts_now * rad_per_count, w_est)
        rec["ipk"][k] = ipk
    return Trace(rec["t"], rec_ref, rec["i_d"], rec["i_q"], rec["w_e"], rec["theta_e"], rec["u_d"], rec["u_q"],
                 rec["ipk"], rec["sat"], rec["w_meas"])


def metrics(tr: Trace, sc: Scenario, settle_floor: float = 0.0, preview: float = 0.0) -> dict:
    """Tracking figures per reference segment plus peaks.

    steps: overshoot (% of the step), settling time (to within max(2 % of the step,
    settle_floor) and staying there until the segment ends, less the ``preview``
    window in which the controller already sees the next segment's references),
    ramps: mean and max |error| over the second half of the ramp (the constant lag
    of algorithm 1 vs ~0 for algorithm 2), peak phase current, peak |i_dq|, peak output,
    saturations; steps also the mean i_d over their second half (field weakening).
    ``settling_time_max`` is the largest settling time, or the string "unsettled (n of m
    steps)" when a step never settles (``unsettled_steps`` counts them,
    ``settling_time_max_settled`` is the maximum over the settled ones).
    """
    y = tr.output(sc.task)
    r = tr.ref[:, 2]
    e = r - y
    out = {"segments": [], "peak_i_d": float(np.max(np.abs(tr.i_d))), "peak_i_q": float(np.max(np.abs(tr.i_q))),
           "peak_phase_current": float(np.max(tr.i_phase_peak)), "saturations": int(np.sum(tr.sat)),
           "peak_current": float(np.max(np.hypot(tr.i_d, tr.i_q))), "peak_output": float(np.max(y)),
           "rms_error": float(np.sqrt(np.mean(e * e)))}
    ramp_means, overshoots, settles, unsettled = [], [], [], 0
    for kind, t0, t1, v0, v1 in sc.segments:
        sel = (tr.t >= t0) & (tr.t < t1)
        if not np.any(sel):
            continue
        seg = {"kind": kind, "t0": t0, "t1": t1, "from": v0, "to": v1}
        if kind == "step":
            sel = sel & (tr.t < t1 - preview)
            size = v1 - v0
            band = max(0.02 * abs(size), settle_floor)
            seg["band"] = band
            ys = y[sel]
            ts = tr.t[sel]
            if size != 0:
                over = (np.max((ys - v1) * np.sign(size))) / abs(size) * 100.0
                seg["overshoot_pct"] = float(max(over, 0.0))
                overshoots.append(seg["overshoot_pct"])
            outside = np.nonzero(np.abs(ys - v1) > band)[0]
            if len(outside) == 0:
                seg["settling_time"] = 0.0
            elif outside[-1] == len(ys) - 1:
                seg["settling_time"] = None      # never settled within the segment
            else:
                seg["settling_time"] = float(ts[outside[-1] + 1] - t0)
            if seg["settling_time"] is not None:
                settles.append(seg["settling_time"])
            else:
                unsettled += 1
            tail = e[sel][-max(1, len(ys) // 2):]
            seg["final_error"] = float(np.mean(np.abs(tail[-max(1, len(ys) // 10):])))
            seg["final_error_mean"] = float(np.mean(tail))       # signed: zero-symmetric error -> ~0
            seg["i_d_mean"] = float(np.mean(tr.i_d[sel][-max(1, len(ys) // 2):]))
        elif kind == "ramp":
            half = sel & (tr.t >= 0.5 * (t0 + t1))
            if not np.any(half):
                continue
            seg["ramp_error_mean"] = float(np.mean(e[half]))
            seg["ramp_error_max"] = float(np.max(np.abs(e[half])))
            seg["ramp_error_std"] = float(np.std(e[half]))
            ramp_means.append(abs(seg["ramp_error_mean"]))
        out["segments"].append(seg)
    out["ramp_error_mean_abs"] = float(np.mean(ramp_means)) if ramp_means else None
    out["overshoot_pct_max"] = float(np.max(overshoots)) if overshoots else None
    # a step that never settles is reported as such, not dropped from the maximum
    n_steps = len(settles) + unsettled
    out["unsettled_steps"] = unsettled
    out["settling_time_max_settled"] = float(np.max(settles)) if settles else None
    if unsettled:
        out["settling_time_max"] = f"unsettled ({unsettled} of {n_steps} steps)"
    else:
        out["settling_time_max"] = float(np.max(settles)) if settles else None
    return out
