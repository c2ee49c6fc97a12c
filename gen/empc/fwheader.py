"""C header for the LPC4088 firmware, generated from the register map: ``fw/empc_regs.h``.

``render()`` returns the text (committed; ``python -m empc.regmap --all`` rewrites it and
gen/tests/test_regmap.py fails when it is stale).  ``expected_macros()`` lists every macro
the header must define with its value: gen/tests/test_fw.py compiles a program that prints
them through the C compiler and compares them with this list and with the map.

Everything in the header is a CPU BYTE address or byte offset (the RTL header and
docs/registers.md count 32-bit words): FPGA word w is at EMPC_EMC_BASE + 4 w.
"""
from __future__ import annotations

from . import formats, image
from .regmap import (AXIS_BASE, AXIS_STRIDE, BLOCKS, COEF_BASE, COEF_STRIDE, EMC_CS0_BASE, ID_MAGIC, VERSION,
                     ROUTE_AXES, ROUTE_OUTPUTS, ROUTE_PHASES, MapError, UDC_FRESH_PERIODS, UNLOCK_ARM, UNLOCK_KEY,
                     WDOG_KEY, WORD_BYTES, Reg)

ACC_CODE = {"RO": 0, "RW": 1, "WO": 2, "W1C": 3}
_HDR = "/* Generated from gen/empc/regmap.py by gen/empc/fwheader.py (python -m empc.regmap --all). Do not edit. */"


def _u(v: int, digits: int = 8) -> str:
    return f"0x{v:0{digits}X}u"


def reset_mask(r: Reg) -> int:
    """Bits of the word whose value after reset (after configuration, for memory-backed
    windows) the map defines: none for live read-only values; build-dependent fields
    (empc_formats.vh macros, see CAPS) excluded."""
    if r.access == "RO" and not r.const:
        return 0
    return 0xFFFFFFFF & ~r.reset_build_mask()


def reg_macros(scope: str, r: Reg) -> list[tuple[str, str, int]]:
    """(name, text, value) of the macros of one register."""
    p = f"EMPC_{scope}_{r.name}"
    sg = 1 if r.signed else 0
    out = [(p, _u(r.offset * WORD_BYTES, 3), r.offset * WORD_BYTES),
           (f"{p}_ACCESS", f"EMPC_ACC_{r.access}", ACC_CODE[r.access]),
           (f"{p}_RESET", _u(r.reset_int()), r.reset_int()),
           (f"{p}_RESET_MASK", _u(reset_mask(r)), reset_mask(r)),
           (f"{p}_BITS", _u(r.mask), r.mask),
           (f"{p}_SIGNED", str(sg), sg)]
    for f in r.fields:
        q = f"{p}_{f.name.upper()}"
        out += [(f"{q}_SHIFT", f"{f.lsb}u", f.lsb), (f"{q}_MASK", _u(f.mask), f.mask),
                (f"{q}_WIDTH", f"{f.width}u", f.width)]
    for f in r.parts():                    # legal ranges: the firmware can check before writing
        if isinstance(f.legal, range):
            q = f"{p}_{f.name.upper()}" if r.fields else p
            out += [(f"{q}_LEGAL_MIN", f"{f.legal.start}u", f.legal.start),
                    (f"{q}_LEGAL_MAX", f"{f.legal.stop - 1}u", f.legal.stop - 1)]
    return out


