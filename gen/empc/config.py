"""Configuration (TOML): motor, inverter, sensors, FPGA clock, ratings, MPC design, robustness box,
reference governor, field weakening.

``load(path)`` returns a validated :class:`Config`; bad input raises :class:`ConfigError`
with one line naming the key, the value and the allowed range.  Validation is driven by
one table, :data:`SCHEMA` (tables and keys with type, default, range and unit): unknown
tables and keys are refused with a did-you-mean, types are strict (no bool or string
where a number belongs, no float where an integer belongs), and every value the RTL
stores is checked against its field (:data:`RTL_LIMITS`, derived quantities named by the
keys they come from).  A new key is one :class:`Key` row in :data:`SCHEMA`, read in
:func:`from_dict` (tables without a field of their own, like ``[governor]`` and
``[field_weakening]``, map one to one onto their dataclass).

Weights are per unit of the motor's ratings (``[weights] units = "pu"``, the default
when a configuration has no ``[weights]`` table: :data:`DEFAULT_WEIGHTS_PU`), or SI
(``units = "si"``, kept for older files).  See :func:`pu_bases` for the bases.

The default configuration is the paper's BLWR233D set-up (``configs/blwr233d.toml``).
"""
from __future__ import annotations

import copy
import difflib
import math
import re
import tomllib
from dataclasses import dataclass, field, replace
from pathlib import Path

from . import formats                  # formats.py imports nothing of the package
from .governor import TAU_POSITION   # governor.py imports nothing of the package

DEFAULT_CONFIG = Path(__file__).with_name("configs") / "blwr233d.toml"


class ConfigError(ValueError):
    """A configuration value is invalid; the message names it."""


# ----------------------------------------------------------------------------------------------
# The schema: one row per key.  kind: float, int, bool, str, float[n], bool[n].
# ----------------------------------------------------------------------------------------------
REQUIRED = object()


@dataclass(frozen=True)
class Key:
    table: str
    name: str
    kind: str
    default: object = REQUIRED
    lo: float | None = None          # range (inclusive unless *_open)
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    choices: tuple = ()
    unit: str = ""
    doc: str = ""

    @property
    def path(self) -> str:
        return f"{self.table}.{self.name}"

    def range_text(self) -> str:
        if self.choices:
            return "one of " + ", ".join(repr(c) for c in self.choices)
        what = {"int": "an integer", "bool": "true or false", "str": "a string"}.get(self.kind, "a number")
        if self.kind.startswith("float["):
            what = f"a list of {self.kind[6:-1]} numbers"
        elif self.kind.startswith("bool["):
            what = f"a list of {self.kind[5:-1]} booleans"
        elif self.kind == "str[]":
            return "a list of strings, each one of " + ", ".join(repr(c) for c in self.choices)
        lo = None if self.lo is None else f"{'>' if self.lo_open else '>='} {self.lo:g}"
        hi = None if self.hi is None else f"{'<' if self.hi_open else '<='} {self.hi:g}"
        if lo and hi and not self.lo_open and not self.hi_open:
            rng = f"{self.lo:g} .. {self.hi:g}"
        else:
            rng = " and ".join(x for x in (lo, hi) if x)
        unit = f" {self.unit}" if self.unit and rng else ""
        return f"{what}{' ' + rng if rng else ''}{unit}"


_WEIGHT_TABLES = tuple(f"weights.alg{a}.{t}" for a in (1, 2) for t in ("speed", "position"))

# table -> (required, doc)
TABLES = {
    "motor": (True, "motor parameters (SI)"),
    "inverter": (True, "power stage"),
    "sensors": (True, "encoder and current ADC"),
    "fpga": (False, "FPGA clock"),
    "control": (True, "control law, horizon, period, operating range"),
    "ratings": (False, "the motor's ratings: the per-unit bases of the weights"),
    "governor": (False, "reference governor: the current limit of the control law (gen/empc/governor.py)"),
    "field_weakening": (False, "field weakening: a negative d-current reference from the voltage margin"),
    "robustness": (False, "the box of plant parameters and the margins the design check requires"),
    "weights": (False, "MPC weights (diagonals of Q_*): per unit of the ratings or SI"),
    "weights.alg1": (False, "algorithm 1 designs"),
    "weights.alg2": (False, "algorithm 2 designs"),
    **{t: (False, "weights of one design") for t in _WEIGHT_TABLES},
}

SPEED_WINDOWS = tuple(1 << m for m in range(formats.WIN_LOG2_MAX + 1))   # control.speed_window M = 2^m
                                                                         # (1, 2, 4, 8, 16 at WIN_LOG2_MAX = 4)

