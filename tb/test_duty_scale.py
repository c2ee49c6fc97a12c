"""duty_scale: bit-exact vs empc.rtlmodel.duty_scale (random + corners: duty 0 and 100 %,
kdc = 0.5 / 1.0 / 2.0 / 0 / max, negative voltages, saturation at PWM_HALF_PERIOD), exact
rounding vs rational math, start/done protocol, reset; a second build with another
PWM_HALF_PERIOD."""
from __future__ import annotations

import os
import random
from fractions import Fraction
from pathlib import Path

import cocotb

from empc import header
from empc.rtlmodel import duty_scale as M
from startdone_driver import check_reset, run_ops, setup

SEED = int(os.environ.get("EMPC_SEED", 3701))
LATENCY = 7
INPUTS = ["v_a", "v_b", "v_c", "kdc"]
OUTPUTS = {"cmp_a": False, "cmp_b": False, "cmp_c": False}
V_W, V_FRAC, KDC_W, KDC_FRAC = 18, M.V_FRAC, 18, M.KDC_FRAC
LO, HI = -(1 << (V_W - 1)), (1 << (V_W - 1)) - 1
ONE = 1 << KDC_FRAC


def _header_half_period() -> int:
    roms = Path(os.environ.get("EMPC_ROMS", Path(__file__).resolve().parents[1] / "build" / "roms" / "default"))
    return header.read(roms / "empc_formats.vh")["PWM_HALF_PERIOD"]


def test_duty_scale():
    from runner import run
    run(toplevel="duty_scale", test_module="test_duty_scale",
        extra_env={"DUTY_HALF_PERIOD": str(_header_half_period())})


def test_duty_scale_other_period():
    from runner import run
    run(toplevel="duty_scale", test_module="test_duty_scale", parameters={"PWM_HALF_PERIOD": 1000},
        extra_env={"DUTY_HALF_PERIOD": "1000"}, name="test_duty_scale_p1000")


