"""cocotb tests of out_route with the generated global register block (tb/hdl/out_route_tb.v), Icarus.

Reference: regblock.Model of rtl/global_regs.v (stores and guards OUT_SEL0/1, ADC_SEL0/1, IN_SEL)
plus gen/empc/rtlmodel/out_route.py.  Every clock, every output of the harness is compared with
the models: the pins, mapped, bad_sel, wr_refused and reg_rdata after the edge, the input
multiplexers (ax_miso, ax_irc_*, ax_hall) before it.

* random (NAXES = 4 and 1): TB_CLOCKS clocks (default 20000) of random pwm_center pairs, trips,
  board inputs, resets, reads, and routing writes (legal maps, codes 13..15, random words) with
  bridges_live random in runs; seed EMPC_SEED (default 1601), printed.
* corners, each also checked against the models every clock:
  - reset: pins off, mapped 0 until one scan, then today's pinout (output 3 a + p = axis a,
    phase p) and every register at its reset value;
  - a write of every routing register while bridges_live: refused (wr_refused), read-back and
    pins unchanged, mapped not restarted;
  - a word with seven legal codes and one of 13..15 (bridges off): refused as a whole;
  - two (and three) outputs selecting the same phase: all follow the pair, hi and lo together;
  - a trip of one axis: its outputs off at the next edge, the other axes' outputs unchanged;
  - NAXES < 4: a code naming a missing axis is accepted by the register block (the map is the
    board's) but the output stays off (like code 0);
  - a build with fewer board lines (NAXES = 2, 5 IRC, 3 HALL, 6 ADC): input selects beyond them
    read MISO 1 / IRC 0 / HALL 000 and set ROUTE_STATUS.bad_sel (random test).
"""
from __future__ import annotations

import os
import random
import sys
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge, Timer

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "gen"))
from empc import regblock, regmap  # noqa: E402
from empc.rtlmodel.out_route import OutRoute, Selects  # noqa: E402

DEFAULT_SEED = 1601
GLOBAL = next(b for b in regmap.BLOCKS if b.module == "global_regs")
REG = {r.name: r for r in GLOBAL.regs}
ROUTE_RW = ("OUT_SEL0", "OUT_SEL1", "ADC_SEL0", "ADC_SEL1", "IN_SEL")
NOUT, PH = regmap.ROUTE_OUTPUTS, regmap.ROUTE_PHASES
# board lines of the harness (NENC, NHALL, NADC): LX_RoCoN's, or fewer to exercise bad_sel
LINES = tuple(int(x) for x in os.environ.get("TB_LINES", f"{regmap.ROUTE_ENC},{regmap.ROUTE_HALL},"
                                                        f"{regmap.ROUTE_ADC}").split(","))


def field_word(reg: str, values: dict) -> int:
    """Register word from {field name: value}; unnamed fields at their reset value."""
    r = REG[reg]
    w = 0
    for f in r.fields:
        v = values.get(f.name, (r.reset_int() >> f.lsb) & ((1 << f.width) - 1))
        w |= (v & ((1 << f.width) - 1)) << f.lsb
    return w


