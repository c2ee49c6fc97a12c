"""cocotb block test of ctrl_seq (with ref_gen and mpc_core) against CtrlSeq / RefGen / mpc_core models.

tb/hdl/ctrl_seq_tb.v wires ctrl_seq to ref_gen and mpc_core; the test drives the PWM timing, the
encoder count and angle, the ADC samples and the registers itself, so every period can be far
from what a running motor produces:

* every PWM period: the three compare values equal CtrlSeq.period() (bit-exact);
* every control period with the law running: the core's u, ebar and flags equal the model's
  core.update() on the inputs the model formed (so every input word ctrl_seq wrote is checked
  through the core); the front-end saturation pulse equals the model's ``front_sat``;
* randomised (seed EMPC_SEED, printed): count jumps of any size (speed and angle increments that
  saturate the SIG_W words, eq. 37 speeds beyond Q16.16), kacc / kacc_shift / load_shift (the
  load estimate of the speed, 0..15) / kdc / current
  references, run on and off, 1..5 PWM periods per control period, ref_gen's governor on (header
  words) with a random hold per control period, reference programs with random
  64-bit slots, relative / last segments, syncs, and references that saturate in the core format
  (position task: rel >> 24 at +-2^31 and the +2^39 wrap case);
* both tasks: speed (boot image) and position (algorithm 2 image uploaded through the core's
  configuration port and swapped in);
* counter clears (CMD.clear_counters) just before a trigger, so that the trigger interrupts the
  zero sweep: at a random clock, or in a clock where the sweep is in E_OP (a counter op or the
  sweep's end marker); that period must still match the model, and the zero sweep must complete
  after it.
"""
from __future__ import annotations

import os
import random
import re
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge

from empc import formats as F
from empc import header, image
from empc.rtlmodel import ctrl_seq as CS
from empc.rtlmodel import mpc_core as core
from empc.rtlmodel.ctrl_seq import CtrlSeq, Regs
from empc.rtlmodel.ref_gen import FIELDS, RefGen, Slot, slot_field

DEFAULT_SEED = 777


def _rtl_consts(*names: str) -> list[int]:
    """Sized decimal localparams of rtl/ctrl_seq.v, which defines them (no copy here)."""
    text = (Path(__file__).resolve().parents[1] / "rtl" / "ctrl_seq.v").read_text()
    out = []
    for n in names:
        m = re.search(rf"\b{n}\s*=\s*\d+'d(\d+)", text)
        assert m, f"localparam {n} not found in rtl/ctrl_seq.v"
        out.append(int(m.group(1)))
    return out


# engine state E_OP and the counter-sweep ops (uw[3:0], microprogram table), for timing triggers
# onto sweep E_OP clocks
(E_OP,) = _rtl_consts("E_OP")
OP_CNT, OP_CEND = CS.OP["CNT"], CS.OP["CEND"]
N = 4
PERIODS = int(os.environ.get("EMPC_CS_PERIODS", "400"))


def _s13(rng):
    return rng.choice([rng.randrange(-4096, 4096), rng.randrange(-200, 200), 4095, -4096, 0])


def _unpack(v: int, n: int, w: int) -> tuple:
    return tuple(F.wrap(v >> (w * i), w) for i in range(n))


