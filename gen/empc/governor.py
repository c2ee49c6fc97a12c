"""Reference governor: the current limit of the control law (issue 15 item 4).

The explicit law is linear and unconstrained (the paper's only constraint handling is the
saturation of u).  Large reference changes therefore draw large currents: a 150 -> 900 rad/s
speed step 12-19 A, a 200 rad position step 11-22 A over the plant box, with i_max = 10 A.
The governor shapes the task reference where it is generated (rtl/ref_gen.v), N periods ahead
of its use, into a trajectory the loop can follow within the current limit, so the law never
sees an infeasible demand (no windup, no saturation) and its preview W_{k+1..k+N} stays
consistent.  Per control period, with the target r (the CPU's profile) and the governed
reference g (what the controller gets), its increment v:

    vd = (r_k - r_{k-1}) + (r_{k-1} - g) >>> ksh      feed-forward + proportional catch-up
    vd = clamp(vd, -vmax, vmax)
    if hold and speed task and vd would raise |g| (not: g != 0 and sign(vd) != sign(g)): vd = 0
    dv = clamp(vd - v, -a, a)
    if hold and position task and dv would increase |v|: dv = 0
    v += dv;  g += v

Position task, braking distance (issue 15, the position overshoot): while the target holds (r_k = r_{k-1}) and v moves
towards it, vd = 0 (brake at a) when |r - g| < B and n >= 2 (B > V: at |v| <= a the proportional catch-up
stops in time by itself, and a brake there stopped the last approach every other period, which doubled the
time constant of the final approach), and no speed-up when |r - g| < B + 2 V, where
V = n a >= |v| (n changes by at most one per period: V += a when |v| > V, V -= a when |v| + a <= V,
after the step) and B = a n (n + 1) / 2 the distance the reference travels while braking at a from
a speed <= V (B += V on the way up, -= V on the way down): the time-optimal switching curve
v^2 / 2a + |v| / 2 kept with adds only (rtl/ref_gen.v passes G1, G4, G5).  Near the target (B
small) the proportional catch-up below does the final approach.

Position task: v is the reference speed (<= vmax: speed_frac of the no-load base speed
u_max/psi and of Omega_e), dv its change (<= a: the acceleration that needs accel_current x
i_max at the box corner J x box_J, psi x box_psi).  Speed task: v is the reference's
acceleration (<= vmax, the same acceleration limit), dv its change per period (a = vmax /
jerk_periods).  ``hold`` (the previous control period had |i_q| > hold_current x i_max or the
voltage limiter active) stops the reference from demanding more: the position reference does
not speed up (it may slow down); the speed reference's acceleration decays to 0 unless vd points
towards lower |g| (g != 0, sign(vd) != sign(g): braking, or backing off the voltage limit), which
passes as without the hold.  Both signs of speed alike; at g = 0 every vd raises |g|.  The hold was
two-sided (vd = 0) before issue 15 item 6: on the voltage limit (field weakening, spmsm_002 at
box corner_b) the reference crept up in the periods between holds and the hold then also kept it
up when the target turned down (RMS error 8.2 % of the top speed; one-sided: see
docs/field_weakening.md).  In steady tracking of a feasible
profile (ramps within the limits) the governed reference equals the target exactly.

The catch-up is a proportional position (speed) loop on the reference with time constant
tau = Ts x 2^ksh: it brakes (v follows vd = e >> ksh down) from an error of tau x the reference speed
w; it follows that braking exactly while the deceleration it asks, w / tau, is within the acceleration
limit alpha, and stops without overshoot while the braking distance w^2 / 2 alpha is within w tau
(w <= 2 alpha tau); above that the braking distance takes over (it brakes when the remaining distance
falls to the braking distance, whatever tau).  Position task: the limits are SI (vmax = w_max Ts, a = alpha Ts^2), so
the same braking needs the same tau at every control period, and ``shift_position`` defaults to
:func:`default_shift_position` of Ts: the smallest ksh with tau >= 4 ms, the tau of 4 at 250 us (the
value the configurations were tuned with): 200 us 5, 100 us 6, 50 us 7.  Taken as 4 at 50 us (tau =
0.8 ms) the governed position reference itself overshot 75-88 % on the premo and the EC 45 flat
(docs/design.md).  Speed task: a = vmax / jerk_periods is per period, so the braking condition
2^-ksh x vmax <= a (ksh >= log2 jerk_periods = 2) does not depend on Ts, and ``shift_speed`` stays 3.

Raw form (rtl/ref_gen.v, rtlmodel/ref_gen.py): values Q.32 of the task unit (counts, counts/Ts),
64-bit two's complement; :func:`raw_params` gives vmax, a (Q.32) and ksh.  This module holds the
float form (SI units) used by the float and fixed controllers.
"""
from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Params:
    task: str
    vmax: float          # per control period: rad (position) or rad/s (speed)
    a: float             # per control period^2: rad (position) or rad/s (speed)
    ksh: int
    enable: bool


