"""`empc tune`: the chosen weights meet the specifications, the binding one is named, the printed
tables are a valid configuration whose design passes the check."""
import copy
import tomllib

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
