"""Configuration (TOML): motor, inverter, sensors, FPGA clock, MPC design.

``load(path)`` returns a validated :class:`Config`; bad input raises
:class:`ConfigError` naming the parameter and its value.  The default is the
paper's BLWR233D set-up (``configs/blwr233d.toml``).
"""
from __future__ import annotations

import copy
import math
import tomllib
from dataclasses import dataclass, field, replace
from pathlib import Path

DEFAULT_CONFIG = Path(__file__).with_name("configs") / "blwr233d.toml"


class ConfigError(ValueError):
    """A configuration value is invalid; the message names it."""


@dataclass(frozen=True)
class Motor:
    name: str
    R: float
    Ld: float
    Lq: float
    psi: float
    p: int
    J: float
    B: float = 0.0
    tau_c: float = 0.0


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


@dataclass(frozen=True)
class Governor:
    """Reference governor in the reference generator (current limit, issue 15 item 4).

    The task reference is shaped, N periods ahead of its use, into a trajectory whose
    acceleration needs at most ``accel_current`` x i_max at the robustness-box corner
    (inertia x ``box_J``, flux x ``box_psi``), with the position reference's speed at most
    ``speed_frac`` of the no-load base speed u_max / psi (and of Omega_e); the reference
    holds its acceleration (speed) or speed (position) while |i_q| > ``hold_current`` x i_max
    or the voltage limiter was active.  See gen/empc/governor.py."""
    enable: bool = True
    accel_current: float = 0.5
    box_J: float = 1.3
    box_psi: float = 0.8
    speed_frac: float = 0.7
    hold_current: float = 0.7
    shift_speed: int = 3
    shift_position: int = 4
    jerk_periods: int = 4


@dataclass(frozen=True)
class FieldWeakening:
    """Field weakening from the voltage margin (issue 15 item 6): the d-current reference
    moves by ``step`` x i_max per control period toward -``i_max_frac`` x i_max while
    |u_raw| > ``u_hi`` x u_max, back toward 0 while |u_raw| < ``u_lo`` x u_max."""
    enable: bool = True
    u_hi: float = 0.90
    u_lo: float = 0.82
    step: float = 0.02
    i_max_frac: float = 0.6


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
    weights: dict = field(default_factory=dict)   # {(alg, task): Weights}
    speed_load_shift: int = 6                     # "accel_load": load estimate gain 2^-shift per period
    governor: Governor = field(default_factory=Governor)
    field_weakening: FieldWeakening = field(default_factory=FieldWeakening)

    def weights_for(self, algorithm: int | None = None, task: str | None = None) -> Weights:
        key = (algorithm or self.algorithm, task or self.task)
        try:
            return self.weights[key]
        except KeyError:
            raise ConfigError(f"weights.alg{key[0]}.{key[1]} missing from the configuration") from None


