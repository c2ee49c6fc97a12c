"""Microprogram of rtl/mx_seq.v, the word-parallel sequencer (docs/four_axes.md 3.4, docs/blocks/mx_seq.md).

What the sequencer computes is :class:`empc.rtlmodel.ctrl_seq.CtrlSeq` (``period``, its speed
estimate, field weakening and hold); this module says HOW the RTL computes it: the tables below are
the one source of the microprogram block RAM (``python -m empc.ucode`` writes rtl/mx_seq_ucode.vh and
rtl/mx_seq_rom.vh), and :func:`run_job` is an instruction-level model that executes those microwords
with the RTL's pipeline timing; tb/test_mx_seq.py checks it against CtrlSeq (fast, Python only) and
the RTL against CtrlSeq (cocotb).

Datapath (one op per clock, 48-bit, no multiplexer in front of the adder but the shift of A):
    issue (D)   the microword at pc; a waiting op holds pc.  RAM port B reads word ``rb`` of the job's
                axis ({axis, word}); the A source is staged (a register cleared unless selected)
    E           A = OR of the staged sources | P, the shift ``ash`` applied to P only (theta's
                ash 1 in its stage; no other source may be shifted), negated if ``na``; B = mode ``bm`` of the
                RAM word (signed, or bits 31:16 / 31:24 unsigned with their rounding bit 15 / 23),
                negated if ``nb``; R = A + B + cin; P = R if ``pe`` (the forward path: the next op
                may take it as A, wrapped to 32 bits if ``aw``)
    W           W = sat32 / wrap32 / wrap36 / R of R; written to the destination ``dk`` (core input
                buffer, axis state RAM port A, status word, omega register, theta_mod register, the
                serial shifter) under the condition ``cond``; ``fs``: a saturation is a front_sat
                event; the actions (core start, modulation start, program end) happen here too
Hazards (the scheduler below inserts NOPs): a RAM word or a special register (omega, theta_mod,
shifter) is read >= 3 issues after the op that writes it; status words are written >= 2 issues apart.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

from .. import formats as F
from .. import regmap
from .. import ucode as U
from . import mpc_core as core
from .ctrl_seq import win_eff

# ---- microword ----------------------------------------------------------------------------
CTL = {"OP": 0, "WTH": 1, "WREF": 2, "WFRONT": 3, "WSH": 4, "START": 5, "WCORE": 6, "END": 7}
ASEL = {"NONE": 0, "POS": 1, "TH": 2, "ID": 3, "IQ": 4, "IDR": 5, "IQR": 6, "U0": 7, "U1": 8, "E0": 9,
        "E1": 10, "E2": 11, "PH": 12, "SH": 13, "OMR": 14, "P": 15}   # PH: pos_{k-M} (the position history's tap)
ASH = {0: 0, 1: 1, 8: 2, 16: 3}
BM = {"ZERO": 0, "Q": 1, "HI16": 2, "HI24": 3}
WM = {"SAT32": 0, "WRAP32": 1, "WRAP36": 2, "FULL": 3}
DK = {"NONE": 0, "CORE": 1, "RAM": 2, "STAT": 3, "OMR": 4, "THM": 5, "SHKA": 6, "SHT2": 7}
COND = {"ALWAYS": 0, "FIRST": 1, "LS": 2, "NOLS": 3}
UW = U.Layout((("ctl", 3), ("asel", 4), ("aw", 1), ("ash", 2), ("na", 1), ("nb", 1), ("bm", 2), ("rc", 1),
               ("cr", 1), ("rb", 5), ("pe", 1), ("wm", 2), ("fs", 1), ("dk", 3), ("da", 6), ("cond", 2)))
assert UW.width == 36

# ---- axis state RAM: 32 words of 36 bits per axis, address {axis, word} --------------------
WORDS = {"POS_PREV": 0, "SPD": 1, "NDSP": 2, "SPD_PREV": 3, "D": 4, "ID_PREV": 5, "IQ_PREV": 6, "OM_PREV": 7,
         "TH_PREV": 8}
REF0 = 12                     # w_{k+m}: low word at REF0 + 2 m, high word at REF0 + 2 m + 1 (m = 0..N_MAX)
RAM_WORDS = 32
RAM_W = 36
assert REF0 + 2 * (core.N_MAX + 1) <= RAM_WORDS

# ---- program layout -----------------------------------------------------------------------
ENTRY = {"SPD": 0, "POS": 96, "MOD": 192}
ROM_ROWS = 256
N_RANGE = range(1, core.N_MAX + 1)


def _a(name: str) -> int:
    return regmap.axis_reg(name).offset


@dataclass(frozen=True)
class Op:
    ctl: str = "OP"
    a: str = "NONE"
    aw: bool = False
    ash: int = 0
    na: bool = False
    nb: bool = False
    bm: str = "ZERO"
    rb: str | int = 0           # RAM word (name or number)
    rc: bool = False            # cin = rounding bit of the RAM word (bm HI16: bit 15, HI24: bit 23)
    cr: bool = False            # cin = the shifter's rounding bit
    pe: bool = False
    wm: str = "WRAP32"
    fs: bool = False
    dk: str = "NONE"
    da: str | int = 0           # destination word (core input word, RAM word name, status offset)
    cond: str = "ALWAYS"
    note: str = ""

    @property
    def rbn(self) -> int:
        return WORDS[self.rb] if isinstance(self.rb, str) else self.rb

    @property
    def dan(self) -> int:
        return WORDS[self.da] if isinstance(self.da, str) else self.da

    def reads_ram(self) -> int | None:
        return self.rbn if self.bm != "ZERO" else None

    def writes(self) -> tuple[str, int] | None:
        if self.dk == "RAM":
            return ("RAM", self.dan)
        if self.dk in ("OMR", "THM"):
            return (self.dk, 0)
        if self.dk in ("SHKA", "SHT2"):
            return ("SH", 0)
        return None

    def reads(self) -> list[tuple[str, int]]:
        out = []
        if self.reads_ram() is not None:
            out.append(("RAM", self.rbn))
        if self.a in ("OMR",):
            out.append(("OMR", 0))
        if self.a == "SH" or self.ctl == "WSH":
            out.append(("SH", 0))
        return out

    def word(self) -> int:
        assert int(self.na) + int(self.nb) + int(self.rc) + int(self.cr) <= 1, f"two carry-ins: {self}"
        assert not self.rc or self.bm in ("HI16", "HI24"), self
        # the RTL shifts P (the forward path) and theta (in its stage, by 1 only), no other source
        assert self.ash == 0 or self.a == "P", f"shift of {self.a}: {self}"
        return UW.pack(ctl=CTL[self.ctl], asel=ASEL[self.a], aw=int(self.aw), ash=ASH[self.ash], na=int(self.na),
                       nb=int(self.nb), bm=BM[self.bm], rc=int(self.rc), cr=int(self.cr), rb=self.rbn,
                       pe=int(self.pe), wm=WM[self.wm], fs=int(self.fs), dk=DK[self.dk], da=self.dan,
                       cond=COND[self.cond])


NOP = Op(note="(pipeline gap)")
SH_WIN = 1        # da of a shifter load (dk SHT2): 1 = m steps (KACC.win), 0 = load_shift + 1 - m steps (>= 0)
SH_W = 40         # serial shifter: |kacc i_q| < 2^35; |t2| = |2 (ka - D) + ndsp| < 2^37 (D wraps at 36 bits)
HAZARD = 3        # a RAM word / special register is read >= 3 issues after its write
STAT_GAP = 2      # after a status-word write, the next STAT or CORE write >= 2 issues later: axis_status defers
                  # one that meets a CPU read and takes st_addr / st_wdata in the next clock, which the RTL
                  # holds (the same registers as core_in_addr / core_in_wdata, loaded by either write)


def _theta_ops() -> list[Op]:
    return [Op("WTH", "TH", pe=True, dk="RAM", da="TH_PREV", cond="FIRST",
               note="P = theta; first period: theta_prev = theta"),
            Op(a="P", ash=1, nb=True, bm="Q", rb="TH_PREV", dk="THM",
               note="theta_mod = 2 theta - theta_prev (16 bit)"),
            Op(a="TH", dk="RAM", da="TH_PREV", note="theta_prev = theta")]


def _trigger_ops(n: int, task_pos: bool) -> list[Op]:
    """From the trigger: every core input word that does not depend on the currents."""
    ops = [Op(a="POS", nb=True, bm="Q", rb="POS_PREV", pe=True, note="P = dpos = pos - pos_prev"),
           Op(a="P", aw=True, ash=8, wm="SAT32", fs=True, dk="CORE", da=core.IN_DX + 3,
              note="dx3 = sat32(dpos << 8)"),
           Op(a="POS", dk="RAM", da="POS_PREV", note="pos_prev = pos"),
           Op(dk="CORE", da=core.IN_DX + 4, note="dx4 = 0")]
    # the speed over the window M = 2^m (KACC.win): spd = sat32((pos - pos_{k-M}) << (16 - m)) as
    # sat32(((dpos_M << 8) >>> m) << 8) (exact: m <= F.WIN_LOG2_MAX < 8), the shift by m on the serial shifter;
    # the ebar / u_prev words fill the hazard gaps
    e = [Op(a=f"E{o}", dk="CORE", da=core.IN_EBAR + o, note=f"ebar_prev[{o}]") for o in range(3)]
    u = [Op(a=f"U{o}", dk="CORE", da=core.IN_UPREV + o, note=f"u_prev[{o}]") for o in range(2)]
    ops += [e[0],
            Op(a="PH", na=True, bm="Q", rb="POS_PREV", pe=True, note="P = dpos_M = pos - pos_{k-M}"),
            Op(a="P", aw=True, ash=8, wm="FULL", dk="SHT2", da=SH_WIN, note="shifter = dpos_M << 8, m steps"),
            e[1], e[2],
            Op("WSH", "SH", pe=True, note="P = (dpos_M << 8) >>> m"),
            Op(a="P", ash=8, wm="SAT32", fs=True, dk="RAM", da="SPD", note="spd = sat32(P << 8)"),
            u[0], u[1]]
    ops += [Op(bm="Q", rb="SPD", pe=True, note="P = spd"),
            Op(a="P", na=True, bm="Q", rb="SPD_PREV", wm="WRAP36", dk="RAM", da="NDSP",
               note="ndsp = spd_prev - spd"),
            Op(a="P", wm="WRAP36", dk="RAM", da="SPD_PREV", note="spd_prev = spd")]
    ops += _theta_ops()
    for m in range(n + 1):
        lo, hi = REF0 + 2 * m, REF0 + 2 * m + 1
        wa = core.IN_WREF + 3 * m
        wait = "WREF" if m == 0 else "OP"          # the references read from ref_gen (prefetch)
        if task_pos:
            ops += [Op(wait, "POS", na=True, bm="Q", rb=hi, pe=True, note=f"P = w_hi[{m}] - pos"),
                    Op(a="P", aw=True, ash=8, bm="HI24", rb=lo, rc=True, wm="SAT32", dk="CORE", da=wa + 2,
                       note=f"w3[{m}] = sat32(wrap32(P) << 8 + round(w_lo >> 24))")]
            if m == 0:
                ops += [Op(bm="Q", rb=hi, pe=True, note="P = w_hi[0]"),
                        Op(a="P", ash=8, bm="HI24", rb=lo, dk="STAT", da=_a("REF"), note="REF = w_k bits 55:24")]
        else:
            ops += [Op(wait, bm="Q", rb=hi, pe=True, note=f"P = w_hi[{m}]"),
                    Op(a="P", ash=16, bm="HI16", rb=lo, rc=True, wm="SAT32", dk="CORE", da=wa + 2,
                       note=f"w3[{m}] = sat32(P << 16 + round(w_lo >> 16))")]
            if m == 0:
                ops += [Op(a="P", ash=16, bm="HI16", rb=lo, dk="STAT", da=_a("REF"), note="REF = w_k bits 47:16")]
        ops += [Op(a="IDR", dk="CORE", da=wa, note=f"wref[{m}] id_ref"),
                Op(a="IQR", dk="CORE", da=wa + 1, note=f"wref[{m}] iq_ref")]
    return ops


def _dependent_ops(task_pos: bool) -> list[Op]:
    """From the front's done: the words that depend on i_d, i_q, then the core start."""
    return [Op("WFRONT", "ID", dk="CORE", da=core.IN_Y + 0, note="y0 = i_d"),
            Op(a="ID", nb=True, bm="Q", rb="ID_PREV", dk="CORE", da=core.IN_DX + 0, note="dx0 = i_d - i_d,prev"),
            Op(a="IQ", dk="CORE", da=core.IN_Y + 1, note="y1 = i_q"),
            Op(a="IQ", nb=True, bm="Q", rb="IQ_PREV", dk="CORE", da=core.IN_DX + 1, note="dx1 = i_q - i_q,prev"),
            Op(dk="SHKA", note="shifter = kacc * i_q (xform's product, loaded directly), kacc_shift steps"),
            Op("WSH", "SH", cr=True, pe=True, note="P = ka = rshift_round(kacc i_q, s)"),
            Op(a="P", nb=True, bm="Q", rb="D", pe=True, note="P = u1 = ka - D"),
            Op(a="P", bm="Q", rb="SPD", wm="SAT32", fs=True, dk="OMR", note="omega = sat32(spd + u1)"),
            Op(a="P", ash=1, wm="FULL", dk="SHT2", da=SH_WIN, note="shifter = 2 u1, m steps"),
            Op(a="OMR", dk="CORE", da=core.IN_OMEGA, note="omega"),
            Op(a="NONE" if task_pos else "OMR", dk="CORE", da=core.IN_Y + 2,
               note="y2 = 0 (position task)" if task_pos else "y2 = omega"),
            Op(a="OMR", nb=True, bm="Q", rb="OM_PREV", wm="SAT32", fs=True, dk="CORE", da=core.IN_DX + 2,
               note="dx2 = sat32(omega - omega_prev)"),
            Op("START", note="core start (or, law off, skip)")]


