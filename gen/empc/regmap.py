"""CPU register map: the one source for the register blocks of the RTL, the RTL header,
the firmware's C header, the documentation and the Python driver.

The LPC4088 external memory controller sees the FPGA as 32-bit static memory
(CS0); addresses here are WORD addresses on emc_a.  Global registers sit at
0x000..0x0ff, axis n's registers at AXIS_BASE + n * AXIS_STRIDE, axis n's
coefficient-image window (write-only, into the inactive bank; `CMD.coef_swap`
makes it active at the next control-period boundary) at COEF_BASE + n * COEF_STRIDE.
The CPU sees word w at byte address EMC_CS0_BASE + 4 w (docs/registers.md).

Generated from these tables (``python -m empc.regmap --all``, or ``make regs``; the
tests in gen/tests/test_regmap.py fail when a committed file is stale):
  rtl/global_regs.v, rtl/axis_regs.v   register blocks (gen/empc/regblock.py)
  fw/empc_regs.h                       C header for the LPC4088 firmware (gen/empc/fwheader.py)
  docs/registers.md                    the table for people
and, by `empc roms`, empc_regs.vh (offsets, field positions and widths for the RTL).

A register is one ``Reg`` line; the attributes say what the generator builds:
  access    RO (input port, or ``const``), RW (stored: output port), WO (write pulses),
            W1C (sticky bits: set input, write 1 to clear)
  reset     reset value; a string names a macro of empc_formats.vh (build-dependent)
  width, signed, fields    data bits (a signed register reads back sign-extended)
  ext       the storage lives in another block (EXT): strobe/data or window ports
  const     RO register whose value is ``reset`` (no port)
  key       WO: one pulse, only when the written value equals key
  arm       key register: writing the key arms the block's unlock until the ``arm``-th pulse of the
            block input ``<port>_tick``; the next write to the block (any register) consumes it; a
            wrong value disarms and is refused
  unlock    names the key register (``arm``) whose unlock a write needs: refused unless armed
  floor     RW: a written value below floor is stored as floor
  guard     writes refused (unchanged, ``wr_refused`` pulse) while this input is high
  legal     allowed written values (range or tuple): others refuse the write
  wstrobe   RW: also a one-clock output ``<port>_wr`` when a write is accepted (freshness timers)
  port      port name when the lower-case register name will not do
  read      "copy" or "mux": read path of this register if not the block's default
Fields take reset, floor and legal too, and two attributes of their own: ``guard`` (a write that
would change this field while the input is high is refused; rewriting its value is accepted, and
a pulse field refuses a 1) and ``safe`` (the value a refused write still stores when it writes
exactly that value: CTRL.enable = 0 switches off even inside a refused write).  A refused write
changes nothing else.  Adding a register: docs/conventions.md.
"""
from __future__ import annotations

import argparse
import re
from dataclasses import dataclass, field
from pathlib import Path

from .formats import WIN_LOG2_MAX   # formats.py imports nothing of the package

ID_MAGIC = 0x454D5043   # 'EMPC'
VERSION = 0x00010000     # major.minor.patch = 1.0.0 (bits 31:16 major, 15:8 minor, 7:0 patch)
AXIS_BASE = 0x100
AXIS_STRIDE = 0x100
COEF_BASE = 0x1000
COEF_STRIDE = 0x400
WDOG_KEY = 0x5A5A
# LPC408x/407x (UM10562) memory map: EMC static chip select 0 is 0x8000_0000..0x83FF_FFFF.
# 32-bit static bus with SCS.EMCSC = 0 (addresses shifted to the bus width): the pins
# EMC_A[13:0] carry CPU byte-address bits [15:2], i.e. word w is at EMC_CS0_BASE + 4 w.
EMC_CS0_BASE = 0x80000000
WORD_BYTES = 4
ACCESS = ("RO", "RW", "WO", "W1C")
# ADC plausibility persistence (build-time, rtl/adc_spi.v parameter defaults via empc_regs.vh)
ADC_STUCK_FRAMES = 4      # consecutive frames with a code at a rail -> FAULT.adc_stuck
ADC_SUM_FRAMES = 4        # consecutive frames with |sum of the phase currents| > ADC_SUM_THRESH -> FAULT.adc_sum
ADC_FROZEN_PERIODS = 4    # consecutive PWM periods (bridges on) with a channel bit-identical -> FAULT.adc_frozen
# Build-time hard limits of the board (issue 14): the register blocks refuse (``legal``) every write
# outside them, whatever the CPU does; the safety settings change only with the bridges off
# (``guard="bridges_live"``: CTRL.enable set or the outputs switching; globally: on any axis).  The
# routing registers' guard ``route_locked`` is bridges_live, or high for good in a build without
# out_route (CAPS.route = 0: they keep today's pinout, refuse every write and cost no flip-flops).
ADC_CODE_BITS = 12        # current ADC code width (ADC_OFFx, OC_THRESH)
DEAD_TIME_MIN = 20        # complementary-mode dead time floor, fabric clocks (200 ns at 100 MHz)
OC_THRESH_MAX = 1900      # ADC LSB (19 A at 10 mA/LSB): below the ADC rails for every legal offset, so that
                          # |code - offset| > OC_THRESH stays reachable in both directions
ADC_OFF_LEGAL = range(OC_THRESH_MAX + 1, (1 << ADC_CODE_BITS) - 1 - OC_THRESH_MAX)   # 1901..2194
WDOG_TIMEOUT_BITS = 11    # WDOG_TIMEOUT: 1..2047 PWM periods (102 ms at 20 kHz); 0 (off) is refused: the watchdog
WDOG_TIMEOUT_MAX = (1 << WDOG_TIMEOUT_BITS) - 1   # cannot be disabled
UDC_FRESH_PERIODS = 200   # PWM periods (10 ms): UDC not rewritten for this long -> FAULT.dclink (stale value)
UDC_W = 20                # DC-link registers in mV: 20 bits hold 1048 V (16 held 65 V, below a 320 V drive's link)
UDC_LEGAL_MAX = (1 << UDC_W) - 2
SEQ_STALL_PERIODS = 2     # PWM periods without new compare values -> FAULT.overrun (stalled sequencer)
UNLOCK_KEY = 0xC0DE       # UNLOCK: arms one write of FAULT_MASK (axis) / WDOG_TIMEOUT (global)
UNLOCK_ARM = 2            # the unlock ends at the 2nd PWM period start after the key (50..100 us) or at the
                          # next write of the block, whichever is first
# Output and input routing (issue 16 item 4, docs/four_axes.md section 5; rtl/out_route.v): the
# board's resources that the global routing registers assign to axes.  Field widths follow from them.
ROUTE_AXES = 4            # axes the routing table can name (LX_RoCoN: up to four PMSMs)
ROUTE_PHASES = 3          # half-bridges per axis (phases A, B, C = 0, 1, 2)
ROUTE_OUTPUTS = 16        # LX_PWR half-bridge outputs (PWM + enable each)
ROUTE_ENC = 8             # IRC inputs (A, B, index, mark each)
ROUTE_HALL = 4            # HALL sensor sets (3 lines each)
ROUTE_ADC = 16            # current ADC channels (one per half-bridge output)
ROUTE_OUT_W = (ROUTE_AXES * ROUTE_PHASES).bit_length()   # OUT_SEL code: 0 = off, 1 + 3 a + p = axis a, phase p
ROUTE_ENC_W = (ROUTE_ENC - 1).bit_length()
ROUTE_HALL_W = (ROUTE_HALL - 1).bit_length()
ROUTE_ADC_W = (ROUTE_ADC - 1).bit_length()
ROUTE_NIB = 4             # every select field starts at a multiple of 4 bits (readable in hex)
ROUTE_PER_WORD = 32 // ROUTE_NIB                          # OUT_SEL fields per register


