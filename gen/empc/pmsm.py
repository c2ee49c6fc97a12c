"""PMSM plant, averaged inverter and sensors for closed-loop simulation.

Plant: nonlinear dq model (paper 000 eqs. 1-3) with L_d != L_q, reluctance
torque, viscous and Coulomb friction and a load torque, integrated by RK4 with
sub-steps inside each PWM period.  Inverter: averaged phase voltages from the
duty cycles and the DC link (star winding, floating neutral), optional dead-time
voltage error.  Sensors: encoder counts (quantised, eq. 38), HALL sector,
current ADC codes with offset, quantisation and noise.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

SQRT3 = math.sqrt(3.0)


def clarke(a: float, b: float, c: float) -> tuple[float, float]:
    """Amplitude-invariant Clarke of a balanced triple (paper eq. 32 uses alpha=a, beta=(b-c)/sqrt3)."""
    return a, (b - c) / SQRT3


def inv_clarke(alpha: float, beta: float) -> tuple[float, float, float]:
    """Eq. 35."""
    return alpha, -0.5 * alpha + 0.5 * SQRT3 * beta, -0.5 * alpha - 0.5 * SQRT3 * beta


def park(alpha: float, beta: float, theta: float) -> tuple[float, float]:
    """Eq. 33."""
    c, s = math.cos(theta), math.sin(theta)
    return c * alpha + s * beta, -s * alpha + c * beta


def inv_park(d: float, q: float, theta: float) -> tuple[float, float]:
    """Eq. 34."""
    c, s = math.cos(theta), math.sin(theta)
    return c * d - s * q, s * d + c * q


def min_subtract(a: float, b: float, c: float) -> tuple[float, float, float]:
    """Eq. 36: shift the three phase voltages so the smallest is zero."""
    m = min(a, b, c)
    return a - m, b - m, c - m


@dataclass
class PlantState:
    i_d: float = 0.0
    i_q: float = 0.0
    w_e: float = 0.0       # electrical speed, rad/s
    theta_e: float = 0.0   # electrical angle, rad (multi-turn, continuous)

    def as_array(self) -> np.ndarray:
        return np.array([self.i_d, self.i_q, self.w_e, self.theta_e])


@dataclass
class Plant:
    """PMSM with an averaged inverter; ``step_pwm`` advances one PWM period."""
    motor: object
    Udc: float
    f_pwm: float
    substeps: int = 4
    dead_time: float = 0.0
    state: PlantState = field(default_factory=PlantState)
    tau_load: float = 0.0
    theta_offset: float = 0.0    # encoder zero vs. rotor d axis, electrical rad

    # --- dynamics ---
    def _deriv(self, i_d, i_q, w, th, u_alpha, u_beta):
        m = self.motor
        c, s = math.cos(th), math.sin(th)
        u_d = c * u_alpha + s * u_beta
        u_q = -s * u_alpha + c * u_beta
        did = (u_d - m.R * i_d + w * m.Lq * i_q) / m.Ld
        diq = (u_q - m.R * i_q - w * m.Ld * i_d - w * m.psi) / m.Lq
        torque = 1.5 * m.p * (m.psi * i_q + (m.Ld - m.Lq) * i_d * i_q)
        w_m = w / m.p
        friction = m.B * w_m + (m.tau_c * math.tanh(w_m / 0.05) if m.tau_c else 0.0)
        dw = m.p * (torque - friction - self.tau_load) / m.J
        return did, diq, dw, w

    def phase_voltages(self, duties) -> tuple[float, float]:
        """Averaged alpha-beta voltage of the inverter for phase duties in [0, 1]."""
        v = [self.Udc * min(max(float(d), 0.0), 1.0) for d in duties]
        if self.dead_time:
            # each switching edge pair loses t_dead of the commanded voltage against the current
            loss = self.Udc * 2.0 * self.dead_time * self.f_pwm
            v = [vi - math.copysign(loss, ii) if ii else vi for vi, ii in zip(v, self.phase_currents())]
        mean = (v[0] + v[1] + v[2]) / 3.0
        return clarke(v[0] - mean, v[1] - mean, v[2] - mean)

    def phase_currents(self) -> np.ndarray:
        a, b = inv_park(self.state.i_d, self.state.i_q, self.state.theta_e)
        return np.array(inv_clarke(a, b))

    def step(self, duration: float, duties) -> None:
        """Hold ``duties`` (phase A, B, C in [0,1]) for ``duration`` seconds (RK4 sub-steps)."""
        ua, ub = self.phase_voltages(duties)
        h = duration / self.substeps
        st = self.state
        x0, x1, x2, x3 = st.i_d, st.i_q, st.w_e, st.theta_e
        f = self._deriv
        for _ in range(self.substeps):
            a0, a1, a2, a3 = f(x0, x1, x2, x3, ua, ub)
            b0, b1, b2, b3 = f(x0 + 0.5 * h * a0, x1 + 0.5 * h * a1, x2 + 0.5 * h * a2, x3 + 0.5 * h * a3, ua, ub)
            c0, c1, c2, c3 = f(x0 + 0.5 * h * b0, x1 + 0.5 * h * b1, x2 + 0.5 * h * b2, x3 + 0.5 * h * b3, ua, ub)
            d0, d1, d2, d3 = f(x0 + h * c0, x1 + h * c1, x2 + h * c2, x3 + h * c3, ua, ub)
            k = h / 6.0
            x0 += k * (a0 + 2 * b0 + 2 * c0 + d0)
            x1 += k * (a1 + 2 * b1 + 2 * c1 + d1)
            x2 += k * (a2 + 2 * b2 + 2 * c2 + d2)
            x3 += k * (a3 + 2 * b3 + 2 * c3 + d3)
        self.state = PlantState(x0, x1, x2, x3)

    def step_pwm(self, duties) -> None:
        self.step(1.0 / self.f_pwm, duties)


@dataclass
class Sensors:
    """Encoder, HALL and current-ADC models in the RTL's raw units."""
    cfg: object
    rng: np.random.Generator = field(default_factory=lambda: np.random.default_rng(0))
    hall_offset: float = 0.0    # electrical angle of the HALL sector boundaries vs. the d axis

    def encoder_count(self, theta_e: float) -> int:
        """Encoder counter (x4 decoded), eq. 38: floor of the mechanical angle in counts."""
        cpr = self.cfg.sensors.encoder_cpr
        return int(math.floor(theta_e / self.cfg.motor.p / (2 * math.pi) * cpr))

    def hall_sector(self, theta_e: float) -> int:
        """HALL sector 1..6 (60 electrical degrees each)."""
        a = (theta_e - self.hall_offset) % (2 * math.pi)
        return int(a // (math.pi / 3)) + 1

    def adc_codes(self, i_abc) -> list[int]:
        s = self.cfg.sensors
        out = []
        for i in i_abc:
            v = i / s.adc_amps_per_lsb + s.adc_offset
            if s.adc_noise_lsb:
                v += self.rng.normal(0.0, s.adc_noise_lsb)
            out.append(int(min(max(round(v), 0), (1 << 12) - 1)))
        return out


def quantise_angle(theta: float, marks: int) -> float:
    """Eq. 38: angle rounded to the sensor resolution (marks per revolution of this angle)."""
    return 2 * math.pi / marks * round(theta * marks / (2 * math.pi))