def _post_ops() -> list[Op]:
    """While the core runs: the previous-sample words, the status words, the load estimate."""
    return [Op(a="OMR", dk="RAM", da="OM_PREV", note="omega_prev"),
            Op(a="ID", dk="RAM", da="ID_PREV", note="i_d,prev"),
            Op(a="IQ", dk="RAM", da="IQ_PREV", note="i_q,prev"),
            Op(a="OMR", dk="STAT", da=_a("SPEED"), note="SPEED"),
            Op(a="ID", dk="STAT", da=_a("I_D"), note="I_D"),
            Op(a="IQ", dk="STAT", da=_a("I_Q"), note="I_Q"),
            Op("WSH", "SH", bm="Q", rb="NDSP", wm="FULL", dk="SHT2",
               note="shifter = t2 = (2 u1 >>> m) - (spd - spd_prev), load_shift + 1 - m steps (>= 0)"),
            Op("WSH", "SH", bm="Q", rb="D", wm="WRAP36", dk="RAM", da="D", cond="LS",
               note="D += t2 >>> (load_shift + 1)"),
            Op(wm="WRAP36", dk="RAM", da="D", cond="NOLS", note="D = 0 (no load estimate)")]


def _mod_ops() -> list[Op]:
    return [Op("WCORE", note="modulation start (held u, theta_mod), after the core"),
            Op(a="U0", dk="STAT", da=_a("U_D"), note="U_D = the u applied"),
            Op(a="U1", dk="STAT", da=_a("U_Q"), note="U_Q"),
            Op("END", note="program end")]


