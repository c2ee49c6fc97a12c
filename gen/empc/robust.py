"""Robust design check: the loop as built (loop.py) over a box of plant parameters and Omega_e.

The gains are designed on the nominal motor; the check runs the loop with the plant at
every point of the robustness box (``[robustness]`` of the configuration; default L, R, J
+-30 %, psi +-20 %: the 16 corners, the nominal point and the 8 half-way points on the
axes) and every speed of a grid over Omega_e, with the exact gains and with the gains
the core applies (fitted polynomials, quantised coefficients: quantise.gains_si).

Criterion, per closed-loop eigenvalue z (continuous equivalent s = ln(z) / Ts):
  * decay: |z| <= exp(-decay_min Ts)    (the radius bound 1 - margin, margin = 1 - exp(-decay_min Ts);
    decay_min defaults to 0.01 / T_m, T_m the mechanical time constant at the rated current);
  * damping: zeta = -Re(s) / |s| >= damping_min for oscillatory modes (Im s != 0).
The report gives the worst spectral radius and the worst damping with where they occur
(speed, box point, gain set, frequency of the mode).
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field, replace

import numpy as np

from . import loop as loop_mod
from . import mpc

FACTORS = ("L", "R", "J", "psi")


def perturbed(motor, f: dict):
    """The motor with its parameters scaled by the factors ``f`` (L scales Ld and Lq, J the total inertia)."""
    return replace(motor, Ld=motor.Ld * f["L"], Lq=motor.Lq * f["L"], R=motor.R * f["R"],
                   J=motor.J * f["J"], psi=motor.psi * f["psi"])


def box_points(rob) -> list[dict]:
    """Nominal point, the 2^4 corners and the 8 half-way points on the axes of the box."""
    half = {k: getattr(rob, k) for k in FACTORS}
    pts = [{k: 1.0 for k in FACTORS}]
    for signs in itertools.product((-1, 1), repeat=len(FACTORS)):
        pts.append({k: 1.0 + s * half[k] for k, s in zip(FACTORS, signs)})
    for k in FACTORS:
        for s in (-0.5, 0.5):
            p = {kk: 1.0 for kk in FACTORS}
            p[k] = 1.0 + s * half[k]
            pts.append(p)
    out, seen = [], set()
    for p in pts:
        key = tuple(round(p[k], 12) for k in FACTORS)
        if key not in seen:
            seen.add(key)
            out.append(p)
    return out


def label(f: dict) -> str:
    parts = [f"{k} {100 * (v - 1):+.0f} %" for k, v in f.items() if abs(v - 1) > 1e-12]
    return ", ".join(parts) if parts else "nominal"


def speeds(cfg, points: int) -> np.ndarray:
    c = cfg.control
    g = np.linspace(c.omega_min, c.omega_max, points)
    if c.omega_min < 0 < c.omega_max:
        g = np.unique(np.append(g, 0.0))
    return g


def modes(ev: np.ndarray, Ts: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(|z|, damping ratio, frequency in Hz) of discrete eigenvalues."""
    z = ev.astype(complex)
    r = np.abs(z)
    s = np.log(np.where(r > 1e-300, z, 1e-300)) / Ts
    wn = np.abs(s)
    zeta = np.where(np.abs(s.imag) > 1e-9 * np.maximum(wn, 1.0), -s.real / np.maximum(wn, 1e-300), 1.0)
    return r, zeta, np.abs(s.imag) / (2 * math.pi)


@dataclass
class Worst:
    value: float
    omega: float = 0.0
    point: dict = field(default_factory=dict)
    gains: str = ""
    freq_hz: float = 0.0
    i_q0: float = 0.0          # the operating point's load current (0: the i = 0 linearisation)
    i_d0: float = 0.0

    def where(self) -> str:
        load = f", loaded i_q0 = {self.i_q0:.3g} A (i_d0 = {self.i_d0:.3g} A)" if self.i_q0 else ""
        return (f"omega_e = {self.omega:.0f} rad/s{load}, plant {label(self.point)}, {self.gains} gains"
                + (f", mode {self.freq_hz:.0f} Hz" if self.freq_hz > 0.5 else ""))

    def as_dict(self) -> dict:
        return {"value": self.value, "omega_e": self.omega, "plant": label(self.point),
                "factors": self.point, "gains": self.gains, "freq_hz": self.freq_hz,
                "i_q0": self.i_q0, "i_d0": self.i_d0}