@cocotb.test()
async def random_and_corners(dut):
    hp = int(os.environ["DUTY_HALF_PERIOD"])
    rng = random.Random(SEED + hp)
    dut._log.info(f"seed {SEED} (EMPC_SEED overrides), PWM_HALF_PERIOD = {hp}")
    await setup(dut, INPUTS)
    full = hp << V_FRAC                                         # 100 % duty at kdc = 1.0
    ops = []
    for kdc in (ONE // 2, ONE, 2 * ONE, 0, 1, (1 << KDC_W) - 1, ONE + 1, ONE - 1):
        for trip in ((0, 0, 0), (full, full, full), (0, full // 2, full), (full, 0, full + 8),
                     (full + 7, full - 8, full - 9), (2 * full, full // 2, 2 * full + 1),
                     (-1, -8, -9), (LO, HI, 0), (HI, HI, HI), (LO, LO, LO), (1, 7, 8)):
            ops.append({"v_a": trip[0], "v_b": trip[1], "v_c": trip[2], "kdc": kdc})
    n_corner = len(ops)
    for k in range(1500):
        if k % 4 == 0:                                          # anything, mostly clamped
            kdc, vmin, vmax = rng.randint(0, (1 << KDC_W) - 1), LO, HI
        else:                                                   # operating range, few clamps
            kdc = rng.choice([ONE // 2, ONE, 2 * ONE, rng.randint(ONE * 3 // 4, ONE * 3 // 2)])
            vmin, vmax = 0, full * ONE // kdc
        ops.append({"v_a": rng.randint(vmin, vmax), "v_b": rng.randint(vmin, vmax),
                    "v_c": rng.randint(vmin, vmax), "kdc": kdc})

    def garbage(r):
        return {"v_a": r.randint(LO, HI), "v_b": r.randint(LO, HI), "v_c": r.randint(LO, HI),
                "kdc": r.randint(0, (1 << KDC_W) - 1)}

    res = await run_ops(dut, ops, OUTPUTS, LATENCY, rng, garbage)
    n_sat = n_full = n_zero = 0
    max_err = Fraction(0)
    for op, got in zip(ops, res):
        exp = M.duty_scale(op["v_a"], op["v_b"], op["v_c"], op["kdc"], hp)
        assert got == (exp[0], exp[1], exp[2], int(exp[3])), f"{op}: rtl {got} model {exp}"
        sat = False
        for v, c in zip((op["v_a"], op["v_b"], op["v_c"]), got[:3]):
            exact = Fraction(v * op["kdc"], 1 << (KDC_FRAC + V_FRAC))
            assert 0 <= c <= hp
            if 0 <= exact <= hp:
                err = abs(c - exact)
                assert err <= Fraction(1, 2), f"{op}: |{c} - {float(exact)}| > 0.5"
                max_err = max(max_err, err)
            else:
                assert c == (0 if exact < 0 else hp)
            sat |= not (-Fraction(1, 2) <= exact < hp + Fraction(1, 2))
            n_full += c == hp
            n_zero += c == 0
        assert got[3] == int(sat), f"{op}: sat {got[3]} expected {int(sat)}"
        n_sat += got[3]
    # the corner semantics spelled out
    assert M.duty_scale(full, 0, full, ONE, hp) == (hp, 0, hp, False)           # 100 % / 0 %, no clamp
    assert M.duty_scale(full, full, full, 2 * ONE, hp) == (hp, hp, hp, True)    # kdc = 2.0 -> clamp
    assert M.duty_scale(2 * full, full, 0, ONE // 2, hp) == (hp, hp // 2, 0, False)
    assert M.duty_scale(-16, 0, 0, ONE, hp) == (0, 0, 0, True)
    assert n_sat > 50 and n_full > 50 and n_zero > 50
    dut._log.info(f"random_and_corners: {len(ops)} vectors bit-exact ({n_corner} corners), latency {LATENCY}, "
                  f"{n_sat} with clamping, {n_full} phases at 100 %, {n_zero} at 0 %, "
                  f"max |cmp - exact| (unclamped) = {float(max_err):.4f} tick (bound 0.5)")
    await check_reset(dut, ops[1], list(OUTPUTS), INPUTS)


def test_duty_scale_model_np():
    """numpy variant equals the scalar model."""
    import numpy as np
    rng = np.random.default_rng(SEED)
    hp = _header_half_period()
    v = [rng.integers(LO, HI + 1, 20000) for _ in range(3)]
    kdc = rng.integers(0, 1 << KDC_W, 20000)
    a, b, c, sat = M.duty_scale_np(*v, kdc, hp)
    for k in range(0, 20000, 7):
        assert (int(a[k]), int(b[k]), int(c[k]), bool(sat[k])) == M.duty_scale(*(int(x[k]) for x in v), int(kdc[k]), hp)


def test_modulation_chain_models():
    """Integer chain sincos -> inv_park -> inv_clarke -> min_sub -> duty_scale against the float
    chain of empc.pmsm (eqs. 34-36, duty = u / Udc): within 1.0 tick for |u_dq| up to the
    linear limit, kdc = 1.0 (and kdc = 2^16 * Udc_nom/Udc for a 10 % low DC link).
    Budget: 0.5 tick final rounding + (Q.4 quantisation of u_dq, inv_park rounding and sin/cos
    error, inv_clarke rounding, doubled by the min-subtraction) <= ~0.35 tick."""
    import math
    from empc import pmsm
    from empc.rtlmodel.inv_clarke import inv_clarke
    from empc.rtlmodel.inv_park import inv_park
    from empc.rtlmodel.min_sub import min_sub
    from empc.rtlmodel.sincos import sincos
    hp = _header_half_period()
    rng = random.Random(SEED)
    worst = 0.0
    for _ in range(5000):
        r = rng.uniform(0, hp / math.sqrt(3) * 0.999)          # PWM ticks, linear range
        phi = rng.uniform(0, 2 * math.pi)
        ud, uq = r * math.cos(phi), r * math.sin(phi)
        angle = rng.randrange(1 << 16)
        for udc_ratio in (1.0, 0.9):
            kdc = round(ONE / udc_ratio)
            s, c = sincos(angle)
            ua, ub, _ = inv_park(round(ud * 16), round(uq * 16), s, c)
            va, vb, vc, _ = inv_clarke(ua, ub)
            wa, wb, wc, sat0 = min_sub(va, vb, vc)
            cmp = M.duty_scale(wa, wb, wc, kdc, hp)
            th = angle * 2 * math.pi / 65536
            fa, fb = pmsm.inv_park(ud, uq, th)
            f = [x / udc_ratio for x in pmsm.min_subtract(*pmsm.inv_clarke(fa, fb))]
            if max(f) > hp:
                continue                                         # out of the DC link's reach
            assert not sat0 and not cmp[3]
            worst = max(worst, max(abs(cc - ff) for cc, ff in zip(cmp[:3], f)))
    print(f"modulation chain: max |cmp - float| = {worst:.4f} tick over 10000 cases")
    assert worst <= 1.0
