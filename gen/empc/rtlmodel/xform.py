"""Model of ``rtl/xform.v``: the whole transform chain on ONE multiply-accumulate unit.

Two operations, each bit-exact to the composition of the per-step specification
models (which stay the reference, also for :mod:`empc.rtlmodel.ctrl_seq`):

* **front** (measurement side): ``clarke -> park`` with sin/cos of the angle
  (:func:`front`):  ``(i_a, i_b, i_c, angle) -> (i_d, i_q, sat)``
* **mod** (actuation side): ``u_to_v -> inv_park -> inv_clarke -> min_sub -> duty_scale``
  with sin/cos of the angle (:func:`modulate`):
  ``(u_d, u_q, angle, kdc) -> (cmp_a, cmp_b, cmp_c, sat)``, u_d/u_q in the MPC's
  format (signed U_W = 24 bit, U_FRAC = 8), converted as ctrl_seq does (:func:`u_to_v`)

``sat`` is the OR of the saturation flags of the steps (not of u_to_v, which has none).

Implementation (identical in RTL and :func:`run`): a microprogram (:data:`PROGRAM`)
of multiply-accumulate *passes* on one registered 18x18 multiplier with a 48-bit
accumulator (all inside one DSP48A1; 38 bits used).  A pass loads the accumulator with a constant
``C`` (0, the rounding constant 2**15, or the sine rounding constant), adds the
products ``a * b`` of its rows, and writes ``y = sat18(acc >> 16)`` (or, for the
compare values, ``min(acc >> 16, PWM_HALF_PERIOD)``) to a register file, a flag or
an output.  Every step is rewritten exactly for the fixed window ``>> 16``:

* sin/cos (sign s, nodes T[k], T[k+1], fraction f = 0..32, see :mod:`sincos`):
  ``s (T[k] + ((D f + 16) >> 5)) = (T[k] (s (32 - f)) 2**11 + T[k+1] (s f) 2**11 + C) >> 16``
  (since 32 T[k] + D f = T[k] (32 - f) + T[k+1] f) with ``C = 2**15`` (s = +1) or
  ``2**15 - 2**11`` (s = -1: ``-floor(x) = floor(-x + 15/32)`` for x in units of 1/32).
  Computed for sin, cos and -sin from the 513 nodes T[0..512] (rows 0..512 of the
  1024 x 18 block RAM; the microprogram sits in rows UC_BASE.. of the same RAM and is
  read through its second port).
* u_to_v (Q16.8 -> Q14.4, round half up, saturate): with u = 64 uh + ul (ul = 0..63),
  ``sat18((4 (uh 2**16) + ul 4096 + 2**15) >> 16) = sat18((u + 8) >> 4)``.
* clarke: ``i_alpha = 16 i_a`` (an operand, no pass); ``i_beta = ((4 i_b)(K1 + K2)
  - (4 i_c)(K1 + K2) + 2**15) >> 16`` with K1 + K2 = K_BETA (each < 2**17).
* park / inverse park: two products each, as in :func:`empc.rtlmodel.xform_steps.park.rotate`
  (-sin is an operand, so every pass only adds).
* inverse Clarke (shift 21 -> 16): with K_SQ3 = 32 * 56755 + 27,
  ``t = floor(u_beta 27/32) = (u_beta * 55296) >> 16``,
  ``t' = floor(-u_beta 27/32) = (u_beta * -55296) >> 16``,
  ``u_B = (u_beta 56755 + t - u_alpha 2**15 + 2**15) >> 16``,
  ``u_C = (-u_beta 56755 + t' - u_alpha 2**15 + 2**15) >> 16``
  (floor(floor(x/32)/2**16) = floor(x/2**21), and (1 - u_alpha) 2**20 is a multiple of 32).
* min_sub: two compare passes ``(x - y) 2**16`` (sign -> flag) pick the register of the
  minimum m, then ``w_x = sat18(((u_x - m) 2**16) >> 16)``.
* duty_scale (shift 20 -> 16): with kdc = 16 kh + kl,
  ``tw = floor(w kl / 16) = (w (kl << 12)) >> 16``,
  ``cmp = min((w kh + tw + 2**15) >> 16, PWM_HALF_PERIOD)`` (w >= 0, so never < 0).

Timing is static: rows issue one per clock; a row marked ``wait`` issues only when no
pass is still in flight (result written 5 clocks after its last row was issued).
:func:`schedule` computes every row's issue cycle, checks that every operand read
happens after the pass that writes it has written it, and gives the latencies.
:func:`ucode_vh` / :func:`rom_vh` generate ``rtl/xform_ucode.vh`` (codes, RF_B constants,
entry points) / ``rtl/xform_rom.vh`` (block RAM image: sine nodes + microprogram) through the
microcode compiler :mod:`empc.ucode`, which ctrl_seq uses too (regenerate: ``python -m empc.ucode``
or ``python -m empc.rtlmodel.xform ucode|rom``; the tests check the files).
"""
from __future__ import annotations

