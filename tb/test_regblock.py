"""cocotb tests of the generated register blocks (gen/empc/regblock.py).

Every block is compared clock by clock with ``regblock.Model`` (the cycle model of what the
generator emits), on random stimulus plus directed corner cases:

* the real blocks rtl/axis_regs.v and rtl/global_regs.v (committed, generated from
  gen/empc/regmap.py);
* a small test map (TEST_REGS below) that uses every attribute the real map uses and the
  ones it does not use yet (``guard`` on registers and fields (stored and pulse), ``safe``,
  ``legal`` as a range, a set and a table, ``floor`` above 1, a key register with ``arm``
  and a register that needs its ``unlock``, ``wstrobe``, a signed input, a mux read on two
  pages, a guarded window, a strobe group with mixed widths), generated twice: "copy" and
  "mux" read paths.

Per clock: random reg_wr / reg_rd (sometimes both), an address near a register or anywhere,
random data (sometimes the key, a legal value or all ones), every input port random, rare
resets.  Checked every clock: every output port (registered outputs against the model
state, reg_rdata and the window strobes combinationally).
"""
from __future__ import annotations

import json
import os
import random
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, Timer

from empc import header, regblock, regmap
from empc.regmap import Block, Ext, Field, Reg

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_SEED = 1313

TEST_EXT = (
    Ext("grp", "strobe", "strobe group"),
    Ext("win", "window", "writable window", idx=True, rdata="win_rdata"),
    Ext("row", "window", "read-only window sharing the read data", rdata="win_rdata"),
)
TEST_REGS = (
    Reg("CTRL", 0x00, "RW", 0x3, "fields with floor, legal set and a build reset", (
        Field("en", 0, 1, "enable"),
        Field("mode", 1, 2, "mode", legal=(0, 1, 3)),
        Field("div", 8, 8, "divider", reset="EMPC_PWM_PER_CONTROL", floor=3))),
    Reg("CMD", 0x01, "WO", 0, "pulses", (Field("go", 0, 1, "go"),
                                         Field("clr", 3, 2, "two-bit pulse, refused while armed", guard="armed"))),
    Reg("STAT", 0x02, "RO", 0, "input fields", (Field("a", 0, 1, "a"), Field("b", 4, 12, "b"))),
    Reg("LIM", 0x03, "RW", 1000, "legal range (compares)", width=16, legal=range(10, 60001)),
    Reg("SREF", 0x04, "RW", 0, "signed, guarded", width=18, signed=True, guard="armed"),
    Reg("OFF0", 0x05, "RW", 7, "strobe member", width=12, ext="grp"),
    Reg("OFF1", 0x06, "RW", 7, "strobe member, narrower, legal", width=8, ext="grp", legal=range(0, 200)),
    Reg("KICK", 0x07, "WO", 0, "key", width=16, key=0x5A5A),
    Reg("START", 0x08, "WO", 0, "pulse and data, guarded", width=4, guard="armed"),
    Reg("IRQ", 0x09, "W1C", 0x4, "sticky bits", (Field("p", 0, 1, "p"), Field("q", 2, 1, "q"))),
    Reg("MAGIC", 0x0a, "RO", 0x12345678, "constant", const=True),
    Reg("MUXED", 0x0b, "RW", 0xABC, "read through the mux", width=12, read="mux"),
    Reg("BIG", 0x0c, "RW", 0, "legal set on 32 bits", legal=(0, 5, 0x10000, 0xFFFFFFFF)),
    Reg("NIB", 0x0d, "RW", 2, "legal range on 4 bits (table)", width=4, legal=range(2, 12), guard="locked"),
    Reg("CFG", 0x0e, "RW", 0x0501, "field guard and safe", (
        Field("on", 0, 1, "switch: 0 always accepted", safe=0),
        Field("per", 8, 8, "period: changes refused while armed, 0 illegal", legal=range(1, 256), guard="armed"))),
    Reg("UNL", 0x0f, "WO", 0, "key register: arms one write until the 5th unl_tick", width=16, key=0xC0DE, arm=5),
    Reg("LOCKD", 0x13, "RW", 0x33, "needs the unlock, guarded", width=8, unlock="UNL", guard="locked"),
    Reg("FRESH", 0x14, "RW", 0, "write strobe", width=16, wstrobe=True),
    Reg("W0", 0x10, "RW", 0, "window word 0", ext="win", guard="armed"),
    Reg("W1", 0x11, "RW", 0, "window word 1", ext="win", guard="armed"),
    Reg("W2", 0x12, "RO", 0, "window word 2 (read-only)", ext="win"),
    Reg("LIVE", 0x21, "RO", 0, "signed input, second page", width=20, signed=True),
    Reg("MRO", 0x25, "RO", 0, "input read through the mux, second page", width=7, read="mux"),
    Reg("R0", 0x30, "RO", 0, "read-only window", ext="row"),
    Reg("R1", 0x34, "RO", 0, "read-only window", ext="row"),
)
TEST_BLOCKS = (
    Block("tst_copy_regs", "T", TEST_REGS, "copy", "test block, gated copies", ext=TEST_EXT),
    Block("tst_mux_regs", "T", TEST_REGS, "mux", "test block, shared read register", ext=TEST_EXT),
)
ALL_BLOCKS = {b.module: b for b in regmap.BLOCKS + TEST_BLOCKS}


