"""Cycle-accurate model of ``rtl/pwm_center.v`` (centre-aligned PWM, dead time, fault).

Two levels of API:

* :class:`PwmCenter` - a register-level model: :meth:`PwmCenter.step` takes the
  inputs present during one clock cycle and returns the registered outputs after
  the following rising edge.  Bit-exact per clock against the RTL (the cocotb test
  compares every output bit on every clock).
* :func:`ideal_high`, :func:`period_waveform` - the waveform of one period for a
  constant compare value (what the closed-loop simulation needs: on-time per
  period = ``2 * cmp`` clocks, i.e. duty ``cmp / P``).

Timing (``P`` = ``PWM_HALF_PERIOD``): the counter runs 0, 1, .., P-1 (up), P, P-1,
.., 1 (down), period ``2 P`` clocks.  Position ``n`` = 0..2P-1 in the period is
counter ``n`` for ``n < P`` and ``2P - n`` otherwise.  The ideal high-side command
is ``cnt < cmp`` on the up-count and ``cnt <= cmp`` on the down-count, which is
high for positions ``[0, cmp)`` and ``[2P - cmp, 2P)``: exactly ``2 cmp`` clocks,
symmetric about the period centre ``n = P`` (where ``adc_trig`` is).  Outputs lag
the counter by one register stage; ``period_start`` and ``adc_trig`` are aligned
with the outputs (period_start in the output cycle of position 0, adc_trig in the
output cycle of position P).

Carrier stagger (``phase`` = the RTL's PHASE, docs/four_axes.md D4): the counter starts
at reset, and restarts at a ``sync_in`` rise, at position ``2P - phase`` (:func:`start_position`),
so its counter and strobes are those of a ``phase = 0`` instance delayed by ``phase``
clocks; such a restart (``phase`` > 0) is no boundary: the outputs go off until the next
boundary.  :func:`stagger_step` is the offset between neighbouring axes (the header's
``PWM_STAGGER_<NAXES>``).
"""
from __future__ import annotations

from dataclasses import dataclass, field

MODE_COMPL = 0   # complementary hi/lo with dead time
MODE_PWM_EN = 1  # hi = PWM command, lo = bridge enable (dead time in the bridge)



def default_half_period() -> int:
    """``EMPC_PWM_HALF_PERIOD`` of the default configuration (2500 at 100 MHz / 20 kHz)."""
    from .. import config
    return config.default().pwm_half_period


def stagger_step(naxes: int, half_period: int, frame_period: int) -> int:
    """Carrier offset between axis n and n + 1 (clocks): TF * round(2P / (NAXES TF)), a whole number
    of ADC frames so that one frame grid centres a window on every axis's PWM centre
    (docs/four_axes.md section 3.1; 2P = 5000, TF = 74: 2516, 1702, 1258 for 2, 3, 4 axes)."""
    if naxes < 1:
        raise ValueError("naxes >= 1")
    return 0 if naxes == 1 else frame_period * round(2 * half_period / (naxes * frame_period))


def start_position(phase: int, half_period: int) -> int:
    """Period position (0 = boundary, P = centre) of the counter at reset / at a sync restart."""
    if not 0 <= phase < 2 * half_period:
        raise ValueError(f"phase {phase} outside 0..2P-1")
    return (2 * half_period - phase) % (2 * half_period)


def counter_at(pos: int, half_period: int) -> tuple[int, int]:
    """(cnt, dir) of period position ``pos``: up 0..P-1, then P, P-1, .., 1 down."""
    return (pos, 1) if pos < half_period else (2 * half_period - pos, 0)


def ideal_high(pos: int, cmp: int, half_period: int) -> int:
    """Ideal high-side command at position ``pos`` (0..2P-1) of a period with compare ``cmp``."""
    P = half_period
    cmp = min(max(cmp, 0), P)
    return 1 if (pos < cmp or pos >= 2 * P - cmp) else 0


