"""Closed-loop scenarios reproducing paper 000's experiments on the BLWR233D (sec. VI).

- speed_steps:  speed steps with algorithm 1 (Fig. 5: zero-symmetric speed error).
- position_alg1 / position_alg2: position steps and ramps (Figs. 6 and 7):
  algorithm 1 keeps a constant lag on ramps, algorithm 2's ramp error goes to ~0.
- load_step: position hold with algorithm 2 under a load-torque step (offset-free).
- speed_alg2: speed steps and a ramp with algorithm 2.
- fault_step: a 20 rad position step at 0.5 ms (algorithm 2), the base of the short fault
  co-simulations of issue 14 (not a paper experiment).
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
}
POINTS["position_alg2"] = POINTS["position_alg1"]
POINTS["fault_step"] = [(0.0005, 20.0, "step")]


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


def _fault_step() -> Scenario:
    segs = [("step", 0.0005, 0.02, 0.0, 20.0)]
    return Scenario("fault_step", "position", 0.02, steps_and_ramps(POINTS["fault_step"]), segments=segs,
                    description="position step 20 rad at 0.5 ms (electrical), algorithm 2: the short fault "
                                "co-simulations (tb/test_closed_loop.py)")


def _speed_alg2() -> Scenario:
    pts = POINTS["speed_alg2"]
    segs = [("step", 0.01, 0.11, 0.0, 300.0), ("step", 0.11, 0.21, 300.0, 600.0), ("ramp", 0.21, 0.31, 600.0, 100.0)]
    return Scenario("speed_alg2", "speed", 0.40, steps_and_ramps(pts), segments=segs,
                    description="speed steps 0 -> 300 -> 600 rad/s and a ramp to 100 rad/s, algorithm 2")


SCENARIOS = {
    "speed_steps": (_speed_steps, 1),
    "position_alg1": (lambda: _position(1), 1),
    "position_alg2": (lambda: _position(2), 2),
    "load_step": (_load_step, 2),
    "speed_alg2": (_speed_alg2, 2),
    "fault_step": (_fault_step, 2),
}


def get(name: str) -> tuple[Scenario, int]:
    try:
        make, alg = SCENARIOS[name]
    except KeyError:
        raise KeyError(f"unknown scenario {name!r}; choose from {', '.join(SCENARIOS)}") from None
    return make(), alg