SCHEMA: list[Key] = [
    Key("motor", "name", "str", "motor"),
    Key("motor", "R", "float", lo=0, lo_open=True, unit="ohm", doc="stator resistance (phase)"),
    Key("motor", "Ld", "float", lo=0, lo_open=True, unit="H"),
    Key("motor", "Lq", "float", lo=0, lo_open=True, unit="H"),
    Key("motor", "psi", "float", lo=0, lo_open=True, unit="Wb", doc="PM flux linkage (amplitude)"),
    Key("motor", "p", "int", lo=1, hi=256, doc="pole pairs"),
    Key("motor", "J", "float", lo=0, lo_open=True, unit="kg m^2", doc="rotor inertia"),
    Key("motor", "J_load", "float", 0.0, lo=0, unit="kg m^2", doc="load inertia on the shaft (the design uses J + J_load)"),
    Key("motor", "B", "float", 0.0, lo=0, unit="N m s/rad"),
    Key("motor", "tau_c", "float", 0.0, lo=0, unit="N m", doc="Coulomb friction (plant only)"),
    Key("inverter", "Udc", "float", lo=0, lo_open=True, unit="V"),
    Key("inverter", "f_pwm", "float", lo=0, lo_open=True, unit="Hz"),
    Key("inverter", "dead_time", "float", 0.0, lo=0, unit="s"),
    Key("sensors", "encoder_cpr", "int", lo=4, hi=(1 << 17) - 1,
        doc="counts per mechanical revolution after x4 (pos_sense: one 17-bit DSP48A1 multiplier)"),
    Key("sensors", "adc_amps_per_lsb", "float", lo=0, lo_open=True, unit="A"),
    Key("sensors", "adc_offset", "int", 2048, lo=0, hi=4095, doc="ADC code at zero current (12-bit ADC_OFF registers)"),
    Key("sensors", "adc_noise_lsb", "float", 0.0, lo=0, hi=100, unit="LSB"),
    Key("fpga", "f_clk", "float", 100e6, lo=1e6, hi=500e6, unit="Hz"),
    Key("control", "algorithm", "int", 1, choices=(1, 2)),
    Key("control", "task", "str", "speed", choices=("speed", "position")),
    Key("control", "N", "int", 4, lo=1, hi=8, doc="prediction horizon (core N_MAX = 8, CAPS.horizon 4 bit)"),
    Key("control", "Ts", "float", lo=0, lo_open=True, unit="s", doc="control period, a whole number of PWM periods"),
    Key("control", "omega_min", "float", unit="rad/s"),
    Key("control", "omega_max", "float", unit="rad/s"),
    Key("control", "omega_points", "int", 101, lo=3, hi=10001),
    Key("control", "design_quantised", "bool", True),
    Key("control", "voltage_limit", "str", "circle", choices=("circle",)),
    Key("control", "i_max", "float", 10.0, lo=0, lo_open=True, unit="A"),
    Key("control", "speed_estimate", "str", "accel_load", choices=("eq37", "accel", "accel_load"),
        doc="eq37: backward difference of the encoder angle; accel: + (Ts/2) acceleration from i_q; "
            "accel_load: accel less a load estimate (offset-free under a constant load; estimator.py)"),
    Key("control", "speed_load_shift", "int", 6, lo=1, hi=15,
        doc="accel_load: load-estimate gain 2^-shift per control period (KACC.load_shift, 4 bit; 0 there = off)"),
    Key("control", "speed_window", "int", 1, choices=SPEED_WINDOWS,
        doc="speed estimate over M control periods: (theta_k - theta_{k-M}) / (M Ts), the acceleration "
            "correction over (M/2) Ts (estimator.py; 1 = eq. 37 over one period). RTL: KACC.win = log2 M "
            "(reset from the header), needs speed_load_shift >= log2 M - 1 with accel_load"),
    Key("governor", "enable", "bool", True, doc="reference governor in rtl/ref_gen.v (the current limit)"),
    Key("governor", "accel_current", "float", 0.5, lo=0, lo_open=True, hi=1,
        doc="the governed reference's acceleration needs at most this x i_max at the box corner"),
    Key("governor", "accel_current_position", "float", None, lo=0, lo_open=True, hi=1,
        doc="the same for the position task (default accel_current); below it the default shift_position "
            "grows with the catch-up time it needs (governor.default_shift_position)"),
    Key("governor", "box_J", "float", None, lo=0.5, hi=3,
        doc="inertia factor of that corner (default 1 + robustness.J)"),
    Key("governor", "box_psi", "float", None, lo=0, lo_open=True, hi=1,
        doc="flux factor of that corner (default 1 - robustness.psi)"),
    Key("governor", "speed_frac", "float", 0.7, lo=0, lo_open=True, hi=1,
        doc="position task: reference speed at most this x min(u_max / psi, Omega_e)"),
    Key("governor", "hold_current", "float", 0.7, lo=0, lo_open=True, hi=1,
        doc="hold the reference after a period with |i_q| >= this x i_max (IQ_HOLD, 12 bit ADC LSB)"),
    Key("governor", "shift_speed", "int", 3, lo=0, hi=31, doc="catch-up gain 2^-shift per period, speed task (ksh, 5 bit)"),
    Key("governor", "shift_position", "int", None, lo=0, hi=31,
        doc="the same, position task (default from control.Ts: Ts x 2^shift >= tau_position, 4 at 250 us, 7 at 50 us)"),
    Key("governor", "tau_position", "float", TAU_POSITION, lo=0, lo_open=True, hi=1.0,
        doc="position catch-up time (s): the default shift_position is the smallest with Ts x 2^shift >= "
            "tau_position x accel_current / accel_current_position; a longer one brakes earlier (no overshoot of "
            "the governed step while the reference speed w <= 2 x acceleration x tau) but closes the last gap slower"),
    Key("governor", "jerk_periods", "int", 4, lo=1, hi=1 << 16,
        doc="speed task: periods the acceleration takes to ramp to its limit"),
    Key("field_weakening", "enable", "bool", True, doc="d-current reference from the voltage margin (FW register)"),
    Key("field_weakening", "u_hi", "float", 0.90, lo=0, lo_open=True, hi=1,
        doc="|u_raw| above this x u_max: the d-current reference steps down (FW_R2.hi)"),
    Key("field_weakening", "u_lo", "float", 0.82, lo=0, lo_open=True, hi=1,
        doc="|u_raw| below this x u_max: it steps back toward 0 (FW_R2.lo; below u_hi)"),
    Key("field_weakening", "step", "float", 0.02, lo=0, lo_open=True, hi=1,
        doc="step per control period, x i_max (rounded to a power of two of Q.4 ADC LSB: EMPC_FW_SHIFT)"),
    Key("field_weakening", "i_max_frac", "float", 0.6, lo=0, lo_open=True, hi=1,
        doc="deepest d-current reference, x i_max (FW.nmax steps, 8 bit)"),
    Key("ratings", "current", "float", None, lo=0, lo_open=True, unit="A",
        doc="rated current, phase peak (default control.i_max / 2)"),
    Key("ratings", "voltage", "float", None, lo=0, lo_open=True, unit="V",
        doc="rated voltage, phase peak (default inverter.Udc / sqrt 3)"),
    Key("ratings", "speed_rpm", "float", None, lo=0, lo_open=True, unit="rpm",
        doc="rated speed, mechanical (default: no-load speed at the rated voltage, voltage / psi)"),
    Key("ratings", "position", "float", None, lo=0, lo_open=True, unit="rad",
        doc="position scale, electrical (default: angle covered at rated speed over N Ts)"),
    Key("ratings", "power", "float", None, lo=0, lo_open=True, unit="W", doc="rated power (reports only)"),
    Key("robustness", "L", "float", 0.3, lo=0, hi=0.9, doc="relative half-width of the box: Ld and Lq"),
    Key("robustness", "R", "float", 0.3, lo=0, hi=0.9),
    Key("robustness", "J", "float", 0.3, lo=0, hi=0.9, doc="total inertia (motor + load)"),
    Key("robustness", "psi", "float", 0.2, lo=0, hi=0.9),
    Key("robustness", "decay_min", "float", None, lo=0, unit="1/s",
        doc="every mode decays at least this fast: radius <= exp(-decay_min Ts) = 1 - margin "
            "(default 0.01 / T_m: no mode slower than 100 mechanical time constants)"),
    Key("robustness", "damping_min", "float", 0.05, lo=0, hi=1, doc="damping ratio of every oscillatory mode"),
    Key("robustness", "speed_points", "int", 25, lo=3, hi=1001, doc="speeds checked over Omega_e (plus 0)"),
    Key("robustness", "load", "float", 1.0, lo=0, hi=2,
        doc="the check also linearises at the loaded operating points i_q0 = +-load x ratings.current "
            "(the law's own steady state: i_d0, the plant's w L i terms, the scheduled gains on the loaded "
            "errors); 0 checks i = 0 only"),
    Key("robustness", "load_id_max", "float", 2.0, lo=0, lo_open=True, hi=1e6,
        doc="largest |i_d0| / |i_q0| of the law's steady state under load (the d current it spends "
            "per ampere of load current), at every speed of Omega_e"),
    Key("robustness", "fit_max", "float", 0.5, lo=0, lo_open=True, hi=10,
        doc="polynomial fit error (relative to the gain's peak) of a gain element that matters above "
            "which empc roms warns (the refusal is the loop check with the fitted gains)"),
    Key("weights", "units", "str", "si", choices=("pu", "si"),
        doc="pu: per unit of [ratings]; si: SI units (older files; the default when units is absent)"),
    Key("weights", "designs", "str[]", (), choices=tuple(t[len("weights."):] for t in _WEIGHT_TABLES),
        doc="designs that take the default per-unit weights (DEFAULT_WEIGHTS_PU) unless a table gives them"),
]
for _t in _WEIGHT_TABLES:
    SCHEMA += [
        Key(_t, "Q_yw", "float[3]", lo=0,
            doc="output error weight (i_d, i_q, speed/angle); 0 leaves the output out of the tracking cost "
                "(algorithm 2: i_q, whose reference 0 a load cannot follow, docs/design.md)"),
        Key(_t, "Q_dy", "float[3]", lo=0, lo_open=True, doc="output increment weight"),
        Key(_t, "Q_du", "float[2]", lo=0, lo_open=True, doc="input increment weight (u_d, u_q)"),
        Key(_t, "speed_window", "int", 0, choices=(0,) + SPEED_WINDOWS,
            doc="this design's speed window M (control.speed_window; 0 = control.speed_window): the window's "
                "lag helps one design and costs another its margin (docs/design.md), so a control-period "
                "table may set it per design; the firmware writes KACC with the design (manifest designs.kacc)"),
    ]
    if _t.startswith("weights.alg2"):
        SCHEMA += [
            Key(_t, "ebar_step_max", "float[3]", (0.0, 0.0, 0.0), lo=0,
                doc="clamp of the eq. 25 error increments (weight units; 0 = default)"),
            Key(_t, "integrate", "bool[3]", (True, True, True), doc="outputs with the second integrator"),
            Key(_t, "Q_yp", "float[3]", (0.0, 0.0, 0.0), lo=0,
                doc="weight of the output errors themselves (not integrated) over the horizon: proportional "
                    "action that does not shrink with the horizon N Ts (the integrated errors of eq. 25 give "
                    "the law a proportional part only through N Ts; docs/design.md); 0 = the paper's cost"),
        ]


