"""xform: the transform chain engine, bit-exact against the composed step models
(empc.rtlmodel.xform.front / modulate = the steps of empc.rtlmodel.xform_steps: clarke -> park,
inv_park -> inv_clarke -> min_sub -> duty_scale, with sincos), plus the start/done protocol, output hold, reset.

Vectors reuse the corner sets of the former per-block tests: clarke (every combination of
lo, lo+1, -1, 0, 1, hi-1, hi), park/inv_park (angles 0/90/180/270 deg +-1, 2 LSB, 45 deg,
225 deg x full-scale, negative full-scale, +-1, 0 ...), inv_clarke (at angle 0 the inverse
Park is the identity, so u_alpha/u_beta hit its corners), duty_scale (kdc 0.5/1.0/2.0/0/max/
1 +- LSB x 0 %, 100 %, over-range), random full-range and linear-range vectors; the Q.8
inputs u_d/u_q carry random fractional bits (u_to_v rounding) and reach +-2^23 (saturation).
Pytest-only checks: generated include files, the microprogram's instruction-level model
against the spec (sine/cosine exhaustively), its static schedule, the step models' numpy
variants and the float modulation chain.
"""
from __future__ import annotations

import itertools
import math
import os
import random
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ReadOnly, RisingEdge, Timer

from empc import header
from empc.rtlmodel import xform as X
from empc.rtlmodel.xform_steps import sincos as S
from empc.rtlmodel.xform_steps.clarke import clarke
from empc.rtlmodel.xform_steps.inv_clarke import inv_clarke
from empc.rtlmodel.xform_steps.inv_park import inv_park
from empc.rtlmodel.xform_steps.min_sub import min_sub
from empc.rtlmodel.xform_steps.duty_scale import duty_scale
from empc.rtlmodel.xform_steps.park import park
from files import roms_dir

ROOT = Path(__file__).resolve().parents[1]
SEED = int(os.environ.get("EMPC_SEED", 4101))
LAT = {"front": X.latency("front"), "mod": X.latency("mod")}
W = X.W
LO, HI = -(1 << (W - 1)), (1 << (W - 1)) - 1
ULO, UHI = -(1 << 23), (1 << 23) - 1            # u_d, u_q: Q16.8 in 24 bit (the MPC's u)
ONE = 1 << 16                                   # kdc 1.0
KDC_MAX = (1 << 18) - 1
CORNER_ANGLES = sorted({((q << 14) + d) & 0xFFFF for q in range(4) for d in (-2, -1, 0, 1, 2)}
                       | {0x2000, 0x6000, 0xA000, 0xE000, 0xFFFF, 0x8000})
