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


# ---------------------------------------------------------------------------------------------
# NAXES axes (docs/four_axes.md piece 2): one block RAM {axis, word}, one sweep engine, a queue
# ---------------------------------------------------------------------------------------------
MX_SEED = 1601
MX_CLOCKS = int(os.environ.get("EMPC_AS_MX_CLOCKS", "30000"))
ISO_CLOCKS = int(os.environ.get("EMPC_AS_ISO_CLOCKS", "12000"))
ISO_GAP = 400           # the victim's own pulses / clears are >= this apart (a control period is >= 5000 clocks)


def _naxes(dut) -> int:
    return len(dut.busy)


def _mx_stimulus(rng, n, clocks, *, p_sweep=0.02, p_clear=0.002, p_event=0.03, p_rst=0.0003, axes=None,
                 gap=0, counters_ok=True, cmd_from=0):
    """Random inputs within the contract (reads >= 2 clocks apart, word writes >= 2 apart, st_addr /
    st_wdata held the clock after st_we) for ``axes`` (default: all).  ``gap``: an axis's sweep
    pulses and clears at least that many clocks apart; ``counters_ok``: word writes also to the
    counters (preloaded at and near 2^32 - 1); ``cmd_from``: no pulse, clear or word write before that
    clock."""
    axes = range(n) if axes is None else axes
    words = sorted(M.STATUS_ADDR | M.COUNTER_ADDR) if counters_ok else sorted(M.STATUS_ADDR)
    out = []
    last_rd = last_we = -10
    last_cmd = {a: -10 ** 6 for a in axes}
    held = (0, 0)
    for c in range(clocks):
        v = {k: 0 for k in INPUTS}
        if c < 3 or rng.random() < p_rst:
            v["rst"] = 1
        quiet = c < 3 or c >= clocks - 3            # (the first clocks: a new model; the last: the read-back)
        if not quiet and c - last_rd >= 2 and rng.random() < 0.3:
            a = rng.choice(list(axes)) if rng.random() < 0.9 else rng.randrange(1 << M.axis_bits(n))
            off = rng.choice(sorted(M.STATUS_ADDR | M.COUNTER_ADDR) + [rng.randrange(64), rng.randrange(256)])
            v.update(reg_rd=1, reg_addr=(a << 8) | off, cnt_re=int(off in M.COUNTER_ADDR),
                     stat_re=int(off in M.STATUS_ADDR))
            last_rd = c
        if not quiet and c >= cmd_from and c - last_we >= 2 and rng.random() < 0.15:
            a = rng.choice(list(axes))
            d = rng.choice([rng.getrandbits(32), M.MASK32, M.MASK32 - 1, 0])
            v.update(st_we=1, st_addr=(a << 6) | rng.choice(words), st_wdata=d)
            last_we, held = c, (v["st_addr"], d)
        elif c == last_we + 1:
            v.update(st_addr=held[0], st_wdata=held[1])
        else:
            v.update(st_addr=rng.getrandbits(6 + M.axis_bits(n)), st_wdata=rng.getrandbits(32))
        burst = rng.random() < 0.003            # every axis in the same clock
        for a in axes:
            if rng.random() < 0.05 or burst:
                v["core_done"] |= 1 << a
                v["core_flags"] |= rng.getrandbits(11) << (11 * a)
            for e in M.EVENTS:
                if rng.random() < p_event or burst:
                    v[e] |= 1 << a
            if c - last_cmd[a] >= gap and c >= cmd_from:
                if rng.random() < p_sweep or burst:
                    v["sweep"] |= 1 << a
                    last_cmd[a] = c
                elif rng.random() < p_clear or (burst and rng.random() < 0.3):
                    v["cnt_clear"] |= 1 << a
                    last_cmd[a] = c
        if c == 20 and cmd_from <= c:           # a clear inside the zero sweep after the first reset
            v["cnt_clear"] |= 1 << rng.choice(list(axes))
        out.append(v)
    return out


