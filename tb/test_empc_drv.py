"""The firmware driver and C header against the RTL: fw/empc_drv.c, compiled into a shared
library (flow/fw_build.py, tb/empc_drv_host.c), drives lx_rocon_top (tb/hdl/cosim_top.v, Icarus)
through the LPC4088 EMC bus-functional model (tb/emc_bfm.py).

The driver's two bus functions are ctypes callbacks that run the BFM's coroutines
(cocotb.task.bridge / resume: the C code runs in a thread that blocks while the simulator
performs each access).  The callbacks translate the CPU byte address the C code computes
into the word on the FPGA's emc_a pins as the LPC4088 EMC does (CS0 at 0x80000000, 32-bit
bus, SCS.EMCSC = 0: emc_a = byte address bits [15:2]); any other address fails the test.

* registers_vs_header: every register of the compiled C header's table (EMPC_GLOBAL_REGS,
  EMPC_AXIS_REGS; addresses from its address macros): the names are the map's; after reset
  it reads its _RESET in the _RESET_MASK bits (build-dependent fields: the build's value);
  WO registers read 0; every RW register reads back a written pattern in its _BITS
  (sign-extended if _SIGNED) and is restored.
* driver_flow: empc_init (ID, VERSION, CAPS against empc_formats.vh), empc_axis_config
  (read back by the driver and checked here over the bus), refused with the bridges on
  (empc_axis_enable), empc_coef_load refuses (EMPC_ERR_PERIOD, nothing written) an image designed for
  another control period than CTRL.pwm_per_control; empc_coef_load of another image (alg1 speed) into the inactive bank
  and the swap (the bank's decoded configuration, seen in mpc_coef_mem, is the image's;
  the window writes are the image words in order), empc_status_read against plain reads,
  every per-axis call with an axis the bitstream does not have (or a DC link past UDC) refused before any
  bus access, the watchdog fault: empc_wdog_set(1) expires it, empc_fault_clear reports the cause while
  it is present, and clears it after empc_wdog_kick.
* design_load_kacc: empc_design_load with the designs of the build's configuration at a control period of
  one PWM period (generated here by empc.roms; KACC differs from the boot design's and between designs):
  a KACC word outside its rules refused before any bus access; with the law off the design's KACC reads
  back bit-exact to the manifest's fields and the bank swaps; with the law running (STATUS.running) a
  design with another KACC is refused with nothing written (KACC and bank unchanged), one with the same
  KACC loads the image alone; a swap the FPGA refuses (incomplete image) writes the old KACC back; the
  active bank's decoded configuration is the loaded design's.
* fault_during_design_load: the law running on the boot design, the power-stage fault pin pulled low half way
  through empc_design_load of another design (same KACC: the image alone): the bridges go off within a few
  clocks, the load's result and the active bank agree (EMPC_OK and the new design's decoded configuration, or
  an error and the old one: never a mix); empc_fault_clear reports the cause while the pin is low, clears it
  once the pin is back, and the law restarts (STATUS.running) on the active bank; a second load then swaps.
"""
from __future__ import annotations

import ctypes
import json
import os
import shutil
import tempfile
from pathlib import Path

import cocotb
from cocotb.clock import Clock
from cocotb.task import bridge, resume
from cocotb.triggers import ClockCycles

from emc_bfm import EmcBfm
from empc import config, header, image, regmap, roms

ROOT = Path(__file__).resolve().parents[1]
EMC_BASE = 0x80000000
AW = 14
# a 320 V drive's DC link (the premo's): above 16 bits of mV, inside the 20-bit registers; the clear below
# succeeds only if the FPGA compares all 20 bits (FAULT.dclink otherwise)
UDC_MV, UDC_MIN_MV, UDC_MAX_MV = 320_000, 200_000, 400_000


class HostReg(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char_p), ("axis_block", ctypes.c_uint32), ("ofs", ctypes.c_uint32),
                ("access", ctypes.c_uint32), ("reset", ctypes.c_uint32), ("reset_mask", ctypes.c_uint32),
                ("bits", ctypes.c_uint32), ("sign", ctypes.c_uint32)]


class Caps(ctypes.Structure):
    _fields_ = [(n, ctypes.c_uint32) for n in ("version", "naxes", "horizon", "img_layout", "pwm_per_control",
                                               "pwm_half", "complementary")]


class AxisCfg(ctypes.Structure):
    _fields_ = [(n, ctypes.c_uint32) for n in ("pwm_per_control", "dead_time", "fault_mask", "kdc",
                                               "udc_mv", "udc_min_mv", "udc_max_mv", "oc_thresh", "angle_cal",
                                               "hall_offset")]


class Status(ctypes.Structure):
    _fields_ = [("status", ctypes.c_uint32), ("fault", ctypes.c_uint32), ("pos", ctypes.c_uint32),
                ("speed", ctypes.c_int32), ("theta", ctypes.c_uint32), ("i_d", ctypes.c_int32),
                ("i_q", ctypes.c_int32), ("u_d", ctypes.c_int32), ("u_q", ctypes.c_int32),
                ("latency", ctypes.c_uint32), ("periods", ctypes.c_uint32)]


RD_FN = ctypes.CFUNCTYPE(ctypes.c_uint32, ctypes.c_uint32)
WR_FN = ctypes.CFUNCTYPE(None, ctypes.c_uint32, ctypes.c_uint32)
EMPC_OK, EMPC_ERR_ARG, EMPC_ERR_BUSY, EMPC_ERR_FAULT, EMPC_ERR_REFUSED, EMPC_ERR_PERIOD = 0, -3, -4, -7, -8, -9


def _roms() -> Path:
    return Path(os.environ.get("EMPC_ROMS", ROOT / "build" / "roms" / "default"))


class Env:
    """The C library with its bus callbacks on the BFM, and the header's register table."""

    def __init__(self, dut):
        self.dut = dut
        self.lib = ctypes.CDLL(os.environ["EMPC_HOST_LIB"])
        self.bfm = EmcBfm(dut, pins=dict(cs_n="cpu_cs_n", oe_n="cpu_oe_n", we_n="cpu_we_n", a="cpu_a", d="cpu_d",
                                         d_oe="cpu_d_oe", bus="emc_d_seen"))
        self.writes: list[tuple[int, int]] = []
        self.reads = 0
        self.errors: list[str] = []
        rd, wr = resume(self.bfm.read), resume(self.bfm.write)

        def word(addr: int) -> int:
            if addr & 3 or not EMC_BASE <= addr < EMC_BASE + (4 << AW):
                raise ValueError(f"address {addr:#010x} is not a word of the EMC CS0 window")
            return (addr - EMC_BASE) >> 2

        def cb_rd(addr):
            self.reads += 1
            try:
                return rd(word(addr))
            except Exception as e:           # ctypes would swallow it: keep it for the test
                self.errors.append(f"read {addr:#x}: {e!r}")
                return 0

        def cb_wr(addr, value):
            try:
                self.writes.append((word(addr), value))
                wr(word(addr), value)
            except Exception as e:
                self.errors.append(f"write {addr:#x}: {e!r}")

        self._cbs = (RD_FN(cb_rd), WR_FN(cb_wr))      # keep the callbacks alive
        self.lib.empc_host_set_bus(*self._cbs)
        for f in ("empc_host_global_addr", "empc_host_axis_addr", "empc_host_coef_addr"):
            getattr(self.lib, f).restype = ctypes.c_uint32
        n = ctypes.c_uint32.in_dll(self.lib, "empc_host_nregs").value
        self.regs = list((HostReg * n).in_dll(self.lib, "empc_host_regs"))
        self.macros = header.read(_roms() / "empc_formats.vh")

    def addr(self, r: HostReg) -> int:
        return self.lib.empc_host_axis_addr(0, r.ofs) if r.axis_block else self.lib.empc_host_global_addr(r.ofs)

    def reg(self, name: str) -> HostReg:
        return next(r for r in self.regs if r.name.decode() == name)

    async def read(self, name: str) -> int:
        return await self.bfm.read((self.addr(self.reg(name)) - EMC_BASE) >> 2)

    async def write(self, name: str, value: int) -> None:
        await self.bfm.write((self.addr(self.reg(name)) - EMC_BASE) >> 2, value)

    async def call(self, fname: str, *args) -> int:
        fn = getattr(self.lib, fname)

        def blocking():                      # runs in a bridge thread; the bus callbacks resume the sim
            return fn(*args)
        blocking.__qualname__ = fname
        rc = await bridge(blocking)()
        assert not self.errors, self.errors
        return rc

    async def start(self):
        d = self.dut
        cocotb.start_soon(Clock(d.clk, 10, unit="ns").start())
        d.rst_n.value = 0
        d.enc_target.value = 0
        d.idx_enable.value = 0
        d.mark.value = 0
        d.enc_glitch.value = 0
        d.hall.value = 0b001
        d.pwr_fault_n.value = 1
        for i in range(3):
            getattr(d, f"adc_code{i}").value = self.macros["ADC_OFFSET"]
            getattr(d, f"adc_amp{i}").value = 0          # tb/hdl/adc_ripple.v: no ripple, no noise
        d.adc_seed.value = 0
        d.adc_noise.value = 0
        d.adc_inj_en.value = 0
        d.adc_hold.value = 0
        d.adc_lead.value = 0
        self.bfm.idle()
        await ClockCycles(d.clk, 20)
        d.rst_n.value = 1
        await ClockCycles(d.clk, 200)

    async def start_driver(self) -> "Caps":
        """start(), then empc_init: the capabilities it read."""
        await self.start()
        caps = Caps()
        assert await self.call("empc_init", ctypes.byref(caps)) == EMPC_OK
        return caps


def reg_legal_word(reg) -> int:
    """A word whose every field is a legal value (the middle of each legal range; random bits elsewhere)."""
    v = 0x5A5A5A5A
    for f in reg.parts():
        v &= ~f.mask
        x = sorted(f.legal)[len(f.legal) // 2] if f.legal is not None else 0x5A5A5A5A >> f.lsb
        v |= (x & ((1 << f.width) - 1)) << f.lsb
    return v & 0xFFFFFFFF


@cocotb.test()
async def registers_vs_header(dut):
    env = Env(dut)
    await env.start()
    names = {(r.axis_block, r.name.decode()) for r in env.regs}
    assert names == {(0, r.name) for r in regmap.GLOBAL} | {(1, r.name) for r in regmap.AXIS}, \
        "the header's register table is not the map's"
    by_name = {r.name: r for r in regmap.GLOBAL + regmap.AXIS}
    n_reset = n_rw = n_refused = 0
    # a build without out_route (CAPS.route = 0) locks the routing registers (guard route_locked) for good
    caps_reg = by_name["CAPS"]
    caps = await env.bfm.read(caps_reg.offset)
    routes = (caps >> next(f.lsb for f in caps_reg.fields if f.name == "route")) & 1
    for r in env.regs:
        name = r.name.decode()
        w = (env.addr(r) - EMC_BASE) >> 2
        v = await env.bfm.read(w)
        if name == "IRQ_STATUS":        # the DC-link fault latched at reset (UDC resets to 0: missing) raises it
            v &= ~(1 << next(f.lsb for f in by_name[name].fields if f.name == "fault"))
        assert v & r.reset_mask == r.reset, f"{name} @word {w:#x}: {v:#x} after reset, header {r.reset:#x}"
        if r.access != 0 and r.reset_mask != 0xFFFFFFFF:           # build-dependent fields: the build's
            want = by_name[name].reset_word(env.macros)
            assert v == want, f"{name}: {v:#x} after reset, build value {want:#x}"
        n_reset += 1
        if r.access == 1 and name != "CTRL":                      # RW (CTRL would switch the bridges on)
            reg = by_name[name]
            for pat in (0xFFFFFFFF, 0xA5A5A5A5 ^ (w * 0x9E3779B1 & 0xFFFFFFFF), reg_legal_word(reg)):
                for unlocked in ((False, True) if reg.unlock else (False,)):
                    if unlocked:                                   # the key arms the next write
                        await env.bfm.write(w & ~0xFF | by_name[reg.unlock].offset, by_name[reg.unlock].key)
                    before = await env.bfm.read(w)
                    await env.bfm.write(w, pat)
                    got = await env.bfm.read(w)
                    exp = pat & r.bits
                    if r.sign and exp & (r.bits + 1) >> 1:
                        exp |= ~r.bits & 0xFFFFFFFF
                    locked = reg.guard == "route_locked" and not routes
                    if not reg.accepts(pat, live=locked, unlocked=unlocked):   # refused: unchanged (legal, unlock, lock)
                        exp = before
                        n_refused += 1
                    assert got == exp, f"{name}: wrote {pat:#x}, read {got:#x}, header/map say {exp:#x}"
            if reg.unlock:
                await env.bfm.write(w & ~0xFF | by_name[reg.unlock].offset, by_name[reg.unlock].key)
            await env.bfm.write(w, v)
            assert await env.bfm.read(w) == v, f"{name}: not restored"
            n_rw += 1
    dut._log.info("%d registers of fw/empc_regs.h read their reset value over the bus, %d RW registers "
                  "read back three patterns in their _BITS (%d writes refused as the map says: legal values, "
                  "unlock)", n_reset, n_rw, n_refused)
    assert n_refused > 10
    rep = ROOT / "build" / "reports"
    rep.mkdir(parents=True, exist_ok=True)
    (rep / "empc_drv.json").write_text(json.dumps(
        {"registers_reset_checked": n_reset, "rw_registers_patterns": n_rw, "writes_refused_as_the_map_says": n_refused},
        indent=1) + "\n")
    assert n_reset == len(regmap.GLOBAL) + len(regmap.AXIS) and n_rw > 20


@cocotb.test()
async def driver_flow(dut):
    env = Env(dut)
    caps = await env.start_driver()
    m = env.macros
    assert (caps.version, caps.naxes, caps.horizon, caps.img_layout, caps.pwm_per_control, caps.pwm_half,
            caps.complementary) == (regmap.VERSION, 1, m["N"], image.LAYOUT, m["PWM_PER_CONTROL"],
                                    m["PWM_HALF_PERIOD"], 0)
    # out of the build limits: the driver refuses before writing anything
    n0 = len(env.writes)
    for bad in (dict(dead_time=regmap.DEAD_TIME_MIN - 1), dict(oc_thresh=regmap.OC_THRESH_MAX + 1),
                dict(udc_min_mv=0), dict(udc_max_mv=regmap.UDC_LEGAL_MAX + 1),
                dict(fault_mask=1 << len(regmap.FAULT_CAUSES))):
        kw = dict(pwm_per_control=0, dead_time=40, fault_mask=0x7F, kdc=0x10000, udc_mv=UDC_MV, udc_min_mv=UDC_MIN_MV,
                  udc_max_mv=UDC_MAX_MV, oc_thresh=1500, angle_cal=0x1234, hall_offset=0x4321)
        kw.update(bad)
        assert await env.call("empc_axis_config", ctypes.byref(caps), 0, ctypes.byref(AxisCfg(**kw))) == \
            EMPC_ERR_ARG, bad
    assert len(env.writes) == n0
    # an axis this bitstream does not have (axis 1 of a one-axis build, the map's last axis, 15: axis 0's
    # coefficient window, 0xFFFFFFFF) or a DC link past UDC's 20 bits: refused before any bus access
    # (an access would address another axis's registers, the global registers or nothing)
    n0, r0 = len(env.writes), env.reads
    one = (ctypes.c_uint32 * 16)(*range(16))
    st_bad = Status()
    for ax in (caps.naxes, regmap.ROUTE_AXES - 1, 15, 0xFFFFFFFF):
        for fn, args in (("empc_axis_config", (ctypes.byref(AxisCfg(pwm_per_control=0, dead_time=40)),)),
                         ("empc_axis_enable", (0, 0)), ("empc_coef_load", (one, 16, 1)),
                         ("empc_fault_clear", (None,)), ("empc_status_read", (ctypes.byref(st_bad),)),
                         ("empc_udc_write", (UDC_MV,))):
            assert await env.call(fn, ctypes.byref(caps), ctypes.c_uint32(ax), *args) == EMPC_ERR_ARG, (fn, ax)
    assert await env.call("empc_udc_write", ctypes.byref(caps), 0, 1 << 20) == EMPC_ERR_ARG
    assert await env.call("empc_fault_clear", None, 0, None) == EMPC_ERR_ARG
    assert (len(env.writes), env.reads) == (n0, r0), "a refused call touched the bus"
    cfg = AxisCfg(pwm_per_control=0, dead_time=40, fault_mask=0x7F, kdc=0x10000, udc_mv=UDC_MV,
                  udc_min_mv=UDC_MIN_MV, udc_max_mv=UDC_MAX_MV, oc_thresh=1500, angle_cal=0x1234, hall_offset=0x4321)
    assert await env.call("empc_axis_config", ctypes.byref(caps), 0, ctypes.byref(cfg)) == EMPC_OK
    want = {"DEAD_TIME": 40, "FAULT_MASK": 0x7F, "KDC": 0x10000, "UDC": UDC_MV, "UDC_MIN": UDC_MIN_MV,
            "UDC_MAX": UDC_MAX_MV, "OC_THRESH": 1500, "ANGLE_CAL": 0x1234, "HALL_OFFSET": 0x4321,
            "CTRL": m["PWM_PER_CONTROL"] << 8}
    got = {n: await env.read(n) for n in want}
    assert got == want, got
    # FAULT_MASK went through the unlock: a plain write is refused and counted
    ref0 = await env.read("CNT_WR_REFUSED")
    await env.write("FAULT_MASK", 0)
    assert await env.read("FAULT_MASK") == 0x7F and await env.read("CNT_WR_REFUSED") == ref0 + 1
    assert (await env.read("STATUS")) >> regmap.axis_reg("STATUS").fields[12].lsb & 1
    assert await env.call("empc_fault_clear", ctypes.byref(caps), 0, None) == EMPC_OK      # UDC was 0 (missing) until the config
    # bridges on: the driver refuses to change the configuration
    assert await env.call("empc_axis_enable", ctypes.byref(caps), 0, 1, 0) == EMPC_OK
    await ClockCycles(dut.clk, 2 * m["PWM_HALF_PERIOD"] + 10)        # the outputs start at a period boundary
    assert (await env.read("STATUS")) >> 1 & 1, "bridges did not come on"
    assert await env.call("empc_axis_config", ctypes.byref(caps), 0, ctypes.byref(cfg)) == EMPC_ERR_BUSY
    # the FPGA refuses too, whatever the driver does: a safety register written with the bridges live
    await env.write("DEAD_TIME", 99)
    assert await env.read("DEAD_TIME") == 40
    assert await env.call("empc_wdog_set", 100) == EMPC_ERR_REFUSED          # an axis is live
    assert await env.call("empc_axis_enable", ctypes.byref(caps), 0, 0, 0) == EMPC_OK
    assert not (await env.read("STATUS")) >> 1 & 1
    # coefficient image: another design into the inactive bank, then the swap
    words = image.read_hex(_roms() / "coef_alg1_speed.hex")[:image.USED]
    params = image.decode(words + [0] * (1024 - image.USED))
    st0 = await env.read("STATUS")
    n0 = len(env.writes)
    arr = (ctypes.c_uint32 * len(words))(*words)
    # the swap is decided at the PWM boundary before the next control sample (up to pwm_per_control PWM periods)
    polls = 4 * m["PWM_PER_CONTROL"] * m["PWM_HALF_PERIOD"]
    # the same image designed for another control period (CFG[23:16]): refused by the driver, nothing written
    assert image.period(words) == m["PWM_PER_CONTROL"]
    other = image.with_period(words, 1 if m["PWM_PER_CONTROL"] != 1 else 2)
    oarr = (ctypes.c_uint32 * len(other))(*other)
    assert await env.call("empc_coef_load", ctypes.byref(caps), 0, oarr, len(other), polls) == EMPC_ERR_PERIOD
    assert not [a for a, _ in env.writes[n0:] if a >= regmap.COEF_BASE], "a refused image was written"
    assert await env.call("empc_coef_load", ctypes.byref(caps), 0, arr, len(words), polls) == EMPC_OK
    coef_w = [(a, v) for a, v in env.writes[n0:] if a >= regmap.COEF_BASE]
    assert coef_w == [(regmap.COEF_BASE + i, v) for i, v in enumerate(words)], "window writes are not the image"
    st1 = await env.read("STATUS")
    assert (st1 >> 6 & 1) != (st0 >> 6 & 1) and not st1 >> 7 & 1, (st0, st1)
    mem = dut.u_top.g_axis[0].u_axis.u_core.u_mem
    assert (int(mem.ncols.value), int(mem.pos.value), int(mem.alg2.value)) == \
        (params.ncols, int(params.task == "position"), int(params.algorithm == 2)), "active bank is not the image"
    # status snapshot
    st = Status()
    assert await env.call("empc_status_read", ctypes.byref(caps), 0, ctypes.byref(st)) == EMPC_OK
    plain = {n: await env.read(n) for n in ("STATUS", "FAULT", "THETA", "LATENCY")}
    assert (st.status, st.fault, st.theta, st.latency) == tuple(plain.values())
    # watchdog: 0 (off) is out of the build limits; through the unlock with every axis off it takes a value
    assert await env.call("empc_wdog_set", 0) == EMPC_ERR_ARG
    await env.write("WDOG_TIMEOUT", 1)                                       # without the unlock: refused
    ref0 = await env.read("CNT_WR_REFUSED")
    await env.write("WDOG_TIMEOUT", 2)                                       # counted by the axes too
    assert await env.read("WDOG_TIMEOUT") == 400 and await env.read("CNT_WR_REFUSED") == ref0 + 1
    # watchdog fault: expires after one PWM period, the clear reports the cause until the kick
    assert await env.call("empc_wdog_set", 1) == EMPC_OK
    assert await env.call("empc_udc_write", ctypes.byref(caps), 0, UDC_MV) == EMPC_OK
    await ClockCycles(dut.clk, 4 * 2 * m["PWM_HALF_PERIOD"])
    fault_bit = 1 << regmap.AXIS[3].fields[3].lsb
    assert regmap.AXIS[3].fields[3].name == "watchdog"
    rem = ctypes.c_uint32(0)
    assert await env.call("empc_fault_clear", ctypes.byref(caps), 0, ctypes.byref(rem)) == EMPC_ERR_FAULT
    assert rem.value & fault_bit, rem.value
    await env.call("empc_wdog_kick")
    assert await env.call("empc_fault_clear", ctypes.byref(caps), 0, ctypes.byref(rem)) == EMPC_OK and rem.value == 0
    assert await env.call("empc_wdog_set", 400) == EMPC_OK
    dut._log.info("driver: init, config (+ refused with bridges on), %d-word image uploaded and swapped "
                  "(ncols %d, %s), status, watchdog fault reported and cleared; %d bus writes by the C code",
                  len(words), params.ncols, params.task, len(env.writes))


def _field(reg: str, name: str):
    return next(f for f in regmap.axis_reg(reg).parts() if f.name == name)


def _get(reg: str, name: str, word: int) -> int:
    f = _field(reg, name)
    return (word >> f.lsb) & ((1 << f.width) - 1)


@cocotb.test()
async def design_load_kacc(dut):
    """empc_design_load writes the design's KACC with its image, and never while the law runs."""
    env = Env(dut)
    caps = await env.start_driver()
    m = env.macros
    # the build's configuration at a control period of one PWM period: another Ts, so every design's KACC differs
    # from the boot design's, and three of the four (speed window 8) differ from alg1_speed's (window 1)
    man0 = json.loads((_roms() / "manifest.json").read_text())
    base = config.load(ROOT / man0["config"])
    cfg = config.load(ROOT / man0["config"], {"control.Ts": 1 / base.inverter.f_pwm})
    out = Path(tempfile.mkdtemp(prefix="design_load_", dir=ROOT / "build"))
    man = roms.generate(cfg, out, all_designs=True, force=True)
    assert man["header_constants"]["IMG_FMT_ID"] == m["IMG_FMT_ID"], "another build's format"
    ppc = man["header_constants"]["PWM_PER_CONTROL"]
    assert ppc == 1 != m["PWM_PER_CONTROL"]
    des = {d: (image.read_hex(out / v["file"])[:image.USED], v["kacc"]) for d, v in man["designs"].items()}
    shutil.rmtree(out, ignore_errors=True)
    polls = 4 * ppc * m["PWM_HALF_PERIOD"]
    kacc_w = regmap.AXIS_BASE + regmap.axis_reg("KACC").offset
    coef_written = lambda n0: [a for a, _ in env.writes[n0:] if a >= regmap.COEF_BASE]   # noqa: E731

    async def load(d, words=None, kacc=None):
        w, k = des[d]
        w = words or w
        arr = (ctypes.c_uint32 * len(w))(*w)
        return await env.call("empc_design_load", ctypes.byref(caps), 0, arr, len(w),
                              ctypes.c_uint32(k["word"] if kacc is None else kacc), polls)

    def same_fields(word, k):           # the register's fields read back = the manifest's (kacc signed 18 bit)
        kf = _field("KACC", "kacc")
        got = {f.name: _get("KACC", f.name, word) for f in regmap.axis_reg("KACC").parts()}
        got["kacc"] -= (got["kacc"] >> (kf.width - 1)) << kf.width
        return got == {n: k[n] for n in got}

    boot = regmap.axis_reg("KACC").reset_word(m)
    assert await env.read("KACC") == boot
    assert all(k["word"] != boot for _, k in des.values())
    cfg_ax = AxisCfg(pwm_per_control=ppc, dead_time=40, fault_mask=0x7F, kdc=0x10000, udc_mv=UDC_MV,
                     udc_min_mv=UDC_MIN_MV, udc_max_mv=UDC_MAX_MV, oc_thresh=1500, angle_cal=0, hall_offset=0)
    assert await env.call("empc_axis_config", ctypes.byref(caps), 0, ctypes.byref(cfg_ax)) == EMPC_OK
    # a KACC word the sequencer would not run as written: refused before any bus access
    n0, r0 = len(env.writes), env.reads
    k1 = des["alg1_position"][1]["word"]
    wf, lf = _field("KACC", "win"), _field("KACC", "load_shift")
    for bad in (k1 | 1 << 22, k1 | 7 << wf.lsb, (k1 & ~lf.mask) | 1 << lf.lsb):
        assert await load("alg1_position", kacc=bad) == EMPC_ERR_ARG, hex(bad)
    assert (len(env.writes), env.reads) == (n0, r0), "a refused call touched the bus"
    # law off (bridges off): KACC written bit-exact to the manifest's fields, then the image swapped
    st0 = await env.read("STATUS")
    assert await load("alg1_speed") == EMPC_OK
    got = await env.read("KACC")
    assert got == des["alg1_speed"][1]["word"] and same_fields(got, des["alg1_speed"][1]), (hex(got), des["alg1_speed"][1])
    st1 = await env.read("STATUS")
    assert _get("STATUS", "coef_bank", st1) != _get("STATUS", "coef_bank", st0)
    # the law running: a design with another KACC is refused, nothing written (KACC, window, bank unchanged)
    assert await env.call("empc_udc_write", ctypes.byref(caps), 0, UDC_MV) == EMPC_OK
    rem = ctypes.c_uint32(0)
    assert await env.call("empc_fault_clear", ctypes.byref(caps), 0, ctypes.byref(rem)) == EMPC_OK, hex(rem.value)
    assert await env.call("empc_axis_enable", ctypes.byref(caps), 0, 1, 1) == EMPC_OK
    await ClockCycles(dut.clk, 6 * m["PWM_HALF_PERIOD"])
    st1 = await env.read("STATUS")
    assert _get("STATUS", "running", st1), f"law not running: STATUS {st1:#x}, FAULT {await env.read('FAULT'):#x}"
    n0 = len(env.writes)
    assert await load("alg1_position") == EMPC_ERR_BUSY
    assert env.writes[n0:] == [], f"refused load wrote {env.writes[n0:]}"
    st2 = await env.read("STATUS")
    assert await env.read("KACC") == got and _get("STATUS", "coef_bank", st2) == _get("STATUS", "coef_bank", st1)
    # ... the same KACC while running: the image alone (KACC not written), swapped
    n0 = len(env.writes)
    assert await load("alg1_speed") == EMPC_OK
    assert kacc_w not in [a for a, _ in env.writes[n0:]] and len(coef_written(n0)) == image.USED
    st3 = await env.read("STATUS")
    assert _get("STATUS", "coef_bank", st3) != _get("STATUS", "coef_bank", st2) and _get("STATUS", "running", st3)
    # law off, bridges on (zero voltage): the other design with its KACC
    assert await env.call("empc_axis_enable", ctypes.byref(caps), 0, 1, 0) == EMPC_OK
    await ClockCycles(dut.clk, 2 * m["PWM_HALF_PERIOD"])
    # an image the FPGA refuses at the swap (incomplete: its first words only): the old KACC is written back,
    # the old bank stays
    w, k = des["alg1_position"]
    n0 = len(env.writes)
    assert await load("alg1_position", words=w[:image.A_CFG + 1]) == EMPC_ERR_REFUSED
    assert [v for a, v in env.writes[n0:] if a == kacc_w] == [k["word"], got], "KACC not restored after the refusal"
    st4 = await env.read("STATUS")
    assert await env.read("KACC") == got and _get("STATUS", "coef_bank", st4) == _get("STATUS", "coef_bank", st3)
    assert await load("alg1_position") == EMPC_OK
    got = await env.read("KACC")
    assert got == k["word"] and same_fields(got, k), (hex(got), k)
    assert _get("KACC", "win", got) == k["win"] == 3
    mem = dut.u_top.g_axis[0].u_axis.u_core.u_mem
    p = image.decode(w + [0] * (image.DEPTH - image.USED))
    assert (int(mem.ncols.value), int(mem.pos.value), int(mem.alg2.value)) == (p.ncols, 1, 0), "active bank"
    assert await env.call("empc_axis_enable", ctypes.byref(caps), 0, 0, 0) == EMPC_OK
    dut._log.info("design_load: KACC %#x -> %#x (alg1_speed) -> %#x (alg1_position, window %d) read back; "
                  "refused while running, restored after a refused swap", boot, des["alg1_speed"][1]["word"],
                  got, k["speed_window"])


@cocotb.test()
async def fault_during_design_load(dut):
    """A power-stage fault in the middle of a design load, then one clear: the law restarts on a whole bank."""
    env = Env(dut)
    caps = await env.start_driver()
    m = env.macros
    man = json.loads((_roms() / "manifest.json").read_text())
    boot = f"alg{man['boot']['algorithm']}_{man['boot']['task']}"
    new = next(d for d in ("alg2_position", "alg1_position", "alg2_speed") if d in man["designs"])
    des = {d: (image.read_hex(_roms() / v["file"])[:image.USED], v["kacc"]) for d, v in man["designs"].items()}
    assert des[new][1]["word"] == await env.read("KACC"), "the same KACC: the image alone while running"
    mem = dut.u_top.g_axis[0].u_axis.u_core.u_mem

    dut.adc_seed.value, dut.adc_noise.value = 0x5EED, 3   # +-3 LSB: a live ADC (a constant one trips adc_frozen)
    dut._log.info("ADC noise seed %#x", 0x5EED)

    def decoded():                      # the active bank's decoded configuration (mpc_coef_mem)
        return int(mem.ncols.value), int(mem.pos.value), int(mem.alg2.value)

    def want(d):
        p = image.decode(des[d][0] + [0] * (image.DEPTH - image.USED))
        return p.ncols, int(p.task == "position"), int(p.algorithm == 2)
    assert want(new) != want(boot) and decoded() == want(boot)
    ppc = m["PWM_PER_CONTROL"]
    polls = 4 * ppc * m["PWM_HALF_PERIOD"]
    cfg_ax = AxisCfg(pwm_per_control=ppc, dead_time=40, fault_mask=0x7F, kdc=0x10000, udc_mv=UDC_MV,
                     udc_min_mv=UDC_MIN_MV, udc_max_mv=UDC_MAX_MV, oc_thresh=1500, angle_cal=0, hall_offset=0)
    assert await env.call("empc_axis_config", ctypes.byref(caps), 0, ctypes.byref(cfg_ax)) == EMPC_OK
    rem = ctypes.c_uint32(0)

    async def run_law():
        assert await env.call("empc_udc_write", ctypes.byref(caps), 0, UDC_MV) == EMPC_OK
        assert await env.call("empc_fault_clear", ctypes.byref(caps), 0, ctypes.byref(rem)) == EMPC_OK, hex(rem.value)
        assert await env.call("empc_axis_enable", ctypes.byref(caps), 0, 1, 1) == EMPC_OK
        await ClockCycles(dut.clk, 6 * m["PWM_HALF_PERIOD"])
        st = await env.read("STATUS")
        assert _get("STATUS", "running", st), f"law not running: STATUS {st:#x}, FAULT {await env.read('FAULT'):#x}"
        assert int(dut.pwm_en.value) == 0b111, "bridges not on"
        return st
    st0 = await run_law()
    n0 = len(env.writes)
    half = n0 + image.USED // 2
    off_at: list[int] = []

    async def pull_pin():               # the pin low once half the image is written; the bridges must follow
        while len([a for a, _ in env.writes[n0:] if a >= regmap.COEF_BASE]) < image.USED // 2:
            await ClockCycles(dut.clk, 1)
        dut.pwr_fault_n.value = 0
        for n in range(64):
            await ClockCycles(dut.clk, 1)
            if int(dut.pwm_en.value) == 0:
                off_at.append(n + 1)
                return
    task = cocotb.start_soon(pull_pin())
    w, k = des[new]
    arr = (ctypes.c_uint32 * len(w))(*w)
    rc = await env.call("empc_design_load", ctypes.byref(caps), 0, arr, len(w), ctypes.c_uint32(k["word"]), polls)
    await task
    assert len(env.writes) > half and off_at, f"bridges still on 64 clocks after the fault pin ({off_at})"
    fault = await env.read("FAULT")
    st1 = await env.read("STATUS")
    pst = next(f for f in regmap.FAULT_CAUSES if f.name == "pstage")
    assert fault >> pst.lsb & 1, hex(fault)
    assert not _get("STATUS", "running", st1) and int(dut.pwm_en.value) == 0
    swapped = _get("STATUS", "coef_bank", st1) != _get("STATUS", "coef_bank", st0)
    assert (rc == EMPC_OK) == swapped, (rc, hex(st0), hex(st1))
    assert decoded() == want(new if swapped else boot), (rc, decoded())
    # the cause present: the clear reports it and the bridges stay off
    assert await env.call("empc_fault_clear", ctypes.byref(caps), 0, ctypes.byref(rem)) == EMPC_ERR_FAULT
    assert rem.value >> pst.lsb & 1 and int(dut.pwm_en.value) == 0, (hex(rem.value), hex(fault))
    dut.pwr_fault_n.value = 1
    await ClockCycles(dut.clk, 4 * m["PWM_HALF_PERIOD"])
    st2 = await run_law()                # one clear, then the law runs again on the active bank
    assert await env.read("FAULT") == 0 and decoded() == want(new if swapped else boot)
    if not swapped:                      # the refused load leaves the axis ready for the same load
        assert await env.call("empc_design_load", ctypes.byref(caps), 0, arr, len(w), ctypes.c_uint32(k["word"]),
                              polls) == EMPC_OK
        assert decoded() == want(new) and _get("STATUS", "running", await env.read("STATUS"))
    assert await env.call("empc_axis_enable", ctypes.byref(caps), 0, 0, 0) == EMPC_OK
    dut._log.info("fault during design load: bridges off %d clocks after the pin, load rc %d (%s), STATUS %#x -> "
                  "%#x -> %#x, FAULT %#x, restarted on %s", off_at[0], rc, "swapped" if swapped else "not swapped",
                  st0, st1, st2, fault, new)


def test_empc_drv():
    import fw_build
    from runner import BUILD, run
    lib = fw_build.build_host_lib(BUILD / "fw")
    run(toplevel="cosim_top", test_module="test_empc_drv", name="test_empc_drv",
        extra_env={"EMPC_HOST_LIB": str(lib)})