def period_waveform(cmp: int, half_period: int, dead: int = 0, mode: int = MODE_COMPL):
    """Steady-state (hi, lo) lists over one period (positions 0..2P-1) for a constant ``cmp``.

    Complementary mode: each switch turns on ``dead`` clocks after the other one turned
    off; a pulse not longer than ``dead`` disappears.  PWM+enable mode: ``hi`` = ideal
    command, ``lo`` = 1.  Positions are those of the output registers (period_start = 0).
    """
    P = half_period
    h = [ideal_high(n, cmp, P) for n in range(2 * P)]
    if mode == MODE_PWM_EN:
        return h, [1] * (2 * P)
    # run the dead-time logic on three periods and keep the last one (steady state)
    hi = lo = 0
    q = (1 << 30)
    out_hi, out_lo = [], []
    for rep in range(3):
        for n in range(2 * P):
            qok = q >= dead
            hi_n = h[n] & (hi | qok)
            lo_n = (1 - h[n]) & (lo | qok)
            hi, lo = hi_n, lo_n
            q = 0 if (hi | lo) else q + 1
            if rep == 2:
                out_hi.append(hi)
                out_lo.append(lo)
    return out_hi, out_lo


@dataclass
class PwmInputs:
    """Inputs of one clock cycle (values sampled by the next rising edge)."""
    rst: int = 0
    enable: int = 0
    mode: int = MODE_COMPL
    dead: int = 0
    cmp_in: list = field(default_factory=list)
    cmp_load: int = 0
    sync_in: int = 0
    fault: int = 0
    fault_clear: int = 0


