"""Coefficient image and the bit-accurate core model against the float law."""
import os

import numpy as np
import pytest

from empc import config, design, fit, formats as F, image, mpc, quantise
from empc.rtlmodel import mpc_core as core

SEED = int(os.environ.get("EMPC_SEED", "7"))
CFG = config.default()
DESIGNS = {k: design.design(CFG, *k) for k in [(1, "speed"), (1, "position"), (2, "speed"), (2, "position")]}


@pytest.mark.parametrize("key", list(DESIGNS))
def test_image_roundtrip_and_checksum(key):
    p = DESIGNS[key]["params"]
    w = image.encode(p, period=1)
    q = image.decode(w)
    assert q == p
    bad = list(w)
    bad[image.A_GAINS + 5] ^= 1
    with pytest.raises(ValueError, match="checksum"):
        image.decode(bad)


def test_coefficient_count_matches_eq30():
    for (alg, task), d in DESIGNS.items():
        N = CFG.control.N
        expect = (18 * N + 30) if alg == 1 else 3 * (2 * 3 + 2 * 3 * N + 2 * 3 + 2 * 5)
        assert d["report"]["n_coefficients"] == expect
    assert DESIGNS[(1, "speed")]["report"]["n_coefficients"] == 102


def _random_inputs(rng, cfg, task, n_ref):
    """Operating points in SI and their raw encodings."""
    c = cfg.control
    omega = rng.uniform(c.omega_min, c.omega_max)
    i = rng.normal(0, 1.5, 2)
    th = rng.uniform(-200, 200)
    y3 = omega if task == "speed" else th
    W = np.zeros((n_ref, 3))
    W[:, :2] = i + rng.normal(0, 0.3, 2)
    W[:, 2] = y3 + (rng.normal(0, 40, n_ref) if task == "speed" else rng.normal(0, 0.2) + np.arange(n_ref) * omega * c.Ts)
    dx = np.array([rng.normal(0, 0.2), rng.normal(0, 0.2), rng.normal(0, 10), omega * c.Ts, 0.0])
    ebar = rng.normal(0, 0.5, 3) * np.array([1, 1, 20 if task == "speed" else 0.05])
    u_prev = rng.normal(0, 3, 2)
    return omega, np.array([i[0], i[1], y3]), W, dx, ebar, u_prev


def _to_raw(cfg, task, omega, y, W, dx, ebar, u_prev):
    si_i = cfg.amps_per_lsb / (1 << F.I_FRAC)
    si_w = cfg.rad_s_per_count_ts / (1 << F.W_FRAC)
    si_th = cfg.rad_per_count / (1 << F.TH_FRAC)
    s3 = si_w if task == "speed" else si_th
    r = lambda v, s: int(round(v / s))
    yr = (r(y[0], si_i), r(y[1], si_i), r(y[2], s3))
    wr = tuple((r(w[0], si_i), r(w[1], si_i), r(w[2], s3)) for w in W)
    dxr = (r(dx[0], si_i), r(dx[1], si_i), r(dx[2], si_w), r(dx[3], si_th), 0)
    eb = (r(ebar[0], si_i), r(ebar[1], si_i), r(ebar[2], s3))
    up = tuple(r(u, cfg.volts_per_tick / (1 << F.U_FRAC)) for u in u_prev)
    # back to SI so the float law sees exactly the quantised signals
    y_q = np.array([yr[0] * si_i, yr[1] * si_i, yr[2] * s3])
    W_q = np.array([[w[0] * si_i, w[1] * si_i, w[2] * s3] for w in wr])
    dx_q = np.array([dxr[0] * si_i, dxr[1] * si_i, dxr[2] * si_w, dxr[3] * si_th, 0.0])
    eb_q = np.array([eb[0] * si_i, eb[1] * si_i, eb[2] * s3])
    up_q = np.array(up) * cfg.volts_per_tick / (1 << F.U_FRAC)
    return core.Inputs(y=yr, omega=r(omega, si_w), dx=dxr, wref=wr, u_prev=up, ebar_prev=eb), (y_q, W_q, dx_q, eb_q, up_q)