def _macros() -> dict:
    roms = Path(os.environ.get("EMPC_ROMS", ROOT / "build" / "roms" / "default"))
    return header.read(roms / "empc_formats.vh")


async def run_block(dut, b: Block, n: int) -> None:
    seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
    rng = random.Random(seed)
    m = regblock.Model(b, _macros())
    g = m.g
    ins_ports = [(p[1], p[2]) for p in m.ports if p[0] == "input" and p[1] != "clk"]
    outs = [p[1] for p in m.ports if p[0] == "output"]
    comb_outs = {"reg_rdata"} | {f"{e.name}_{s}" for e in g.windows for s in ("we", "re", "idx")} \
        | {f"{a.base}_armed" for a in g.arms} | ({"rd_vals", "sh_we"} if b.shared else set())
    offsets = [r.offset for r in b.regs]
    locked_offs = [r.offset for r in b.regs if r.unlock]
    key_offs = [r.offset for r in b.regs if r.arm is not None]
    specials = [0, 0xFFFFFFFF, 0x5A5A] + [r.key for r in b.regs if r.key is not None]
    for r in b.regs:
        for f in r.parts():
            if f.legal is not None:
                vals = list(f.legal)
                specials += [(v << f.lsb) & 0xFFFFFFFF for v in (vals[0], vals[-1], vals[0] - 1, vals[-1] + 1) if v >= 0]
            if f.floor is not None:
                specials += [v << f.lsb for v in (0, f.floor - 1, f.floor, f.floor + 1)]
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    stats = dict(wr=0, rd=0, refused=0, rdata_nz=0, rst=0, pulses=0, unlocked=0)
    pulse_ports = [r.part_port(f) for r in b.regs for f in r.parts()
                   if g.k[r.name].pulses or (g.k[r.name].key and r.arm is None) or g.k[r.name].wodata]
    pulse_ports += [f"{e.name}_we" for e in g.strobes]

    last_wr_addr = [None]

    def stimulus(k: int) -> dict:
        ins = {}
        for name, w in ins_ports:
            ins[name] = rng.getrandbits(w)
        ins["rst"] = int(k < 2 or rng.random() < 0.003)
        x = rng.random()
        ins["reg_wr"] = int(x < 0.35 or 0.97 < x)
        ins["reg_rd"] = int(0.35 <= x < 0.7 or 0.97 < x)
        a = rng.choice(offsets) if rng.random() < 0.85 else rng.getrandbits(g.aw)
        if locked_offs and last_wr_addr[0] in key_offs and rng.random() < 0.7:
            a = rng.choice(locked_offs)            # after a key write: the register it unlocks
        if ins["reg_wr"]:
            last_wr_addr[0] = a
        ins["reg_addr"] = a
        ins["reg_wdata"] = rng.choice(specials) if rng.random() < 0.3 else rng.getrandbits(32)
        if a in key_offs and rng.random() < 0.6:
            ins["reg_wdata"] = next(r.key for r in b.regs if r.offset == a)
        for gname in g.guards:
            ins[gname] = int(rng.random() < 0.3)
        for p in [p for p in ins if p.endswith("_set")]:
            ins[p] = int(rng.random() < 0.1)
        return ins

    rdata_ports = {e.rdata_port: [x.name for x in g.windows if x.rdata_port == e.rdata_port] for e in g.windows}
    prev_re = set()
    for k in range(n):
        ins = stimulus(k)
        for p, wins in rdata_ports.items():      # a window drives read data only after its read
            if not prev_re & set(wins):
                ins[p] = 0
        for name, v in ins.items():
            getattr(dut, name).value = v
        await Timer(1, unit="ns")
        exp = m.comb(ins)
        for o in outs:
            want = exp[o] if o in comb_outs else m.state[o]
            got = int(getattr(dut, o).value)
            assert got == want, (f"{b.module} clock {k} seed {seed}: {o} = {got:#x}, model {want:#x}; "
                                 f"inputs {ins}")
        stats["rdata_nz"] += exp["reg_rdata"] != 0
        prev_re = {e.name for e in g.windows if exp[f"{e.name}_re"]}
        m.clock(ins)
        stats["wr"] += ins["reg_wr"]
        stats["rd"] += ins["reg_rd"]
        stats["rst"] += ins["rst"]
        stats["refused"] += m.state.get("wr_refused", 0)
        stats["unlocked"] += int(bool(ins["reg_wr"] and not ins["rst"] and ins["reg_addr"] in locked_offs
                                      and not m.state["wr_refused"]))
        stats["pulses"] += any(m.state[p] for p in pulse_ports)
        await FallingEdge(dut.clk)
    dut._log.info("%s: %d clocks vs model (seed %d, EMPC_SEED): %s", b.module, n, seed, stats)
    rep = ROOT / "build" / "reports"
    rep.mkdir(parents=True, exist_ok=True)
    (rep / f"regblock_{b.module}.json").write_text(json.dumps(
        {"block": b.module, "clocks": n, "seed": seed, "writes": stats["wr"], "refused_writes": stats["refused"],
         "unlocked_writes": stats["unlocked"], "compared_with": "regblock.Model, every output every clock"},
        indent=1) + "\n")
    assert stats["rdata_nz"] > n // 20 and stats["pulses"] > 0 and stats["rst"] > 2
    if g.refuse:
        assert stats["refused"] > 0
    if locked_offs:
        assert stats["unlocked"] > 0, "no write passed an unlock"