def decay_min(cfg) -> float:
    """Required decay rate (1/s): ``robustness.decay_min``, default 0.01 / T_m (no mode slower than
    100 mechanical time constants T_m = J w_b / (1.5 p^2 psi I_b), config.pu_bases)."""
    d = cfg.robustness.decay_min
    return d if d is not None else 0.01 / cfg.bases("speed").T_m


def radius_bound(cfg) -> float:
    return math.exp(-decay_min(cfg) * cfg.control.Ts)


def _memo(f):
    """f(omega) evaluated once per omega: the gains are a pure function of the speed, read and never
    changed by loop.law / operating_point (the loaded points ask for f(w) and f(w +- h) at each of
    +-i_q0, and the law for f(w) at every load)."""
    cache = {}

    def g(w):
        w = float(w)
        if w not in cache:
            cache[w] = f(w)
        return cache[w]
    return g


def survey(cfg, algorithm: int, task: str, gain_sets: dict, points: list[dict] | None = None,
           grid: np.ndarray | None = None, estimator=None, loads: float | None = None) -> dict:
    """Worst radius and damping over the box and the speed grid for each gain set, at i = 0 and at the
    loaded operating points i_q0 = +-``loads`` A (default robustness.load x ratings.current; 0: none):
    there the plant is linearised at the law's own steady state (loop.operating_point: i_d0, the
    w L i terms) and the scheduled gains act on the loaded errors (kw).  ``worst_load_id`` is the
    largest |i_d0| / |i_q0| of that steady state over the grid (robustness.load_id_max).

    ``gain_sets``: {name: f(omega) -> gains in SI}.  Returns a dict with ``worst_radius``,
    ``worst_damping`` (:class:`Worst`), ``nominal_radius``, ``nominal_damping`` and per
    gain set its worst radius."""
    cfg = cfg.for_design(algorithm, task)
    rob = cfg.robustness
    gain_sets = {name: _memo(f) for name, f in gain_sets.items()}    # f(w) is asked 9 times per speed
    points = points if points is not None else box_points(rob)
    grid = grid if grid is not None else speeds(cfg, rob.speed_points)
    Ts = cfg.control.Ts
    est = estimator or loop_mod.estimator_for(cfg)
    plants = [perturbed(cfg.motor, p) for p in points]
    wr, wz = Worst(-1.0), Worst(2.0)
    per_set = {name: Worst(-1.0) for name in gain_sets}
    nom_r, nom_z = 0.0, 1.0
    delay = 0.5 / cfg.inverter.f_pwm
    nominal = [all(abs(v - 1) < 1e-12 for v in p.values()) for p in points]
    i_load = rob.load * cfg.ratings.current if loads is None else loads
    iqs = [0.0] + ([i_load, -i_load] if i_load else [])
    wl = Worst(-1.0)                      # largest |i_d0| / |i_q0| of the law's loaded steady state (-1: no load)
    for w in grid:
        plant_cache = {}
        for name, f in gain_sets.items():
            for iq0 in iqs:
                if iq0:
                    op = loop_mod.operating_point(f, algorithm, task, cfg.control.N, float(w), iq0)
                    ratio = abs(op.i_d0 / iq0)
                    if not np.isfinite(ratio) or ratio > wl.value:
                        wl = Worst(float(ratio), float(w), {}, name, 0.0, iq0, op.i_d0)
                    if not np.all(np.isfinite(op.kw)):
                        continue
                    i0 = (op.i_d0, iq0)
                else:
                    op, i0 = None, (0.0, 0.0)
                key = tuple(round(x, 9) for x in i0)
                if key not in plant_cache:
                    plant_cache[key] = loop_mod.plants_delayed(plants, float(w), Ts, delay, i0)
                Ad, B0, B1 = plant_cache[key]
                lw = loop_mod.law(cfg, algorithm, task, f(float(w)), estimator=est,
                                  kw=op.kw if op is not None else None)
                evs = loop_mod.eigenvalues_batch(lw, Ad, B0, B1)
                R, Z, FR = modes(evs, Ts)
                I = np.argmax(R, axis=1)
                Zo = np.where(FR > 0.0, Z, 2.0)
                Jo = np.argmin(Zo, axis=1)
                for k, p in enumerate(points):
                    r, fr = R[k], FR[k]
                    i, j = int(I[k]), int(Jo[k])
                    zmin = min(1.0, float(Zo[k, j]))
                    if r[i] > wr.value:
                        wr = Worst(float(r[i]), float(w), p, name, float(fr[i]), iq0, i0[0])
                    if r[i] > per_set[name].value:
                        per_set[name] = Worst(float(r[i]), float(w), p, name, float(fr[i]), iq0, i0[0])
                    if zmin < wz.value:
                        wz = Worst(zmin, float(w), p, name, float(fr[j]) if Zo[k, j] <= 1.0 else 0.0, iq0, i0[0])
                    if nominal[k]:
                        nom_r, nom_z = max(nom_r, float(r[i])), min(nom_z, zmin)
    return {"worst_radius": wr, "worst_damping": wz, "nominal_radius": nom_r, "nominal_damping": nom_z,
            "per_gain_set": per_set, "box_points": len(points), "speeds": len(grid),
            "load_current": i_load, "worst_load_id": wl}


