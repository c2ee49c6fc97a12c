"""CPU register map: the one source for the RTL header, the documentation and the Python driver.

The LPC4088 external memory controller sees the FPGA as 32-bit static memory
(CS0); addresses here are WORD addresses on emc_a.  Global registers sit at
0x000..0x0ff, axis n's registers at AXIS_BASE + n * AXIS_STRIDE, axis n's
coefficient-image window (write-only, into the inactive bank; `CMD.coef_swap`
makes it active at the next control-period boundary) at COEF_BASE + n * COEF_STRIDE.

``python -m empc.regmap --vh FILE --md FILE`` writes the Verilog header and the
markdown table; `empc roms` writes the header next to the formats header and a
test keeps docs/registers.md in step.
"""
from __future__ import annotations

import argparse
from dataclasses import dataclass, field
from pathlib import Path

ID_MAGIC = 0x454D5043   # 'EMPC'
VERSION = 0x00010000     # major.minor.patch = 1.0.0 (bits 31:16 major, 15:8 minor, 7:0 patch)
AXIS_BASE = 0x100
AXIS_STRIDE = 0x100
COEF_BASE = 0x1000
COEF_STRIDE = 0x400
WDOG_KEY = 0x5A5A
# ADC plausibility persistence (build-time, rtl/adc_spi.v parameter defaults via empc_regs.vh)
ADC_STUCK_FRAMES = 4      # consecutive frames with a code at a rail -> FAULT.adc_stuck
ADC_SUM_FRAMES = 4        # consecutive frames with |sum of the phase currents| > ADC_SUM_THRESH -> FAULT.adc_sum
ADC_FROZEN_PERIODS = 4    # consecutive PWM periods (bridges on) with a channel bit-identical -> FAULT.adc_frozen


@dataclass(frozen=True)
class Field:
    name: str
    lsb: int
    width: int
    doc: str


@dataclass(frozen=True)
class Reg:
    name: str
    offset: int
    access: str          # RO, RW, WO (write pulses), W1C (sticky, write 1 to clear)
    reset: int
    doc: str
    fields: tuple = field(default_factory=tuple)
    width: int = 32
    signed: bool = False     # a width < 32 value reads back sign-extended to 32 bits

    def readback(self, value: int) -> int:
        """What an RW register reads after ``value`` was written: the fields (or the low
        ``width`` bits, sign-extended if ``signed``) of the word, other bits 0."""
        if self.fields:
            return sum(value & (((1 << f.width) - 1) << f.lsb) for f in self.fields)
        v = value & ((1 << self.width) - 1)
        if self.signed and v >> (self.width - 1):
            v -= 1 << self.width
        return v & 0xFFFFFFFF


GLOBAL = (
    Reg("ID", 0x000, "RO", ID_MAGIC, "Magic 'EMPC' (0x454D5043): the bus works and the FPGA is configured."),
    Reg("VERSION", 0x001, "RO", VERSION, "IP version major.minor.patch (31:16, 15:8, 7:0)."),
    Reg("CAPS", 0x002, "RO", 0, "Build parameters.", (
        Field("naxes", 0, 4, "axes in this bitstream"),
        Field("horizon", 4, 4, "prediction horizon N of the core"),
        Field("img_layout", 8, 8, "coefficient image layout version"),
        Field("pwm_per_control", 16, 8, "PWM periods per control period Ts (reset value)"))),
    Reg("PWM_HALF", 0x003, "RO", 0, "PWM half period in fabric clocks (centre-aligned: period = 2 x this)."),
    Reg("SCRATCH", 0x004, "RW", 0, "Free for bus tests."),
    Reg("WDOG_TIMEOUT", 0x008, "RW", 400, "Watchdog timeout in PWM periods (0 disables). Expiry latches the "
        "watchdog fault on every axis (all bridges off).", width=16),
    Reg("WDOG_KICK", 0x009, "WO", 0, f"Write {WDOG_KEY:#06x} to restart the watchdog; other values are ignored."),
    Reg("TIME", 0x00a, "RO", 0, "Free-running PWM period counter."),
    Reg("IRQ_STATUS", 0x00b, "W1C", 0, "Interrupt causes (sticky, write 1 to clear).", (
        Field("period", 0, 1, "a control period completed on axis 0"),
        Field("fault", 1, 1, "a fault latched on any axis"))),
    Reg("IRQ_ENABLE", 0x00c, "RW", 0, "Interrupt enables (same bits as IRQ_STATUS); cpu_irq = |(status & enable)."),
)