@cocotb.test()
async def block_vs_model(dut):
    b = ALL_BLOCKS[os.environ["TB_BLOCK"]]
    if os.environ.get("TB_SHARED"):
        await run_shared(dut, b, int(os.environ["TB_NAXES"]), int(os.environ.get("TB_CLOCKS", "6000")))
    else:
        await run_block(dut, b, int(os.environ.get("TB_CLOCKS", "6000")))


async def run_shared(dut, b: Block, naxes: int, n: int) -> None:
    """The shared read path rtl/<b.shared>.v against regblock.SharedReadModel, driven by NAXES block models
    (regblock.Model, random inputs every clock, as in run_block): their rd_vals and sh_we exports, bus
    writes and reads of any axis (also axes >= NAXES) and word, window read data after a read, rare
    resets.  reg_rdata is compared every clock with the shared model and with what the read axis's own
    block (its copies, Model) returns: the shadow RAM reads exactly the stored registers."""
    seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
    rng = random.Random(seed)
    mac = _macros()
    m = regblock.SharedReadModel(b, naxes, mac)
    ax = [regblock.Model(b, mac) for _ in range(naxes)]
    g = m.g
    vw = g.rd_width()
    nsh = len(g.sh)
    ab = max(1, (naxes - 1).bit_length())
    offsets = [r.offset for r in b.regs]
    sh_offs = [r.offset for r in g.sh]
    ins_ports = [(p[1], p[2]) for p in ax[0].ports if p[0] == "input" and p[1] != "clk"]
    specials = [0, 0xFFFFFFFF] + [r.key for r in b.regs if r.key is not None]
    for r in b.regs:
        for f in r.parts():
            if f.legal is not None:
                vals = list(f.legal)
                specials += [(v << f.lsb) & 0xFFFFFFFF for v in (vals[0], vals[-1], vals[0] - 1, vals[-1] + 1) if v >= 0]
    rdp = sorted({e.rdata_port for e in g.windows})
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    st = dict(nz=0, per_axis=0, sh_rd=0, sh_rd_written=0, sh_wr=0, refused=0, both=0)
    prev_rd = False
    for k in range(n):
        x = rng.random()
        bus = {"rst": int(k < 2 or rng.random() < 0.003), "reg_wr": int(x < 0.4 or 0.97 < x),
               "reg_rd": int(0.4 <= x < 0.8 or 0.97 < x), "rd_axis": rng.getrandbits(ab),
               "reg_addr": (rng.choice(sh_offs) if rng.random() < 0.5 else rng.choice(offsets))
               if rng.random() < 0.9 else rng.getrandbits(g.aw),
               "reg_wdata": rng.choice(specials) if rng.random() < 0.3 else rng.getrandbits(32)}
        for p in rdp:                               # windows answer only after a read
            bus[p] = rng.getrandbits(32) if prev_rd and rng.random() < 0.2 else 0
        vals, shw, ref, aix = [], [], 0, []
        for a in range(naxes):
            ia = {name: rng.getrandbits(w) for name, w in ins_ports}
            for gname in ax[a].g.guards:
                ia[gname] = int(rng.random() < 0.3)
            sel = bus["rd_axis"] == a
            ia.update(rst=bus["rst"], reg_wr=bus["reg_wr"] & sel, reg_rd=bus["reg_rd"] & sel,
                      reg_addr=bus["reg_addr"], reg_wdata=bus["reg_wdata"])
            for p in rdp:
                ia[p] = 0
            c = ax[a].comb(ia)
            vals.append(c["rd_vals"])
            shw.append(c.get("sh_we", 0))
            ref |= c["reg_rdata"]                   # the axes' own read paths (0 unless read; windows 0 here)
            aix.append(ia)
        ins = dict(bus, rd_vals=vals, sh_we=shw)
        dut.rst.value = ins["rst"]
        dut.reg_rd.value = ins["reg_rd"]
        dut.rd_axis.value = ins["rd_axis"]
        dut.reg_addr.value = ins["reg_addr"]
        dut.rd_vals.value = sum(v << (vw * a) for a, v in enumerate(vals))
        if nsh:
            dut.reg_wdata.value = ins["reg_wdata"]
            dut.sh_we.value = sum(v << (nsh * a) for a, v in enumerate(shw))
        for p in rdp:
            getattr(dut, p).value = ins[p]
        await Timer(1, unit="ns")
        want = m.comb(ins)
        got = int(dut.reg_rdata.value)
        assert got == want, f"{b.shared} clock {k} seed {seed}: reg_rdata = {got:#x}, model {want:#x}"
        win = 0
        for p in rdp:
            win |= ins[p]
        assert want == ref | win, (f"{b.shared} clock {k} seed {seed}: shared model {want:#x}, the axis's own "
                                   f"read path {ref | win:#x}")
        st["nz"] += want != 0
        st["per_axis"] += bool(m.q | m.sh_q) and ins["rd_axis"] == naxes - 1
        st["sh_rd"] += bool(m.sh_q)
        st["both"] += bool(ins["reg_rd"] and any(shw))
        prev_rd = bool(ins["reg_rd"])
        m.clock(ins)
        if nsh and ins["reg_rd"] and ins["rd_axis"] < naxes and ins["reg_addr"] in sh_offs:
            kk = sh_offs.index(ins["reg_addr"])
            st["sh_rd_written"] += m.flags[ins["rd_axis"]] >> kk & 1
        st["sh_wr"] += any(shw)
        for a in range(naxes):
            ax[a].clock(aix[a])
            st["refused"] += ax[a].state.get("wr_refused", 0)
        await FallingEdge(dut.clk)
    dut._log.info("%s, NAXES %d: %d clocks vs SharedReadModel and the axes' own read paths (seed %d): %s",
                  b.shared, naxes, n, seed, st)
    assert st["nz"] > n // 10 and st["per_axis"] > 0
    if nsh:
        assert st["sh_rd"] > n // 50 and st["sh_rd_written"] > n // 100 and st["sh_wr"] > n // 50
        assert st["refused"] > 0 and st["both"] > 0