@cocotb.test()
async def random_periods(dut):
    seed = int(os.environ.get("EMPC_SEED", DEFAULT_SEED))
    rng = random.Random(seed)
    task = os.environ["CS_TASK"]
    roms = Path(os.environ["EMPC_ROMS"])
    half = int(os.environ.get("CS_HALF", "2500"))
    dut._log.info("ctrl_seq random periods: task %s, seed %d (EMPC_SEED), %d periods", task, seed, PERIODS)
    Clock(dut.clk, 10, unit="ns").start()
    for n in ("adc_trig", "period_start", "run", "adc_valid", "seg_we", "start", "sync", "sync_bit", "cfg_we",
              "cfg_swap", "swap_at", "seg_slot", "seg_field", "seg_wdata", "start_slot", "cfg_addr", "cfg_wdata", "theta", "pos",
              "cur0", "cur1", "cur2", "kacc", "kacc_shift", "load_shift", "hold", "id_ref", "iq_ref", "cnt_clear"):
        getattr(dut, n).value = 0
    dut.ppc.value = 1
    dut.kdc.value = 1 << F.KDC_FRAC
    dut.rst.value = 1
    await ClockCycles(dut.clk, 5)
    dut.rst.value = 0
    await ClockCycles(dut.clk, 900, rising=False)          # core boot, ref_gen clears itself
    params = image.decode(image.read_hex(roms / "coef_boot.hex"))
    if task == "position":
        words = image.read_hex(roms / "coef_alg2_position.hex")
        for a in range(image.USED):
            dut.cfg_we.value = 1
            dut.cfg_addr.value = a
            dut.cfg_wdata.value = words[a]
            await FallingEdge(dut.clk)
        dut.cfg_we.value = 0
        dut.cfg_swap.value = 1
        await FallingEdge(dut.clk)
        dut.cfg_swap.value = 0
        await ClockCycles(dut.clk, 3, rising=False)
        dut.swap_at.value = 1                               # a control-period boundary: the swap is decided
        await FallingEdge(dut.clk)
        dut.swap_at.value = 0
        await ClockCycles(dut.clk, 10, rising=False)
        params = image.decode(words)
    assert int(dut.task_pos.value) == (task == "position")
    model = CtrlSeq(params=params, N=N)
    ref = RefGen(N)
    hdr = header.read(roms / "empc_formats.vh")         # ref_gen's governor words after configuration
    ref.write_gov(hdr["GOV_VMAX_LO"] | hdr["GOV_VMAX_HI"] << 32, hdr["GOV_A_LO"] | hdr["GOV_A_HI"] << 32,
                  hdr["GOV_KSH"], bool(hdr["GOV_EN"]))
    regs = Regs(pwm_per_control=1, half_period=half, run=True)
    sync_val = [0]

    async def sync_drv():
        while True:
            await FallingEdge(dut.clk)
            dut.sync_bit.value = (sync_val[0] >> int(dut.sync_idx.value)) & 1
    cocotb.start_soon(sync_drv())

    async def write_slot(i, s):
        s = s.normalised()
        for f in range(len(FIELDS)):
            await FallingEdge(dut.clk)
            dut.seg_we.value = 1
            dut.seg_slot.value = i
            dut.seg_field.value = f
            dut.seg_wdata.value = slot_field(s, f)
        await FallingEdge(dut.clk)
        dut.seg_we.value = 0
        ref.write_slot(i, s)

    fs_seen = [False]

    async def front_sat_mon():
        while True:
            await FallingEdge(dut.clk)
            if int(dut.front_sat.value):
                fs_seen[0] = True
    cocotb.start_soon(front_sat_mon())

    sw = core.SIG_W
    pos = rng.getrandbits(32)
    st = dict(periods=0, control=0, core_checked=0, run0=0, spd_sat=0, dth_sat=0, dom_sat=0, ref_sat=0,
              front_sat=0, int_op=0, int_cend=0, int_any=0)
    for k in range(PERIODS):
        await FallingEdge(dut.clk)
        if rng.random() < 0.5 or task != "position":
            pos = (pos + rng.choice([0, 1, -1, 300, -300, rng.getrandbits(32), 1 << 15, -(1 << 15), 40000,
                                     1 << 23, -(1 << 23), (1 << 23) - 1])) & 0xFFFFFFFF
        r = rng.random()
        if r < 0.1:
            slot = rng.randrange(16)
            if task == "position" and rng.random() < 0.7:
                # references around the saturation of the core word: rel >> 24 near +-2^31 and the
                # wrap case rel + 2^23 >= 2^63
                hi = rng.choice([0x7FFFFFFF, 0x7FFFFE, 0x7FFFFF, 0x800000, -0x800000, -0x800001])
                frac = rng.choice([0xFF800000 | rng.getrandbits(23), rng.getrandbits(32)])
                s = Slot(0, (((pos + hi) & 0xFFFFFFFF) << 32) | frac, 0, 0)
            else:
                s = Slot(rng.choice([0, 1, 3, 7]), rng.getrandbits(64), rng.getrandbits(rng.choice([8, 40, 64])),
                         rng.randrange(-2**31, 2**31), relative=rng.random() < 0.3, last=rng.random() < 0.3)
            await write_slot(slot, s)
            await FallingEdge(dut.clk)
            dut.start.value = 1
            dut.start_slot.value = slot
            await FallingEdge(dut.clk)
            dut.start.value = 0
            ref.start(slot)
        elif r < 0.13:
            sync_val[0] = rng.getrandbits(64)
            dut.sync.value = 1
            await FallingEdge(dut.clk)
            dut.sync.value = 0
            ref.sync(sync_val[0])
            while int(dut.ref_busy.value):
                await FallingEdge(dut.clk)
        if rng.random() < 0.3:
            regs.kacc = rng.randrange(-2**17, 2**17)
            regs.kacc_shift = rng.randrange(32)
        if rng.random() < 0.2:
            regs.load_shift = rng.choice([0, 1, 6, 15, rng.randrange(16)])
        hold = rng.random() < 0.3
        if rng.random() < 0.2:
            regs.kdc = rng.randrange(2**18)
        if rng.random() < 0.2:
            regs.id_ref = rng.randrange(-2**17, 2**17)
            regs.iq_ref = rng.randrange(-2**17, 2**17)
        if rng.random() < 0.05:
            regs.pwm_per_control = rng.choice([1, 2, 3, 5])
        regs.run = rng.random() > 0.1
        dut.kacc.value = regs.kacc & 0x3FFFF
        dut.kacc_shift.value = regs.kacc_shift
        dut.load_shift.value = regs.load_shift
        dut.hold.value = int(hold)
        dut.kdc.value = regs.kdc
        dut.id_ref.value = regs.id_ref & 0x3FFFF
        dut.iq_ref.value = regs.iq_ref & 0x3FFFF
        dut.ppc.value = regs.pwm_per_control
        dut.run.value = int(regs.run)
        theta = rng.getrandbits(16)
        cur = (_s13(rng), _s13(rng), _s13(rng))
        dut.pos.value = pos
        dut.theta.value = theta
        await ClockCycles(dut.clk, 20, rising=False)
        # ---- one PWM period: trigger, ADC samples, compare values ----
        control = model.per_cnt + 1 >= regs.pwm_per_control
        ref_w = ref.advance(hold=hold, task_pos=task == "position") if control else None
        if control:
            dpos = F.wrap(pos - model.pos_prev, 32)
            st["spd_sat"] += int(F.sat(dpos << F.W_FRAC, F.W_W) != dpos << F.W_FRAC)
            st["dth_sat"] += int(F.sat(dpos << F.TH_FRAC, sw) != dpos << F.TH_FRAC)
            for wv in ref_w:
                x = F.rshift_round(F.wrap(wv - (pos << 32), 64), 32 - F.TH_FRAC) if task == "position" \
                    else F.rshift_round(F.wrap(wv, 64), 32 - F.W_FRAC)
                st["ref_sat"] += int(F.sat(x, sw) != x)
        omega_prev = model.omega_prev
        out = model.period(theta, pos, cur, regs, ref_w)
        if control:
            st["dom_sat"] += int(F.sat(out["omega"] - omega_prev, sw) != out["omega"] - omega_prev)
        fs_seen[0] = False
        # CMD.clear_counters shortly before the trigger: the zero sweep it starts is interrupted by
        # the trigger, in half of the cases in a clock where the sweep is in E_OP (counter op or its
        # end marker), where the trigger must still start the control program
        interrupted = rng.random() < 0.12
        if interrupted:
            dut.cnt_clear.value = 1
            await FallingEdge(dut.clk)
            dut.cnt_clear.value = 0
            if rng.random() < 0.5:
                skip, seen, n = rng.randrange(16), 0, 0
                while True:
                    await FallingEdge(dut.clk)
                    op = int(dut.u_seq.uw.value) & 0xF
                    if int(dut.u_seq.est.value) == E_OP and op in (OP_CNT, OP_CEND):
                        if seen == skip or op == OP_CEND:
                            break
                        seen += 1
                    n += 1
                    assert n < 2000, "no zero sweep after cnt_clear"
                st["int_op"] += 1
                st["int_cend"] += int(op == OP_CEND)
            else:
                await ClockCycles(dut.clk, rng.randrange(1, 600), rising=False)
                st["int_any"] += 1
        dut.adc_trig.value = 1
        await FallingEdge(dut.clk)
        dut.adc_trig.value = 0
        await ClockCycles(dut.clk, 70, rising=False)
        dut.cur0.value = cur[0] & 0x1FFF
        dut.cur1.value = cur[1] & 0x1FFF
        dut.cur2.value = cur[2] & 0x1FFF
        dut.adc_valid.value = 1
        await FallingEdge(dut.clk)
        dut.adc_valid.value = 0
        n = 0
        while not int(dut.cmp_load.value):
            await FallingEdge(dut.clk)
            n += 1
            assert n < half - 80, f"period {k}: no compare values within the half period ({half} clocks)"
        fs_seen[0] |= bool(int(dut.front_sat.value))      # a modulation saturation pulses with cmp_load
        v = int(dut.cmp.value)
        got = tuple((v >> (12 * i)) & 0xFFF for i in range(3))
        assert got == tuple(out["cmp"]), f"period {k} (control {control}): cmp rtl {got} model {out['cmp']}"
        assert fs_seen[0] == bool(out["front_sat"]), \
            f"period {k}: front_sat rtl {fs_seen[0]} model {out['front_sat']}"
        st["front_sat"] += int(fs_seen[0])
        if control and "core" in out:
            c = out["core"]
            u = _unpack(int(dut.u_core.u.value), 2, F.U_W)
            eb = _unpack(int(dut.u_core.ebar.value), 3, sw)
            fl = int(dut.u_core.flags.value)
            assert (u, eb, fl) == (tuple(c.u), tuple(c.ebar), c.flags), \
                f"period {k}: core outputs rtl {(u, eb, fl)} model {(c.u, c.ebar, c.flags)}"
            st["core_checked"] += 1
        st["periods"] += 1
        st["control"] += int(control)
        st["run0"] += int(not regs.run)
        await ClockCycles(dut.clk, 700, rising=False)        # counter sweep, settle
        if interrupted:     # the interrupted zero sweep ran again after the period and completed
            assert int(dut.u_status.hide_cnt.value) == 0, f"period {k}: zero sweep not completed"
    dut._log.info("ctrl_seq %s: seed %d, %s (all compare values, core outputs and front_sat pulses "
                  "bit-exact with the model)", task, seed, st)
    for key in ("dth_sat", "dom_sat", "ref_sat", "spd_sat", "run0", "core_checked", "int_op", "int_cend", "int_any"):
        assert st[key] > 0, f"no period exercised {key}: {st}"


