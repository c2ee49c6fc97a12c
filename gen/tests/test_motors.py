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
import numpy as np
import pytest

from empc import closedloop as cl, config, corners, design, governor, report, robust, scenarios
from empc.controllers.explicit import ExplicitMPC
from empc.controllers.fixed import FixedMPC

CONFIGS = corners.CONFIGS
MOTORS = list(corners.MOTORS)
NEW = ["ec45flat_24v", "premo_320v"]
load = corners.load


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
    cfg = load(name) if ts is None else load(name, **{"control.Ts": ts, "inverter.f_pwm": corners.TS_PWM})
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


_plant = corners.plant_factors     # nominal: None; corner_a: the design check's least-damped box point; corner_b


def _run(cfg, name, plant, fixed, duration=None):
    """One scenario run (corners.simulate: the same plants and forms as `make corners`) and its metrics."""
    sc, c, tr, _ = corners.simulate(cfg, name, plant, "fixed" if fixed else "float", duration)
    m = cl.metrics(tr, sc, settle_floor=report._band(c, sc), preview=c.control.N * c.control.Ts)
    return sc, tr, m


def _bounds(cfg, name, sc, tr_f, m_f, tr_x, m_x):
    y_ref = np.max(np.abs(tr_f.ref[:, 2])) + 1e-9
    for tr, m in ((tr_f, m_f), (tr_x, m_x)):
        # finite and the task output bounded; the phase current within i_max and the ADC range needs the
        # current limit (test_every_scenario_within_current_limit): a tuned position loop asks hundreds of amperes
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
    point: |i| <= 1.05 i_max and below the ADC range (it replaces the two 0.12 s runs of the two added
    motors that checked the same).  fault_step (a step 0.5 ms after the start, inside the first window) drew
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
        assert np.max(tr.i_phase_peak) < cfg.adc_range_amps, (name, scen, np.max(tr.i_phase_peak))
        ran += 1
    assert ran >= 4, (name, ran)


# Field weakening (issue 15 item 6) on every motor, off the nominal path.  The scenario's top speed and
# ramp duration are scaled per motor (scenarios.fw_plan); the plant at a box corner may not reach the
# top at all (its flux +20 %: a lower speed limit), so each run is checked against what that plant can
# reach, its steady-state speed limit w_fw with i_d >= -fw_max (scenarios.fw_speed_limit):
FW_REACH_TOL = 0.97     # the plant holds at least 0.98 x min(top, 0.97 x its w_fw) in the hold's second half
FW_RMS = 0.03           # RMS speed error where the reference is within reach: at most 3 % of the top speed
FW_END = 0.01           # the speed at the end within 1 % of the top speed of 0
FW_ID = -0.05           # i_d mean in the hold's second half below -0.05 i_max where the plant needs FW
# spmsm_002 (J = 0.0134 kg m^2): its ramps take 12.5 s.  It stopped at 0.61 x base (755 of 1538 rad/s) at
# every plant until its algorithm-1 speed weights were retuned: the default Q_dy[2] = 190 pu let the
# encoder quantisation (1.9 rad/s per count at 200 us) drive 5.8 V RMS of u_q (21 % of u_max) through the
# speed-increment term; Q_dy[2] = 68, Q_yw[2] = 40000 pu: 2.7 % (configs/spmsm_002.toml).  Now nominal and
# corner_a pass (hold at 0.997 of the top, RMS error 0.6 % of the top, end 0.2 %, peak 0.73 / 0.77 i_max).
# corner_b (L, R, J -30 %, psi +20 %: its steady-state limit w_fw = 0.81 x top) stops at 1176 rad/s, 0.976-0.977 of
# what the test expects it to reach (0.97 w_fw = 1203), on the voltage circle (|u| = 0.998 u_max) with
# i_d = -9.3 A of the -12.16 A the FW counter asks (u = (-3.2, 27.5) V: the law's voltage is nearly all q).
# Until issue 15 item 6 it also stayed there for 3.1 s after the reference had fallen below it (RMS error
# 8.2 % of the top): the reference governor's speed-task hold (a period with the voltage limiter active,
# 41-98 % of the periods from 10 s) set vd = 0 both ways, so the governed reference crept up to 1330 rad/s
# (155 above the plant) between held periods and, once the target turned, could not come down.  The hold is
# now one-sided (governor.py, rtlmodel/ref_gen.gov_step, rtl/ref_gen.v: held, vd passes only towards lower
# |g|): RMS 8.2 -> 0.6 % of the top (float and fixed), the plant comes down 0.1 s (was 3.1 s) after the
# target passed below it; hold 0.977 / 0.976 of reach, peak 0.68 i_max, end 0.2 % of the top unchanged
# (docs/field_weakening.md).  Open, strict xfail: the hold speed (0.977 < 0.98
# of reach, i.e. 0.948 of w_fw against 0.951 asked): the voltage circle's vector scaling leaves i_d 2.8 A
# short of its reference (the lock mechanism of docs/field_weakening.md, here without a run-away).
FW_XFAIL = {("spmsm_002", "corner_b", fixed): "spmsm_002 corner_b: stops at 0.977 of its reach on the voltage "
            "circle (i_d -9.3 of -12.2 A: the vector scaling leaves i_d short of the FW reference)"
            for fixed in (False, True)}