def schedule(ops: list[Op]) -> list[Op]:
    """Insert NOPs so that every read of a RAM word / special register comes >= HAZARD issues after
    its write (in-order, static; waits only delay an issue, never reorder)."""
    out: list[Op] = []
    last_w: dict[tuple[str, int], int] = {}
    last_st = -10
    for op in ops:
        need = max([last_w[r] + HAZARD for r in op.reads() if r in last_w] + [len(out)])
        if op.dk in ("STAT", "CORE"):        # axis_status defers one write that meets a CPU read
            need = max(need, last_st + STAT_GAP)
        if op.dk == "STAT":
            last_st = need
        while len(out) < need:
            out.append(NOP)
        w = op.writes()
        if w is not None:
            last_w[w] = len(out)
        out.append(op)
    return out


def program(kind: str, n: int) -> list[Op]:
    """The scheduled program of ``kind`` (SPD, POS: control periods of the task; MOD: modulation only)."""
    if kind == "MOD":
        ops = _theta_ops() + _mod_ops()
    else:
        tp = kind == "POS"
        ops = _trigger_ops(n, tp) + _dependent_ops(tp) + _post_ops() + _mod_ops()
    prog = schedule(ops)
    return prog


def programs(n: int) -> dict[int, Op]:
    out = {}
    ends = sorted(ENTRY.values()) + [ROM_ROWS]
    for kind, e in ENTRY.items():
        prog = program(kind, n)
        nxt = min(x for x in ends if x > e)
        assert e + len(prog) <= nxt, f"program {kind} (N={n}) has {len(prog)} rows, room for {nxt - e}"
        out.update({e + i: op for i, op in enumerate(prog)})
    return out


