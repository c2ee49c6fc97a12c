"""Bit-accurate model of the per-axis control sequencer (rtl/ctrl_seq.v).

``CtrlSeq.period(...)`` is one PWM period, evaluated at the ADC trigger with
the angle and encoder count of that instant and the ADC samples of the period:
it returns the compare values the RTL loads for the next PWM period, and on a
control period also runs the front end, the MPC core model and updates the
loop state exactly like the RTL.

Front end of a control period (issue 15 items 1 and 6), raw units:

    spd   = sat32(dpos << 16)                                  eq. 37, counts/Ts Q16.16
    ka    = rshift_round(kacc * i_q, kacc_shift)               (Ts/2) accel from i_q
    u1    = ka - D
    omega = sat32(spd + u1)
    load_shift > 0:  t2 = 2 u1 - (spd - spd_prev);  D = D + (t2 >> (load_shift + 1))
    (load_shift = 0: D = 0, the plain "accel" estimate; kacc = 0 as well: eq. 37).
    t2 / 2 = u1 - (spd - spd_prev) / 2: the load estimate's error (float form: estimator.py).
    D is not saturated: it is a low-pass of ka - (spd - spd_prev) / 2, so |D| < 2^35 (|ka| <=
    2^34, |spd| < 2^31), and the sequencer keeps it in 40 bits (never wraps).
    field weakening (rtl/mpc_axis.v; fw_nmax > 0, law running): n = min(n + 1, fw_nmax) if
        fw_hi, max(n - 1, 0) if fw_lo (the core's flags of the previous update); the
        d-current references are sat18(id_ref - (n << fw_shift))
    hold (for the reference governor, rtl/mpc_axis.v): after the core update of a running
        control period, (iq_hold > 0 and (i_q >= 16 iq_hold or i_q < -16 iq_hold)) or the
        voltage limiter was active; 0 when the law is off.

The second half of this module is the RTL's microprogram: the tables (ops, pass table,
programs) from which ``empc.ucode`` generates rtl/ctrl_seq_ucode.vh and rtl/ctrl_seq_rom.vh
(``python -m empc.ucode``).  They describe how the RTL computes, not what: the model above
does not use them.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .. import formats as F
from .. import regmap
from .. import ucode as U
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
    load_shift: int = 0            # KACC.load_shift: load estimate of the speed (0 = off)
    fw_shift: int = 8              # EMPC_FW_SHIFT: field-weakening step 2^fw_shift Q.4 ADC LSB
    fw_nmax: int = 0               # FW.nmax: steps of the d-current offset (0 = field weakening off)
    fw_thr: tuple = (0xFFFF, 0)    # FW_R2 (hi, lo): thresholds on the limiter's r >> 20
    iq_hold: int = 0               # IQ_HOLD: |i_q| hold threshold of the governor, ADC LSB (0 = off)


def speed_estimate(dpos: int, i_q: int, regs: "Regs", state: dict) -> tuple[int, bool]:
    """omega (Q16.16) of one control period; ``state`` holds D and spd_prev (updated).
    Returns (omega, saturated)."""
    spd = dpos << F.W_FRAC
    spd_s = F.sat(spd, F.W_W)
    ka = F.rshift_round(regs.kacc * i_q, regs.kacc_shift) if regs.kacc_shift else regs.kacc * i_q
    u1 = ka - state["D"]
    om = spd_s + u1
    omega = F.sat(om, F.W_W)
    sat = spd_s != spd or omega != om
    if regs.load_shift:
        t2 = 2 * u1 - (spd_s - state["spd_prev"])
        state["D"] = state["D"] + (t2 >> (regs.load_shift + 1))
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
        omega, esat = speed_estimate(dpos, i_q, regs, self.est)
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
                        u_prev=self.u, ebar_prev=self.ebar, fw_thr=regs.fw_thr)
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
# Microprogram of rtl/ctrl_seq.v.  The tables below are the one source of the sequencer's two
# block RAMs; ucode_vh() / rom_vh() write them (through empc.ucode, the compiler xform uses too)
# into rtl/ctrl_seq_ucode.vh (field positions, codes, entry points) and rtl/ctrl_seq_rom.vh (the
# RAM images).  Regenerate with `python -m empc.ucode`; tb/test_ctrl_seq.py checks the files.
#
# The engine executes one step per instruction: in state E_OP it decodes the step (next state,
# zero writes), then, for an op with a pass, runs the pass bit by bit (E_PASS, one bit a clock,
# controlled by the pass table word of (pass kind, bit)), optionally rewrites a saturated word
# (E_FIX) and writes the word to the core input buffer (E_WR).  Everything the RTL would have
# to decode from (op, source, m) behind the block RAM is decoded here instead: the microword
# uw carries the fields and the op flags, the second word ub the engine's decode.
# ==============================================================================================
NUC_MAX = 64                    # control program rows 0..63 (7-bit pc; status programs from 64)
OP = {"POS": 0, "ZERO": 1, "COPY": 2, "REF": 3, "DIFF": 4, "OM": 5, "FIX3": 6, "W6": 7, "ZPOS": 8, "END": 9,
      "STAT": 10, "SEND": 11, "CNT": 12, "CEND": 13, "LD": 14}
# sources of the COPY / STAT / DIFF / POS steps: stage registers, selected one-hot (ub.nsel, active low)
SRC = {"POS": 0, "E0": 1, "E1": 2, "E2": 3, "U0": 4, "U1": 5, "IDR": 6, "IQR": 7, "ID": 8, "IQ": 9}
N_SRC = len(SRC)
# pass kinds (rows 64 k .. 64 k + 63 of the pass table); the reference kinds are {1, 0, task_pos,
# m == 0}: the microword holds REFS / REFS0 and the RTL ORs task_pos into bit 1 (REFP / REFP0)
PK = {"POS": 0, "DIFF": 1, "OM": 2, "FIX3": 3, "W6": 4, "STAT": 5, "CNT": 6, "FIX": 7, "REFS": 8, "REFS0": 9,
      "REFP": 10, "REFP0": 11, "LD": 12}


@dataclass(frozen=True)
class Op:
    """What the engine does with an op.  ``go``: the next state from E_OP: "stage" (E_STG, load X
    from the selected stage), "pass" (E_PASS), "zero" (write 0 to the core word now, next step;
    ZPOS only for the position task), "idle" (end of a program), or the condition an op flag
    waits for: "front" (DIFF: front end done -> stage), "ref_ok" (REF -> pass), "product" (OM:
    multiplier finished -> pass).  ``kind``: pass kind (None: no pass).  ``back``: the pass ends
    in E_OP (no core write).  ``sat``: the word is saturated to SIG_W bits (E_FIX).  ``sub``: the
    pass subtracts B.  ``status``: the pass streams a status word (REF: for m = 0 only)."""
    go: str
    kind: str | None = None
    back: bool = False
    sat: bool = False
    sub: bool = False
    status: bool = False


OPS = {
    "POS":  Op("stage", "POS", sat=True, sub=True),             # dpos = count - count_prev, dx3 = dpos << 8
    "ZERO": Op("zero"),                                          # core word = 0
    "COPY": Op("stage"),                                         # core word = a stage (copied through X)
    "REF":  Op("ref_ok", "REFS", sat=True, status=True),         # w3[m] from ref_gen (REF status word: m = 0)
    "DIFF": Op("front", "DIFF", sub=True, status=True),          # y = i_d / i_q, dx = y - y_prev (I_D / I_Q)
    "OM":   Op("product", "OM", back=True),                      # omega (raw) = spd + ka - D, t2 (load term)
    "FIX3": Op("pass", "FIX3", status=True),                     # omega saturated -> core, SPEED
    "W6":   Op("pass", "W6", sat=True, sub=True),                # dx2 = omega - omega_prev
    "ZPOS": Op("zero"),                                          # y2 = 0 (position task only)
    "END":  Op("idle"),                                          # control program done: core start
    "STAT": Op("stage", "STAT", back=True, status=True),         # a status word out of X (U_D, U_Q)
    "SEND": Op("idle"),                                          # status program done
    "CNT":  Op("pass", "CNT", back=True, status=True),           # a sweep word (bits from axis_status)
    "CEND": Op("idle"),                                          # counter sweep done
    "LD":   Op("pass", "LD", back=True),                         # D += t2 >>> (load_shift + 1)
}
# op flags in uw (registered as is_*): the ops whose pass the datapath treats apart (not CNT: the
# sweep words' bits come from axis_status)
FLAG_OPS = ("POS", "REF", "DIFF", "OM", "FIX3", "W6", "STAT")

# uw: op (read by the test bench only), src (bit 0: DIFF i_q), wa (core word), age (ref_age = N - m),
# st (status / sweep word offset), op flags, sub, pk (pass kind; the RTL ORs task_pos into bit 1
# of a reference kind)
UW = U.Layout((("op", 4), ("src", 4), ("wa", 6), ("age", 4), ("st", 6))
              + tuple((n.lower(), 1) for n in FLAG_OPS) + (("sub", 1), ("pk", 4)))
# ub: stage selects (active low, one per SRC), next state from E_OP (to E_STG / E_PASS / E_IDLE; the
# waits are the op flags), zero is "next step in E_OP" (ZERO, ZPOS), end markers (END: core start;
# CEND: sweep done), COPY (E_LD -> E_WR), the zero writes (ZERO; ZPOS for the position task), the
# pass-end actions: back to E_OP, saturated to SIG_W, writes a status / sweep word; ld: the load-
# estimate pass (its datapath apart, like the uw op flags)
UB = U.Layout((("nsel", N_SRC), ("to_stg", 1), ("to_pass", 1), ("zero", 1), ("to_idle", 1), ("end", 1), ("cend", 1),
               ("copy", 1), ("wz", 1), ("zpos", 1), ("back", 1), ("sat", 1), ("stw", 1), ("ld", 1), ("spare", 13)))
assert UW.width == UB.width == 36

# Pass table: per kind, the bits b (0..63) of the pass in which each control bit is set.
#   XS shift X (result in at the top)    PE pass end              SS status bit out (st_sh)
#   HA / HB hold the A / B sign          CA / CB capture it        AL ALU carry chain active
#   R1 / R2 / R3 shift rings (B operands, omega, dpos)             L31 / L16 below bit 31 / 16
#   F1 / F2 / F3 flag strobes of the op  W0 core write at bit 0    G saturation reference bit (SW-1)
PT = U.Layout(tuple((n, 1) for n in ("XS", "PE", "SS", "HA", "HB", "CA", "CB", "R1", "R2", "R3", "AL", "L31",
                                     "L16", "F1", "F2", "F3", "W0", "G")))
_ALL = range(64)
_REFS = dict(AL=range(16, 64), XS=range(16, 56), PE=[63], G=[47])                  # (w >> 16) + w[15]
_REFP = dict(AL=range(24, 64), XS=range(24, 64), R1=range(32, 64), F1=[23], F2=range(24, 64), PE=[63],
             G=[55])                                                                # (w - count << 32) >> 24 + w[23]
PASSES = {
    "POS":   dict(XS=_ALL, R1=_ALL, R3=_ALL, AL=_ALL, PE=[31], F1=[15], F2=range(16, 64), F3=[31], G=[23]),
    "DIFF":  dict(XS=_ALL, AL=_ALL, SS=range(32), HB=range(18, 64), CB=[17], R1=range(18), W0=[0], PE=[39]),
    "OM":    dict(AL=_ALL, HA=range(32, 64), CA=[31], R2=range(32), R3=range(16, 32), L31=range(31),
                  L16=range(16), F1=[31], F2=range(32, 64), F3=[39], PE=[39]),
    "FIX3":  dict(XS=_ALL, AL=_ALL, SS=range(32), HA=range(32, 64), CA=[31], R2=range(32), L31=range(31), PE=[39]),
    "W6":    dict(XS=_ALL, AL=_ALL, HA=range(32, 64), CA=[31], HB=range(32, 64), CB=[31], R1=range(32),
                  R2=range(32), PE=[39], G=[31]),
    "STAT":  dict(XS=_ALL, AL=_ALL, SS=range(32), PE=[32]),
    "CNT":   dict(SS=range(32), PE=[32]),                    # sweep word: axis_status forms the bits
    "FIX":   dict(PE=[39], XS=range(31, 64)),               # E_FIX (second port): bits 31.. of the pattern
    "REFS":  _REFS,
    "REFS0": dict(_REFS, SS=range(16, 48)),                  # m = 0: also the REF status word
    "REFP":  _REFP,
    "REFP0": dict(_REFP, SS=range(24, 56)),
    "LD":    dict(PE=[39]),                                  # D += t2 >>> (load_shift + 1): own adder
}
assert list(PASSES) == list(PK)


def pass_word(kind: str, b: int) -> int:
    return PT.pack(**{c: 1 for c, bits in PASSES[kind].items() if b in bits})


@dataclass(frozen=True)
class Step:
    """One instruction: op, source (SRC name), wa (core input word, or the register offset of a
    STAT / CNT word), m (reference w_{k+m})."""
    op: str
    src: str = "POS"
    wa: int = 0
    m: int = 0
    note: str = ""


def _a(name: str) -> int:
    return regmap.axis_reg(name).offset


STATUS_WORDS = ("SPEED", "I_D", "I_Q", "U_D", "U_Q", "REF")
COUNTERS = ("SAT_OPERAND", "SAT_GAIN", "SAT_TERM", "SAT_ACC", "SAT_DU", "SAT_U", "SAT_EBAR", "SAT_EBAR_INC",
            "SAT_LIMIT", "SAT_WN", "SAT_SIGNAL", "SAT_FRONT", "CNT_OVERRUN", "PERIODS", "SAT_GOV")


def control_program(n: int) -> list[Step]:
    """From the trigger of a control period: the core's input words, then core start."""
    prog = [Step("POS", "POS", core.IN_DX + 3, note="dx3 = dpos << 8 (and dpos, the speed)"),
            Step("ZERO", wa=core.IN_DX + 4, note="dx4 = 0")]
    prog += [Step("COPY", f"E{o}", core.IN_EBAR + o, note=f"ebar_prev[{o}]") for o in range(3)]
    prog += [Step("COPY", f"U{o}", core.IN_UPREV + o, note=f"u_prev[{o}]") for o in range(2)]
    for m in range(n + 1):
        a = core.IN_WREF + 3 * m
        prog += [Step("COPY", "IDR", a, note=f"wref[{m}] = (id_ref,"), Step("COPY", "IQR", a + 1, note="iq_ref,"),
                 Step("REF", wa=a + 2, m=m, note=f"w3[{m}] from w_(k+{m}))")]
    prog += [Step("DIFF", "ID", core.IN_Y + 0, note="y0 = i_d, dx0 (at +4); waits for the front"),
             Step("DIFF", "IQ", core.IN_Y + 1, note="y1 = i_q, dx1; feeds the multiplier"),
             Step("OM", note="omega = spd + ka - D, t2 = 2 (ka - D) - spd + spd_prev; waits for the product"),
             Step("LD", note="D += t2 >>> (load_shift + 1) (the load estimate of the speed)"),
             Step("FIX3", wa=core.IN_OMEGA, note="omega saturated (and y2 = omega for the speed task)"),
             Step("W6", wa=core.IN_DX + 2, note="dx2 = omega - omega_prev"),
             Step("ZPOS", wa=core.IN_Y + 2, note="y2 = 0 (position task)"),
             Step("END", note="core start")]
    assert len(prog) == 15 + 3 * (n + 1) <= NUC_MAX
    return prog