from dataclasses import dataclass

from .. import formats as F
from .. import ucode as U
from .xform_steps import sincos as SC
from .xform_steps.clarke import K_BETA, clarke
from .xform_steps.duty_scale import duty_scale
from .xform_steps.inv_clarke import K_SHIFT as IC_SHIFT, K_SQ3, inv_clarke
from .xform_steps.inv_park import inv_park
from .xform_steps.min_sub import min_sub
from .xform_steps.park import park

W = F.OPW                     # 18: every datapath word (I_W = V_W = TRIG_W = OPW)
SH = F.TRIG_FRAC              # 16: the one output window: y = acc >> 16
RND = 1 << (SH - 1)           # 2**15
PIPE = 5                      # clocks from a pass's last row to the first row that may read its result
ACC_BITS = 38                 # accumulator bits used (|acc| < 2**37; u_to_v reaches 2**35)
assert F.I_W == F.V_W == F.TRIG_W == W and SH == 16

# ---- constants (all fit a signed 18-bit operand) --------------------------------------
K1 = (1 << (W - 1)) - 1                 # 131071
K2 = K_BETA - K1                        # 20278: K1 + K2 = K_BETA
IC_HI, IC_LO = divmod(K_SQ3, 1 << (IC_SHIFT - SH))   # 56755, 27
IC_T = IC_LO << (SH - (IC_SHIFT - SH))  # 27 * 2**11 = 55296: t = (u_beta * IC_T) >> 16
KL_BITS = F.KDC_FRAC + F.V_FRAC - SH    # 4: kdc = (kh << 4) + kl
UV_SH = F.U_FRAC - F.V_FRAC             # 4: u (Q.8) -> transform voltage (Q.4)
UL_BITS = F.U_W - W                     # 6: u = (uh << 6) + ul
assert 0 < K2 < K1 and IC_T < K1 and IC_HI < K1 and KL_BITS == 4 and UV_SH == 4 and UL_BITS == 6

# ---- register files --------------------------------------------------------------------
# RF_A (A operands, written by passes).  Addresses 14/15 read the minimum selected by FLAG1/2;
# BETA (front) shares its address with UA (mod); UDV/UQV (12/13) do not count for ``sat``.
RFA = {n: i for i, n in enumerate(["UA", "UB", "T1", "T2", "PB", "PC", "WA", "WB", "WC",
                                    "TWA", "TWB", "TWC", "UDV", "UQV"])}
RFA["BETA"] = RFA["UA"]
RFA_M1, RFA_M = 14, 15                  # min(u_A, u_B) / min(u_A, u_B, u_C)
NOSAT = ("UDV", "UQV", "FLAG1", "FLAG2")
# RF_B (B operands): sin, cos, -sin written by the trig passes, the rest constants (LUT-RAM init)
RFB_CONST = {"ONE": (0, 1), "P65536": (4, 1 << SH), "N65536": (5, -(1 << SH)),
             "K1": (6, K1), "K2": (7, K2), "NK1": (8, -K1), "NK2": (9, -K2),
             "PT": (10, IC_T), "NT": (11, -IC_T), "PH": (12, IC_HI), "NH": (13, -IC_HI),
             "NHALF": (14, -(1 << (SH - 1))), "C4096": (15, 1 << (SH - 4))}
RFB = {"S": 1, "C": 2, "MS": 3, **{n: a for n, (a, _) in RFB_CONST.items()}}
assert RFB["N65536"] == RFB["P65536"] ^ 1      # the trig sign flips address bit 0


def rfb_init() -> list[int]:
    """Initial RF_B contents (16 words; entries 1..3 are written before they are read)."""
    v = [0] * 16
    for a, c in RFB_CONST.values():
        v[a] = c
    return v


# ---- microword (18 bits: one block-RAM word) ------------------------------------------------
# a: 0..12 RF_A entries, 14/15 dynamic minimum, 16..21 sine-node rows, 24..28 inputs
A_CODE = {**RFA, "M1": RFA_M1, "M": RFA_M,
          "ROM_S0": 16, "ROM_S1": 17, "ROM_C0": 18, "ROM_C1": 19, "ROM_MS0": 20, "ROM_MS1": 21,
          "IA16": 24, "IB4": 25, "IC4": 26, "UHD": 27, "UHQ": 28, "ULD": 29, "ULQ": 30}
# b: 0..15 RF_B entries, 16.. special operands
B_CODE = {**RFB, "F": 16, "KH": 17, "KL": 18}
C_SEL = {"ACC": 0, "ZERO": 1, "RND": 2, "TRIG": 3}
DST = {**{n: a for n, a in RFA.items()}, "NONE": 16, "S": 17, "C": 18, "MS": 19,
       "FLAG1": 20, "FLAG2": 21, "ID": 24, "IQ": 25, "CMPA": 28, "CMPB": 29, "CMPC": 30}
LAYOUT = U.Layout((("a", 5), ("b", 5), ("c_sel", 2), ("wait", 1), ("dst", 5)))  # LSB first
UCW = LAYOUT.width                                                              # 18
FINAL = ("IQ", "CMPC")                                                          # the last write of an operation
ROM_DEPTH = 1 << 10                                                             # 1024 x 18 block RAM
assert UCW == W


@dataclass(frozen=True)
class Row:
    """One issue slot: product a * b (operand names), accumulator load, write-back."""
    a: str                   # RF_A name, "M1"/"M" (minimum), ROM_<S|C|MS><0|1>, IA16, IB4, IC4, UH*, UL*
    b: str                   # RF_B name, or F (trig fraction), KH, KL
    c: str = "ACC"           # ACC (accumulate) or the value loaded first: ZERO, RND, TRIG
    wait: bool = False
    dst: str = "NONE"        # set on a pass's last row

    @property
    def trig(self) -> str | None:
        return self.a[4:-1] if self.a.startswith("ROM_") else None

    def word(self) -> int:
        return LAYOUT.pack(a=A_CODE[self.a], b=B_CODE[self.b], c_sel=C_SEL[self.c], wait=int(self.wait),
                           dst=DST[self.dst])


def _trig(k: str) -> list[Row]:
    return [Row(f"ROM_{k}0", "F", "TRIG"), Row(f"ROM_{k}1", "F", dst=k)]


def _pass(products, c: str, dst: str, wait: bool = False) -> list[Row]:
    rows = [Row(a, b) for a, b in products]
    rows[0] = Row(rows[0].a, rows[0].b, c, wait=wait)
    rows[-1] = Row(rows[-1].a, rows[-1].b, rows[-1].c, rows[-1].wait, dst)
    return rows


FRONT = (_trig("S") + _trig("C") + _trig("MS")
         + _pass([("IB4", "K1"), ("IB4", "K2"), ("IC4", "NK1"), ("IC4", "NK2")], "RND", "BETA")
         + _pass([("IA16", "C"), ("BETA", "S")], "RND", "ID", wait=True)             # i_d = c a + s b
         + _pass([("BETA", "C"), ("IA16", "MS")], "RND", "IQ"))                      # i_q = c b - s a
MOD = (_trig("S") + _trig("C") + _trig("MS")
       + _pass([("UHD", "P65536")] * 4 + [("ULD", "C4096")], "RND", "UDV")           # u_to_v(u_d)
       + _pass([("UHQ", "P65536")] * 4 + [("ULQ", "C4096")], "RND", "UQV")           # u_to_v(u_q)
       + _pass([("UDV", "C"), ("UQV", "MS")], "RND", "UA", wait=True)                # u_alpha
       + _pass([("UDV", "S"), ("UQV", "C")], "RND", "UB")                            # u_beta
       + _pass([("UB", "PT")], "ZERO", "T1", wait=True)                              # floor(u_beta 27/32)
       + _pass([("UB", "NT")], "ZERO", "T2")                                         # floor(-u_beta 27/32)
       + _pass([("UB", "PH"), ("T1", "ONE"), ("UA", "NHALF")], "RND", "PB", wait=True)   # u_B
       + _pass([("UB", "NH"), ("T2", "ONE"), ("UA", "NHALF")], "RND", "PC")          # u_C
       + _pass([("UA", "P65536"), ("PB", "N65536")], "ZERO", "FLAG1", wait=True)     # u_A < u_B ?
       + _pass([("M1", "P65536"), ("PC", "N65536")], "ZERO", "FLAG2", wait=True)     # m1 < u_C ?
       + _pass([("UA", "P65536"), ("M", "N65536")], "ZERO", "WA", wait=True)         # w = u - min
       + _pass([("PB", "P65536"), ("M", "N65536")], "ZERO", "WB")
       + _pass([("PC", "P65536"), ("M", "N65536")], "ZERO", "WC")
       + _pass([("WA", "KL")], "ZERO", "TWA", wait=True)                             # floor(w kl / 16)
       + _pass([("WB", "KL")], "ZERO", "TWB")
       + _pass([("WC", "KL")], "ZERO", "TWC")
       + _pass([("WA", "KH"), ("TWA", "ONE")], "RND", "CMPA", wait=True)             # compare values
       + _pass([("WB", "KH"), ("TWB", "ONE")], "RND", "CMPB")
       + _pass([("WC", "KH"), ("TWC", "ONE")], "RND", "CMPC"))
