"""`empc tune`: per-unit weights that meet stated specifications, and which specification binds.

The search scales the configuration's weights of one design (per unit of the ratings) by
two factors on a logarithmic grid: ``a`` on the task output (Q_yw[2] x a, Q_dy[2] x sqrt(a): the
speed or position loop's bandwidth at about the same damping) and ``b`` on the voltage
increments (Q_du: how hard the current loop pushes).  Each candidate is measured on the loop as built (loop.py, nominal plant at
omega_e = 0, references seen N periods ahead as in the scenarios):

  settling       task-output step, time to stay within 2 % of the step (linear loop)
  overshoot      of that step, % (algorithm 1; the linear loop has no eq. 25 clamp, so for
                 algorithm 2 it is reported, and checked only if --overshoot is given)
  current        peak |i_dq| for a task step of ``step`` per unit, against control.i_max
  current_rise   i_d step (the current loop's settling), time to reach 90 % of its final value
                 (algorithm 1 trades i_d against the task output in steady state: a slow tail
                 that a settling band would measure instead of the current loop)
  chatter        RMS i_q that the sensor quantisation drives (encoder count, ADC LSB), per unit
                 of the rated current, the worst over the robustness box (robust.noise_box; likewise
                 the RMS |u|, ``u_chatter``): a design quiet on the nominal plant can chatter at a
                 box corner (faster, less damped current loop with L, R -30 %)
  robustness     the design check's box and margins (robust.py), on a 7-point speed grid (the
                 chosen weights then go through the full check of `empc roms`)

Among the candidates that meet every specification the one with the shortest settling is
chosen; the specification that stops the faster candidates is reported as binding.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from . import config as config_mod, loop as loop_mod, mpc, robust

A_GRID = [2.0 ** k for k in range(-3, 11)]           # task-output weight factor 1/8 .. 1024
B_GRID = [2.0 ** k for k in range(-3, 4)]            # Q_du factor 1/8 .. 8


@dataclass
class Specs:
    settling: float | None = None          # s
    current_rise: float | None = None      # s (default 20 Ts)
    overshoot: float | None = None         # % (default 20 for algorithm 1, none for algorithm 2)
    step: float = 0.1                      # per unit of rated speed / position scale
    chatter: float = 0.2                   # per unit of rated current (RMS)
    u_chatter: float = 0.5                 # RMS |u| the sensor quantisation drives, per unit of the voltage limit

    @classmethod
    def from_args(cls, a) -> "Specs":
        return cls(settling=a.settling, current_rise=a.current_rise, overshoot=a.overshoot,
                   step=a.step, chatter=a.chatter, u_chatter=getattr(a, "u_chatter", 0.5))


@dataclass
class Candidate:
    a: float
    b: float
    weights_pu: config_mod.Weights
    m: dict = field(default_factory=dict)
    fails: list = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.fails


@dataclass
class TuneResult:
    algorithm: int
    task: str
    passed: bool
    chosen: Candidate | None
    binding: str
    tried: int
    base_pu: config_mod.Weights
    note: str = ""
    speed_window: int = 1          # the design's speed window the weights were tuned with (Control.window_of)

    def as_dict(self) -> dict:
        c = self.chosen
        return {"algorithm": self.algorithm, "task": self.task, "passed": self.passed, "binding": self.binding,
                "tried": self.tried, "note": self.note,
                "factors": {"a": c.a, "b": c.b} if c else None,
                "weights_pu": _wd(c.weights_pu) if c else None, "metrics": c.m if c else None}

    def explain(self) -> str:
        c = self.chosen
        head = f"algorithm {self.algorithm} / {self.task}: "
        if c is None:
            return head + f"no candidate meets the specifications ({self.binding}); {self.note}"
        m = c.m
        if "factors" in m:
            return (head + f"settling {1e3 * m['settling']:.1f} ms, overshoot {m['overshoot']:.1f} %, peak current "
                    f"{m['current']:.2f} A for a {m['step_si']:.3g} step, i_d rise {1e3 * m['current_rise']:.2f} ms, "
                    f"chatter {m['chatter_pu']:.3f} pu; {self.binding}")
        return (head + f"task weight x{c.a:g}, Q_du x{c.b:g}: settling {1e3 * m['settling']:.1f} ms, overshoot "
                f"{m['overshoot']:.1f} %, peak current {m['current']:.2f} A for a {m['step_si']:.3g} step, "
                f"i_d rise {1e3 * m['current_rise']:.2f} ms, chatter {m['chatter_pu']:.3f} pu, worst radius "
                f"{m['radius']:.4f}, worst damping {m['damping']:.3f}.  Binding: {self.binding}")


def _wd(w) -> dict:
    return {"Q_yw": [round(v, 6) for v in w.Q_yw], "Q_dy": [round(v, 6) for v in w.Q_dy],
            "Q_du": [round(v, 6) for v in w.Q_du], "ebar_step_max": list(w.ebar_step_max),
            "integrate": list(w.integrate), "Q_yp": [round(v, 6) for v in w.Q_yp]}


def _settling(y: np.ndarray, final: float, k0: int, Ts: float, band: float) -> float:
    out = np.nonzero(np.abs(y - final) > band)[0]
    if len(out) == 0:
        return 0.0
    if out[-1] == len(y) - 1:
        return math.inf
    return (out[-1] + 1 - k0) * Ts


def measure(cfg, algorithm: int, task: str, w_si, specs: Specs, robust_grid: int | None = 7) -> dict:
    cfg = cfg.for_design(algorithm, task)
    c = cfg.control
    rt = cfg.ratings
    g = mpc.gains(cfg.motor, c, 0.0, algorithm, task, weights=w_si)
    lp = loop_mod.loop(cfg, cfg.motor, 0.0, algorithm, task, g)
    k0 = c.N
    steps = 2000
    size = specs.step * (rt.speed if task == "speed" else rt.position)
    sr = loop_mod.step_response(lp, [0.0, 0.0, size], steps, k0)
    y = sr["w_e"] if task == "speed" else sr["theta_e"]
    m = {"step_si": size}
    m["settling"] = _settling(y, size, k0, c.Ts, 0.02 * abs(size))
    m["overshoot"] = max(0.0, float(np.max(y) - size) / abs(size) * 100.0)
    m["current"] = float(np.max(np.hypot(sr["i_d"], sr["i_q"])))
    si = loop_mod.step_response(lp, [0.1 * rt.current, 0.0, 0.0], 400, k0)
    fin = si["i_d"][-1]
    up = np.nonzero(si["i_d"][k0:] * np.sign(fin) >= 0.9 * abs(fin))[0]
    m["current_rise"] = float(up[0] + 1) * c.Ts if len(up) else math.inf
    noise = robust.noise_box(cfg, algorithm, task, g, 0.0)
    m["chatter_pu"] = noise["i_q_rms"] / rt.current
    m["u_chatter"] = noise["u_rms"] / cfg.u_max
    m["chatter_nominal_pu"] = noise["i_q_rms_nominal"] / rt.current
    m["chatter_where"] = robust.label(noise["i_q_point"]) if noise["i_q_point"] is not None else ""
    if robust_grid is None:               # the caller has the full design check's figures
        return m
    res = robust.survey(cfg, algorithm, task, {"exact": robust.exact_gains(cfg, algorithm, task, w_si)},
                        grid=robust.speeds(cfg, robust_grid))
    ok, why = robust.verdict(cfg, res)
    m["radius"], m["damping"] = res["worst_radius"].value, res["worst_damping"].value
    m["robust"] = why
    m["robust_ok"] = ok
    return m


def _fails(cfg, algorithm: int, m: dict, specs: Specs) -> list[str]:
    c = cfg.control
    f = []
    if not m["robust_ok"]:
        f.append(f"robustness ({m['robust']})")
    ov = specs.overshoot if specs.overshoot is not None else (20.0 if algorithm == 1 else None)
    if ov is not None and m["overshoot"] > ov:
        f.append(f"overshoot {m['overshoot']:.1f} % > {ov:g} %")
    if m["current"] > c.i_max:
        f.append(f"current {m['current']:.2f} A > control.i_max = {c.i_max:g} A for a {specs.step:g} pu step")
    ics = specs.current_rise if specs.current_rise is not None else 20 * c.Ts
    if m["current_rise"] > ics:
        f.append(f"current-loop rise {1e3 * m['current_rise']:.2f} ms > {1e3 * ics:.2f} ms")
    if m["chatter_pu"] > specs.chatter:
        f.append(f"quantisation chatter {m['chatter_pu']:.3f} pu > {specs.chatter:g} pu"
                 + (f" (at {m['chatter_where']})" if m.get("chatter_where") else ""))
    if m["u_chatter"] > specs.u_chatter:
        # a voltage noise near the limit makes the loop bang between +-u_max (a limit cycle the linear
        # check does not see: 50 us designs with u_rms = 4.6 u_max, docs/design.md)
        f.append(f"quantisation voltage chatter {m['u_chatter']:.2f} x u_max > {specs.u_chatter:g}")
    if specs.settling is not None and m["settling"] > specs.settling:
        f.append(f"settling {1e3 * m['settling']:.1f} ms > {1e3 * specs.settling:.1f} ms")
    return f


def scaled(base: config_mod.Weights, a: float, b: float) -> config_mod.Weights:
    """Task-output error weight x a, its increment weight x sqrt(a) (the proportional and the
    derivative part of the task loop scale together: faster at about the same damping), Q_du x b."""
    r = math.sqrt(a)
    return replace(base, Q_yw=(base.Q_yw[0], base.Q_yw[1], base.Q_yw[2] * a),
                   Q_dy=(base.Q_dy[0], base.Q_dy[1], base.Q_dy[2] * r), Q_du=tuple(q * b for q in base.Q_du))


def tune(cfg, algorithm: int, task: str, specs: Specs | None = None, a_grid=None, b_grid=None) -> TuneResult:
    specs = specs or Specs()
    base = cfg.weights_pu(algorithm, task)
    cands = []
    for b in (b_grid or B_GRID):
        for a in (a_grid or A_GRID):
            wpu = scaled(base, a, b)
            cand = Candidate(a, b, wpu)
            try:
                cand.m = measure(cfg, algorithm, task, config_mod.weights_si(wpu, cfg.bases(task)), specs)
                cand.fails = _fails(cfg, algorithm, cand.m, specs)
            except (np.linalg.LinAlgError, ValueError) as e:
                cand.fails = [f"design failed: {e}"]
            cands.append(cand)
    good = [c for c in cands if c.ok]
    if not good:
        counts: dict = {}
        for c in cands:
            for f in c.fails:
                k = f.split(" ")[0]
                counts[k] = counts.get(k, 0) + 1
        binding = "every candidate fails: " + ", ".join(f"{k} ({n})" for k, n in sorted(counts.items(), key=lambda x: -x[1]))
        return _result(cfg, algorithm, task, False, None, binding, len(cands), base,
                          note="relax the specifications or the robustness box, or change N / Ts")
    from . import design as design_mod
    for best in sorted(good, key=lambda c: (c.m["settling"], -c.m["damping"]))[:8]:
        # the full design check (every box point, the full speed grid, fitted and quantised gains)
        c2 = cfg.with_control(weights={**cfg.control.weights,
                                       (algorithm, task): config_mod.weights_si(best.weights_pu, cfg.bases(task))})
        try:
            st = design_mod.design(c2, algorithm, task, force=True)["stability"]
            ok, why = st["passed"], st["reason"]
        except config_mod.ConfigError as e:
            ok, why = False, str(e)
        if ok:
            break
        best.fails.append(f"robustness (full check: {why})")
    else:
        return _result(cfg, algorithm, task, False, None, "the candidates that meet the specifications on the coarse "
                          "grid fail the full design check", len(cands), base)
    faster = [c for c in cands if not c.ok and c.m and c.m.get("settling", math.inf) < best.m["settling"]]
    if faster:
        counts = {}
        for c in faster:
            for f in c.fails:
                k = f.split(" (")[0].split(" ")[0]
                counts.setdefault(k, []).append(f)
        top = max(counts.items(), key=lambda kv: len(kv[1]))
        binding = (f"{top[0]} stops {len(top[1])} of the {len(faster)} faster candidates, e.g. {top[1][0]}")
    else:
        binding = "none: the fastest candidate on the grid meets every specification (widen the grid)"
    return _result(cfg, algorithm, task, True, best, binding, len(cands), base)


# --------------------------------------------------------------------------------------------------
# Refinement: one factor per weight element (and Q_yp for algorithm 2), for designs the two-factor grid
# cannot reach (typically a control period the weights were not tuned at: docs/design.md)
# --------------------------------------------------------------------------------------------------
REFINE_KEYS = ("Q_du", "Q_yw0", "Q_yw1", "Q_yw2", "Q_dy0", "Q_dy1", "Q_dy2", "Q_yp2")
DAMPING_AIM = 0.01          # aim this much inside damping_min (the full check's margin)


def refined(base: config_mod.Weights, f: dict) -> config_mod.Weights:
    """``base`` with element factors ``f`` (Q_du: both inputs; Q_yp2: the value itself, per unit)."""
    def vec(name, v):
        return tuple(x * f.get(f"{name}{i}", 1.0) for i, x in enumerate(v))
    w = replace(base, Q_yw=vec("Q_yw", base.Q_yw), Q_dy=vec("Q_dy", base.Q_dy),
                Q_du=tuple(x * f.get("Q_du", 1.0) for x in base.Q_du))
    if "Q_yp2" in f:
        w = replace(w, Q_yp=(w.Q_yp[0], w.Q_yp[1], f["Q_yp2"]))
    return w


def _violation(cfg, radius: float, damping: float, bound: float) -> float:
    """The check's violation: the radius over its bound, or the damping under its minimum (with the aim)."""
    return max(radius - bound, 0.02 * (cfg.robustness.damping_min + DAMPING_AIM - damping))