@pytest.mark.parametrize("key", list(DESIGNS))
def test_core_model_vs_float_law(key):
    """du of the bit-accurate core vs the float law with the fitted gains (quantisation only)
    and with the exact gains (fit + quantisation); bounds relative to the voltage limit."""
    alg, task = key
    d = DESIGNS[key]
    p, gf = d["params"], d["fit"]
    rng = np.random.default_rng(SEED + alg * 3 + len(task))
    cfg = CFG
    vpu = cfg.volts_per_tick / (1 << F.U_FRAC)
    worst_fit, worst_exact, n = 0.0, 0.0, 300
    for _ in range(n):
        omega, y, W, dx, ebar, u_prev = _random_inputs(rng, cfg, task, cfg.control.N + 1)
        x, (y_q, W_q, dx_q, eb_q, up_q) = _to_raw(cfg, task, omega, y, W, dx, ebar, u_prev)
        out = core.update(p, x)
        assert out.flags & ~((1 << core.FLAG_BITS["limit"]) | (1 << core.FLAG_BITS["ebar_inc"])) == 0, out.counts
        du_core = np.array(out.du) * vpu
        omega_q = x.omega * cfg.rad_s_per_count_ts / (1 << F.W_FRAC)
        if task == "position":   # relative angles, as the core
            W_q = W_q.copy(); W_q[:, 2] -= y_q[2]; y_q = y_q.copy(); y_q[2] = 0.0
        ebar_k = eb_q
        if alg == 2:
            lim = np.array(p.ebar_lim) * np.array([cfg.amps_per_lsb / 16] * 2 + [
                (cfg.rad_s_per_count_ts / 65536) if task == "speed" else (cfg.rad_per_count / 256)])
            ebar_k = eb_q + np.clip(W_q[0] - y_q, -lim, lim)
        for gains, store in ((gf.evaluate(omega_q), "fit"), (mpc.gains(cfg.motor, cfg.control, float(np.clip(omega_q, cfg.control.omega_min, cfg.control.omega_max)), alg, task), "exact")):
            Wv = W_q[1:].reshape(-1)
            if alg == 1:
                du = gains["K_e"] @ (Wv - np.tile(y_q, cfg.control.N)) - gains["K_dx"] @ dx_q
            else:
                du = gains["K_ebar"] @ ebar_k + gains["K_WL"] @ Wv - gains["K_y"] @ y_q - gains["K_dx"] @ dx_q
            err = float(np.max(np.abs(du - du_core))) / cfg.u_max
            if store == "fit":
                worst_fit = max(worst_fit, err)
            else:
                worst_exact = max(worst_exact, err)
    print(f"seed {SEED}: alg {alg} {task}: {n} points, |du_core - du_float(fitted)| <= {worst_fit:.2e} u_max, "
          f"vs exact gains {worst_exact:.2e} u_max")
    assert worst_fit < 2e-4, worst_fit          # quantisation: below 0.02 % of the voltage limit
    assert worst_exact < 0.05, worst_exact      # fit + quantisation: below 5 % of the voltage limit


def test_limiter_keeps_inside_circle_and_direction():
    rng = np.random.default_rng(SEED)
    u_max = DESIGNS[(1, "speed")]["params"].u_max
    worst_in = 1.0
    for _ in range(5000):
        a = rng.uniform(0, 2 * np.pi)
        m = rng.uniform(1.0, 5.5) * u_max     # |u| < 8192 ticks: no pre-saturation of the limiter operands
        u_raw = [int(m * np.cos(a)) << 4, int(m * np.sin(a)) << 4]
        out, lim = core.limit_circle(u_raw, u_max)
        assert lim
        r = np.hypot(out[0], out[1]) / 16
        assert r <= u_max, (u_raw, out)
        worst_in = min(worst_in, r / u_max)
        if r > 100:
            assert abs(np.angle(complex(*out)) - np.angle(complex(*u_raw))) < 2e-3 or \
                abs(abs(np.angle(complex(*out)) - np.angle(complex(*u_raw))) - 2 * np.pi) < 2e-3
    assert worst_in > 0.997, worst_in
    inside = [int(0.5 * u_max) << 4, -(int(0.5 * u_max) << 4)]
    assert core.limit_circle(inside, u_max) == (inside, False)


# ---- Ts = 50 us: the biased operand shift (formats.SIG_SHIFT_BIAS, issue 16 item 5) ----
MOTORS = ("blwr233d", "ec45flat_24v", "ipmsm_001", "premo_320v", "spmsm_002")


def _quantised(name: str, ts: float | None):
    ov = {} if ts is None else {"control.Ts": ts, "inverter.f_pwm": 20000.0}
    cfg = config.load(config.DEFAULT_CONFIG.parent / f"{name}.toml", ov or None)
    return {k: quantise.build(cfg, *k)[0] for k in sorted(cfg.control.weights)}


