"""cocotb tests of watchdog against empc.rtlmodel.watchdog.

* corners (direct): expiry exactly one clock after the timeout-th tick for
  timeout 1, 2, 5 and 2**TW-1 (largest count); kick clears at once and
  restarts the interval; kick in the same clock as a tick; timeout = 0
  disables (and clears); lowering timeout below the count expires without a
  tick; raising it keeps expired;
* random: random ticks, kicks and timeout changes compared with the model
  every clock.
"""
from __future__ import annotations

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from empc.rtlmodel.watchdog import Watchdog

DEFAULT_SEED = 4711
TW = 8          # small width so saturation is reachable; the top uses 16


class Env:
    def __init__(self, dut):
        self.dut = dut
        self.seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
        self.rng = random.Random(self.seed)
        self.model = Watchdog(TW)
        self.n = 0
        dut._log.info("TW %d seed %d (EMPC_SEED)", TW, self.seed)

    async def start(self):
        d = self.dut
        Clock(d.clk, 10, unit="ns").start()
        d.rst.value = 1
        d.tick.value = 0
        d.kick.value = 0
        d.timeout.value = 0
        for _ in range(3):
            await FallingEdge(d.clk)
        d.rst.value = 0
        self.model.reset()
        assert int(d.expired.value) == 0

    async def cycle(self, tick=0, kick=0, timeout=0):
        d = self.dut
        d.tick.value = tick
        d.kick.value = kick
        d.timeout.value = timeout
        exp = self.model.step(bool(tick), bool(kick), timeout)
        await FallingEdge(d.clk)
        self.n += 1
        e = int(d.expired.value)
        assert e == int(exp), f"clock {self.n}: expired={e} model={int(exp)} (tick={tick} kick={kick} timeout={timeout})"
        return e


@cocotb.test()
async def corners(dut):
    env = Env(dut)
    await env.start()
    checks = 0
    for to in (1, 2, 5, (1 << TW) - 1):
        await env.cycle(kick=1, timeout=to)
        for k in range(1, to + 1):
            assert await env.cycle(tick=1, timeout=to) == (1 if k == to else 0), f"timeout {to}: tick {k}"
            for _ in range(2):                      # idle clocks between ticks
                assert await env.cycle(timeout=to) == (1 if k == to else 0)
        for _ in range(3):                          # stays expired while ticks go on
            assert await env.cycle(tick=1, timeout=to) == 1
        assert await env.cycle(kick=1, timeout=to) == 0, "kick clears at once"
        if to > 1:
            assert await env.cycle(tick=1, timeout=to) == 0, "kick restarts the interval"
        checks += 1
    # kick and tick in the same clock: kick wins
    await env.cycle(kick=1, timeout=2)
    await env.cycle(tick=1, timeout=2)
    assert await env.cycle(tick=1, kick=1, timeout=2) == 0
    assert await env.cycle(tick=1, timeout=2) == 0
    assert await env.cycle(tick=1, timeout=2) == 1
    # timeout 0 disables and clears; ticks while disabled do not count
    assert await env.cycle(timeout=0) == 0
    for _ in range(5):
        assert await env.cycle(tick=1, timeout=0) == 0
    assert await env.cycle(tick=1, timeout=3) == 0
    # lowering the timeout below the count expires without a tick
    await env.cycle(timeout=3)
    assert await env.cycle(timeout=1) == 1
    # raising it keeps expired until kick
    assert await env.cycle(timeout=200) == 1
    assert await env.cycle(kick=1, timeout=200) == 0
    checks += 4
    dut._log.info("corners: %d scenario checks (%d clocks)", checks, env.n)


@cocotb.test()
async def random_vs_model(dut):
    env = Env(dut)
    await env.start()
    rng = env.rng
    timeout = 5
    n_exp = n_kick = 0
    while env.n < 20000:
        if rng.random() < 0.005:
            timeout = rng.choice([0, 1, 2, 3, 7, 20, 100, (1 << TW) - 1, rng.randrange(1 << TW)])
        tick = 1 if rng.random() < 0.3 else 0
        kick = 1 if rng.random() < 0.02 else 0
        n_kick += kick
        n_exp += await env.cycle(tick, kick, timeout)
    dut._log.info("random: %d clocks bit-exact vs model (expired in %d clocks, %d kicks, seed %d)",
                  env.n, n_exp, n_kick, env.seed)
    assert n_exp > 0


def test_watchdog():
    from runner import run
    run(toplevel="watchdog", test_module="test_watchdog", parameters={"TW": TW})