def accel_limit(cfg, task: str = "speed") -> float:
    """Acceleration (rad/s^2, electrical) that needs accel_current x i_max at the box corner (position
    task: accel_current_position x i_max)."""
    m, g = cfg.motor, cfg.control.governor
    ac = g.accel_current_position if task == "position" else g.accel_current
    return ac * cfg.control.i_max * 1.5 * m.p * m.p * m.psi * g.box_psi / (m.J * g.box_J)


def speed_limit(cfg) -> float:
    """Largest reference speed of the position task (rad/s, electrical)."""
    c, g = cfg.control, cfg.control.governor
    w_top = min(c.omega_max, -c.omega_min, cfg.u_max / cfg.motor.psi)
    return g.speed_frac * w_top


TS_REF = 250e-6               # control period of the position catch-up's reference shift
SHIFT_POSITION_REF = 4        # 2^-4 per period at 250 us: tau = 4 ms
TAU_POSITION = TS_REF * 2 ** SHIFT_POSITION_REF   # governor.tau_position's default (the configurations' tuning)


def default_shift_position(Ts: float, stretch: float = 1.0, tau: float = TAU_POSITION) -> int:
    """Position catch-up shift for control period Ts (s): the smallest ksh whose Ts x 2^ksh is at
    least ``tau`` (governor.tau_position; default the 4 ms of 4 at 250 us: 200 us 5, 100 us 6, 50 us 7),
    within 0..31.  Rounded down instead (tau >= 2.8 ms: 6 at 50 us) the premo's scaled position step
    still overshot 40 %.  ``stretch``: at least stretch x tau, for an acceleration limit 1 / stretch of
    accel_current's (accel_current_position: the braking condition w <= 2 alpha tau keeps its margin)."""
    return min(31, max(0, math.ceil(math.log2(stretch * tau / Ts) - 1e-9)))


def params(cfg, task: str) -> Params:
    c, g = cfg.control, cfg.control.governor
    Ts = c.Ts
    alpha = accel_limit(cfg, task)
    if task == "speed":
        vmax = alpha * Ts
        return Params(task, vmax, vmax / g.jerk_periods, g.shift_speed, g.enable)
    return Params(task, speed_limit(cfg) * Ts, alpha * Ts * Ts, g.shift_position, g.enable)


def raw_params(cfg, task: str) -> dict:
    """Q.32 register values (slot memory field 7, see rtlmodel/ref_gen.GOV_*): vmax, a, ksh, enable."""
    p = params(cfg, task)
    unit = cfg.rad_per_count if task == "position" else cfg.rad_s_per_count_ts
    q = lambda x: int(math.floor(x / unit * 2.0 ** 32))
    return {"vmax": q(p.vmax), "a": max(1, q(p.a)), "ksh": p.ksh, "enable": p.enable}


def hold_current_raw(cfg) -> int:
    """IQ_HOLD register: |i_q| threshold of the hold in ADC LSB (the integer part of i_q Q.4)."""
    return int(round(cfg.control.governor.hold_current * cfg.control.i_max / cfg.amps_per_lsb))


