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

from empc import closedloop as cl, config, design, report, robust, scenarios
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


# designs that do not pass at a Ts variant (reported in issue 15's report; design_<motor>.json)
# (every 50 us design quantises since the biased operand shift, SIG_SHIFT_BIAS: the failures left are
# weights tuned at 250 us, with the exact gains as well)
KNOWN = {
    ("blwr233d", 50e-6, (1, "position")): "damping 0.044 < 0.05 (111 Hz, exact gains, -1200 rad/s, L/R/J +30 %, psi -20 %)",
    ("blwr233d", 50e-6, (2, "position")): "radius 1.065 (4444 Hz current mode, exact gains, L/R/J -30 %)",
    ("blwr233d", 50e-6, (2, "speed")): "radius 1.155 (3729 Hz current mode, L/R/J -30 %, psi +20 %, loaded; weights tuned at 250 us)",
    ("premo_320v", 50e-6, (2, "speed")): "radius 1.277 (4055 Hz current mode, L/R/J -30 %, psi +20 %; weights from 250 us)",
    ("premo_320v", 50e-6, (2, "position")): "radius 1.277 (L/R -30 %, J/psi +30/+20 %, loaded, quantised gains; weights searched at 250 us)",
    ("ipmsm_001", 250e-6, (2, "speed")): "radius 1.051 (weights searched at its Ts = 100 us; L +30 %, R/J -30 %, loaded)",
    ("ec45flat_24v", 50e-6, (2, "speed")): "radius 1.259 (4102 Hz current mode, L/R/J -30 %; weights searched at 250 us)",
    ("ec45flat_24v", 50e-6, (2, "position")): "radius 1.217 (L/R/J -30 %, loaded; weights searched at 250 us)",
}


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
        assert last["final_error"] <= 0.5 * step + 4 * res, last      # moved at least half way


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


@pytest.mark.parametrize("name", NEW)
def test_current_within_limit(name):
    cfg = load(name)
    for scen in ("speed_steps", "position_alg1"):
        _, tr, _ = _run(cfg, scen, "nominal", fixed=True, duration=0.12)
        assert np.max(tr.i_phase_peak) <= 1.05 * cfg.control.i_max, (name, scen, np.max(tr.i_phase_peak))
        assert np.max(tr.i_phase_peak) < cfg.adc_range_amps, (name, scen, np.max(tr.i_phase_peak))