def keys_of(table: str) -> dict[str, Key]:
    return {k.name: k for k in SCHEMA if k.table == table}


def _subtables(table: str) -> list[str]:
    pre = table + "."
    return [t for t in TABLES if t.startswith(pre) and "." not in t[len(pre):]]


def _fmt(v) -> str:
    """A value as it would be written in TOML."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return f"{v:.6g}" if v == v else "nan"
    if isinstance(v, str):
        return '"' + v.replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_fmt(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {_fmt(x)}" for k, x in v.items()) + "}"
    return str(v)


def _mean(name: str, options) -> str:
    m = difflib.get_close_matches(name, list(options), n=1, cutoff=0.6)
    return f"; did you mean {m[0]!r}?" if m else f" (known: {', '.join(sorted(options))})"


def _is_num(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _check_value(k: Key, v):
    """Type and range of one value; returns it converted (tuple for lists, float for floats)."""
    def scalar(x, kind, path):
        def bad(why):
            raise ConfigError(f"{path} = {_fmt(x)}: {why}; allowed: {k.range_text()}")
        if kind == "float":
            if not _is_num(x):
                bad(f"must be a number, not {type(x).__name__}")
            x = float(x)
            if not math.isfinite(x):
                bad("must be finite")
        elif kind == "int":
            if isinstance(x, bool) or not isinstance(x, int):
                bad(f"must be an integer, not {type(x).__name__}")
        elif kind == "bool":
            if not isinstance(x, bool):
                bad(f"must be true or false, not {type(x).__name__}")
            return x
        elif kind == "str":
            if not isinstance(x, str):
                bad(f"must be a string, not {type(x).__name__}")
        if k.choices and x not in k.choices:
            bad("not allowed")
        if kind in ("float", "int"):
            if k.lo is not None and (x < k.lo or (k.lo_open and x == k.lo)):
                bad("out of range")
            if k.hi is not None and (x > k.hi or (k.hi_open and x == k.hi)):
                bad("out of range")
        return x

    if k.kind == "str[]":
        if not isinstance(v, list):
            raise ConfigError(f"{k.path} = {_fmt(v)}: must be a list; allowed: {k.range_text()}")
        out = tuple(scalar(x, "str", f"{k.path}[{i}]") for i, x in enumerate(v))
        if len(set(out)) != len(out):
            raise ConfigError(f"{k.path} = {_fmt(v)}: a design is listed twice; allowed: {k.range_text()}")
        return out
    if "[" in k.kind:
        base, n = k.kind[:-1].split("[")
        n = int(n)
        if not isinstance(v, list) or len(v) != n:
            raise ConfigError(f"{k.path} = {_fmt(v)}: must be a list of {n}; allowed: {k.range_text()}")
        return tuple(scalar(x, base, f"{k.path}[{i}]") for i, x in enumerate(v))
    return scalar(v, k.kind, k.path)


# Control-period weight tables: [weights.alg<a>.<task>.Ts_<microseconds>us] holds some of the design's
# keys; when control.Ts is that period (within TS_MATCH relative) they replace the design's own.
PER_TS = "weights.per_ts"          # validate(): {design table: {name: (Ts in s, {key: value})}}
TS_MATCH = 1e-6
_PER_TS_RE = re.compile(r"^Ts_([0-9]+(?:\.[0-9]*)?)us$")


def per_ts_period(name: str) -> float | None:
    """The control period (s) a table name ``Ts_<microseconds>us`` is for; None if the name is not one."""
    m = _PER_TS_RE.match(name)
    return float(m.group(1)) * 1e-6 if m else None


def validate(d: dict) -> dict:
    """Check the raw TOML dict against :data:`SCHEMA`; returns {table: {key: value}} with defaults."""
    if not isinstance(d, dict):
        raise ConfigError("configuration must be a TOML document of tables")
    out: dict = {}

    def walk(node: dict, table: str | None):
        subs = _subtables(table) if table else [t for t in TABLES if "." not in t]
        ks = keys_of(table) if table else {}
        for name, v in node.items():
            path = f"{table}.{name}" if table else name
            if path in TABLES:
                if not isinstance(v, dict):
                    raise ConfigError(f"{path} must be a table [{path}], got {_fmt(v)}")
                walk(v, path)
            elif name in ks:
                if isinstance(v, dict):
                    raise ConfigError(f"{path} must be a value, not a table; allowed: {ks[name].range_text()}")
                out.setdefault(table, {})[name] = _check_value(ks[name], v)
            elif table in _WEIGHT_TABLES and isinstance(v, dict):
                per_ts(v, table, name)
            else:
                options = [s.split(".")[-1] for s in subs] + list(ks)
                kind = "table" if isinstance(v, dict) else "key"
                where = f"[{path}]" if kind == "table" else path
                raise ConfigError(f"unknown {kind} {where}{_mean(name, options) if options else ''}")
        if table in _WEIGHT_TABLES and node and all(isinstance(x, dict) for x in node.values()):
            return          # only control-period tables: they change the weights of weights.designs
        if table:
            out.setdefault(table, {})
            for name, k in ks.items():
                if name not in out[table]:
                    if k.default is REQUIRED:
                        raise ConfigError(f"{k.path} is missing; allowed: {k.range_text()}")
                    out[table][name] = k.default

    def per_ts(node: dict, table: str, name: str):
        """[<design>.Ts_<us>us]: some of the design's keys, used when control.Ts is that period."""
        path = f"{table}.{name}"
        ts = per_ts_period(name)
        if ts is None:
            raise ConfigError(f"unknown table [{path}]; a control-period table is named Ts_<microseconds>us "
                              f"(e.g. [{table}.Ts_50us]); the design's keys: {', '.join(keys_of(table))}")
        if ts <= 0.0:
            raise ConfigError(f"[{path}]: a control period of {ts * 1e6:g} us; allowed: > 0 us")
        ks = keys_of(table)
        got = {}
        for kname, v in node.items():
            if kname not in ks:
                kind = "table" if isinstance(v, dict) else "key"
                where = f"[{path}.{kname}]" if kind == "table" else f"{path}.{kname}"
                raise ConfigError(f"unknown {kind} {where}{_mean(kname, ks)}")
            if isinstance(v, dict):
                raise ConfigError(f"{path}.{kname} must be a value, not a table; allowed: {ks[kname].range_text()}")
            got[kname] = _check_value(replace(ks[kname], table=path), v)
        if not got:
            raise ConfigError(f"[{path}] is empty; allowed: one or more of {', '.join(ks)}")
        tabs = out.setdefault(PER_TS, {}).setdefault(table, {})
        for other, (t2, _) in tabs.items():
            if abs(t2 - ts) <= TS_MATCH * ts:
                raise ConfigError(f"[{table}.{other}] and [{path}] are both for Ts = {ts * 1e6:g} us; allowed: one table "
                                  f"per control period")
        tabs[name] = (ts, got)

    walk(d, None)
    for t, (req, _) in TABLES.items():
        if req and t not in out:
            raise ConfigError(f"table [{t}] is missing")
    return out


