"""Motors of very different size with the default per-unit weights (issue 15 acceptance, item F).

For each bundled motor: every design passes the robust design check (the box, the margins, the
fit gate) at the configured Ts and at 250 us / 50 us (issue 16 item 5), and the five scenarios
(amplitudes scaled with the ratings, scenarios.scale_for) run in float and in the bit-accurate
form with the plant at nominal and at box corners, with bounds:
  * stable: finite, the task output bounded, held steps end near their target;
  * the fixed-point loop follows the float loop (RMS tracking error within 10 % + 1 LSB);
  * held steps end at least half way to their target (plus 4 sensor counts): the default weights give
    loops whose speed follows 1 / T_m, and 001's T_m is 115 ms against 100 ms segments;
  * |i| <= 1.05 i_max (the reference governor's current limit, issue 15 item 4) and below the ADC range.
The fast suite checks the two added motors on short runs; the full sweep is ``@pytest.mark.full``.
"""
import dataclasses

import numpy as np
import pytest

from empc import closedloop as cl, config, design, governor, report, robust, scenarios
from empc.controllers.explicit import ExplicitMPC
from empc.controllers.fixed import FixedMPC

CONFIGS = config.DEFAULT_CONFIG.parent
MOTORS = ["blwr233d", "ipmsm_001", "spmsm_002", "ec45flat_24v", "premo_320v"]
NEW = ["ec45flat_24v", "premo_320v"]


def load(name, **ov):
    return config.load(CONFIGS / f"{name}.toml", ov or None)


def test_new_motors_are_10x_apart():
    a, b = load("ec45flat_24v"), load("premo_320v")
    assert b.ratings.power / a.ratings.power >= 10
    assert b.motor.J / a.motor.J >= 10
    assert b.inverter.Udc / a.inverter.Udc >= 10


@pytest.mark.parametrize("name", NEW)
def test_default_per_unit_weights_pass_the_box(name):
    cfg = load(name)
    assert cfg.control.weight_units == "pu"
    dflt = cfg.with_control(weights={k: config.weights_si(config.DEFAULT_WEIGHTS_PU[k], cfg.bases(k[1]))
                                     for k in [(1, "speed"), (1, "position")]})
    for c, what in ((dflt, "default"), (cfg, "configured (empc tune)")):
        for key in sorted(c.control.weights):
            st = design.design(c, *key)["stability"]
            assert st["passed"], (name, what, key, st["reason"])


# designs that do not pass at a Ts variant: none.  The weights tuned at 250 us failed at 50 us (the PWM
# update delay is 0.5 Ts there, and algorithm 2's proportional action shrinks with the horizon N Ts:
# docs/design.md); the bundled configurations hold control-period tables [weights.<design>.Ts_50us]
# (ipmsm_001: Ts_250us, its own Ts is 100 us) found with the coordinate search of `empc tune --refine`.
# Was: blwr233d 50 us alg1 position damping 0.044, alg2 position radius 1.065, alg2 speed 1.155;
# premo_320v 50 us alg2 speed 1.277, position 1.277; ipmsm_001 250 us alg2 speed 1.051; ec45flat_24v
# 50 us alg2 speed 1.259, position 1.217.
KNOWN: dict = {}


@pytest.mark.full
@pytest.mark.parametrize("name", MOTORS)
@pytest.mark.parametrize("ts", [None, 250e-6, 50e-6])
def test_every_design_passes_at_each_ts(name, ts):
    cfg = load(name) if ts is None else load(name, **{"control.Ts": ts, "inverter.f_pwm": 20000.0})
    for key in sorted(cfg.control.weights):
        why = KNOWN.get((name, ts)) or KNOWN.get((name, ts, key))
        try:
            st = design.design(cfg, *key, force=True)["stability"]
            ok, reason = st["passed"], st["reason"]
        except config.ConfigError as e:
            ok, reason = False, str(e)
        if why:
            assert not ok, (name, ts, key, "known failure now passes: update KNOWN")
            continue
        assert ok, (name, ts, key, reason)


def _plant(cfg, alg, task, plant):
    """None (nominal), or the box point where the design's loop is least damped ("corner_a", from
    its design check) or the opposite corner ("corner_b")."""
    if plant == "nominal":
        return None
    f = design.design(cfg, alg, task)["stability"]["worst_damping"]["factors"]
    if plant == "corner_b":
        f = {k: 2.0 - v for k, v in f.items()}
    return f