SPMSM_UQ_RIPPLE = 0.05      # u_q RMS about its mean at a steady speed, x u_max (was 0.21: the FW stop above)


def test_spmsm_002_speed_design_quiet():
    """spmsm_002's algorithm-1 speed design: the sensor quantisation drives at most 5 % of u_max, in the
    linear noise model (robust.noise_rms: 0.026, was 0.205) and in a 0.3 s hold at 400 and 1000 rad/s
    (float and fixed, the second half: 1.9-2.8 %, was 15-24 %)."""
    from empc.reference import steps_and_ramps
    cfg = load("spmsm_002")
    g = robust.exact_gains(cfg, 1, "speed")(0.0)
    assert robust.noise_rms(cfg, 1, "speed", g)["u_rms"] <= SPMSM_UQ_RIPPLE * cfg.u_max
    c = cfg.with_control(algorithm=1, task="speed")
    for w in (400.0, 1000.0):
        sc = cl.Scenario("hold", "speed", 0.3, steps_and_ramps([(0.0, w, "step")]), x0=(0.0, 0.0, w, 0.0))
        for ctl in (ExplicitMPC(c, gains="poly"), FixedMPC(c)):
            tr = cl.simulate(c, ctl, sc)
            half = tr.t >= 0.15
            rip = float(np.std(tr.u_q[half]) / cfg.u_max)
            assert rip <= SPMSM_UQ_RIPPLE, (w, type(ctl).__name__, rip)
            # the start (i_q = 0 against friction) costs 26 rad/s that the heavy rotor recovers in ~0.3 s
            assert abs(np.mean(tr.w_e[half]) - w) <= 0.05 * w, (w, type(ctl).__name__, np.mean(tr.w_e[half]))


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
        request.applymarker(pytest.mark.xfail(reason=why, strict=True))      # flags when fixed
    _fw_check(load(name), name, plant, fixed)