# ----------------------------------------------------------------------------------------------
# Data model
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Motor:
    name: str
    R: float
    Ld: float
    Lq: float
    psi: float
    p: int
    J: float                 # total inertia the design uses (motor + load)
    B: float = 0.0
    tau_c: float = 0.0
    J_load: float = 0.0      # of which load inertia


@dataclass(frozen=True)
class Inverter:
    Udc: float
    f_pwm: float
    dead_time: float = 0.0


@dataclass(frozen=True)
class Sensors:
    encoder_cpr: int
    adc_amps_per_lsb: float
    adc_offset: int = 2048
    adc_noise_lsb: float = 0.0


@dataclass(frozen=True)
class Weights:
    Q_yw: tuple[float, float, float]
    Q_dy: tuple[float, float, float]
    Q_du: tuple[float, float]
    ebar_step_max: tuple[float, float, float] = (0.0, 0.0, 0.0)   # algorithm 2, eq. 25 clamps (0 = default)
    integrate: tuple[bool, bool, bool] = (True, True, True)        # algorithm 2: outputs with the 2nd integrator
    Q_yp: tuple[float, float, float] = (0.0, 0.0, 0.0)             # algorithm 2: weight of the errors (not integrated)


@dataclass(frozen=True)
class Ratings:
    """Per-unit bases.  current I_b (A, phase peak), voltage U_b (V, phase peak), speed w_b
    (electrical rad/s), position th_b (electrical rad); ``derived`` names the ones not given."""
    current: float
    voltage: float
    speed: float
    position: float
    power: float | None = None
    derived: tuple = ()

    def ybase(self, task: str) -> tuple[float, float, float]:
        return (self.current, self.current, self.speed if task == "speed" else self.position)


@dataclass(frozen=True)
class Robustness:
    L: float
    R: float
    J: float
    psi: float
    decay_min: float | None     # None: 0.01 / T_m (robust.decay_min)
    damping_min: float
    speed_points: int
    fit_max: float
    load: float                 # loaded operating points i_q0 = +-load x ratings.current (0: i = 0 only)
    load_id_max: float          # bound on |i_d0| / |i_q0| of the law's loaded steady state


@dataclass(frozen=True)
class Governor:
    """Reference governor in the reference generator (current limit, issue 15 item 4).

    The task reference is shaped, N periods ahead of its use, into a trajectory whose
    acceleration needs at most ``accel_current`` x i_max at the robustness-box corner
    (inertia x ``box_J``, flux x ``box_psi``), with the position reference's speed at most
    ``speed_frac`` of the no-load base speed u_max / psi (and of Omega_e); the reference
    does not raise its |speed| (speed task: its acceleration decays, a demand towards lower |speed|
    passes) or its speed (position) while |i_q| > ``hold_current`` x i_max or the voltage limiter
    was active.  The position catch-up ``shift_position`` defaults to
    :func:`governor.default_shift_position` of control.Ts (at least ``tau_position`` at every Ts).
    ``accel_current_position`` (default ``accel_current``) is the position task's own: a design
    whose position loop rings at a box corner needs less (premo_320v, docs/design.md).
    See gen/empc/governor.py."""
    enable: bool
    accel_current: float
    accel_current_position: float
    box_J: float
    box_psi: float
    speed_frac: float
    hold_current: float
    shift_speed: int
    shift_position: int
    tau_position: float
    jerk_periods: int


@dataclass(frozen=True)
class FieldWeakening:
    """Field weakening from the voltage margin (issue 15 item 6): the d-current reference
    moves by ``step`` x i_max per control period toward -``i_max_frac`` x i_max while
    |u_raw| > ``u_hi`` x u_max, back toward 0 while |u_raw| < ``u_lo`` x u_max."""
    enable: bool
    u_hi: float
    u_lo: float
    step: float
    i_max_frac: float