STATUS_PROGRAM = [Step("STAT", "U0", _a("U_D"), note="U_D = the u applied"),
                  Step("STAT", "U1", _a("U_Q"), note="U_Q"), Step("SEND")]
# sweeps of axis_status (it supplies the bits: counter + event, or 0 in a zero sweep); the zero
# sweep after rst zeroes the status words, then runs into the counters
ZERO_PROGRAM = [Step("CNT", wa=_a(w), note=f"{w} = 0") for w in STATUS_WORDS]
COUNT_PROGRAM = [Step("CNT", wa=_a(c), note=c) for c in COUNTERS] + [Step("CEND")]
# entry points: the control program at 0, the others from NUC_MAX on; the zero sweep (after rst)
# runs into the counter sweep
ENTRY = {"CTL": 0, "STAT": NUC_MAX, "ZERO": NUC_MAX + len(STATUS_PROGRAM),
         "CNT": NUC_MAX + len(STATUS_PROGRAM) + len(ZERO_PROGRAM)}
UROM_ROWS = 2 * NUC_MAX        # pc 0..127; uw at pc, ub at 128 + pc
DEFAULT = Step("SEND")


def words(s: Step, n: int) -> tuple[int, int]:
    """(uw, ub) of step ``s`` for horizon ``n``."""
    d = OPS[s.op]
    src = SRC[s.src]
    ref = s.op == "REF"
    kind = d.kind or "CNT"
    if ref and s.m == 0:
        kind = "REFS0"
    st = {"REF": _a("REF"), "DIFF": _a("I_D") + (src & 1), "FIX3": _a("SPEED")}.get(s.op, s.wa)
    # (every field range-checked by pack: no silent truncation, e.g. of m or N - m)
    uw = UW.pack(op=OP[s.op], src=src, wa=s.wa, age=n - s.m, st=st, sub=int(d.sub), pk=PK[kind],
                 **({s.op.lower(): 1} if s.op in FLAG_OPS else {}))
    ub = UB.pack(nsel=((1 << N_SRC) - 1) & ~(1 << src), to_stg=int(d.go == "stage"), to_pass=int(d.go == "pass"),
                 zero=int(d.go == "zero"), to_idle=int(d.go == "idle"), end=int(s.op == "END"),
                 cend=int(s.op == "CEND"), copy=int(s.op == "COPY"), wz=int(s.op == "ZERO"), zpos=int(s.op == "ZPOS"),
                 back=int(d.back), sat=int(d.sat), stw=int(d.status and (not ref or s.m == 0)),
                 ld=int(s.op == "LD"))
    return uw, ub