def _run(block: Block) -> None:
    from runner import BUILD, run
    extra = []
    if block in TEST_BLOCKS:
        d = BUILD / "regblock"
        d.mkdir(parents=True, exist_ok=True)
        f = d / f"{block.module}.v"
        f.write_text(regblock.render(block))
        extra = [f]
    run(toplevel=block.module, test_module="test_regblock", name=f"test_regblock_{block.module}",
        extra_sources=extra, extra_env={"TB_BLOCK": block.module})


@pytest.mark.cost(7)          # seconds on an idle core (make sim starts the costliest first)
def test_axis_regs():
    _run(ALL_BLOCKS["axis_regs"])


@pytest.mark.parametrize("naxes,split", [(3, None), (4, None), (2, None), (3, 1)])
def test_axis_rd(naxes, split):
    """The read path shared by the axes (rtl/axis_rd.v) against regblock.SharedReadModel; NAXES 3
    also reads the absent axis 3.  SPLIT: its default (NAXES <= 2: read registers per axis; 3, 4: one set
    behind the rd_axis multiplexer), and per axis at NAXES = 3."""
    from runner import run
    b = ALL_BLOCKS["axis_regs"]
    run(toplevel=b.shared, test_module="test_regblock",
        name=f"test_regblock_{b.shared}" + ("" if split is None else f"_split{split}"),
        parameters={"NAXES": naxes, **({} if split is None else {"SPLIT": split})},
        extra_env={"TB_BLOCK": b.module, "TB_SHARED": "1", "TB_NAXES": str(naxes)})


