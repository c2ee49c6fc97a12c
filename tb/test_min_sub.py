"""min_sub: bit-exact vs empc.rtlmodel.min_sub (random + corners: equal voltages, one/two at
the minimum, full-scale span -> saturation), exactness, start/done protocol, reset."""
from __future__ import annotations

import itertools
import os
import random

import cocotb

from empc.rtlmodel import min_sub as M
from startdone_driver import check_reset, run_ops, setup

SEED = int(os.environ.get("EMPC_SEED", 3601))
LATENCY = 3
INPUTS = ["u_a", "u_b", "u_c"]
OUTPUTS = {"w_a": True, "w_b": True, "w_c": True}
LO, HI = -(1 << (M.V_W - 1)), (1 << (M.V_W - 1)) - 1


def test_min_sub():
    from runner import run
    run(toplevel="min_sub", test_module="test_min_sub")


@cocotb.test()
async def random_and_corners(dut):
    rng = random.Random(SEED)
    dut._log.info(f"seed {SEED} (EMPC_SEED overrides)")
    await setup(dut, INPUTS)
    vals = [LO, LO + 1, -1, 0, 1, 1000, HI - 1, HI]
    ops = [dict(zip(INPUTS, t)) for t in itertools.product(vals, repeat=3)]
    ops += [dict.fromkeys(INPUTS, v) for v in (LO, -5, 0, 7, HI)]                  # equal voltages
    ops += [dict(zip(INPUTS, (rng.randint(LO, HI) for _ in range(3)))) for _ in range(1500)]
    for _ in range(500):                                                          # in-range spans
        base = rng.randint(LO, HI - 40000)
        ops.append(dict(zip(INPUTS, (base + rng.randint(0, 40000) for _ in range(3)))))

    def garbage(r):
        return {k: r.randint(LO, HI) for k in INPUTS}

    res = await run_ops(dut, ops, OUTPUTS, LATENCY, rng, garbage)
    n_sat = 0
    for op, got in zip(ops, res):
        exp = M.min_sub(op["u_a"], op["u_b"], op["u_c"])
        assert got == (exp[0], exp[1], exp[2], int(exp[3])), f"{op}: rtl {got} model {exp}"
        u = [op[k] for k in INPUTS]
        m = min(u)
        assert list(got[:3]) == [min(x - m, HI) for x in u] and min(got[:3]) == 0
        assert got[3] == int(max(u) - m > HI)
        n_sat += got[3]
    assert n_sat > 10, "saturation not exercised"
    for v in (LO, -5, 0, 7, HI):
        assert M.min_sub(v, v, v) == (0, 0, 0, False)
    dut._log.info(f"random_and_corners: {len(ops)} vectors bit-exact and exact vs integer math "
                  f"({len(vals)**3} + 5 equal-voltage corners), latency {LATENCY}, {n_sat} saturated")
    await check_reset(dut, ops[0], list(OUTPUTS), INPUTS)


def test_min_sub_model_np():
    """numpy variant equals the scalar model."""
    import numpy as np
    rng = np.random.default_rng(SEED)
    u = [rng.integers(LO, HI + 1, 20000) for _ in range(3)]
    wa, wb, wc, sat = M.min_sub_np(*u)
    for k in range(0, 20000, 7):
        assert (int(wa[k]), int(wb[k]), int(wc[k]), bool(sat[k])) == M.min_sub(*(int(x[k]) for x in u))