def programs(n: int) -> dict[int, Step]:
    """pc -> step of every program (the other rows hold DEFAULT)."""
    out = dict(enumerate(control_program(n)))
    for entry, prog in ((ENTRY["STAT"], STATUS_PROGRAM), (ENTRY["ZERO"], ZERO_PROGRAM + COUNT_PROGRAM)):
        out.update({entry + i: s for i, s in enumerate(prog)})
    return out


def urom_image(n: int) -> list[int]:
    """The 256 x 36 microprogram RAM for horizon ``n``: uw at pc, ub at 128 + pc."""
    prog = programs(n)
    img = [0] * (2 * UROM_ROWS)
    for pc in range(UROM_ROWS):
        img[pc], img[UROM_ROWS + pc] = words(prog.get(pc, DEFAULT), n)
    return img


def crom_image() -> list[int]:
    """The 1024 x 18 pass table: word 64 k + b = control bits of bit b of pass kind k."""
    img = [0] * 1024
    for kind, k in PK.items():
        for b in range(64):
            img[64 * k + b] = pass_word(kind, b)
    return img


# ---- generated Verilog ---------------------------------------------------------------------
N_RANGE = range(1, core.N_MAX + 1)      # the horizons the RTL accepts (parameter N)
# the names rtl/ctrl_seq.v refers to (the others stay out of the header: no unused localparams)
RTL_NAMES = {"UW_SRC", "UW_WA", "UW_AGE", "UW_ST", "UW_SUB", "UW_PK", *(f"UW_{n}" for n in FLAG_OPS),
             *(f"UB_{n.upper()}" for n, _ in UB.fields if n != "spare"),
             *(f"PT_{n}" for n, _ in PT.fields), *(f"SRC_{n}" for n in SRC), "PK_FIX",
             *(f"PC_{n}" for n in ENTRY)}


