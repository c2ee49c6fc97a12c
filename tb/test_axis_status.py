"""cocotb test of axis_status against empc.rtlmodel.axis_status, clock by clock.

The test drives every input at random (seed EMPC_SEED, printed) within the block's contract (a CPU
read at most every other clock, the sequencer's word writes at least 2 clocks apart) and checks
every clock: the read data and ``busy`` against the model; at the end, every word of the memory
(read through the CPU port once idle).

* status words written at random offsets, also to the counters: preloaded at 2**32 - 1 and near it
  so that sweeps saturate them (and PERIODS wraps);
* events (core flags at core_done, front_sat, overrun, period, gov) at random clocks, also in the
  clock of the sweep pulse (taken by that sweep) and during a sweep (held for the next);
* sweep pulses while a sweep runs (not taken), CPU reads and word writes during sweeps (the sweep
  waits for port A), a word write that meets a read (deferred one clock);
* cnt_clear during a counting sweep and during the zero sweep after rst, rst in the middle of a
  sweep; reads of hidden words (0).
The test fails unless each of these happened.
"""
from __future__ import annotations

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

from empc.rtlmodel import axis_status as M

DEFAULT_SEED = 1301
CLOCKS = int(os.environ.get("EMPC_AS_CLOCKS", "40000"))
INPUTS = ("rst", "reg_rd", "reg_addr", "cnt_re", "stat_re", "cnt_clear", "core_done", "core_flags") + M.EVENTS + \
         ("st_we", "st_addr", "st_wdata", "sweep")
WORDS = sorted(M.STATUS_ADDR | M.COUNTER_ADDR)


@cocotb.test()
async def random_clocks(dut):
    seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
    rng = random.Random(seed)
    dut._log.info("axis_status: seed %d (EMPC_SEED), %d clocks", seed, CLOCKS)
    Clock(dut.clk, 10, unit="ns").start()
    model = M.AxisStatus()
    st = dict(reads=0, reads_nonzero=0, reads_hidden=0, sweeps=0, saturated=0, wrapped=0, deferred=0,
              sweep_ignored=0, clear_in_sweep=0, clear_in_zero=0, rst_in_sweep=0, ev_in_pulse=0)
    last_rd = last_we = -10
    held = (0, 0)
    for c in range(CLOCKS):
        await FallingEdge(dut.clk)
        v = {n: 0 for n in INPUTS}
        if c < 3 or rng.random() < 0.0005:
            v["rst"] = 1
            st["rst_in_sweep"] += int(model.act)
        if c - last_rd >= 2 and rng.random() < 0.3:
            a = rng.choice(WORDS + [rng.randrange(64), rng.randrange(256)])
            v.update(reg_rd=1, reg_addr=a, cnt_re=int(a in M.COUNTER_ADDR), stat_re=int(a in M.STATUS_ADDR))
            last_rd = c
        if c - last_we >= 2 and rng.random() < 0.15:
            a = rng.choice(WORDS)
            d = rng.choice([rng.getrandbits(32), M.MASK32, M.MASK32 - 1, 0])
            v.update(st_we=1, st_addr=a, st_wdata=d)
            last_we, held = c, (a, d)
            st["deferred"] += v["reg_rd"]
        elif c == last_we + 1:          # the contract: the sequencer holds them for a deferred write
            v.update(st_addr=held[0], st_wdata=held[1])
        else:                           # otherwise they are don't-care: garbage must not be written
            v.update(st_addr=rng.choice(WORDS), st_wdata=rng.getrandbits(32))
        if rng.random() < 0.05:
            v.update(core_done=1, core_flags=rng.getrandbits(11))
        for e in M.EVENTS:
            if rng.random() < 0.03:
                v[e] = 1
        if rng.random() < 0.02:
            v["sweep"] = 1
            st["sweep_ignored"] += int(model.act or model.zact)
            st["ev_in_pulse"] += int(any(v[e] for e in M.EVENTS) or v["core_done"])
        if rng.random() < 0.002:
            v["cnt_clear"] = 1
            st["clear_in_sweep"] += int(model.act)
            st["clear_in_zero"] += int(model.zact and model.zall)
        # saturation / wrap evidence: a counter at 2^32 - 1 whose event is being added
        if model.act and model.q_ok and model.k < M.NCNT and (model.sev >> model.k) & 1 and model.q == M.MASK32:
            st["wrapped" if M.CNT_ADDR[model.k] == M.PERIODS else "saturated"] += 1
        for n, x in v.items():
            getattr(dut, n).value = x
        st["sweeps"] += int(v["sweep"] and not v["rst"] and not v["cnt_clear"] and not (model.act or model.zact))
        exp = model.clock(**v)
        # compare after the edge: the registered outputs of this clock
        if v["reg_rd"]:
            st["reads"] += 1
            st["reads_nonzero"] += int(exp != 0)
            st["reads_hidden"] += int(exp == 0 and v["reg_addr"] in M.COUNTER_ADDR | M.STATUS_ADDR and
                                      ((model.hide_cnt and v["reg_addr"] in M.COUNTER_ADDR) or
                                       (model.hide_st and v["reg_addr"] in M.STATUS_ADDR)))
        await RisingEdge(dut.clk)
        await ReadOnly()
        assert int(dut.rdata.value) == exp, f"clock {c}: rdata {int(dut.rdata.value):#x} model {exp:#x} ({v})"
        assert int(dut.busy.value) == int(model.busy), f"clock {c}: busy {int(dut.busy.value)} model {model.busy}"
    # the whole memory, read back once idle
    await FallingEdge(dut.clk)
    for n in INPUTS:
        getattr(dut, n).value = 0
    model.clock()
    for _ in range(100):
        await FallingEdge(dut.clk)
        model.clock()
    for a in range(64):
        await FallingEdge(dut.clk)
        dut.reg_rd.value, dut.reg_addr.value = 1, a
        dut.cnt_re.value, dut.stat_re.value = int(a in M.COUNTER_ADDR), int(a in M.STATUS_ADDR)
        exp = model.clock(reg_rd=1, reg_addr=a, cnt_re=int(a in M.COUNTER_ADDR), stat_re=int(a in M.STATUS_ADDR))
        await FallingEdge(dut.clk)
        dut.reg_rd.value = 0
        model.clock()
        assert int(dut.rdata.value) == exp, f"word {a}: {int(dut.rdata.value):#x} model {exp:#x}"
    dut._log.info("axis_status: seed %d, %d clocks, %s (every read and busy equal to the model)", seed, CLOCKS, st)
    for k, x in st.items():
        assert x > 0, f"never exercised: {k} ({st})"


def test_axis_status():
    from runner import run
    run(toplevel="axis_status", test_module="test_axis_status")