@dataclass(frozen=True)
class Config:
    motor: Motor
    inverter: Inverter
    sensors: Sensors
    f_clk: float
    control: Control
    source: str = "<default>"

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
        With "accel_load" a load estimate removes the part of i_q that holds a load
        (gen/empc/estimator.py), so that the estimate is offset-free under load.
        """
        if self.control.speed_estimate not in ("accel", "accel_load"):
            return 0.0
        m = self.motor
        return 0.5 * self.control.Ts * 1.5 * m.p * m.p * m.psi / m.J

    @property
    def speed_load_shift(self) -> int:
        """Load-estimate gain 2^-shift of the "accel_load" estimate; 0 = no load estimate."""
        return self.control.speed_load_shift if self.control.speed_estimate == "accel_load" else 0

    @property
    def u_max(self) -> float:
        """Voltage limit in volts: circle Udc/sqrt(3)."""
        return self.inverter.Udc / math.sqrt(3.0)

    def with_control(self, **kw) -> "Config":
        return replace(self, control=replace(self.control, **kw))

    def with_motor(self, **kw) -> "Config":
        return replace(self, motor=replace(self.motor, **kw))


def _req(d: dict, key: str, section: str):
    if key not in d:
        raise ConfigError(f"{section}.{key} is missing")
    return d[key]


def _positive(value, name: str, allow_zero: bool = False):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ConfigError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        raise ConfigError(f"{name} must be {'non-negative' if allow_zero else 'positive'}, got {value!r}")
    return v


def _vector(value, n: int, name: str, positive: bool = True) -> tuple:
    if not isinstance(value, (list, tuple)) or len(value) != n:
        raise ConfigError(f"{name} must be a list of {n} numbers, got {value!r}")
    return tuple(_positive(v, f"{name}[{i}]", allow_zero=not positive) for i, v in enumerate(value))


def _bools(value, n: int, name: str) -> tuple:
    if not isinstance(value, (list, tuple)) or len(value) != n or not all(isinstance(v, bool) for v in value):
        raise ConfigError(f"{name} must be a list of {n} booleans, got {value!r}")
    if not any(value):
        raise ConfigError(f"{name} must integrate at least one output, got {value!r}")
    return tuple(value)


def _fraction(value, name: str, lo: float = 0.0, hi: float = 1.0):
    v = _positive(value, name, allow_zero=True)
    if not lo < v <= hi:
        raise ConfigError(f"{name} must be in ({lo}, {hi}], got {value!r}")
    return v


def _int_in(value, name: str, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
        raise ConfigError(f"{name} must be an integer in {lo}..{hi}, got {value!r}")
    return value


def _flag(value, name: str) -> bool:
    if not isinstance(value, bool):
        raise ConfigError(f"{name} must be true or false, got {value!r}")
    return value


def _governor(d: dict) -> Governor:
    g = Governor()
    if not isinstance(d, dict):
        raise ConfigError(f"[governor] must be a table, got {d!r}")
    unknown = set(d) - set(g.__dataclass_fields__)
    if unknown:
        raise ConfigError(f"governor.{sorted(unknown)[0]} is not a governor setting")
    return Governor(
        enable=_flag(d.get("enable", g.enable), "governor.enable"),
        accel_current=_fraction(d.get("accel_current", g.accel_current), "governor.accel_current"),
        box_J=_positive(d.get("box_J", g.box_J), "governor.box_J"),
        box_psi=_fraction(d.get("box_psi", g.box_psi), "governor.box_psi"),
        speed_frac=_fraction(d.get("speed_frac", g.speed_frac), "governor.speed_frac"),
        hold_current=_fraction(d.get("hold_current", g.hold_current), "governor.hold_current"),
        shift_speed=_int_in(d.get("shift_speed", g.shift_speed), "governor.shift_speed", 0, 31),
        shift_position=_int_in(d.get("shift_position", g.shift_position), "governor.shift_position", 0, 31),
        jerk_periods=_int_in(d.get("jerk_periods", g.jerk_periods), "governor.jerk_periods", 1, 1 << 16),
    )


def _field_weakening(d: dict) -> FieldWeakening:
    f = FieldWeakening()
    if not isinstance(d, dict):
        raise ConfigError(f"[field_weakening] must be a table, got {d!r}")
    unknown = set(d) - set(f.__dataclass_fields__)
    if unknown:
        raise ConfigError(f"field_weakening.{sorted(unknown)[0]} is not a field-weakening setting")
    fw = FieldWeakening(
        enable=_flag(d.get("enable", f.enable), "field_weakening.enable"),
        u_hi=_fraction(d.get("u_hi", f.u_hi), "field_weakening.u_hi"),
        u_lo=_fraction(d.get("u_lo", f.u_lo), "field_weakening.u_lo"),
        step=_fraction(d.get("step", f.step), "field_weakening.step"),
        i_max_frac=_fraction(d.get("i_max_frac", f.i_max_frac), "field_weakening.i_max_frac"),
    )
    if fw.u_lo >= fw.u_hi:
        raise ConfigError(f"field_weakening.u_lo ({fw.u_lo!r}) must be below field_weakening.u_hi ({fw.u_hi!r})")
    return fw


def _choice(value, options: tuple, name: str):
    if value not in options:
        raise ConfigError(f"{name} must be one of {', '.join(map(repr, options))}, got {value!r}")
    return value


def from_dict(d: dict, source: str = "<dict>") -> Config:
    m = _req(d, "motor", "config")
    motor = Motor(
        name=str(m.get("name", "motor")),
        R=_positive(_req(m, "R", "motor"), "motor.R"),
        Ld=_positive(_req(m, "Ld", "motor"), "motor.Ld"),
        Lq=_positive(_req(m, "Lq", "motor"), "motor.Lq"),
        psi=_positive(_req(m, "psi", "motor"), "motor.psi"),
        p=int(_positive(_req(m, "p", "motor"), "motor.p")),
        J=_positive(_req(m, "J", "motor"), "motor.J"),
        B=_positive(m.get("B", 0.0), "motor.B", allow_zero=True),
        tau_c=_positive(m.get("tau_c", 0.0), "motor.tau_c", allow_zero=True),
    )
    if motor.p != float(_req(m, "p", "motor")):
        raise ConfigError(f"motor.p must be a whole number of pole pairs, got {m['p']!r}")
    i = _req(d, "inverter", "config")
    inverter = Inverter(
        Udc=_positive(_req(i, "Udc", "inverter"), "inverter.Udc"),
        f_pwm=_positive(_req(i, "f_pwm", "inverter"), "inverter.f_pwm"),
        dead_time=_positive(i.get("dead_time", 0.0), "inverter.dead_time", allow_zero=True),
    )
    s = _req(d, "sensors", "config")
    cpr = _req(s, "encoder_cpr", "sensors")
    if not isinstance(cpr, int) or cpr < 4:
        raise ConfigError(f"sensors.encoder_cpr must be an integer >= 4 (counts per revolution after x4), got {cpr!r}")
    sensors = Sensors(
        encoder_cpr=cpr,
        adc_amps_per_lsb=_positive(_req(s, "adc_amps_per_lsb", "sensors"), "sensors.adc_amps_per_lsb"),
        adc_offset=int(s.get("adc_offset", 2048)),
        adc_noise_lsb=_positive(s.get("adc_noise_lsb", 0.0), "sensors.adc_noise_lsb", allow_zero=True),
    )
    f_clk = _positive(d.get("fpga", {}).get("f_clk", 100e6), "fpga.f_clk")
    c = _req(d, "control", "config")
    alg = c.get("algorithm", 1)
    if alg not in (1, 2):
        raise ConfigError(f"control.algorithm must be 1 or 2, got {alg!r}")
    task = c.get("task", "speed")
    if task not in ("speed", "position"):
        raise ConfigError(f"control.task must be 'speed' or 'position', got {task!r}")
    N = c.get("N", 4)
    if not isinstance(N, int) or N < 1:
        raise ConfigError(f"control.N must be an integer >= 1, got {N!r}")
    if N > 8:
        raise ConfigError(f"control.N must be <= 8 (coefficient memory layout), got {N!r}")
    Ts = _positive(_req(c, "Ts", "control"), "control.Ts")
    wmin, wmax = float(_req(c, "omega_min", "control")), float(_req(c, "omega_max", "control"))
    if not (math.isfinite(wmin) and math.isfinite(wmax)) or wmax <= wmin:
        raise ConfigError(f"control.omega_min..omega_max (Omega_e) is empty: [{wmin!r}, {wmax!r}]")
    npts = c.get("omega_points", 101)
    if not isinstance(npts, int) or npts < 3:
        raise ConfigError(f"control.omega_points must be an integer >= 3, got {npts!r}")
    vl = c.get("voltage_limit", "circle")
    if vl != "circle":
        raise ConfigError(f"control.voltage_limit must be 'circle', got {vl!r}")
    weights = {}
    wsec = d.get("weights", {})
    for a in (1, 2):
        for t in ("speed", "position"):
            sec = wsec.get(f"alg{a}", {}).get(t)
            if sec is None:
                continue
            name = f"weights.alg{a}.{t}"
            weights[(a, t)] = Weights(
                Q_yw=_vector(_req(sec, "Q_yw", name), 3, f"{name}.Q_yw"),
                Q_dy=_vector(_req(sec, "Q_dy", name), 3, f"{name}.Q_dy"),
                Q_du=_vector(_req(sec, "Q_du", name), 2, f"{name}.Q_du"),
                ebar_step_max=_vector(sec.get("ebar_step_max", [0.0, 0.0, 0.0]), 3, f"{name}.ebar_step_max",
                                      positive=False),
                integrate=_bools(sec.get("integrate", [True, True, True]), 3, f"{name}.integrate"),
            )
    if (alg, task) not in weights:
        raise ConfigError(f"weights.alg{alg}.{task} is missing (needed by control.algorithm={alg}, task={task!r})")
    control = Control(
        algorithm=alg, task=task, N=N, Ts=Ts, omega_min=wmin, omega_max=wmax, omega_points=npts,
        design_quantised=bool(c.get("design_quantised", True)), voltage_limit=vl,
        i_max=_positive(c.get("i_max", 10.0), "control.i_max"),
        speed_estimate=_choice(c.get("speed_estimate", "accel_load"), ("eq37", "accel", "accel_load"),
                               "control.speed_estimate"),
        weights=weights,
        speed_load_shift=_int_in(c.get("speed_load_shift", 6), "control.speed_load_shift", 1, 15),
        governor=_governor(d.get("governor", {})),
        field_weakening=_field_weakening(d.get("field_weakening", {})),
    )
    cfg = Config(motor=motor, inverter=inverter, sensors=sensors, f_clk=f_clk, control=control, source=source)
    ratio = Ts * inverter.f_pwm
    if abs(ratio - round(ratio)) > 1e-6 or round(ratio) < 1:
        raise ConfigError(f"control.Ts must be a whole number of PWM periods (1/inverter.f_pwm), got Ts={Ts!r}")
    if cfg.pwm_half_period < 16:
        raise ConfigError(f"inverter.f_pwm={inverter.f_pwm!r} is too high for fpga.f_clk={f_clk!r} (half period < 16 ticks)")
    return cfg


def load(path: str | Path | None = None, overrides: dict | None = None) -> Config:
    p = Path(path) if path else DEFAULT_CONFIG
    try:
        d = tomllib.loads(p.read_text())
    except FileNotFoundError:
        raise ConfigError(f"configuration file not found: {p}") from None
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(f"{p}: not valid TOML: {e}") from None
    if overrides:
        d = copy.deepcopy(d)
        for dotted, v in overrides.items():
            cur = d
            *head, last = dotted.split(".")
            for k in head:
                cur = cur.setdefault(k, {})
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