def rom_image(n: int) -> list[int]:
    prog = programs(n)
    return [prog.get(pc, Op("END")).word() for pc in range(ROM_ROWS)]


# ---- generated Verilog --------------------------------------------------------------------
def _hdr(what: str, cmd: str) -> list[str]:
    return U.header("empc.rtlmodel.mx_seq", what, "rtl/mx_seq.v", cmd, f"rtl/mx_seq_{cmd}.vh", "tb/test_mx_seq.py")


# the names rtl/mx_seq.v refers to (the others stay out of the header: no unused localparams)
RTL_NAMES = {*(f"UW_{n.upper()}" for n, _ in UW.fields), *(f"CTL_{n}" for n in CTL if n != "OP"),
             *(f"AS_{n}" for n in ASEL if n != "NONE"), "BM_ZERO", "BM_Q", "BM_HI16", "WM_SAT32",
             *(f"DK_{n}" for n in DK if n != "NONE"), *(f"CD_{n}" for n in COND if n != "ALWAYS"),
             *(f"PC_{n}" for n in ENTRY), "SW_REF0"}


def ucode_vh() -> str:
    lines = _hdr("ucode_vh", "ucode")
    lines.append(f"// microword (LSB first): {UW.doc()}")
    lines += UW.positions("UW_")
    lines += U.localparams("CTL_", CTL, 3, names=RTL_NAMES)
    lines += U.localparams("AS_", ASEL, 4, names=RTL_NAMES)
    lines += U.localparams("BM_", BM, 2, names=RTL_NAMES)
    lines += U.localparams("WM_", WM, 2, names=RTL_NAMES)
    lines += U.localparams("DK_", DK, 3, names=RTL_NAMES)
    lines += U.localparams("CD_", COND, 2, names=RTL_NAMES)
    lines += U.localparams("PC_", ENTRY, 8, names=RTL_NAMES)
    lines += U.localparams("SW_", {**WORDS, "REF0": REF0}, 5, names=RTL_NAMES)
    chk = [f"`EMPC_IN_{n} == {getattr(core, 'IN_' + n)}" for n in ("Y", "OMEGA", "DX", "UPREV", "EBAR", "WREF")]
    chk += [f"`EMPC_A_{n} == {_a(n)}" for n in ("SPEED", "I_D", "I_Q", "U_D", "U_Q", "REF")]
    lines.append("// the core input words and status offsets the images were generated for")
    lines.append("localparam UC_MAP_OK = " + " &&\n    ".join(
        " && ".join(f"({c})" for c in chk[i:i + 4]) for i in range(0, len(chk), 4)) + ";")
    return "\n".join(lines) + "\n"


