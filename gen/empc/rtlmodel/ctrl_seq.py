"""Bit-accurate model of the per-axis control sequencer (rtl/mx_seq.v: what it computes).

``CtrlSeq.period(...)`` is one PWM period, evaluated at the ADC trigger with
the angle and encoder count of that instant and the ADC samples of the period:
it returns the compare values the RTL loads for the next PWM period, and on a
control period also runs the front end, the MPC core model and updates the
loop state exactly like the RTL.

Front end of a control period (issue 15 items 1 and 6), raw units:

    spd   = sat32(dpos << 16)                                  eq. 37, counts/Ts Q16.16
            (KACC.win = m > 0: sat32((pos_k - pos_{k-M}) << (16 - m)), M = 2^m, the counts of the
            last HIST (formats.WIN_DEPTH) control samples kept, 0 before the first ones after reset; the load update
            below then takes ((2 u1 >> m) - (spd - spd_prev)) >> (load_shift + 1 - m))
    ka    = rshift_round(kacc * i_q, kacc_shift)               (Ts/2) accel from i_q
    u1    = ka - D
    omega = sat32(spd + u1)
    load_shift > 0:  t2 = 2 u1 - (spd - spd_prev);  D = D + (t2 >> (load_shift + 1))
    (load_shift = 0: D = 0, the plain "accel" estimate; kacc = 0 as well: eq. 37).
    t2 / 2 = u1 - (spd - spd_prev) / 2: the load estimate's error (float form: estimator.py).
    D is not saturated: it is a low-pass of ka - (spd - spd_prev) / 2, so |D| < 2^35 (|ka| <=
    2^34, |spd| < 2^31), and the sequencer keeps it in 40 bits (never wraps).
    field weakening (rtl/axis_periph.v; fw_nmax > 0, law running): n = min(n + 1, fw_nmax) if
        fw_hi, max(n - 1, 0) if fw_lo (the core's flags of the previous update); the
        d-current references are sat18(id_ref - (n << fw_shift))
    hold (for the reference governor, rtl/axis_periph.v): after the core update of a running
        control period, (iq_hold > 0 and (i_q >= 16 iq_hold or i_q < -16 iq_hold)) or the
        voltage limiter was active; 0 when the law is off.
    anti-windup of the speed integral: the core's aw input from i_q and iq_hold (mpc_core.aw_bits; step 2
        of mpc_core.update: the speed task's eq. 25 increment is held while |i_q| >= 16 iq_hold and it would
        drive |i_q| further).

How the RTL computes it (the word-parallel microprogram, its pipeline and latency) is
:mod:`empc.rtlmodel.mx_seq`.  The RTL decides a period's kind and advances the references at
the PWM boundary before the sample: :meth:`CtrlSeq.boundary` (docs/four_axes.md D5).
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
HIST = F.WIN_DEPTH                 # position history (rtl/mx_seq.v: per axis, SRL16 at 16): window M <= HIST


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
    load_shift: int = 0            # KACC.load_shift: load estimate of the speed (0 = off)
    fw_shift: int = 8              # EMPC_FW_SHIFT: field-weakening step 2^fw_shift Q.4 ADC LSB
    fw_nmax: int = 0               # FW.nmax: steps of the d-current offset (0 = field weakening off)
    fw_thr: tuple = (0xFFFF, 0)    # FW_R2 (hi, lo): thresholds on the limiter's r >> 20
    iq_hold: int = 0               # IQ_HOLD: |i_q| hold threshold of the governor, ADC LSB (0 = off)
    win_shift: int = 0             # KACC.win: log2 control.speed_window (0..WIN_MAX; more acts as WIN_MAX)


WIN_MAX = F.WIN_LOG2_MAX           # KACC.win: the RTL's position history is HIST = 2^WIN_MAX deep (M <= HIST)


def win_eff(m: int) -> int:
    """The window shift the RTL uses for the 3-bit KACC.win field (values above WIN_MAX act as WIN_MAX)."""
    return min(m, WIN_MAX)


def speed_estimate(dpos: int, i_q: int, regs: "Regs", state: dict) -> tuple[int, bool]:
    """omega (Q16.16) of one control period; ``state`` holds D and spd_prev (updated).
    Returns (omega, saturated).  ``regs.win_shift`` = m (control.speed_window = 2^m; 0: eq. 37 over one
    period): ``dpos`` is the count difference over 2^m periods, spd = sat32(dpos << (16 - m)) (exact),
    and the load update compares u1 with 2^m (spd - spd_prev) / 2 (estimator.py)."""
    m = win_eff(regs.win_shift)
    spd = dpos << (F.W_FRAC - m)
    spd_s = F.sat(spd, F.W_W)
    ka = F.rshift_round(regs.kacc * i_q, regs.kacc_shift) if regs.kacc_shift else regs.kacc * i_q
    u1 = ka - state["D"]
    om = spd_s + u1
    omega = F.sat(om, F.W_W)
    sat = spd_s != spd or omega != om
    if regs.load_shift:
        # D += (2 u1 - ((spd - spd_prev) << m)) >> (load_shift + 1), computed as the RTL's serial shifter
        # does it (right shifts only): ((2 u1 >> m) - (spd - spd_prev)) >> (load_shift + 1 - m); equal
        # (floor(floor(a / 2^m) / 2^j) = floor(a / 2^(m+j))) while load_shift + 1 >= m (the configuration
        # refuses less); below that the second shift is 0 (rtl/mx_seq.v clamps the count)
        t2 = (2 * u1 >> m) - (spd_s - state["spd_prev"])
        state["D"] = state["D"] + (t2 >> max(regs.load_shift + 1 - m, 0))
    else:
        state["D"] = 0
    state["spd_prev"] = spd_s
    return omega, sat


def fw_update(n: int, hi: bool, lo: bool, regs: "Regs") -> int:
    """Field-weakening step count n after one control period (offset -n << fw_shift)."""
    if not regs.fw_nmax:
        return 0
    n = min(n + 1, regs.fw_nmax) if hi else max(n - 1, 0) if lo else n
    return min(n, regs.fw_nmax)


def fw_offset(n: int, regs: "Regs") -> int:
    return -(n << regs.fw_shift)


def hold_flag(i_q: int, limited: bool, regs: "Regs") -> bool:
    h = regs.iq_hold
    return bool(limited or (h > 0 and (i_q >= 16 * h or i_q < -16 * h)))


@dataclass
class CtrlSeq:
    params: core.Params
    N: int
    per_cnt: int = 0
    first: bool = True
    theta_trig: int = 0
    pos_prev: int = 0
    pos_hist: list = field(default_factory=lambda: [0] * HIST)   # counts of the last HIST control samples
    id_prev: int = 0
    iq_prev: int = 0
    omega_prev: int = 0
    u: tuple = (0, 0)
    ebar: tuple = (0, 0, 0)
    last: dict = field(default_factory=dict)
    est: dict = field(default_factory=lambda: {"D": 0, "spd_prev": 0})
    fw_n: int = 0
    fw_flags: tuple = (False, False)
    hold: bool = False
    ctl_next: bool | None = None   # decided at the PWM boundary before the sample (boundary())

    def boundary(self, regs: Regs) -> bool:
        """The PWM boundary before a sample (docs/four_axes.md D5): decides whether the coming
        sample is a control sample (CTRL.pwm_per_control as at the boundary); the references
        advance here, so the caller advances ref_gen's model when this returns True, before any
        CPU command of the half period (a SEG_START / CMD.ref_sync after the boundary is taken
        by the next control period's advance)."""
        self.ctl_next = self.per_cnt + 1 >= regs.pwm_per_control
        return self.ctl_next

    def period(self, theta: int, pos: int, cur: tuple, regs: Regs, ref_w=None) -> dict:
        """One PWM period.  theta: 16-bit angle at the trigger; pos: encoder count (32-bit);
        cur: offset-corrected ADC samples (3 signed ints); ref_w: N+1 Q.32 references
        (w_k..w_{k+N}) after this period's advance (only used on control periods)."""
        out = {"control": False, "front_sat": False}
        theta_mod = (theta + (0 if self.first else (theta - self.theta_trig))) & ANGLE_MASK
        self.first = False
        self.theta_trig = theta
        pos &= POS_MASK
        control = self.per_cnt + 1 >= regs.pwm_per_control if self.ctl_next is None else self.ctl_next
        self.ctl_next = None
        if control:
            self.per_cnt = 0
            out["control"] = True
            self._control(theta, pos, cur, regs, ref_w, out)
        else:
            self.per_cnt += 1
        if not regs.run:
            self.u, self.ebar = (0, 0), (0, 0, 0)
            self.fw_n, self.fw_flags, self.hold = 0, (False, False), False
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
        # the speed window: pos_k - pos_{k-M}, from the history of the control samples' counts (0 before
        # the first M samples after reset, as pos_prev: the first M speeds see pos_k - 0)
        dpos_m = F.wrap(pos - self.pos_hist[(1 << win_eff(regs.win_shift)) - 1], F.POS_W)
        self.pos_hist = [pos] + self.pos_hist[:-1]
        omega, esat = speed_estimate(dpos_m, i_q, regs, self.est)
        out["front_sat"] |= bool(sat0 or sat1 or esat)
        if regs.run:
            self.fw_n = fw_update(self.fw_n, *self.fw_flags, regs)
        id_eff = F.sat(regs.id_ref + fw_offset(self.fw_n, regs), F.I_W)
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
            wref.append((id_eff, regs.iq_ref, w3))
        # dx in the core's SIG_W-bit words: the speed and angle increments saturate (only for
        # impossible jumps: 2^15 counts/Ts of speed change, 2^23 counts per Ts)
        dom = F.sat(omega - self.omega_prev, sw)
        dth = F.sat(dpos << F.TH_FRAC, sw)
        eng_sat = bool(esat or dom != omega - self.omega_prev or dth != dpos << F.TH_FRAC)
        out["front_sat"] |= eng_sat
        dx = (i_d - self.id_prev, i_q - self.iq_prev, dom, dth, 0)
        x = core.Inputs(y=(i_d, i_q, 0 if task_pos else omega), omega=omega, dx=dx, wref=tuple(wref),
                        u_prev=self.u, ebar_prev=self.ebar, fw_thr=regs.fw_thr,
                        aw=core.aw_bits(i_q, regs.iq_hold))
        self.id_prev, self.iq_prev, self.omega_prev, self.pos_prev = i_d, i_q, omega, pos
        out.update(i_d=i_d, i_q=i_q, omega=omega, dpos=dpos, i_fw=fw_offset(self.fw_n, regs), id_eff=id_eff,
                   x=x, eng_sat=eng_sat)
        if regs.run:
            r = core.update(self.params, x)
            self.u, self.ebar = r.u, r.ebar
            self.fw_flags = (r.fw_hi, r.fw_lo)
            self.hold = hold_flag(i_q, bool(r.flags >> core.FLAG_BITS["limit"] & 1), regs)
            out["core"] = r
        out["hold"] = self.hold


# ==============================================================================================
# The status words the sequencer writes and the counters axis_status keeps (register names, in
# the counters' event order: rtl/axis_status.v counts event i into SAT_OPERAND + i).  The
# microprogram that computes the above is rtl/mx_seq.v's (rtlmodel/mx_seq.py); the bit-serial
# ctrl_seq and its tables were retired with it.
STATUS_WORDS = ("SPEED", "I_D", "I_Q", "U_D", "U_Q", "REF")
COUNTERS = ("SAT_OPERAND", "SAT_GAIN", "SAT_TERM", "SAT_ACC", "SAT_DU", "SAT_U", "SAT_EBAR", "SAT_EBAR_INC",
            "SAT_LIMIT", "SAT_WN", "SAT_SIGNAL", "SAT_FRONT", "CNT_OVERRUN", "PERIODS", "SAT_GOV")
