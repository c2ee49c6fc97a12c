"""Bit-accurate model of the per-axis control sequencer (rtl/ctrl_seq.v).

``CtrlSeq.period(...)`` is one PWM period, evaluated at the ADC trigger with
the angle and encoder count of that instant and the ADC samples of the period:
it returns the compare values the RTL loads for the next PWM period, and on a
control period also runs the front end, the MPC core model and updates the
loop state exactly like the RTL.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .. import formats as F
from . import mpc_core as core
from .xform_steps.clarke import clarke
from .xform_steps.duty_scale import duty_scale
from .xform_steps.inv_clarke import inv_clarke
from .xform_steps.inv_park import inv_park
from .xform_steps.min_sub import min_sub
from .xform_steps.park import park
from .xform_steps.sincos import sincos

ANGLE_MASK = (1 << F.ANGLE_BITS) - 1
POS_MASK = (1 << F.POS_W) - 1
MASK64 = (1 << 64) - 1


@dataclass
class Regs:
    pwm_per_control: int
    kdc: int = 1 << F.KDC_FRAC
    kacc: int = 0
    kacc_shift: int = 0
    id_ref: int = 0
    iq_ref: int = 0
    half_period: int = 2500
    run: bool = True


@dataclass
class CtrlSeq:
    params: core.Params
    N: int
    per_cnt: int = 0
    first: bool = True
    theta_trig: int = 0
    pos_prev: int = 0
    id_prev: int = 0
    iq_prev: int = 0
    omega_prev: int = 0
    u: tuple = (0, 0)
    ebar: tuple = (0, 0, 0)
    last: dict = field(default_factory=dict)

    def period(self, theta: int, pos: int, cur: tuple, regs: Regs, ref_w=None) -> dict:
        """One PWM period.  theta: 16-bit angle at the trigger; pos: encoder count (32-bit);
        cur: offset-corrected ADC samples (3 signed ints); ref_w: N+1 Q.32 references
        (w_k..w_{k+N}) after this period's advance (only used on control periods)."""
        out = {"control": False, "front_sat": False}
        theta_mod = (theta + (0 if self.first else (theta - self.theta_trig))) & ANGLE_MASK
        self.first = False
        self.theta_trig = theta
        pos &= POS_MASK
        if self.per_cnt + 1 >= regs.pwm_per_control:
            self.per_cnt = 0
            out["control"] = True
            self._control(theta, pos, cur, regs, ref_w, out)
        else:
            self.per_cnt += 1
        if not regs.run:
            self.u, self.ebar = (0, 0), (0, 0, 0)
        # modulation chain for the held u
        sh = F.U_FRAC - F.V_FRAC
        ud = F.sat(F.rshift_round(self.u[0], sh), F.V_W)
        uq = F.sat(F.rshift_round(self.u[1], sh), F.V_W)
        s, c = sincos(theta_mod)
        ua, ub, sat1 = inv_park(ud, uq, s, c)
        va, vb, vc, sat2 = inv_clarke(ua, ub)
        wa, wb, wc, sat3 = min_sub(va, vb, vc)
        ca, cb, cc, sat4 = duty_scale(wa, wb, wc, regs.kdc, regs.half_period)
        out["front_sat"] |= bool(sat1 or sat2 or sat3 or sat4)
        out["cmp"] = (ca, cb, cc)
        out["u"] = self.u
        out["theta_mod"] = theta_mod
        self.last = out
        return out

    def _control(self, theta, pos, cur, regs, ref_w, out):
        ia, ib, sat0 = clarke(*cur)
        s, c = sincos(theta)
        i_d, i_q, sat1 = park(ia, ib, s, c)
        dpos = F.wrap(pos - self.pos_prev, F.POS_W)
        spd = dpos << F.W_FRAC
        spd_s = F.sat(spd, F.W_W)
        ka = F.rshift_round(regs.kacc * i_q, regs.kacc_shift) if regs.kacc_shift else regs.kacc * i_q
        om = spd_s + ka
        omega = F.sat(om, F.W_W)
        out["front_sat"] |= bool(sat0 or sat1 or spd_s != spd or omega != om)
        task_pos = self.params.task == "position"
        sw = core.SIG_W
        wref = []
        for j in range(self.N + 1):
            wv = ref_w[j] if ref_w is not None else 0
            if task_pos:
                rel = F.wrap(wv - (pos << 32), 64)
                w3 = F.sat(F.rshift_round(rel, 32 - F.TH_FRAC), sw)
            else:
                w3 = F.sat(F.rshift_round(F.wrap(wv, 64), 32 - F.W_FRAC), sw)
            wref.append((regs.id_ref, regs.iq_ref, w3))
        # dx in the core's SIG_W-bit words: the speed and angle increments saturate (only for
        # impossible jumps: 2^15 counts/Ts of speed change, 2^23 counts per Ts)
        dom = F.sat(omega - self.omega_prev, sw)
        dth = F.sat(dpos << F.TH_FRAC, sw)
        out["front_sat"] |= bool(dom != omega - self.omega_prev or dth != dpos << F.TH_FRAC)
        dx = (i_d - self.id_prev, i_q - self.iq_prev, dom, dth, 0)
        x = core.Inputs(y=(i_d, i_q, 0 if task_pos else omega), omega=omega, dx=dx, wref=tuple(wref),
                        u_prev=self.u, ebar_prev=self.ebar)
        self.id_prev, self.iq_prev, self.omega_prev, self.pos_prev = i_d, i_q, omega, pos
        out.update(i_d=i_d, i_q=i_q, omega=omega, dpos=dpos)
        if regs.run:
            r = core.update(self.params, x)
            self.u, self.ebar = r.u, r.ebar
            out["core"] = r