def _score_floor(cfg, algorithm: int, task: str) -> float:
    """A lower bound of the design check's :func:`_violation`: the exact gains at a subset of the check's
    own speeds (its ends, middle and 0).  The check surveys these and more speeds with the exact,
    fitted and quantised gains, so its worst radius is no smaller and its worst damping no larger."""
    rob = cfg.for_design(algorithm, task).robustness
    g = robust.speeds(cfg.for_design(algorithm, task), rob.speed_points)
    sub = np.unique(np.concatenate([g[[0, len(g) // 2, len(g) - 1]], g[g == 0.0]]))
    res = robust.survey(cfg, algorithm, task, {"exact": robust.exact_gains(cfg, algorithm, task)}, grid=sub)
    return _violation(cfg, res["worst_radius"].value, res["worst_damping"].value, robust.radius_bound(cfg))


def _penalty(cfg, m: dict, fails: list[str], specs: Specs) -> float:
    """The score's part for the specifications other than the check: a penalty above any margin left,
    growing with the excess so that the search can walk towards them (the current-loop rise is
    reported, not searched for)."""
    lim = {"chatter_pu": specs.chatter, "u_chatter": specs.u_chatter, "current": cfg.control.i_max}
    pen = sum(1e-3 * (1.0 + math.log(m[k] / x)) for k, x in lim.items() if not m[k] <= x)
    if not math.isfinite(m["settling"]):
        pen += 1e-3
    if any(f.startswith("overshoot") or f.startswith("settling") for f in fails):
        pen += 1e-3
    return pen


def _score(v: float, pen: float) -> float:
    return max(v, 0.0) + (pen if math.isfinite(pen) else 1.0) if pen else v


def _refine_score(cfg, algorithm: int, task: str, wpu, specs: Specs, beat: float = math.inf):
    """(score, candidate): score < 0 when the full design check passes with margin and the specifications
    hold; the check's violation (radius over its bound, damping under its minimum) dominates.  A
    candidate whose score is bounded below by ``beat`` (:func:`_score_floor`'s violation with the
    specification penalty) is not designed and returns that bound: the search keeps only a score
    below ``beat``, so its walk is the one it takes with every candidate designed."""
    from . import design as design_mod
    cand = Candidate(0.0, 0.0, wpu)
    w_si = config_mod.weights_si(wpu, cfg.bases(task))
    c2 = cfg.with_control(weights={**cfg.control.weights, (algorithm, task): w_si})
    try:
        m = measure(cfg, algorithm, task, w_si, specs, robust_grid=None)
        m["robust_ok"], m["robust"] = True, "not checked yet"
        pen = _penalty(cfg, m, _fails(cfg, algorithm, m, specs), specs)
        if math.isfinite(beat):
            floor = _score(_score_floor(c2, algorithm, task), pen)
            if floor >= beat:
                cand.m = m
                cand.fails = [f"pruned: the score is at least {floor:.4g}"]
                return floor, cand
        st = design_mod.design(c2, algorithm, task, force=True)["stability"]
    except (config_mod.ConfigError, np.linalg.LinAlgError, ValueError) as e:
        cand.fails = [f"design failed: {e}"]
        return math.inf, cand
    m["radius"], m["damping"] = st["worst_radius"]["value"], st["worst_damping"]["value"]
    m["robust_ok"], m["robust"] = st["passed"], st["reason"]
    cand.m = m
    cand.fails = _fails(cfg, algorithm, m, specs)
    return _score(_violation(cfg, m["radius"], m["damping"], st["radius_bound"]), pen), cand


def refine(cfg, algorithm: int, task: str, specs: Specs | None = None, start: dict | None = None,
           rounds: int = 12) -> TuneResult:
    """Coordinate search over :data:`REFINE_KEYS` (factors x2 / x0.5, then x sqrt 2) from the configured
    weights until the full design check passes and the specifications hold.  For algorithm 2 the
    proportional weight Q_yp[2] enters, seeded at 3 x Q_yw[2] when it is 0 (docs/design.md: the integrated
    errors give the law its proportional action only through the horizon N Ts)."""
    specs = specs or Specs()
    base = cfg.weights_pu(algorithm, task)
    keys = [k for k in REFINE_KEYS if not (k.startswith("Q_yw") and base.Q_yw[int(k[-1])] == 0.0)
            and (k != "Q_yp2" or algorithm == 2)]
    starts = [dict(start)] if start else [{}]
    if algorithm == 2 and not start and not base.Q_yp[2]:
        # the patterns that pass at 50 us (docs/design.md): speed, a proportional weight of about 5 x the
        # integrated one and a slower current loop; position, a weak integrator and a proportional weight
        starts = [{"Q_yp2": 5.0 * base.Q_yw[2], "Q_du": 4.0},
                  {"Q_yp2": 2.5 * base.Q_yw[2], "Q_du": 8.0, "Q_yw2": 1.0 / 32.0, "Q_dy0": 4.0}] + starts
    tried, best = 0, None
    for f0 in starts:
        f = {k: f0.get(k, base.Q_yp[2] if k == "Q_yp2" else 1.0) for k in keys}
        if f.get("Q_yp2", 1.0) == 0.0:
            f.pop("Q_yp2")                 # multiplicative steps cannot leave 0
        score, cand = _refine_score(cfg, algorithm, task, refined(base, f), specs)
        tried += 1
        step = 2.0
        for _ in range(rounds):
            if score < 0:
                break
            moved = False
            for k in list(f):
                for s in (step, 1.0 / step):
                    g = dict(f, **{k: f[k] * s})
                    sc, c = _refine_score(cfg, algorithm, task, refined(base, g), specs, beat=score - 1e-9)
                    tried += 1
                    if sc < score - 1e-9:
                        score, cand, f, moved = sc, c, g, True
            if not moved:
                if step < 1.2:
                    break
                step = math.sqrt(step)
        cand.a, cand.b = f.get("Q_yw2", 1.0), f.get("Q_du", 1.0)
        cand.m["factors"] = dict(f)
        if best is None or score < best[0]:
            best = (score, cand)
        if score < 0:
            break
    score, cand = best
    if score >= 0:
        return _result(cfg, algorithm, task, False, None, "refinement: no candidate passes the full design check "
                          f"and the specifications (best: {'; '.join(cand.fails) or 'no margin'})", tried, base,
                          note="relax the specifications or the robustness box, or change N / Ts")
    fac = ", ".join(f"{k} x{v:.3g}" if k != "Q_yp2" else f"Q_yp[2] = {v:.4g}" for k, v in cand.m["factors"].items()
                    if k == "Q_yp2" or abs(v - 1.0) > 1e-9)
    return _result(cfg, algorithm, task, True, cand, f"refinement ({fac}): the full design check passes (worst "
                      f"radius {cand.m['radius']:.5f}, damping {cand.m['damping']:.3f})", tried, base)


def _result(cfg, *args, **kw) -> TuneResult:
    """A TuneResult with the design's speed window (the table written for it carries it)."""
    r = TuneResult(*args, **kw)
    return replace(r, speed_window=cfg.control.window_of(r.algorithm, r.task))


def _table_name(r: "TuneResult", ts: float | None) -> str:
    name = f"weights.alg{r.algorithm}.{r.task}"
    return name if ts is None else f"{name}.Ts_{ts * 1e6:.6g}us"


def toml_tables(results: list[TuneResult], ts: float | None = None) -> str:
    """The chosen weights as [weights.*] tables (per unit) to paste into the configuration; with ``ts``
    as control-period tables [weights.<design>.Ts_<us>us] (docs/design.md) that give every key."""
    out = ["[weights]", 'units = "pu"']
    for r in results:
        if not r.chosen:
            continue
        w = r.chosen.weights_pu
        out += ["", f"[{_table_name(r, ts)}]",
                f"Q_yw = [{', '.join(f'{v:.6g}' for v in w.Q_yw)}]",
                f"Q_dy = [{', '.join(f'{v:.6g}' for v in w.Q_dy)}]",
                f"Q_du = [{', '.join(f'{v:.6g}' for v in w.Q_du)}]"]
        if r.algorithm == 2:
            out += [f"integrate = [{', '.join('true' if v else 'false' for v in w.integrate)}]",
                    f"ebar_step_max = [{', '.join(f'{v:.6g}' for v in w.ebar_step_max)}]"]
            if any(w.Q_yp):
                out += [f"Q_yp = [{', '.join(f'{v:.6g}' for v in w.Q_yp)}]"]
        if r.speed_window != 1:
            out += [f"speed_window = {r.speed_window}"]
    return "\n".join(out)