def _op_text(op: Op) -> str:
    parts = [op.ctl] if op.ctl != "OP" else []
    if op.note:
        parts.append(op.note)
    return " ".join(parts) if parts else "-"


def rom_vh() -> str:
    lines = _hdr("rom_vh", "rom")
    lines.append(f"// microprogram rom[pc] ({UW.doc()}); entries {ENTRY}; for the horizon N")
    end = Op("END").word()
    for n in N_RANGE:
        prog = programs(n)
        lines.append(f"if (N == {n}) begin")
        lines.append(f"    for (ui = 0; ui < {ROM_ROWS}; ui = ui + 1) rom[ui] = {U.word_literal(36, end)};   // END")
        for pc in sorted(prog):
            lines.append(f"    rom[{pc}] = {U.word_literal(36, prog[pc].word())};   // {pc} {_op_text(prog[pc])}")
        lines.append("end")
    return "\n".join(lines) + "\n"


# ---- instruction-level model ---------------------------------------------------------------
M48 = (1 << 48) - 1


@dataclass
class Ctx:
    """What a job sees: the sampled inputs, the registers and the held loop values."""
    pos: int
    theta: int
    i_d: int = 0
    i_q: int = 0
    kacc: int = 0
    kacc_shift: int = 0
    load_shift: int = 0
    win_shift: int = 0         # KACC.win (the speed window M = 2^m; above F.WIN_LOG2_MAX: as it)
    pos_m: int = 0             # pos_{k-M}: the history's tap (0 before M control samples after reset)
    id_ref: int = 0            # the d-current reference after field weakening (mpc_axis)
    iq_ref: int = 0
    u: tuple = (0, 0)          # held u (u_st), 0 while the law is off
    ebar: tuple = (0, 0, 0)    # the core's ebar, 0 if zeroed
    first: bool = False