@dataclass(frozen=True)
class Control:
    algorithm: int
    task: str
    N: int
    Ts: float
    omega_min: float
    omega_max: float
    omega_points: int
    design_quantised: bool
    voltage_limit: str
    i_max: float
    speed_estimate: str
    weights: dict = field(default_factory=dict)   # {(alg, task): Weights}, SI units
    weight_units: str = "si"                      # how the configuration gave them
    speed_load_shift: int = 6                     # "accel_load": load estimate gain 2^-shift per period
    speed_window: int = 1                         # speed estimate over M periods (estimator.py; RTL: KACC.win):
                                                  # this design's (algorithm, task), see window_of
    speed_window_default: int = 1                 # control.speed_window: designs without their own
    speed_windows: dict = field(default_factory=dict)   # {(alg, task): M} a design table's speed_window
    governor: Governor = field(default_factory=Governor)
    field_weakening: FieldWeakening = field(default_factory=FieldWeakening)
    weight_tables: dict = field(default_factory=dict)   # {(alg, task): "weights.alg2.speed.Ts_50us"} where a
                                                        # control-period table gave (some of) the weights

    def window_of(self, algorithm: int, task: str) -> int:
        """The speed window M of one design: its table's speed_window, else control.speed_window."""
        return self.speed_windows.get((algorithm, task), self.speed_window_default)

    def weights_for(self, algorithm: int | None = None, task: str | None = None) -> Weights:
        key = (algorithm or self.algorithm, task or self.task)
        try:
            return self.weights[key]
        except KeyError:
            raise ConfigError(f"weights.alg{key[0]}.{key[1]} missing from the configuration") from None


RTL_SPEED_WINDOWS = SPEED_WINDOWS      # control.speed_window values the RTL implements (rtl/mx_seq.v: KACC.win,
                                       # a formats.WIN_DEPTH-deep position history per axis)


def require_rtl_speed_window(cfg) -> None:
    """Refuse a configuration whose speed window the RTL does not implement (ROMs, the RTL's model):
    M not in RTL_SPEED_WINDOWS, or a load estimate with speed_load_shift + 1 < log2 M (the sequencer's
    load update shifts right by log2 M, then by speed_load_shift + 1 - log2 M: rtlmodel/ctrl_seq.py)."""
    c = cfg.control
    for key, M in [(None, c.speed_window), (None, c.speed_window_default), *sorted(c.speed_windows.items())]:
        what = "control.speed_window" if key is None else (c.weight_tables.get(key) or f"weights.alg{key[0]}.{key[1]}") + ".speed_window"
        if M not in RTL_SPEED_WINDOWS:
            raise ConfigError(f"{what} = {M}: the RTL implements {', '.join(map(str, RTL_SPEED_WINDOWS))} "
                              f"only (the window is modelled in the float/fixed controllers and the design check)")
        m = M.bit_length() - 1
        if cfg.speed_load_shift and cfg.speed_load_shift + 1 < m:
            raise ConfigError(f"{what} = {M} needs control.speed_load_shift >= {m - 1} "
                              f"(is {cfg.speed_load_shift}): the RTL's load update shifts by speed_load_shift + 1 - log2 M")


@dataclass(frozen=True)
class Config:
    motor: Motor
    inverter: Inverter
    sensors: Sensors
    f_clk: float
    control: Control
    source: str = "<default>"
    ratings: Ratings | None = None
    robustness: Robustness = field(default_factory=Robustness)

    # --- derived quantities shared by the generator, the models and the tests ---
    @property
    def pwm_half_period(self) -> int:
        """Centre-aligned PWM: the counter runs 0..P..0, P clock ticks each way."""
        return int(round(self.f_clk / self.inverter.f_pwm / 2))

    @property
    def pwm_per_control(self) -> int:
        """Control period Ts as a whole number of PWM periods."""
        return int(round(self.control.Ts * self.inverter.f_pwm))

    @property
    def volts_per_tick(self) -> float:
        return self.inverter.Udc / self.pwm_half_period

    @property
    def amps_per_lsb(self) -> float:
        return self.sensors.adc_amps_per_lsb

    @property
    def rad_per_count(self) -> float:
        """Electrical radians per encoder count."""
        return 2 * math.pi * self.motor.p / self.sensors.encoder_cpr

    @property
    def rad_s_per_count_ts(self) -> float:
        """Electrical rad/s per (encoder count per control period)."""
        return self.rad_per_count / self.control.Ts

    @property
    def speed_correction(self) -> float:
        """Half-period acceleration term added to the backward difference (eq. 37), rad/s per A of i_q.

        Eq. 37 is the mean speed over the last period, i.e. the speed half a period ago;
        the model state wants the speed now.  The torque equation gives the missing
        (Ts/2) * dw/dt = (Ts/2) * 1.5 p^2 psi / J * i_q.  0 when speed_estimate = "eq37".
        Over a window of M = ``control.speed_window`` periods the difference is the speed (M/2) Ts
        ago and the term is (M Ts/2) * 1.5 p^2 psi / J * i_q.
        With "accel_load" a load estimate removes the part of i_q that holds a load
        (gen/empc/estimator.py), so that the estimate is offset-free under load.
        """
        if self.control.speed_estimate not in ("accel", "accel_load"):
            return 0.0
        m = self.motor
        kc = 0.5 * self.control.Ts * 1.5 * m.p * m.p * m.psi / m.J
        return kc * self.control.speed_window if self.control.speed_window != 1 else kc

    @property
    def speed_load_shift(self) -> int:
        """Load-estimate gain 2^-shift of the "accel_load" estimate; 0 = no load estimate."""
        return self.control.speed_load_shift if self.control.speed_estimate == "accel_load" else 0

    @property
    def u_max(self) -> float:
        """Voltage limit in volts: circle Udc/sqrt(3)."""
        return self.inverter.Udc / math.sqrt(3.0)

    @property
    def adc_range_amps(self) -> float:
        """Largest current both signs of the 12-bit ADC measure around the offset."""
        from .formats import ADC_BITS
        off = self.sensors.adc_offset
        return min(off, (1 << ADC_BITS) - 1 - off) * self.sensors.adc_amps_per_lsb

    def with_control(self, **kw) -> "Config":
        """A copy with control fields replaced.  ``speed_window`` given: M for every design (the design
        tables' own are dropped); ``algorithm`` / ``task`` given: the speed window follows the design."""
        c = self.control
        if "speed_window" in kw:
            kw.setdefault("speed_window_default", kw["speed_window"])
            kw.setdefault("speed_windows", {})
        elif "algorithm" in kw or "task" in kw:
            kw["speed_window"] = c.window_of(kw.get("algorithm", c.algorithm), kw.get("task", c.task))
        return replace(self, control=replace(c, **kw))

    def for_design(self, algorithm: int, task: str) -> "Config":
        """This configuration as one design (algorithm, task) runs it: control.speed_window is the
        design's (Control.window_of); algorithm and task themselves are unchanged."""
        m = self.control.window_of(algorithm, task)
        return self if m == self.control.speed_window else replace(self, control=replace(self.control, speed_window=m))

    def with_motor(self, **kw) -> "Config":
        return replace(self, motor=replace(self.motor, **kw))

    def bases(self, task: str) -> "Bases":
        """Per-unit bases of the weights of a ``task`` design (:func:`pu_bases`)."""
        return pu_bases(self.ratings, self.motor, self.control.Ts, task)

    def weights_pu(self, algorithm: int, task: str) -> "Weights":
        return weights_pu(self.control.weights_for(algorithm, task), self.bases(task))


