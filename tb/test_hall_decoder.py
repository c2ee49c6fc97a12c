"""cocotb tests of hall_decoder against empc.rtlmodel.hall_decoder (and against the stimulus).

All outputs are compared bit-exact with the cycle model every clock.  The
stimulus knows the true sector, so independently of the model the test checks
after every segment: sector, valid, the number of change pulses (one per
change of legal sector, none for the first), fault pulses (one per entry into
000/111) and the sticky fault (held until fault_clear, not clearable while the
code is illegal).  Glitches shorter than DEBOUNCE on single HALL lines never
reach the outputs.  Two builds: the default table and a mirrored table (the
SECTOR_MAP parameter).
"""
from __future__ import annotations

import json
import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from empc.rtlmodel.hall_decoder import DEFAULT_MAP, DEFAULT_SEQUENCE, HallDecoder, map_to_param

DEFAULT_SEED = 777
MIRROR_MAP = tuple([0] + [0] * 7)
_m = [0] * 8
for _s in range(1, 7):
    _m[DEFAULT_SEQUENCE[6 - _s]] = _s     # sector s <- code of default sector 7-s
MIRROR_MAP = tuple(_m)


class Env:
    def __init__(self, dut):
        self.dut = dut
        cfg = json.loads(os.environ["TB_PARAMS"])
        self.deb = cfg["DEBOUNCE"]
        self.table = tuple(cfg["TABLE"])
        self.code_of = {s: c for c, s in enumerate(self.table) if 1 <= s <= 6}
        self.seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
        self.rng = random.Random(self.seed)
        self.model = HallDecoder(self.deb, self.table)
        self.code = self.code_of[1]
        self.last_sector = 0          # last legal sector applied
        self.exp_change = self.exp_fault_pulse = 0
        self.exp_fault = 0
        self.in_fault = False
        self.n = self.n_change = self.n_fault_pulse = self.n_checks = self.n_glitch = 0
        dut._log.info("DEBOUNCE %d table %s seed %d (EMPC_SEED)", self.deb, self.table, self.seed)

    async def start(self, code):
        d = self.dut
        Clock(d.clk, 10, unit="ns").start()
        d.hall.value = code
        d.fault_clear.value = 0
        d.rst.value = 1
        for _ in range(3):
            await FallingEdge(d.clk)
        d.rst.value = 0
        self.model.reset()
        self.set_code(code)

    def set_code(self, code):
        self.code = code
        s = self.table[code]
        if 1 <= s <= 6:
            if self.last_sector and s != self.last_sector:
                self.exp_change += 1
            self.last_sector = s
            self.in_fault = False
        else:
            if not self.in_fault:
                self.exp_fault_pulse += 1
            self.in_fault = True
            self.exp_fault = 1

    async def cycle(self, code=None, fault_clear=0):
        d = self.dut
        code = self.code if code is None else code
        d.hall.value = code
        d.fault_clear.value = fault_clear
        self.model.step(code, fault_clear)
        await FallingEdge(d.clk)
        self.n += 1
        for k, v in self.model.outputs().items():
            got = int(getattr(d, k).value)
            assert got == v, f"cycle {self.n}: {k}={got} model={v} (hall={code:03b})"
        self.n_change += int(d.change.value)
        self.n_fault_pulse += int(d.fault_pulse.value)

    async def dwell(self, n, glitch=False):
        if glitch and self.deb > 1 and n >= 3 * self.deb:
            g = self.rng.randint(1, self.deb - 1)
            t0 = self.rng.randint(self.deb, n - self.deb - g)
            gc = self.code ^ (1 << self.rng.randrange(3))
            for t in range(n):
                await self.cycle(gc if t0 <= t < t0 + g else None)
            self.n_glitch += 1
        else:
            for _ in range(n):
                await self.cycle()

    async def settle_check(self, what):
        await self.dwell(self.deb + 4)
        d = self.dut
        s = self.table[self.code]
        legal = 1 <= s <= 6
        assert int(d.valid.value) == int(legal), f"{what}: valid"
        if legal:
            assert int(d.sector.value) == s, f"{what}: sector {int(d.sector.value)} expected {s}"
        assert int(d.code.value) == self.code
        assert self.n_change == self.exp_change, f"{what}: {self.n_change} change pulses, expected {self.exp_change}"
        assert self.n_fault_pulse == self.exp_fault_pulse, f"{what}: fault pulses {self.n_fault_pulse}/{self.exp_fault_pulse}"
        assert int(d.fault.value) == self.exp_fault, f"{what}: fault {int(d.fault.value)} expected {self.exp_fault}"
        self.n_checks += 1