def constants() -> list[tuple[str, str, int, str]]:
    """(name, text, value, comment) of the global constants."""
    return [
        ("EMPC_EMC_BASE", _u(EMC_CS0_BASE), EMC_CS0_BASE, "CPU byte address of FPGA word 0 (EMC CS0)"),
        ("EMPC_WORD_BYTES", f"{WORD_BYTES}u", WORD_BYTES, "bytes per FPGA word (32-bit accesses only)"),
        ("EMPC_AXIS_BASE", _u(AXIS_BASE * WORD_BYTES), AXIS_BASE * WORD_BYTES, "byte offset of axis 0's registers"),
        ("EMPC_AXIS_STRIDE", _u(AXIS_STRIDE * WORD_BYTES), AXIS_STRIDE * WORD_BYTES, "bytes per axis"),
        ("EMPC_COEF_BASE", _u(COEF_BASE * WORD_BYTES), COEF_BASE * WORD_BYTES,
         "byte offset of axis 0's coefficient window (write-only, inactive bank)"),
        ("EMPC_COEF_STRIDE", _u(COEF_STRIDE * WORD_BYTES), COEF_STRIDE * WORD_BYTES, "bytes per coefficient window"),
        ("EMPC_COEF_WORDS", f"{COEF_STRIDE}u", COEF_STRIDE, "words in one coefficient window"),
        ("EMPC_IMG_USED", f"{image.USED}u", image.USED, "words of a coefficient image (gen/empc/image.py)"),
        ("EMPC_IMG_LAYOUT", f"{image.LAYOUT}u", image.LAYOUT, "image layout version (CAPS.img_layout)"),
        ("EMPC_IMG_A_CFG", f"{image.A_CFG}u", image.A_CFG, "image word holding the configuration (CFG)"),
        ("EMPC_IMG_CFG_PERIOD_LSB", f"{image.CFG_PERIOD_LSB}u", image.CFG_PERIOD_LSB,
         "CFG field: control period the image was designed for (PWM periods; = CTRL.pwm_per_control)"),
        ("EMPC_IMG_CFG_PERIOD_BITS", f"{image.CFG_PERIOD_BITS}u", image.CFG_PERIOD_BITS, "width of that field"),
        ("EMPC_ID_MAGIC", _u(ID_MAGIC), ID_MAGIC, "value of ID ('EMPC')"),
        ("EMPC_IP_VERSION", _u(VERSION), VERSION, "value of VERSION (major 31:16, minor 15:8, patch 7:0)"),
        ("EMPC_WDOG_KEY", _u(WDOG_KEY, 4), WDOG_KEY, "write to WDOG_KICK to restart the watchdog"),
        ("EMPC_UNLOCK_KEY", _u(UNLOCK_KEY, 4), UNLOCK_KEY,
         "write to UNLOCK: the next write of that block may change FAULT_MASK / WDOG_TIMEOUT"),
        ("EMPC_UNLOCK_ARM_PERIODS", f"{UNLOCK_ARM}u", UNLOCK_ARM,
         "the unlock ends at this PWM period start after the key (or at the next write of the block)"),
        ("EMPC_UDC_FRESH_PERIODS", f"{UDC_FRESH_PERIODS}u", UDC_FRESH_PERIODS,
         "PWM periods a UDC value stays valid (rewrite it more often, else FAULT.dclink)"),
        ("EMPC_ROUTE_AXES", f"{ROUTE_AXES}u", ROUTE_AXES, "axes the routing registers can name"),
        ("EMPC_ROUTE_PHASES", f"{ROUTE_PHASES}u", ROUTE_PHASES,
         "OUT_SEL code of axis a, phase p: 1 + EMPC_ROUTE_PHASES * a + p (0 = output off)"),
        ("EMPC_ROUTE_OUTPUTS", f"{ROUTE_OUTPUTS}u", ROUTE_OUTPUTS, "half-bridge outputs (OUT_SEL0/1 fields)"),
        ("EMPC_WIN_LOG2_MAX", f"{formats.WIN_LOG2_MAX}u", formats.WIN_LOG2_MAX,
         "largest KACC.win the sequencer implements (speed window 2^win; larger values act as this)"),
        ("EMPC_ACC_RO", "0u", 0, "access: read-only"),
        ("EMPC_ACC_RW", "1u", 1, "access: read/write"),
        ("EMPC_ACC_WO", "2u", 2, "access: write pulses (reads 0)"),
        ("EMPC_ACC_W1C", "3u", 3, "access: sticky bits, write 1 to clear"),
    ]


def expected_macros() -> dict[str, int]:
    """Every value macro of the header with its value (from the map); MapError if two
    registers or fields would define the same name."""
    out = {n: v for n, _, v, _ in constants()}
    for b in BLOCKS:
        for r in b.regs:
            for n, _, v in reg_macros(b.scope, r):
                if n in out:
                    raise MapError(f"fw/empc_regs.h: macro {n} defined twice (rename a register or field)")
                out[n] = v
    return out


def _comment(text: str, width: int = 104) -> list[str]:
    """A C comment wrapped at ``width`` columns."""
    words, lines, line = text.split(), [], "/*"
    for w in words:
        if len(line) + 1 + len(w) > width:
            lines.append(line)
            line = "  "
        line += " " + w
    lines.append(line + " */")
    return lines