@dataclass(frozen=True)
class Field:
    name: str
    lsb: int
    width: int
    doc: str
    reset: int | str | None = None      # None: the register's reset bits; str: empc_formats.vh macro
    floor: int | None = None
    legal: range | tuple | None = None
    guard: str = ""                     # field guard: a change of this field is refused while high
    safe: int | None = None             # stored even by a refused write that writes this value

    @property
    def mask(self) -> int:
        return ((1 << self.width) - 1) << self.lsb


@dataclass(frozen=True)
class Ext:
    """A block that keeps the storage of the registers whose ``ext`` names it.

    strobe: the register block emits a one-hot write pulse ``<name>_we`` (bit i = i-th
            register of the group) and the written data ``<name>_wdata`` (both registered);
            each register's value comes back on an input port named after it.
    window: the block decodes its own words: ``<name>_we`` / ``<name>_re`` (reg_wr / reg_rd
            and the address in the window, combinational), ``<name>_idx`` (word index in the
            window, if ``idx``) and the read data on input ``rdata`` (default ``<name>_rdata``,
            0 unless read; windows may share one), ORed into reg_rdata.
    """
    name: str
    kind: str
    doc: str
    rdata: str = ""
    idx: bool = False

    @property
    def rdata_port(self) -> str:
        return self.rdata or f"{self.name}_rdata"


@dataclass(frozen=True)
class Reg:
    name: str
    offset: int
    access: str          # RO, RW, WO (write pulses), W1C (sticky, write 1 to clear)
    reset: int | str
    doc: str
    fields: tuple = field(default_factory=tuple)
    width: int = 32
    signed: bool = False     # a width < 32 value reads back sign-extended to 32 bits
    ext: str = ""
    const: bool = False
    key: int | None = None
    guard: str = ""
    legal: range | tuple | None = None
    floor: int | None = None
    port: str = ""
    read: str = ""
    arm: int | None = None      # key register: clocks an unlock stays armed
    unlock: str = ""            # the key register (with arm) this register's writes need
    wstrobe: bool = False       # output <port>_wr: pulse when a write is accepted

    @property
    def base(self) -> str:
        """Port name of the register (fields: prefix of their ports)."""
        return self.port or self.name.lower()

    def parts(self) -> tuple:
        """The fields, or one field standing for a field-less register's data bits."""
        if self.fields:
            return self.fields
        return (Field(self.base, 0, self.width, self.doc, self.reset, self.floor, self.legal),)

    def part_port(self, f: Field) -> str:
        return self.base if (not self.fields or f.name == self.base) else f"{self.base}_{f.name}"

    @property
    def bits(self) -> int:
        """Data bits: msb + 1 of the fields, else width."""
        return max(f.lsb + f.width for f in self.parts())

    @property
    def mask(self) -> int:
        """Bits the register stores / reports (before sign extension)."""
        return sum(f.mask for f in self.parts())

    def reset_int(self) -> int:
        """Reset word with build-dependent (macro) parts as 0."""
        if not self.fields:
            return self.reset if isinstance(self.reset, int) else 0
        v = 0
        for f in self.fields:
            r = (self.reset >> f.lsb) & ((1 << f.width) - 1) if f.reset is None else f.reset
            if isinstance(r, int):
                v |= r << f.lsb
        return v

    def reset_build_mask(self) -> int:
        """Bits whose reset value comes from the build (empc_formats.vh macro)."""
        return sum(f.mask for f in self.parts() if isinstance(f.reset, str))

    def reset_word(self, macros: dict) -> int:
        """Reset word with the build's macro values (``macros``: empc.header.read, no EMPC_ prefix)."""
        v = self.reset_int()
        for f in self.parts():
            if isinstance(f.reset, str):
                v |= (macros[f.reset.removeprefix("EMPC_")] & ((1 << f.width) - 1)) << f.lsb
        return v

    def pack(self, values: dict, partial: bool = False) -> int:
        """The word with every field set to ``values[field name]`` (exactly the register's fields, or with
        ``partial`` any of them, the others 0; each value fitting its width: unsigned, or two's complement
        for a negative value); MapError otherwise."""
        parts = self.parts()
        names = {f.name for f in parts}
        if not (set(values) <= names if partial else set(values) == names):
            raise MapError(f"{self.name}: fields {sorted(values)} given, the register has {[f.name for f in parts]}")
        v = 0
        for f in parts:
            if f.name not in values:
                continue
            x = values[f.name]
            if not -(1 << (f.width - 1)) <= x < (1 << f.width):
                raise MapError(f"{self.name}.{f.name} = {x} does not fit {f.width} bits")
            v |= (x & ((1 << f.width) - 1)) << f.lsb
        return v

    def readback(self, value: int) -> int:
        """What an RW register reads after ``value`` was written: the fields (or the low
        ``width`` bits, sign-extended if ``signed``) of the word, other bits 0 (floor and
        legal values aside)."""
        if self.fields:
            return sum(value & f.mask for f in self.fields)
        v = value & ((1 << self.width) - 1)
        if self.signed and v >> (self.width - 1):
            v -= 1 << self.width
        return v & 0xFFFFFFFF

    def accepts(self, value: int, live: bool = False, unlocked: bool = False, stored: int | None = None) -> bool:
        """Whether the register block accepts a write of ``value`` (the rules of the generated
        blocks, gen/empc/regblock.py): ``live`` = the guard inputs are high, ``unlocked`` = the key
        register armed it, ``stored`` = the register's word now (field guards accept a rewrite of the
        stored field; None: the reset word with build fields 0)."""
        if (self.guard and live) or (self.unlock and not unlocked):
            return False
        old = self.reset_int() if stored is None else stored
        for f in self.parts():
            x = (value >> f.lsb) & ((1 << f.width) - 1)
            if f.legal is not None and x not in f.legal:
                return False
            if f.guard and live:
                keep = (old >> f.lsb) & ((1 << f.width) - 1) if self.access == "RW" else 0
                if x != keep:
                    return False
        return True

    @property
    def attrs(self) -> str:
        """Short text of the generator attributes (docs)."""
        out = []
        if self.ext:
            out.append(f"in {self.ext}")
        if self.const:
            out.append("constant")
        if self.key is not None:
            out.append(f"key {self.key:#x}")
        if self.arm is not None:
            out.append(f"key arms one write for {self.arm} clocks")
        if self.unlock:
            out.append(f"needs {self.unlock}")
        if self.guard:
            out.append(f"refused while {self.guard}")
        if self.wstrobe:
            out.append("write strobe")
        for f in self.parts():
            n = f"{f.name} " if self.fields else ""
            if f.floor is not None:
                out.append(f"{n}below {f.floor} stored as {f.floor}")
            if f.legal is not None:
                out.append(f"{n}legal {_legal_text(f.legal)}")
            if f.guard:
                out.append(f"{n}changes refused while {f.guard}")
            if f.safe is not None:
                out.append(f"{n}{f.safe} always accepted")
        return ", ".join(out)


def _legal_text(legal) -> str:
    if isinstance(legal, range):
        return f"{legal.start}..{legal.stop - 1}"
    return "{" + ", ".join(str(v) for v in legal) + "}"



def route_out_code(axis: int, phase: int) -> int:
    """OUT_SEL code of (axis, phase): 0 is off."""
    return 1 + ROUTE_PHASES * axis + phase