class PwmCenter:
    """Register-level model of one ``pwm_center`` instance.

    Parameters mirror the RTL: ``nch``, ``half_period`` (P), ``dead_w``,
    ``sync_stages``, ``sync_lead``, ``phase`` (``half_period`` None = the default config's P).  Output register values are attributes
    (``hi``, ``lo`` as lists of bits, ``period_start``, ``adc_trig``, ``sync_out``,
    ``fault_latched``, ``mode_eff``, ``cmp_clip``) and are returned by :meth:`step`
    as a dict.  The state after construction is the reset state.
    """

    def __init__(self, nch: int = 3, half_period: int | None = None, dead_w: int = 8,
                 sync_stages: int = 0, sync_lead: int = 2, phase: int = 0):
        if half_period is None:
            half_period = default_half_period()
        if half_period < 2:
            raise ValueError("half_period must be >= 2")
        if not 0 <= sync_lead <= half_period:
            raise ValueError("sync_lead must be 0..half_period")
        self.nch = nch
        self.P = half_period
        self.cw = max(1, (half_period).bit_length())   # clog2(P + 1)
        self.dead_w = dead_w
        self.q_max = (1 << dead_w) - 1
        self.sync_stages = sync_stages
        self.sync_lead = sync_lead
        self.phase = phase
        self.cnt0, self.dir0 = counter_at(start_position(phase, half_period), half_period)
        self.reset()

    # ------------------------------------------------------------------ state
    def reset(self) -> None:
        """Synchronous reset (the state after a clock edge with ``rst`` = 1)."""
        n = self.nch
        self.sync_pipe = [0] * self.sync_stages
        self.sync_prev = 0
        self.cnt = self.cnt0
        self.dir = self.dir0
        self.shadow = [0] * n
        self.cmp_act = [0] * n
        self.mode_act = MODE_COMPL
        self.run = 0
        self.fault_latched = 0
        self.cmp_clip = 0
        self.period_start = 0
        self.adc_trig = 0
        self.sync_out = 0
        self.mode_eff = MODE_COMPL
        self.on = 0
        self.hi = [0] * n
        self.lo = [0] * n
        self.q = [0] * n

    def outputs(self) -> dict:
        return {
            "hi": list(self.hi), "lo": list(self.lo),
            "period_start": self.period_start, "adc_trig": self.adc_trig,
            "sync_out": self.sync_out, "fault_latched": self.fault_latched,
            "mode_eff": self.mode_eff, "cmp_clip": self.cmp_clip, "on": self.on,
        }

    def ideal(self) -> list:
        """Current ideal high-side commands (stage A, combinational)."""
        return [int(self.cnt < c) if self.dir else int(self.cnt <= c) for c in self.cmp_act]

    # ------------------------------------------------------------------ clock
    def step(self, inp: PwmInputs | None = None, **kw) -> dict:
        """Advance one clock: ``inp`` (or keyword arguments of :class:`PwmInputs`)
        are the inputs during the cycle; returns the outputs after the edge."""
        if inp is None:
            inp = PwmInputs(**kw)
        if inp.rst:
            self.reset()
            return self.outputs()
        P = self.P
        cmp_in = list(inp.cmp_in) if inp.cmp_in else [0] * self.nch
        dead = inp.dead & self.q_max

        # combinational (stage A)
        sync_s = self.sync_pipe[-1] if self.sync_stages else (inp.sync_in & 1)
        sync_rise = sync_s & (1 - self.sync_prev)
        nat_bnd = int(not self.dir and self.cnt <= 1)
        jump = int(bool(self.phase) and sync_rise)          # restart at the phase: no boundary
        bnd_edge = int(nat_bnd and not sync_rise) if self.phase else int(nat_bnd or sync_rise)
        ok = int(inp.enable and not inp.fault and not self.fault_latched)
        alive = self.run & ok
        clipped = [min(c, P) for c in cmp_in]
        any_clip = int(any(c > P for c in cmp_in))
        h = self.ideal()

        # stage B next state
        hi_n, lo_n = [0] * self.nch, [0] * self.nch
        for i in range(self.nch):
            if not alive:
                pass
            elif self.mode_act != MODE_COMPL:
                hi_n[i], lo_n[i] = h[i], 1
            else:
                qok = int(self.q[i] >= dead)
                hi_n[i] = h[i] & (self.hi[i] | qok)
                lo_n[i] = (1 - h[i]) & (self.lo[i] | qok)
        q_n = [0 if (hi_n[i] | lo_n[i]) else min(self.q[i] + 1, self.q_max) for i in range(self.nch)]
        lead_dir = 1 if self.sync_lead == 0 else 0
        ps_n = int(self.dir == 1 and self.cnt == 0)
        adc_n = int(self.dir == 0 and self.cnt == P)
        so_n = int(self.dir == lead_dir and self.cnt == self.sync_lead)
        mode_eff_n = self.mode_act

        # stage A next state
        if jump:
            cnt_n, dir_n = self.cnt0, self.dir0
        elif bnd_edge:
            cnt_n, dir_n = 0, 1
        elif self.dir:
            cnt_n, dir_n = (P, 0) if self.cnt >= P - 1 else (self.cnt + 1, 1)
        else:
            cnt_n, dir_n = self.cnt - 1, 0
        shadow_n = clipped if inp.cmp_load else self.shadow
        if bnd_edge:
            cmp_act_n, mode_act_n, run_n = list(self.shadow), inp.mode & 1, ok
        else:
            cmp_act_n, mode_act_n, run_n = self.cmp_act, self.mode_act, alive & (1 - jump)
        fl_n = int(inp.fault or (self.fault_latched and not inp.fault_clear))

        # commit
        if self.sync_stages:
            self.sync_pipe = [inp.sync_in & 1] + self.sync_pipe[:-1]
        self.sync_prev = sync_s
        self.cnt, self.dir = cnt_n, dir_n
        self.shadow, self.cmp_act = shadow_n, cmp_act_n
        self.mode_act, self.run = mode_act_n, run_n
        self.fault_latched = fl_n
        self.cmp_clip = int(inp.cmp_load and any_clip)
        self.period_start, self.adc_trig, self.sync_out = ps_n, adc_n, so_n
        self.mode_eff = mode_eff_n
        self.on = alive
        self.hi, self.lo, self.q = hi_n, lo_n, q_n
        return self.outputs()