@cocotb.test()
async def rotation_sequence(dut):
    """Forward then backward through all sectors at the debounce limit: mapping and change pulses."""
    env = Env(dut)
    await env.start(env.code_of[1])
    await env.dwell(env.deb + 6)
    assert int(dut.ready.value) == 1 and int(dut.valid.value) == 1 and int(dut.sector.value) == 1
    assert env.n_change == 0, "no change pulse for the first sector"
    seq = list(range(2, 7)) + [1, 2] + list(range(1, 7))[::-1]
    seen = []
    for s in seq:
        env.set_code(env.code_of[s])
        await env.dwell(env.deb + 4)        # pin -> sector latency is 2 + DEBOUNCE + 1
        seen.append(int(dut.sector.value))
    assert seen == seq, f"sectors {seen} expected {seq}"
    # and at the debounce limit (each code held exactly DEBOUNCE clocks)
    for s in seq:
        env.set_code(env.code_of[s])
        await env.dwell(env.deb)
    await env.settle_check("rotation")
    dut._log.info("rotation: sectors %s, %d change pulses, %d clocks", seen, env.n_change, env.n)


@cocotb.test()
async def startup_illegal(dut):
    """Illegal code at start-up (disconnected sensor 111): fault, no valid; then recovery."""
    env = Env(dut)
    await env.start(0b111)
    await env.settle_check("startup 111")
    assert int(dut.sector.value) == 0 and int(dut.valid.value) == 0
    await env.cycle(fault_clear=1)           # still illegal: fault stays
    await env.settle_check("clear while illegal")
    env.set_code(env.code_of[4])
    await env.settle_check("recover")
    await env.cycle(fault_clear=1)
    env.exp_fault = 0
    await env.settle_check("cleared")
    dut._log.info("startup illegal: %d clocks", env.n)


@cocotb.test()
async def random_hall(dut):
    """Random sector walk with jumps, glitches, illegal codes 000/111 and fault clears."""
    env = Env(dut)
    rng = env.rng
    s = rng.randint(1, 6)
    await env.start(env.code_of[s])
    await env.settle_check("start")
    while env.n < 15000:
        r = rng.random()
        if r < 0.1:
            env.set_code(rng.choice((0, 7)))
            await env.dwell(rng.randint(env.deb, 4 * env.deb))
        elif r < 0.15:
            await env.settle_check("random")
            await env.cycle(fault_clear=1)
            if not env.in_fault:
                env.exp_fault = 0
        elif r < 0.2:
            s = rng.randint(1, 6)          # implausible jump
            env.set_code(env.code_of[s])
            await env.dwell(rng.randint(env.deb, 3 * env.deb))
        else:
            step = rng.choice((1, -1))
            for _ in range(rng.randint(1, 12)):
                s = (s - 1 + step) % 6 + 1
                env.set_code(env.code_of[s])
                await env.dwell(rng.choice([env.deb, env.deb + 1, rng.randint(env.deb, 6 * env.deb)]),
                                glitch=rng.random() < 0.4)
    await env.settle_check("end")
    dut._log.info("random: %d clocks bit-exact vs model, %d settle checks, %d change / %d fault pulses, "
                  "%d glitches (seed %d)", env.n, env.n_checks, env.n_change, env.n_fault_pulse, env.n_glitch,
                  env.seed)


def _run(table, name):
    from runner import run
    deb = 6
    params = dict(DEBOUNCE=deb, SECTOR_MAP=map_to_param(table))
    run(toplevel="hall_decoder", test_module="test_hall_decoder", parameters=params, name=name,
        extra_env={"TB_PARAMS": json.dumps(dict(DEBOUNCE=deb, TABLE=list(table)))})


def test_hall_decoder():
    _run(DEFAULT_MAP, "test_hall_decoder")


def test_hall_decoder_mirrored_map():
    _run(MIRROR_MAP, "test_hall_decoder_mirror")