async def _mx_run(dut, model, stim, log_name, stats=None, observe=None):
    """Drive ``stim`` clock by clock; every clock rdata and busy against ``model``.  ``observe(c, v,
    busy_before, rdata)`` sees each clock."""
    n = model.naxes
    for c, v in enumerate(stim):
        await FallingEdge(dut.clk)
        if stats is not None:
            _mx_cover(model, v, stats)
        busy_before = model.busy
        for k, x in v.items():
            getattr(dut, k).value = x
        exp = model.clock(**v)
        await RisingEdge(dut.clk)
        await ReadOnly()
        got = int(dut.rdata.value)
        assert got == exp, f"{log_name} clock {c}: rdata {got:#x} model {exp:#x} ({v})"
        assert int(dut.busy.value) == model.busy, \
            f"{log_name} clock {c}: busy {int(dut.busy.value):0{n}b} model {model.busy:0{n}b}"
        if observe is not None:
            observe(c, v, busy_before, got)


async def _mx_readback(dut, model, axes):
    """Idle 400 clocks, then read every word of ``axes`` through the CPU port: {(axis, offset): value}."""
    seen = {}
    quiet = {k: 0 for k in INPUTS}
    for _ in range(400):
        await FallingEdge(dut.clk)
        for k in INPUTS:
            getattr(dut, k).value = 0
        model.clock(**quiet)
    assert model.busy == 0, "a sweep still runs after 400 idle clocks"
    for a in axes:
        for off in range(64):
            v = dict(quiet, reg_rd=1, reg_addr=(a << 8) | off, cnt_re=int(off in M.COUNTER_ADDR),
                     stat_re=int(off in M.STATUS_ADDR))
            await FallingEdge(dut.clk)
            for k, x in v.items():
                getattr(dut, k).value = x
            exp = model.clock(**v)
            await FallingEdge(dut.clk)
            dut.reg_rd.value = 0
            model.clock(**quiet)
            assert int(dut.rdata.value) == exp, f"axis {a} word {off}: {int(dut.rdata.value):#x} model {exp:#x}"
            seen[(a, off)] = exp
    return seen


def _mx_cover(m, v, st):
    """Count the corners of the multi-axis engine this clock's inputs hit (model state before the edge)."""
    if v["rst"]:
        return
    busy = m.busy
    on = m.eng_on()
    take = v["sweep"] & ~busy & m.full
    st["sweeps"] += bin(take).count("1")
    st["simultaneous_pulses"] += int(bin(take).count("1") >= 2)
    if on and not m.zall:
        st["queued"] += bin(take).count("1")          # the engine serves another axis: these wait
    elif not on and take:
        st["queued"] += bin(take).count("1") - 1      # an idle engine starts one request
    st["not_taken"] += bin(v["sweep"] & busy).count("1")
    clr = v["cnt_clear"]
    if clr:
        if m.zact and m.zall:
            st["clear_in_rst_sweep"] += 1
        elif (m.act or m.zact) and (clr >> m.ax) & 1:
            st["clear_restarts"] += 1
        if (m.act or m.zact) and not m.zall and clr & ~(1 << m.ax):
            st["clear_queued"] += 1
        st["clear_cancels_pending"] += int(bool(clr & m.cp))
        st["clear_and_pulse_other_axis"] += int(bool(v["sweep"] & ~clr))
    if not (m.act or m.zact) and m.zp and not clr:
        st["queued_zero_started"] += 1
    if m.act and m.q_ok and (m.sev >> m.k) & 1 and m.q == M.MASK32:
        st["wrapped" if M.CNT_ADDR[m.k] == M.PERIODS else "saturated"] += 1
    st["deferred"] += int(v["st_we"] and v["reg_rd"])
    if v["reg_rd"]:
        a, off = v["reg_addr"] >> 8, v["reg_addr"] & 255
        hid = off in M.COUNTER_ADDR and a < m.naxes and (m.hide_cnt >> a) & 1 and not m.hide_st
        st["reads_hidden_counter_one_axis"] += int(bool(hid) and m.hide_cnt != m.full)