def _out_sel(word: int) -> Reg:
    """OUT_SEL<word>: outputs 8 word .. 8 word + 7; reset: today's single-axis pinout (output
    3 a + p = axis a, phase p, the outputs beyond the routable pairs off)."""
    first = word * ROUTE_PER_WORD
    n = ROUTE_AXES * ROUTE_PHASES
    return Reg(f"OUT_SEL{word}", 0x010 + word, "RW", 0,
               f"Output select of half-bridge outputs {first}..{first + ROUTE_PER_WORD - 1}: 0 = off (PWM and "
               f"enable held low), 1 + 3 a + p = axis a, phase p (0..2 = A..C); an output has one source or none, "
               f"a phase may drive several outputs; {n + 1}..15 are refused; a code naming an axis the build lacks "
               "is held off like 0 (CAPS.naxes). Written only with every axis off (CTRL.enable clear, "
               "no output switching) in a build that routes (CAPS.route); the pins follow one clock after "
               "pwm_center.", tuple(
                   Field(f"out{k}", ROUTE_NIB * (k - first), ROUTE_OUT_W, f"output {k}",
                         reset=k + 1 if k < n else 0, legal=range(0, n + 1))
                   for k in range(first, first + ROUTE_PER_WORD)),
               guard="route_locked", wstrobe=True)


def _adc_sel(word: int) -> Reg:
    """ADC_SEL<word>: the ADC channel of (axis, phase) for two axes; reset: channel 3 a + p."""
    per = 32 // (ROUTE_NIB * ROUTE_PHASES)        # axes per word
    fields = tuple(Field(f"ax{a}_{'abc'[p]}", ROUTE_NIB * (ROUTE_PHASES * (a - word * per) + p), ROUTE_ADC_W,
                         f"ADC channel of axis {a}, phase {'ABC'[p]}", reset=ROUTE_PHASES * a + p)
                   for a in range(word * per, min(ROUTE_AXES, (word + 1) * per)) for p in range(ROUTE_PHASES))
    return Reg(f"ADC_SEL{word}", 0x012 + word, "RW", 0,
               f"Current ADC channel (MISO input 0..{ROUTE_ADC - 1}) that measures each phase; written only with "
               "every axis off.", fields, guard="route_locked")


ROUTE_REGS = (
    _out_sel(0), _out_sel(1), _adc_sel(0), _adc_sel(1),
    Reg("IN_SEL", 0x014, "RW", 0, "Position inputs of each axis; written only with every axis off.",
        tuple(Field(f"enc{a}", ROUTE_NIB * a, ROUTE_ENC_W, f"IRC input (0..{ROUTE_ENC - 1}) of axis {a}", reset=a)
              for a in range(ROUTE_AXES)) +
        tuple(Field(f"hall{a}", 16 + ROUTE_NIB * a, ROUTE_HALL_W, f"HALL set (0..{ROUTE_HALL - 1}) of axis {a}",
                    reset=a) for a in range(ROUTE_AXES)), guard="route_locked"),
    Reg("ROUTE_STATUS", 0x015, "RO", 0, "Routing state (rtl/out_route.v).",
        tuple(Field(f"mapped{a}", ROUTE_NIB * a, ROUTE_PHASES, f"axis {a}: bit p = phase p drives at least one "
                    "output (a 16-clock scan of OUT_SEL; 0 from an OUT_SEL write until the next complete scan)")
              for a in range(ROUTE_AXES)) +
        (Field("bad_sel", 16, 1, "an ADC_SEL / IN_SEL select of an axis of this build names an ADC channel, "
               "IRC input or HALL set the build does not have (read as MISO 1, IRC 0, HALL 000: a fault)"),)),
)


GLOBAL = (
    Reg("ID", 0x000, "RO", ID_MAGIC, "Magic 'EMPC' (0x454D5043): the bus works and the FPGA is configured.",
        const=True),
    Reg("VERSION", 0x001, "RO", VERSION, "IP version.", (
        Field("patch", 0, 8, "fixes"), Field("minor", 8, 8, "compatible additions"),
        Field("major", 16, 16, "incompatible register-map changes")), const=True),
    Reg("CAPS", 0x002, "RO", 0, "Build parameters.", (
        Field("naxes", 0, 4, "axes in this bitstream"),
        Field("horizon", 4, 4, "prediction horizon N of the core"),
        Field("img_layout", 8, 8, "coefficient image layout version"),
        Field("pwm_per_control", 16, 8, "PWM periods per control period Ts (reset value)"),
        Field("complementary", 24, 1, "bridge mode of the build (board): 0 = PWM + enable (LX_PWR), "
              "1 = complementary high/low with dead time"),
        Field("route", 25, 1, "1 = outputs and inputs routed by OUT_SEL / ADC_SEL / IN_SEL (rtl/out_route.v); "
              "0 = fixed pinout: those registers read today's pinout and refuse every write"))),
    Reg("PWM_HALF", 0x003, "RO", 0, "PWM half period in fabric clocks (centre-aligned: period = 2 x this)."),
    Reg("SCRATCH", 0x004, "RW", 0, "Free for bus tests.", read="copy"),
    Reg("WDOG_TIMEOUT", 0x008, "RW", 400, "Watchdog timeout in PWM periods. Expiry latches the watchdog fault "
        "on every axis (all bridges off, not maskable). Written only with every axis off and right after "
        "UNLOCK; 0 (off) is refused.", width=WDOG_TIMEOUT_BITS,
        legal=range(1, WDOG_TIMEOUT_MAX + 1), guard="bridges_live", unlock="WDOG_UNLOCK"),
    Reg("WDOG_KICK", 0x009, "WO", 0, f"Write {WDOG_KEY:#06x} to restart the watchdog; other values are ignored.",
        width=16, key=WDOG_KEY),
    Reg("TIME", 0x00a, "RO", 0, "Free-running PWM period counter.", port="time_cnt"),
    Reg("IRQ_STATUS", 0x00b, "W1C", 0, "Interrupt causes (sticky, write 1 to clear).", (
        Field("period", 0, 1, "a control period completed on axis 0"),
        Field("fault", 1, 1, "a fault latched on any axis"))),
    Reg("IRQ_ENABLE", 0x00c, "RW", 0, "Interrupt enables (same bits as IRQ_STATUS); cpu_irq = OR of "
        "(status AND enable).", width=2),
    Reg("WDOG_UNLOCK", 0x00d, "WO", 0, f"Write {UNLOCK_KEY:#06x} to let the next write of a global register change "
        "WDOG_TIMEOUT (within the arm time; any other value is refused).", width=16, key=UNLOCK_KEY,
        arm=UNLOCK_ARM),
) + ROUTE_REGS

# FAULT: one bit per cause, contiguous from bit 0 (FAULT_MASK has the same bits; axis_periph: NCAUSE =
# EMPC_A_FAULT_W).  Adding a cause = one line here plus its signal in axis_periph.v.
FAULT_CAUSES = (
    Field("overcurrent", 0, 1, "|phase current| above OC_THRESH in some ADC frame (every frame is "
          "checked)"),
    Field("hall", 1, 1, "illegal HALL code 000 or 111"),
    Field("encoder", 2, 1, "illegal quadrature transition"),
    Field("watchdog", 3, 1, "CPU did not kick the watchdog in time (not maskable)"),
    Field("dclink", 4, 1, f"UDC outside UDC_MIN..UDC_MAX, or not rewritten for {UDC_FRESH_PERIODS} PWM periods "
          "(stale; UDC resets to 0: missing)"),
    Field("overrun", 5, 1, f"a control computation did not finish before its PWM update, or the sequencer "
          f"loaded no compare values for {SEQ_STALL_PERIODS} PWM periods (stalled; not maskable)"),
    Field("adc", 6, 1, "ADC frame error (leading zero bit read as 1)"),
    Field("pstage", 7, 1, "power-stage fault input pwr_fault_n was low (clock-independent kill; not maskable)"),
    Field("clock", 8, 1, "PLL lock lost or fabric clock stopped (clock-independent kill; not maskable)"),
    Field("coef", 9, 1, "the active coefficient bank holds no valid image (bad boot image), or its control "
          "period (image CFG[23:16]) is not CTRL.pwm_per_control (not maskable)"),
    Field("hall_enc", 10, 1, "HALL sector and encoder disagree (angle 2+ sectors apart, HALL against or "
          "beyond the encoder)"),
    Field("enc_break", 11, 1, "encoder line break: a whole HALL sector crossed with under half its counts"),
    Field("adc_stuck", 12, 1, f"an ADC code at a rail (0 or full scale) in {ADC_STUCK_FRAMES} consecutive frames"),
    Field("adc_sum", 13, 1, f"|i_a + i_b + i_c| above ADC_SUM_THRESH in {ADC_SUM_FRAMES} consecutive frames"),
    Field("adc_frozen", 14, 1, f"an ADC channel bit-identical in every frame of {ADC_FROZEN_PERIODS} PWM "
          "periods with the bridges on"),
)
ADC_PSUM_FIELDS = (Field("sum", 0, 20, "signed 20-bit sum, ADC LSB"), Field("count", 24, 7, "frames"))