# ----------------------------------------------------------------------------------------------
# Per-unit weights
# ----------------------------------------------------------------------------------------------
# Defaults for a configuration without [weights] (per unit of the ratings; see weights_si).
DEFAULT_WEIGHTS_PU = {
    (1, "speed"): Weights(Q_yw=(38.0, 23.0, 2.0e4), Q_dy=(230.0, 2500.0, 190.0), Q_du=(1200.0, 1200.0)),
    (1, "position"): Weights(Q_yw=(4.3, 8.0, 59.0), Q_dy=(2.6, 8.5, 29.0), Q_du=(26.0, 55.0)),
    (2, "speed"): Weights(Q_yw=(400.0, 0.0, 6233.0), Q_dy=(2.474, 14.85, 4024.0), Q_du=(8400.0, 4200.0),
                          ebar_step_max=(0.0, 0.0, 0.05776), integrate=(False, False, True)),
    (2, "position"): Weights(Q_yw=(72.0, 0.325, 47.37), Q_dy=(7.918, 17.32, 70.63), Q_du=(34.02, 13.02),
                             ebar_step_max=(0.0, 0.0, 0.04813), integrate=(False, False, True)),
}


@dataclass(frozen=True)
class Bases:
    """Per-unit bases of one design's weights (see :func:`pu_bases`)."""
    y: tuple          # outputs: i_d, i_q, speed or angle
    dy: tuple         # output increments per control period
    du: float         # voltage increments per control period
    tau_i: float      # L_q I_b / U_b: time the rated voltage takes to move the current by I_b
    T_m: float        # J w_b / (1.5 p^2 psi I_b): time the rated current takes to reach the rated speed


def pu_bases(ratings: Ratings, motor: Motor, Ts: float, task: str) -> Bases:
    """Bases of the per-unit weights.  Outputs are per unit of the ratings (I_b, I_b, w_b or th_b).
    Increments over one control period are per unit of the rated rate of change times Ts: currents
    I_b Ts / tau_i, speed w_b Ts / T_m (rated acceleration); voltage increments per unit of
    L_q I_b / Ts (the step that moves the current by I_b in one period); angle increments per unit
    of Ts sqrt(w_b th_b / T_m), which is w_b Ts sqrt(N Ts / T_m) with the default th_b = w_b N Ts:
    the proportional (th_b) and derivative (angle increment) parts of the position law then scale
    together, so the position loop's frequency follows 1 / T_m with the same damping for motors
    whose T_m is 5 or 5000 times the horizon N Ts.  With these bases the weights are free of the
    motor's size, of its electrical and mechanical time constants and of Ts, so one set of defaults
    serves motors of very different size."""
    tau_i = motor.Lq * ratings.current / ratings.voltage
    T_m = motor.J * ratings.speed / (1.5 * motor.p * motor.p * motor.psi * ratings.current)
    y = ratings.ybase(task)
    if task == "speed":
        d3 = ratings.speed * Ts / T_m
    else:
        d3 = Ts * math.sqrt(ratings.speed * ratings.position / T_m)
    dy = (ratings.current * Ts / tau_i, ratings.current * Ts / tau_i, d3)
    return Bases(y=y, dy=dy, du=motor.Lq * ratings.current / Ts, tau_i=tau_i, T_m=T_m)


def weights_si(w: Weights, b: Bases) -> Weights:
    """Per-unit weights -> SI.  A weight q on a quantity with base B penalises (q x / B)^2, so
    q_SI = q_pu / B; the eq. 25 clamps are values (x_SI = x_pu B)."""
    return replace(w, Q_yw=tuple(q / x for q, x in zip(w.Q_yw, b.y)),
                   Q_dy=tuple(q / x for q, x in zip(w.Q_dy, b.dy)),
                   Q_du=tuple(q / b.du for q in w.Q_du),
                   ebar_step_max=tuple(x * y for x, y in zip(w.ebar_step_max, b.y)),
                   Q_yp=tuple(q / x for q, x in zip(w.Q_yp, b.y)))


def weights_pu(w: Weights, b: Bases) -> Weights:
    """Inverse of :func:`weights_si`."""
    return replace(w, Q_yw=tuple(q * x for q, x in zip(w.Q_yw, b.y)),
                   Q_dy=tuple(q * x for q, x in zip(w.Q_dy, b.dy)),
                   Q_du=tuple(q * b.du for q in w.Q_du),
                   ebar_step_max=tuple(x / y for x, y in zip(w.ebar_step_max, b.y)),
                   Q_yp=tuple(q * x for q, x in zip(w.Q_yp, b.y)))


def derive_ratings(r: dict, motor: Motor, inverter: Inverter, i_max: float, horizon: float) -> Ratings:
    """Ratings from [ratings], the missing ones derived (and named in ``derived``):
    current = i_max / 2; voltage = Udc / sqrt 3 (the voltage circle); speed = voltage / psi
    (no-load speed at the rated voltage, electrical); position = speed * horizon (the angle the
    rotor covers at rated speed over the prediction horizon N Ts, the scale of position errors
    the law sees; see pu_bases)."""
    derived = []
    cur = r.get("current")
    if cur is None:
        cur, _ = i_max / 2.0, derived.append("current")
    volt = r.get("voltage")
    if volt is None:
        volt, _ = inverter.Udc / math.sqrt(3.0), derived.append("voltage")
    rpm = r.get("speed_rpm")
    if rpm is None:
        speed, _ = volt / motor.psi, derived.append("speed")
    else:
        speed = rpm * 2 * math.pi / 60.0 * motor.p
    pos = r.get("position")
    if pos is None:
        pos, _ = speed * horizon, derived.append("position")
    return Ratings(current=cur, voltage=volt, speed=speed, position=pos, power=r.get("power"), derived=tuple(derived))