THETA_LAT = 4      # rtl/mx_seq.v default: pos_sense's clocks from a count to its angle


def job_timing(t_valid: int, core_lat: int | None, theta_lat: int = THETA_LAT, delay: int = 0) -> dict:
    """The wait conditions of a job in :func:`run_job`'s clocks (clock 1 = the clock after the job's
    start cycle: the first issue).  ``t_valid``: the ADC's valid pulse, in clocks after the trigger
    cycle; ``core_lat``: mpc_core.latency(ncols), or None with the law off (run low); ``delay``: clocks
    from the trigger to the job's start (0: the trigger starts it; NAXES > 1: the job waited in the
    queue, :func:`schedule_axes`).
    rtl/mx_seq.v: adc_seen the clock after valid, th_ok the clock after theta_lat clocks, the front
    request the clock after all three of them and the job running (its start cycle), done
    ``xform.latency("front")`` later, front_done the clock after."""
    from . import xform
    req = max(delay + 1, t_valid + 1, theta_lat + 1)
    return {"th": 1 + theta_lat - delay, "front": req + 1 + xform.latency("front") + 1 - delay, "core_lat": core_lat}


def latency(kind: str, n: int, kacc_shift: int, load_shift: int, timing: dict, win_shift: int = 0) -> int:
    """The RTL's ``latency`` (trigger -> cmp_load, in clocks, its counter's convention) of a job whose
    references are ready (read before the control program's WREF step): the program executed clock by
    clock with the waits of ``timing`` (:func:`job_timing`), then the modulation: the WCORE op's W
    stage requests it (issue + 2), xform starts the clock after and is done ``xform.latency("mod")``
    later, cmp_load the clock after.  The latency register counts cmp_load's cycle - trigger's - 1.
    A pure function of its arguments, cached (:func:`schedule_axes` asks it for every job of a run)."""
    return _latency(kind, n, kacc_shift, load_shift, tuple(sorted(timing.items())), win_shift)


@functools.lru_cache(maxsize=4096)
def _latency(kind: str, n: int, kacc_shift: int, load_shift: int, timing_items: tuple, win_shift: int = 0) -> int:
    from . import xform
    ctx = Ctx(pos=0, theta=0, kacc_shift=kacc_shift, load_shift=load_shift, win_shift=win_shift)
    r = run_job(kind, n, {}, ctx, dict(timing_items))
    return r["wcore"] + 3 + xform.latency("mod")


@dataclass
class Job:
    """One PWM sample of one axis for :func:`schedule_axes`: the trigger's cycle and what the job runs."""
    axis: int
    t_trig: int                 # the cycle of the axis's adc_trig (the trigger taken)
    kind: str                   # SPD, POS (control) or MOD (modulation only)
    n: int
    t_valid: int                # the axis's ADC valid, clocks after its trigger (adc_spi valid_delay)
    kacc_shift: int = 0
    load_shift: int = 0
    core_lat: int | None = None  # mpc_core.latency(ncols), None with the law off
    win_shift: int = 0          # KACC.win