@pytest.mark.parametrize("name", MOTORS)
def test_every_design_quantises_at_50us(name):
    """Every design of every bundled motor fits the coefficient format at 50 us (BLWR233D needs product
    shift 16 on some gains: their column takes the bit, c_j = -1; the EC 45 flat's algorithm-2 position
    table did too, K_dx column 21, until its issue-16 retune: every product shift <= 15 now), and at
    the configured Ts and 250 us no column needs the left shift (the designs there are unchanged)."""
    neg = 0
    for key, p in _quantised(name, 50e-6).items():
        assert min(p.col_shift) >= quantise.MIN_SIG_SHIFT == -F.SIG_SHIFT_BIAS
        assert max(c[3] for row in p.coef for c in row) <= quantise.MAX_PROD_SHIFT
        neg += sum(c < 0 for c in p.col_shift)
        for j, c in enumerate(p.col_shift):   # a left-shifted column has a gain at the top product shift
            if c < 0:
                assert max(p.coef[i][j][3] for i in range(2)) == quantise.MAX_PROD_SHIFT, (key, j)
    if name == "blwr233d":
        assert neg > 0
    for ts in (None, 250e-6):
        for key, p in _quantised(name, ts).items():
            assert min(p.col_shift) >= 0, (name, ts, key)


def test_biased_shift_fields_roundtrip_and_model():
    """Image fields hold shift + SIG_SHIFT_BIAS; decode, the bank model and the core model agree on a
    design with left-shifted columns, and a left-shifted column computes with a = 2 S."""
    cfg = config.load(config.DEFAULT_CONFIG, {"control.Ts": 50e-6, "inverter.f_pwm": 20000.0})
    p = quantise.build(cfg, 1, "speed")[0]
    assert -1 in p.col_shift
    fmt = 0x1234
    w = image.encode(p, fmt, period=cfg.pwm_per_control)
    for j, c in enumerate(p.col_shift):
        assert (w[image.A_COLS + j] >> 8) & 0xF == c + F.SIG_SHIFT_BIAS
    assert w[image.A_WS] == p.ws + F.SIG_SHIFT_BIAS
    assert image.decode(w) == p
    assert core.Banks(w, p.N, fmt).active() == p
    with pytest.raises(ValueError):
        image.encode(core.Params(**{**p.__dict__, "ws": image.SHIFT_MIN - 1}), period=1)
    # c_j = -1: a = sat18(2 S) -- the same term as c_j = 0 with the product shift one higher
    one = (1 << (F.OPW - 1)) - 1
    col = lambda c, s: core.Params(**{**p.__dict__, "col_sig": [core.SIG_DX], "col_shift": [c],
                                      "coef": [[(one, 0, 0, s)], [(0, 0, 0, 0)]]})
    dx = lambda v: core.Inputs(y=(0, 0, 0), omega=0, dx=(v, 0, 0, 0, 0), wref=((0, 0, 0),) * (p.N + 1), u_prev=(0, 0))
    for v in (1000, -3000, 32769, -(1 << 16)):
        o = core.update(col(-1, 0), dx(v))
        assert o.du == core.update(col(0, 1), dx(v)).du
        assert o.du[0] == F.rshift_round(one * 2 * v, F.ACC_FRAC - F.U_FRAC) and o.du[0] != 0
        assert not o.counts.get("operand")
    o = core.update(col(-1, 0), dx(1 << 16))                    # 2 S = 2^17 saturates the operand
    assert o.counts.get("operand") and o.du[0] == F.rshift_round(one * one, F.ACC_FRAC - F.U_FRAC)


def test_image_control_period():
    """CFG[23:16] holds the design's control period (PWM periods); image.check accepts it for the build
    whatever the period (the fingerprint has no Ts), and with ``pwm_per_control`` refuses another
    period with a message naming both (the drivers' rule, empc.driver.period_mismatch); reserved CFG
    bits 15 and 7 are refused."""
    from empc import driver, header
    for ts in (50e-6, 100e-6, 250e-6):
        cfg = config.load(None, {"control.Ts": ts, "inverter.f_pwm": 20000.0})
        fmt = header.flat(cfg)["IMG_FMT_ID"]
        assert fmt == header.flat(CFG)["IMG_FMT_ID"]
        p = DESIGNS[(1, "speed")]["params"]
        w = image.encode(p, fmt, period=cfg.pwm_per_control)
        assert image.period(w) == cfg.pwm_per_control and (w[image.A_CFG] >> 16) & 0xFF == cfg.pwm_per_control
        assert image.check(w, p.N, fmt) == [] and image.check(w, p.N, fmt, cfg.pwm_per_control) == []
        assert driver.period_mismatch(w, cfg.pwm_per_control) == ""
        other = 5 if cfg.pwm_per_control != 5 else 1
        why = image.check(w, p.N, fmt, other)
        assert len(why) == 1 and f"control period {cfg.pwm_per_control}" in why[0] and f"pwm_per_control {other}" in why[0]
        assert driver.period_mismatch(w, other) == why[0]
    for bit in (15, 7):
        bad = list(w)
        bad[image.A_CFG] |= 1 << bit
        bad[image.A_CSUM] = image.checksum(bad)
        assert any("reserved" in x for x in image.check(bad, p.N, fmt)), bit
    for per in (0, 256):
        with pytest.raises(ValueError, match="control period"):
            image.encode(p, fmt, period=per)