# ------------------------------------------------------------------------------------------------
# The closed loop at 50 us (control.Ts = 50 us, 20 kHz PWM: the variant test_every_design_passes_at_each_ts
# checks), every motor and every design it has: the per-control-period weight tables
# ([weights.<design>.Ts_50us]) pass the linear design check, this runs them.  A speed step (0.12 s of
# speed_steps / speed_alg2: 0 -> 300 k rad/s at 10 ms) or a position step (0.06 s of position_alg1 /
# position_alg2: 0 -> 20 k rad at 10 ms), nominal plant (the full sweep: also the box corners), float and
# fixed, with the bounds:
TS_50US = {"control.Ts": 50e-6, "inverter.f_pwm": corners.TS_PWM}
STEP_50US = corners.TS_STEP
PEAK_50US = corners.LIMIT   # |i| <= 1.05 i_max (the reference governor's limit; test_current_corners too)
OV_50US = 25.0          # overshoot of the step, % (the measured worst that passes: see the table below)
UQ_50US = 0.25          # u_q RMS about its mean over the step's last 30 % (no limit cycle on the voltage limit), x u_max
AGREE_50US = 0.10       # fixed vs float RMS tracking error within 10 % + 1 sensor LSB (as _bounds)
# and the step settles (within max(2 % of the step, the sensor floor) before its segment ends).
# Known failures (strict xfail, so they flag when fixed): the measured numbers (nominal plant, float / fixed)
# and the cause.  Two causes (a third, the reference governor's catch-up, and a fourth and fifth, weights,
# are fixed: see below):
#  * the sensor resolution at 50 us: one encoder count per period is 126 rad/s on the BLWR233D (4000 cpr)
#    and 123 rad/s on the EC 45 flat (its scaled speed step, 120 rad/s, is less than one count); the
#    quantisation drives u_q (docs/design.md: u_rms 95 V against u_max 20.8 V for blwr alg2 speed);
#  * not found in the time (stated as such).
# The reference governor's catch-up shift_position was 4 at every Ts (2^-4 of the error per period): it
# starts braking when the error falls below 2^4 periods of the reference speed, a distance that shrinks
# with Ts while the braking distance does not, so at 50 us the governed position reference itself
# overshot (premo alg1 / alg2 position 82 / 88 %, EC 45 flat alg1 75 %, BLWR233D alg2 5.5 %).  Its
# default now follows Ts (governor.default_shift_position: Ts x 2^ksh >= 4 ms, 7 at 50 us): the premo and
# EC 45 flat algorithm-1 position steps pass (0 / 0.1 %, settled in 27 / 29 ms).
# A fourth cause, fixed: the ipmsm_001 and spmsm_002 algorithm-1 position designs had the default per-unit
# weights, whose position loop follows 1 / T_m (T_m 115 ms / 3.1 s, 22 / 600 x the BLWR233D's): a static
# stiffness of 0.21 / 0.020 A of i_q per electrical rad at 50 us, i.e. 0.25 / 0.0008 A for the scaled
# 1.19 / 0.04 rad step (final error 80 / 100 % after 50 ms; no quantisation: float and fixed alike, and
# spmsm_002 does not move in 50 ms without its Coulomb friction either; with it, 0.149 A, the rotor stuck
# anywhere within 7.6 rad).  Their configurations now carry `empc tune` weights (ipmsm_001 task weight x16
# at every Ts; spmsm_002 x90 = 2^6.5, and at 50 us x181 = 2^7.5 with Q_du x4): 53 / 507 A/rad, settled in
# 28 / 37 ms, peak 0.36 / 0.24 i_max (nominal; corners 30-36 / 37-38 ms).
# The fifth, fixed: premo_320v alg2 position's Ts_50us table let the encoder quantisation drive u_rms =
# 0.35 u_max (robust.noise_rms), the u_q RMS measured in its step's tail (0.36 / 0.35 u_max); with Q_du x4 and
# Q_yw[i_q] x32 (from `empc tune --refine --u-chatter 0.2`): 0.13 linear, 0.12 / 0.11 in the tail, overshoot
# 5.2 %, settled in 48 ms (configs/premo_320v.toml).
KNOWN_50US: dict = {}
# ec45flat_24v alg2 position (the rotor crept: final error 65-67 % of the 8 rad step after 50 ms, u_q tail RMS
# 0.51-0.55 u_max; first blamed on the sensor resolution, 123 rad/s per count, but the same at 128000 cpr and at any
# speed window: its Ts_50us table was a slow loop, a 1.35 Hz mode, radius 0.99969, 0.11 A for a 0.1 pu step in
# the linear loop) passes since that table is the algorithm-1 Ts_50us table as the proportional part (Q_yp[2] =
# its Q_yw[2]) with a weak position integrator Q_yw[2] = 10 (issue 16, configs/ec45flat_24v.toml): radius 0.99955,
# damping 0.251; settled in 28.9 / 31.0 / 27.1 ms nominal / corner_a / corner_b, overshoot <= 2.0 %, peak <= 0.76
# i_max, u_q tail RMS <= 0.12 u_max (float and fixed alike).
# ipmsm_001 alg2 speed at corner_a (peak 1.033 / 1.096 i_max) passes since the speed integral's anti-windup
# (issue 15, docs/design.md): 0.994 / 0.842, overshoot 15.2 / 8.3 %.
# ec45flat_24v alg1 position at corner_a (peak 1.037 / 1.077 i_max, u_q RMS 0.34 / 0.35 u_max in the tail) passes
# since its own Ts_50us table (issue 15, docs/design.md): peaks 0.46 / 0.30 / 0.70 i_max nominal / corner_a / corner_b,
# u_q tail RMS <= 0.11 u_max, overshoot <= 2.1 %, settled in 29-33 ms.
# blwr233d alg1 speed (overshoot 42.6 / 42.6 %, linear 42.6 %: the weights, not the sensor resolution: 42.3 % with
# 128000 cpr and at any speed window) passes since its own Ts_50us table (`empc tune`, configs/blwr233d.toml):
# overshoot 0.0 / 2.4 / 0.0 % nominal / corner_a / corner_b, but slow: settled in 69 / 59 / 83 ms.
# premo_320v alg2 speed (overshoot 41 / 41 %, u_q tail RMS 0.54 / 0.53 u_max: linear u chatter 0.72 u_max) passes
# since its Ts_50us table was retuned (`empc tune --refine --u-chatter 0.2 --overshoot 20`, configs/premo_320v.toml):
# overshoot 10.2 / 8.0 % (float / fixed, the same at both corners), u_q tail RMS <= 0.07 u_max, settled in 55-66 ms.
# ec45flat_24v alg2 speed (overshoot 30.7 / 30.7 %, linear 29.6 %: the weights, not the resolution) passes since
# its Ts_50us table's Q_yw[2] x0.5 (the same `empc tune`): overshoot 13.7 / 13.5 % (corners <= 14.6 %), u_q tail
# RMS <= 0.07 u_max.
# at the box corners (full sweep): the same designs fail there (blwr alg1 speed did: overshoot 28 / 55 %), and
# ec45flat_24v alg1 speed at corner_a (the sensor resolution: the step is one count; u_q RMS 0.49 / 0.50 u_max in the
# tail, final error 26 %) passes since its Ts_50us table's speed_window = 4 (configs/ec45flat_24v.toml): u_q tail
# RMS <= 0.056 u_max at the three plants, final error <= 3.0 %.
KNOWN_50US_CORNERS: dict = {}