# ----------------------------------------------------------------------------------------------
# RTL field limits of derived quantities: (name, value(cfg), lo, hi, keys, what)
# ----------------------------------------------------------------------------------------------
def _rtl_limits():
    from . import formats as F
    from .regmap import axis_reg

    ctrl_ppc = next(f for f in axis_reg("CTRL").fields if f.name == "pwm_per_control")
    kacc = axis_reg("KACC")
    kacc_w = next(f for f in kacc.fields if f.name == "kacc").width
    kacc_sh = next(f for f in kacc.fields if f.name == "shift").width
    dead_w = axis_reg("DEAD_TIME").width
    vmax = (1 << (F.V_W - 1)) - 1

    def kacc_raw(cfg):
        from .header import speed_correction_raw
        return speed_correction_raw(cfg)

    fw_nmax_w = axis_reg("FW").fields[0].width
    fw_r2_w = next(f for f in axis_reg("FW_R2").fields if f.name == "hi").width
    iq_hold_w = axis_reg("IQ_HOLD").width

    def fw(cfg):
        from .header import field_weakening_raw
        return field_weakening_raw(cfg)

    def gov_vmax(cfg):
        from .governor import raw_params
        return max(raw_params(cfg, t)["vmax"] for t in ("speed", "position"))

    def counts_per_ts(cfg):
        c = cfg.control
        return max(abs(c.omega_min), abs(c.omega_max)) / cfg.rad_s_per_count_ts

    return [
        ("PWM periods per control period (CTRL.pwm_per_control, %d bit)" % ctrl_ppc.width,
         lambda cfg: cfg.control.Ts * cfg.inverter.f_pwm, 1, (1 << ctrl_ppc.width) - 1, ("control.Ts", "inverter.f_pwm")),
        ("PWM half period in clocks x 2^V_FRAC (phase voltages after eq. 36 span up to it, Q14.4 in %d bit)" % F.V_W,
         lambda cfg: cfg.pwm_half_period * (1 << F.V_FRAC), 0, vmax, ("inverter.f_pwm", "fpga.f_clk")),
        ("PWM half period in clocks (the work of a control period, from the boundary's reference advance "
         "to the compare values (rtl/mx_seq.v), must end before the next PWM boundary)",
         lambda cfg: cfg.pwm_half_period, SEQ_LATENCY_MAX, None, ("inverter.f_pwm", "fpga.f_clk")),
        ("encoder counts per control period at max |Omega_e| (speed word Q16.16 in %d bit)" % F.W_W,
         counts_per_ts, 0, (1 << (F.W_W - F.W_FRAC - 1)) - 1,
         ("control.omega_min", "control.omega_max", "sensors.encoder_cpr", "control.Ts")),
        ("speed-estimate gain KACC (%d-bit signed field)" % kacc_w,
         lambda cfg: kacc_raw(cfg)[0], -(1 << (kacc_w - 1)), (1 << (kacc_w - 1)) - 1,
         ("control.speed_estimate", "motor.J", "motor.psi", "control.Ts")),
        ("KACC shift (%d-bit field)" % kacc_sh, lambda cfg: kacc_raw(cfg)[1], 0, (1 << kacc_sh) - 1,
         ("control.speed_estimate", "motor.J", "motor.psi")),
        ("dead time in clocks (DEAD_TIME, %d bit)" % dead_w,
         lambda cfg: cfg.inverter.dead_time * cfg.f_clk, 0, (1 << dead_w) - 1, ("inverter.dead_time", "fpga.f_clk")),
        ("field-weakening steps FW.nmax (%d bit; 1 at least when enabled)" % fw_nmax_w,
         lambda cfg: fw(cfg)["FW_NMAX"] if cfg.control.field_weakening.enable else 1, 1, (1 << fw_nmax_w) - 1,
         ("field_weakening.i_max_frac", "field_weakening.step", "control.i_max", "sensors.adc_amps_per_lsb")),
        ("field-weakening step shift EMPC_FW_SHIFT (Q.4 ADC LSB)", lambda cfg: fw(cfg)["FW_SHIFT"], 0, 15,
         ("field_weakening.step", "control.i_max", "sensors.adc_amps_per_lsb")),
        ("field-weakening threshold FW_R2.hi (|u|^2 >> 20 in PWM ticks Q.4, %d bit)" % fw_r2_w,
         lambda cfg: fw(cfg)["FW_R2_HI"], 0, (1 << fw_r2_w) - 1, ("field_weakening.u_hi", "inverter.f_pwm", "fpga.f_clk")),
        ("governor hold current IQ_HOLD in ADC LSB (%d bit)" % iq_hold_w,
         lambda cfg: cfg.control.governor.hold_current * cfg.control.i_max / cfg.sensors.adc_amps_per_lsb,
         0, (1 << iq_hold_w) - 1, ("governor.hold_current", "control.i_max", "sensors.adc_amps_per_lsb")),
        ("governor speed / acceleration limit vmax (Q.32 of the task unit, 63 bit)", gov_vmax, 1, (1 << 63) - 1,
         ("governor.accel_current", "governor.accel_current_position", "governor.speed_frac", "motor.J", "control.Ts",
          "sensors.encoder_cpr")),
        ("current limit in ADC LSB (the 12-bit ADC measures +-min(offset, 4095 - offset) LSB)",
         lambda cfg: cfg.control.i_max / cfg.sensors.adc_amps_per_lsb,
         0, None, ("control.i_max", "sensors.adc_amps_per_lsb", "sensors.adc_offset")),
    ]


# clocks: bound on a control period's work per half period.  It was the latency of the bit-serial
# ctrl_seq (N = 4: 994 with the governor and the load estimate); rtl/mx_seq.v splits it: the boundary's
# reference advance and prefetch before the sample, trigger -> cmp_load after it (about 270 at N = 4,
# docs/blocks/mx_seq.md).  Kept at the old bound: no configuration that passed before is refused.
SEQ_LATENCY_MAX = 1200


def check_rtl_limits(cfg) -> None:
    for what, f, lo, hi, keys in _rtl_limits():
        v = f(cfg)
        if what.startswith("current limit"):
            hi = cfg.adc_range_amps / cfg.sensors.adc_amps_per_lsb
        if (lo is not None and v < lo) or (hi is not None and v > hi):
            rng = f"{lo:g} .. {hi:g}" if lo is not None and hi is not None else (f">= {lo:g}" if lo is not None else f"<= {hi:g}")
            vals = ", ".join(f"{k} = {_fmt(_lookup(cfg, k))}" for k in keys)
            raise ConfigError(f"{vals}: {what} = {v:.6g} is outside {rng}")


def _lookup(cfg, dotted: str):
    t, k = dotted.split(".")
    obj = {"motor": cfg.motor, "inverter": cfg.inverter, "sensors": cfg.sensors, "control": cfg.control,
           "governor": cfg.control.governor, "field_weakening": cfg.control.field_weakening}.get(t)
    if t == "fpga":
        return cfg.f_clk
    return getattr(obj, k)


def _table(v: dict, table: str) -> dict:
    """The validated keys of ``table`` with the schema's defaults (also when the table is absent)."""
    got = v.get(table) or {}
    return {name: got.get(name, k.default) for name, k in keys_of(table).items()}