@cocotb.test()
async def multi_axis(dut):
    """Every axis at random (pulses, clears, events, word writes, reads), also all at once, every
    clock rdata and busy[NAXES] against the model; the whole memory at the end."""
    n = _naxes(dut)
    seed = int(os.environ.get("EMPC_SEED", MX_SEED))
    rng = random.Random(seed)
    dut._log.info("axis_status NAXES %d: seed %d (EMPC_SEED), %d clocks", n, seed, MX_CLOCKS)
    Clock(dut.clk, 10, unit="ns").start()
    model = M.AxisStatus(naxes=n)
    st = {k: 0 for k in ("sweeps", "simultaneous_pulses", "queued", "not_taken", "clear_in_rst_sweep",
                         "clear_restarts", "clear_queued", "clear_cancels_pending", "clear_and_pulse_other_axis",
                         "queued_zero_started", "saturated", "wrapped", "deferred",
                         "reads_hidden_counter_one_axis")}
    # round robin: while axis b waits, the engine starts at most one sweep of each other axis
    waits = [0] * n
    prev = {"idle": False}
    worst = [0]

    def observe(c, v, busy_before, got):
        m = model
        started = prev["idle"] and (m.act or m.zact) and not v["rst"]
        if v["rst"]:
            waits[:] = [0] * n
        elif started:
            for b in range(n):
                if b != m.ax and ((m.cp | m.zp) >> b) & 1:
                    waits[b] += 1
                    worst[0] = max(worst[0], waits[b])
            waits[m.ax] = 0
        prev["idle"] = not (m.act or m.zact)
    await _mx_run(dut, model, _mx_stimulus(rng, n, MX_CLOCKS), "multi_axis", stats=st, observe=observe)
    assert worst[0] <= n - 1, f"an axis waited for {worst[0]} sweeps of other axes (round robin: <= {n - 1})"
    st["most_sweeps_waited"] = worst[0]
    mem = await _mx_readback(dut, model, range(n))
    nz = sum(1 for x in mem.values() if x)
    dut._log.info("axis_status NAXES %d: seed %d, %d clocks, %s; %d of %d words non-zero at the end "
                  "(every read and busy equal to the model)", n, seed, MX_CLOCKS, st, nz, len(mem))
    need = [k for k in st if n > 1 or k in ("sweeps", "not_taken", "clear_restarts", "saturated", "wrapped",
                                             "deferred", "clear_in_rst_sweep")]
    for k in need:
        assert st[k] > 0, f"never exercised: {k} ({st})"


