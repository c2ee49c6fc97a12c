"""Closed-loop scenarios reproducing paper 000's experiments on the BLWR233D (sec. VI).

- speed_steps:  speed steps with algorithm 1 (Fig. 5: zero-symmetric speed error).
- position_alg1 / position_alg2: position steps and ramps (Figs. 6 and 7):
  algorithm 1 keeps a constant lag on ramps, algorithm 2's ramp error goes to ~0.
- load_step: position hold with algorithm 2 under a load-torque step (offset-free).
- speed_alg2: speed steps and a ramp with algorithm 2.
Issue 15 (off the paper's path; BLWR233D: i_max = 10 A, no-load base speed u_max / psi = 1039 rad/s):
- speed_limit: 150 -> 900 -> 150 rad/s steps, algorithm 1: the current limit (reference governor).
- position_large: 200 rad position step and back, algorithm 2: the current and speed limit.
- load_speed: speed hold at 300 rad/s, a rated-torque load (0.227 N m, 1.9 A) from 0.1 to 0.25 s,
  algorithm 2: the speed estimate offset-free under load.
- field_weakening: speed ramp 0 -> 1400 rad/s (1.35 x base speed) and back under the rated load,
  algorithm 1: field weakening (i_d < 0) within |i| <= i_max.
Angles and speeds are electrical (rad, rad/s); the motor has p = 4 pole pairs.
"""
from __future__ import annotations

from .closedloop import Scenario
from .reference import steps_and_ramps


# Breakpoints (t, value, kind) of each profile (reference.steps_and_ramps); the RTL co-simulation
# turns the same list into reference-generator segments (rtlmodel/ref_gen.segments_from_points).
POINTS = {
    "speed_steps": [(0.01, 300.0, "step"), (0.11, 600.0, "step"), (0.21, -300.0, "step"), (0.31, 0.0, "step")],
    "position_alg1": [(0.01, 20.0, "step"), (0.06, 20.0, "step"), (0.26, 120.0, "ramp"), (0.36, 120.0, "step"),
                      (0.56, 20.0, "ramp"), (0.60, 0.0, "step")],
    "load_step": [(0.01, 10.0, "step")],
    "speed_alg2": [(0.01, 300.0, "step"), (0.11, 600.0, "step"), (0.21, 600.0, "step"), (0.31, 100.0, "ramp")],
    "speed_limit": [(0.01, 150.0, "step"), (0.11, 900.0, "step"), (0.21, 150.0, "step")],
    "position_large": [(0.01, 200.0, "step"), (0.36, 0.0, "step")],
    "load_speed": [(0.01, 300.0, "step")],
    "field_weakening": [(0.02, 0.0, "step"), (0.22, 1400.0, "ramp"), (0.32, 1400.0, "step"), (0.52, 0.0, "ramp")],
}
RATED_LOAD = 0.227      # N m: the BLWR233D's 95 W at 4000 rpm
POINTS["position_alg2"] = POINTS["position_alg1"]


def _speed_steps() -> Scenario:
    pts = POINTS["speed_steps"]
    segs = [("step", 0.01, 0.11, 0.0, 300.0), ("step", 0.11, 0.21, 300.0, 600.0),
            ("step", 0.21, 0.31, 600.0, -300.0), ("step", 0.31, 0.40, -300.0, 0.0)]
    return Scenario("speed_steps", "speed", 0.40, steps_and_ramps(pts), segments=segs,
                    description="speed steps 0 -> 300 -> 600 -> -300 -> 0 rad/s (electrical), algorithm 1")


def _position(alg: int) -> Scenario:
    pts = POINTS[f"position_alg{alg}"]
    segs = [("step", 0.01, 0.06, 0.0, 20.0), ("ramp", 0.06, 0.26, 20.0, 120.0), ("step", 0.26, 0.36, 120.0, 120.0),
            ("ramp", 0.36, 0.56, 120.0, 20.0), ("step", 0.60, 0.70, 20.0, 0.0)]
    return Scenario(f"position_alg{alg}", "position", 0.70, steps_and_ramps(pts), segments=segs,
                    description=f"position step 20 rad, ramps 20 -> 120 -> 20 rad at 500 rad/s, step to 0 "
                                f"(electrical), algorithm {alg}")


