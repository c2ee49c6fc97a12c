"""park: bit-exact vs empc.rtlmodel.park (random + corners: angles 0/90/180/270 deg +-1,2 LSB,
full-scale and negative-full-scale inputs, raw full-range sin/cos), float accuracy bounds,
start/done protocol, reset.  ``rotation_test`` is shared with tb/test_inv_park.py."""
from __future__ import annotations

import itertools
import math
import os
import random

import cocotb

from empc.rtlmodel import park as P
from empc.rtlmodel import sincos as S
from startdone_driver import check_reset, run_ops, setup

SEED = int(os.environ.get("EMPC_SEED", 3301))
LATENCY = 8
W = P.I_W
LO, HI = -(1 << (W - 1)), (1 << (W - 1)) - 1
TRIG_LO, TRIG_HI = -(1 << (S.TRIG_W - 1)), (1 << (S.TRIG_W - 1)) - 1
CORNER_ANGLES = [(q << 14) + d & 0xFFFF for q in range(4) for d in (-2, -1, 0, 1, 2)] + [0x2000, 0xA000]
CORNER_X = [LO, LO + 1, -(1 << 16), -1, 0, 1, 46341, 1 << 16, HI]


def test_park():
    from runner import run
    run(toplevel="park", test_module="test_park")


async def rotation_test(dut, inverse: bool, x_names: tuple[str, str], y_names: tuple[str, str], seed: int):
    rng = random.Random(seed)
    name = "inv_park" if inverse else "park"
    dut._log.info(f"{name}: seed {seed} (EMPC_SEED overrides)")
    inputs = [*x_names, "sin_in", "cos_in"]
    await setup(dut, inputs)

    def op(x0, x1, s, c, angle=None):
        return ({x_names[0]: x0, x_names[1]: x1, "sin_in": s, "cos_in": c}, angle)

    ops = []
    for a in CORNER_ANGLES:
        s, c = S.sincos(a)
        for x0, x1 in itertools.product(CORNER_X, repeat=2):
            if rng.random() < 0.35 or a in (0, 1 << 14, 1 << 15, 3 << 14):
                ops.append(op(x0, x1, s, c, a))
    n_corner = len(ops)
    for k in range(1500):                                       # random angle, full-scale / realistic inputs
        a = rng.randrange(1 << 16)
        s, c = S.sincos(a)
        m = HI if k % 2 else 1 << 16
        ops.append(op(rng.randint(-m - 1, m), rng.randint(-m - 1, m), s, c, a))
    for _ in range(300):                                        # raw full-range operands (datapath only)
        ops.append(op(rng.randint(LO, HI), rng.randint(LO, HI), rng.randint(TRIG_LO, TRIG_HI),
                      rng.randint(TRIG_LO, TRIG_HI)))

    def garbage(r):
        return {x_names[0]: r.randint(LO, HI), x_names[1]: r.randint(LO, HI),
                "sin_in": r.randint(TRIG_LO, TRIG_HI), "cos_in": r.randint(TRIG_LO, TRIG_HI)}

    res = await run_ops(dut, [o for o, _ in ops], dict.fromkeys(y_names, True), LATENCY, rng, garbage)
    n_sat = 0
    err_int = err_full = err_real = 0.0
    for (o, angle), got in zip(ops, res):
        x0, x1, s, c = o[x_names[0]], o[x_names[1]], o["sin_in"], o["cos_in"]
        exp = P.rotate(x0, x1, s, c, inverse)
        assert got == (exp[0], exp[1], int(exp[2])), f"{name} {o}: rtl {got} model {exp}"
        n_sat += exp[2]
        if exp[2]:
            continue
        sg = -1 if inverse else 1
        # float math with the same integer sin/cos: one rounding, <= 0.5 LSB
        f = ((c * x0 + sg * s * x1) / 65536, (-sg * s * x0 + c * x1) / 65536)
        e = max(abs(got[0] - f[0]), abs(got[1] - f[1]))
        assert e <= 0.5, f"{name} {o}: error {e} vs float with the same sin/cos"
        err_int = max(err_int, e)
        if angle is None:
            continue
        # float math with the exact angle: + sin/cos error (< ERR_BOUND_FLOAT / 2^16 each)
        th = angle * 2 * math.pi / 65536
        sf, cf = math.sin(th), math.cos(th)
        f = (cf * x0 + sg * sf * x1, -sg * sf * x0 + cf * x1)
        e = max(abs(got[0] - f[0]), abs(got[1] - f[1]))
        bound = 0.5 + S.ERR_BOUND_FLOAT * (abs(x0) + abs(x1)) / 65536
        assert e <= bound, f"{name} {o} angle {angle}: error {e} > {bound} vs exact float"
        err_full = max(err_full, e)
        if max(abs(x0), abs(x1)) <= 1 << 16:
            err_real = max(err_real, e)
    assert n_sat > 10, "saturation not exercised"
    dut._log.info(f"{name}: {len(ops)} vectors bit-exact ({n_corner} corner vectors), latency {LATENCY}, "
                  f"{n_sat} saturated; max error vs float with the same sin/cos {err_int:.4f} LSB (bound 0.5), "
                  f"vs exact-angle float {err_full:.4f} LSB (all), {err_real:.4f} LSB (|x| <= 2^16; "
                  f"bound 0.5 + {S.ERR_BOUND_FLOAT} (|x0|+|x1|)/2^16)")
    await check_reset(dut, ops[-1][0], list(y_names), inputs)


@cocotb.test()
async def random_and_corners(dut):
    await rotation_test(dut, False, ("i_alpha", "i_beta"), ("i_d", "i_q"), SEED)


def test_park_models_np():
    """numpy variants of the park/inv_park models equal the scalar models (random, full range)."""
    import numpy as np
    rng = np.random.default_rng(SEED)
    n = 20000
    x0, x1 = rng.integers(LO, HI + 1, n), rng.integers(LO, HI + 1, n)
    s, c = rng.integers(TRIG_LO, TRIG_HI + 1, n), rng.integers(TRIG_LO, TRIG_HI + 1, n)
    for inverse in (False, True):
        y0, y1, sat = P.rotate_np(x0, x1, s, c, inverse)
        for k in range(0, n, 7):
            assert (int(y0[k]), int(y1[k]), bool(sat[k])) == P.rotate(int(x0[k]), int(x1[k]), int(s[k]), int(c[k]), inverse)