def schedule_axes(jobs: list[Job], theta_lat: int = THETA_LAT) -> list[dict]:
    """The job queue of rtl/mx_seq.v with NAXES > 1 (one job at a time, jobs in sample order,
    triggers of the same cycle: the lower axis first): every job's start cycle, its ``delay`` after its
    trigger, the RTL's ``latency`` register of its axis (trigger -> cmp_load, the counter's
    convention: cmp_load's cycle - trigger's - 1) and cmp_load's cycle.  A job starts in its trigger's
    cycle if the engine is free (busy_period low: from the cycle of the previous cmp_load on), else in
    the cycle of the running job's cmp_load.  The references are taken as read (the prefetch after the
    boundary ends long before the trigger with staggered carriers: docs/four_axes.md 3.3).  A trigger
    of an axis whose previous job is still waiting or running is not taken (the caller leaves it out:
    the RTL pulses that axis's overrun at its boundary)."""
    out = []
    free = None                 # the first cycle the engine is free again
    for j in sorted(jobs, key=lambda j: (j.t_trig, j.axis)):
        start = j.t_trig if free is None else max(j.t_trig, free)
        d = start - j.t_trig
        lat = d + latency(j.kind, j.n, j.kacc_shift, j.load_shift,
                          job_timing(j.t_valid, j.core_lat, theta_lat, delay=d), j.win_shift)
        t_load = j.t_trig + 1 + lat
        free = t_load           # busy_period falls with cmp_load: a waiting job starts in that cycle
        out.append({"job": j, "start": start, "delay": d, "latency": lat, "t_load": t_load})
    return out