@cocotb.test()
async def isolation(dut):
    """Axis b's reads and counters are the same with and without the other axes' traffic: two runs from
    reset with identical inputs of axis b (its pulses and clears >= ISO_GAP apart; pulses, clears and
    word writes, to its status words, after the zero sweep after reset, which every axis's traffic on
    port A stretches), run A with every other axis busy, run B with the other axes silent; every read of
    b at a clock where busy[b] is low in both runs, and b's whole memory at the end, must be equal."""
    import pytest
    n = _naxes(dut)
    if n < 2:
        pytest.skip("isolation needs NAXES >= 2")
    seed = int(os.environ.get("EMPC_SEED", MX_SEED))
    rng = random.Random(seed + 1)
    Clock(dut.clk, 10, unit="ns").start()
    results = []
    for victim in range(n):
        stim_v = _mx_stimulus(random.Random(rng.getrandbits(32)), n, ISO_CLOCKS, axes=[victim], gap=ISO_GAP,
                              counters_ok=False, p_sweep=0.01, p_clear=0.001, p_rst=0,
                              cmd_from=1000)
        others = [a for a in range(n) if a != victim]
        stim_o = _mx_stimulus(random.Random(rng.getrandbits(32)), n, ISO_CLOCKS, axes=others, p_sweep=0.03,
                              p_rst=0)
        # run A: the victim's inputs plus the others'; reads and word writes of the others only where the
        # victim's contract leaves room (reads >= 2 apart, writes >= 2 apart over both)
        stim_a = []
        last_rd = last_we = -10
        for c, (sv, so) in enumerate(zip(stim_v, stim_o)):
            v = dict(sv)
            for k in ("cnt_clear", "core_done", "core_flags", "sweep") + M.EVENTS:
                v[k] = sv[k] | so[k]
            nxt_v = stim_v[c + 1] if c + 1 < len(stim_v) else None
            if not v["reg_rd"] and so["reg_rd"] and c - last_rd >= 2 and not (nxt_v and nxt_v["reg_rd"]):
                v.update(reg_rd=1, reg_addr=so["reg_addr"], cnt_re=so["cnt_re"], stat_re=so["stat_re"])
            if not v["st_we"] and so["st_we"] and c - last_we >= 2 and not (nxt_v and nxt_v["st_we"]) \
                    and not (c >= 1 and stim_v[c - 1]["st_we"]):
                v.update(st_we=1, st_addr=so["st_addr"], st_wdata=so["st_wdata"])
            if c >= 1 and stim_a[c - 1]["st_we"]:
                v.update(st_addr=stim_a[c - 1]["st_addr"], st_wdata=stim_a[c - 1]["st_wdata"])
            last_rd = c if v["reg_rd"] else last_rd
            last_we = c if v["st_we"] else last_we
            stim_a.append(v)
        runs = []
        for name, stim in (("A", stim_a), ("B", stim_v)):
            model = M.AxisStatus(naxes=n)
            rec = {}
            waited = [0]

            def observe(c, v, busy_before, got, rec=rec, model=model, waited=waited):
                if v["reg_rd"] and v["reg_addr"] >> 8 == victim:
                    rec[c] = (got, (busy_before >> victim) & 1, v["reg_addr"] & 255)
                if (model.cp >> victim) & 1:
                    waited[0] += 1
            await _mx_run(dut, model, stim, f"isolation axis {victim} run {name}", observe=observe)
            mem = await _mx_readback(dut, model, [victim])
            runs.append((rec, mem, waited[0]))
        (ra, ma, wa), (rb, mb, _) = runs
        assert ma == mb, f"axis {victim}: memory differs with the other axes' traffic"
        cmp = [c for c in ra if c in rb and not ra[c][1] and not rb[c][1]]
        bad = [c for c in cmp if ra[c][0] != rb[c][0]]
        assert not bad, f"axis {victim}: reads differ at clocks {bad[:5]}: {[(ra[c], rb[c]) for c in bad[:5]]}"
        nzc = sum(1 for c in cmp if ra[c][0])
        cnt_nz = sum(1 for c in cmp if ra[c][0] and ra[c][2] in M.COUNTER_ADDR)
        results.append((victim, len(cmp), nzc, cnt_nz, wa))
        assert len(cmp) > 500 and nzc > 100 and cnt_nz > 50 and wa > 0, \
            f"axis {victim}: too little evidence ({len(cmp)} reads, {nzc} non-zero, {cnt_nz} of counters, {wa} waits)"
    dut._log.info("axis_status isolation NAXES %d seed %d: per axis (axis, reads compared, non-zero, "
                  "non-zero counter reads, clocks its sweep waited behind other axes in run A): %s",
                  n, seed, results)


def test_axis_status_4axes():
    from runner import run
    run(toplevel="axis_status", test_module="test_axis_status", parameters={"NAXES": 4}, name="test_axis_status_n4",
        testcase=os.environ.get("EMPC_AS_TC", "multi_axis,isolation").split(","))