AXIS = (
    Reg("CTRL", 0x00, "RW", 0, "Axis control.", (
        Field("enable", 0, 1, "bridges may switch (PWM running, outputs enabled) unless a fault is latched; "
              "0 is accepted even in a refused write (switching off is never refused)", safe=0),
        Field("run", 1, 1, "control law active; 0 = bridges enabled with zero voltage (u and ebar held at 0); "
              "0 always accepted", safe=0),
        Field("pwm_per_control", 8, 8, "PWM periods per control period Ts (1..255; 0 is refused); reset from "
              "the header; changes refused while the bridges are live (the bridge mode is a build parameter: "
              "CAPS.complementary)", reset="EMPC_PWM_PER_CONTROL", legal=range(1, 256), guard="bridges_live"))),
    Reg("CMD", 0x01, "WO", 0, "Command pulses (write 1).", (
        Field("fault_clear", 0, 1, "clear latched faults (only those whose cause has gone)"),
        Field("adc_cal", 1, 1, "start ADC offset calibration (the write is refused while the bridges are live; "
              "bridges coming on abort it)", guard="bridges_live"),
        Field("ref_sync", 2, 1, "set the reference generator to the measured output (bumpless start)"),
        Field("coef_swap", 3, 1, "make the uploaded coefficient bank active at the PWM boundary before the next "
              "control sample; refused (STATUS.swap_refused, CNT_SWAP_REF) unless it holds a complete valid image"),
        Field("clear_counters", 4, 1, "zero the saturation and event counters"),
        Field("align_clear", 5, 1, "forget the index alignment (back to HALL alignment)"))),
    Reg("STATUS", 0x02, "RO", 0, "Axis state.", (
        Field("running", 0, 1, "control law running (CTRL.run and the outputs switching)"),
        Field("bridges_on", 1, 1, "the outputs are switching (pwm_center's output state: enable, no fault, "
              "angle valid, valid coefficient image, started at a period boundary)"),
        Field("aligned", 2, 1, "angle aligned at the encoder index (else HALL rough alignment)"),
        Field("adc_cal_busy", 3, 1, "ADC offset calibration in progress"),
        Field("adc_cal_done", 4, 1, "ADC calibration has completed since reset"),
        Field("core_ready", 5, 1, "MPC core loaded its boot coefficients"),
        Field("coef_bank", 6, 1, "active coefficient bank"),
        Field("swap_pending", 7, 1, "a bank swap waits for the next control period"),
        Field("fault", 8, 1, "a fault is latched (bridges forced off)"),
        Field("coef_valid", 9, 1, "the inactive bank holds a complete valid upload (a swap is accepted if its "
              "control period is CTRL.pwm_per_control)"),
        Field("swap_refused", 10, 1, "the last decided coefficient swap was refused: no complete valid upload, or "
              "its control period is not CTRL.pwm_per_control (until a swap is accepted)"),
        Field("adc_refused", 11, 1, "an ADC calibration or offset write was refused or a calibration aborted "
              "(bridges on / calibrating); CMD.clear_counters clears it"),
        Field("wr_refused", 12, 1, "a register write was refused (CNT_WR_REFUSED); CMD.clear_counters clears it"))),
    Reg("FAULT", 0x03, "RO", 0, "Latched (sticky) fault causes; cleared by CMD.fault_clear once the cause has gone.",
        FAULT_CAUSES),
    Reg("FAULT_MASK", 0x04, "RW", (1 << len(FAULT_CAUSES)) - 1, "Fault causes that switch the bridges off (same "
        "bits as FAULT). Masked causes are still recorded in FAULT; watchdog, overrun, pstage, clock and coef "
        "always trip. Written only with the bridges off and right after UNLOCK.", width=len(FAULT_CAUSES),
        guard="bridges_live", unlock="UNLOCK"),
    Reg("DEAD_TIME", 0x05, "RW", 50, f"Dead time in fabric clocks (complementary mode; at least the board's "
        f"{DEAD_TIME_MIN}).", width=8, legal=range(DEAD_TIME_MIN, 256), guard="bridges_live"),
    Reg("KDC", 0x06, "RW", 1 << 16, "DC-link compensation Udc_nominal / Udc, unsigned Q2.16 (1.0 = 0x10000).",
        width=18),
    Reg("UDC", 0x07, "RW", 0, f"DC-link voltage in mV as measured by the CPU, checked against UDC_MIN..MAX; it "
        f"resets to 0 (missing: below UDC_MIN) and must be rewritten at least every {UDC_FRESH_PERIODS} PWM "
        "periods (else stale: FAULT.dclink).", width=UDC_W, wstrobe=True),
    Reg("UDC_MIN", 0x08, "RW", 10000, f"Lowest allowed DC link, mV (1..{UDC_LEGAL_MAX}).", width=UDC_W,
        legal=range(1, UDC_LEGAL_MAX + 1), guard="bridges_live"),
    Reg("UDC_MAX", 0x09, "RW", 60000, f"Highest allowed DC link, mV (1..{UDC_LEGAL_MAX}).", width=UDC_W,
        legal=range(1, UDC_LEGAL_MAX + 1), guard="bridges_live"),
    Reg("OC_THRESH", 0x0a, "RW", 1800, f"Overcurrent threshold, ADC LSB of |code - offset| (per phase, every "
        f"frame; 1..{OC_THRESH_MAX}, the board's limit).", width=ADC_CODE_BITS,
        legal=range(1, OC_THRESH_MAX + 1), guard="bridges_live"),
    Reg("ADC_OFF0", 0x0b, "RW", "EMPC_ADC_OFFSET", f"ADC offset phase A (calibration writes it; reads the active "
        f"value; {ADC_OFF_LEGAL.start}..{ADC_OFF_LEGAL.stop - 1}: any legal offset and threshold leave both rails "
        "beyond the threshold; writes refused with the bridges live, and by adc_spi while calibrating: "
        "STATUS.adc_refused).", width=ADC_CODE_BITS, ext="adc_off", legal=ADC_OFF_LEGAL, guard="bridges_live"),
    Reg("ADC_OFF1", 0x0c, "RW", "EMPC_ADC_OFFSET", "ADC offset phase B.", width=ADC_CODE_BITS, ext="adc_off",
        legal=ADC_OFF_LEGAL, guard="bridges_live"),
    Reg("ADC_OFF2", 0x0d, "RW", "EMPC_ADC_OFFSET", "ADC offset phase C.", width=ADC_CODE_BITS, ext="adc_off",
        legal=ADC_OFF_LEGAL, guard="bridges_live"),
    Reg("ANGLE_CAL", 0x0e, "RW", 0, "Electrical angle at the encoder index (2^16 = one electrical turn).", width=16,
        guard="bridges_live"),
    Reg("HALL_OFFSET", 0x0f, "RW", 0, "Electrical angle of the HALL sector-1 start (2^16 = one turn).", width=16,
        guard="bridges_live"),
    Reg("KACC", 0x10, "RW", 0, "Speed estimate (docs/blocks/ctrl_seq.md): omega = eq. 37 + (KACC * i_q) >> "
        "KACC_SHIFT - D, D the load estimate (reset from the header; kacc = 0: plain eq. 37).", (
        Field("kacc", 0, 18, "signed gain", reset="EMPC_KACC"),
        Field("load_shift", 18, 4, "load-estimate gain 2^-load_shift per control period (0 = no load estimate: "
              "offset kacc i_load under a load)", reset="EMPC_KACC_LOAD_SHIFT"),
        Field("shift", 24, 5, "right shift", reset="EMPC_KACC_SHIFT"),
        Field("win", 29, 3, "speed window m: the speed over M = 2^m control periods, "
              "(pos_k - pos_{k-M}) << (16 - m), the load update's difference x M (control.speed_window; "
              f"{WIN_LOG2_MAX + 1}..7 act as {WIN_LOG2_MAX}; needs load_shift + 1 >= m)", reset="EMPC_KACC_WIN"))),
    Reg("ID_REF", 0x11, "RW", 0, "d-current reference, ADC LSB Q.4 (signed 18 bit).", width=18, signed=True),
    Reg("IQ_REF", 0x12, "RW", 0, "q-current reference (feed-forward), ADC LSB Q.4 (signed 18 bit).", width=18,
        signed=True),
    Reg("SEG_ADDR", 0x13, "RW", 0, "Reference segment slot (0..15) that the SEG_LEN .. SEG_FLAGS fields access. "
        "Each field write goes straight into the slot (no staging): do not rewrite a slot that the "
        "next control period may load (the active slot's successor or a pending SEG_START slot).", width=4),
    Reg("SEG_LEN", 0x14, "RW", 0, "Segment length in control periods (0 = hold forever); field of slot SEG_ADDR "
        "(SEG_* reads return the field of slot SEG_ADDR).", ext="seg"),
    Reg("SEG_R0_LO", 0x15, "RW", 0, "Segment start value, low word (task output, 64-bit Q.32: counts or counts/Ts).",
        ext="seg"),
    Reg("SEG_R0_HI", 0x16, "RW", 0, "Segment start value, high word.", ext="seg"),
    Reg("SEG_D1_LO", 0x17, "RW", 0, "First forward difference per control period, low word (64-bit Q.32).",
        ext="seg"),
    Reg("SEG_D1_HI", 0x18, "RW", 0, "First forward difference, high word.", ext="seg"),
    Reg("SEG_D2", 0x19, "RW", 0, "Second forward difference (signed 32-bit Q.32 of the output unit).",
        ext="seg"),
    Reg("SEG_FLAGS", 0x1a, "RW", 0, "Segment flags of slot SEG_ADDR.", (
        Field("relative", 0, 1, "start from the current reference value instead of R0"),
        Field("last", 1, 1, "hold at the end of this segment instead of moving to the next slot")), ext="seg"),
    Reg("SEG_START", 0x1b, "WO", 0, "Write a slot number to start the profile there at the next control period.",
        width=4),
    Reg("SEG_GOV", 0x1c, "RW", "EMPC_GOV_VMAX_LO", "Reference-governor word of slot SEG_ADDR (slot memory field "
        "7; docs/blocks/ref_gen.md): slots 0/1 vmax low/high, 2/3 a low/high (Q.32, 63 bit), 4 bit 0 enable and "
        "bits 12:8 ksh; the header's values (boot task) after configuration (after reset SEG_ADDR = 0: vmax low).",
        ext="gov"),
    Reg("FW", 0x1d, "RW", 0, "Field weakening: the d-current references get -n * 2^EMPC_FW_SHIFT (Q.4 ADC LSB); "
        "n steps up by one per control period (to nmax) while FW_R2.hi < |u_raw|^2 >> 20, down (to 0) while "
        "|u_raw|^2 >> 20 < FW_R2.lo; 0 while the law is off.", (
        Field("nmax", 0, 8, "largest n (0 = field weakening off)", reset="EMPC_FW_NMAX"),)),
    Reg("FW_R2", 0x1e, "RW", 0, "Field-weakening band on the limiter's |u_raw|^2 (PWM ticks Q.4, squared, >> 20).", (
        Field("hi", 0, 16, "above: n up (more negative d current)", reset="EMPC_FW_R2_HI"),
        Field("lo", 16, 16, "below: n down", reset="EMPC_FW_R2_LO"))),
    Reg("IQ_HOLD", 0x1f, "RW", "EMPC_IQ_HOLD", "Reference-governor hold: a control period with |i_q| >= IQ_HOLD "
        "ADC LSB (or the voltage limit active) holds the reference's acceleration in the next (0 = no current "
        "hold); in that period the algorithm-2 speed task's integral is held too when the speed error would drive "
        "|i_q| further (anti-windup, counted in SAT_EBAR_INC).", width=12),
    Reg("POS", 0x20, "RO", 0, "Encoder count (x4, modular 32 bit)."),
    Reg("SPEED", 0x21, "RO", 0, "Speed estimate at the last control period, counts per Ts, signed Q16.16.",
        ext="stat"),
    Reg("THETA", 0x22, "RO", 0, "Electrical angle (2^16 = one turn).", width=16),
    Reg("I_D", 0x23, "RO", 0, "i_d at the last control period, ADC LSB Q.4 (signed).", width=18, signed=True,
        ext="stat"),
    Reg("I_Q", 0x24, "RO", 0, "i_q at the last control period, ADC LSB Q.4 (signed).", width=18, signed=True,
        ext="stat"),
    Reg("U_D", 0x25, "RO", 0, "u_d applied, PWM ticks Q16.8 (signed 24 bit).", width=24, signed=True, ext="stat"),
    Reg("U_Q", 0x26, "RO", 0, "u_q applied, PWM ticks Q16.8 (signed 24 bit).", width=24, signed=True, ext="stat"),
    Reg("REF", 0x27, "RO", 0, "Task-output reference w_k of the last control period (bits 47:16 speed, Q16.16 / "
        "55:24 position, Q24.8 of the generator value).", ext="stat"),
    Reg("IABC0", 0x28, "RO", 0, "Last raw ADC codes.", (
        Field("a", 0, 12, "phase A"), Field("b", 16, 12, "phase B"))),
    Reg("IABC1", 0x29, "RO", 0, "Last raw ADC code phase C (11:0).", width=12),
    Reg("LATENCY", 0x2a, "RO", 0, "Clocks from the ADC trigger to the new PWM compare values of the last control "
        "period.",
        width=16),
    Reg("PERIODS", 0x2b, "RO", 0, "Control periods run since enable.", ext="cnt"),
    Reg("ADC_PSUM0", 0x2c, "RO", 0, "Phase A: sum of code - offset over the ADC frames of the last complete PWM "
        "period, and their number (period mean = sum / count; both from the same period).", ADC_PSUM_FIELDS),
    Reg("ADC_PSUM1", 0x2d, "RO", 0, "Phase B: as ADC_PSUM0.", ADC_PSUM_FIELDS),
    Reg("ADC_PSUM2", 0x2e, "RO", 0, "Phase C: as ADC_PSUM0.", ADC_PSUM_FIELDS),
    Reg("CNT_WR_REFUSED", 0x2f, "RO", 0, "Refused writes of this axis' registers and of the global registers "
        "(guard, unlock or illegal value; 8-bit, saturating; CMD.clear_counters zeroes it).", width=8),
    Reg("SAT_OPERAND", 0x30, "RO", 0, "Saturation counter: core operand. SAT_* and CNT_OVERRUN count control "
        "periods in which the event happened (32-bit, saturating; updated after the control period's "
        "modulation).", ext="cnt"),
    Reg("SAT_GAIN", 0x31, "RO", 0, "Saturation counter: gain polynomial.", ext="cnt"),
    Reg("SAT_TERM", 0x32, "RO", 0, "Saturation counter: product term.", ext="cnt"),
    Reg("SAT_ACC", 0x33, "RO", 0, "Saturation counter: accumulator.", ext="cnt"),
    Reg("SAT_DU", 0x34, "RO", 0, "Saturation counter: du.", ext="cnt"),
    Reg("SAT_U", 0x35, "RO", 0, "Saturation counter: u before the limiter.", ext="cnt"),
    Reg("SAT_EBAR", 0x36, "RO", 0, "Saturation counter: ebar.", ext="cnt"),
    Reg("SAT_EBAR_INC", 0x37, "RO", 0, "Counter: ebar increment clamped or the speed increment held "
        "(eq. 25 anti-windup active, IQ_HOLD).", ext="cnt"),
    Reg("SAT_LIMIT", 0x38, "RO", 0, "Counter: voltage limit active.", ext="cnt"),
    Reg("SAT_WN", 0x39, "RO", 0, "Counter: scheduling speed clamped to Omega_e.", ext="cnt"),
    Reg("SAT_SIGNAL", 0x3a, "RO", 0, "Saturation counter: core signal (SIG_W).", ext="cnt"),
    Reg("SAT_FRONT", 0x3b, "RO", 0, "Saturation counter: front end (transforms, speed, duty).", ext="cnt"),
    Reg("CNT_OVERRUN", 0x3c, "RO", 0, "Control computations that missed their PWM update.", ext="cnt"),
    Reg("CNT_ADC_MISS", 0x3d, "RO", 0, "PWM centres that missed the ADC sampling window (trigger off the frame "
        "grid, or a sync restart cut the window: no current sample that period; 8-bit, saturating; not cleared by "
        "CMD.clear_counters).", width=8),
    Reg("CNT_ENC_ERR", 0x3e, "RO", 0, "Illegal quadrature transitions (16-bit, saturating).", width=16),
    Reg("SAT_GOV", 0x3f, "RO", 0, "Counter: the reference governor shaped the reference (current limit: a clamp "
        "or its hold was active).", ext="cnt"),
    # issue 14 (safety), beyond the 64-word status memory of axis_status (offsets 0x40..):
    Reg("ADC_SUM_THRESH", 0x40, "RW", 300, f"Sum-of-currents threshold, ADC LSB of |d_a + d_b + d_c| (d = code - "
        f"offset), checked on every frame (FAULT.adc_sum; 1..{OC_THRESH_MAX}).", width=ADC_CODE_BITS,
        legal=range(1, OC_THRESH_MAX + 1), guard="bridges_live"),
    Reg("UNLOCK", 0x41, "WO", 0, f"Write {UNLOCK_KEY:#06x} to let the next write of this axis change FAULT_MASK "
        "(within the arm time; any other value is refused).", width=16, key=UNLOCK_KEY, arm=UNLOCK_ARM),
    Reg("CNT_SWAP_REF", 0x42, "RO", 0, "Refused coefficient swaps (8-bit, saturating; CMD.clear_counters zeroes "
        "it).", width=8),
)


