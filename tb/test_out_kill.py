"""cocotb tests of out_kill (clock-independent kill path), Icarus.

The reference is written here (as for fault_ctrl): q = d & kill_n where kill_n is low while
pwr_fault_n, locked (once armed: after the first clock out of reset) or rst_n_in say so, and
after every kill event until the synchronised cause has been taken over.

* corners, each with the registered inputs d = all ones (the worst case: outputs on):
  - a power-stage fault pulse of 2 ns between two clock edges: q = 0 within the pulse (no
    clock edge in between), `pstage` rises 2 clock edges later, stays >= 3 clocks, and q
    stays 0 until `pstage` has fallen;
  - pwr_fault_n held low 50 clocks: q = 0 and pstage = 1 throughout, q = 0 for >= 2 clocks
    after the release;
  - locked low after arming: q = 0 at once, `clock` cause; rst_n_in low: q = 0, no cause;
  - start-up: before the first reset release (not armed) locked low and pwr_fault_n low
    turn q off without a cause;
  - clk_dead pulse: q = 0 at once, `clock` cause;
  - a pulse during rst: q = 0, the cause appears after rst is released (>= 3 clocks);
  - the clock stopped: a fault pulse while there is no clock edge turns q off and the cause
    appears once the clock runs again;
* random: 300 kill pulses of random width (0.3 .. 40 ns) at random phase on the three kill
  inputs, random d every clock; checked every 0.5 ns against the reference: q = 0 from the
  pulse on until the cause has been seen at 2 clock edges with rst low, q = d otherwise, and
  every pulse produced a cause of >= 3 clocks.
Seed: EMPC_SEED (default 2718).
"""
from __future__ import annotations

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge, ReadOnly, RisingEdge, Timer

W = 6
ALL = (1 << W) - 1
SEED = int(os.environ.get("EMPC_SEED", "2718"))


class Env:
    def __init__(self, dut):
        self.dut = dut
        self.clk = Clock(dut.clk, 10, unit="ns")

    async def start(self, locked=1, reset_clocks=4):
        d = self.dut
        d.rst.value = 1
        d.d.value = ALL
        d.pwr_fault_n.value = 1
        d.rst_n_in.value = 1
        d.locked.value = locked
        d.clk_dead.value = 0
        self.clk.start()
        await ClockCycles(d.clk, reset_clocks)
        await FallingEdge(d.clk)
        d.rst.value = 0
        await ClockCycles(d.clk, 4)            # armed; the sync chains hold 0
        await FallingEdge(d.clk)
        assert int(d.q.value) == ALL and int(d.pstage.value) == 0 and int(d.clock.value) == 0

    async def cause_profile(self, sig, max_clocks=40):
        """Clock edges until `sig` rises and how long it stays; q must stay 0 until it has fallen."""
        d = self.dut
        rise, high = None, 0
        for n in range(max_clocks):
            await RisingEdge(d.clk)
            await ReadOnly()
            v = int(getattr(d, sig).value)
            if v:
                rise = n + 1 if rise is None else rise
                high += 1
            assert int(d.q.value) == 0 or (rise is not None and not v), \
                f"q = {int(d.q.value):#x} at clock {n + 1} before {sig} was taken over"
            if rise is not None and not v:
                break
        return rise, high


async def _pulse(dut, name, width_ns, level=0):
    getattr(dut, name).value = level
    await Timer(round(width_ns * 100) * 10, unit="ps")
    getattr(dut, name).value = 1 - level


@cocotb.test()
async def startup_unlocked(dut):
    """Before the first lock and reset release the outputs are off and no cause is raised."""
    env = Env(dut)
    dut.rst.value = 1
    dut.d.value = ALL
    dut.pwr_fault_n.value = 1
    dut.rst_n_in.value = 1
    dut.locked.value = 0
    dut.clk_dead.value = 0
    env.clk.start()
    for k in range(20):
        await RisingEdge(dut.clk)
        await ReadOnly()
        assert int(dut.q.value) == 0 and int(dut.clock.value) == 0 and int(dut.pstage.value) == 0
        await FallingEdge(dut.clk)
        dut.pwr_fault_n.value = k % 2             # the power stage still powering up
    await FallingEdge(dut.clk)
    dut.pwr_fault_n.value = 1
    dut.locked.value = 1
    await ClockCycles(dut.clk, 3)
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    for _ in range(20):
        await RisingEdge(dut.clk)
        await ReadOnly()
        assert int(dut.clock.value) == 0 and int(dut.pstage.value) == 0, "start-up counted as a fault"
    assert int(dut.q.value) == ALL
    dut._log.info("start-up: q = 0 while unlocked, no clock cause after the first lock")