def _hdr(what: str, cmd: str) -> list[str]:
    return U.header("empc.rtlmodel.ctrl_seq", what, "rtl/ctrl_seq.v", cmd, f"rtl/ctrl_seq_{cmd}.vh",
                    "tb/test_ctrl_seq.py")


def _positions(prefix: str, layout: U.Layout) -> list[str]:
    lines = layout.positions(prefix)
    items = [x for line in lines for x in line[len("localparam integer "):-1].split(", ")
             if x.split(" = ")[0] in RTL_NAMES]
    return [f"localparam integer {', '.join(items[i:i + 6])};" for i in range(0, len(items), 6)]


def ucode_vh() -> str:
    """Text of ``rtl/ctrl_seq_ucode.vh`` (module scope): field positions, codes, entry points."""
    lines = _hdr("ucode_vh", "ucode")
    lines.append(f"// microword uw (LSB first): {UW.doc()}")
    lines += _positions("UW_", UW)
    lines.append(f"// engine decode ub (LSB first): {UB.doc()}")
    lines += _positions("UB_", UB)
    lines.append(f"// pass table word (LSB first): {PT.doc()}")
    lines += _positions("PT_", PT)
    lines += U.localparams("SRC_", SRC, 4, names=RTL_NAMES)
    lines += U.localparams("PK_", PK, 4, names=RTL_NAMES)
    lines += U.localparams("PC_", ENTRY, 7, names=RTL_NAMES)
    # what the images were generated for: ctrl_seq.v stops elaboration if empc_formats.vh /
    # empc_regs.vh say otherwise
    chk = [f"`EMPC_IN_{n} == {getattr(core, 'IN_' + n)}" for n in ("Y", "OMEGA", "DX", "UPREV", "EBAR", "WREF")]
    chk += [f"`EMPC_A_{n} == {_a(n)}" for n in STATUS_WORDS + COUNTERS]
    lines.append("// the core input words and register offsets the images were generated for")
    lines.append("localparam UC_MAP_OK = " + " &&\n    ".join(
        " && ".join(f"({c})" for c in chk[i:i + 4]) for i in range(0, len(chk), 4)) + ";")
    return "\n".join(lines) + "\n"