def _designs_50us(plants=(None,), only_task=None):
    out = []
    for name in MOTORS:
        for key in sorted(load(name, **TS_50US).control.weights):
            if only_task and key[1] != only_task:
                continue
            d = f"alg{key[0]}.{key[1]}"
            for plant in plants:
                why = KNOWN_50US.get((name, d)) or (KNOWN_50US_CORNERS.get((name, d, plant)) if plant else None)
                marks = [pytest.mark.xfail(reason=why, strict=True)] if why else []
                args = (name, key) if plant is None else (name, key, plant)
                out.append(pytest.param(*args, id="-".join(x for x in (name, d, plant) if x), marks=marks))
    return out


def _step_50us(cfg, key, plant, fixed):
    scen, dur = STEP_50US[key]
    sc, tr, m = _run(cfg, scen, plant, fixed=fixed, duration=dur)
    assert len(sc.segments) == 1 and sc.segments[0][0] == "step", sc.segments
    _, t0, t1, v0, v1 = sc.segments[0]
    seg = m["segments"][0]
    tail = (tr.t >= t0 + 0.7 * (t1 - t0)) & (tr.t < t1 - cfg.control.N * cfg.control.Ts)
    step = abs(v1 - v0)
    # the governor's reference profile reaches the target within 60 % of the segment (else the step is
    # governor-limited: a heavy motor's scaled step, and it only has to move at least half way)
    reach = _governed_reach(cfg, sc.task, 0.6 * (t1 - t0 - cfg.control.N * cfg.control.Ts))
    fig = {"peak/i_max": float(np.max(tr.i_phase_peak) / cfg.control.i_max), "overshoot_pct": seg["overshoot_pct"],
           "settling_time": seg["settling_time"], "final_error/step": seg["final_error"] / step,
           "governed": reach < step, "reach/step": min(reach, 1e9) / step,
           "u_q_tail_rms/u_max": float(np.std(tr.u_q[tail]) / cfg.u_max), "rms_error": m["rms_error"]}
    return sc, tr, fig