def run_job(kind: str, n: int, ram: dict, ctx: Ctx, timing: dict | None = None) -> dict:
    """Execute program ``kind`` clock by clock with the RTL's pipeline (issue, E, W; RAM read data and
    staged sources at issue + 1, writes at the end of issue + 2); ``ram`` (word -> signed 36-bit value)
    is updated.  Returns the core input words, status words, theta_mod, the front-saturation flag,
    the shifter's busy clocks and ``wcore``, the issue clock of the WCORE step.  Without ``timing``
    the waits are taken as satisfied (data is there); with it (:func:`job_timing`) WTH, WFRONT and
    WCORE wait as in the RTL (the references are taken as read).  The shifter's waits are real."""
    tm = timing or {"th": 0, "front": 0, "core_lat": None}
    t_core = 0 if (kind == "MOD" or timing is None) else None     # core_fin from this clock on
    prog = program(kind, n)
    src = {"NONE": 0, "POS": ctx.pos & 0xFFFFFFFF, "PH": ctx.pos_m & 0xFFFFFFFF, "TH": ctx.theta, "ID": ctx.i_d, "IQ": ctx.i_q,
           "IDR": ctx.id_ref, "IQR": ctx.iq_ref, "U0": ctx.u[0], "U1": ctx.u[1], "E0": ctx.ebar[0], "E1": ctx.ebar[1],
           "E2": ctx.ebar[2]}
    out = {"core": {}, "stat": {}, "thm": None, "fs": False, "omr": None, "wcore": None}
    regs = {"P": 0, "OMR": 0, "SH": 0, "r": 0, "sh_left": 0, "THM": 0}
    pending = []               # (clock at whose end it lands, what)
    pc, clock = 0, 0
    pipe = []                  # ops in flight: (issue clock, op, staged A, q)
    while True:
        clock += 1
        # writes landing at the end of the previous clock are visible now
        for when, fn in [p for p in pending if p[0] < clock]:
            fn()
        pending = [p for p in pending if p[0] >= clock]
        # shifter steps (the RTL's first step is the clock after its load: not in the clock the load lands)
        if regs.pop("sh_load", False):
            pass
        elif regs["sh_left"] > 0:
            regs["r"] = regs["SH"] & 1
            regs["SH"] >>= 1
            regs["sh_left"] -= 1
        if pc >= len(prog):
            if not pipe and not pending:
                break
        else:
            op = prog[pc]
            wait = {"WTH": clock < tm["th"], "WFRONT": clock < tm["front"],
                    "WCORE": t_core is None or clock < t_core}.get(op.ctl, False)
            if op.ctl == "WSH" and (regs["sh_left"] > 0 or any(p[1].dk in ("SHKA", "SHT2") for p in pipe)):
                pass            # stall
            elif wait:
                pass
            else:
                if op.ctl == "WCORE":
                    out["wcore"] = clock
                q = ram.get(op.rbn, 0)
                if op.reads_ram() is not None:
                    assert not any(p[1].writes() == ("RAM", op.rbn) for p in pipe), f"RAM hazard at {pc}"
                a_src = {"SH": regs["SH"], "OMR": regs["OMR"]}.get(op.a, src.get(op.a, 0))
                pipe.append((clock, op, a_src, q))
                pc += 1
                if op.ctl == "END":
                    pc = len(prog)
        # E stage: op issued at clock - 1 (its staged values are those of issue time; P is live)
        for i, (t, op, a_src, q) in enumerate(pipe):
            if t == clock - 1:
                a = regs["P"] if op.a == "P" else a_src
                if op.a == "P" and op.aw:
                    a = F.wrap(a, 32)
                a = F.wrap(a << op.ash, 48)
                qs = F.wrap(q, RAM_W) & 0xFFFFFFFF
                b = {"ZERO": 0, "Q": F.wrap(q, RAM_W), "HI16": qs >> 16, "HI24": qs >> 24}[op.bm]
                cin = int(op.na or op.nb)
                if op.rc:
                    cin = (qs >> (15 if op.bm == "HI16" else 23)) & 1
                if op.cr:
                    cin = regs["r"]
                r = F.wrap((~a if op.na else a) + (~b if op.nb else b) + cin, 48)
                if op.pe:
                    regs["P"] = r
                pipe[i] = (t, op, r, q)
        # W stage: op issued at clock - 2
        for (t, op, r, q) in [p for p in pipe if p[0] == clock - 2]:
            if op.ctl == "START" and t_core is None:      # core_start (or, law off, core_fin) next clock
                t_core = clock + 1 if tm["core_lat"] is None else clock + 2 + tm["core_lat"]
            wv = {"SAT32": F.sat(r, 32), "WRAP32": F.wrap(r, 32), "WRAP36": F.wrap(r, 36), "FULL": r}[op.wm]
            if op.fs and wv != r:
                out["fs"] = True
            ok = {"ALWAYS": True, "FIRST": ctx.first, "LS": ctx.load_shift != 0,
                  "NOLS": ctx.load_shift == 0}[op.cond]
            if ok:
                def land(op=op, wv=wv):
                    if op.dk == "CORE":
                        out["core"][op.dan] = F.wrap(wv, 32)
                    elif op.dk == "STAT":
                        out["stat"][op.dan] = wv & 0xFFFFFFFF
                    elif op.dk == "RAM":          # R's low 36 bits (SAT32: the saturated word)
                        ram[op.dan] = F.wrap(wv if op.wm == "SAT32" else r, RAM_W)
                    elif op.dk == "OMR":
                        regs["OMR"] = F.wrap(wv, 32)
                        out["omr"] = regs["OMR"]
                    elif op.dk == "THM":
                        regs["THM"] = wv & 0xFFFF
                        out["thm"] = regs["THM"]
                    elif op.dk in ("SHKA", "SHT2"):   # SHKA: the product kacc * i_q, not R
                        regs["SH"] = F.wrap(ctx.kacc * ctx.i_q if op.dk == "SHKA" else wv, SH_W)
                        regs["r"] = 0
                        mw = win_eff(ctx.win_shift)
                        regs["sh_left"] = (ctx.kacc_shift if op.dk == "SHKA" else mw if op.dan == SH_WIN
                                           else max(ctx.load_shift + 1 - mw, 0))
                        regs["sh_load"] = True
                pending.append((clock, land))
        pipe = [p for p in pipe if p[0] > clock - 2]
        assert clock < 10000
    out["clocks"] = clock
    return out


if __name__ == "__main__":
    import sys

    what = sys.argv[1] if len(sys.argv) > 1 else ""
    if what in ("ucode", "rom"):
        sys.stdout.write(ucode_vh() if what == "ucode" else rom_vh())
    else:
        sys.stdout.write("usage: python -m empc.rtlmodel.mx_seq ucode|rom  (or python -m empc.ucode)\n")
