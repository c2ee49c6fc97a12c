"""Closed-loop scenarios reproducing paper 000's experiments on the BLWR233D (sec. VI).

- speed_steps:  speed steps with algorithm 1 (Fig. 5: zero-symmetric speed error).
- position_alg1 / position_alg2: position steps and ramps (Figs. 6 and 7):
  algorithm 1 keeps a constant lag on ramps, algorithm 2's ramp error goes to ~0.
- load_step: position hold with algorithm 2 under a load-torque step (offset-free).
- speed_alg2: speed steps and a ramp with algorithm 2.
- fault_step: a 20 rad position step at 0.5 ms (algorithm 2), the base of the short fault
  co-simulations of issue 14 (not a paper experiment).
Issue 15 (off the paper's path; BLWR233D: i_max = 10 A, no-load base speed u_max / psi = 1039 rad/s):
- speed_limit: 150 -> 900 -> 150 rad/s steps, algorithm 1: the current limit (reference governor).
- position_large: 200 rad position step and back, algorithm 2: the current and speed limit.
- load_speed: speed hold at 300 rad/s, a rated-current load (1.5 p psi I_rated: 0.6 N m, 5 A on the
  BLWR233D) from 0.1 to 0.25 s, algorithm 2: the speed estimate offset-free under load.
- field_weakening: speed ramp 0 -> 1400 rad/s (1.35 x base speed) and back under 0.227 N m (the
  BLWR233D's 95 W at 4000 rpm), algorithm 1: field weakening (i_d < 0) within |i| <= i_max.
Angles and speeds are electrical (rad, rad/s); the motor has p = 4 pole pairs.

For another motor (``get(name, cfg)``) the amplitudes scale with its ratings so that each
scenario asks the same share of its capability: speeds, angles and ramp rates by the
ratio of peak accelerations a = 1.5 p^2 psi i_max / J (capped by the ratio of the speed
ranges max|Omega_e|), load torques by the ratio of peak torques 1.5 p psi i_max, both
against the BLWR233D of the default configuration (factor 1 there); the timing is kept.
Two exceptions: field_weakening's top speed scales with the no-load base speed u_max / psi
(it is about the voltage limit), load_speed's load is the motor's own rated-current torque
1.5 p psi I_rated (``[ratings] current``).
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
    "speed_limit": [(0.01, 150.0, "step"), (0.11, 900.0, "step"), (0.21, 150.0, "step")],
    "position_large": [(0.01, 200.0, "step"), (0.46, 0.0, "step")],
    "load_speed": [(0.01, 300.0, "step")],
    "field_weakening": [(0.02, 0.0, "step"), (0.22, 1400.0, "ramp"), (0.32, 1400.0, "step"), (0.52, 0.0, "ramp")],
}
FW_LOAD = 0.227         # N m: the BLWR233D's 95 W at 4000 rpm (field_weakening; scaled as load torques)
POINTS["position_alg2"] = POINTS["position_alg1"]
POINTS["fault_step"] = [(0.0005, 20.0, "step")]


@dataclass(frozen=True)
class Scale:
    motion: float = 1.0      # speeds, angles, ramp rates
    torque: float = 1.0      # load torques
    base: float = 1.0        # no-load base speed u_max / psi (field_weakening)
    rated_load: float = 0.0  # N m: rated-current torque 1.5 p psi I_rated (load_speed)


def _peak_accel(cfg) -> float:
    m = cfg.motor
    return 1.5 * m.p * m.p * m.psi * cfg.control.i_max / m.J


def _top(cfg) -> float:
    return max(abs(cfg.control.omega_min), abs(cfg.control.omega_max))


def rated_torque(cfg) -> float:
    """Torque of the rated current, N m: 1.5 p psi I_rated (config.Ratings.current)."""
    return 1.5 * cfg.motor.p * cfg.motor.psi * cfg.ratings.current


def scale_for(cfg) -> Scale:
    """Amplitude factors of the scenarios for ``cfg`` (1, 1, 1 for the default configuration's motor;
    ``cfg`` None: the default configuration)."""
    from . import config as config_mod
    ref = config_mod.default()
    cfg = cfg or ref
    k = min(_peak_accel(cfg) / _peak_accel(ref), _top(cfg) / _top(ref))
    tq = (cfg.motor.p * cfg.motor.psi * cfg.control.i_max) / (ref.motor.p * ref.motor.psi * ref.control.i_max)
    base = (cfg.u_max / cfg.motor.psi) / (ref.u_max / ref.motor.psi)
    return Scale(motion=k, torque=tq, base=base, rated_load=rated_torque(cfg))


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


def _speed_limit(sc: Scale) -> Scenario:
    k = sc.motion
    segs = [("step", 0.01, 0.11, 0.0, 150.0 * k), ("step", 0.11, 0.21, 150.0 * k, 900.0 * k),
            ("step", 0.21, 0.30, 900.0 * k, 150.0 * k)]
    return Scenario("speed_limit", "speed", 0.30, steps_and_ramps(_pts("speed_limit", k)), segments=segs,
                    description=f"speed steps {150 * k:.4g} -> {900 * k:.4g} -> {150 * k:.4g} rad/s, algorithm 1 "
                                f"(current limit)")


def _position_large(sc: Scale) -> Scenario:
    k = sc.motion
    segs = [("step", 0.01, 0.46, 0.0, 200.0 * k), ("step", 0.46, 0.91, 200.0 * k, 0.0)]
    return Scenario("position_large", "position", 0.91, steps_and_ramps(_pts("position_large", k)), segments=segs,
                    description=f"position step 0 -> {200 * k:.4g} -> 0 rad, algorithm 2 (current limit)")


def _load_speed(sc: Scale) -> Scenario:
    k, tq = sc.motion, sc.rated_load
    segs = [("step", 0.01, 0.10, 0.0, 300.0 * k), ("step", 0.10, 0.25, 300.0 * k, 300.0 * k),
            ("step", 0.25, 0.35, 300.0 * k, 300.0 * k)]
    return Scenario("load_speed", "speed", 0.35, steps_and_ramps(_pts("load_speed", k)), segments=segs,
                    load=lambda t: tq if 0.10 <= t < 0.25 else 0.0,
                    description=f"speed hold {300 * k:.4g} rad/s, rated-current load {tq:.4g} N m from 0.1 to "
                                f"0.25 s, algorithm 2")


def _field_weakening(sc: Scale) -> Scenario:
    b, tq = sc.base, FW_LOAD * sc.torque
    top = 1400.0 * b
    segs = [("ramp", 0.02, 0.22, 0.0, top), ("step", 0.22, 0.32, top, top), ("ramp", 0.32, 0.52, top, 0.0)]
    return Scenario("field_weakening", "speed", 0.56, steps_and_ramps(_pts("field_weakening", b)), segments=segs,
                    load=lambda t: tq,
                    description=f"speed ramp 0 -> {top:.4g} rad/s (1.35 x the no-load base speed) and back under "
                                f"{tq:.3g} N m, algorithm 1 (field weakening)")


SCENARIOS = {
    "speed_steps": (_speed_steps, 1),
    "position_alg1": (lambda sc: _position(1, sc), 1),
    "position_alg2": (lambda sc: _position(2, sc), 2),
    "load_step": (_load_step, 2),
    "speed_alg2": (_speed_alg2, 2),
    "fault_step": (_fault_step, 2),
    "speed_limit": (_speed_limit, 1),
    "position_large": (_position_large, 2),
    "load_speed": (_load_speed, 2),
    "field_weakening": (_field_weakening, 1),
}


def get(name: str, cfg=None) -> tuple[Scenario, int]:
    """Scenario ``name`` and its algorithm; amplitudes scaled for ``cfg`` (default: paper 000's values)."""
    try:
        make, alg = SCENARIOS[name]
    except KeyError:
        raise KeyError(f"unknown scenario {name!r}; choose from {', '.join(SCENARIOS)}") from None
    return make(scale_for(cfg)), alg