def _check_50us(name, key, plant, extra=None):
    cfg = load(name, **TS_50US, **(extra or {}))
    assert cfg.control.Ts == 50e-6 and cfg.pwm_per_control == 1
    res = cfg.rad_per_count if key[1] == "position" else cfg.rad_s_per_count_ts
    figs = {}
    for fixed in (False, True):
        _, tr, fig = _step_50us(cfg, key, plant, fixed)
        figs["fixed" if fixed else "float"] = fig
        print(name, key, plant, "fixed" if fixed else "float", {k: (round(float(v), 4) if v is not None else None)
                                                               for k, v in fig.items()})
    for what, fig in figs.items():
        assert np.isfinite(fig["rms_error"]), (name, key, what, fig)
        assert fig["peak/i_max"] <= PEAK_50US, (name, key, what, fig)
        assert fig["overshoot_pct"] <= OV_50US, (name, key, what, fig)
        if not fig["governed"]:
            assert fig["settling_time"] is not None, (name, key, what, fig)        # settles in the segment
        else:                                                                      # moved at least half way
            assert fig["final_error/step"] <= 1.0 - 0.5 * fig["reach/step"], (name, key, what, fig)
        assert fig["u_q_tail_rms/u_max"] <= UQ_50US, (name, key, what, fig)        # no limit cycle
    f, x = figs["float"]["rms_error"], figs["fixed"]["rms_error"]
    assert abs(f - x) <= AGREE_50US * f + res, (name, key, f, x)


@pytest.mark.parametrize("name,key", _designs_50us())
def test_closed_loop_at_50us_nominal(name, key):
    _check_50us(name, key, "nominal")


@pytest.mark.full
@pytest.mark.parametrize("name,key,plant", _designs_50us(plants=("corner_a", "corner_b")))
def test_closed_loop_at_50us_box_corners(name, key, plant):
    _check_50us(name, key, plant)


# The speed window (the speed estimate over M control periods, estimator.py; the RTL: KACC.win, rtl/mx_seq.v),
# per design: configs/blwr233d.toml's Ts_50us tables set speed_window = 8 for three designs (126 rad/s per
# count at 50 us).  The window takes the quantisation chatter of the position designs under the step's bound
# (u_q tail RMS 0.47 / 0.37 u_max at M = 1 -> 0.16 / 0.12 at M = 8), and the algorithm-2 speed table is tuned
# for it (radius 0.99868, damping 0.331).  test_closed_loop_at_50us_nominal runs them as bundled; this test
# checks that the window is what makes them pass: the same designs at M = 1 fail the step's bounds.
# Algorithm 1 speed overshot 42 % at any M with the 250-us weights (not the resolution; now its own Ts_50us table,
# M = 1).  flow/speed_window.py writes
# the sweep (build/reports/speed_window_50us.json).
WINDOW_50US = [("blwr233d", (1, "position"), 8), ("blwr233d", (2, "position"), 8), ("blwr233d", (2, "speed"), 8)]


@pytest.mark.parametrize("name,key,M", WINDOW_50US, ids=[f"{n}-alg{k[0]}.{k[1]}-M{m}" for n, k, m in WINDOW_50US])
def test_closed_loop_at_50us_speed_window(name, key, M):
    cfg = load(name, **TS_50US)
    assert cfg.control.window_of(*key) == M and cfg.for_design(*key).control.speed_window == M
    assert design.design(cfg, *key)["stability"]["passed"]
    one = cfg.with_control(speed_window=1)
    _, _, fig = _step_50us(one, key, "nominal", fixed=True)
    print(name, key, "M = 1", {k: (round(float(v), 4) if v is not None else None) for k, v in fig.items()})
    bad = (fig["u_q_tail_rms/u_max"] > UQ_50US or fig["overshoot_pct"] > OV_50US
           or (not fig["governed"] and fig["settling_time"] is None))
    assert bad, (name, key, "passes at M = 1 too: the design table's speed_window is not needed", fig)