def _run(cfg, name, plant, fixed, duration=None):
    sc, alg = scenarios.get(name, cfg)
    if duration:
        sc = dataclasses.replace(sc, duration=duration, segments=[s for s in sc.segments if s[2] <= duration + 1e-9])
    c = cfg.with_control(algorithm=alg, task=sc.task)
    pt = _plant(c, alg, sc.task, plant)
    ctl = FixedMPC(c) if fixed else ExplicitMPC(c, gains="poly")
    tr = cl.simulate(c, ctl, sc, plant_motor=robust.perturbed(c.motor, pt) if pt else None)
    m = cl.metrics(tr, sc, settle_floor=report._band(c, sc), preview=c.control.N * c.control.Ts)
    return sc, tr, m


def _bounds(cfg, name, sc, tr_f, m_f, tr_x, m_x):
    y_ref = np.max(np.abs(tr_f.ref[:, 2])) + 1e-9
    for tr, m in ((tr_f, m_f), (tr_x, m_x)):
        # finite and the task output bounded; the phase current within i_max and the ADC range needs the
        # current limit (test_current_within_limit): a tuned position loop asks hundreds of amperes
        # for the scaled position step without it (issue 15 item 4)
        assert np.max(np.abs(tr.output(sc.task))) < 2.0 * y_ref + 50 * (cfg.rad_per_count if sc.task == "position"
                                                                       else cfg.rad_s_per_count_ts)
        assert np.all(np.isfinite(tr.i_q)) and np.all(np.isfinite(tr.u_q))
    res = cfg.rad_per_count if sc.task == "position" else cfg.rad_s_per_count_ts
    assert abs(m_f["rms_error"] - m_x["rms_error"]) <= 0.10 * m_f["rms_error"] + res, (m_f["rms_error"], m_x["rms_error"])
    last = m_x["segments"][-1]
    if last["kind"] == "step":
        step = max(abs(last["to"] - last["from"]), abs(last["to"]), 1e-9)
        reach = min(step, _governed_reach(cfg, sc.task, last["t1"] - last["t0"] - cfg.control.N * cfg.control.Ts))
        assert last["final_error"] <= step - 0.5 * reach + 4 * res, last      # moved at least half way


def _governed_reach(cfg, task, T):
    """How far the reference governor lets the task reference move in T seconds from rest (the
    triangular or trapezoidal profile of its acceleration and speed limits): fault_step's 20 ms are
    shorter than the governed 20 rad move on the BLWR233D (25 ms)."""
    p, Ts = governor.params(cfg, task), cfg.control.Ts
    if task == "speed":
        return p.vmax / Ts * max(T, 0.0)
    a, vmax = p.a / Ts ** 2, p.vmax / Ts
    T = max(T, 0.0)
    return a * (T / 2) ** 2 if a * T / 2 <= vmax else vmax * T - vmax ** 2 / a


@pytest.mark.parametrize("name", NEW)
@pytest.mark.parametrize("plant", ["nominal", "corner_a"])
def test_new_motor_short_runs_float_and_fixed(name, plant):
    cfg = load(name)
    for scen in ("speed_steps", "position_alg1"):
        sc, tr_f, m_f = _run(cfg, scen, plant, fixed=False, duration=0.12)
        _, tr_x, m_x = _run(cfg, scen, plant, fixed=True, duration=0.12)
        _bounds(cfg, f"{name}/{scen}/{plant}", sc, tr_f, m_f, tr_x, m_x)


@pytest.mark.full
@pytest.mark.parametrize("name", MOTORS)
@pytest.mark.parametrize("scen", list(scenarios.SCENARIOS))
@pytest.mark.parametrize("plant", ["nominal", "corner_a", "corner_b"])
def test_five_scenarios_float_and_fixed(name, scen, plant):
    cfg = load(name)
    sc0, alg = scenarios.get(scen, cfg)
    if (alg, sc0.task) not in cfg.control.weights:
        pytest.skip(f"{name} has no weights.alg{alg}.{sc0.task} design (it does not pass the box)")
    sc, tr_f, m_f = _run(cfg, scen, plant, fixed=False)
    _, tr_x, m_x = _run(cfg, scen, plant, fixed=True)
    _bounds(cfg, f"{name}/{scen}/{plant}", sc, tr_f, m_f, tr_x, m_x)


