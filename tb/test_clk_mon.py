"""cocotb tests of clk_mon (loss-of-clock monitor), Icarus.

The configuration-oscillator stand-in `osc_sim` is driven here with a clock asynchronous to
clk (periods that are not multiples of the fabric clock, random phase).

* healthy: fabric clock 100 MHz, oscillator at 25, 37, 50, 71 and 100 MHz (the nominal
  50 MHz CFGMCLK halved and doubled): `dead` stays 0 over 20 us each;
* stop: the fabric clock stops at a random phase: `dead` rises within the bound of the
  header, 2 + 1 + (2**LIMIT_BITS - 1) + 1 oscillator cycles after the last tgl edge (measured
  from the stop: <= 19 oscillator periods), for each oscillator frequency; it falls again
  within 2**(DIV_BITS-1) clocks + 4 oscillator cycles once the clock runs again;
* slow clock: a fabric clock below the detection threshold (2.5 MHz with a 50 MHz
  oscillator) is declared dead; one above it (40 MHz with 100 MHz) is not;
* disarmed: with rst held the monitor never declares the clock dead (start-up before the
  first PLL lock), also with the clock stopped.
Seed: EMPC_SEED (default 1618).
"""
from __future__ import annotations

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, Timer

SEED = int(os.environ.get("EMPC_SEED", "1618"))
DIV_BITS, LIMIT_BITS = 3, 4
BOUND_OSC = 2 + 1 + (2 ** LIMIT_BITS - 1) + 1          # osc cycles from the last tgl edge to dead


def ps(ns: float) -> int:
    return int(round(ns * 1000))


class Env:
    def __init__(self, dut, rng):
        self.dut, self.rng = dut, rng
        self.clk = None
        self.osc = None

    def start_clk(self, period_ps=10000):
        self.clk = Clock(self.dut.clk, period_ps, unit="ps")
        self.clk.start()

    def start_osc(self, mhz):
        period = 2 * round(1e6 / mhz / 2)
        if self.osc is not None:
            self.osc.stop()
        self.osc = Clock(self.dut.osc_sim, period, unit="ps")
        self.osc.start()
        return period

    async def watch_dead(self, t_ns):
        """max of dead over t_ns (sampled every 1 ns)"""
        seen = 0
        for _ in range(int(t_ns)):
            await Timer(1, unit="ns")
            seen |= int(self.dut.dead.value)
        return seen


@cocotb.test()
async def monitor(dut):
    rng = random.Random(SEED)
    env = Env(dut, rng)
    dut._log.info("seed %d (EMPC_SEED)", SEED)
    dut.rst.value = 1
    env.start_clk()
    env.start_osc(50)
    # disarmed: rst held, clock running and stopped
    await ClockCycles(dut.clk, 20)
    assert await env.watch_dead(500) == 0
    env.clk.stop()
    assert await env.watch_dead(2000) == 0, "dead while disarmed (rst held, start-up)"
    env.start_clk()
    await ClockCycles(dut.clk, 3)
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    res = {}
    for mhz in (25, 37, 50, 71, 100):
        period = env.start_osc(mhz)
        await Timer(ps(200 + rng.random() * 50), unit="ps")
        assert await env.watch_dead(20000) == 0, f"false trip with a healthy clock, osc {mhz} MHz"
        # stop the fabric clock at a random phase and time the trip
        await Timer(ps(rng.random() * 10), unit="ps")
        env.clk.stop()
        t0 = cocotb.utils.get_sim_time("ps")
        while not int(dut.dead.value):
            await Timer(100, unit="ps")
            assert cocotb.utils.get_sim_time("ps") - t0 < 40 * period, f"no trip at osc {mhz} MHz"
        t_trip = cocotb.utils.get_sim_time("ps") - t0
        assert t_trip <= BOUND_OSC * period, (mhz, t_trip, BOUND_OSC * period)
        await Timer(ps(1000), unit="ps")
        assert int(dut.dead.value) == 1
        env.start_clk()
        t1 = cocotb.utils.get_sim_time("ps")
        while int(dut.dead.value):
            await Timer(100, unit="ps")
            assert cocotb.utils.get_sim_time("ps") - t1 < 2000000, \
                f"dead did not clear: clk {dut.clk.value} div {dut.div.value} armed {dut.armed.value} cnt {dut.cnt.value}"
        t_clear = cocotb.utils.get_sim_time("ps") - t1
        assert t_clear <= 2 ** (DIV_BITS - 1) * 10000 + 4 * period, (mhz, t_clear)
        res[mhz] = (round(t_trip / 1000, 1), round(t_trip / period, 1), round(t_clear / 1000, 1))
    dut._log.info("trip after clock stop (ns, osc cycles; bound %d) and clear after restart (ns) per osc MHz: %s",
                  BOUND_OSC, res)
    # slow fabric clocks: below / above the threshold f_clk > 2**(DIV_BITS-1) f_osc / (2**LIMIT_BITS - 3)
    env.clk.stop()
    env.start_clk(400000)                       # 2.5 MHz
    env.start_osc(50)
    assert await env.watch_dead(5000) == 1, "a 2.5 MHz fabric clock not declared dead (osc 50 MHz)"
    env.clk.stop()
    env.start_clk(25000)                        # 40 MHz
    env.start_osc(100)
    await Timer(500, unit="ns")
    assert await env.watch_dead(10000) == 0, "a 40 MHz fabric clock declared dead (osc 100 MHz)"
    dut._log.info("slow clock: 2.5 MHz declared dead (osc 50 MHz), 40 MHz not (osc 100 MHz)")


def test_clk_mon():
    from runner import run
    run(toplevel="clk_mon", test_module="test_clk_mon", timescale=("1ns", "1ps"))
