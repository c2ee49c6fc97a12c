"""cocotb tests of fault_ctrl against empc.rtlmodel.fault_ctrl.

* corners (checked directly, without the model): a one-clock masked cause
  pulse trips in the same clock and stays tripped; a masked-off cause is
  recorded but does not trip, and trips once its mask bit is set; clear while
  the cause is active keeps the bit (and trip), clear after it has gone
  clears it; reset state;
* random: random level/pulse cause patterns, random mask changes and clear
  pulses, trip (combinational, sampled 1 ns after the inputs change) and
  fault_latched compared with the model every clock, plus the invariant
  trip == |((latched | cause) & mask).
"""
from __future__ import annotations

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, Timer

from empc.rtlmodel.fault_ctrl import FaultCtrl

DEFAULT_SEED = 5150
NCAUSE = 7


class Env:
    def __init__(self, dut):
        self.dut = dut
        self.seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
        self.rng = random.Random(self.seed)
        self.model = FaultCtrl(NCAUSE)
        self.n = 0
        dut._log.info("NCAUSE %d seed %d (EMPC_SEED)", NCAUSE, self.seed)

    async def start(self):
        d = self.dut
        Clock(d.clk, 10, unit="ns").start()
        d.rst.value = 1
        d.cause_in.value = 0
        d.mask.value = 0
        d.clear.value = 0
        for _ in range(3):
            await FallingEdge(d.clk)
        d.rst.value = 0
        self.model.reset()
        assert int(d.fault_latched.value) == 0, "fault_latched after reset"

    async def cycle(self, cause, mask, clear=0):
        """Apply inputs after a falling edge, check trip in the same clock, then latched after the edge."""
        d = self.dut
        d.cause_in.value = cause
        d.mask.value = mask
        d.clear.value = clear
        await Timer(1, unit="ns")
        trip = int(d.trip.value)
        exp = self.model.step(cause, mask, bool(clear))
        latched_before = int(d.fault_latched.value)
        assert trip == int(bool((latched_before | cause) & mask)), "trip invariant"
        assert trip == int(exp), f"clock {self.n}: trip={trip} model={int(exp)} cause={cause:07b} mask={mask:07b}"
        await FallingEdge(d.clk)
        self.n += 1
        lat = int(d.fault_latched.value)
        assert lat == self.model.latched, f"clock {self.n}: latched={lat:07b} model={self.model.latched:07b}"
        return trip, lat


@cocotb.test()
async def corners(dut):
    env = Env(dut)
    await env.start()
    allm = (1 << NCAUSE) - 1
    checks = 0
    for bit in range(NCAUSE):
        b = 1 << bit
        # masked cause: one-clock pulse trips in the same clock, then stays
        trip, lat = await env.cycle(b, allm)
        assert trip == 1 and lat == b, f"bit {bit}: pulse must trip at once and latch"
        for _ in range(3):
            trip, lat = await env.cycle(0, allm)
            assert trip == 1 and lat == b, f"bit {bit}: trip must stay until clear"
        trip, lat = await env.cycle(0, allm, clear=1)
        assert trip == 1, "trip still high in the clear clock (latched bit)"
        assert lat == 0, f"bit {bit}: clear with the cause gone must clear"
        trip, lat = await env.cycle(0, allm)
        assert trip == 0
        # level cause: clear while active keeps the bit
        trip, lat = await env.cycle(b, allm)
        trip, lat = await env.cycle(b, allm, clear=1)
        assert trip == 1 and lat == b, f"bit {bit}: clear while the cause is active must keep it"
        trip, lat = await env.cycle(0, allm)
        assert trip == 1 and lat == b
        trip, lat = await env.cycle(0, allm, clear=1)
        assert lat == 0
        # masked off: recorded, no trip; unmasking trips
        trip, lat = await env.cycle(b, allm & ~b)
        assert trip == 0 and lat == b, f"bit {bit}: masked-off cause must be recorded without trip"
        trip, lat = await env.cycle(0, allm & ~b)
        assert trip == 0
        trip, lat = await env.cycle(0, b)
        assert trip == 1, f"bit {bit}: setting the mask bit of a latched cause must trip"
        trip, lat = await env.cycle(0, 0, clear=1)
        assert trip == 0 and lat == 0
        checks += 8
    dut._log.info("corners: %d checks over %d causes (%d clocks)", checks, NCAUSE, env.n)


@cocotb.test()
async def random_vs_model(dut):
    env = Env(dut)
    await env.start()
    rng = env.rng
    level = 0
    mask = rng.getrandbits(NCAUSE)
    n_cycles = 20000
    n_trip = n_clear = n_clear_active = 0
    while env.n < n_cycles:
        r = rng.random()
        if r < 0.02:
            level ^= 1 << rng.randrange(NCAUSE)          # level cause toggles
        pulse = (1 << rng.randrange(NCAUSE)) if rng.random() < 0.03 else 0
        if rng.random() < 0.01:
            mask = rng.getrandbits(NCAUSE)
        clear = 1 if rng.random() < 0.05 else 0
        cause = level | pulse
        if clear and (cause & env.model.latched):
            n_clear_active += 1
        n_clear += clear
        trip, _ = await env.cycle(cause, mask, clear)
        n_trip += trip
    dut._log.info("random: %d clocks bit-exact vs model (trip in %d, %d clears, %d with an active cause; seed %d)",
                  env.n, n_trip, n_clear, n_clear_active, env.seed)
    assert n_trip > 0 and n_clear_active > 0


def test_fault_ctrl():
    from runner import run
    run(toplevel="fault_ctrl", test_module="test_fault_ctrl", parameters={"NCAUSE": NCAUSE})