EXT = (
    Ext("adc_off", "strobe", "adc_spi keeps the offsets (calibration writes them too)"),
    Ext("seg", "window", "ref_gen keeps the segment table: slot SEG_ADDR, field = word - SEG_LEN", idx=True),
    Ext("gov", "window", "ref_gen keeps the governor words: field 7 of slot SEG_ADDR", rdata="seg_rdata"),
    Ext("stat", "window", "status words in the block RAM of mpc_axis", rdata="smem_rdata"),
    Ext("cnt", "window", "event counters in the block RAM of mpc_axis", rdata="smem_rdata"),
)


@dataclass(frozen=True)
class Block:
    """One generated register block: rtl/<module>.v."""
    module: str
    scope: str          # macro prefix in empc_regs.vh / fw/empc_regs.h: G (global) or A (axis)
    regs: tuple
    read: str           # read path unless a register says: "copy" (one gated copy per register,
                        # 0 unless its word is read, ORed) or "mux" (one shared read register)
    doc: str
    span: int = AXIS_STRIDE
    ext: tuple = EXT    # the blocks that keep ext storage (a test map brings its own)
    shared: str = ""    # also a read path shared by NAXES blocks: rtl/<shared>.v (gen/empc/regblock.py
                        # render_shared) reads the blocks' ``rd_vals`` exports, one copy set for all axes
    shadow: bool = False  # the shared read path reads the stored registers (regblock ``shadowed``) back from a
                          # write-through block RAM {axis, word} written at the blocks' ``sh_we`` (accepted
                          # writes); rd_vals then carries only the other readable values