PROGRAM = FRONT + MOD
ENTRY = {"front": 0, "mod": len(FRONT)}
PC_BITS = 6
UC_BASE = ROM_DEPTH - (1 << PC_BITS)          # microprogram rows in the block RAM
assert len(PROGRAM) <= 1 << PC_BITS


# ---- static timing ------------------------------------------------------------------------
def _reads(r: Row) -> list[str]:
    out = []
    if r.a == "M1":
        out += ["FLAG1", "UA", "PB"]
    elif r.a == "M":
        out += ["FLAG1", "FLAG2", "UA", "PB", "PC"]
    elif r.a in RFA:
        out.append(r.a)
    if r.b in ("S", "C", "MS"):
        out.append(r.b)
    return out


def schedule(rows: list[Row]) -> dict:
    """Issue cycle of every row (first row at 0) under the hardware's stall rule, with checks.

    A row with ``wait`` issues only when no earlier pass is in flight (its last row issued
    >= PIPE clocks ago); a pass writes its result at (last row) + PIPE - 1, readable from
    (last row) + PIPE on.  Raises AssertionError on a read-before-write hazard, a pass
    without a destination, or a register written twice.  Returns ``{"issue": [...],
    "done": cycle of done relative to the first issue}``.
    """
    t, issue, last_write = -1, [], None
    ready: dict[str, int] = {}
    open_pass = False
    for r in rows:
        t += 1
        if r.wait and last_write is not None:
            t = max(t, last_write + PIPE)
        if r.c != "ACC":
            assert not open_pass, f"pass started before the previous one ended: {r}"
            open_pass = True
        assert open_pass, f"row outside a pass: {r}"
        for name in _reads(r):
            assert name in ready and t >= ready[name], f"{r}: reads {name} before it is written (cycle {t})"
        issue.append(t)
        if r.dst != "NONE":
            assert r.dst not in ready, f"{r.dst} written twice"
            ready[r.dst] = t + PIPE
            last_write = t
            open_pass = False
    assert not open_pass and rows[-1].dst in FINAL
    return {"issue": issue, "done": issue[-1] + PIPE}


def latency(op: str) -> int:
    """Clock cycles from the start cycle to the done cycle of ``op`` ("front" or "mod")."""
    rows = FRONT if op == "front" else MOD
    return 1 + schedule(rows)["done"]            # the first row issues the cycle after start


# ---- block RAM image -------------------------------------------------------------------
def rom_words() -> list[int]:
    """1024 x 18 block RAM: rows 0..512 sine nodes T[k] = round(2**16 sin(k pi/1024))
    (see :mod:`sincos`), rows UC_BASE + pc the microprogram, the rest 0."""
    t = SC.node_values()
    words = t + [0] * (ROM_DEPTH - len(t))
    for pc, r in enumerate(PROGRAM):
        words[UC_BASE + pc] = r.word()
    return words


def trig_fold(angle: int, kind: str) -> tuple[int, int, bool]:
    """(node index k, fraction f = 0..32, negative) for sin / cos / -sin (kind S, C, MS):
    |value| = T[k] + ((D[k] f + 16) >> 5); odd quadrants use k = ~r[13:5], f = ~r[4:0] + 1."""
    a = angle & 0xFFFF
    q1, q0 = (a >> 15) & 1, (a >> 14) & 1
    odd = q0 ^ (kind == "C")
    neg = {"S": q1, "C": q1 ^ q0, "MS": q1 ^ 1}[kind]
    rr = (a & 0x3FFF) ^ (0x3FFF if odd else 0)
    return rr >> 5, (rr & 31) + odd, bool(neg)


