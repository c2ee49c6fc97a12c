"""Reference generator: time-parameterised polynomial segments (paper 000 sec. V-A).

A profile is a list of segments; each holds on [t0, t0 + duration) the values
r(tau) = c0 + c1 tau + c2 tau^2 + c3 tau^3 of the three controlled outputs
(i_d, i_q, w_e or theta_e) with tau = t - t0.  Steps and ramps are segments of
order 0 and 1; the last segment holds beyond its end.  Evaluated per sample.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Segment:
    t0: float
    duration: float
    coeffs: tuple   # 3 outputs x (c0, c1, c2, c3)

    def value(self, t: float) -> np.ndarray:
        tau = min(max(t - self.t0, 0.0), self.duration)
        c = np.asarray(self.coeffs, dtype=float)
        return c[:, 0] + tau * (c[:, 1] + tau * (c[:, 2] + tau * c[:, 3]))


class Profile:
    def __init__(self, segments: list[Segment]):
        if not segments:
            raise ValueError("a reference profile needs at least one segment")
        self.segments = sorted(segments, key=lambda s: s.t0)

    def __call__(self, t: float) -> np.ndarray:
        seg = self.segments[0]
        for s in self.segments:
            if s.t0 <= t:
                seg = s
            else:
                break
        return seg.value(t)

    def samples(self, t: float, Ts: float, n: int) -> np.ndarray:
        """w_{k+1} .. w_{k+n} for the sample at time t (shape n x 3)."""
        return np.array([self(t + (j + 1) * Ts) for j in range(n)])

    @property
    def end(self) -> float:
        s = self.segments[-1]
        return s.t0 + s.duration


def steps_and_ramps(points, output: int = 2, i_d: float = 0.0, i_q: float = 0.0) -> Profile:
    """Build a profile from (t, value, kind) breakpoints: kind 'step' jumps to value at t,
    'ramp' moves linearly from the previous value to reach value at t."""
    segs = []
    t_prev, v_prev = 0.0, 0.0
    for t, v, kind in points:
        if kind == "step":
            segs.append(_const(t_prev, t - t_prev, v_prev, output, i_d, i_q))
            t_prev, v_prev = t, v
        elif kind == "ramp":
            d = t - t_prev
            c = [[i_d, 0, 0, 0], [i_q, 0, 0, 0], [0, 0, 0, 0]]
            c[output] = [v_prev, (v - v_prev) / d, 0, 0]
            segs.append(Segment(t_prev, d, tuple(map(tuple, c))))
            t_prev, v_prev = t, v
        else:
            raise ValueError(f"unknown breakpoint kind {kind!r}")
    segs.append(_const(t_prev, 1e9, v_prev, output, i_d, i_q))
    return Profile([s for s in segs if s.duration > 0])


def _const(t0, d, v, output, i_d, i_q) -> Segment:
    c = [[i_d, 0, 0, 0], [i_q, 0, 0, 0], [0, 0, 0, 0]]
    c[output] = [v, 0, 0, 0]
    return Segment(t0, d, tuple(map(tuple, c)))