BLOCKS = (
    Block("global_regs", "G", GLOBAL, "mux", "global registers of lx_rocon_top (watchdog, time, interrupts)"),
    Block("axis_regs", "A", AXIS, "copy", "registers of one axis (mpc_axis)", shared="axis_rd", shadow=True),
)


class MapError(ValueError):
    """A register map that the generators refuse (one-line message naming the register)."""


_IDENT = re.compile(r"^[a-z][a-z0-9_]*$")


def check(regs, span: int, ext=EXT, what: str = "map") -> None:
    """Raise MapError (one line, naming the register) unless ``regs`` is a consistent map."""
    exts = {e.name: e for e in ext}

    def bad(r, msg):
        raise MapError(f"{what}: {r.name}: {msg}")

    seen_off, seen_name = {}, set()
    for r in regs:
        if r.name in seen_name:
            bad(r, "name used twice")
        seen_name.add(r.name)
        if not 0 <= r.offset < span:
            bad(r, f"offset {r.offset:#x} outside 0..{span - 1:#x}")
        if r.offset in seen_off:
            bad(r, f"offset {r.offset:#x} also used by {seen_off[r.offset]}")
        seen_off[r.offset] = r.name
        if r.access not in ACCESS:
            bad(r, f"access {r.access!r} not one of {ACCESS}")
        if not 1 <= r.width <= 32:
            bad(r, f"width {r.width} outside 1..32")
        if isinstance(r.reset, int) and not 0 <= r.reset < (1 << 32):
            bad(r, "reset does not fit 32 bits")
        if r.signed and r.fields:
            bad(r, "signed applies to field-less registers only")
        if not _IDENT.match(r.base):
            bad(r, f"port name {r.base!r} is not a lower-case identifier")
        if r.base in VERILOG_KEYWORDS:
            bad(r, f"port name {r.base!r} is a Verilog keyword: set port=")
        if r.ext and r.ext not in exts:
            bad(r, f"ext {r.ext!r} is not in EXT")
        if r.const and (r.access != "RO" or r.ext or not isinstance(r.reset, int)):
            bad(r, "const needs access RO, an integer reset and no ext")
        if r.key is not None and (r.access != "WO" or r.fields or not 0 <= r.key < (1 << r.width)):
            bad(r, "key needs a field-less WO register and a key that fits its width")
        if r.read not in ("", "copy", "mux"):
            bad(r, f"read {r.read!r} not copy or mux")
        if r.guard and (r.access == "RO" or not _IDENT.match(r.guard)):
            bad(r, "guard needs a writable register and a lower-case identifier")
        if r.arm is not None and (r.key is None or not 1 <= r.arm < (1 << 16)):
            bad(r, "arm needs a key register and 1..65535 ticks")
        if r.unlock:
            k = next((x for x in regs if x.name == r.unlock), None)
            if k is None or k.arm is None:
                bad(r, f"unlock {r.unlock!r} is not a key register with arm in this block")
            if r.access not in ("RW", "WO") or r.ext:
                bad(r, "unlock applies to RW/WO registers decoded by the block")
        if r.wstrobe and (r.access != "RW" or r.ext):
            bad(r, "wstrobe needs a stored RW register")
        if r.access == "W1C" and (r.ext or any(f.width != 1 for f in r.parts())):
            bad(r, "W1C registers are 1-bit fields stored in the block")
        e = exts.get(r.ext)
        if e and e.kind == "strobe" and (r.access != "RW" or r.fields):
            bad(r, "strobe registers are field-less RW")
        bits = 0
        for f in r.parts():
            if not _IDENT.match(f.name) or f.name in ("reset", "w"):
                bad(r, f"field name {f.name!r} is not usable")
            if f.width < 1 or f.lsb < 0 or f.lsb + f.width > 32 or bits & f.mask:
                bad(r, f"field {f.name} overlaps or exceeds 32 bits")
            bits |= f.mask
            if isinstance(f.reset, int) and not 0 <= f.reset < (1 << f.width):
                bad(r, f"reset {f.reset} of {f.name} does not fit {f.width} bits" if r.fields else
                    f"reset {f.reset} does not fit {f.width} bits")
            if isinstance(f.reset, str) and not re.match(r"^EMPC_[A-Z0-9_]+$", f.reset):
                bad(r, f"reset {f.reset!r} is not an EMPC_* macro of empc_formats.vh")
            if f.floor is not None and (r.access != "RW" or r.ext or not 0 < f.floor < (1 << f.width)):
                bad(r, "floor applies to stored RW values and must fit the width")
            if f.guard and (not r.fields or not _IDENT.match(f.guard) or r.ext
                            or r.access not in ("RW", "WO") or r.key is not None):
                bad(r, f"field guard of {f.name} needs a field of a stored RW or a pulse WO register")
            if f.safe is not None and (not r.fields or r.access != "RW" or r.ext
                                       or not 0 <= f.safe < (1 << f.width)):
                bad(r, f"safe of {f.name} needs a field of a stored RW register and must fit it")
            if f.legal is not None:
                vals = list(f.legal)
                if r.access == "RO" or (e and e.kind == "window") or not vals:
                    bad(r, "legal applies to writable registers stored in the block or strobed, and must allow a value")
                if min(vals) < 0 or max(vals) >= (1 << f.width):
                    bad(r, f"legal values of {f.name} do not fit {f.width} bits")
                if isinstance(f.legal, range) and f.legal.step != 1:
                    bad(r, "legal ranges must have step 1")
                fr = f.reset if f.reset is not None and r.fields else (
                    (r.reset >> f.lsb) & ((1 << f.width) - 1) if isinstance(r.reset, int) else None)
                if isinstance(fr, int) and fr not in f.legal:
                    bad(r, f"reset value {fr} of {f.name} is not a legal value")
    for e in ext:
        members = [r for r in regs if r.ext == e.name]
        if e.kind not in ("strobe", "window"):
            raise MapError(f"{what}: ext {e.name}: kind {e.kind!r} not strobe or window")
        if e.kind == "window" and members:
            offs = sorted(r.offset for r in members)
            if e.idx and offs != list(range(offs[0], offs[0] + len(offs))):
                raise MapError(f"{what}: ext {e.name}: an indexed window must be contiguous")
            if len({r.guard for r in members if r.access != "RO"}) > 1:
                raise MapError(f"{what}: ext {e.name}: the writable registers of a window share one guard")