# ---- instruction-level model ----------------------------------------------------------------
def run(op: str, *, angle: int, i_a: int = 0, i_b: int = 0, i_c: int = 0, u_d: int = 0, u_q: int = 0,
        kdc: int = 0, half_period: int = 0) -> dict:
    """Execute ``op``'s microprogram the way the datapath does (sequential semantics; the
    timing is checked separately by :func:`schedule`).  ``half_period`` (PWM_HALF_PERIOD)
    is needed for "mod" only.  Returns the outputs (``i_d, i_q`` or ``cmp``), ``sat`` and
    the register files for inspection."""
    hp = half_period
    rom = _ROM
    rfa, rfb = [0] * 16, rfb_init()
    flag = {"FLAG1": False, "FLAG2": False}
    m1 = m = 0
    acc = 0
    out: dict = {}
    sat = False
    cmp = [0, 0, 0]
    for r in (FRONT if op == "front" else MOD):
        k = f = 0
        neg = False
        if r.trig:
            k, f, neg = trig_fold(angle, r.trig)
        second = r.a.endswith("1")                          # T[k+1] row (else T[k])
        # operands
        if r.trig:
            a = rom[k + second]
        elif r.a in ("IA16", "IB4", "IC4", "UHD", "UHQ", "ULD", "ULQ"):
            a = {"IA16": i_a << 4, "IB4": i_b << 2, "IC4": i_c << 2, "UHD": u_d >> UL_BITS, "UHQ": u_q >> UL_BITS,
                 "ULD": u_d & ((1 << UL_BITS) - 1), "ULQ": u_q & ((1 << UL_BITS) - 1)}[r.a]
        else:
            a = rfa[{"M1": m1, "M": m}.get(r.a, RFA.get(r.a))]
        if r.b == "F":
            fr = f if second else 32 - f
            b = (-fr if neg else fr) << 11
        elif r.b == "KH":
            b = kdc >> KL_BITS
        elif r.b == "KL":
            b = (kdc & ((1 << KL_BITS) - 1)) << (SH - KL_BITS)
        else:
            b = rfb[RFB[r.b]]
        assert -(1 << (W - 1)) <= a < (1 << (W - 1)) and -(1 << (W - 1)) <= b < (1 << (W - 1)), (r, a, b)
        if r.c != "ACC":
            acc = {"ZERO": 0, "RND": RND, "TRIG": RND - (1 << 11) if neg else RND}[r.c]
        acc += a * b
        assert -(1 << (ACC_BITS - 1)) <= acc < (1 << (ACC_BITS - 1)), (r, acc)     # fits ACC_BITS
        if r.dst == "NONE":
            continue
        y, ovf = F.sat_flag(acc >> SH, W)
        if r.dst in ("FLAG1", "FLAG2"):
            flag[r.dst] = acc < 0
            if r.dst == "FLAG1":
                m1 = RFA["UA"] if acc < 0 else RFA["PB"]
            else:
                m = m1 if acc < 0 else RFA["PC"]
            continue
        if r.dst.startswith("CMP"):
            clamp = (acc >> SH) > hp
            y = hp if clamp else y
            sat |= clamp
            cmp["ABC".index(r.dst[-1])] = y
        if r.dst not in NOSAT:
            sat |= ovf
        if r.dst in RFA:
            rfa[RFA[r.dst]] = y
        elif r.dst in ("S", "C", "MS"):
            rfb[RFB[r.dst]] = y
        elif r.dst == "ID":
            out["i_d"] = y
        elif r.dst == "IQ":
            out["i_q"] = y
    if op == "mod":
        out["cmp"] = tuple(cmp)
    out.update(sat=sat, rfa=rfa, rfb=rfb)
    return out


_ROM = rom_words()


# ---- specification (composition of the step models) ----------------------------------------
def front(i_a: int, i_b: int, i_c: int, angle: int) -> tuple[int, int, bool]:
    """(i_d, i_q, sat) = clarke -> park(sincos(angle)), sat = OR of the step flags."""
    al, be, s0 = clarke(i_a, i_b, i_c)
    s, c = SC.sincos(angle)
    i_d, i_q, s1 = park(al, be, s, c)
    return i_d, i_q, s0 or s1


def u_to_v(u: int) -> int:
    """MPC voltage (Q16.8, 24 bit) -> transform voltage (Q14.4, 18 bit): round half up, saturate
    (as ctrl_seq.py)."""
    return F.sat(F.rshift_round(u, UV_SH), W)