def _load_step() -> Scenario:
    pts = POINTS["load_step"]
    segs = [("step", 0.01, 0.10, 0.0, 10.0), ("step", 0.10, 0.30, 10.0, 10.0)]
    return Scenario("load_step", "position", 0.30, steps_and_ramps(pts), segments=segs,
                    load=lambda t: 0.05 if t >= 0.10 else 0.0,
                    description="position step to 10 rad, then a 0.05 N m load-torque step at 0.1 s, algorithm 2")


def _speed_alg2() -> Scenario:
    pts = POINTS["speed_alg2"]
    segs = [("step", 0.01, 0.11, 0.0, 300.0), ("step", 0.11, 0.21, 300.0, 600.0), ("ramp", 0.21, 0.31, 600.0, 100.0)]
    return Scenario("speed_alg2", "speed", 0.40, steps_and_ramps(pts), segments=segs,
                    description="speed steps 0 -> 300 -> 600 rad/s and a ramp to 100 rad/s, algorithm 2")


def _speed_limit() -> Scenario:
    segs = [("step", 0.01, 0.11, 0.0, 150.0), ("step", 0.11, 0.21, 150.0, 900.0), ("step", 0.21, 0.30, 900.0, 150.0)]
    return Scenario("speed_limit", "speed", 0.30, steps_and_ramps(POINTS["speed_limit"]), segments=segs,
                    description="speed steps 150 -> 900 -> 150 rad/s, algorithm 1 (current limit)")


def _position_large() -> Scenario:
    segs = [("step", 0.01, 0.36, 0.0, 200.0), ("step", 0.36, 0.72, 200.0, 0.0)]
    return Scenario("position_large", "position", 0.72, steps_and_ramps(POINTS["position_large"]), segments=segs,
                    description="position step 0 -> 200 -> 0 rad (50 turns of the rotor), algorithm 2 (current limit)")


def _load_speed() -> Scenario:
    segs = [("step", 0.01, 0.10, 0.0, 300.0), ("step", 0.10, 0.25, 300.0, 300.0), ("step", 0.25, 0.35, 300.0, 300.0)]
    return Scenario("load_speed", "speed", 0.35, steps_and_ramps(POINTS["load_speed"]), segments=segs,
                    load=lambda t: RATED_LOAD if 0.10 <= t < 0.25 else 0.0,
                    description="speed hold 300 rad/s, rated load 0.227 N m from 0.1 to 0.25 s, algorithm 2")


def _field_weakening() -> Scenario:
    segs = [("ramp", 0.02, 0.22, 0.0, 1400.0), ("step", 0.22, 0.32, 1400.0, 1400.0), ("ramp", 0.32, 0.52, 1400.0, 0.0)]
    return Scenario("field_weakening", "speed", 0.56, steps_and_ramps(POINTS["field_weakening"]), segments=segs,
                    load=lambda t: RATED_LOAD,
                    description="speed ramp 0 -> 1400 rad/s (1.35 x the no-load base speed) and back under the "
                                "rated load, algorithm 1 (field weakening)")


SCENARIOS = {
    "speed_steps": (_speed_steps, 1),
    "position_alg1": (lambda: _position(1), 1),
    "position_alg2": (lambda: _position(2), 2),
    "load_step": (_load_step, 2),
    "speed_alg2": (_speed_alg2, 2),
    "speed_limit": (_speed_limit, 1),
    "position_large": (_position_large, 2),
    "load_speed": (_load_speed, 2),
    "field_weakening": (_field_weakening, 1),
}


def get(name: str) -> tuple[Scenario, int]:
    try:
        make, alg = SCENARIOS[name]
    except KeyError:
        raise KeyError(f"unknown scenario {name!r}; choose from {', '.join(SCENARIOS)}") from None
    return make(), alg