ADC_PSUM_FIELDS = (Field("sum", 0, 20, "signed 20-bit sum, ADC LSB"), Field("count", 24, 7, "frames"))

AXIS = (
    Reg("CTRL", 0x00, "RW", 0, "Axis control.", (
        Field("enable", 0, 1, "bridges may switch (PWM running, outputs enabled) unless a fault is latched"),
        Field("run", 1, 1, "control law active; 0 = bridges enabled with zero voltage (u and ebar held at 0)"),
        Field("complementary", 2, 1, "bridge mode: 0 = PWM + enable (LX_PWR), 1 = complementary high/low with dead time"),
        Field("pwm_per_control", 8, 8, "PWM periods per control period Ts (>= 1); reset from the header"))),
    Reg("CMD", 0x01, "WO", 0, "Command pulses (write 1).", (
        Field("fault_clear", 0, 1, "clear latched faults (only those whose cause has gone)"),
        Field("adc_cal", 1, 1, "start ADC offset calibration (refused while the bridges are on; bridges on abort it)"),
        Field("ref_sync", 2, 1, "set the reference generator to the measured output (bumpless start)"),
        Field("coef_swap", 3, 1, "make the uploaded coefficient bank active at the next control period"),
        Field("clear_counters", 4, 1, "zero the saturation and event counters"),
        Field("align_clear", 5, 1, "forget the index alignment (back to HALL alignment)"))),
    Reg("STATUS", 0x02, "RO", 0, "Axis state.", (
        Field("running", 0, 1, "control law running"),
        Field("bridges_on", 1, 1, "outputs enabled (enable and no fault)"),
        Field("aligned", 2, 1, "angle aligned at the encoder index (else HALL rough alignment)"),
        Field("adc_cal_busy", 3, 1, "ADC offset calibration in progress"),
        Field("adc_cal_done", 4, 1, "ADC calibration has completed since reset"),
        Field("core_ready", 5, 1, "MPC core loaded its boot coefficients"),
        Field("coef_bank", 6, 1, "active coefficient bank"),
        Field("swap_pending", 7, 1, "a bank swap waits for the next control period"),
        Field("fault", 8, 1, "a fault is latched (bridges forced off)"),
        Field("adc_refused", 9, 1, "an ADC calibration or offset write was refused or a calibration aborted (bridges on / calibrating); CMD.clear_counters clears it"))),
    Reg("FAULT", 0x03, "RO", 0, "Latched (sticky) fault causes; cleared by CMD.fault_clear once the cause has gone.", (
        Field("overcurrent", 0, 1, "|phase current| above OC_THRESH in some ADC frame (every frame is checked)"),
        Field("hall", 1, 1, "illegal HALL code 000 or 111"),
        Field("encoder", 2, 1, "illegal quadrature transition"),
        Field("watchdog", 3, 1, "CPU did not kick the watchdog in time"),
        Field("dclink", 4, 1, "UDC outside UDC_MIN..UDC_MAX"),
        Field("overrun", 5, 1, "the control computation did not finish before the PWM update"),
        Field("adc", 6, 1, "ADC frame error (leading zero bit read as 1)"),
        Field("adc_stuck", 7, 1, f"an ADC code at a rail (0 or full scale) in {ADC_STUCK_FRAMES} consecutive frames"),
        Field("adc_sum", 8, 1, f"|i_a + i_b + i_c| above ADC_SUM_THRESH in {ADC_SUM_FRAMES} consecutive frames"),
        Field("adc_frozen", 9, 1, f"an ADC channel bit-identical in every frame of {ADC_FROZEN_PERIODS} PWM periods with the bridges on"))),
    Reg("FAULT_MASK", 0x04, "RW", 0x3ff, "Fault causes that switch the bridges off (same bits as FAULT). "
        "Masked causes are still recorded in FAULT."),
    Reg("DEAD_TIME", 0x05, "RW", 50, "Dead time in fabric clocks (complementary mode).", width=8),
    Reg("KDC", 0x06, "RW", 1 << 16, "DC-link compensation Udc_nominal / Udc, unsigned Q2.16 (1.0 = 0x10000).", width=18),
    Reg("UDC", 0x07, "RW", 36000, "DC-link voltage in mV as measured by the CPU (checked against UDC_MIN..MAX).", width=16),
    Reg("UDC_MIN", 0x08, "RW", 0, "Lowest allowed DC link, mV (0 disables the lower check).", width=16),
    Reg("UDC_MAX", 0x09, "RW", 0xffff, "Highest allowed DC link, mV.", width=16),
    Reg("OC_THRESH", 0x0a, "RW", 1800, "Overcurrent threshold, ADC LSB of |code - offset| (per phase, every frame).", width=12),
    Reg("ADC_OFF0", 0x0b, "RW", 2048, "ADC offset phase A (calibration writes it; reads the active value; writes refused while calibrating or with the bridges on: STATUS.adc_refused).", width=12),
    Reg("ADC_OFF1", 0x0c, "RW", 2048, "ADC offset phase B.", width=12),
    Reg("ADC_OFF2", 0x0d, "RW", 2048, "ADC offset phase C.", width=12),
    Reg("ANGLE_CAL", 0x0e, "RW", 0, "Electrical angle at the encoder index (2^16 = one electrical turn).", width=16),
    Reg("HALL_OFFSET", 0x0f, "RW", 0, "Electrical angle of the HALL sector-1 start (2^16 = one turn).", width=16),
    Reg("KACC", 0x10, "RW", 0, "Speed-estimate acceleration term: omega += (KACC * i_q) >> KACC_SHIFT "
        "(reset from the header; 0 = plain eq. 37).", (
        Field("kacc", 0, 18, "signed gain"), Field("shift", 24, 5, "right shift"))),
    Reg("ID_REF", 0x11, "RW", 0, "d-current reference, ADC LSB Q.4 (signed 18 bit).", width=18, signed=True),
    Reg("IQ_REF", 0x12, "RW", 0, "q-current reference (feed-forward), ADC LSB Q.4 (signed 18 bit).", width=18, signed=True),
    Reg("SEG_ADDR", 0x13, "RW", 0, "Reference segment slot (0..15) that the SEG_LEN .. SEG_FLAGS fields access. "
        "Each field write goes straight into the slot (no staging): do not rewrite a slot that the "
        "next control period may load (the active slot's successor or a pending SEG_START slot).", width=4),
    Reg("SEG_LEN", 0x14, "RW", 0, "Segment length in control periods (0 = hold forever); field of slot SEG_ADDR "
        "(SEG_* reads return the field of slot SEG_ADDR).", width=32),
    Reg("SEG_R0_LO", 0x15, "RW", 0, "Segment start value, low word (task output, 64-bit Q.32: counts or counts/Ts)."),
    Reg("SEG_R0_HI", 0x16, "RW", 0, "Segment start value, high word."),
    Reg("SEG_D1_LO", 0x17, "RW", 0, "First forward difference per control period, low word (64-bit Q.32)."),
    Reg("SEG_D1_HI", 0x18, "RW", 0, "First forward difference, high word."),
    Reg("SEG_D2", 0x19, "RW", 0, "Second forward difference (signed 32-bit Q.32 of the output unit)."),
    Reg("SEG_FLAGS", 0x1a, "RW", 0, "Segment flags of slot SEG_ADDR.", (
        Field("relative", 0, 1, "start from the current reference value instead of R0"),
        Field("last", 1, 1, "hold at the end of this segment instead of moving to the next slot"))),
    Reg("SEG_START", 0x1b, "WO", 0, "Write a slot number to start the profile there at the next control period."),
    Reg("ADC_SUM_THRESH", 0x1c, "RW", 300, "Sum-of-currents threshold, ADC LSB of |d_a + d_b + d_c| (d = code - offset), checked on every frame (FAULT.adc_sum).", width=12),
    Reg("POS", 0x20, "RO", 0, "Encoder count (x4, modular 32 bit)."),
    Reg("SPEED", 0x21, "RO", 0, "Speed estimate at the last control period, counts per Ts, signed Q16.16."),
    Reg("THETA", 0x22, "RO", 0, "Electrical angle (2^16 = one turn).", width=16),
    Reg("I_D", 0x23, "RO", 0, "i_d at the last control period, ADC LSB Q.4 (signed).", width=18, signed=True),
    Reg("I_Q", 0x24, "RO", 0, "i_q at the last control period, ADC LSB Q.4 (signed).", width=18, signed=True),
    Reg("U_D", 0x25, "RO", 0, "u_d applied, PWM ticks Q16.8 (signed 24 bit).", width=24, signed=True),
    Reg("U_Q", 0x26, "RO", 0, "u_q applied, PWM ticks Q16.8 (signed 24 bit).", width=24, signed=True),
    Reg("REF", 0x27, "RO", 0, "Task-output reference w_k of the last control period (bits 47:16 speed, Q16.16 / "
        "55:24 position, Q24.8 of the generator value)."),
    Reg("IABC0", 0x28, "RO", 0, "Last raw ADC codes phases A (11:0) and B (27:16).", width=28),
    Reg("IABC1", 0x29, "RO", 0, "Last raw ADC code phase C (11:0).", width=12),
    Reg("LATENCY", 0x2a, "RO", 0, "Clocks from the ADC trigger to the new PWM compare values of the last control period."),
    Reg("PERIODS", 0x2b, "RO", 0, "Control periods run since enable."),
    Reg("ADC_PSUM0", 0x2c, "RO", 0, "Phase A: sum of code - offset over the ADC frames of the last complete PWM period, "
        "and their number (period mean = sum / count; both from the same period).", ADC_PSUM_FIELDS),
    Reg("ADC_PSUM1", 0x2d, "RO", 0, "Phase B: as ADC_PSUM0.", ADC_PSUM_FIELDS),
    Reg("ADC_PSUM2", 0x2e, "RO", 0, "Phase C: as ADC_PSUM0.", ADC_PSUM_FIELDS),
    Reg("SAT_OPERAND", 0x30, "RO", 0, "Saturation counter: core operand. SAT_* and CNT_OVERRUN count control "
        "periods in which the event happened (32-bit, saturating; updated after the control period's "
        "modulation)."),
    Reg("SAT_GAIN", 0x31, "RO", 0, "Saturation counter: gain polynomial."),
    Reg("SAT_TERM", 0x32, "RO", 0, "Saturation counter: product term."),
    Reg("SAT_ACC", 0x33, "RO", 0, "Saturation counter: accumulator."),
    Reg("SAT_DU", 0x34, "RO", 0, "Saturation counter: du."),
    Reg("SAT_U", 0x35, "RO", 0, "Saturation counter: u before the limiter."),
    Reg("SAT_EBAR", 0x36, "RO", 0, "Saturation counter: ebar."),
    Reg("SAT_EBAR_INC", 0x37, "RO", 0, "Counter: ebar increment clamped (eq. 25 anti-windup active)."),
    Reg("SAT_LIMIT", 0x38, "RO", 0, "Counter: voltage limit active."),
    Reg("SAT_WN", 0x39, "RO", 0, "Counter: scheduling speed clamped to Omega_e."),
    Reg("SAT_SIGNAL", 0x3a, "RO", 0, "Saturation counter: core signal (SIG_W)."),
    Reg("SAT_FRONT", 0x3b, "RO", 0, "Saturation counter: front end (transforms, speed, duty)."),
    Reg("CNT_OVERRUN", 0x3c, "RO", 0, "Control computations that missed their PWM update."),
    Reg("CNT_ADC_MISS", 0x3d, "RO", 0, "PWM centres that missed the ADC sampling window (trigger off the frame grid, or a sync restart cut the window: no current sample that period; 8-bit, saturating; not cleared by "
        "CMD.clear_counters).", width=8),
    Reg("CNT_ENC_ERR", 0x3e, "RO", 0, "Illegal quadrature transitions (16-bit, saturating).", width=16),
)


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