def modulate(u_d: int, u_q: int, angle: int, kdc: int, half_period: int) -> tuple[int, int, int, bool]:
    """(cmp_a, cmp_b, cmp_c, sat) = u_to_v -> inv_park -> inv_clarke -> min_sub -> duty_scale,
    u_d/u_q in Q16.8 (U_W bit)."""
    s, c = SC.sincos(angle)
    ua, ub, s1 = inv_park(u_to_v(u_d), u_to_v(u_q), s, c)
    va, vb, vc, s2 = inv_clarke(ua, ub)
    wa, wb, wc, s3 = min_sub(va, vb, vc)
    ca, cb, cc, s4 = duty_scale(wa, wb, wc, kdc, half_period)
    return ca, cb, cc, s1 or s2 or s3 or s4


# ---- generated Verilog ----------------------------------------------------------------------
def _hdr(what: str, cmd: str) -> list[str]:
    return U.header("empc.rtlmodel.xform", what, "rtl/xform.v", cmd, f"rtl/xform_{cmd}.vh", "tb/test_xform.py")


def rom_vh() -> str:
    """Text of ``rtl/xform_rom.vh`` (inside the block RAM's ``initial`` block)."""
    lines = _hdr("rom_vh", "rom")
    lines.append(f"// rows 0..512: T[k] = round(2**16 sin(k pi/1024)); rows {UC_BASE}..: microprogram "
                 f"(fields: {LAYOUT.doc()}, LSB first); other rows 0.")
    words = rom_words()
    keep = {i: w for i, w in enumerate(words) if i <= 512 or UC_BASE <= i < UC_BASE + len(PROGRAM)}
    notes = {UC_BASE + pc: f"pc {pc} {'front' if pc < len(FRONT) else 'mod'}: {_row_text(r)}"
             for pc, r in enumerate(PROGRAM)}
    lines += U.rom_lines("rom", W, keep, notes)
    return "\n".join(lines) + "\n"


def _row_text(r: Row) -> str:
    c = "" if r.c == "ACC" else f"acc = {r.c}; "
    w = "wait, " if r.wait else ""
    d = "" if r.dst == "NONE" else f" -> {r.dst}"
    return f"{w}{c}acc += {r.a} * {r.b}{d}"


# the codes rtl/xform.v refers to by name
RTL_CODES = {"A_UA", "A_PB", "A_PC", "A_M1", "A_M", "A_IA16", "A_IB4", "A_IC4", "A_UHD", "A_UHQ", "A_ULD",
             "A_ULQ", "D_UDV",
             "B_F", "B_KH", "C_ACC", "C_RND", "C_TRIG", "D_NONE", "D_FLAG1", "D_FLAG2", "D_ID", "D_IQ",
             "D_CMPA", "D_CMPB", "D_CMPC"}


def ucode_vh() -> str:
    """Text of ``rtl/xform_ucode.vh`` (module scope): microword codes, RF_B initial contents,
    program entry points (the microprogram itself is in the block RAM image)."""
    lines = _hdr("ucode_vh", "ucode")
    lines.append("// microword fields (LSB first): " + LAYOUT.doc())
    lines.append(f"localparam integer PCW = {PC_BITS};")
    lines += U.localparams("PC_", {"FRONT": ENTRY["front"], "MOD": ENTRY["mod"]}, PC_BITS)
    lines.append(f"localparam [9:0] UC_BASE = 10'd{UC_BASE};")
    for prefix, table, width in (("A_", A_CODE, 5), ("B_", B_CODE, 5), ("C_", C_SEL, 2), ("D_", DST, 5)):
        items = U.localparams(prefix, table, width, names=RTL_CODES)
        vals = [x.split(" = ")[1] for line in items for x in line[:-1].split("] ", 1)[1].split(", ")]
        assert len(vals) == len(set(vals)) or prefix == "A_", items
        lines += items
    init = rfb_init()
    lines.append("localparam [16*W-1:0] RFB_INIT = {" + ", ".join(
        f"{W}'h{v & ((1 << W) - 1):05x}" for v in reversed(init)) + "};")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    import sys

    what = sys.argv[1] if len(sys.argv) > 1 else ""
    if what == "rom":
        sys.stdout.write(rom_vh())
    elif what == "ucode":
        sys.stdout.write(ucode_vh())
    else:
        sys.stdout.write(f"usage: python -m empc.rtlmodel.xform rom|ucode\nfront latency {latency('front')}, "
                         f"mod latency {latency('mod')}, {len(PROGRAM)} rows\n")
