"""`empc tune`: the chosen weights meet the specifications, the binding one is named, the printed
tables are a valid configuration whose design passes the check."""
import copy
import tomllib

import pytest

from empc import config, design, tune

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


@pytest.mark.cost(43)          # seconds on an idle core (clean-clone make sim): started with the long tests
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