def exact_gains(cfg, algorithm: int, task: str, weights=None):
    return lambda w: mpc.gains(cfg.motor, cfg.control, w, algorithm, task, weights=weights)


def verdict(cfg, res: dict) -> tuple[bool, str]:
    """(passed, reason) against the configuration's margins."""
    rob = cfg.robustness
    bound = radius_bound(cfg)
    wr, wz = res["worst_radius"], res["worst_damping"]
    wl = res.get("worst_load_id")
    if wl is not None and wl.i_q0 and not wl.value <= rob.load_id_max:
        return False, (f"under load the law settles at i_d0 = {wl.i_d0:.3g} A for i_q0 = {wl.i_q0:.3g} A "
                       f"(|i_d0/i_q0| = {wl.value:.3g} > robustness.load_id_max = {rob.load_id_max:g}) at "
                       f"omega_e = {wl.omega:.0f} rad/s, {wl.gains} gains: the cost trades the load current "
                       f"against the d current (a Q_yw weight on i_q with its reference 0; see docs/design.md)")
    if wr.value > bound:
        return False, (f"spectral radius {wr.value:.5f} > {bound:.5f} (decay rate {decay_min(cfg):.3g}/s, "
                       f"robustness.decay_min) at {wr.where()}")
    if wz.value < rob.damping_min:
        return False, (f"damping {wz.value:.3f} < robustness.damping_min = {rob.damping_min:g} at {wz.where()}")
    return True, "ok"


def noise_rms(cfg, algorithm: int, task: str, g: dict, omega: float = 0.0, factors: dict | None = None) -> dict:
    """RMS of i_q (A) and |u| (V) driven by the sensor quantisation at ``omega``, on the nominal plant or
    the plant scaled by ``factors`` (a box point): encoder angle uniform over one count (eq. 38), ADC
    uniform over one LSB."""
    cfg = cfg.for_design(algorithm, task)
    plant = perturbed(cfg.motor, factors) if factors else cfg.motor
    lp = loop_mod.loop(cfg, plant, omega, algorithm, task, g)
    sig = np.array([cfg.rad_per_count, cfg.amps_per_lsb, cfg.amps_per_lsb]) / math.sqrt(12.0)
    return loop_mod.noise_gain(lp, sig)


def noise_box(cfg, algorithm: int, task: str, g: dict, omega: float = 0.0) -> dict:
    """:func:`noise_rms` at every point of the robustness box (box_points): the worst i_q RMS and the
    worst |u| RMS with their box points, and the nominal values.  The quantisation chatter of a design is
    its worst over the box, not its nominal value: with L and R -30 % the current loop is faster and less
    damped (the EC 45 flat's algorithm-2 designs: 0.23 i_max RMS nominal, 0.48 at L, R -30 %)."""
    out = {"i_q_rms": -1.0, "u_rms": -1.0, "i_q_point": None, "u_point": None}
    for p in box_points(cfg.robustness):
        n = noise_rms(cfg, algorithm, task, g, omega, p)
        if all(abs(v - 1) < 1e-12 for v in p.values()):
            out["i_q_rms_nominal"], out["u_rms_nominal"] = n["i_q_rms"], n["u_rms"]
        if not n["i_q_rms"] <= out["i_q_rms"]:
            out["i_q_rms"], out["i_q_point"] = n["i_q_rms"], p
        if not n["u_rms"] <= out["u_rms"]:
            out["u_rms"], out["u_point"] = n["u_rms"], p
    return out
