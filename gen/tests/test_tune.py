"""`empc tune`: the chosen weights meet the specifications, the binding one is named, the printed
tables are a valid configuration whose design passes the check."""
import copy
import dataclasses
import tomllib

import pytest

from empc import config, design, mpc, robust, tune

CFG = config.default()


def test_tune_small_grid_meets_specs_and_names_the_binding_one():
    specs = tune.Specs(overshoot=20.0, chatter=0.2)
    r = tune.tune(CFG, 1, "position", specs, a_grid=[0.5, 1.0, 4.0], b_grid=[1.0, 4.0])
    assert r.tried == 6
    assert r.passed and r.chosen is not None, r.binding
    m = r.chosen.m
    assert m["robust_ok"] and m["overshoot"] <= 20.0 and m["chatter_pu"] <= 0.2 and m["current"] <= CFG.control.i_max
    assert r.binding and ("stops" in r.binding or r.binding.startswith("none")), r.binding
    text = r.explain()
    assert "Binding:" in text and "settling" in text
    # the printed tables are valid configuration text; the design with them passes the full check
    d = tomllib.loads(config.DEFAULT_CONFIG.read_text())
    t = tomllib.loads(tune.toml_tables([r]))
    d = copy.deepcopy(d)
    d["weights"] = {"units": "pu", "alg1": {"position": t["weights"]["alg1"]["position"]}}
    d["control"]["algorithm"], d["control"]["task"] = 1, "position"
    cfg = config.from_dict(d)
    assert design.design(cfg, 1, "position")["stability"]["passed"]


def test_tune_reports_infeasible_specifications():
    r = tune.tune(CFG, 1, "speed", tune.Specs(settling=1e-4), a_grid=[1.0], b_grid=[1.0])
    assert not r.passed and "settling" in r.binding, r.binding


@pytest.mark.cost(24)          # seconds on an idle core (43 before the pruned refine, x0.54): started with the long tests
def test_refine_finds_control_period_weights_at_50_us():
    """The weights tuned at 250 us fail the check at 50 us (algorithm 2 speed: radius 1.155, a 3.7 kHz
    current mode); `empc tune --refine` finds per-element factors and the proportional weight Q_yp that
    pass, and --ts-table prints them as a [weights.alg2.speed.Ts_50us] table that the configuration
    selects at 50 us and whose design passes the full check."""
    d = tomllib.loads(config.DEFAULT_CONFIG.read_text())
    for alg in d["weights"].values():               # the bundled Ts_50us tables out: start from 250 us
        if isinstance(alg, dict):
            for t in alg.values():
                for name in [k for k in t if k.startswith("Ts_")]:
                    t.pop(name)
    d50 = copy.deepcopy(d)
    d50["control"]["Ts"] = 50e-6
    cfg = config.from_dict(d50)
    assert not design.design(cfg, 2, "speed", force=True)["stability"]["passed"]
    r = tune.refine(cfg, 2, "speed", tune.Specs(chatter=0.5))
    assert r.passed and r.chosen.m["robust_ok"], r.binding
    assert r.chosen.weights_pu.Q_yp[2] > 0 and "refinement" in r.binding
    t = tomllib.loads(tune.toml_tables([r], ts=50e-6))
    table = t["weights"]["alg2"]["speed"]["Ts_50us"]
    d2 = copy.deepcopy(d)
    d2["weights"]["alg2"]["speed"]["Ts_50us"] = table
    c50 = config.from_dict({**d2, "control": {**d2["control"], "Ts": 50e-6}})
    assert c50.control.weight_tables[(2, "speed")] == "weights.alg2.speed.Ts_50us"
    assert design.design(c50, 2, "speed")["stability"]["passed"]
    c250 = config.from_dict(d2)                      # at 250 us the table is not used
    assert c250.control.weights == config.default().control.weights