class Governor:
    """Float governor of one task output (SI units), stepped once per control period at the head."""

    def __init__(self, p: Params):
        self.p = p
        self.K = 2.0 ** -p.ksh
        self.reset(0.0)
        self.clamped = False

    def reset(self, value: float) -> None:
        self.r = value
        self.g = value
        self.v = 0.0
        self.vq = 0.0                       # braking state: V = n a >= |v|, B = a n (n + 1) / 2
        self.bq = 0.0

    def step(self, r_new: float, hold: bool) -> float:
        p = self.p
        if not p.enable:
            self.r = self.g = r_new
            self.v = self.vq = self.bq = 0.0
            self.clamped = False
            return self.g
        x1 = r_new - self.r
        e = self.r - self.g
        vd0 = x1 + self.K * e
        vd = min(max(vd0, -p.vmax), p.vmax)
        if hold and p.task == "speed" and not (self.g != 0.0 and (vd < 0.0) != (self.g < 0.0)):
            vd = 0.0                        # no more |speed| while held (towards lower |g| passes)
        # braking distance (position task, target holding, moving towards it): brake at a inside B,
        # no speed-up inside B + 2 V
        brake = slow = False
        if p.task == "position" and x1 == 0.0 and self.v != 0.0 and (self.v < 0.0) == (e < 0.0):
            brake, slow = abs(e) < self.bq and self.vq > 1.5 * p.a, abs(e) < self.bq + 2.0 * self.vq   # n >= 2 (V = n a; raw: B > V)
        if brake:
            vd = 0.0
        dv0 = vd - self.v
        dv = min(max(dv0, -p.a), p.a)
        if (hold or slow) and p.task == "position" and dv * self.v > 0:
            dv = 0.0                        # no more speed while held (slowing down stays allowed)
        self.clamped = bool(hold or vd != vd0 or dv != dv0)
        s = self.v < 0.0 if self.v != 0.0 else dv0 < 0.0
        self.v += dv
        self.g += self.v
        self.r = r_new
        w = -self.v if s else self.v
        if w > self.vq:                     # V, B of n + 1
            self.vq += p.a
            self.bq += self.vq
        elif w + p.a <= self.vq:            # of n - 1
            self.bq -= self.vq
            self.vq -= p.a
        return self.g


class ReferencePath:
    """The governed reference window of a controller: w_k .. w_{k+N} of the task output.

    ``window(meas_w_k, meas_W, hold)`` takes the profile's samples (what the CPU programmed)
    and returns the governed ones; the governor runs on the head w_{k+N} (it is stepped once
    per call) and a delay line keeps the N earlier governed values, as in rtl/ref_gen.v.
    """

    def __init__(self, cfg, task: str):
        self.gov = Governor(params(cfg, task))
        self.N = cfg.control.N
        self.dl = None
        self.clamps = 0

    def reset(self) -> None:
        self.dl = None
        self.clamps = 0

    def window(self, w_k: float, W: list, hold: bool) -> tuple[float, list]:
        if self.dl is None and not self.gov.p.enable:
            self.dl = [float(w_k)] + [float(x) for x in W]      # bumpless start: the window as given
        elif self.dl is None:
            # as rtl/ref_gen.v after its sync: the delay line at w_k and the governor from there, so
            # a profile change inside the first window is governed too (taken as given, a step
            # 0.5 ms after the start drew 4.7 i_max on the premo, 2.9 on the EC 45 flat)
            self.dl = [float(w_k)] * (self.N + 1)
            self.gov.reset(float(w_k))
            self.dl = self.dl[1:] + [self.gov.step(float(W[-1]), hold)]
            self.clamps += int(self.gov.clamped)
        else:
            self.dl = self.dl[1:] + [self.gov.step(float(W[-1]), hold)]
            self.clamps += int(self.gov.clamped)
        return self.dl[0], self.dl[1:]