def out_words(codes: list) -> tuple:
    """OUT_SEL0/1 words for the 16 output codes."""
    per = regmap.ROUTE_PER_WORD
    return tuple(field_word(f"OUT_SEL{w}", {f"out{k}": codes[k] for k in range(w * per, (w + 1) * per)})
                 for w in range(NOUT // per))


class Env:
    """Drives the harness and keeps both models in step; every clock is checked."""

    def __init__(self, dut, naxes: int, seed: int):
        self.dut = dut
        self.naxes = naxes
        self.rng = random.Random(seed)
        self.regs = regblock.Model(GLOBAL, {})
        self.nenc, self.nhall, self.nadc = LINES
        self.route = OutRoute(naxes, nenc=self.nenc, nhall=self.nhall, nadc=self.nadc)
        self.ins = {p[1]: 0 for p in self.regs.ports if p[0] == "input" and p[1] != "clk"}
        self.ins["rst"] = 1
        self.hw = dict(hi=0, lo=0, trip=0, miso=0, irc_a=0, irc_b=0, irc_idx=0, irc_mark=0, hall=0)
        self.clocks = 0
        self.stats = dict(refused=0, accepted=0, trips=0, pins_on=0, bad=0)

    def selects(self) -> Selects:
        s = self.regs.state
        words = {}
        for name in ROUTE_RW:
            r = REG[name]
            words[name] = sum(s[r.part_port(f)] << f.lsb for f in r.fields)
        return Selects.from_regs(words, self.naxes)

    def status_ins(self) -> None:
        m = self.route
        for a in range(regmap.ROUTE_AXES):
            self.ins[f"route_status_mapped{a}"] = (m.mapped >> (PH * a)) & 0b111 if a < self.naxes else 0
        self.ins["route_status_bad_sel"] = m.bad_sel

    async def start(self):
        cocotb.start_soon(Clock(self.dut.clk, 10, unit="ns").start())
        await self.clock(rst=1)
        await self.clock(rst=1)

    async def clock(self, **kw) -> None:
        """One clock: apply the inputs (kw: rst, reg_wr, reg_rd, reg_addr, reg_wdata, bridges_live and
        the harness' hi, lo, trip, miso, irc_*, hall; absent keys: strobes 0, the rest unchanged),
        check the combinational outputs, take the edge in the models, check the registered ones."""
        d = self.dut
        for k in ("reg_wr", "reg_rd", "rst"):
            self.ins[k] = 0
        for k, v in kw.items():
            if k in self.hw:
                self.hw[k] = v
            else:
                self.ins[k] = v
        self.ins["route_locked"] = self.ins["bridges_live"]     # the harness: a build that routes
        self.ins["caps_route"] = 1
        self.status_ins()
        for k in ("rst", "reg_wr", "reg_rd", "reg_addr", "reg_wdata", "bridges_live"):
            getattr(d, k).value = self.ins[k]
        for k, v in self.hw.items():
            getattr(d, k).value = v
        await Timer(1, unit="ns")
        sel = self.selects()
        exp = self.route.comb(sel, self.hw["miso"], tuple(self.hw[k] for k in ("irc_a", "irc_b", "irc_idx",
                                                                              "irc_mark")), self.hw["hall"])
        for k, v in exp.items():
            got = int(getattr(d, k).value)
            assert got == v, f"clock {self.clocks}: {k} = {got:#x}, model {v:#x}; selects {sel}"
        osel_wr = self.regs.state["out_sel0_wr"] | self.regs.state["out_sel1_wr"]
        self.route.step(bool(self.ins["rst"]), sel, bool(osel_wr), self.hw["hi"], self.hw["lo"], self.hw["trip"])
        self.regs.clock(dict(self.ins))
        await RisingEdge(d.clk)
        await ReadOnly()
        self.clocks += 1
        m, s = self.route, self.regs.state
        want = dict(pin_hi=m.pin_hi, pin_lo=m.pin_lo, mapped=m.mapped, bad_sel=m.bad_sel,
                    wr_refused=s["wr_refused"], reg_rdata=self.regs.q)
        for k, v in want.items():
            got = int(getattr(d, k).value)
            assert got == v, (f"clock {self.clocks}: {k} = {got:#x}, model {v:#x}; inputs {self.ins} {self.hw}; "
                              f"selects {sel}")
        if self.ins["reg_wr"] and not self.ins["rst"] and self.ins["reg_addr"] in (REG[n].offset for n in ROUTE_RW):
            self.stats["refused" if s["wr_refused"] else "accepted"] += 1
        self.stats["pins_on"] += bin(m.pin_hi | m.pin_lo).count("1")
        self.stats["bad"] += m.bad_sel
        await FallingEdge(d.clk)

    async def idle(self, n: int, **kw) -> None:
        for _ in range(n):
            await self.clock(**kw)

    async def write(self, name: str, value: int, live: int = 0) -> bool:
        """Write a register; True if accepted (read back through the bus)."""
        before = await self.read(name)
        await self.clock(reg_wr=1, reg_addr=REG[name].offset, reg_wdata=value, bridges_live=live)
        refused = self.regs.state["wr_refused"]
        after = await self.read(name)
        if refused:
            assert after == before, f"{name}: refused write changed the register {before:#x} -> {after:#x}"
        return not refused

    async def read(self, name: str) -> int:
        await self.clock(reg_rd=1, reg_addr=REG[name].offset)
        return int(self.dut.reg_rdata.value)

    def random_inputs(self) -> dict:
        r = self.rng
        np_ = PH * self.naxes
        ne = self.nenc
        return dict(hi=r.getrandbits(np_), lo=r.getrandbits(np_),
                    trip=r.getrandbits(self.naxes) if r.random() < 0.05 else 0, miso=r.getrandbits(self.nadc),
                    irc_a=r.getrandbits(ne), irc_b=r.getrandbits(ne), irc_idx=r.getrandbits(ne),
                    irc_mark=r.getrandbits(ne), hall=r.getrandbits(PH * self.nhall))


def today_pinout(naxes: int) -> int:
    return (1 << (PH * naxes)) - 1


@cocotb.test()
async def reset_state(dut):
    naxes = int(os.environ["TB_NAXES"])
    env = Env(dut, naxes, 0)
    await env.start()
    assert int(dut.pin_hi.value) == 0 and int(dut.pin_lo.value) == 0 and int(dut.mapped.value) == 0
    await env.idle(NOUT + 1, hi=today_pinout(naxes), lo=today_pinout(naxes))
    assert env.route.mapped == today_pinout(naxes), "reset map is not today's pinout"
    # today's pinout: output 3 a + p follows (a, p) for the axes of the build, the rest off
    assert int(dut.pin_hi.value) == today_pinout(naxes) and int(dut.pin_lo.value) == today_pinout(naxes)
    for name in ROUTE_RW:
        assert await env.read(name) == REG[name].reset_int(), name
    st = await env.read("ROUTE_STATUS")
    assert st & 0xFFFF == sum(0b111 << (regmap.ROUTE_NIB * a) for a in range(naxes)) and not st >> 16
    # a reset in the middle of a switching map: pins off at the next edge, the scan restarts
    await env.clock(rst=1)
    assert int(dut.pin_hi.value) == 0 and int(dut.mapped.value) == 0
    dut._log.info("reset: pins off, mapped after %d clocks, registers at today's pinout (NAXES %d)", NOUT, naxes)


@cocotb.test()
async def refused_writes(dut):
    naxes = int(os.environ["TB_NAXES"])
    env = Env(dut, naxes, 1)
    await env.start()
    np_ = PH * naxes
    await env.idle(NOUT + 2, hi=today_pinout(naxes), lo=0)
    # every routing register: a different value while a bridge is live is refused, nothing changes
    for name in ROUTE_RW:
        r = REG[name]
        new = field_word(name, {f.name: 0 for f in r.fields})   # "everything off / channel 0"
        assert not await env.write(name, new, live=1), f"{name} accepted while bridges_live"
        assert env.route.mapped == today_pinout(naxes)
        await env.idle(NOUT + 2, bridges_live=1)
        assert env.route.mapped == today_pinout(naxes), "mapped changed after a refused write"
        assert int(dut.pin_hi.value) == today_pinout(naxes)
    # nothing half-written: seven legal codes and one of 13..15 (bridges off)
    for bad in range(regmap.ROUTE_AXES * PH + 1, 1 << regmap.ROUTE_OUT_W):
        for pos in (0, 7):
            codes = [0] * NOUT
            codes[pos] = bad
            assert not await env.write("OUT_SEL0", out_words(codes)[0]), f"code {bad} accepted"
            assert int(dut.pin_hi.value) == today_pinout(naxes)
    # legal: all off; then back
    w0, w1 = out_words([0] * NOUT)
    assert await env.write("OUT_SEL0", w0) and await env.write("OUT_SEL1", w1)
    await env.idle(2)
    assert int(dut.pin_hi.value) == 0 and env.route.mapped == 0
    await env.idle(NOUT + 1)
    assert env.route.mapped == 0
    dut._log.info("refused: 5 registers while live, %d words with one illegal code; %d clocks bit-exact (np %d)",
                  2 * (16 - regmap.ROUTE_AXES * PH - 1), env.clocks, np_)


@cocotb.test()
async def shared_phase_and_trip(dut):
    naxes = int(os.environ["TB_NAXES"])
    env = Env(dut, naxes, 2)
    await env.start()
    np_ = PH * naxes
    # outputs 15, 14 and 3 all from axis 0 phase B; output 0 from the last axis' phase C
    codes = [0] * NOUT
    codes[15] = codes[14] = codes[3] = regmap.ROUTE_PHASES * 0 + 1 + 1
    codes[0] = np_
    for w, v in zip(("OUT_SEL0", "OUT_SEL1"), out_words(codes)):
        assert await env.write(w, v)
    await env.idle(NOUT + 2)
    want = (1 << 1) | (1 << (np_ - 1))
    assert env.route.mapped == want, f"mapped {env.route.mapped:#x}"
    for hi, lo in ((0b010, 0), (0, 0b010), (0b010, 0b010), (0, 0)):
        await env.clock(hi=hi, lo=lo)
        pins = (1 << 15) | (1 << 14) | (1 << 3)
        assert int(dut.pin_hi.value) & pins == (pins if hi else 0)
        assert int(dut.pin_lo.value) & pins == (pins if lo else 0)
    # trip of the last axis: output 0 off at the next edge; axis 0's outputs keep switching
    full = (1 << np_) - 1
    await env.clock(hi=full, lo=full)
    assert int(dut.pin_hi.value) & 1
    await env.clock(hi=full, lo=full, trip=1 << (naxes - 1))
    p = int(dut.pin_hi.value) | int(dut.pin_lo.value)
    assert not p & 1, "tripped axis' output on"
    if naxes > 1:
        assert p & (1 << 15), "another axis' trip turned axis 0 off"
    await env.clock(hi=full, lo=full, trip=0)
    assert int(dut.pin_hi.value) & 1
    if naxes < regmap.ROUTE_AXES:
        # a code naming an axis this build lacks: accepted by the map (the board's), held off like 0
        codes[5] = 1 + PH * naxes + 2
        assert await env.write("OUT_SEL0", out_words(codes)[0])
        await env.idle(3, hi=full, lo=full)
        assert not (int(dut.pin_hi.value) >> 5) & 1 and not (int(dut.pin_lo.value) >> 5) & 1
    dut._log.info("shared phase (3 outputs), trip isolation, missing-axis code; %d clocks bit-exact", env.clocks)


@cocotb.test()
async def random_vs_model(dut):
    naxes = int(os.environ["TB_NAXES"])
    seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
    n = int(os.environ.get("TB_CLOCKS", "20000"))
    dut._log.info("random: seed %d (EMPC_SEED), %d clocks, NAXES %d", seed, n, naxes)
    env = Env(dut, naxes, seed)
    r = env.rng
    await env.start()
    np_ = PH * naxes
    live = 0
    offs = [REG[x].offset for x in ROUTE_RW] + [REG["ROUTE_STATUS"].offset]
    while env.clocks < n:
        if r.random() < 0.01:
            live ^= 1
        kw = env.random_inputs()
        kw["bridges_live"] = live
        kw["rst"] = int(r.random() < 0.0005)
        x = r.random()
        if x < 0.03:
            name = r.choice(ROUTE_RW)
            if name.startswith("OUT_SEL") and r.random() < 0.8:
                codes = [r.randrange(0, np_ + 1) if r.random() < 0.9 else r.randrange(0, 1 << regmap.ROUTE_OUT_W)
                         for _ in range(NOUT)]
                v = out_words(codes)[int(name[-1])]
            elif r.random() < 0.7:
                r_ = REG[name]
                v = field_word(name, {f.name: r.getrandbits(f.width) for f in r_.fields})
            else:
                v = r.getrandbits(32)
            kw.update(reg_wr=1, reg_addr=REG[name].offset, reg_wdata=v)
        elif x < 0.06:
            kw.update(reg_rd=1, reg_addr=r.choice(offs))
        await env.clock(**kw)
        env.stats["trips"] += kw["trip"] != 0
    st = env.stats
    dut._log.info("random: %d clocks bit-exact vs models (seed %d): %s", env.clocks, seed, st)
    assert st["refused"] > 20 and st["accepted"] > 20 and st["trips"] > 50 and st["pins_on"] > n
    if LINES != (regmap.ROUTE_ENC, regmap.ROUTE_HALL, regmap.ROUTE_ADC):
        assert 0 < st["bad"] < env.clocks, "bad_sel never or always set with fewer board lines"


def _run(naxes: int, lines: tuple = (regmap.ROUTE_ENC, regmap.ROUTE_HALL, regmap.ROUTE_ADC)) -> None:
    from runner import run
    nenc, nhall, nadc = lines
    run(toplevel="out_route_tb", test_module="test_out_route",
        parameters={"NAXES": naxes, "NENC": nenc, "NHALL": nhall, "NADC": nadc},
        name=f"out_route_n{naxes}_{nenc}_{nhall}_{nadc}",
        extra_env={"TB_NAXES": str(naxes), "TB_LINES": ",".join(map(str, lines))})


@pytest.mark.cost(14)          # Icarus, 20,000 random clocks + corners, checked every clock
def test_out_route_naxes4():
    _run(4)


@pytest.mark.cost(14)          # Icarus, 20,000 random clocks + corners, checked every clock
def test_out_route_naxes1():
    _run(1)


@pytest.mark.cost(14)          # Icarus, 20,000 random clocks + corners, checked every clock
def test_out_route_fewer_lines():
    """NAXES = 2 with 5 IRC inputs, 3 HALL sets, 6 ADC channels: selects beyond them read the fail-safe
    values and set bad_sel."""
    _run(2, (5, 3, 6))
