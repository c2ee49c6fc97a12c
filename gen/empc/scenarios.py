"""Closed-loop scenarios reproducing paper 000's experiments on the BLWR233D (sec. VI).

- speed_steps:  speed steps with algorithm 1 (Fig. 5: zero-symmetric speed error).
- position_alg1 / position_alg2: position steps and ramps (Figs. 6 and 7):
  algorithm 1 keeps a constant lag on ramps, algorithm 2's ramp error goes to ~0.
- load_step: position hold with algorithm 2 under a load-torque step (offset-free).
- speed_alg2: speed steps and a ramp with algorithm 2.
- fault_step: a 20 rad position step at 0.5 ms (algorithm 2), the base of the short fault
  co-simulations of issue 14 (not a paper experiment).
Angles and speeds are electrical (rad, rad/s); the motor has p = 4 pole pairs.

For another motor (``get(name, cfg)``) the amplitudes scale with its ratings so that each
scenario asks the same share of its capability: speeds, angles and ramp rates by the
ratio of peak accelerations a = 1.5 p^2 psi i_max / J (capped by the ratio of the speed
ranges max|Omega_e|), load torques by the ratio of peak torques 1.5 p psi i_max, both
against the BLWR233D of the default configuration (factor 1 there); the timing is kept.
"""
from __future__ import annotations

from dataclasses import dataclass

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


@dataclass(frozen=True)
class Scale:
    motion: float = 1.0      # speeds, angles, ramp rates
    torque: float = 1.0      # load torques


def _peak_accel(cfg) -> float:
    m = cfg.motor
    return 1.5 * m.p * m.p * m.psi * cfg.control.i_max / m.J


def _top(cfg) -> float:
    return max(abs(cfg.control.omega_min), abs(cfg.control.omega_max))


def scale_for(cfg) -> Scale:
    """Amplitude factors of the scenarios for ``cfg`` (1, 1 for the default configuration's motor)."""
    if cfg is None:
        return Scale()
    from . import config as config_mod
    ref = config_mod.default()
    k = min(_peak_accel(cfg) / _peak_accel(ref), _top(cfg) / _top(ref))
    tq = (cfg.motor.p * cfg.motor.psi * cfg.control.i_max) / (ref.motor.p * ref.motor.psi * ref.control.i_max)
    return Scale(motion=k, torque=tq)


def _pts(name: str, k: float) -> list:
    return [(t, v * k, kind) for t, v, kind in POINTS[name]]


def _speed_steps(sc: Scale) -> Scenario:
    k = sc.motion
    segs = [("step", 0.01, 0.11, 0.0, 300.0 * k), ("step", 0.11, 0.21, 300.0 * k, 600.0 * k),
            ("step", 0.21, 0.31, 600.0 * k, -300.0 * k), ("step", 0.31, 0.40, -300.0 * k, 0.0)]
    return Scenario("speed_steps", "speed", 0.40, steps_and_ramps(_pts("speed_steps", k)), segments=segs,
                    description=f"speed steps 0 -> {300 * k:.4g} -> {600 * k:.4g} -> {-300 * k:.4g} -> 0 rad/s "
                                f"(electrical), algorithm 1")


def _position(alg: int, sc: Scale) -> Scenario:
    k = sc.motion
    segs = [("step", 0.01, 0.06, 0.0, 20.0 * k), ("ramp", 0.06, 0.26, 20.0 * k, 120.0 * k),
            ("step", 0.26, 0.36, 120.0 * k, 120.0 * k), ("ramp", 0.36, 0.56, 120.0 * k, 20.0 * k),
            ("step", 0.60, 0.70, 20.0 * k, 0.0)]
    return Scenario(f"position_alg{alg}", "position", 0.70, steps_and_ramps(_pts(f"position_alg{alg}", k)),
                    segments=segs,
                    description=f"position step {20 * k:.4g} rad, ramps {20 * k:.4g} -> {120 * k:.4g} -> {20 * k:.4g} "
                                f"rad at {500 * k:.4g} rad/s, step to 0 (electrical), algorithm {alg}")


def _load_step(sc: Scale) -> Scenario:
    k, tq = sc.motion, 0.05 * sc.torque
    segs = [("step", 0.01, 0.10, 0.0, 10.0 * k), ("step", 0.10, 0.30, 10.0 * k, 10.0 * k)]
    return Scenario("load_step", "position", 0.30, steps_and_ramps(_pts("load_step", k)), segments=segs,
                    load=lambda t: tq if t >= 0.10 else 0.0,
                    description=f"position step to {10 * k:.4g} rad, then a {tq:.4g} N m load-torque step at 0.1 s, "
                                f"algorithm 2")


def _speed_alg2(sc: Scale) -> Scenario:
    k = sc.motion
    segs = [("step", 0.01, 0.11, 0.0, 300.0 * k), ("step", 0.11, 0.21, 300.0 * k, 600.0 * k),
            ("ramp", 0.21, 0.31, 600.0 * k, 100.0 * k)]
    return Scenario("speed_alg2", "speed", 0.40, steps_and_ramps(_pts("speed_alg2", k)), segments=segs,
                    description=f"speed steps 0 -> {300 * k:.4g} -> {600 * k:.4g} rad/s and a ramp to {100 * k:.4g} "
                                f"rad/s, algorithm 2")


def _fault_step(sc: Scale) -> Scenario:
    k = sc.motion
    segs = [("step", 0.0005, 0.02, 0.0, 20.0 * k)]
    return Scenario("fault_step", "position", 0.02, steps_and_ramps(_pts("fault_step", k)), segments=segs,
                    description=f"position step {20 * k:.4g} rad at 0.5 ms (electrical), algorithm 2: the short fault "
                                "co-simulations (tb/test_closed_loop.py)")


SCENARIOS = {
    "speed_steps": (_speed_steps, 1),
    "position_alg1": (lambda sc: _position(1, sc), 1),
    "position_alg2": (lambda sc: _position(2, sc), 2),
    "load_step": (_load_step, 2),
    "speed_alg2": (_speed_alg2, 2),
    "fault_step": (_fault_step, 2),
}


def get(name: str, cfg=None) -> tuple[Scenario, int]:
    """Scenario ``name`` and its algorithm; amplitudes scaled for ``cfg`` (default: paper 000's values)."""
    try:
        make, alg = SCENARIOS[name]
    except KeyError:
        raise KeyError(f"unknown scenario {name!r}; choose from {', '.join(SCENARIOS)}") from None
    return make(scale_for(cfg)), alg
