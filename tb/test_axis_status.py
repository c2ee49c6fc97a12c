"""cocotb test of axis_status against empc.rtlmodel.axis_status, with the test as ctrl_seq's engine.

The test drives the word stream and the sweep handshake with the engine's timing (a word: one
E_OP clock, 32 bit clocks with st_sh and st_bit one bit ahead, the st_wr clock; a sweep: sw_go,
the zero words if sw_all, the 14 counters, the sw_end clock) and the CPU side, random (seed
EMPC_SEED, printed), and checks every clock:

* sw_req / sw_all against the model;
* every CPU read (the clock after reg_rd) against the model: status words and counters, hidden
  words (after rst, after CMD.clear_counters until a zero sweep ends), other offsets (0);
* so every word written: status words streamed at random offsets (also counters: preloaded near
  2**32 - 1 so that sweeps saturate them, and PERIODS wraps), counters + events of the sweeps,
  zero sweeps.

Corner cases forced: reads in the st_wr clock (the write waits one clock), events in the clock a
counter step starts (counted in the next sweep) and in the sw_end clock (lost), ctl_go in every
phase of a sweep (an E_OP clock, a bit clock, the st_wr clock, the sw_end clock), cnt_clear in the
sw_go / sw_end clock, rst in the middle of a sweep; sweeps get garbage on st_d (ignored).  The test
fails unless each of these happened and saturations, wraps and completed zero sweeps were seen.
"""
from __future__ import annotations

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from empc.rtlmodel import axis_status as M
from empc.rtlmodel.ctrl_seq import COUNTERS, STATUS_WORDS

DEFAULT_SEED = 1301
CLOCKS = int(os.environ.get("EMPC_AS_CLOCKS", "40000"))
INPUTS = ("rst", "reg_rd", "reg_addr", "cnt_re", "stat_re", "cnt_clear", "core_done", "core_flags") + M.EVENTS + \
         ("st_sh", "st_d", "st_wr", "st_addr", "st_bit", "sw_go", "sw_end", "ctl_go")
WORDS = sorted(M.STATUS_ADDR | M.COUNTER_ADDR)


def word_job(addr: int, value: int) -> list[dict]:
    """A word streamed outside a sweep (a status program step): E_OP, bits 0..31, st_wr."""
    steps = [dict(st_addr=addr, kind="op")]
    steps += [dict(st_addr=addr, st_sh=1, st_d=(value >> j) & 1, st_bit=(j + 1) & 31, kind="bit")
              for j in range(32)]
    steps.append(dict(st_addr=addr, st_wr=1, kind="wr", write=(addr, value)))
    return steps


def sweep_job(rng: random.Random, zero_words: bool) -> list[dict]:
    """sw_go, then per word an E_OP clock (the model forms the word), 32 bit clocks with garbage on
    st_d, the st_wr clock; then the sw_end clock."""
    steps = [dict(st_addr=rng.randrange(64), sw_go=1, kind="go")]
    words = [M.ADDR[w] for w in STATUS_WORDS] * zero_words + [M.ADDR[c] for c in COUNTERS]
    for a in words:
        steps.append(dict(st_addr=a, kind="op", sweep_word=a))
        steps += [dict(st_addr=a, st_sh=1, st_d=rng.getrandbits(1), st_bit=(j + 1) & 31, kind="bit")
                  for j in range(32)]
        steps.append(dict(st_addr=a, st_wr=1, kind="wr", sweep_commit=a))
    steps.append(dict(st_addr=0, sw_end=1, kind="end"))
    return steps