@cocotb.test()
async def corners(dut):
    env = Env(dut)
    await env.start()
    res = {}
    # short power-stage pulse between two edges
    await FallingEdge(dut.clk)
    await Timer(1, unit="ns")
    dut.pwr_fault_n.value = 0
    await Timer(1, unit="ns")
    assert int(dut.q.value) == 0, "q not off during a 2 ns pulse (no clock edge in between)"
    await Timer(1, unit="ns")
    dut.pwr_fault_n.value = 1
    await Timer(1, unit="ns")
    assert int(dut.q.value) == 0, "q came back after the pulse before the cause was taken over"
    rise, high = await env.cause_profile("pstage")
    assert rise is not None and rise <= 3 and high >= 3, (rise, high)
    res["pulse 2 ns"] = (rise, high)
    await ClockCycles(dut.clk, 3)
    await ReadOnly()
    assert int(dut.q.value) == ALL
    # held low 50 clocks
    await FallingEdge(dut.clk)
    dut.pwr_fault_n.value = 0
    for n in range(50):
        await RisingEdge(dut.clk)
        await ReadOnly()
        assert int(dut.q.value) == 0 and (n < 2 or int(dut.pstage.value) == 1), n
    await FallingEdge(dut.clk)
    dut.pwr_fault_n.value = 1
    after = 0
    while True:
        await RisingEdge(dut.clk)
        await ReadOnly()
        if int(dut.q.value):
            break
        after += 1
        assert after < 20
    assert after >= 2, f"q back {after} clocks after the release"
    assert int(dut.pstage.value) == 0
    res["held 50 clocks: clocks off after release"] = after
    # locked low (armed)
    await FallingEdge(dut.clk)
    await Timer(2, unit="ns")
    dut.locked.value = 0
    await Timer(1, unit="ns")
    assert int(dut.q.value) == 0, "PLL unlock did not turn q off at once"
    await Timer(3, unit="ns")
    dut.locked.value = 1
    rise, high = await env.cause_profile("clock")
    assert rise is not None and rise <= 3 and high >= 3, (rise, high)
    res["unlock 4 ns"] = (rise, high)
    await ClockCycles(dut.clk, 3)
    # clk_dead pulse
    await FallingEdge(dut.clk)
    dut.clk_dead.value = 1
    await Timer(1, unit="ns")
    assert int(dut.q.value) == 0
    await Timer(1, unit="ns")
    dut.clk_dead.value = 0
    rise, high = await env.cause_profile("clock")
    assert rise is not None and rise <= 3 and high >= 3, (rise, high)
    res["clk_dead 2 ns"] = (rise, high)
    await ClockCycles(dut.clk, 3)
    # rst_n_in: q off, no cause
    await FallingEdge(dut.clk)
    dut.rst_n_in.value = 0
    await Timer(1, unit="ns")
    assert int(dut.q.value) == 0
    for _ in range(10):
        await RisingEdge(dut.clk)
        await ReadOnly()
        assert int(dut.q.value) == 0 and int(dut.pstage.value) == 0 and int(dut.clock.value) == 0
    await FallingEdge(dut.clk)
    dut.rst_n_in.value = 1
    await Timer(1, unit="ns")
    assert int(dut.q.value) == ALL
    # a pulse during rst: reported after it (counted at the edges where rst is low: the cause is
    # sampled mid-cycle, i.e. the value the fault latch takes at the next edge)
    dut.rst.value = 1
    await ClockCycles(dut.clk, 3)
    await _pulse(dut, "pwr_fault_n", 3)
    for _ in range(20):
        await RisingEdge(dut.clk)
        await ReadOnly()
        assert int(dut.q.value) == 0, "q on during reset after a pulse"
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    await Timer(1, unit="ns")
    high = int(dut.pstage.value)                  # seen by the edge that ends this cycle
    for _ in range(10):
        await FallingEdge(dut.clk)
        if int(dut.q.value):
            break
        high += int(dut.pstage.value)
    assert high >= 3, f"cause of a pulse during reset seen for {high} clocks after it"
    res["pulse during rst: cause clocks after release"] = high
    await ClockCycles(dut.clk, 4)
    # clock stopped: the gate needs no edge; the capture is reported when the clock runs again
    await FallingEdge(dut.clk)
    env.clk.stop()
    await Timer(50, unit="ns")
    assert int(dut.q.value) == ALL, "outputs frozen on (no kill yet) while the clock is stopped"
    await _pulse(dut, "pwr_fault_n", 5)
    await Timer(1, unit="ns")
    assert int(dut.q.value) == 0, "q not off with the clock stopped"
    await Timer(500, unit="ns")
    assert int(dut.q.value) == 0 and int(dut.pstage.value) == 0
    env.clk.start()
    rise, high = await env.cause_profile("pstage")
    assert rise is not None and rise <= 3 and high >= 3, (rise, high)
    res["pulse with the clock stopped"] = (rise, high)
    dut._log.info("corners (cause rise edge, cause high clocks): %s", res)