# sine fold boundaries: every quadrant x node index 0, 1, 255, 256, 510, 511 x fraction 0, 1, 16, 31
FOLD_ANGLES = [(q << 14) | (j << 5) | f for q in range(4) for j in (0, 1, 255, 256, 510, 511) for f in (0, 1, 16, 31)]
CORNER_X = [LO, LO + 1, -(1 << 16), -1, 0, 1, 46341, 1 << 16, HI]
KDC_CORNERS = [ONE // 2, ONE, 2 * ONE, 0, 1, KDC_MAX, ONE + 1, ONE - 1]
FRONT_IN = ["i_a", "i_b", "i_c", "angle"]
MOD_IN = ["u_d", "u_q", "angle", "kdc"]


def _header_half_period() -> int:
    return header.read(roms_dir() / "empc_formats.vh")["PWM_HALF_PERIOD"]


# ---------------------------------------------------------------- pytest entries
@pytest.mark.cost(7)          # seconds on an idle core (make sim starts the costliest first)
def test_xform():
    from runner import run
    run(toplevel="xform", test_module="test_xform",
        extra_env={"XFORM_HP": str(_header_half_period()), "XFORM_IN_W": "13"})


def test_xform_p1000_inw14():
    """Other PWM_HALF_PERIOD, 14-bit currents (Clarke and Park saturate)."""
    from runner import run
    run(toplevel="xform", test_module="test_xform", parameters={"PWM_HALF_PERIOD": 1000, "IN_W": 14},
        extra_env={"XFORM_HP": "1000", "XFORM_IN_W": "14"}, name="test_xform_p1000")


@pytest.mark.full
def test_xform_angle_sweep():
    """All 65536 angles through the RTL front op (Verilator; make sim-full)."""
    from runner import run
    run(toplevel="xform", test_module="test_xform", sim="verilator", testcase="angle_sweep",
        extra_env={"XFORM_HP": str(_header_half_period()), "XFORM_IN_W": "13", "XFORM_SWEEP": "1"},
        name="test_xform_sweep")


def test_xform_generated_files():
    """rtl/xform_rom.vh and rtl/xform_ucode.vh equal what the model generates."""
    assert (ROOT / "rtl" / "xform_rom.vh").read_text() == X.rom_vh(), \
        "rtl/xform_rom.vh is stale: python -m empc.rtlmodel.xform rom > rtl/xform_rom.vh"
    assert (ROOT / "rtl" / "xform_ucode.vh").read_text() == X.ucode_vh(), \
        "rtl/xform_ucode.vh is stale: python -m empc.rtlmodel.xform ucode > rtl/xform_ucode.vh"


def test_xform_program_schedule():
    """Static schedule: no operand read before its pass has written it, 64 rows at most,
    latencies as documented in rtl/xform.v and docs/blocks/xform.md."""
    for op in ("front", "mod"):
        X.schedule(X.FRONT if op == "front" else X.MOD)
    assert len(X.PROGRAM) <= 1 << X.PC_BITS == 64
    assert LAT == {"front": 23, "mod": 84}, LAT
    print(f"program: {len(X.FRONT)} + {len(X.MOD)} rows, latency front {LAT['front']}, mod {LAT['mod']}")


def test_xform_program_trig_exhaustive():
    """The sine rows (fold, nodes T[k], T[k+1] from the block RAM, +-(32 - f) / +-f << 11
    products, sign-dependent rounding constant) give sincos.sincos() exactly for all 65536
    angles, for sin, cos and -sin; the program's trig passes write the same values."""
    rom = X.rom_words()
    for a in range(1 << 16):
        s, c = S.sincos(a)
        for kind, ref in (("S", s), ("C", c), ("MS", -s)):
            k, f, neg = X.trig_fold(a, kind)
            sg = -1 if neg else 1
            acc = (X.RND - (1 << 11) if neg else X.RND) + rom[k] * (sg * (32 - f) << 11) \
                + rom[k + 1] * (sg * f << 11)
            assert acc >> 16 == ref, (a, kind, acc >> 16, ref)
    for a in CORNER_ANGLES:
        r = X.run("front", angle=a)
        assert r["rfb"][1:4] == [*S.sincos(a), -S.sincos(a)[0]]


def test_xform_program_model():
    """Instruction-level model of the microprogram == composed step models (random full range,
    operating range, corners), with every step's saturation exercised."""
    rng = random.Random(SEED)
    hp = _header_half_period()
    n = 0
    for in_w in (13, 14):
        lo, hi = -(1 << (in_w - 1)), (1 << (in_w - 1)) - 1
        vals = [lo, lo + 1, -1, 0, 1, hi - 1, hi]
        cases = [(*t, rng.choice(CORNER_ANGLES)) for t in itertools.product(vals, repeat=3)]
        cases += [(rng.randint(lo, hi), rng.randint(lo, hi), rng.randint(lo, hi), rng.randrange(1 << 16))
                  for _ in range(3000)]
        for ia, ib, ic, a in cases:
            r = X.run("front", angle=a, i_a=ia, i_b=ib, i_c=ic)
            assert (r["i_d"], r["i_q"], r["sat"]) == X.front(ia, ib, ic, a), (ia, ib, ic, a)
            n += 1
    for ud, uq, a, kdc in _mod_vectors(rng, hp, 3000):
        r = X.run("mod", angle=a, u_d=ud, u_q=uq, kdc=kdc, half_period=hp)
        assert (*r["cmp"], r["sat"]) == X.modulate(ud, uq, a, kdc, hp), (ud, uq, a, kdc)
        assert r["rfa"][X.RFA["UDV"]] == X.u_to_v(ud) and r["rfa"][X.RFA["UQV"]] == X.u_to_v(uq)
        n += 1
    print(f"instruction-level model == spec for {n} vectors")


def test_step_models_np():
    """numpy variants of the step models equal the scalar models (random, full range)."""
    import numpy as np
    from empc.rtlmodel.xform_steps import clarke as CM, duty_scale as DM, inv_clarke as ICM, min_sub as MM, park as PM
    rng = np.random.default_rng(SEED)
    n = 20000
    assert CM.K_BETA == round(2 ** CM.K_SHIFT / math.sqrt(3)) == 151349
    assert ICM.K_SQ3 == round(2 ** ICM.K_SHIFT * math.sqrt(3) / 2) == 1816187
    a, b, c = (rng.integers(-(1 << 16), 1 << 16, n) for _ in range(3))
    ya, yb, sat = CM.clarke_np(a, b, c)
    x0, x1 = rng.integers(LO, HI + 1, n), rng.integers(LO, HI + 1, n)
    s, co = rng.integers(LO, HI + 1, n), rng.integers(LO, HI + 1, n)
    kdc = rng.integers(0, 1 << 18, n)
    hp = _header_half_period()
    rot = [PM.rotate_np(x0, x1, s, co, inv) for inv in (False, True)]
    ic = ICM.inv_clarke_np(x0, x1)
    ms = MM.min_sub_np(x0, x1, s)
    ds = DM.duty_scale_np(x0, x1, s, kdc, hp)
    for k in range(0, n, 7):
        i = lambda *v: tuple(int(q[k]) if not isinstance(q[k], (bool, np.bool_)) else bool(q[k]) for q in v)  # noqa: E731
        assert i(ya, yb, sat) == CM.clarke(int(a[k]), int(b[k]), int(c[k]))
        for inv in (0, 1):
            assert i(*rot[inv]) == PM.rotate(int(x0[k]), int(x1[k]), int(s[k]), int(co[k]), bool(inv))
        assert i(*ic) == ICM.inv_clarke(int(x0[k]), int(x1[k]))
        assert i(*ms) == MM.min_sub(int(x0[k]), int(x1[k]), int(s[k]))
        assert i(*ds) == DM.duty_scale(int(x0[k]), int(x1[k]), int(s[k]), int(kdc[k]), hp)
    xs = rng.integers(0, 1 << 16, 3000)
    sn, cs = S.sincos_np(xs)
    for k in range(0, 3000, 3):
        assert S.sincos(int(xs[k])) == (int(sn[k]), int(cs[k]))


def test_step_models_accuracy():
    """Accuracy of the step models (the spec) against float math, as the former per-block tests
    stated it: sincos (all angles) |out - round(2^16 sin)| <= 1, |out - 2^16 sin| < 1.0, exact at
    0/90/180/270 deg; clarke |i_beta - 16 (i_b - i_c)/sqrt3| <= 0.5 + constant error; park /
    inverse Park <= 0.5 LSB against float with the same sin/cos and <= 0.5 + 1.0 (|x0|+|x1|)/2^16
    with the exact angle; inverse Clarke <= 0.5 + constant error, phases sum to -1..1; min_sub
    exact; duty_scale |cmp - v kdc/2^20| <= 1/2 unless clamped."""
    import numpy as np
    from empc.rtlmodel.xform_steps import clarke as CM, duty_scale as DM, inv_clarke as ICM, min_sub as MM, park as PM
    rng = np.random.default_rng(SEED)
    a = np.arange(1 << 16)
    sn, cs = S.sincos_np(a)
    th = a * (2 * math.pi / (1 << 16))
    es, ec = (1 << 16) * np.sin(th), (1 << 16) * np.cos(th)
    assert max(np.abs(sn - np.floor(es + 0.5)).max(), np.abs(cs - np.floor(ec + 0.5)).max()) <= S.ERR_BOUND_ROUNDED
    err_trig = max(np.abs(sn - es).max(), np.abs(cs - ec).max())
    assert err_trig < S.ERR_BOUND_FLOAT
    assert [S.sincos(q << 14) for q in range(4)] == [(0, 1 << 16), (1 << 16, 0), (0, -(1 << 16)), (-(1 << 16), 0)]
    n = 20000
    ib, ic = rng.integers(-4096, 4096, n), rng.integers(-4096, 4096, n)
    _, be, sat = CM.clarke_np(np.zeros(n, dtype=np.int64), ib, ic)
    kb = 0.5 + 8191 * 16 * abs(CM.K_BETA - (1 << CM.K_SHIFT) / math.sqrt(3)) / (1 << CM.K_SHIFT)
    assert not sat.any() and np.abs(be - 16 * (ib - ic) / math.sqrt(3)).max() <= kb
    ang = rng.integers(0, 1 << 16, n)
    s_, c_ = S.sincos_np(ang)
    x0, x1 = rng.integers(-(1 << 16), (1 << 16) + 1, n), rng.integers(-(1 << 16), (1 << 16) + 1, n)
    thr = ang * (2 * math.pi / (1 << 16))
    for inv in (False, True):
        sg = -1 if inv else 1
        y0, y1, sat = PM.rotate_np(x0, x1, s_, c_, inv)
        ok = ~sat
        f0, f1 = (c_ * x0 + sg * s_ * x1) / 65536, (-sg * s_ * x0 + c_ * x1) / 65536
        assert max(np.abs(y0 - f0)[ok].max(), np.abs(y1 - f1)[ok].max()) <= 0.5
        g0 = np.cos(thr) * x0 + sg * np.sin(thr) * x1
        g1 = -sg * np.sin(thr) * x0 + np.cos(thr) * x1
        bound = 0.5 + S.ERR_BOUND_FLOAT * (np.abs(x0) + np.abs(x1)) / 65536
        assert (np.maximum(np.abs(y0 - g0), np.abs(y1 - g1))[ok] <= bound[ok]).all()
    r, phi = rng.uniform(0, 2 ** 17 * 0.86, n), rng.uniform(0, 2 * math.pi, n)
    ua, ub = (r * np.cos(phi)).astype(np.int64), (r * np.sin(phi)).astype(np.int64)
    va, vb, vc, sat = ICM.inv_clarke_np(ua, ub)
    kc = 0.5 + (1 << 17) * abs(ICM.K_SQ3 - (1 << ICM.K_SHIFT) * math.sqrt(3) / 2) / (1 << ICM.K_SHIFT)
    ok = ~sat
    assert (va == ua).all() and np.abs(vb - (-ua / 2 + math.sqrt(3) / 2 * ub))[ok].max() <= kc
    assert np.abs(vc - (-ua / 2 - math.sqrt(3) / 2 * ub))[ok].max() <= kc and np.abs(va + vb + vc)[ok].max() <= 1
    u = [rng.integers(LO, HI + 1, n) for _ in range(3)]
    w = MM.min_sub_np(*u)
    m = np.minimum(np.minimum(u[0], u[1]), u[2])
    for k in range(3):
        assert (w[k] == np.minimum(u[k] - m, HI)).all()
    hp = _header_half_period()
    v = [rng.integers(0, HI + 1, n) for _ in range(3)]
    kdc = rng.integers(0, 1 << 18, n)
    d = DM.duty_scale_np(*v, kdc, hp)
    for k in range(3):
        exact = v[k] * kdc / 2.0 ** 20
        inr = (exact >= 0) & (exact <= hp)
        assert np.abs(d[k] - exact)[inr].max() <= 0.5 and (d[k][exact > hp + 0.5] == hp).all()
    print(f"step models: sin/cos max |err| {err_trig:.4f} LSB (all angles); clarke, park, inverse Park, "
          f"inverse Clarke, min_sub, duty_scale within their bounds over {n} vectors each")


def test_modulation_chain_float():
    """Integer chain (modulate) against the float chain of empc.pmsm (eqs. 34-36, duty = u/Udc):
    within 1.0 tick for |u_dq| up to the linear limit, kdc = 1.0 and a 10 % low DC link."""
    from empc import pmsm
    hp = _header_half_period()
    rng = random.Random(SEED)
    worst = 0.0
    for _ in range(4000):
        r = rng.uniform(0, hp / math.sqrt(3) * 0.999)
        phi = rng.uniform(0, 2 * math.pi)
        ud, uq = r * math.cos(phi), r * math.sin(phi)
        angle = rng.randrange(1 << 16)
        for udc_ratio in (1.0, 0.9):
            kdc = round(ONE / udc_ratio)
            cmp = X.modulate(round(ud * 256), round(uq * 256), angle, kdc, hp)
            fa, fb = pmsm.inv_park(ud, uq, angle * 2 * math.pi / 65536)
            f = [x / udc_ratio for x in pmsm.min_subtract(*pmsm.inv_clarke(fa, fb))]
            if max(f) > hp:
                continue
            assert not cmp[3]
            worst = max(worst, max(abs(cc - ff) for cc, ff in zip(cmp[:3], f)))
    print(f"modulation chain: max |cmp - float| = {worst:.4f} tick")
    assert worst <= 1.0


# ---------------------------------------------------------------- vectors
def _front_vectors(rng: random.Random, in_w: int, n_rand: int) -> list[dict]:
    lo, hi = -(1 << (in_w - 1)), (1 << (in_w - 1)) - 1
    vals = [lo, lo + 1, -1, 0, 1, hi - 1, hi]
    ops = [dict(zip(FRONT_IN, (*t, CORNER_ANGLES[k % len(CORNER_ANGLES)])))
           for k, t in enumerate(itertools.product(vals, repeat=3))]
    for a in CORNER_ANGLES:                                      # angle corners, large currents
        for _ in range(4):
            ops.append({"i_a": rng.choice(vals), "i_b": rng.choice(vals), "i_c": rng.randint(lo, hi), "angle": a})
    for a in FOLD_ANGLES:                                        # sine fold boundaries
        ops.append({"i_a": rng.randint(lo, hi), "i_b": rng.randint(lo, hi), "i_c": rng.randint(lo, hi), "angle": a})
    for _ in range(n_rand):
        ops.append({"i_a": rng.randint(lo, hi), "i_b": rng.randint(lo, hi), "i_c": rng.randint(lo, hi),
                    "angle": rng.randrange(1 << 16)})
    for _ in range(n_rand // 4):                                 # balanced currents, the operating case
        a, b = rng.randint(lo // 2, hi // 2), rng.randint(lo // 2, hi // 2)
        ops.append({"i_a": a, "i_b": b, "i_c": -a - b, "angle": rng.randrange(1 << 16)})
    return ops


def _mod_vectors(rng: random.Random, hp: int, n_rand: int) -> list[tuple[int, int, int, int]]:
    """(u_d, u_q, angle, kdc), u in Q.8: the Q.4 corner values v enter as 16 v (exact) or
    16 v + 7 / 16 v - 8 (the same after rounding) or 16 v + 8 (rounds up)."""
    def q8(v: int) -> int:
        return max(ULO, min(UHI, 16 * v + rng.choice([0, 0, 7, -8, 8])))

    ops = [(rng.randint(16 * LO, 16 * HI), rng.randint(16 * LO, 16 * HI), a, ONE) for a in FOLD_ANGLES]
    for a in CORNER_ANGLES[::3] + [0, 1 << 14]:                # inverse Park corners
        for x0, x1 in itertools.product(CORNER_X, repeat=2):
            if rng.random() < 0.3:
                ops.append((q8(x0), q8(x1), a, rng.choice(KDC_CORNERS)))
    icv = [LO, LO + 1, -(1 << 16), -2, -1, 0, 1, 2, 1 << 16, HI - 1, HI]
    for x0, x1 in itertools.product(icv, repeat=2):             # angle 0: inv_clarke sees (u_d, u_q)
        ops.append((16 * x0, 16 * x1, 0, rng.choice(KDC_CORNERS)))
    for u in (ULO, ULO + 1, 16 * LO - 9, 16 * LO - 8, 16 * HI + 7, 16 * HI + 8, UHI, -9, -8, -1, 7, 8):
        ops.append((u, rng.choice([0, u, -u - 1]), rng.randrange(1 << 16), ONE))   # u_to_v rounding, saturation
    full = hp << 8
    for kdc in KDC_CORNERS:                                      # duty corners: 0 %, 100 %, over-range
        for ud, uq in ((0, 0), (full // 2, 0), (full, 0), (-full, 0), (0, full), (2 * full, 0), (1, 1)):
            ops.append((ud, uq, rng.choice([0, 1 << 14, 1 << 15, rng.randrange(1 << 16)]), kdc))
    lin = int(full / math.sqrt(3))
    for k in range(n_rand):
        a = rng.randrange(1 << 16)
        if k % 6 == 0:                                           # anything
            ops.append((rng.randint(ULO, UHI), rng.randint(ULO, UHI), a, rng.randint(0, KDC_MAX)))
        elif k % 6 == 1:                                         # the transforms' full range
            ops.append((rng.randint(16 * LO, 16 * HI), rng.randint(16 * LO, 16 * HI), a, rng.randint(0, KDC_MAX)))
        else:                                                    # linear range, realistic kdc
            r, phi = rng.uniform(0, lin), rng.uniform(0, 2 * math.pi)
            ops.append((int(r * math.cos(phi)), int(r * math.sin(phi)), a,
                        rng.choice([ONE, rng.randint(ONE * 3 // 4, ONE * 3 // 2)])))
    return ops


def _mod_steps_sat(ud: int, uq: int, a: int, kdc: int, hp: int) -> tuple[bool, bool, bool, bool]:
    s, c = S.sincos(a)
    ua, ub, s1 = inv_park(X.u_to_v(ud), X.u_to_v(uq), s, c)
    va, vb, vc, s2 = inv_clarke(ua, ub)
    wa, wb, wc, s3 = min_sub(va, vb, vc)
    *_, s4 = duty_scale(wa, wb, wc, kdc, hp)
    return s1, s2, s3, s4


def _front_steps_sat(ia: int, ib: int, ic: int, a: int) -> tuple[bool, bool]:
    al, be, s0 = clarke(ia, ib, ic)
    s, c = S.sincos(a)
    return s0, park(al, be, s, c)[2]


# ---------------------------------------------------------------- cocotb helpers
async def _setup(dut):
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    dut.rst.value = 1
    for n in ("start_front", "start_mod", *FRONT_IN, *MOD_IN[:2], "kdc", "mul_b"):
        getattr(dut, n).value = 0
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.rst.value = 0
    await RisingEdge(dut.clk)


def _outs(dut) -> tuple:
    return (dut.i_d.value.to_signed(), dut.i_q.value.to_signed(),
            int(dut.cmp_a.value), int(dut.cmp_b.value), int(dut.cmp_c.value))


def _expect(kind: str, op: dict, hp: int) -> tuple:
    if kind == "front":
        i_d, i_q, sat = X.front(op["i_a"], op["i_b"], op["i_c"], op["angle"])
        return (i_d, i_q), sat
    *cmp, sat = X.modulate(op["u_d"], op["u_q"], op["angle"], op["kdc"], hp)
    return tuple(cmp), sat


def _garbage(rng: random.Random, in_w: int) -> dict:
    lo, hi = -(1 << (in_w - 1)), (1 << (in_w - 1)) - 1
    return {"i_a": rng.randint(lo, hi), "i_b": rng.randint(lo, hi), "i_c": rng.randint(lo, hi),
            "u_d": rng.randint(ULO, UHI), "u_q": rng.randint(ULO, UHI), "angle": rng.randrange(1 << 16),
            "kdc": rng.randint(0, KDC_MAX)}


async def _bulk(dut, ops: list[tuple[str, dict]], hp: int) -> int:
    """Back-to-back requests, checked in their done cycle only (fast path)."""
    n = 0
    for kind, op in ops:
        for k, v in op.items():
            getattr(dut, k).value = v
        getattr(dut, f"start_{kind}").value = 1
        await RisingEdge(dut.clk)                                # start cycle s ends
        getattr(dut, f"start_{kind}").value = 0
        await Timer(LAT[kind] * 10 - 5, "ns")                    # middle of cycle s + LAT
        await RisingEdge(dut.clk)                                # registers during cycle s + LAT
        assert int(dut.done.value) == 1, f"{kind}: no done {LAT[kind]} cycles after start ({op})"
        exp, sat = _expect(kind, op, hp)
        o = _outs(dut)
        got = o[:2] if kind == "front" else o[2:]
        assert got == exp and int(dut.sat.value) == int(sat), f"{kind} {op}: rtl {got} sat {int(dut.sat.value)}, model {exp} {sat}"
        n += 1
    return n


# ---------------------------------------------------------------- cocotb tests
@cocotb.test()
async def front_vectors(dut):
    """Front operation: clarke corners x corner angles, random, balanced currents: bit-exact."""
    in_w = int(os.environ["XFORM_IN_W"])
    hp = int(os.environ["XFORM_HP"])
    rng = random.Random(SEED + in_w)
    dut._log.info(f"seed {SEED} (EMPC_SEED overrides), IN_W = {in_w}, PWM_HALF_PERIOD = {hp}")
    await _setup(dut)
    ops = _front_vectors(rng, in_w, 2000 if in_w == 13 else 500)
    n = await _bulk(dut, [("front", o) for o in ops], hp)
    sats = [_front_steps_sat(o["i_a"], o["i_b"], o["i_c"], o["angle"]) for o in ops]
    n_cl, n_pk = sum(s[0] for s in sats), sum(s[1] for s in sats)
    if in_w == 13:
        assert n_cl == 0 and n_pk == 0, "13-bit currents cannot saturate clarke or park"
    else:
        assert n_cl > 5 and n_pk > 5, f"saturation not exercised (clarke {n_cl}, park {n_pk})"
    dut._log.info(f"front_vectors: {n} vectors bit-exact (343 clarke corners, {4 * len(CORNER_ANGLES)} "
                  f"angle corners, {len(FOLD_ANGLES)} fold boundaries), latency {LAT['front']}, "
                  f"saturated: clarke {n_cl}, park {n_pk}")


@cocotb.test()
async def mod_vectors(dut):
    """Modulation: inverse Park corners, inverse Clarke corners (angle 0), duty/kdc corners,
    random full range and linear range: bit-exact, every step's saturation exercised."""
    hp = int(os.environ["XFORM_HP"])
    rng = random.Random(SEED + hp)
    await _setup(dut)
    vecs = _mod_vectors(rng, hp, 1500 if hp == _header_half_period() else 400)
    ops = [dict(zip(MOD_IN, v)) for v in vecs]
    n = await _bulk(dut, [("mod", o) for o in ops], hp)
    sats = [_mod_steps_sat(*v, hp) for v in vecs]
    cnt = [sum(s[i] for s in sats) for i in range(4)]
    assert min(cnt) > 5, f"step saturation not exercised: inv_park/inv_clarke/min_sub/duty {cnt}"
    cmps = [X.modulate(*v, hp) for v in vecs]
    n_full = sum(c.count(hp) for c in (x[:3] for x in cmps))
    n_zero = sum(c.count(0) for c in (x[:3] for x in cmps))
    assert n_full > 20 and n_zero > 20
    dut._log.info(f"mod_vectors: {n} vectors bit-exact, latency {LAT['mod']}, saturated: inv_park {cnt[0]}, "
                  f"inv_clarke {cnt[1]}, min_sub {cnt[2]}, duty clamp {cnt[3]}; {n_full} phases at 100 %, "
                  f"{n_zero} at 0 %")


@cocotb.test()
async def protocol(dut):
    """Mixed front/mod requests, checked every cycle: done exactly LAT cycles after an accepted
    start, busy in between, starts while busy (garbage inputs) and start_mod together with
    start_front ignored, back-to-back start in the done cycle, i_d/i_q change only with a
    front done and cmp_* only with a mod done, sat only with done; then reset mid-operation."""
    in_w = int(os.environ["XFORM_IN_W"])
    hp = int(os.environ["XFORM_HP"])
    rng = random.Random(SEED + 7)
    await _setup(dut)
    fr = _front_vectors(rng, in_w, 40)
    md = [dict(zip(MOD_IN, v)) for v in _mod_vectors(rng, hp, 40)]
    ops = [("front", o) for o in rng.sample(fr, 50)] + [("mod", o) for o in rng.sample(md, 50)]
    rng.shuffle(ops)
    held = _outs(dut)
    assert held == (0, 0, 0, 0, 0)
    nxt, issue, kind_f, cyc = 0, None, None, 0
    n_spur = n_b2b = n_both = 0
    while nxt < len(ops) or issue is not None:
        in_flight = issue is not None and cyc < issue + LAT[kind_f]
        new = None
        dut.start_front.value = 0
        dut.start_mod.value = 0
        if not in_flight and nxt < len(ops) and rng.random() >= 0.3:
            kind, op = ops[nxt]
            for k, v in _garbage(rng, in_w).items():
                getattr(dut, k).value = v
            for k, v in op.items():
                getattr(dut, k).value = v
            getattr(dut, f"start_{kind}").value = 1
            if kind == "front" and rng.random() < 0.3:
                dut.start_mod.value = 1                          # must be ignored: front has priority
                n_both += 1
            n_b2b += issue is not None
            new = (cyc, kind)
        elif in_flight and rng.random() < 0.1:
            for k, v in _garbage(rng, in_w).items():
                getattr(dut, k).value = v
            getattr(dut, rng.choice(["start_front", "start_mod"])).value = 1
            n_spur += 1
        elif rng.random() < 0.5:
            for k, v in _garbage(rng, in_w).items():
                getattr(dut, k).value = v
        await RisingEdge(dut.clk)
        done, busy, sat = int(dut.done.value), int(dut.busy.value), int(dut.sat.value)
        o = _outs(dut)
        if issue is not None and cyc == issue + LAT[kind_f]:
            assert done == 1 and busy == 0, f"cycle {cyc}: done {done} busy {busy} ({kind_f} started {issue})"
            exp, esat = _expect(kind_f, ops[nxt - 1][1], hp)
            got = o[:2] if kind_f == "front" else o[2:]
            keep = o[2:] == held[2:] if kind_f == "front" else o[:2] == held[:2]
            assert got == exp and sat == int(esat), f"{kind_f}: rtl {got} sat {sat}, model {exp} {esat}"
            assert keep, f"{kind_f} done changed the other operation's outputs"
            held = o
            issue = None
        else:
            assert done == 0 and sat == 0, f"cycle {cyc}: done {done} sat {sat} outside a done cycle"
            assert o == held, f"cycle {cyc}: outputs changed without done"
            if issue is not None:
                assert busy == (1 if cyc > issue else 0), f"cycle {cyc}: busy {busy}, start in {issue}"
            else:
                assert busy == 0, f"cycle {cyc}: busy while idle"
        if new is not None:
            issue, kind_f = new
            nxt += 1
        cyc += 1
    for _ in range(LAT["mod"] + 2):
        dut.start_front.value = 0
        dut.start_mod.value = 0
        await RisingEdge(dut.clk)
        assert int(dut.done.value) == 0 and int(dut.busy.value) == 0
    # reset in the middle of an operation: dropped, outputs cleared
    for kind, op in (("front", ops[0][1] if ops[0][0] == "front" else fr[0]), ("mod", md[0])):
        for k, v in op.items():
            getattr(dut, k).value = v
        getattr(dut, f"start_{kind}").value = 1
        await RisingEdge(dut.clk)
        getattr(dut, f"start_{kind}").value = 0
        for _ in range(LAT[kind] // 2):
            await RisingEdge(dut.clk)
        dut.rst.value = 1
        await RisingEdge(dut.clk)
        dut.rst.value = 0
        for _ in range(LAT["mod"] + 5):
            await RisingEdge(dut.clk)
            await ReadOnly()
            assert int(dut.done.value) == 0 and int(dut.busy.value) == 0 and int(dut.sat.value) == 0
            assert _outs(dut) == (0, 0, 0, 0, 0), "outputs not cleared by reset"
        await RisingEdge(dut.clk)
    dut._log.info(f"protocol: {len(ops)} mixed requests checked every cycle over {cyc} cycles "
                  f"({n_b2b} back-to-back, {n_spur} ignored starts while busy, {n_both} start_mod with "
                  f"start_front ignored); reset mid-front and mid-mod")


@cocotb.test()
async def product(dut):
    """The multiplier lent to the sequencer: prod = mul_b (sampled in the clock before a front's
    done) * i_q, exact, from the third clock after done through the fourth after the next start
    (front or mod, from the done cycle on), with garbage on mul_b in every other clock."""
    in_w = int(os.environ["XFORM_IN_W"])
    hp = int(os.environ["XFORM_HP"])
    rng = random.Random(SEED + 11)
    await _setup(dut)
    fr = _front_vectors(rng, in_w, 60)
    md = [dict(zip(MOD_IN, v)) for v in _mod_vectors(rng, hp, 20)]
    mb_corners = [LO, LO + 1, -1, 0, 1, HI - 1, HI]
    cyc, n, n_chk = 0, 0, 0
    start, kind_f, exp, valid_to = None, None, None, None   # valid_to: last cycle prod must hold
    ops = [("front", o) for o in fr] + [("mod", o) for o in rng.sample(md, 20)]
    rng.shuffle(ops)
    ops = [("front", fr[0])] + ops
    nxt, mb = 0, None
    while nxt < len(ops) or start is not None:
        dut.start_front.value = 0
        dut.start_mod.value = 0
        done_cyc = None if start is None else start + LAT[kind_f]
        new = None
        if (start is None or cyc == done_cyc) and nxt < len(ops) and rng.random() >= 0.5:
            kind, op = ops[nxt]
            for k, v in op.items():
                getattr(dut, k).value = v
            getattr(dut, f"start_{kind}").value = 1
            new = (cyc, kind)
        if start is not None and kind_f == "front" and cyc == done_cyc - 1:
            mb = rng.choice(mb_corners) if rng.random() < 0.3 else rng.randint(LO, HI)
            dut.mul_b.value = mb
        else:
            dut.mul_b.value = rng.randint(LO, HI)                # not sampled
        await RisingEdge(dut.clk)
        if start is not None and cyc == done_cyc:
            assert int(dut.done.value) == 1
            if kind_f == "front":
                exp = mb * dut.i_q.value.to_signed()
                valid_from, valid_to = cyc + 3, None
                n += 1
            start = None
        if exp is not None and cyc >= valid_from and (valid_to is None or cyc <= valid_to):
            assert dut.prod.value.to_signed() == exp, f"cycle {cyc}: prod {dut.prod.value.to_signed()}, expected {exp}"
            n_chk += 1
        if new is not None:
            start, kind_f = new
            nxt += 1
            if exp is not None and valid_to is None:
                valid_to = cyc + 4
        cyc += 1
    dut._log.info(f"product: {n} fronts, prod checked in {n_chk} cycles (mul_b corners and random)")


@cocotb.test(skip=os.environ.get("XFORM_SWEEP", "0") != "1")
async def angle_sweep(dut):
    """All 65536 angles, front op with i_a = 0, i_b - i_c = 8191: i_beta = 75665 > 2^16, so
    i_d = (sin i_beta + 2^15) >> 16 and i_q = (cos i_beta + 2^15) >> 16 are strictly monotonic
    in sin / cos: any sin/cos error shows."""
    hp = int(os.environ["XFORM_HP"])
    await _setup(dut)
    ops = [{"i_a": 0, "i_b": 4095, "i_c": -4096, "angle": a} for a in range(1 << 16)]
    beta = clarke(0, 4095, -4096)[1]
    assert beta > 1 << 16
    n = await _bulk(dut, [("front", o) for o in ops], hp)
    dut._log.info(f"angle_sweep: {n} angles bit-exact (i_beta = {beta})")
