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
        """
        if self.control.speed_estimate != "accel":
            return 0.0
        m = self.motor
        return 0.5 * self.control.Ts * 1.5 * m.p * m.p * m.psi / m.J

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
        speed_estimate=_choice(c.get("speed_estimate", "accel"), ("eq37", "accel"), "control.speed_estimate"),
        weights=weights,
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