def _step_text(s: Step) -> str:
    src = f" {s.src}" if s.op in ("POS", "COPY", "DIFF", "STAT") else ""
    dst = f" -> {s.wa}" if s.op not in ("OM", "END", "SEND", "CEND") else ""
    return f"{s.op}{src}{dst}" + (f" m {s.m}" if s.op == "REF" else "") + (f": {s.note}" if s.note else "")


def rom_vh() -> str:
    """Text of ``rtl/ctrl_seq_rom.vh`` (inside the ``initial`` block): the pass table crom and,
    for every N, the microprogram urom (uw at pc, ub at 128 + pc)."""
    lines = _hdr("rom_vh", "rom")
    lines.append(f"// pass table crom: word 64 k + b = control bits ({PT.doc()}) of bit b of pass kind k; "
                 "other words 0")
    lines.append("for (ui = 0; ui < 1024; ui = ui + 1) crom[ui] = 18'h00000;")
    img = crom_image()
    for kind, k in PK.items():
        runs = img[64 * k:64 * k + 64]
        notes = {}
        for b in range(64):
            if b == 0 or runs[b] != runs[b - 1]:
                bits = [n for n, v in PT.unpack(runs[b]).items() if v]
                notes[b] = f"{kind} {b}: {' '.join(bits) if bits else '-'}"
        lines += U.rom_runs("crom", PT.width, runs, "ui", base=str(64 * k), notes=notes, skip=0)
    lines.append(f"// microprogram urom: uw ({UW.doc()}) at pc, ub ({UB.doc()}) at 128 + pc, "
                 "for the horizon N (the age field, the control program's length)")
    for n in N_RANGE:
        prog = programs(n)
        duw, dub = words(DEFAULT, n)
        lines.append(f"if (N == {n}) begin")
        lines.append(f"    for (ui = 0; ui < {UROM_ROWS}; ui = ui + 1) begin urom[ui] = {U.word_literal(36, duw)}; "
                     f"urom[{UROM_ROWS} + ui] = {U.word_literal(36, dub)}; end   // {_step_text(DEFAULT)}")
        for pc in sorted(prog):
            uw, ub = words(prog[pc], n)
            lines.append(f"    urom[{pc}] = {U.word_literal(36, uw)}; urom[{UROM_ROWS + pc}] = "
                         f"{U.word_literal(36, ub)};   // pc {pc} {_step_text(prog[pc])}")
        lines.append("end")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    import sys

    what = sys.argv[1] if len(sys.argv) > 1 else ""
    if what in ("ucode", "rom"):
        sys.stdout.write(ucode_vh() if what == "ucode" else rom_vh())
    else:
        sys.stdout.write("usage: python -m empc.rtlmodel.ctrl_seq ucode|rom  (or python -m empc.ucode)\n")