def test_global_regs():
    _run(ALL_BLOCKS["global_regs"])


def test_test_map_copy():
    _run(ALL_BLOCKS["tst_copy_regs"])


def test_test_map_mux():
    _run(ALL_BLOCKS["tst_mux_regs"])


# ---------------------------------------------------------------- the model against the rules
def _step(m: regblock.Model, **kw) -> dict:
    """One clock of the model with every input 0 but ``kw``; returns the combinational outputs."""
    ins = {p[1]: 0 for p in m.ports if p[0] == "input" and p[1] != "clk"}
    ins.update(kw)
    out = m.comb(ins)
    m.clock(ins)
    return out


def test_model_guard_and_legal():
    """Refused writes (guard high, a field outside its legal values) change nothing and pulse
    wr_refused; accepted ones act; floor; key; the window strobe follows the guard."""
    m = regblock.Model(TEST_BLOCKS[0], {"PWM_PER_CONTROL": 5})
    s = m.state
    assert (s["ctrl_en"], s["ctrl_mode"], s["ctrl_div"], s["lim"], s["nib"], s["irq_q"]) == (1, 1, 5, 1000, 2, 1)
    a = {r.name: r.offset for r in TEST_REGS}
    cases = [  # (register, data, extra inputs, refused, {output: value after})
        ("LIM", 9, {}, True, {"lim": 1000}),
        ("LIM", 60001, {}, True, {"lim": 1000}),
        ("LIM", 10, {}, False, {"lim": 10}),
        ("LIM", 0xFFFF0000 | 60000, {}, False, {"lim": 60000}),        # bits outside the field ignored
        ("SREF", 0x3FFFF, {"armed": 1}, True, {"sref": 0}),
        ("SREF", 0x3FFFF, {"locked": 1}, False, {"sref": 0x3FFFF}),   # another guard does not matter
        ("CTRL", (2 << 1) | 0 | (9 << 8), {}, True, {"ctrl_en": 1, "ctrl_mode": 1, "ctrl_div": 5}),  # whole word
        ("CTRL", (3 << 1) | 0 | (1 << 8), {}, False, {"ctrl_en": 0, "ctrl_mode": 3, "ctrl_div": 3}),  # floor 3
        ("CTRL", (0 << 1) | 1 | (4 << 8), {}, False, {"ctrl_en": 1, "ctrl_mode": 0, "ctrl_div": 4}),
        ("BIG", 6, {}, True, {"big": 0}),
        ("BIG", 0x10000, {}, False, {"big": 0x10000}),
        ("NIB", 1, {}, True, {"nib": 2}),
        ("NIB", 11, {"locked": 1}, True, {"nib": 2}),
        ("NIB", 11, {"armed": 1}, False, {"nib": 11}),
        ("OFF1", 200, {}, True, {"grp_we": 0}),
        ("OFF1", 199, {}, False, {"grp_we": 2, "grp_wdata": 199}),
        ("OFF0", 0xFFF, {"armed": 1}, False, {"grp_we": 1, "grp_wdata": 0xFFF}),
        ("START", 7, {"armed": 1}, True, {"start": 0}),
        ("START", 7, {}, False, {"start": 1, "start_data": 7}),
        ("KICK", 0x5A5B, {}, False, {"kick": 0}),
        ("KICK", 0xFFFF5A5A, {}, False, {"kick": 1}),
        ("IRQ", 0x4, {}, False, {"irq_q": 0}),
    ]
    for name, data, extra, refused, after in cases:
        _step(m, reg_wr=1, reg_addr=a[name], reg_wdata=data, **extra)
        assert s["wr_refused"] == int(refused), (name, data, extra)
        for k, v in after.items():
            assert s[k] == v, (name, data, extra, k, s[k], v)
    out = _step(m, reg_wr=1, reg_addr=a["W1"], reg_wdata=1, armed=1)
    assert out["win_we"] == 0 and out["win_idx"] == 1 and s["wr_refused"] == 1
    out = _step(m, reg_wr=1, reg_addr=a["W1"], reg_wdata=1)
    assert out["win_we"] == 1 and s["wr_refused"] == 0
    out = _step(m, reg_rd=1, reg_addr=a["W2"], armed=1)
    assert out["win_re"] == 1 and s["wr_refused"] == 0                   # reads are never refused
    # W1C: a set in the clock of a write of the register survives, even a write that clears that bit
    # (issue 14 item 6: an event arriving with the acknowledge is not lost)
    _step(m, irq_p_set=1)
    assert s["irq_p"] == 1
    _step(m, reg_wr=1, reg_addr=a["IRQ"], reg_wdata=0, irq_q_set=1)
    assert s["irq_p"] == 1 and s["irq_q"] == 1
    _step(m, reg_wr=1, reg_addr=a["IRQ"], reg_wdata=0x1, irq_q_set=1)     # clears p, q set again
    assert s["irq_p"] == 0 and s["irq_q"] == 1
    _step(m, reg_wr=1, reg_addr=a["IRQ"], reg_wdata=0x4, irq_q_set=1)     # clear and set together: kept
    assert s["irq_q"] == 1
    _step(m, reg_wr=1, reg_addr=a["IRQ"], reg_wdata=0x4)                   # cleared without a set
    assert s["irq_q"] == 0
    # read path: signed, constant, fields with gaps; 0 in the clock without a read
    _step(m, reg_rd=1, reg_addr=a["SREF"])
    assert _step(m)["reg_rdata"] == 0xFFFFFFFF and _step(m)["reg_rdata"] == 0
    _step(m, reg_rd=1, reg_addr=a["MAGIC"])
    assert _step(m)["reg_rdata"] == 0x12345678
    _step(m, reg_rd=1, reg_addr=a["STAT"], stat_a=1, stat_b=0xABC)
    assert _step(m)["reg_rdata"] == 0xABC1