@pytest.mark.parametrize("alg,task,ts,factors", [
    (2, "speed", 50e-6, {}),                                   # fails the check (radius 1.155 at 0 rad/s)
    (2, "speed", 50e-6, {"Q_du": 4.0, "Q_yp2": 5.0 * 6233.0}),
    (1, "position", 250e-6, {}),                               # passes
    (1, "position", 250e-6, {"Q_yw2": 2.0, "Q_du": 0.5}),
])
def test_refine_prunes_only_what_the_check_would_refuse(alg, task, ts, factors):
    """`refine` skips the full design of a candidate whose score floor cannot beat the best so far
    (tune._score_floor: the exact gains at the check's end, middle and zero speeds).  The floor must
    never exceed the check's own violation, or the search would walk differently with the pruning;
    at 50 us the search takes the same 141 steps to the same weights as with every candidate
    designed (measured: 58 designs instead of 141)."""
    d = tomllib.loads(config.DEFAULT_CONFIG.read_text())
    d["control"]["Ts"] = ts
    for a in d["weights"].values():
        if isinstance(a, dict):
            for t in a.values():
                for name in [k for k in t if k.startswith("Ts_")]:
                    t.pop(name)
    cfg = config.from_dict(d)
    wpu = tune.refined(cfg.weights_pu(alg, task), factors)
    c2 = cfg.with_control(weights={**cfg.control.weights, (alg, task): config.weights_si(wpu, cfg.bases(task))})
    st = design.design(c2, alg, task, force=True)["stability"]
    full = tune._violation(cfg, st["worst_radius"]["value"], st["worst_damping"]["value"], st["radius_bound"])
    floor = tune._score_floor(c2, alg, task)
    assert floor <= full, (floor, full, st["reason"])
    assert full - floor < 1e-3, (floor, full)      # informative: measured within 1e-6 on these four
    sc, cand = tune._refine_score(cfg, alg, task, wpu, tune.Specs(chatter=0.5), beat=floor)
    assert cand.fails[0].startswith("pruned") and sc >= floor
    sc_full, cand_full = tune._refine_score(cfg, alg, task, wpu, tune.Specs(chatter=0.5))
    assert sc_full >= sc and (sc_full < 0) == (cand_full.m["robust_ok"] and not cand_full.fails)


def test_chatter_is_the_worst_over_the_box():
    """`empc tune`'s chatter specification is the RMS i_q the sensor quantisation drives at the worst point of the
    robustness box (robust.noise_box), not on the nominal plant: the EC 45 flat's former algorithm-2 speed table
    had 0.23 i_max nominal, 0.48 at L, R, J -30 %, psi +20 % (load_speed at corner_b 1.54 i_max); the retuned one
    stays within the default 0.2 pu of the rated current at every box point (docs/design.md)."""
    cfg = config.load(config.DEFAULT_CONFIG.parent / "ec45flat_24v.toml")
    old = config.Weights(Q_yw=(416.6, 8.264, 219400.0), Q_dy=(0.2303, 9.447, 8534.0), Q_du=(4694.0, 4743.0),
                         ebar_step_max=(0.0, 0.0, 0.05776), integrate=(False, False, True))
    g = mpc.gains(cfg.motor, cfg.control, 0.0, 2, "speed", weights=config.weights_si(old, cfg.bases("speed")))
    nb = robust.noise_box(cfg, 2, "speed", g)
    assert nb["i_q_rms_nominal"] == pytest.approx(robust.noise_rms(cfg, 2, "speed", g)["i_q_rms"])
    assert nb["i_q_rms"] > 2.0 * nb["i_q_rms_nominal"]
    assert (nb["i_q_point"]["L"], nb["i_q_point"]["R"]) == (0.7, 0.7)
    assert nb["i_q_rms"] / cfg.ratings.current > 0.2
    w_si = cfg.control.weights_for(2, "speed")
    m = tune.measure(cfg, 2, "speed", w_si, tune.Specs(), robust_grid=3)
    assert m["chatter_nominal_pu"] <= m["chatter_pu"] <= 0.2, m
    assert not [f for f in tune._fails(cfg, 2, m, tune.Specs()) if f.startswith("quantisation")]
    m_old = tune.measure(cfg, 2, "speed", config.weights_si(old, cfg.bases("speed")), tune.Specs(), robust_grid=3)
    assert any(f.startswith("quantisation chatter") and "at L -30 %" in f
               for f in tune._fails(cfg, 2, m_old, tune.Specs())), m_old


def test_tune_table_carries_the_design_speed_window():
    """A design tuned with its own speed window (Control.window_of) gets a table that says so: pasted into the
    configuration, the design runs with the window its weights were tuned for."""
    cfg = CFG.with_control(speed_window=4)
    r = tune.tune(cfg, 1, "position", tune.Specs(), a_grid=[1.0], b_grid=[1.0])
    assert r.speed_window == 4 and tune.tune(CFG, 1, "position", tune.Specs(), a_grid=[1.0], b_grid=[1.0]).speed_window == 1
    r = dataclasses.replace(r, chosen=tune.Candidate(1.0, 1.0, cfg.weights_pu(1, "position")))
    t = tomllib.loads(tune.toml_tables([r], ts=50e-6))["weights"]["alg1"]["position"]["Ts_50us"]
    assert t["speed_window"] == 4
    d = tomllib.loads(config.DEFAULT_CONFIG.read_text())
    d["weights"]["alg1"]["position"]["Ts_50us"] = t
    c50 = config.from_dict({**d, "control": {**d["control"], "Ts": 50e-6}})
    assert c50.control.window_of(1, "position") == 4 and c50.control.window_of(1, "speed") == 1