@cocotb.test()
async def random_pulses(dut):
    rng = random.Random(SEED)
    env = Env(dut)
    await env.start()
    dut._log.info("seed %d (EMPC_SEED)", SEED)
    state = {"pending": {"pstage": False, "clock": False}, "seen": {"pstage": 0, "clock": 0}, "edges": 0,
             "checks": 0, "causes": {"pstage": 0, "clock": 0}, "run": {"pstage": 0, "clock": 0},
             "short": 0, "stop": False}

    async def driver():
        while not state["stop"]:
            await RisingEdge(dut.clk)
            dut.d.value = rng.getrandbits(W)

    async def edges():
        # the reference: a kill event is pending until its cause has been seen at 2 edges (rst low)
        while not state["stop"]:
            await RisingEdge(dut.clk)
            await ReadOnly()
            for c in ("pstage", "clock"):
                v = int(getattr(dut, c).value)
                if v:
                    state["run"][c] += 1
                    if state["pending"][c]:
                        state["seen"][c] += 1
                        if state["seen"][c] >= 2:
                            state["pending"][c] = False
                elif state["run"][c]:
                    state["causes"][c] += 1
                    if state["run"][c] < 3:
                        state["short"] += 1
                    state["run"][c] = 0

    async def checker():
        while not state["stop"]:
            await Timer(0.5, unit="ns")
            await ReadOnly()
            kill_now = (not int(dut.pwr_fault_n.value)) or (not int(dut.locked.value)) or int(dut.clk_dead.value)
            pend = any(state["pending"].values())
            q, d = int(dut.q.value), int(dut.d.value)
            if kill_now or pend:
                assert q == 0, f"q = {q:#x} with a kill pending {state['pending']} (kill inputs {kill_now})"
            elif not int(dut.pstage.value) and not int(dut.clock.value):
                assert q == d, f"q = {q:#x}, d = {d:#x} without a kill"
            state["checks"] += 1

    cocotb.start_soon(driver())
    cocotb.start_soon(edges())
    cocotb.start_soon(checker())
    n_pulses = 300
    for k in range(n_pulses):
        await Timer((rng.choice([3, 7, 11, 23, 40, 90]) * 100 + rng.randrange(1000)) * 10, unit="ps")
        src = rng.choice(["pwr_fault_n", "locked", "clk_dead"])
        c = "pstage" if src == "pwr_fault_n" else "clock"
        width = round(0.3 + rng.random() * 40, 1)
        state["pending"][c] = True
        state["seen"][c] = 0
        await _pulse(dut, src, width, level=1 if src == "clk_dead" else 0)
        # wait until the cause has been taken over and the outputs are back
        for _ in range(30):
            await RisingEdge(dut.clk)
            await ReadOnly()
            if not state["pending"][c] and not int(dut.pstage.value) and not int(dut.clock.value):
                break
        assert not state["pending"][c], f"pulse {k} ({src}, {width} ns): cause never taken over"
    await ClockCycles(dut.clk, 5)
    state["stop"] = True
    await ClockCycles(dut.clk, 2)
    total = state["causes"]["pstage"] + state["causes"]["clock"]
    assert total >= n_pulses, f"{total} causes for {n_pulses} pulses"
    assert state["short"] == 0, f"{state['short']} causes shorter than 3 clocks"
    dut._log.info("random: %d pulses (0.3..40 ns), %d causes (each >= 3 clocks), %d checks every 0.5 ns",
                  n_pulses, total, state["checks"])


def test_out_kill():
    from runner import run
    run(toplevel="out_kill", test_module="test_out_kill", parameters={"W": W}, timescale=("1ns", "10ps"))