def test_model_unlock_field_guard_safe():
    """Field guards (a change refused while the guard is high, a rewrite accepted, a pulse field's 1
    refused), safe values (written even by a refused write), the unlock (armed by the key for `arm`
    ticks, consumed by the next write of the block, a wrong key refused and disarming), wstrobe."""
    m = regblock.Model(TEST_BLOCKS[0], {"PWM_PER_CONTROL": 5})
    s = m.state
    a = {r.name: r.offset for r in TEST_REGS}
    assert (s["cfg_on"], s["cfg_per"], s["lockd"]) == (1, 5, 0x33)

    def wr(name, data, **kw):
        _step(m, reg_wr=1, reg_addr=a[name], reg_wdata=data, **kw)
        return s["wr_refused"]

    assert wr("CFG", (5 << 8) | 1, armed=1) == 0                       # same period: accepted
    assert wr("CFG", (6 << 8) | 1, armed=1) == 1 and s["cfg_per"] == 5  # change while armed: refused
    assert wr("CFG", (6 << 8) | 0, armed=1) == 1 and (s["cfg_on"], s["cfg_per"]) == (0, 5)  # off passes
    assert wr("CFG", (6 << 8) | 1) == 0 and (s["cfg_on"], s["cfg_per"]) == (1, 6)
    assert wr("CFG", (0 << 8) | 0) == 1 and (s["cfg_on"], s["cfg_per"]) == (0, 6)           # illegal 0, off passes
    assert wr("CFG", (0 << 8) | 1) == 1 and s["cfg_on"] == 0                                # on is not safe
    assert wr("CMD", 1 << 3, armed=1) == 1 and s["cmd_clr"] == 0          # guarded pulse field
    assert wr("CMD", 1, armed=1) == 0 and s["cmd_go"] == 1                 # the other field is free
    assert wr("LOCKD", 0x44) == 1 and s["lockd"] == 0x33                   # not unlocked
    assert wr("UNL", 0xC0DE) == 0
    assert wr("LOCKD", 0x44) == 0 and s["lockd"] == 0x44                   # the next write: accepted
    assert wr("LOCKD", 0x55) == 1 and s["lockd"] == 0x44                   # consumed
    assert wr("UNL", 0xC0DE) == 0
    assert wr("LOCKD", 0x55, locked=1) == 1 and s["lockd"] == 0x44         # guard still applies, consumed
    assert wr("LOCKD", 0x55) == 1
    assert wr("UNL", 0xC0DE) == 0
    assert wr("LIM", 100) == 0                                              # another write consumes it
    assert wr("LOCKD", 0x55) == 1
    assert wr("UNL", 0xC0DF) == 1                                           # wrong key: refused
    assert wr("LOCKD", 0x55) == 1
    for ticks in (4, 5):                                                    # armed until the 5th tick
        assert wr("UNL", 0xC0DE) == 0
        for _ in range(ticks):
            _step(m, unl_tick=1)
            _step(m)                                                        # clocks without a tick do not count
        assert wr("LOCKD", 0x60 + ticks) == int(ticks == 5), ticks
    assert s["lockd"] == 0x64
    assert wr("FRESH", 7) == 0 and s["fresh_wr"] == 1 and s["fresh"] == 7
    _step(m)
    assert s["fresh_wr"] == 0


def test_unused_mechanisms_emit_nothing():
    """A map without guard / legal / unlock carries no refuse logic."""
    plain = tuple(r for r in TEST_REGS if r.name in ("CMD", "STAT", "OFF0", "KICK", "MAGIC", "IRQ"))
    plain = tuple(Reg(r.name, r.offset, r.access, r.reset, r.doc, tuple(
        Field(f.name, f.lsb, f.width, f.doc) for f in r.fields), width=r.width, ext=r.ext, key=r.key)
        for r in plain)
    text = regblock.render(Block("plain_regs", "T", plain, "copy", "no safety hooks", ext=TEST_EXT))
    assert "wr_refused" not in text and "LEGAL_" not in text and "unl_cnt" not in text
    text = regblock.render(TEST_BLOCKS[0])
    assert "wr_refused" in text and "LEGAL_NIB" in text and "unl_cnt" in text