def render() -> str:
    expected_macros()                     # refuses name clashes
    L = [_HDR, "/*",
         " * empc register map for the LPC4088 firmware (one source: gen/empc/regmap.py, docs/registers.md).",
         " *",
         " * Addresses.  The FPGA is 32-bit static memory on the LPC4088 EMC chip select 0, which the",
         f" * LPC408x/407x user manual (UM10562) maps at 0x{EMC_CS0_BASE:08X}.  Configure EMCStaticConfig0.MW = 2",
         " * (32 bit) and leave SCS.EMCSC = 0 (static addresses shifted to the bus width): the pins",
         " * EMC_A[13:0], wired to the FPGA's emc_a[13:0], then carry CPU byte-address bits [15:2], so",
         " * FPGA word w is the 32-bit location at EMPC_EMC_BASE + 4 w.  Use 32-bit accesses only.  (The LX_CPU",
         " * board code of NuttX, lpc17_40_fpgainitialize.c, sets STATICCONFIG0 = 0x2 and clears SCS.EMCSC.)",
         " * Every offset below is in BYTES:",
         " *   EMPC_G_<REG>        byte offset of a global register: address EMPC_GLOBAL_ADDR(EMPC_G_<REG>)",
         " *   EMPC_A_<REG>        byte offset in an axis block: address EMPC_AXIS_ADDR(n, EMPC_A_<REG>)",
         " *   EMPC_COEF_ADDR(n, w)  word w of axis n's coefficient window (write-only, inactive bank)",
         " * Per register: _ACCESS (EMPC_ACC_*), _RESET (value after reset), _RESET_MASK (the bits",
         " * _RESET defines: 0 for live values; build-dependent fields, e.g. CTRL.pwm_per_control, are",
         " * left out: read them from CAPS), _BITS (bits it stores or reports), _SIGNED (reads back",
         " * sign-extended).  Per field: _SHIFT, _MASK (in place), _WIDTH; EMPC_FIELD / EMPC_GET.",
         " * EMPC_GLOBAL_REGS(X) / EMPC_AXIS_REGS(X) call X(NAME) for every register (tables, dumps,",
         " * tests: paste EMPC_G_##NAME, EMPC_A_##NAME##_RESET, ...).",
         " */",
         "#ifndef EMPC_REGS_H", "#define EMPC_REGS_H", "", "#include <stdint.h>", ""]
    w = max(len(n) for n, *_ in constants())
    for n, t, _, c in constants():
        L.append(f"#define {n:<{w}} {t:<12} /* {c} */")
    L += ["",
          "#define EMPC_GLOBAL_ADDR(ofs)   (EMPC_EMC_BASE + (uint32_t)(ofs))",
          "#define EMPC_AXIS_ADDR(n, ofs)  (EMPC_EMC_BASE + EMPC_AXIS_BASE + (uint32_t)(n) * EMPC_AXIS_STRIDE \\",
          "                                 + (uint32_t)(ofs))",
          "#define EMPC_COEF_ADDR(n, w)    (EMPC_EMC_BASE + EMPC_COEF_BASE + (uint32_t)(n) * EMPC_COEF_STRIDE \\",
          "                                 + EMPC_WORD_BYTES * (uint32_t)(w))",
          "/* field F of a register word: EMPC_FIELD(EMPC_A_CTRL_RUN, 1), EMPC_GET(EMPC_A_STATUS_FAULT, st) */",
          "#define EMPC_FIELD(F, v)        ((((uint32_t)(v)) << F##_SHIFT) & F##_MASK)",
          "#define EMPC_GET(F, word)       ((((uint32_t)(word)) & F##_MASK) >> F##_SHIFT)", ""]
    for b in BLOCKS:
        title = "global registers: byte offsets from EMPC_EMC_BASE" if b.scope == "G" else \
            "axis registers: byte offsets from the axis base (EMPC_AXIS_ADDR)"
        L.append(f"/* ---------------- {title} ---------------- */")
        for r in b.regs:
            doc = r.doc.replace("*/", "* /")
            L += _comment(f"{r.name} ({r.access}{', ' + r.attrs if r.attrs else ''}): {doc}")
            ms = reg_macros(b.scope, r)
            w = max(len(n) for n, *_ in ms)
            L += [f"#define {n:<{w}} {t}" for n, t, _ in ms]
        L.append("")
        tab = "EMPC_GLOBAL_REGS" if b.scope == "G" else "EMPC_AXIS_REGS"
        L.append(f"/* X(NAME) for every {b.module[:-5]} register: EMPC_{b.scope}_##NAME, "
                 f"EMPC_{b.scope}_##NAME##_ACCESS, ... */")
        L.append(f"#define {tab}(X) \\")
        rows, line = [], "   "
        for r in b.regs:
            item = f" X({r.name})"
            if len(line) + len(item) > 100:
                rows.append(line)
                line = "   "
            line += item
        rows.append(line)
        L += [row + " \\" for row in rows[:-1]] + [rows[-1], ""]
    L += ["#endif /* EMPC_REGS_H */", ""]
    return "\n".join(L)