@pytest.mark.parametrize("name", MOTORS)
def test_every_scenario_within_current_limit(name):
    """Issue 15 acceptance: each scenario the motor has a design for, full length, nominal plant, fixed
    point: |i| <= 1.05 i_max.  fault_step (a step 0.5 ms after the start, inside the first window) drew
    4.7 i_max on the premo while the float governor took its first window as given."""
    cfg = load(name)
    ran = 0
    for scen in scenarios.SCENARIOS:
        sc0, alg = scenarios.get(scen, cfg)
        if (alg, sc0.task) not in cfg.control.weights:
            continue
        # spmsm_002's field_weakening (12.5 s ramps): its first second here, all of it in the full FW test
        _, tr, _ = _run(cfg, scen, "nominal", fixed=True, duration=1.0 if sc0.duration > 1.0 else None)
        assert np.max(tr.i_phase_peak) <= 1.05 * cfg.control.i_max, (name, scen, np.max(tr.i_phase_peak))
        ran += 1
    assert ran >= 4, (name, ran)


@pytest.mark.parametrize("name", NEW)
def test_current_within_limit(name):
    cfg = load(name)
    for scen in ("speed_steps", "position_alg1"):
        _, tr, _ = _run(cfg, scen, "nominal", fixed=True, duration=0.12)
        assert np.max(tr.i_phase_peak) <= 1.05 * cfg.control.i_max, (name, scen, np.max(tr.i_phase_peak))
        assert np.max(tr.i_phase_peak) < cfg.adc_range_amps, (name, scen, np.max(tr.i_phase_peak))


# Field weakening (issue 15 item 6) on every motor, off the nominal path.  The scenario's top speed and
# ramp duration are scaled per motor (scenarios.fw_plan); the plant at a box corner may not reach the
# top at all (its flux +20 %: a lower speed limit), so each run is checked against what that plant can
# reach, its steady-state speed limit w_fw with i_d >= -fw_max (scenarios.fw_speed_limit):
FW_REACH_TOL = 0.97     # the plant holds at least 0.98 x min(top, 0.97 x its w_fw) in the hold's second half
FW_RMS = 0.03           # RMS speed error where the reference is within reach: at most 3 % of the top speed
FW_END = 0.01           # the speed at the end within 1 % of the top speed of 0
FW_ID = -0.05           # i_d mean in the hold's second half below -0.05 i_max where the plant needs FW
# spmsm_002 (J = 0.0134 kg m^2): its ramps take 12.5 s; the speed stops at 755 rad/s (0.61 x base, the
# reference at 1538) at every plant, float and fixed: u_q carries a broadband 1.3-2.5 kHz ripple of 5.8 V
# RMS (21 % of u_max; 0.94 A on i_q) under the scenario's load, the same without ADC noise, dead time,
# friction or field weakening and with either speed estimate, so |u| touches the circle at 0.66 u_max on
# average, the limiter's flag holds the governor (the reference stops) and the FW counter sees |u_raw|
# cross u_hi and u_lo in turn.  Its algorithm-1 speed design (worst radius 0.9999 over the box) needs
# retuning (issue 15 items 2/3), not the field weakening.
FW_XFAIL = {("spmsm_002", plant, fixed): "spmsm_002: u_q ripple 21 % of u_max holds the governor at 0.61 x "
            "base (its alg-1 speed design, not FW)" for plant in ("nominal", "corner_a", "corner_b")
            for fixed in (False, True)}


def _fw_check(cfg, name, plant, fixed):
    sc, tr, _ = _run(cfg, "field_weakening", plant, fixed=fixed)
    plan = scenarios.fw_plan(cfg)
    f = _plant(cfg.with_control(algorithm=1, task="speed"), 1, "speed", plant)
    pp = scenarios.fw_plan(cfg, robust.perturbed(cfg.motor, f) if f else cfg.motor)
    top, i_max = plan.top, cfg.control.i_max
    reach = min(top, FW_REACH_TOL * pp.w_fw)
    w, ref, t = tr.output("speed"), tr.ref[:, 2], tr.t
    _, t1, t2, _, _ = sc.segments[1]                         # the hold at the top
    hold = (t >= 0.5 * (t1 + t2)) & (t < t2)
    ok = ref <= reach
    rms = float(np.sqrt(np.mean((w[ok] - ref[ok]) ** 2)))
    fig = {"w_hold_min/reach": float(np.min(w[hold]) / reach), "w_max/top": float(np.max(w) / top),
           "rms/top": rms / top, "i_d_hold/i_max": float(np.mean(tr.i_d[hold]) / i_max),
           "peak/i_max": float(np.max(tr.i_phase_peak) / i_max), "w_end/top": float(w[-1] / top),
           "top/base": top / plan.base, "reach/top": reach / top, "needs_fw": pp.w_nofw < 0.98 * top}
    print(name, plant, "fixed" if fixed else "float", {k: round(v, 3) for k, v in fig.items()})
    assert fig["w_hold_min/reach"] >= 0.98, (name, plant, fig)               # reaches its top and holds it
    assert fig["w_max/top"] <= 1.03, (name, plant, fig)
    assert fig["rms/top"] <= FW_RMS, (name, plant, fig)                      # no lock on the voltage circle
    assert fig["peak/i_max"] <= 1.05, (name, plant, fig)
    assert abs(fig["w_end/top"]) <= FW_END, (name, plant, fig)               # the ramp down returns to 0
    if fig["needs_fw"]:
        assert fig["i_d_hold/i_max"] < FW_ID, (name, plant, fig)             # i_d < 0 at the top
    return fig