def render_vh() -> str:
    lines = ["// Generated from gen/empc/regmap.py (python -m empc.regmap / empc roms). Do not edit.",
             "`ifndef EMPC_REGS_VH", "`define EMPC_REGS_VH",
             f"`define EMPC_REG_AXIS_BASE {AXIS_BASE}", f"`define EMPC_REG_AXIS_STRIDE {AXIS_STRIDE}",
             f"`define EMPC_REG_COEF_BASE {COEF_BASE}", f"`define EMPC_REG_COEF_STRIDE {COEF_STRIDE}",
             f"`define EMPC_ID_MAGIC 32'h{ID_MAGIC:08x}", f"`define EMPC_VERSION 32'h{VERSION:08x}",
             f"`define EMPC_WDOG_KEY {WDOG_KEY}", f"`define EMPC_ADC_STUCK_FRAMES {ADC_STUCK_FRAMES}",
             f"`define EMPC_ADC_SUM_FRAMES {ADC_SUM_FRAMES}", f"`define EMPC_ADC_FROZEN_PERIODS {ADC_FROZEN_PERIODS}"]
    for scope, regs in (("G", GLOBAL), ("A", AXIS)):
        for r in regs:
            lines.append(f"`define EMPC_{scope}_{r.name} {r.offset}")
            lines.append(f"`define EMPC_{scope}_{r.name}_RESET {r.reset}")
            for f in r.fields:
                lines.append(f"`define EMPC_{scope}_{r.name}_{f.name.upper()} {f.lsb}")
                if f.width > 1:
                    lines.append(f"`define EMPC_{scope}_{r.name}_{f.name.upper()}_W {f.width}")
    lines.append("`endif")
    return "\n".join(lines) + "\n"