# ----------------------------------------------------------------------------------------------
def from_dict(d: dict, source: str = "<dict>") -> Config:
    v = validate(d)
    m = v["motor"]
    motor = Motor(name=m["name"], R=m["R"], Ld=m["Ld"], Lq=m["Lq"], psi=m["psi"], p=m["p"],
                  J=m["J"] + m["J_load"], B=m["B"], tau_c=m["tau_c"], J_load=m["J_load"])
    i = v["inverter"]
    inverter = Inverter(Udc=i["Udc"], f_pwm=i["f_pwm"], dead_time=i["dead_time"])
    s = v["sensors"]
    sensors = Sensors(encoder_cpr=s["encoder_cpr"], adc_amps_per_lsb=s["adc_amps_per_lsb"],
                      adc_offset=s["adc_offset"], adc_noise_lsb=s["adc_noise_lsb"])
    f_clk = v["fpga"]["f_clk"] if "fpga" in v else 100e6
    c = v["control"]
    if c["omega_max"] <= c["omega_min"]:
        raise ConfigError(f"control.omega_min = {_fmt(c['omega_min'])}, control.omega_max = {_fmt(c['omega_max'])}: "
                          f"Omega_e is empty; allowed: omega_min < omega_max")
    ratings = derive_ratings(v.get("ratings", {}), motor, inverter, c["i_max"], c["N"] * c["Ts"])
    robustness = Robustness(**_table(v, "robustness"))   # defaults: the schema (one source)
    gv = _table(v, "governor")
    from .governor import default_shift_position
    acp = gv["accel_current"] if gv["accel_current_position"] is None else gv["accel_current_position"]
    governor = Governor(**dict(gv, box_J=1.0 + robustness.J if gv["box_J"] is None else gv["box_J"],
                               box_psi=1.0 - robustness.psi if gv["box_psi"] is None else gv["box_psi"],
                               accel_current_position=acp,
                               shift_position=(default_shift_position(c["Ts"], gv["accel_current"] / acp,
                                                                      gv["tau_position"])
                                               if gv["shift_position"] is None else gv["shift_position"])))
    if governor.box_psi <= 0.0:
        raise ConfigError(f"robustness.psi = {_fmt(robustness.psi)}: the governor's flux corner 1 - psi is not "
                          f"positive; allowed: robustness.psi < 1 or governor.box_psi given")
    fw = FieldWeakening(**_table(v, "field_weakening"))
    if fw.u_lo >= fw.u_hi:
        raise ConfigError(f"field_weakening.u_lo = {_fmt(fw.u_lo)}, field_weakening.u_hi = {_fmt(fw.u_hi)}: "
                          f"the band is empty; allowed: u_lo < u_hi")
    wv = v.get("weights")
    weights, units, weight_tables, windows = {}, "pu", {}, {}
    if wv is None:
        weights = {k: weights_si(w, pu_bases(ratings, motor, c["Ts"], k[1])) for k, w in DEFAULT_WEIGHTS_PU.items()}
    else:
        units = wv["units"]
        per_ts = v.get(PER_TS, {})
        for t in _WEIGHT_TABLES:
            a, task = int(t.split(".")[1][3:]), t.split(".")[2]
            listed = t[len("weights."):] in wv["designs"]
            tabs = per_ts.get(t, {})
            if t in v:
                sec, pu = dict(v[t]), units == "pu"
            elif listed:
                dw = DEFAULT_WEIGHTS_PU[(a, task)]
                sec, pu = {k: getattr(dw, k) for k in ("Q_yw", "Q_dy", "Q_du", "ebar_step_max", "integrate",
                                                        "Q_yp")}, True
                if tabs and units != "pu":
                    raise ConfigError(f"[{t}.{next(iter(tabs))}] changes the default per-unit weights of "
                                      f"weights.designs; allowed: weights.units = \"pu\"")
            elif tabs:
                raise ConfigError(f"[{t}.{next(iter(tabs))}] has no weights to change: give [{t}] or list "
                                  f"\"{t[len('weights.'):]}\" in weights.designs")
            else:
                continue
            src = t
            for name, (ts, got) in tabs.items():
                if abs(ts - c["Ts"]) <= TS_MATCH * ts:
                    sec.update(got)
                    src = f"{t}.{name}"
            if not any(sec.get("integrate", (True,))):
                raise ConfigError(f"{src}.integrate = {_fmt(sec['integrate'])}: must integrate at least one "
                                  f"output; allowed: a list of 3 booleans, one or more true")
            if sec.get("speed_window"):
                windows[(a, task)] = sec["speed_window"]
            w = Weights(Q_yw=sec["Q_yw"], Q_dy=sec["Q_dy"], Q_du=sec["Q_du"],
                        ebar_step_max=sec.get("ebar_step_max", (0.0, 0.0, 0.0)),
                        integrate=sec.get("integrate", (True, True, True)), Q_yp=sec.get("Q_yp", (0.0, 0.0, 0.0)))
            weights[(a, task)] = weights_si(w, pu_bases(ratings, motor, c["Ts"], task)) if pu else w
            if src != t:
                weight_tables[(a, task)] = src
    alg, task = c["algorithm"], c["task"]
    if (alg, task) not in weights:
        raise ConfigError(f"[weights.alg{alg}.{task}] is missing (needed by control.algorithm = {alg}, "
                          f"control.task = {task!r})")
    control = Control(
        algorithm=alg, task=task, N=c["N"], Ts=c["Ts"], omega_min=c["omega_min"], omega_max=c["omega_max"],
        omega_points=c["omega_points"], design_quantised=c["design_quantised"], voltage_limit=c["voltage_limit"],
        i_max=c["i_max"], speed_estimate=c["speed_estimate"], weights=weights, weight_units=units,
        speed_load_shift=c["speed_load_shift"], speed_window=windows.get((alg, task), c["speed_window"]), speed_window_default=c["speed_window"],
        speed_windows=windows, governor=governor, field_weakening=fw, weight_tables=weight_tables)
    cfg = Config(motor=motor, inverter=inverter, sensors=sensors, f_clk=f_clk, control=control, source=source,
                 ratings=ratings, robustness=robustness)
    ratio = c["Ts"] * inverter.f_pwm
    if abs(ratio - round(ratio)) > 1e-6 or round(ratio) < 1:
        raise ConfigError(f"control.Ts = {_fmt(c['Ts'])}, inverter.f_pwm = {_fmt(inverter.f_pwm)}: Ts is {ratio:.6g} PWM "
                          f"periods; allowed: a whole number of PWM periods >= 1")
    check_rtl_limits(cfg)
    return cfg


def parse_value(text: str):
    """A command-line value as TOML would read it (``--set motor.R=0.5``)."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def load(path: str | Path | None = None, overrides: dict | None = None) -> Config:
    p = Path(path) if path else DEFAULT_CONFIG
    try:
        d = tomllib.loads(p.read_text())
    except FileNotFoundError:
        raise ConfigError(f"configuration file not found: {p}") from None
    except (OSError, UnicodeDecodeError) as e:
        raise ConfigError(f"{p}: cannot read the configuration: {e}") from None
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(f"{p}: not valid TOML: {e}") from None
    if overrides:
        d = copy.deepcopy(d)
        for dotted, v in overrides.items():
            cur = d
            *head, last = dotted.split(".")
            for k in head:
                nxt = cur.setdefault(k, {})
                if not isinstance(nxt, dict):
                    raise ConfigError(f"--set {dotted}: {k} is a value, not a table")
                cur = nxt
            cur[last] = v
    return from_dict(d, source=str(p))


def display_path(source: str) -> str:
    """A configuration path as users see it: relative to the package or repository when possible."""
    p = Path(source)
    for base in (Path(__file__).resolve().parents[2], Path.cwd()):
        try:
            return str(p.resolve().relative_to(base))
        except (ValueError, OSError):
            continue
    return source


def default() -> Config:
    return load(None)