@cocotb.test()
async def random_protocol(dut):
    seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
    rng = random.Random(seed)
    dut._log.info("axis_status: seed %d (EMPC_SEED), %d clocks", seed, CLOCKS)
    Clock(dut.clk, 10, unit="ns").start()
    for n in INPUTS:
        getattr(dut, n).value = 0
    dut.rst.value = 1
    for _ in range(3):
        await FallingEdge(dut.clk)
    model = M.AxisStatus()
    job: list[dict] = []
    job_is_sweep = False
    pending: dict[int, int | None] = {}
    rd_expect = None
    rd_gap = rst_left = 0
    st = dict(reads=0, reads_nonzero=0, reads_hidden=0, sweeps=0, zero_sweeps_done=0, saturated=0, wrapped=0,
              rd_at_wr=0, ev_at_op=0, ev_at_end=0, ctl_in_op=0, ctl_in_bit=0, ctl_at_wr=0, ctl_at_end=0,
              clear_at_go=0, clear_at_end=0, rst_in_sweep=0)
    for clk in range(CLOCKS):
        await FallingEdge(dut.clk)
        # ---- outputs of the previous clock ----
        if rd_expect is not None:
            addr, exp = rd_expect
            got = int(dut.rdata.value)
            assert got == exp, f"clock {clk}: read of {addr:#04x}: rtl {got:#010x} model {exp:#010x}"
            st["reads_nonzero"] += int(got != 0)
            rd_expect = None
        if not rst_left:
            assert (int(dut.sw_req.value), int(dut.sw_all.value)) == (model.sweep_request, model.sweep_all), \
                f"clock {clk}: sw_req/sw_all rtl {(int(dut.sw_req.value), int(dut.sw_all.value))} " \
                f"model {(model.sweep_request, model.sweep_all)}"
        # ---- this clock's inputs ----
        ins = {n: 0 for n in INPUTS}
        if rst_left or rng.random() < 2e-4:
            if not rst_left:
                rst_left = rng.randrange(1, 4)
                st["rst_in_sweep"] += int(job_is_sweep and bool(job))
            rst_left -= 1
            ins["rst"] = 1
            job, job_is_sweep = [], False
            for n, v in ins.items():
                getattr(dut, n).value = v
            model.reset()
            continue
        if not job:
            r = rng.random()
            if model.sweep_request and r < 0.05:
                job, job_is_sweep = sweep_job(rng, model.sweep_all), True
                # a control start in one clock of the sweep: none, or in a clock of a random phase
                phase = rng.choice([None, None, None, "op", "bit", "wr", "end"])
                if phase:
                    rng.choice([x for x in job if x["kind"] == phase])["ctl"] = True
            elif r < 0.08:
                a = rng.choice(WORDS)
                v = rng.choice([rng.getrandbits(32), rng.randrange(4)] + [M.MASK32 - rng.randrange(2)] * 2)
                if rng.random() < 0.2:
                    a, v = M.ADDR["PERIODS"], M.MASK32
                job, job_is_sweep = word_job(a, v), False
        step = job.pop(0) if job else {}
        for k in ("st_addr", "st_sh", "st_d", "st_bit", "st_wr", "sw_go", "sw_end"):
            if k in step:
                ins[k] = step[k]
        kind = step.get("kind")
        ctl = step.get("ctl", False) or rng.random() < (2e-4 if job else 0.01)
        if ctl:
            ins["ctl_go"] = 1
            if job_is_sweep:
                key = {"op": "ctl_in_op", "bit": "ctl_in_bit", "wr": "ctl_at_wr", "end": "ctl_at_end"}.get(kind)
                if key:
                    st[key] += 1
        # CPU read (at most every other clock; often in a st_wr clock)
        if rd_gap:
            rd_gap -= 1
        elif rng.random() < (0.5 if kind == "wr" else 0.15):
            a = rng.choice(WORDS) if rng.random() < 0.85 else rng.randrange(256)
            ins["reg_rd"], ins["reg_addr"] = 1, a
            rd_gap = rng.randrange(1, 4)
            st["rd_at_wr"] += int(kind == "wr")
        # events (often in a counter step's E_OP clock and in the sw_end clock)
        p_ev = 0.3 if kind in ("op", "end") and job_is_sweep else 0.01
        if rng.random() < p_ev:
            ins["core_done"], ins["core_flags"] = 1, rng.getrandbits(11)
        for n in M.EVENTS:
            ins[n] = int(rng.random() < p_ev)
        any_ev = ins["core_done"] or any(ins[n] for n in M.EVENTS)
        st["ev_at_op"] += int(bool(any_ev) and kind == "op" and job_is_sweep)
        st["ev_at_end"] += int(bool(any_ev) and kind == "end")
        ins["cnt_clear"] = int(rng.random() < (0.05 if kind in ("go", "end") else 2e-4))
        st["clear_at_go"] += int(bool(ins["cnt_clear"]) and kind == "go")
        st["clear_at_end"] += int(bool(ins["cnt_clear"]) and kind == "end")
        # the register block's read strobes for this block's words (axis_regs decodes the map)
        ins["cnt_re"] = int(bool(ins["reg_rd"]) and ins["reg_addr"] in M.COUNTER_ADDR)
        ins["stat_re"] = int(bool(ins["reg_rd"]) and ins["reg_addr"] in M.STATUS_ADDR)
        for n, v in ins.items():
            getattr(dut, n).value = v
        # ---- the model, in the RTL's order within the clock ----
        if ins["reg_rd"]:
            rd_expect = (ins["reg_addr"], model.read(ins["reg_addr"]))
            st["reads"] += 1
            st["reads_hidden"] += int(ins["reg_addr"] in M.COUNTER_ADDR and model.hide_cnt)
        if "sweep_word" in step:
            pending[step["sweep_word"]] = model.sweep_word(step["sweep_word"])
        if "sweep_commit" in step:
            a = step["sweep_commit"]
            v = pending.pop(a)
            if v is None:
                st["saturated"] += 1
            else:
                st["wrapped"] += int(a in M.WRAPS and v == 0 and not model.zero and model.mem.get(a, 0) == M.MASK32)
                model.write(a, v)
        if "write" in step:
            model.write(*step["write"])
        if ins["sw_go"]:
            model.sweep_start()
            st["sweeps"] += 1
        events_lost = bool(ins["sw_end"])
        if ins["sw_end"]:
            st["zero_sweeps_done"] += int(model.zero)
            model.sweep_end()
        if ins["ctl_go"]:
            model.control_start()
            job = []            # the control program replaces any program in flight
        if not events_lost:
            if ins["core_done"]:
                model.core_update(ins["core_flags"])
            for n in M.EVENTS:
                if ins[n]:
                    model.event(n)
        if ins["cnt_clear"]:
            model.clear_counters()
        if not job:
            job_is_sweep = False
    dut._log.info("axis_status: seed %d, %d clocks, %s (every read and sw_req/sw_all equal to the model)",
                  seed, CLOCKS, st)
    for k, v in st.items():
        assert v > 0, f"never exercised: {k} ({st})"


def test_axis_status():
    from runner import run
    run(toplevel="axis_status", test_module="test_axis_status")