VERILOG_KEYWORDS = frozenset("""always and assign automatic begin buf bufif0 bufif1 case casex casez cell cmos config
deassign default defparam design disable edge else end endcase endconfig endfunction endgenerate endmodule
endprimitive endspecify endtable endtask event for force forever fork function generate genvar highz0 highz1 if
ifnone incdir include initial inout input instance integer join large liblist library localparam macromodule
medium module nand negedge nmos nor noshowcancelled not notif0 notif1 or output parameter pmos posedge primitive
pull0 pull1 pulldown pullup pulsestyle_ondetect pulsestyle_onevent rcmos real realtime reg release repeat rnmos
rpmos rtran rtranif0 rtranif1 scalared showcancelled signed small specify specparam strong0 strong1 supply0
supply1 table task time tran tranif0 tranif1 tri tri0 tri1 triand trior trireg unsigned use uwire vectored wait
wand weak0 weak1 while wire wor xnor xor""".split())


def axis_reg(name: str) -> Reg:
    """The axis register ``name`` (KeyError if there is none)."""
    for r in AXIS:
        if r.name == name:
            return r
    raise KeyError(name)


def all_registers(naxes: int = 1) -> list[tuple[str, int, Reg]]:
    out = [(r.name, r.offset, r) for r in GLOBAL]
    for a in range(naxes):
        out += [(f"AX{a}_{r.name}", AXIS_BASE + a * AXIS_STRIDE + r.offset, r) for r in AXIS]
    return out


def _reset_text(r: Reg) -> str:
    if r.access == "RO" and not r.const:
        return "-"
    parts = [f"{r.reset_int():#x}"] if r.fields or isinstance(r.reset, int) else []
    for f in r.parts():
        if isinstance(f.reset, str):
            parts.append(f"{f.name}: {f.reset}" if r.fields else f.reset)
    return ", ".join(parts)


def idx_bits(n: int) -> int:
    """Bits of the word index of a window of n registers."""
    return max(1, (n - 1).bit_length())


def _macros(scope: str, regs, ext=EXT) -> list[tuple[str, object]]:
    out = []
    for e in ext:                            # port widths of the ext groups
        n = sum(r.ext == e.name for r in regs)
        if n and e.kind == "strobe":
            out.append((f"EMPC_{scope}_{e.name.upper()}_N", n))
        if n and e.kind == "window" and e.idx:
            out.append((f"EMPC_{scope}_{e.name.upper()}_IDX_W", idx_bits(n)))
    for r in regs:
        out.append((f"EMPC_{scope}_{r.name}", r.offset))
        out.append((f"EMPC_{scope}_{r.name}_RESET", r.reset if isinstance(r.reset, str) else r.reset_int()))
        out.append((f"EMPC_{scope}_{r.name}_W", r.bits))
        for f in r.fields:
            out.append((f"EMPC_{scope}_{r.name}_{f.name.upper()}", f.lsb))
            if f.width > 1:
                out.append((f"EMPC_{scope}_{r.name}_{f.name.upper()}_W", f.width))
    return out


def render_vh() -> str:
    """empc_regs.vh: word offsets, reset values (build-dependent ones as the macro), data
    widths (_W) and field positions of every register, and the widths of the ext ports
    (_N: registers of a strobe group, _IDX_W: window index), for hand-written RTL."""
    lines = ["// Generated from gen/empc/regmap.py (python -m empc.regmap / empc roms). Do not edit.",
             "`ifndef EMPC_REGS_VH", "`define EMPC_REGS_VH",
             f"`define EMPC_REG_AXIS_BASE {AXIS_BASE}", f"`define EMPC_REG_AXIS_STRIDE {AXIS_STRIDE}",
             f"`define EMPC_REG_COEF_BASE {COEF_BASE}", f"`define EMPC_REG_COEF_STRIDE {COEF_STRIDE}",
             f"`define EMPC_ID_MAGIC 32'h{ID_MAGIC:08x}", f"`define EMPC_VERSION 32'h{VERSION:08x}",
             f"`define EMPC_WDOG_KEY {WDOG_KEY}", f"`define EMPC_ADC_STUCK_FRAMES {ADC_STUCK_FRAMES}",
             f"`define EMPC_ADC_SUM_FRAMES {ADC_SUM_FRAMES}", f"`define EMPC_ADC_FROZEN_PERIODS {ADC_FROZEN_PERIODS}",
             f"`define EMPC_UDC_FRESH_PERIODS {UDC_FRESH_PERIODS}",
             f"`define EMPC_SEQ_STALL_PERIODS {SEQ_STALL_PERIODS}",
             f"`define EMPC_UNLOCK_KEY {UNLOCK_KEY}", f"`define EMPC_UNLOCK_ARM {UNLOCK_ARM}",
             f"`define EMPC_UNLOCK_ARM_W {UNLOCK_ARM.bit_length()}",
             f"`define EMPC_DEAD_TIME_MIN {DEAD_TIME_MIN}", f"`define EMPC_OC_THRESH_MAX {OC_THRESH_MAX}",
             f"`define EMPC_ROUTE_AXES {ROUTE_AXES}", f"`define EMPC_ROUTE_PHASES {ROUTE_PHASES}",
             f"`define EMPC_ROUTE_OUTPUTS {ROUTE_OUTPUTS}", f"`define EMPC_ROUTE_ENC {ROUTE_ENC}",
             f"`define EMPC_ROUTE_HALL {ROUTE_HALL}", f"`define EMPC_ROUTE_ADC {ROUTE_ADC}",
             f"`define EMPC_ROUTE_OUT_W {ROUTE_OUT_W}", f"`define EMPC_ROUTE_ENC_W {ROUTE_ENC_W}",
             f"`define EMPC_ROUTE_HALL_W {ROUTE_HALL_W}", f"`define EMPC_ROUTE_ADC_W {ROUTE_ADC_W}",
             f"`define EMPC_ROUTE_NIB {ROUTE_NIB}"]
    names = set()
    for b in BLOCKS:
        ms = _macros(b.scope, b.regs, b.ext)
        if b.shared:                         # width of the rd_vals export (the shared read path's input)
            from .regblock import rd_vals_width, sh_n
            ms.append((f"EMPC_{b.scope}_RD_VALS_W", rd_vals_width(b)))
            if b.shadow:                     # width of the sh_we export (accepted writes of shadowed registers)
                ms.append((f"EMPC_{b.scope}_SH_N", sh_n(b)))
        for name, v in ms:
            if name in names:
                raise MapError(f"empc_regs.vh: macro {name} defined twice (rename a register or field)")
            names.add(name)
            lines.append(f"`define {name} " + (f"`{v}" if isinstance(v, str) else f"{v}"))
    lines.append("`endif")
    return "\n".join(lines) + "\n"


