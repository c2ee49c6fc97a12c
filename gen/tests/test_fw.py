"""Firmware side: fw/empc_drv.c compiles warning-free (-std=c99 -Wall -Wextra -Werror -pedantic)
for the Cortex-M4 (arm-none-eabi-gcc when installed) and the host; every macro of the generated
fw/empc_regs.h, evaluated by the C compiler, equals the register map; the header defines nothing
else.  The header against the RTL: tb/test_empc_drv.py (every register over the bus)."""
import re
import subprocess
from pathlib import Path

import pytest

import fw_build
from empc import fwheader, regmap

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "build" / "fw"
FUNCTION_LIKE = {"EMPC_GLOBAL_ADDR", "EMPC_AXIS_ADDR", "EMPC_COEF_ADDR", "EMPC_FIELD", "EMPC_GET",
                 "EMPC_GLOBAL_REGS", "EMPC_AXIS_REGS", "EMPC_REGS_H"}


def test_driver_compiles_host():
    cmd = fw_build.compile_target(OUT / "empc_drv_host.o", arm=False)
    print(" ".join(cmd))


def test_driver_compiles_cortex_m4():
    if not fw_build.arm_available():
        pytest.skip("arm-none-eabi-gcc not on PATH (apt-get install gcc-arm-none-eabi); host build tested")
    cmd = fw_build.compile_target(OUT / "empc_drv_m4.o", arm=True)
    size = subprocess.run(["arm-none-eabi-size", str(OUT / "empc_drv_m4.o")], capture_output=True, text=True).stdout
    print(" ".join(cmd), "\n", size)


def test_host_lib_builds():
    assert fw_build.build_host_lib(OUT).exists()


def test_header_values_equal_map():
    exp = fwheader.expected_macros()
    prog = ["#include <stdio.h>", '#include "empc_regs.h"', "int main(void) {"]
    prog += [f'    printf("{n} %lu\\n", (unsigned long)({n}));' for n in exp]
    prog += ["    return 0;", "}", ""]
    out = fw_build.run_program("\n".join(prog), OUT, "header_values")
    got = {l.split()[0]: int(l.split()[1]) for l in out.splitlines()}
    assert got == exp
    print(f"{len(exp)} macros of fw/empc_regs.h evaluated by the C compiler equal the map")


def test_header_defines_nothing_else():
    r = subprocess.run([fw_build.host_cc(), "-std=c99", "-dM", "-E", str(ROOT / "fw" / "empc_regs.h")],
                       capture_output=True, text=True, check=True)
    names = {m.group(1) for m in re.finditer(r"^#define (EMPC_\w+)", r.stdout, re.M)}
    extra = names - set(fwheader.expected_macros()) - FUNCTION_LIKE
    assert not extra, f"macros not from the map: {sorted(extra)}"


def test_header_byte_addresses():
    """Word offsets of the map x 4 = byte offsets of the header; CS0 base from UM10562."""
    m = fwheader.expected_macros()
    assert m["EMPC_EMC_BASE"] == 0x80000000
    for b in regmap.BLOCKS:
        for r in b.regs:
            assert m[f"EMPC_{b.scope}_{r.name}"] == 4 * r.offset
            assert m[f"EMPC_{b.scope}_{r.name}_ACCESS"] == fwheader.ACC_CODE[r.access]
            for f in r.fields:
                assert m[f"EMPC_{b.scope}_{r.name}_{f.name.upper()}_MASK"] == f.mask
    assert m["EMPC_AXIS_BASE"] == 4 * regmap.AXIS_BASE and m["EMPC_COEF_STRIDE"] == 4 * regmap.COEF_STRIDE
