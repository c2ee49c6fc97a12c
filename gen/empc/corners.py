"""Peak current of the scenarios with the plant at the robustness-box corners (issue 15: |i| <= 1.05 i_max).

The closed-loop tests and the benchmark ``flow/current_corners.py`` (build/reports/current_corners.json)
run each scenario of a motor's bundled designs with the plant at

  * ``nominal``: the configured motor;
  * ``corner_a``: the box point where the design's loop is least damped (its design check's
    ``worst_damping`` point: a corner or a half-way point of the box of ``robust.box_points``);
  * ``corner_b``: the opposite point (every factor f -> 2 - f).

and report the peak phase current |i| / i_max (the plant's phase currents, sampled twice per PWM
period), where it happened (time, the scenario segment, i_d / i_q at that period) and the trace's
``w_e`` / ``theta_e`` at the end.  ``form``: ``float`` (ExplicitMPC, fitted polynomial gains),
``fixed`` (FixedMPC) or ``bit`` (bitloop: the RTL axis model, slow).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from . import closedloop as cl, config, design, robust, scenarios
from .controllers.explicit import ExplicitMPC
from .controllers.fixed import FixedMPC

PLANTS = ("nominal", "corner_a", "corner_b")
FORMS = ("float", "fixed", "bit")
LIMIT = 1.05                      # |i| <= LIMIT x i_max (issue 15 acceptance)
CONFIGS = config.DEFAULT_CONFIG.parent
MOTORS = ("blwr233d", "ipmsm_001", "spmsm_002", "ec45flat_24v", "premo_320v")


def load(name: str, **ov):
    return config.load(CONFIGS / f"{name}.toml", ov or None)


def plant_factors(cfg, alg: int, task: str, plant: str) -> dict | None:
    """None (nominal) or the factors of ``plant`` (corner_a / corner_b, see the module docstring)."""
    if plant == "nominal":
        return None
    f = design.design(cfg, alg, task)["stability"]["worst_damping"]["factors"]
    if plant == "corner_b":
        f = {k: 2.0 - v for k, v in f.items()}
    elif plant != "corner_a":
        raise ValueError(f"unknown plant {plant!r}; choose from {', '.join(PLANTS)}")
    return f


def scenario_list(cfg) -> list[tuple[str, int, str]]:
    """(scenario, algorithm, task) of every scenario ``cfg`` has a design for."""
    out = []
    for name in scenarios.SCENARIOS:
        sc, alg = scenarios.get(name, cfg)
        if (alg, sc.task) in cfg.control.weights:
            out.append((name, alg, sc.task))
    return out


def shortened(sc: cl.Scenario, duration: float | None) -> cl.Scenario:
    """The scenario cut to ``duration`` s (the segments that end by then), or as it is."""
    if not duration or duration >= sc.duration:
        return sc
    return dataclasses.replace(sc, duration=duration, segments=[s for s in sc.segments if s[2] <= duration + 1e-9])


def simulate(cfg, name: str, plant: str = "nominal", form: str = "float", duration: float | None = None,
             governor: bool = True):
    """One closed-loop run: (scenario, configuration it ran with, trace, plant factors)."""
    sc, alg = scenarios.get(name, cfg)
    sc = shortened(sc, duration)
    c = cfg.with_control(algorithm=alg, task=sc.task)
    if not governor:
        c = c.with_control(governor=dataclasses.replace(c.control.governor, enable=False))
    f = plant_factors(c, alg, sc.task, plant)
    pm = robust.perturbed(c.motor, f) if f else None
    if form == "bit":
        from . import bitloop
        tr = bitloop.simulate(c, sc, plant_motor=pm).trace
    elif form in ("float", "fixed"):
        ctl = FixedMPC(c) if form == "fixed" else ExplicitMPC(c, gains="poly")
        tr = cl.simulate(c, ctl, sc, plant_motor=pm)
    else:
        raise ValueError(f"unknown form {form!r}; choose from {', '.join(FORMS)}")
    return sc, c, tr, f


def peak(cfg, tr: cl.Trace, sc: cl.Scenario) -> dict:
    """Peak |i_phase| / i_max of a trace, where (time, segment, i_d and i_q there, x i_max)."""
    i_max = cfg.control.i_max
    k = int(np.argmax(tr.i_phase_peak))
    t = float(tr.t[k])
    seg = next((i for i, s in enumerate(sc.segments) if s[1] <= t < s[2]), None)
    return {"peak": float(tr.i_phase_peak[k] / i_max), "t": t, "segment": seg,
            "segment_kind": sc.segments[seg][0] if seg is not None else None,
            "i_d": float(tr.i_d[k] / i_max), "i_q": float(tr.i_q[k] / i_max),
            "adc_range": float(tr.i_phase_peak[k] / cfg.adc_range_amps)}


def measure(cfg, name: str, plant: str, form: str = "float", duration: float | None = None,
            governor: bool = True) -> dict:
    sc, c, tr, f = simulate(cfg, name, plant, form, duration, governor)
    out = peak(c, tr, sc)
    out.update({"scenario": name, "plant": plant, "form": form, "duration": sc.duration,
                "factors": f, "algorithm": c.control.algorithm, "task": sc.task})
    return out


# Other control periods: every design at 50 us and at each period the configuration has a table for
# ([weights.<design>.Ts_<us>us], docs/design.md) runs its first step at that Ts with 20 kHz PWM (as
# test_motors.test_closed_loop_at_50us_*): the full scenarios at 50 us cost five times the periods.
TS_STEP = {(1, "speed"): ("speed_steps", 0.12), (2, "speed"): ("speed_alg2", 0.12),
           (1, "position"): ("position_alg1", 0.06), (2, "position"): ("position_alg2", 0.06)}
TS_PWM = 20000.0


def ts_tables(name: str) -> list[tuple[int, str, float]]:
    """(algorithm, task, Ts) of every control-period table in the motor's configuration file."""
    import tomllib
    d = tomllib.loads((CONFIGS / f"{name}.toml").read_text())
    out = []
    for ak, tasks in d.get("weights", {}).items():
        if not (isinstance(tasks, dict) and ak.startswith("alg")):
            continue
        for task, tab in tasks.items():
            for key in (tab if isinstance(tab, dict) else {}):
                ts = config.per_ts_period(key)
                if ts is not None:
                    out.append((int(ak[3:]), task, round(ts, 12)))       # 50e-6, not 50 x 1e-6
    return sorted(out)


EXTRA_TS = (50e-6,)


def other_ts(name: str) -> list[float]:
    """The control periods besides the configured one: EXTRA_TS and those of the tables."""
    own = load(name).control.Ts
    return sorted({round(t, 12) for t in EXTRA_TS} | {t for _, _, t in ts_tables(name)} - {round(own, 12)})


def table_of(cfg, alg: int, task: str) -> str:
    """The weights a design runs with: its control-period table (``Ts_50us``) or ``base``."""
    src = cfg.control.weight_tables.get((alg, task))
    return src.rsplit(".", 1)[-1] if src else "base"


def load_ts(name: str, ts: float):
    return load(name, **{"control.Ts": ts, "inverter.f_pwm": TS_PWM})