def _cell(text: str) -> str:
    return text.replace("|", "\\|")


def render_md() -> str:
    out = ["# Register map", "",
           "Generated from `gen/empc/regmap.py` (`python -m empc.regmap --all`, or `make regs`); do not edit by hand.",
           "The same tables generate the register blocks `rtl/global_regs.v` and `rtl/axis_regs.v`, the firmware "
           "header `fw/empc_regs.h` and `empc_regs.vh`.", "",
           "## Addresses", "",
           "Word addresses on the EMC bus (`emc_a[13:0]`, CS0, 32-bit data):", "",
           "- Global registers: 0x000..0x0ff",
           f"- Axis n registers: {AXIS_BASE:#x} + n * {AXIS_STRIDE:#x} + offset",
           f"- Axis n coefficient image (write-only, inactive bank; layout in docs/blocks/mpc_core.md): "
           f"{COEF_BASE:#x} + n * {COEF_STRIDE:#x} + image word", "",
           f"**CPU byte addresses.**  The FPGA sits on the LPC4088's EMC static chip select 0, which the "
           f"LPC408x/407x user manual (UM10562) maps at {EMC_CS0_BASE:#010x}..0x83ffffff.  The bus is 32 bits wide "
           "(EMCStaticConfig0.MW = 2) and the EMC shifts static addresses to the bus width (SCS.EMCSC = 0), so "
           "the pins EMC_A[13:0], wired to the FPGA's `emc_a[13:0]`, carry CPU byte-address bits [15:2]: word w "
           f"is the 32-bit location at byte address **{EMC_CS0_BASE:#010x} + 4 w** (always 32-bit accesses; "
           "byte lanes are not decoded).  The LX_CPU board code of NuttX "
           "(`boards/arm/lpc17xx_40xx/lx_cpu/src/lpc17_40_fpgainitialize.c`) sets up CS0 for this FPGA exactly so "
           "(EMCStaticConfig0 = 0x2, SCS.EMCSC cleared: \"shift addresses by 2 (32-bit bus)\"); its LPC178x/40xx "
           "memory map lists CS0 at 0x80000000, up to 64 MB.  `fw/empc_regs.h` gives byte addresses: "
           "`EMPC_G_<REG>` and "
           "`EMPC_A_<REG>` are byte offsets, `EMPC_GLOBAL_ADDR(ofs)`, `EMPC_AXIS_ADDR(n, ofs)` and "
           "`EMPC_COEF_ADDR(n, word)` the CPU addresses.", "",
           "Bus timing: the EMC strobes are synchronised into the 100 MHz fabric clock (2 flip-flops), so "
           "configure the LPC4088 static-memory wait states for >= 80 ns read access (WAITOEN/WAITRD) and a "
           ">= 40 ns write pulse (WAITWEN/WAITWR) with >= 20 ns between accesses (WAITTURN).", "",
           "## Columns", "",
           "Offset: word offset (emc_a); byte: CPU byte offset (`fw/empc_regs.h`).  Access: RO read-only, "
           "RW read/write, WO write pulses (read 0), W1C sticky bits cleared by writing 1.  "
           "Reset: the value after reset (`-`: a live value; an `EMPC_*` name: the macro of `empc_formats.vh` "
           "of the build, also readable in CAPS where it matters).  Bits: the data bits (`s`: signed, reads back "
           "sign-extended).  Attributes: `in X` the storage lives in block X; `key` a write acts only with this "
           "value; `below F stored as F`; `refused while G` (guard) and `legal` values (other writes are "
           "refused and counted); `constant`.", ""]
    for b, title in zip(BLOCKS, ("Global", "Axis (offset from the axis base)")):
        out += [f"## {title}", "", "| offset | byte | name | access | reset | bits | attributes | description |",
                "| --- | --- | --- | --- | --- | --- | --- | --- |"]
        for r in b.regs:
            desc = r.doc
            if r.fields:
                desc += " " + "; ".join(f"[{f.lsb + f.width - 1}:{f.lsb}] {f.name}: {f.doc}" if f.width > 1
                                        else f"[{f.lsb}] {f.name}: {f.doc}" for f in r.fields)
            bits = f"{r.bits}{'s' if r.signed else ''}"
            out.append(f"| {r.offset:#05x} | {r.offset * WORD_BYTES:#05x} | {r.name} | {r.access} | "
                       f"{_reset_text(r)} | {bits} | {_cell(r.attrs)} "
                       f"| {_cell(desc)} |")
        out.append("")
    out += ["## Blocks that keep register storage (`ext`)", "", "| name | kind | what |", "| --- | --- | --- |"]
    out += [f"| {e.name} | {e.kind} | {_cell(e.doc)} |" for e in EXT]
    out.append("")
    return "\n".join(out)


def generated_files(root: Path) -> dict[Path, str]:
    """Every committed file generated from the map: path -> text."""
    from . import fwheader, regblock
    out = {root / "docs" / "registers.md": render_md(), root / "fw" / "empc_regs.h": fwheader.render()}
    for b in BLOCKS:
        out[root / "rtl" / f"{b.module}.v"] = regblock.render(b)
        if b.shared:
            out[root / "rtl" / f"{b.shared}.v"] = regblock.render_shared(b)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="write the files generated from the register map")
    ap.add_argument("--all", action="store_true", help="rewrite every committed generated file (make regs)")
    ap.add_argument("--vh", help="write empc_regs.vh here")
    ap.add_argument("--md", help="write the markdown table here")
    a = ap.parse_args(argv)
    if a.all:
        root = Path(__file__).resolve().parents[2]
        for path, text in generated_files(root).items():
            path.parent.mkdir(parents=True, exist_ok=True)
            if not path.exists() or path.read_text() != text:
                path.write_text(text)
                print(f"wrote {path.relative_to(root)}")
    if a.vh:
        Path(a.vh).write_text(render_vh())
    if a.md:
        Path(a.md).write_text(render_md())
    return 0


for _b in BLOCKS:
    check(_b.regs, _b.span, _b.ext, what=_b.module)


if __name__ == "__main__":
    raise SystemExit(main())