def test_field_weakening_plan():
    """The scaled field_weakening: the BLWR233D's scenario unchanged; elsewhere a top speed within
    FW_REACH of the FW speed limit and ramps within FW_ACCEL of the governor's acceleration."""
    from empc import governor
    sc, alg = scenarios.get("field_weakening", load("blwr233d"))
    assert (alg, sc.duration, sc.segments[1]) == (1, 0.56, ("step", 0.22, 0.32, 1400.0, 1400.0))
    assert scenarios.fw_plan(load("blwr233d")).ramp == 0.2
    for name in MOTORS:
        cfg = load(name)
        p = scenarios.fw_plan(cfg)
        sc, _ = scenarios.get("field_weakening", cfg)
        assert p.top <= scenarios.FW_REACH * p.w_fw + 1e-9, (name, p)
        assert p.top <= scenarios.FW_TOP * scenarios.scale_for(cfg).base, (name, p)     # at most 1.35 x base
        assert p.top / p.ramp <= scenarios.FW_ACCEL * governor.accel_limit(cfg) * (1 + 1e-12), (name, p)
        assert sc.segments[0][4] == p.top and abs(sc.segments[0][2] - sc.segments[0][1] - p.ramp) < 1e-12
        assert ("negligible" in sc.description) == p.negligible, (name, sc.description)
        assert np.isclose(sc.profile(sc.segments[1][1] + 0.05)[2], p.top)
    # ipmsm_001: psi / Ld = 400 A against i_max = 10 A, FW adds 1.5 %; spmsm_002: J = 0.0134 kg m^2
    assert scenarios.fw_plan(load("ipmsm_001")).negligible
    assert scenarios.fw_plan(load("spmsm_002")).ramp > 5.0


def test_fw_speed_limit_against_steady_state():
    """fw_speed_limit: |u| = u_max at the returned speed with the returned best i_d (an independent
    evaluation of the voltage equations), and more speed with FW than without on the BLWR233D."""
    cfg = load("blwr233d")
    m = cfg.motor
    w0 = scenarios.fw_speed_limit(m, cfg.u_max, 0.0, cfg.control.i_max, 0.0)
    i_q = m.tau_c / (1.5 * m.p * m.psi)
    u = np.hypot(-w0 * m.Lq * i_q, m.R * i_q + w0 * m.psi)
    assert np.isclose(u, cfg.u_max, rtol=1e-9), (u, cfg.u_max)
    w1 = scenarios.fw_speed_limit(m, cfg.u_max, -0.6 * cfg.control.i_max, cfg.control.i_max, 0.227)
    assert w1 > 2.0 * w0


FW_FAST = ["blwr233d", "ipmsm_001", "ec45flat_24v", "premo_320v"]     # spmsm_002's ramps take 12.5 s


@pytest.mark.parametrize("name", FW_FAST)
def test_field_weakening_nominal_float(name):
    _fw_check(load(name), name, "nominal", fixed=False)


@pytest.mark.full
@pytest.mark.parametrize("name", MOTORS)
@pytest.mark.parametrize("plant", ["nominal", "corner_a", "corner_b"])
@pytest.mark.parametrize("fixed", [False, True], ids=["float", "fixed"])
def test_field_weakening_every_motor_and_corner(name, plant, fixed, request):
    why = FW_XFAIL.get((name, plant, fixed))
    if why:
        request.applymarker(pytest.mark.xfail(reason=why, strict=True))      # flags when the design is fixed
    _fw_check(load(name), name, plant, fixed)