def render_md() -> str:
    out = ["# Register map", "",
           "Generated from `gen/empc/regmap.py` (`python -m empc.regmap --md docs/registers.md`); do not edit by hand.",
           "Word addresses on the EMC bus (CS0, 32-bit). Access: RO read-only, RW read/write, WO write pulses "
           "(read 0), W1C sticky bits cleared by writing 1.", "",
           f"- Global registers: 0x000..0x0ff",
           f"- Axis n registers: {AXIS_BASE:#x} + n * {AXIS_STRIDE:#x} + offset",
           f"- Axis n coefficient image (write-only, inactive bank; layout in docs/blocks/mpc_core.md): "
           f"{COEF_BASE:#x} + n * {COEF_STRIDE:#x} + image word", "",
           "Bus timing: the EMC strobes are synchronised into the 100 MHz fabric clock (2 flip-flops), so "
           "configure the LPC4088 static-memory wait states for >= 80 ns read access (WAITOEN/WAITRD) and a "
           ">= 40 ns write pulse (WAITWEN/WAITWR) with >= 20 ns between accesses (WAITTURN).", ""]
    for title, regs, base in (("Global", GLOBAL, 0), ("Axis (offset from the axis base)", AXIS, None)):
        out += [f"## {title}", "", "| offset | name | access | reset | description |", "| --- | --- | --- | --- | --- |"]
        for r in regs:
            desc = r.doc
            if r.fields:
                desc += " " + "; ".join(f"[{f.lsb + f.width - 1}:{f.lsb}] {f.name}: {f.doc}" if f.width > 1
                                        else f"[{f.lsb}] {f.name}: {f.doc}" for f in r.fields)
            out.append(f"| {r.offset:#05x} | {r.name} | {r.access} | {r.reset:#x} | {desc} |")
        out.append("")
    return "\n".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="write the register map header and docs")
    ap.add_argument("--vh")
    ap.add_argument("--md")
    a = ap.parse_args(argv)
    if a.vh:
        Path(a.vh).write_text(render_vh())
    if a.md:
        Path(a.md).write_text(render_md())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
