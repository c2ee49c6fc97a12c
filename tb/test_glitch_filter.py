"""cocotb tests of glitch_filter against empc.rtlmodel.glitch_filter.

* corners: for several filter lengths L (parameter default via len=0 and
  run-time len values) a pulse of L-1 clocks never reaches q, a pulse of L
  clocks appears exactly L clocks later and lasts exactly L clocks (checked
  directly, independent of the model), on every bit and both polarities;
* random: runs of random length around L, run-time len changes and load
  pulses, compared bit-exact with the model every clock;
* reset value and load;
* FIXED = 1 (LFSR counters, len ignored: the DUT gets the same run-time len values, the model len = 0),
  at L = 5, 1, 8 (irc_decoder's) and 1000 (hall_decoder's): the same checks against the binary-counter model.
"""
from __future__ import annotations

import json
import os
import random

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from empc.rtlmodel.glitch_filter import GlitchFilter

DEFAULT_SEED = 1234
PARAMS = dict(WIDTH=3, FILTER_LEN=5, LEN_W=4, RESET_VALUE=0b101)


class Env:
    def __init__(self, dut):
        self.dut = dut
        self.p = json.loads(os.environ.get("TB_PARAMS", json.dumps(PARAMS)))
        self.seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
        self.rng = random.Random(self.seed)
        self.fixed = bool(self.p.get("FIXED", 0))
        self.model = GlitchFilter(self.p["WIDTH"], self.p["FILTER_LEN"], self.p["LEN_W"], self.p["RESET_VALUE"])
        self.n = 0
        dut._log.info("params %s seed %d (EMPC_SEED)", self.p, self.seed)

    async def start(self):
        d = self.dut
        Clock(d.clk, 10, unit="ns").start()
        d.rst.value = 1
        d.load.value = 0
        d.len.value = 0
        d.d.value = 0
        for _ in range(3):
            await FallingEdge(d.clk)
        d.rst.value = 0
        self.model.reset()
        assert int(d.q.value) == self.p["RESET_VALUE"], "q after reset"

    async def cycle(self, din, length=0, load=0):
        d = self.dut
        d.d.value = din
        d.len.value = length
        d.load.value = load
        self.model.step(din, 0 if self.fixed else length, bool(load))
        await FallingEdge(d.clk)
        self.n += 1
        q = int(d.q.value)
        assert q == self.model.q, f"cycle {self.n}: q={q:b} model={self.model.q:b} (d={din:b} len={length})"
        return q


@cocotb.test()
async def corners(dut):
    env = Env(dut)
    await env.start()
    w = env.p["WIDTH"]
    mask = (1 << w) - 1
    lens = [(0, env.p["FILTER_LEN"]), (1, 1), (2, 2), (7, 7), ((1 << env.p["LEN_W"]) - 1, (1 << env.p["LEN_W"]) - 1)]
    if env.fixed:           # len ignored: every run-time value gives FILTER_LEN
        lens = [(0, env.p["FILTER_LEN"]), (1, env.p["FILTER_LEN"]), ((1 << env.p["LEN_W"]) - 1, env.p["FILTER_LEN"])]
        if env.p["FILTER_LEN"] > 64:
            lens = lens[:2]
    checks = 0
    for length, L in lens:
        for base in (0, mask):
            # settle the output on `base`
            await env.cycle(base, length, load=1)
            for _ in range(2):
                await env.cycle(base, length)
            assert int(dut.q.value) == base
            for bit in range(w):
                for width in (L - 1, L, L + 1):
                    if width < 1:
                        continue
                    pulse = base ^ (1 << bit)
                    trace = []
                    for _ in range(width):
                        trace.append(await env.cycle(pulse, length))
                    for _ in range(2 * L + 2):
                        trace.append(await env.cycle(base, length))
                    # trace[k] = q after the (k+1)-th edge; the input changed before edge 1
                    changed = [k for k, q in enumerate(trace) if q != base]
                    if width < L:
                        assert not changed, f"L={L}: pulse of {width} clocks reached q on bit {bit}"
                    else:
                        assert changed == list(range(L - 1, L - 1 + width)), (
                            f"L={L}: pulse of {width} clocks on bit {bit} gave q pulse at {changed}, "
                            f"expected clocks {L}..{L + width - 1}")
                        assert all(trace[k] == pulse for k in changed)
                    checks += 1
    dut._log.info("corners: %d pulse checks (L-1, L, L+1 per bit, polarity and length %s), %d clocks",
                  checks, [L for _, L in lens], env.n)


@cocotb.test()
async def random_vs_model(dut):
    env = Env(dut)
    await env.start()
    w = env.p["WIDTH"]
    rng = env.rng
    length = 0
    din = 0
    n_cycles = 12000
    n_load = 0
    while env.n < n_cycles:
        if rng.random() < 0.01:
            length = rng.choice([0, 0, 1, 2, 3, 4, 5, 6, 9, 15])
        L = env.p["FILTER_LEN"] if env.fixed else (length or env.p["FILTER_LEN"])
        # a run of one value: glitch-ish or long
        run = rng.choice([1, max(1, L - 1), L, L + 1, rng.randint(1, 3 * L + 2)])
        din = rng.getrandbits(w) if rng.random() < 0.5 else din ^ (1 << rng.randrange(w))
        for k in range(run):
            load = 1 if rng.random() < 0.002 else 0
            n_load += load
            await env.cycle(din, length, load)
    dut._log.info("random: %d clocks bit-exact vs model (%d loads, seed %d)", env.n, n_load, env.seed)


@pytest.mark.parametrize("fixed", [None, (5, 4), (1, 4), (8, 8), (1000, 10)])
def test_glitch_filter(fixed):
    from runner import run
    params = dict(PARAMS) if fixed is None else dict(PARAMS, FILTER_LEN=fixed[0], LEN_W=fixed[1], FIXED=1)
    run(toplevel="glitch_filter", test_module="test_glitch_filter", parameters=params,
        name=None if fixed is None else f"test_glitch_filter_fixed_{fixed[0]}",
        extra_env={"TB_PARAMS": json.dumps(params)})