def _run(task: str):
    from runner import run
    run(toplevel="ctrl_seq_tb", test_module="test_ctrl_seq", sim="verilator", name="ctrl_seq", run_name=task,
        extra_env={"CS_TASK": task})        # one Verilator build for both tasks


@pytest.mark.cost(20)          # Verilator build (shared by the two) + 400 periods
def test_ctrl_seq_speed():
    _run("speed")


@pytest.mark.cost(20)
def test_ctrl_seq_position():
    _run("position")


def test_ctrl_seq_generated_files():
    """rtl/ctrl_seq_ucode.vh and rtl/ctrl_seq_rom.vh equal what the microprogram tables generate."""
    root = Path(__file__).resolve().parents[1]
    for cmd, gen in (("ucode", CS.ucode_vh), ("rom", CS.rom_vh)):
        assert (root / "rtl" / f"ctrl_seq_{cmd}.vh").read_text() == gen(), \
            f"rtl/ctrl_seq_{cmd}.vh is stale: python -m empc.ucode"


def test_ctrl_seq_images():
    """Every horizon's microprogram image decodes back to its programs: the control program reads
    w_k .. w_{k+N} in order (ref_age = N - m; only m = 0 streams the REF status word) and fits
    below the status programs, which run into each other as the RTL's entry points assume."""
    for n in CS.N_RANGE:
        img = CS.urom_image(n)
        uw = [CS.UW.unpack(w) for w in img[:CS.UROM_ROWS]]
        ub = [CS.UB.unpack(w) for w in img[CS.UROM_ROWS:]]
        refs = [(pc, w) for pc, w in enumerate(uw) if w["op"] == CS.OP["REF"]]
        assert [w["age"] for _, w in refs] == list(range(n, -1, -1)), (n, refs)
        assert [ub[pc]["stw"] for pc, _ in refs] == [1] + [0] * n
        assert [w["wa"] for _, w in refs] == [core.IN_WREF + 3 * m + 2 for m in range(n + 1)]
        end = [pc for pc, w in enumerate(uw) if w["op"] == CS.OP["END"]]
        assert end == [14 + 3 * (n + 1)] and end[0] < CS.ENTRY["STAT"], (n, end)
        assert CS.ENTRY["CNT"] == CS.ENTRY["ZERO"] + len(CS.ZERO_PROGRAM)
        assert [w["op"] for w in uw[CS.ENTRY["CNT"]:CS.ENTRY["CNT"] + len(CS.COUNT_PROGRAM)]] == \
            [CS.OP["CNT"]] * len(CS.COUNTERS) + [CS.OP["CEND"]]
        assert CS.ENTRY["CNT"] + len(CS.COUNT_PROGRAM) <= CS.UROM_ROWS
