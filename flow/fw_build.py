"""Compile the firmware side (fw/empc_drv.c with the generated fw/empc_regs.h).

One set of flags for every build: ``-std=c99 -Wall -Wextra -Werror -pedantic``.
* ``compile_target()``: the driver as the LPC4088 firmware builds it (volatile accesses):
  with ``arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -ffreestanding`` when that compiler is on
  PATH (Debian: ``apt-get install gcc-arm-none-eabi``), else with the host gcc;
* ``build_host_lib()``: the driver with ``-DEMPC_HOST`` plus tb/empc_drv_host.c as a shared
  library for the tests (bus functions as ctypes callbacks, the header's register table as data).
Used by gen/tests/test_fw.py and tb/test_empc_drv.py.
"""
from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

from files import ROOT  # noqa: E402  (flow/ is on sys.path for every user of this module)

FW = ROOT / "fw"
CFLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
ARM = ["arm-none-eabi-gcc", "-mcpu=cortex-m4", "-mthumb", "-ffreestanding", "-Os"]


def host_cc() -> str:
    for cc in ("gcc", "cc", "clang"):
        if shutil.which(cc):
            return cc
    raise RuntimeError("no host C compiler (gcc) on PATH: apt-get install gcc")


def arm_available() -> bool:
    return shutil.which(ARM[0]) is not None


def _run(cmd: list[str]) -> None:
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}\n{r.stdout}{r.stderr}")
    if r.stderr.strip():
        raise RuntimeError(f"compiler output (warnings are errors): {r.stderr}")


def compile_target(out: Path, arm: bool | None = None) -> list[str]:
    """Compile fw/empc_drv.c to the object ``out``; returns the command used."""
    arm = arm_available() if arm is None else arm
    cmd = (ARM if arm else [host_cc()]) + CFLAGS + [f"-I{FW}", "-c", str(FW / "empc_drv.c"), "-o", str(out)]
    out.parent.mkdir(parents=True, exist_ok=True)
    _run(cmd)
    return cmd


def build_host_lib(out_dir: Path, driver: Path | None = None, name: str = "libempc_host.so") -> Path:
    """The host shared library (driver + tb/empc_drv_host.c); ``driver``: another driver source (mutants)."""
    out_dir.mkdir(parents=True, exist_ok=True)
    lib = out_dir / name
    _run([host_cc()] + CFLAGS + ["-DEMPC_HOST", "-shared", "-fPIC", f"-I{FW}", str(driver or FW / "empc_drv.c"),
                                 str(ROOT / "tb" / "empc_drv_host.c"), "-o", str(lib)])
    return lib


def run_program(source: str, out_dir: Path, name: str, include: tuple[Path, ...] = ()) -> str:
    """Compile a C program (includes fw/ and ``include``) with the host compiler and the flags above; its stdout."""
    out_dir.mkdir(parents=True, exist_ok=True)
    src = out_dir / f"{name}.c"
    src.write_text(source)
    exe = out_dir / name
    _run([host_cc()] + CFLAGS + [f"-I{FW}"] + [f"-I{p}" for p in include] + [str(src), "-o", str(exe)])
    return subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout
