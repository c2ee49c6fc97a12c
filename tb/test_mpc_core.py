"""mpc_core: bit-exact against gen/empc/rtlmodel/mpc_core.py, bank protocol, latency, float-law error.

pytest entries:
  test_mpc_core          Icarus, ports driven directly: boot, a few hundred vectors over the 4 generated
                         images (inputs written through the input buffer, garbage in the words the core
                         must not read; CPU upload + atomic swap during an update), latency, handshake.
  test_mpc_core_stream   Verilator, tb/hdl/mpc_core_stream.v: >= 100k random vectors per generated image
                         plus corner cases plus random (out-of-range) images, compared with the model.
  test_input_words       the input-buffer word map: header EMPC_IN_* == model IN_*, core.input_words.
  test_batch_model       the numpy twin used for the stream comparison == the scalar model.
  test_float_error       core (model) du vs. the float law with exact gains, bound relative to u_max.
Seed: EMPC_SEED (default 4242); vector count per image in the stream test: EMPC_MPC_VECTORS (100000).
"""
from __future__ import annotations

import json
import os
import random
import time
from pathlib import Path

import numpy as np
import pytest

import mpc_core_vectors as V
from files import roms_dir
from empc import image
from empc.formats import sat, wrap
from empc.rtlmodel import mpc_core as core

ROOT = Path(__file__).resolve().parents[1]
SEED = int(os.environ.get("EMPC_SEED", "4242"))
N_STREAM = int(os.environ.get("EMPC_MPC_VECTORS", "100000"))
IMAGES = ("alg1_speed", "alg1_position", "alg2_speed", "alg2_position")
LAT_BASE = core.LATENCY_BASE
SW, UW, OPW = core.SIG_W, 24, 18


def roms() -> Path:
    return roms_dir()


def load_image(name: str) -> list[int]:
    return image.read_hex(roms() / f"coef_{name}.hex")


def header_consts() -> dict:
    from empc import header
    return header.read(roms() / "empc_formats.vh")


def header_n() -> int:
    return header_consts()["N"]


def header_ppc() -> int:
    """CTRL.pwm_per_control after reset = the control period of the build's images (CFG[23:16])."""
    return header_consts()["PWM_PER_CONTROL"]


# the axis rides above the word address: in_addr = {axis, word}, cfg_addr = {axis, image word}
IN_AW = (core.IN_WORDS - 1).bit_length()
IMG_AW = (image.DEPTH - 1).bit_length()


# ============================================================================ cocotb (Icarus, ports)
def _u(v: int, w: int) -> int:
    return v & ((1 << w) - 1)


def _pack(vals, w: int) -> int:
    out = 0
    for k, v in enumerate(vals):
        out |= _u(int(v), w) << (k * w)
    return out


def _unpack(v: int, n: int, w: int) -> list[int]:
    return [wrap(v >> (k * w), w) for k in range(n)]


def input_words(x: dict, i: int, N: int) -> dict[int, int]:
    """Input-buffer words of vector i (the model's word map, core.input_words)."""
    return core.input_words(V.to_inputs(x, i), N)


async def write_inputs(dut, words: dict[int, int], RisingEdge, axis: int = 0) -> None:
    """Write the words through in_we / in_addr = {axis, word} / in_wdata, one per clock (ends after the
    last write edge)."""
    for a, v in words.items():
        dut.in_we.value = 1
        dut.in_addr.value = (axis << IN_AW) | a
        dut.in_wdata.value = _u(int(v), SW)
        await RisingEdge(dut.clk)
    dut.in_we.value = 0


def unused_words(rng, N: int) -> dict[int, int]:
    """Garbage for the buffer words the core must not read (14, 15 and beyond wref[N])."""
    hi = 1 << (SW - 1)
    addrs = [a for a in range(core.IN_WORDS) if a in (14, 15) or a >= core.IN_WREF + 3 * (N + 1)]
    return {a: int(rng.integers(-hi, hi)) for a in addrs}


def read_out(dut) -> dict:
    return {"u": _unpack(int(dut.u.value), 2, UW), "du": _unpack(int(dut.du.value), 2, UW),
            "u_raw": _unpack(int(dut.u_raw.value), 2, UW), "ebar": _unpack(int(dut.ebar.value), 3, SW),
            "wn": wrap(int(dut.wn.value), OPW), "flags": int(dut.flags.value),
            "fw": (int(dut.fw_hi.value), int(dut.fw_lo.value))}


def _mismatch(got: dict, exp: dict) -> str | None:
    for k in exp:
        if got[k] != exp[k]:
            return f"{k}: dut {got[k]} model {exp[k]}"
    return None


async def reset_core(dut, RisingEdge, ReadOnly, limit: int, swap_at: int = 0) -> int:
    """Three clocks of reset with every input idle, then the clocks until ready (boot streamed); returns
    that count, in the ReadOnly phase of the clock where ready rose."""
    dut.rst.value = 1
    for name in ("start", "cfg_we", "cfg_swap", "in_we", "fw_thr", "aw", "cfg_addr", "cfg_wdata", "in_addr",
                 "in_wdata"):
        getattr(dut, name).value = 0
    dut.swap_at.value = swap_at
    per_w = image.CFG_PERIOD_BITS
    dut.pwm_per_control.value = sum(header_ppc() << (per_w * a) for a in range(len(dut.pwm_per_control) // per_w))
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.rst.value = 0
    n = 0
    while True:
        await RisingEdge(dut.clk)
        n += 1
        await ReadOnly()
        if int(dut.ready.value):
            return n
        assert n < limit, "ready never rose"


class Bench:
    def __init__(self, dut):
        from cocotb.triggers import RisingEdge, ReadOnly
        self.dut, self.RisingEdge, self.ReadOnly = dut, RisingEdge, ReadOnly
        self.N = header_n()
        self.rng = np.random.default_rng(SEED + 7)
        self.boundary_always = True      # swap_at = 1 every clock: a swap is decided at the first idle edge
        self.fw_seen = set()
        self.aw_seen = set()
        # the axis the bench drives (cfg_addr / in_addr top bits, one-hot start, cfg_swap, swap_at)
        self.NA = int(os.environ.get("EMPC_NAXES", "1"))
        self.ax = int(os.environ.get("EMPC_IMG_AXIS", "0"))
        self.sel = 1 << self.ax

    def bit(self, name: str) -> int:
        """The bench axis's bit of a per-axis output."""
        return (int(getattr(self.dut, name).value) >> self.ax) & 1

    async def reset(self) -> int:
        return await reset_core(self.dut, self.RisingEdge, self.ReadOnly, 5000,
                                swap_at=self.sel if self.boundary_always else 0)

    async def write_image(self, words: list[int], during=None) -> None:
        dut = self.dut
        await self.RisingEdge(dut.clk)
        for a in range(image.USED):
            dut.cfg_we.value = 1
            dut.cfg_addr.value = (self.ax << IMG_AW) | a
            dut.cfg_wdata.value = words[a]
            await self.RisingEdge(dut.clk)
        dut.cfg_we.value = 0

    async def load(self, x: dict, i: int, garbage: bool = True) -> None:
        """Write vector i into the input buffer (and garbage into the words the core must not read)."""
        await self.RisingEdge(self.dut.clk)
        self.dut.fw_thr.value = 0
        w = input_words(x, i, self.N)
        if garbage:
            w = {**unused_words(self.rng, self.N), **w}
        await write_inputs(self.dut, w, self.RisingEdge, self.ax)

    async def run(self, x: dict, i: int, swap_at: int | None = None, fw_thr=(0, 0), aw: int = 0) -> tuple[dict, int]:
        """Write vector i, pulse start, wait for done; returns outputs and start->done cycles."""
        dut = self.dut
        await self.load(x, i)
        dut.fw_thr.value = fw_thr[0] | (fw_thr[1] << 16)
        dut.aw.value = aw
        dut.start.value = self.sel
        await self.RisingEdge(dut.clk)
        dut.start.value = 0
        n = 1
        while True:
            if swap_at is not None and n == swap_at:
                dut.cfg_swap.value = self.sel
            await self.ReadOnly()
            assert int(dut.busy.value) == 1 or int(dut.done.value) == 1, f"busy low before done (cycle {n})"
            if int(dut.done.value):
                break
            await self.RisingEdge(dut.clk)
            dut.cfg_swap.value = 0
            n += 1
            assert n < 500, "done never came"
        assert int(dut.busy.value) == 0
        return read_out(dut), n


class AxisView:
    """core.MxBanks seen from one axis (the scalar interface of core.Banks)."""

    def __init__(self, mx: core.MxBanks, ax: int):
        self.mx, self.ax = mx, ax

    bank = property(lambda self: self.mx.bank_v[self.ax])
    pending = property(lambda self: self.mx.pending_v[self.ax])
    upl_ok = property(lambda self: self.mx.upl_ok_v[self.ax])
    img_ok = property(lambda self: self.mx.img_ok_v[self.ax])
    swap_refused = property(lambda self: self.mx.swap_refused_v[self.ax])
    refused = property(lambda self: self.mx.refused_v[self.ax])
    boot_ok = property(lambda self: self.mx.boot_ok)

    def active(self) -> core.Params:
        return self.mx.active(self.ax)

    def write(self, addr: int, v: int) -> None:
        self.mx.write(addr, v, self.ax)

    def request(self) -> None:
        self.mx.request(self.ax)

    def boundary(self, in_flight: bool = False):
        return self.mx.boundary(in_flight, self.ax)


class ImgBench(Bench):
    """Bank protocol driver for the image-check tests: every action is mirrored in core.Banks."""

    def __init__(self, dut):
        super().__init__(dut)
        self.boundary_always = False
        h = header_consts()
        self.fmt = h["IMG_FMT_ID"]
        self.m = None
        self.refused_seen = 0
        self.n_vec = 0
        self.rng = np.random.default_rng(SEED + 11)

    async def reset(self) -> int:
        from cocotb.triggers import RisingEdge, ReadOnly
        n = await super().reset()
        await RisingEdge(self.dut.clk)               # leave the ReadOnly phase
        self.mx = core.MxBanks(image.read_hex(Path(os.environ.get("EMPC_BOOT_HEX", roms() / "coef_boot.hex"))),
                               self.N, self.fmt, self.NA, ppc=header_ppc())
        self.ppcs = [header_ppc()] * self.NA
        self.m = AxisView(self.mx, self.ax)
        self.dut._log.info(f"seed {SEED} (EMPC_SEED); NAXES {self.NA}, axis {self.ax}; boot_ok model "
                           f"{self.m.boot_ok} RTL {int(self.dut.boot_ok.value)}")

        async def watch():
            while True:
                await RisingEdge(self.dut.clk)
                await ReadOnly()
                self.refused_seen += self.bit("refused")
                assert int(self.dut.refused.value) & ~self.sel == 0, "another axis refused a swap"
        import cocotb
        cocotb.start_soon(watch())
        return n

    async def idle(self, n: int) -> None:
        for _ in range(n):
            await self.RisingEdge(self.dut.clk)

    async def set_ppc(self, v: int) -> None:
        """CTRL.pwm_per_control of the bench's axis (the core's input; the others keep theirs)."""
        self.ppcs[self.ax] = v
        self.dut.pwm_per_control.value = sum(x << (image.CFG_PERIOD_BITS * a) for a, x in enumerate(self.ppcs))
        await self.RisingEdge(self.dut.clk)
        self.mx.set_ppc(self.ax, v)

    async def upload(self, words) -> None:
        """Write (addr, word) pairs back to back, one per clock."""
        dut = self.dut
        await self.RisingEdge(dut.clk)
        for a, v in words:
            dut.cfg_we.value = 1
            dut.cfg_addr.value = (self.ax << IMG_AW) | a
            dut.cfg_wdata.value = v
            await self.RisingEdge(dut.clk)
            self.m.write(a, v)
        dut.cfg_we.value = 0
        await self.idle(2)                       # the last word leaves the registered port

    async def request(self) -> None:
        dut = self.dut
        dut.cfg_swap.value = self.sel
        await self.RisingEdge(dut.clk)
        dut.cfg_swap.value = 0
        self.m.request()

    async def boundary(self, write=None) -> None:
        """One swap_at pulse with the core idle (optionally a CPU word requested in that clock)."""
        dut = self.dut
        dut.swap_at.value = self.sel
        if write is not None:
            dut.cfg_we.value, dut.cfg_addr.value, dut.cfg_wdata.value = 1, (self.ax << IMG_AW) | write[0], write[1]
        await self.RisingEdge(dut.clk)
        dut.swap_at.value = 0
        dut.cfg_we.value = 0
        self.m.boundary(in_flight=write is not None)
        if write is not None:
            self.m.write(*write)
        await self.idle(2)

    async def request_at_boundary(self) -> None:
        dut = self.dut
        dut.swap_at.value = self.sel
        dut.cfg_swap.value = self.sel
        b0 = self.bit("bank")
        await self.RisingEdge(dut.clk)
        dut.swap_at.value = 0
        dut.cfg_swap.value = 0
        self.m.request()
        self.m.boundary()
        await self.ReadOnly()
        assert self.bit("bank") == self.m.bank and (self.m.bank != b0) == (not self.m.swap_refused), \
            "request in the clock of a boundary: not decided at that edge"
        await self.idle(2)

    async def boundary_during_update(self) -> None:
        dut = self.dut
        x = V.random_inputs(self.rng, 1, self.m.active(), self.N)
        await self.load(x, 0)
        dut.start.value = self.sel
        await self.RisingEdge(dut.clk)
        dut.start.value = 0
        await self.idle(5)
        dut.swap_at.value = self.sel             # busy: not a decision point
        await self.RisingEdge(dut.clk)
        dut.swap_at.value = 0
        while not int(dut.done.value):
            await self.RisingEdge(dut.clk)
            await self.ReadOnly()
        assert _mismatch(read_out(dut), _model_outputs(self.m.active(), x, 0)) is None, "update used the new bank"
        self.n_vec += 1
        await self.idle(2)

    async def compare(self, label: str) -> None:
        await self.ReadOnly()
        d = self.dut
        got = {"bank": self.bit("bank"), "pending": self.bit("swap_pending"), "upl_ok": self.bit("upl_ok"),
               "img_ok": self.bit("img_ok"), "boot_ok": int(d.boot_ok.value), "refused": self.bit("swap_refused"),
               "refused_count": self.refused_seen}
        m = self.m
        exp = {"bank": m.bank, "pending": int(m.pending), "upl_ok": int(m.upl_ok), "img_ok": int(m.img_ok),
               "boot_ok": int(m.boot_ok), "refused": int(m.swap_refused), "refused_count": m.refused}
        assert got == exp, f"{label}: RTL {got} model {exp}"
        # the other axes (NAXES > 1): untouched, as in the model
        vec = lambda v: sum(int(b) << a for a, b in enumerate(v))
        mx = self.mx
        for name, v in (("bank", mx.bank_v), ("swap_pending", mx.pending_v), ("upl_ok", mx.upl_ok_v),
                        ("img_ok", mx.img_ok_v), ("swap_refused", mx.swap_refused_v)):
            assert int(getattr(d, name).value) == vec(v), f"{label}: {name} of the axes {int(getattr(d, name).value):#x}"
        self.dut._log.info(f"{label}: {got}")
        await self.RisingEdge(d.clk)

    async def vectors(self, n: int) -> None:
        p = self.m.active()
        x = V.random_inputs(self.rng, n, p, self.N)
        self.n_vec += await _check_vectors(self, p, x)
        await self.RisingEdge(self.dut.clk)          # leave the ReadOnly phase


class AxBench:
    """Multi-axis driver (NAXES = dut parameter): every action mirrored in core.MxCore."""

    def __init__(self, dut):
        from cocotb.triggers import RisingEdge, ReadOnly
        self.dut, self.RisingEdge, self.ReadOnly = dut, RisingEdge, ReadOnly
        self.NA = int(os.environ["EMPC_NAXES"])
        self.AXB = (self.NA - 1).bit_length()
        h = header_consts()
        self.N, self.fmt = h["N"], h["IMG_FMT_ID"]
        self.rng = np.random.default_rng(SEED + 23)
        self.refused_seen = [0] * self.NA
        self.stats = {"updates": 0, "swaps_ok": 0, "swaps_refused": 0, "uploads": 0, "busy_swaps": 0,
                      "busy_uploads": 0, "busy_inputs": 0, "no_decision": 0}
        self.cpu_busy = False           # a background upload owns cfg_we
        self.up_axis = None             # its axis
        self.good = [load_image(n) for n in IMAGES]

    async def reset(self) -> int:
        dut = self.dut
        n = await reset_core(dut, self.RisingEdge, self.ReadOnly, 10000)
        await self.RisingEdge(dut.clk)
        boot = image.read_hex(roms() / "coef_boot.hex")
        self.m = core.MxCore(boot, self.N, self.fmt, self.NA, ppc=header_ppc())
        dut._log.info(f"seed {SEED} (EMPC_SEED), NAXES {self.NA}: ready {n} cycles after reset")

        async def watch():
            while True:
                await self.RisingEdge(dut.clk)
                await self.ReadOnly()
                r = int(dut.refused.value)
                for a in range(self.NA):
                    self.refused_seen[a] += (r >> a) & 1
        cocotb.start_soon(watch())
        return n

    def bits(self, name: str) -> list[int]:
        v = int(getattr(self.dut, name).value)
        return [(v >> a) & 1 for a in range(self.NA)]

    async def compare(self, label: str) -> None:
        await self.ReadOnly()
        b = self.m.banks
        got = {k: self.bits(k) for k in ("bank", "swap_pending", "upl_ok", "img_ok", "swap_refused", "task_pos")}
        got["boot_ok"] = int(self.dut.boot_ok.value)
        got["refused_count"] = list(self.refused_seen)
        exp = {"bank": b.bank_v, "swap_pending": [int(x) for x in b.pending_v], "upl_ok": [int(x) for x in b.upl_ok_v],
               "img_ok": [int(x) for x in b.img_ok_v], "swap_refused": [int(x) for x in b.swap_refused_v],
               "task_pos": [int(b.active(a).task == "position") for a in range(self.NA)],
               "boot_ok": int(b.boot_ok), "refused_count": list(b.refused_v)}
        assert got == exp, f"{label}: RTL {got} model {exp}"
        await self.RisingEdge(self.dut.clk)

    async def idle(self, n: int) -> None:
        for _ in range(n):
            await self.RisingEdge(self.dut.clk)

    async def write_inputs(self, axis: int, words: dict[int, int]) -> None:
        await write_inputs(self.dut, words, self.RisingEdge, axis)
        for a, v in words.items():
            self.m.write_input(axis, a, int(v))

    def vector_words(self, axis: int) -> dict[int, int]:
        p = self.m.banks.active(axis)
        x = V.random_inputs(self.rng, 1, p, self.N)
        return {**unused_words(self.rng, self.N), **input_words(x, 0, self.N)}

    async def upload(self, axis: int, words) -> None:
        """(addr, word) pairs into axis, one per clock (owns cfg_we until 2 clocks after the last)."""
        dut = self.dut
        self.cpu_busy, self.up_axis = True, axis
        for a, v in words:
            dut.cfg_we.value = 1
            dut.cfg_addr.value = (axis << IMG_AW) | a
            dut.cfg_wdata.value = v
            await self.RisingEdge(dut.clk)
            self.m.banks.write(a, v, axis)
        dut.cfg_we.value = 0
        await self.idle(2)
        self.cpu_busy, self.up_axis = False, None
        self.stats["uploads"] += 1

    def image_for(self, axis: int):
        """A valid image (generated or random) or, one time in four, a corrupted one."""
        r = self.rng.random()
        if r < 0.5:
            w = list(self.good[int(self.rng.integers(0, len(self.good)))])
        else:
            w = list(V.random_image(self.rng, self.N, self.fmt, valid=True, period=header_ppc())[0])
        if self.rng.random() < 0.25:
            w[int(self.rng.integers(0, image.USED))] ^= 1 << int(self.rng.integers(0, 32))
        return list(enumerate(w[:image.USED]))

    async def swap(self, axis: int, busy_axis: int | None = None) -> None:
        """cfg_swap[axis] then a swap_at[axis] pulse (decided there unless axis's own update runs)."""
        dut = self.dut
        dut.cfg_swap.value = 1 << axis
        await self.RisingEdge(dut.clk)
        dut.cfg_swap.value = 0
        self.m.banks.request(axis)
        await self.idle(int(self.rng.integers(0, 4)))
        dut.swap_at.value = 1 << axis
        await self.ReadOnly()
        own_busy = int(dut.busy.value) == 1 and busy_axis == axis
        in_flight = self.up_axis == axis
        await self.RisingEdge(dut.clk)
        dut.swap_at.value = 0
        if own_busy:
            self.stats["no_decision"] += 1
        else:
            r = self.m.banks.boundary(in_flight=in_flight, axis=axis)
            if r is not None:
                self.stats["swaps_ok" if r else "swaps_refused"] += 1
        await self.idle(2)                      # the refused pulse is counted

    async def update(self, axis: int, during=None) -> None:
        """One update of axis (its inputs written first); ``during`` runs while it is busy."""
        dut = self.dut
        await self.write_inputs(axis, self.vector_words(axis))
        thr = (int(self.rng.integers(0, 1 << 16)), int(self.rng.integers(0, 1 << 16)))
        dut.fw_thr.value = thr[0] | (thr[1] << 16)
        exp_o = self.m.start(axis, fw_thr=thr)
        p = self.m.banks.active(axis)
        exp = {**V.outputs_of(exp_o), "fw": (int(exp_o.fw_hi), int(exp_o.fw_lo))}
        dut.start.value = 1 << axis
        await self.RisingEdge(dut.clk)
        dut.start.value = 0
        task = cocotb.start_soon(during()) if during else None
        n = 1
        while True:
            await self.ReadOnly()
            if n == 2:
                assert int(dut.latency.value) == core.latency(p.ncols), "latency port"
            if int(dut.done.value):
                break
            await self.RisingEdge(dut.clk)
            n += 1
            assert n < 500, "done never came"
        assert n == core.latency(p.ncols), f"axis {axis}: latency {n} != {core.latency(p.ncols)}"
        err = _mismatch(read_out(dut), exp)
        assert err is None, f"axis {axis} update {self.stats['updates']}: {err}"
        self.stats["updates"] += 1
        await self.RisingEdge(dut.clk)
        if task is not None:
            await task

    async def run_random(self, n_ops: int) -> None:
        rng = self.rng
        NA = self.NA
        for a in range(NA):                     # every axis from its boot bank
            await self.update(a)
        for k in range(n_ops):
            op = rng.choice(["update", "upload_swap", "swap_busy", "upload_busy", "inputs_busy", "own_busy"],
                            p=[0.3, 0.2, 0.15, 0.15, 0.1, 0.1])
            a = int(rng.integers(0, NA))
            b = int((a + 1 + rng.integers(0, NA - 1)) % NA) if NA > 1 else a
            if op == "update":
                await self.update(a)
            elif op == "upload_swap":            # upload + swap on axis a, then updates of every axis
                await self.upload(a, self.image_for(a))
                await self.swap(a)
            elif op == "swap_busy":              # a swap of axis b while axis a's update runs
                if not self.m.banks.upl_ok_v[b]:
                    await self.upload(b, self.image_for(b))

                async def during():
                    await self.idle(int(rng.integers(1, 20)))
                    await self.swap(b, busy_axis=a)
                await self.update(a, during)
                self.stats["busy_swaps"] += 1
            elif op == "upload_busy":            # an upload into axis b while axis a's updates run
                up = cocotb.start_soon(self.upload(b, self.image_for(b)))
                while not up.done():
                    await self.update(a)
                await up
                self.stats["busy_uploads"] += 1
            elif op == "inputs_busy":            # axis b's input words written during axis a's update
                words = self.vector_words(b)

                async def during():
                    await self.write_inputs(b, words)
                await self.update(a, during)
                self.stats["busy_inputs"] += 1
            else:                                # a boundary of axis a during its own update: no decision
                if not self.m.banks.upl_ok_v[a]:
                    await self.upload(a, self.image_for(a))

                async def during():
                    await self.idle(3)
                    await self.swap(a, busy_axis=a)
                await self.update(a, during)
                if self.m.banks.pending_v[a]:
                    await self.swap(a)           # (request again) decided at the next idle boundary
            await self.compare(f"op {k} {op} a={a} b={b}")
            for x in range(NA):                  # every axis still computes with its own bank
                if rng.random() < 0.5:
                    await self.update(x)
        assert self.stats["swaps_ok"] > 0 and self.stats["swaps_refused"] > 0 and self.stats["no_decision"] > 0
        self.dut._log.info(f"NAXES {NA}: {self.stats}; refused pulses per axis {self.refused_seen}")


def foreign_builds(log) -> list[tuple[str, list[int]]]:
    """Boot images of the other motor configurations (their own fingerprint), generated once."""
    from empc import config, roms as roms_mod
    out = []
    for cfgfile in ("ipmsm_001.toml", "spmsm_002.toml"):
        d = ROOT / "build" / "sim" / f"foreign_{cfgfile.split('.')[0]}"
        f = d / "coef_boot.hex"
        if not f.exists():
            roms_mod.generate(config.load(ROOT / "gen" / "empc" / "configs" / cfgfile), d, all_designs=False)
        w = image.read_hex(f)
        log.info(f"{cfgfile}: fingerprint {w[image.A_FMT]:#x}, N {(w[image.A_CFG] >> 8) & 15}")
        out.append((cfgfile, w))
    return out


def _model_outputs(p: core.Params, x: dict, i: int, fw_thr=(0, 0), aw: int = 0) -> dict:
    xi = V.to_inputs(x, i)
    o = core.update(p, core.Inputs(xi.y, xi.omega, xi.dx, xi.wref, xi.u_prev, xi.ebar_prev, fw_thr=fw_thr,
                                   aw=aw))
    return {**V.outputs_of(o), "fw": (int(o.fw_hi), int(o.fw_lo))}


def _fw_thresholds(rng, p: core.Params, x: dict, i: int) -> tuple[int, int]:
    """Field-weakening thresholds (FW_R2 hi, lo) around this vector's r >> 20, equality included."""
    rt = core.voltage_r(core.update(p, V.to_inputs(x, i)).u_raw) >> core.FW_R_SHIFT
    pick = lambda: int(min(max(rt + int(rng.choice([-1, 0, 1, int(rng.integers(-300, 300))])), 0), 0xFFFF)) \
        if rng.random() < 0.8 else int(rng.integers(0, 1 << 16))
    return pick(), pick()


def _aw(rng, x: dict, i: int) -> int:
    """The speed-integral hold input for vector i: off, or on with either sign (a random increment has
    either sign: held or not)."""
    return int(rng.choice([0, 2, 1, 3]))


async def _check_vectors(tb: Bench, p: core.Params, x: dict, names=None, log=None) -> int:
    lat_exp = core.latency(p.ncols)
    for i in range(len(x["omega"])):
        thr = _fw_thresholds(tb.rng, p, x, i)
        aw = _aw(tb.rng, x, i)
        got, lat = await tb.run(x, i, fw_thr=thr, aw=aw)
        exp = _model_outputs(p, x, i, thr, aw)
        if aw & 1 and p.algorithm == 2 and p.task == "speed":       # the hold changed ebar (else both sides agree)
            tb.aw_seen.add(_model_outputs(p, x, i, thr)["ebar"] != exp["ebar"])
        tb.fw_seen.update({(k, v) for k, v in zip(("hi", "lo"), exp["fw"])})
        err = _mismatch(got, exp)
        assert err is None, f"vector {i} ({names[i] if names else 'random'}): {err}; inputs {V.to_inputs(x, i)}"
        assert lat == lat_exp, f"latency {lat} != {lat_exp}"
        assert int(tb.dut.latency.value) == lat_exp
    return len(x["omega"])


try:
    import cocotb

    @cocotb.test()
    async def boot_vectors_swap(dut):
        """Boot image, direct vectors on all 4 images, CPU upload and atomic swap."""
        from cocotb.clock import Clock
        from cocotb.triggers import RisingEdge, ReadOnly
        cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
        tb = Bench(dut)
        rng = np.random.default_rng(SEED)
        dut._log.info(f"seed {SEED} (EMPC_SEED), N = {tb.N}")
        n_ready = await tb.reset()
        dut._log.info(f"ready {n_ready} cycles after reset release, boot_ok={int(dut.boot_ok.value)}")
        assert n_ready == core.BOOT_CYCLES, n_ready
        assert int(dut.boot_ok.value) == 1 and int(dut.bank.value) == 0 and int(dut.swap_pending.value) == 0
        boot_w = image.read_hex(roms() / "coef_boot.hex")
        p_boot = image.decode(boot_w)
        total = 0
        # boot image: corners (subset) + random
        xc, names = V.corner_inputs(p_boot, tb.N, rng)
        sel = list(range(0, len(names)))[:60] + list(range(60, len(names), 40))
        total += await _check_vectors(tb, p_boot, V.take(xc, sel), [names[k] for k in sel])
        total += await _check_vectors(tb, p_boot, V.random_inputs(rng, 40, p_boot, tb.N))
        # outputs hold during the next update until its done
        x2 = V.random_inputs(rng, 2, p_boot, tb.N)
        out0, _ = await tb.run(x2, 0)
        await tb.load(x2, 1)
        dut.start.value = 1
        await RisingEdge(dut.clk)
        dut.start.value = 0
        for _ in range(20):
            await RisingEdge(dut.clk)
            await ReadOnly()
            assert read_out(dut) == out0, "outputs changed before done"
            assert int(dut.busy.value) == 1
        # a start while busy is ignored
        await RisingEdge(dut.clk)
        dut.start.value = 1
        await RisingEdge(dut.clk)
        dut.start.value = 0
        while not int(dut.done.value):
            await RisingEdge(dut.clk)
            await ReadOnly()
        assert _mismatch(read_out(dut), _model_outputs(p_boot, x2, 1)) is None
        await RisingEdge(dut.clk)
        await ReadOnly()
        assert int(dut.busy.value) == 0 and int(dut.done.value) == 0, "start during busy was not ignored"
        # walk through the other images: upload into the inactive bank, swap during an update
        p_cur = p_boot
        order = [n for n in IMAGES if load_image(n) != boot_w] + [n for n in IMAGES if load_image(n) == boot_w]
        for k, name in enumerate(order):
            w = load_image(name)
            p_new = image.decode(w)
            bank0 = int(dut.bank.value)
            # upload into the inactive bank while updates run on the active one
            wr = cocotb.start_soon(tb.write_image(w))
            x = V.random_inputs(rng, 12, p_cur, tb.N)
            total += await _check_vectors(tb, p_cur, x)
            await wr
            assert int(dut.bank.value) == bank0, "write changed the active bank"
            # still the old tuning
            x = V.random_inputs(rng, 3, p_cur, tb.N)
            total += await _check_vectors(tb, p_cur, x)
            # swap requested in the middle of an update: that update still uses the old bank
            got, lat = await tb.run(x, 0, swap_at=10)
            assert _mismatch(got, _model_outputs(p_cur, x, 0)) is None, "update during swap used new bank"
            assert int(dut.swap_pending.value) == 1 and int(dut.bank.value) == bank0
            await RisingEdge(dut.clk)
            await ReadOnly()
            assert int(dut.swap_pending.value) == 0 and int(dut.bank.value) == 1 - bank0
            x = V.random_inputs(rng, 50, p_new, tb.N)
            xc, names = V.corner_inputs(p_new, tb.N, rng)
            sel = list(range(0, len(names), 25))
            total += await _check_vectors(tb, p_new, x)
            total += await _check_vectors(tb, p_new, V.take(xc, sel), [names[s] for s in sel])
            dut._log.info(f"image {name}: bank {1 - bank0}, swap during update ok, ncols {p_new.ncols}, "
                          f"latency {core.latency(p_new.ncols)} cycles")
            p_cur = p_new
        # swap requested while idle: takes effect at the next edge; swap + start in one cycle
        w = load_image(IMAGES[0])
        await tb.write_image(w)
        p_new = image.decode(w)
        x = V.random_inputs(rng, 1, p_new, tb.N)
        await tb.load(x, 0)
        dut.cfg_swap.value = 1
        dut.start.value = 1
        await RisingEdge(dut.clk)
        dut.cfg_swap.value = 0
        dut.start.value = 0
        while True:
            await RisingEdge(dut.clk)
            await ReadOnly()
            if int(dut.done.value):
                break
        assert _mismatch(read_out(dut), _model_outputs(p_new, x, 0)) is None, "swap with start in one cycle"
        total += 1
        assert tb.fw_seen == {("hi", 0), ("hi", 1), ("lo", 0), ("lo", 1)}, f"field-weakening flags seen: {tb.fw_seen}"
        assert tb.aw_seen == {False, True}, f"speed-integral hold changed ebar: {tb.aw_seen}"
        dut._log.info(f"checked {total} vectors bit-exact (outputs u, du, u_raw, ebar, wn, flags, fw_hi, fw_lo; inputs written "
                      f"through in_we with garbage in the unused buffer words), latency = {LAT_BASE} + ncols, "
                      f"boot {n_ready} cycles")

    @cocotb.test()
    async def bad_boot(dut):
        """A corrupted boot image: ready still rises, boot_ok = img_ok = 0 (the axis keeps the bridges
        off); a valid upload swapped in makes img_ok = 1, bit-exact against the bank model."""
        from cocotb.clock import Clock
        cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
        tb = ImgBench(dut)
        n_ready = await tb.reset()
        assert n_ready == core.boot_cycles(tb.NA) and int(dut.boot_ok.value) == 0, (n_ready, int(dut.boot_ok.value))
        await tb.compare("bad boot")
        assert tb.bit("img_ok") == 0
        w = load_image(IMAGES[3])
        await tb.upload(list(enumerate(w[:image.USED])))
        await tb.request()
        await tb.boundary()
        await tb.compare("valid upload after a bad boot")
        assert tb.bit("img_ok") == 1 and tb.m.img_ok
        await tb.vectors(4)
        dut._log.info("corrupted boot image: ready after 771 cycles, boot_ok = img_ok = 0; a valid upload and "
                      "swap: img_ok = 1, %d vectors bit-exact", tb.n_vec)

    @cocotb.test()
    async def image_checks(dut):
        """Swap refusal and boundary alignment: corrupted, truncated, reordered, foreign and missing
        uploads, two swaps in a row, requests at / between / during boundaries, writes in flight;
        every step compared with the model (empc.rtlmodel.mpc_core.Banks) and the active bank
        checked bit-exact with update vectors."""
        from cocotb.clock import Clock
        cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
        tb = ImgBench(dut)
        await tb.reset()
        await tb.compare("boot")
        # the boot image runs only at its control period (the build's CTRL.pwm_per_control reset value)
        await tb.set_ppc(header_ppc() % 255 + 1)
        await tb.compare("boot image, pwm_per_control != its period")
        assert tb.bit("img_ok") == 0
        await tb.set_ppc(header_ppc())
        await tb.compare("boot image at its period")
        assert tb.bit("img_ok") == 1
        rng = tb.rng
        good = [load_image(n) for n in IMAGES]
        boot_w = image.read_hex(roms() / "coef_boot.hex")
        other = [w for w in good if w != boot_w][0]
        full = lambda w: list(enumerate(w[:image.USED]))
        acc, ref = 0, 0

        async def swap(label, expect, words=None, at_once=False):
            nonlocal acc, ref
            if words is not None:
                await tb.upload(words)
            if at_once:                      # request in the clock of the boundary
                await tb.request_at_boundary()
            else:
                await tb.request()
                await tb.idle(int(rng.integers(0, 30)))
                await tb.compare(label + " (pending)")
                assert tb.bit("swap_pending") == 1
                await tb.boundary()
            await tb.compare(label)
            got = not tb.bit("swap_refused")
            assert got == expect, f"{label}: swap {'accepted' if got else 'refused'}, expected the opposite"
            acc, ref = acc + got, ref + (not got)
            await tb.vectors(2)

        await swap("swap with no upload", False)
        await swap("valid upload", True, full(other))
        await swap("second swap in a row (no upload since)", False)
        # one bit flipped in every region of the image (header fields, unused header words,
        # column descriptors, gains, the last word), checksum not repaired
        regions = {"magic": 0, "cfg": 1, "ws": 2, "wn_min": 3, "wn_max": 4, "u_max": 5, "ebar_lim": 7,
                   "used": 9, "checksum": 10, "fmt": 11, "unused header": 0x20, "column": 0x41,
                   "gain p0": 0x100 + 4 * 3, "gain shift": 0x100 + 4 * 64 + 3, "last word": image.USED - 1}
        for name, a in regions.items():
            w = list(good[int(rng.integers(0, 4))])
            w[a] ^= 1 << int(rng.integers(0, 32))
            await swap(f"bit flip in {name} (word {a})", False, full(w))
        # truncated upload, then completed later in order (complete = every word, in order)
        w = list(good[0])
        await swap("truncated upload (767 of 768 words)", False, full(w)[:-1])
        await tb.upload(full(w)[:500])
        await tb.idle(7)
        await swap("upload in two parts, in order", True, full(w)[500:])
        # another build's format: header changed and the checksum repaired
        def rebuilt(w, a, v):
            w = list(w)
            w[a] = v
            w[image.A_CSUM] = image.checksum(w)
            return w
        cfg = good[1][image.A_CFG]
        fmt = tb.fmt
        foreign = {"format fingerprint of another build": rebuilt(good[1], image.A_FMT, fmt ^ 0x1234),
                   "layout 1": rebuilt(good[1], image.A_CFG, (cfg & 0xFFFFFF) | (1 << 24)),
                   "horizon N - 1": rebuilt(good[1], image.A_CFG, (cfg & ~0xF00) | ((tb.N - 1) << 8)),
                   "algorithm 3": rebuilt(good[1], image.A_CFG, cfg | (3 << 13)),
                   "ncols 65": rebuilt(good[1], image.A_CFG, (cfg & ~0x7F) | 65),
                   "reserved CFG bit 7": rebuilt(good[1], image.A_CFG, cfg | 0x80),
                   "reserved CFG bit 15": rebuilt(good[1], image.A_CFG, cfg | 0x8000),
                   "used words 767": rebuilt(good[1], image.A_USED, image.USED - 1),
                   "magic 'EMPD'": rebuilt(good[1], image.A_MAGIC, image.MAGIC + 1)}
        for name, w in foreign.items():
            assert image.check(w, tb.N, fmt), name
            await swap(f"{name} (checksum repaired)", False, full(w))
        # images of the other configurations' builds (their own fingerprint and scaling)
        for wname, w in foreign_builds(dut._log):
            await swap(f"image of build {wname}", False, full(w))
        # order: two words exchanged, a word written twice, a rewrite after completion, a restart
        seq = full(good[2])
        seq[5], seq[6] = seq[6], seq[5]
        await swap("two words written out of order", False, seq)
        seq = full(good[2])
        seq.insert(300, seq[299])
        await swap("a word written twice", False, seq)
        await swap("a word rewritten after the upload", False, full(good[2]) + [(123, good[2][123])])
        await swap("a restart at word 0 in the middle, then a whole image", True,
                   full(foreign["layout 1"])[:400] + full(good[3]))
        # timing: request in the clock of a boundary; request then many clocks without a boundary
        await swap("request in the clock of a boundary", True, full(good[0]), at_once=True)
        await tb.upload(full(good[1]))
        await tb.request()
        b0 = tb.bit("bank")
        for _ in range(200):
            await tb.idle(1)
            assert tb.bit("bank") == b0 and tb.bit("swap_pending") == 1, "swap applied without a boundary"
        await tb.boundary()
        await tb.compare("swap applied exactly at the boundary")
        assert tb.bit("bank") != b0
        acc += 1
        # a CPU word in flight at the boundary, and a word written while the swap is pending
        await tb.upload(full(good[2]))
        await tb.request()
        await tb.boundary(write=(0, good[2][0]))
        await tb.compare("word written in the clock of the boundary")
        assert tb.bit("swap_refused") == 1
        await tb.upload(full(good[3]))
        await tb.request()
        await tb.upload([(17, good[3][17])])
        await tb.boundary()
        await tb.compare("word written while the swap was pending")
        assert tb.bit("swap_refused") == 1
        ref += 2
        # a boundary while an update runs is no decision point: the update finishes with its bank
        await tb.upload(full(good[0]))
        await tb.request()
        await tb.boundary_during_update()
        await tb.compare("boundary during an update: still pending")
        assert tb.bit("swap_pending") == 1
        await tb.boundary()
        await tb.compare("next boundary, idle: applied")
        acc += 1
        await tb.vectors(4)
        # control period (CFG[23:16]): an image runs only at the axis's pwm_per_control
        ppc0 = tb.ppcs[tb.ax]
        per = ppc0 + 1 if ppc0 < 255 else 1
        w_per = image.with_period(good[1], per)
        assert not image.check(w_per, tb.N, fmt) and image.check(w_per, tb.N, fmt, ppc0)
        await swap("a valid image of another control period (not the axis's pwm_per_control)", False, full(w_per))
        assert tb.bit("img_ok") == 1 and tb.bit("upl_ok") == 1, "the old tuning must stay valid"
        await tb.set_ppc(per)
        await tb.compare("pwm_per_control changed: the active image's period differs")
        assert tb.bit("img_ok") == 0, "img_ok with the active image's period != pwm_per_control"
        await swap("the same upload, now at its own pwm_per_control", True)
        assert tb.bit("img_ok") == 1
        await tb.set_ppc(ppc0)
        await tb.compare("pwm_per_control back: the active image is of the other period")
        assert tb.bit("img_ok") == 0
        await swap("an image of the build's period at the build's pwm_per_control", True, full(good[2]))
        assert tb.bit("img_ok") == 1
        assert tb.m.refused == tb.refused_seen
        dut._log.info("image checks: %d swaps accepted, %d refused (RTL refused pulses %d = model), %d vectors "
                      "bit-exact on the active bank; every step compared with the bank model", acc, ref,
                      tb.refused_seen, tb.n_vec)

    @cocotb.test()
    async def axes(dut):
        """NAXES > 1: every axis's updates bit-exact against its own bank (core.MxCore) while the other
        axes upload, swap and write their input words; per-axis bank state compared after every step."""
        from cocotb.clock import Clock
        Clock(dut.clk, 10, unit="ns", impl="gpi").start()   # C clock: no Python per edge
        tb = AxBench(dut)
        n_ready = await tb.reset()
        assert n_ready == core.boot_cycles(tb.NA), (n_ready, core.boot_cycles(tb.NA))
        await tb.compare("boot")
        if tb.NA > 1:
            # one upload at a time: an image whose words go to two axes is no image of either
            w = list(enumerate(tb.good[1][:image.USED]))
            await tb.upload(1, w[:400])
            await tb.upload(0, w[400:])
            for a in (0, 1):
                await tb.swap(a)
            await tb.compare("an image split over axes 1 and 0")
            assert tb.bits("swap_refused")[:2] == [1, 1] and tb.bits("bank")[:2] == [0, 0]
        await tb.run_random(int(os.environ.get("EMPC_AX_OPS", "120")))

    @cocotb.test()
    async def stream(dut):
        """Streaming harness (tb/hdl/mpc_core_stream.v): many vectors back to back on Verilator."""
        if not hasattr(dut, "go"):
            return
        from cocotb.triggers import RisingEdge
        N = header_n()                          # the harness runs its own clock: no Python per cycle
        dut.go.value = 0
        rng = np.random.default_rng(SEED)
        t0, c0 = time.time(), time.process_time()
        jobs = stream_jobs(rng, N)
        write_stream(Path("mpc_stream_in.bin"), jobs, N)
        t1, c1 = time.time(), time.process_time()
        dut._log.info(f"seed {SEED}: {sum(len(j['x']['omega']) for j in jobs)} vectors in {len(jobs)} jobs, "
                      f"generated in {t1 - t0:.1f} s ({c1 - c0:.1f} s CPU)")
        for _ in range(5):
            await RisingEdge(dut.clk)
        dut.go.value = 1
        await RisingEdge(dut.clk)
        dut.go.value = 0
        await RisingEdge(dut.finished)          # no Python per clock cycle
        t2, c2 = time.time(), time.process_time()
        dut._log.info(f"simulation {t2 - t1:.1f} s ({c2 - c1:.1f} s CPU), {int(dut.cycles.value)} cycles, "
                      f"{int(dut.cycles.value) / max(c2 - c1, 1e-9) / 1e6:.2f} M clocks per CPU second")
        res = compare_stream(Path("mpc_stream_out.txt"), jobs, dut._log)
        Path("mpc_stream_result.json").write_text(json.dumps(res, indent=1))
        from files import REPORTS, merge_report
        lat = {j["name"]: j["latency"] for j in res["jobs"] if not j["name"].startswith("random")}
        merge_report(REPORTS / "mpc_core.json", {
            "vectors": res["vectors"], "mismatches": res["mismatches"], "seed": SEED,
            "sim_cycles": int(dut.cycles.value), "stream_jobs": res["jobs"],
            "latency_cycles": lat, "latency_formula": f"{core.LATENCY_BASE} + ncols (start -> done)"})
        dut._log.info(f"compare {time.time() - t2:.1f} s ({time.process_time() - c2:.1f} s CPU)")
        assert res["mismatches"] == 0, res
except ImportError:   # pytest without cocotb context
    pass


# ============================================================================ stream files
def stream_jobs(rng, N: int) -> list[dict]:
    """Images with their vectors: the 4 generated ones (random + corners), then random images."""
    jobs = []
    for name in IMAGES:
        w = load_image(name)
        p = image.decode(w)
        xc, names = V.corner_inputs(p, N, rng)
        x = V.concat(xc, V.random_inputs(rng, N_STREAM, p, N))
        jobs.append({"name": name, "words": w, "p": p, "x": x, "corners": len(names)})
    n_rand = int(os.environ.get("EMPC_MPC_RANDOM_IMAGES", "12"))
    fmt = header_consts()["IMG_FMT_ID"]
    for k in range(n_rand):
        w, p = V.random_image(rng, N, fmt, period=header_ppc())
        x = V.random_inputs(rng, 2000, p, N)
        jobs.append({"name": f"random{k}", "words": w, "p": p, "x": x, "corners": 0})
    return jobs


def _hex_cols(vals: np.ndarray, width: int) -> np.ndarray:
    """(n,) int64 -> (n, digits) uint8 ASCII hex of the two's complement in `width` bits."""
    digits = (width + 3) // 4
    v = vals.astype(np.int64)
    u = (v & ((1 << width) - 1)).astype(np.uint64) if width < 64 else v.astype(np.uint64)
    shifts = np.arange(digits - 1, -1, -1, dtype=np.uint64) * np.uint64(4)
    nib = (u[:, None] >> shifts[None, :]) & np.uint64(15)
    return np.frombuffer(b"0123456789abcdef", np.uint8)[nib.astype(np.int64)]


def _lines(cols: list[np.ndarray]) -> bytes:
    n = cols[0].shape[0]
    parts = []
    for c in cols:
        parts.append(c)
        parts.append(np.full((n, 1), ord(" "), np.uint8))
    parts[-1] = np.full((n, 1), ord("\n"), np.uint8)
    return np.concatenate(parts, axis=1).tobytes()


def write_stream(path: Path, jobs: list[dict], N: int) -> None:
    """Binary command file for tb/hdl/mpc_core_stream.v: 'w' cfg write, 's' swap, 'v' update, 'e' end.

    'v' n {addr, 40-bit value} x n: the input-buffer words of one update (V.input_word_arrays,
    the model's word map), written by the harness before start.
    """
    with open(path, "wb") as fh:
        for job in jobs:
            w = job["words"]
            rec = np.zeros(image.USED, dtype=[("c", "u1"), ("a", ">u2"), ("d", ">u4")])
            rec["c"], rec["a"], rec["d"] = ord("w"), np.arange(image.USED), np.array(w[:image.USED], np.uint32)
            fh.write(rec.tobytes())
            fh.write(b"s")
            addrs, vals = V.input_word_arrays(job["x"], N)
            n, nw = vals.shape
            # fixed 6-byte word record {addr, value[39:0]} (tb/hdl/mpc_core_stream.v takes value[SW-1:0])
            u = (vals & ((1 << 40) - 1)).astype(">u8").view(np.uint8).reshape(n, nw, 8)[:, :, 3:]
            a = np.broadcast_to(np.array(addrs, np.uint8)[None, :, None], (n, nw, 1))
            words = np.concatenate([a, u], axis=2).reshape(n, -1)
            head = np.tile(np.array([ord("v"), nw], np.uint8), (n, 1))
            fh.write(np.concatenate([head, words], axis=1).tobytes())
        fh.write(b"e")


OUT_FIELDS = [("u", 2, UW), ("du", 2, UW), ("u_raw", 2, UW), ("ebar", 3, SW), ("wn", 1, OPW), ("flags", 1, 11),
              ("lat", 1, 8)]


def read_stream(path: Path) -> dict:
    raw = np.frombuffer(path.read_bytes(), np.uint8)
    widths = [(w + 3) // 4 * k for _, k, w in OUT_FIELDS]  # vectors are printed as one hex number each
    L = sum(widths) + len(widths)
    assert raw.size % L == 0, f"output file size {raw.size} not a multiple of line length {L}"
    rows = raw.reshape(-1, L)
    lut = np.zeros(256, np.int64)
    for i, c in enumerate(b"0123456789abcdef"):
        lut[c] = i
    out, pos = {}, 0
    for (name, k, w), wd in zip(OUT_FIELDS, widths):
        d = (w + 3) // 4
        vals = []
        for e in range(k - 1, -1, -1):           # highest element printed first
            digs = lut[rows[:, pos + (k - 1 - e) * d: pos + (k - e) * d]]
            v = np.zeros(len(rows), np.int64)
            for c in range(d):
                v = (v << 4) | digs[:, c]
            v = wrap(v, w) if name not in ("flags", "lat") else v
            vals.append((e, v))
        vals.sort()
        out[name] = np.stack([v for _, v in vals], axis=1) if k > 1 else vals[0][1]
        pos += wd + 1
    return out


def compare_stream(path: Path, jobs: list[dict], log) -> dict:
    got = read_stream(path)
    n_total = sum(len(j["x"]["omega"]) for j in jobs)
    assert len(got["wn"]) == n_total, f"{len(got['wn'])} results for {n_total} vectors"
    res = {"seed": SEED, "vectors": n_total, "mismatches": 0, "jobs": []}
    base = 0
    for job in jobs:
        x, p = job["x"], job["p"]
        n = len(x["omega"])
        exp = V.update_batch(p, x)
        bad = np.zeros(n, bool)
        for k in ("u", "du", "u_raw", "ebar", "wn", "flags"):
            g = got[k][base:base + n]
            e = exp[k]
            bad |= (g != e).reshape(n, -1).any(axis=1)
        lat = got["lat"][base:base + n]
        lat_exp = core.latency(p.ncols)
        bad_lat = int((lat != lat_exp).sum())
        nb = int(bad.sum())
        flag_hits = {name: int(((exp["flags"] >> b) & 1).sum()) for name, b in core.FLAG_BITS.items()}
        res["jobs"].append({"name": job["name"], "vectors": n, "corners": job["corners"], "mismatches": nb,
                            "latency": lat_exp, "latency_mismatches": bad_lat, "flag_hits": flag_hits})
        res["mismatches"] += nb + bad_lat
        log.info(f"{job['name']}: {n} vectors ({job['corners']} corner), {nb} mismatches, latency {lat_exp} "
                 f"({bad_lat} off), flags set: {flag_hits}")
        if nb:
            i = int(np.nonzero(bad)[0][0])
            log.error(f"first mismatch vector {i}: dut " +
                      str({k: got[k][base + i].tolist() for k in ('u', 'du', 'u_raw', 'ebar', 'wn', 'flags')}) +
                      " model " + str({k: exp[k][i].tolist() for k in ('u', 'du', 'u_raw', 'ebar', 'wn', 'flags')}))
        base += n
    return res


# ============================================================================ pytest entries
def _file_params() -> dict:
    return {"BOOT_FILE": f'"{roms() / "coef_boot.hex"}"', "RSQRT_FILE": f'"{roms() / "rsqrt.hex"}"'}


def test_mpc_core():
    from runner import run
    run(toplevel="mpc_core", test_module="test_mpc_core", parameters=_file_params(), testcase="boot_vectors_swap")


def test_mpc_core_bad_boot():
    w = image.read_hex(roms() / "coef_boot.hex")
    w[image.A_CSUM] ^= 1
    bad = ROOT / "build" / "sim" / "mpc_core_bad_boot.hex"
    bad.parent.mkdir(parents=True, exist_ok=True)
    image.write_hex(w, bad)
    from runner import run
    run(toplevel="mpc_core", test_module="test_mpc_core", testcase="bad_boot",
        parameters={**_file_params(), "BOOT_FILE": f'"{bad}"'}, extra_env={"EMPC_BOOT_HEX": str(bad)})


def test_mpc_core_image_checks():
    """Image checker and swap protocol against core.Banks (Icarus)."""
    from runner import run
    run(toplevel="mpc_core", test_module="test_mpc_core", parameters=_file_params(), testcase="image_checks")


def test_mpc_core_image_checks_axis2():
    """The same checks on axis 2 of a NAXES = 4 core (issue 14's checks hold per axis): every step also
    compares the other three axes' bank state (untouched) and that only axis 2 refuses swaps."""
    from runner import run
    run(toplevel="mpc_core", test_module="test_mpc_core", testcase="image_checks", name="mpc_core_ax4",
        parameters={**_file_params(), "NAXES": 4}, extra_env={"EMPC_NAXES": "4", "EMPC_IMG_AXIS": "2"})


@pytest.mark.parametrize("naxes", [4])
def test_mpc_core_axes(naxes):
    """NAXES = 4 (Icarus): per-axis updates bit-exact while other axes upload, swap and write inputs;
    per-axis bank / pending / upl_ok / img_ok / refused against core.MxBanks after every step."""
    from runner import run
    run(toplevel="mpc_core", test_module="test_mpc_core", testcase="axes", name=f"mpc_core_ax{naxes}",
        parameters={**_file_params(), "NAXES": naxes}, extra_env={"EMPC_NAXES": str(naxes)})


@pytest.mark.cost(45)          # Verilator build ~20 s, 38 M clocks ~21 s
def test_mpc_core_stream():
    from runner import run
    run(toplevel="mpc_core_stream", test_module="test_mpc_core", sim="verilator", parameters=_file_params(),
        testcase="stream", public=ROOT / "tb" / "hdl" / "mpc_core_stream.vlt", timing=True)


def test_batch_model():
    """The numpy twin equals the scalar model (the specification) on every image, incl. random ones."""
    rng = np.random.default_rng(SEED + 1)
    N = header_n()
    n_checked = 0
    cases = [(name, image.decode(load_image(name))) for name in IMAGES]
    cases += [(f"random{k}", V.random_image(rng, N, valid=k % 2 == 0)[1]) for k in range(8)]
    for name, p in cases:
        xc, names = V.corner_inputs(p, N, rng)
        x = V.concat(xc, V.random_inputs(rng, 1000, p, N)) if name in IMAGES else V.random_inputs(rng, 600, p, N)
        got = V.update_batch(p, x)
        addrs, vals = V.input_word_arrays(x, N)
        for i in range(len(x["omega"])):
            assert dict(zip(addrs, vals[i].tolist())) == input_words(x, i, N), f"{name} vector {i}: word map"
            exp = _model_outputs(p, x, i)
            exp.pop("fw")
            g = {k: (got[k][i].tolist() if np.ndim(got[k][i]) else int(got[k][i])) for k in exp}
            assert g == exp, f"{name} vector {i}: batch {g} scalar {exp}"
            n_checked += 1
    print(f"seed {SEED + 1}: batch model == scalar model (and input word map == core.input_words) on "
          f"{n_checked} vectors, {len(cases)} images")


# ============================================================================ error against the float law
def operating_points(rng, p: core.Params, cfg, units: dict, n: int) -> dict:
    """Realistic operating points in raw units: |i| <= i_max / 2, speeds over Omega_e, small errors."""
    N = p.N
    pos = p.task == "position"
    isc = units["amps_per_lsb"] / (1 << 4)
    wsc = units["rad_s_per_count_per_ts"] / (1 << 16)
    thsc = units["rad_per_count_electrical"] / (1 << 8)
    x = V.empty_inputs(n, N)
    imax = cfg.control.i_max / isc
    x["y"][:, 0:2] = rng.uniform(-0.5, 0.5, (n, 2)) * imax
    om = rng.integers(V.lsh(p.wn_min, p.ws), V.lsh(p.wn_max, p.ws) + 1, n)
    x["omega"] = om
    x["y"][:, 2] = rng.integers(-(1 << 36), 1 << 36, n) if pos else om
    for m in range(N + 1):
        x["wref"][:, m, 0:2] = x["y"][:, 0:2] + rng.uniform(-0.1, 0.1, (n, 2)) * imax
        x["wref"][:, m, 2] = x["y"][:, 2] + (rng.uniform(-1, 1, n) * (0.5 / thsc) if pos
                                             else rng.uniform(-1, 1, n) * (20 / wsc))
    x["dx"][:, 0:2] = rng.uniform(-0.02, 0.02, (n, 2)) * imax
    x["dx"][:, 2] = rng.uniform(-1, 1, n) * (2 / wsc)
    x["dx"][:, 3] = om * 256 // 65536 + rng.integers(-100, 100, n)
    x["ebar_prev"][:, 2] = rng.uniform(-1, 1, n) * (0.3 / thsc if pos else 3 / wsc)
    return x


def float_du(p: core.Params, g: dict, x: dict, ebar_raw, i: int, units: dict) -> np.ndarray:
    """du (V) of eq. 23 / 26 in SI units with gains g, for raw vector i (angles relative, as the core)."""
    N = p.N
    pos = p.task == "position"
    isc = units["amps_per_lsb"] / (1 << 4)
    wsc = units["rad_s_per_count_per_ts"] / (1 << 16)
    thsc = units["rad_per_count_electrical"] / (1 << 8)
    s2 = thsc if pos else wsc
    y = np.array([x["y"][i, 0] * isc, x["y"][i, 1] * isc, x["y"][i, 2] * s2])
    W = np.array([[x["wref"][i, m, 0] * isc, x["wref"][i, m, 1] * isc, x["wref"][i, m, 2] * s2]
                  for m in range(1, N + 1)])
    dx = np.array([x["dx"][i, 0] * isc, x["dx"][i, 1] * isc, x["dx"][i, 2] * wsc, x["dx"][i, 3] * thsc, 0.0])
    if pos:
        W[:, 2] -= y[2]
        y[2] = 0.0
    if p.algorithm == 1:
        return g["K_e"] @ (W.reshape(-1) - np.tile(y, N)) - g["K_dx"] @ dx
    eb = np.array([ebar_raw[0] * isc, ebar_raw[1] * isc, ebar_raw[2] * s2])
    return g["K_ebar"] @ eb + g["K_WL"] @ W.reshape(-1) - g["K_y"] @ y - g["K_dx"] @ dx


BOUND_EXACT = 0.02      # |du_core - du_law(exact gains)| / u_max   (polynomial fit error dominates)
BOUND_FIT = 5e-4        # |du_core - du_law(fitted polynomials, float)| / u_max  (fixed-point error)


def float_error(n: int = 300, seed: int = SEED + 2) -> dict:
    from empc import config, fit, mpc, quantise
    man = json.loads((roms() / "manifest.json").read_text())
    cfg = config.load(ROOT / man["config"])
    units = man["units"]
    rng = np.random.default_rng(seed)
    skip_flags = (1 << core.FLAG_BITS["limit"]) | (1 << core.FLAG_BITS["ebar_inc"])
    res = {}
    for name in IMAGES:
        p = image.decode(load_image(name))
        gf = fit.fit(cfg, p.algorithm, p.task, w_norm=quantise.w_norm_rtl(cfg, p.ws))
        x = operating_points(rng, p, cfg, units, n)
        out = V.update_batch(p, x)
        umax_v = min(p.u_max, core.OP_MAX) / (1 << 4) * units["volts_per_tick"]
        e_ex, e_fit = [], []
        for i in range(n):
            assert not (out["flags"][i] & ~skip_flags), f"{name}: operating point {i} saturates ({out['flags'][i]:#x})"
            w = float(np.clip(x["omega"][i] * units["rad_s_per_count_per_ts"] / 65536.0,
                              cfg.control.omega_min, cfg.control.omega_max))
            du_core = out["du"][i] / 256.0 * units["volts_per_tick"]
            du_ex = float_du(p, mpc.gains(cfg.motor, cfg.control, w, p.algorithm, p.task), x, out["ebar"][i], i, units)
            du_fit = float_du(p, gf.evaluate(w), x, out["ebar"][i], i, units)
            e_ex.append(np.max(np.abs(du_core - du_ex)))
            e_fit.append(np.max(np.abs(du_core - du_fit)))
        res[name] = {"points": n, "u_max_V": umax_v,
                     "max_err_exact_V": float(max(e_ex)), "rel_exact": float(max(e_ex) / umax_v),
                     "max_err_fit_V": float(max(e_fit)), "rel_fit": float(max(e_fit) / umax_v)}
    return res


def test_float_error():
    """du of the core (bit-exact model) vs. the float law with exact gains (and with the fitted polynomials)."""
    res = float_error()
    for name, r in res.items():
        print(f"{name}: {r['points']} operating points, max |du - du_exact| = {r['max_err_exact_V']:.4f} V "
              f"({100 * r['rel_exact']:.3f} % of u_max {r['u_max_V']:.2f} V), max |du - du_fitted_float| = "
              f"{r['max_err_fit_V'] * 1e3:.3f} mV ({100 * r['rel_fit']:.4f} %)")
        assert r["rel_exact"] < BOUND_EXACT, (name, r)
        assert r["rel_fit"] < BOUND_FIT, (name, r)


def test_limiter_bound():
    """Circle limiter of the model (the RTL is bit-exact to it): |u| <= umax and |u| >= 0.998 umax - 2 LSB."""
    rng = np.random.default_rng(SEED + 3)
    n_lim = 0
    for umax in (23094, min(image.decode(load_image(IMAGES[0])).u_max, core.OP_MAX), 131071, 5000, 1000, 50):
        for _ in range(100000 // 6):
            R = umax * np.exp(rng.uniform(0, 5))
            a = rng.uniform(0, 2 * np.pi)
            u = [sat(int(R * np.cos(a)) << 4, 24), sat(int(R * np.sin(a)) << 4, 24)]
            out, lim = core.limit_circle(u, umax)
            if not lim:
                continue
            n_lim += 1
            m2 = (out[0] >> 4) ** 2 + (out[1] >> 4) ** 2
            assert m2 <= umax * umax, (u, umax, out)
            assert np.sqrt(m2) >= 0.998 * umax - 2, (u, umax, out)
    print(f"seed {SEED + 3}: limiter bound held on {n_lim} limited vectors")


def test_input_words():
    """Word map of the input buffer: header == model constants, core.input_words layout and range checks."""
    from empc import header
    h = header.read(roms() / "empc_formats.vh")
    names = ("IN_Y", "IN_OMEGA", "IN_DX", "IN_UPREV", "IN_EBAR", "IN_WREF", "IN_WORDS")
    for n in names:
        assert h[n] == getattr(core, n), (n, h[n], getattr(core, n))
    N = header_n()
    rng = np.random.default_rng(SEED + 4)
    n_checked = 0
    for n_ref in range(core.N_MAX + 1):
        x = V.empty_inputs(1, n_ref)
        for k in x:
            x[k][...] = rng.integers(-(1 << (SW - 1)), 1 << (SW - 1), x[k].shape)
        inp = V.to_inputs(x, 0)
        w = core.input_words(inp)
        assert sorted(w) == list(range(14)) + list(range(core.IN_WREF, core.IN_WREF + 3 * (n_ref + 1))), sorted(w)
        assert max(w) < core.IN_WORDS
        assert [w[core.IN_Y + o] for o in range(3)] == list(inp.y) and w[core.IN_OMEGA] == inp.omega
        assert [w[core.IN_DX + k] for k in range(5)] == list(inp.dx)
        assert [w[core.IN_UPREV + i] for i in range(2)] == list(inp.u_prev)
        assert [w[core.IN_EBAR + o] for o in range(3)] == list(inp.ebar_prev)
        assert all(w[core.IN_WREF + 3 * m + o] == inp.wref[m][o] for m in range(n_ref + 1) for o in range(3))
        n_checked += 1
    x = V.empty_inputs(1, N)
    with pytest.raises(ValueError):
        core.input_words(V.to_inputs(x, 0), N + 1)            # more references than given
    x["omega"][0] = 1 << (SW - 1)
    with pytest.raises(ValueError):
        core.input_words(V.to_inputs(x, 0), N)                # does not fit SW bit
    print(f"input word map: header EMPC_IN_* == model, {n_checked} layouts (N = 0..{core.N_MAX}) checked")


@pytest.mark.full
def test_bench_mpc_core(tmp_path):
    """`make bench` (~1 min of Yosys): the core alone through flow/synth.py --top mpc_core --summary, the
    same script and timing proxy as `make synth`; 6 DSP48A1, headline keys merged beside existing ones."""
    import synth
    summary = tmp_path / "mpc_core.json"
    summary.write_text(json.dumps({"vectors": 1, "stream_jobs": []}))
    assert synth.main(["--top", "mpc_core", "--out", str(tmp_path / "synth"), "--report", str(tmp_path / "synth.json"),
                       "--summary", str(summary)]) == 0
    rep = json.loads(summary.read_text())
    print({k: rep.get(k) for k in ("dsp48a1", "lut", "ff", "ramb16", "ramb8", "clock_mhz", "timing_proxy")})
    assert rep["vectors"] == 1 and rep["stream_jobs"] == [], "the stream test's keys must survive the merge"
    assert rep["block"] == "mpc_core" and rep["dsp48a1"] == 6, rep["dsp48a1"]
    full = json.loads((tmp_path / "synth.json").read_text())
    assert rep["lut"] == full["resources"]["lut"] and rep["clock_mhz"] == full["timing"]["est_fmax_mhz"]
