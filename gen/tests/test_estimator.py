"""Speed estimate (estimator.py, issue 15 item 1): offset-free under a constant load with
"accel_load", the half-period correction kept along an acceleration, and state_space() equal to
the stepped estimator (the robust check plugs it in as a linear block)."""
import numpy as np
import pytest

from empc import config, estimator
from empc.rtlmodel import ctrl_seq as cs

CFG = config.default()
SEED = 15


def _cfg(kind):
    return CFG.with_control(speed_estimate=kind)


def _run(kind, w_true, i_q):
    """Estimates for a rotor at speeds w_true[k] (rad/s at the sampling instants, the angle
    integrated exactly between them) with the measured current i_q[k]."""
    Ts = CFG.control.Ts
    est = estimator.SpeedEstimator(_cfg(kind))
    theta, out = 0.0, []
    for k in range(len(w_true)):
        if k:
            theta += 0.5 * (w_true[k - 1] + w_true[k]) * Ts     # piecewise-linear speed
        out.append(est.step(theta, i_q[k]))
    return np.array(out)


@pytest.mark.parametrize("i_load", [5.0, -3.0])
def test_constant_load_offset(i_load):
    """The rotor turns at 300 rad/s, i_q holds a load: "accel" reads kc i_load high (the old
    25 rad/s at 5 A), "accel_load" converges to the true speed."""
    n = 600
    w = np.full(n, 300.0)
    i = np.full(n, i_load)
    kc = CFG.speed_correction
    assert kc * 5.0 > 20.0                                   # the 25 rad/s at 5 A
    assert abs(_run("accel", w, i)[-1] - 300.0 - kc * i_load) < 1e-9
    e = _run("accel_load", w, i) - 300.0
    assert abs(e[-1]) < 1e-3 * kc * abs(i_load), e[-1]
    assert abs(_run("eq37", w, i)[-1] - 300.0) < 1e-9


def test_acceleration_half_period_kept():
    """No load, the torque accelerates the rotor: w37 lags by Ts/2 x acceleration; "accel" and
    "accel_load" both give the speed at the sampling instant (D stays 0)."""
    Ts, kc = CFG.control.Ts, CFG.speed_correction
    i = np.full(400, 2.0)
    acc = 2.0 * kc / (Ts / 2)                                # rad/s^2 that i_q = 2 A produces
    w = acc * Ts * np.arange(400)
    e = _run("accel", w, i) - w
    assert np.max(np.abs(e[1:])) < 1e-6 * w[-1], np.max(np.abs(e[1:]))
    # accel_load: only the start-up transient of D (its first update has no speed change to
    # compare with), decaying with 1 - 2^-s
    e = _run("accel_load", w, i) - w
    assert abs(e[-1]) < 1e-3, e[-5:]
    assert np.all(np.abs(e[3:]) <= np.abs(e[2:-1]) + 1e-9)     # monotone decay from k = 2
    e37 = _run("eq37", w, i) - w
    assert abs(e37[-1] + acc * Ts / 2) < 1e-6 * w[-1]


@pytest.mark.parametrize("task", ["speed", "position"])
def test_loop_model_with_estimator(task):
    """The design check's loop model (loop.py: the plant with the PWM update delay, the estimator
    block from state_space, the law) against a step-by-step loop of the same delayed plant, the
    algorithm-1 law and the float SpeedEstimator (zero references, a random start): the same
    trajectory.  Plus: accel_load keeps accel's spectral radius up to its own pole 1 - 2^-s."""
    from empc import loop, mpc, robust
    rng = np.random.default_rng(SEED)
    cfg = CFG.with_control(algorithm=1, task=task)
    ctrl, m, w0 = cfg.control, cfg.motor, 300.0
    g = mpc.gains(m, ctrl, w0, 1, task)
    lp = loop.loop(cfg, m, w0, 1, task, g)
    delay = 0.5 / cfg.inverter.f_pwm
    Ad, B0, B1 = loop.plant_delayed(m, w0, ctrl.Ts, delay)
    C = loop.model.output_matrix(task)[:, :loop.NP]
    K_dx = g["K_dx"][:, :loop.NP]
    Kx = -(g["K_e"] @ np.kron(np.ones((ctrl.N, 1)), np.eye(3)) @ C) - K_dx
    x = np.r_[rng.normal(0, 1, 3), 0.3]
    um = rng.normal(0, 2, 2)
    est = estimator.SpeedEstimator(cfg)
    est.theta_prev, est.w37_prev, est.D = rng.normal(0, 0.1), rng.normal(0, 5), rng.normal(0, 2)
    xhm = np.r_[rng.normal(0, 1, 2), rng.normal(0, 5), est.theta_prev]
    s = np.zeros(lp.T.shape[0])
    s[lp.idx["p"]] = x
    s[lp.idx["z"]] = [est.theta_prev, est.w37_prev, est.D]
    s[lp.idx["u"]] = um
    s[lp.idx["xp"]] = xhm
    for k in range(60):
        assert np.allclose(s[lp.idx["p"]], x, rtol=1e-7, atol=1e-7), (k, s[lp.idx["p"]], x)
        xh = np.r_[x[0], x[1], est.step(x[3], x[1]), x[3]]
        u = um + Kx @ xh + K_dx @ xhm
        assert np.allclose(lp.Cu @ s, u, rtol=1e-7, atol=1e-7), k
        x = Ad @ x + B0 @ u + B1 @ um
        um, xhm = u, xh
        s = lp.T @ s
    pole = 1.0 - 2.0 ** -CFG.speed_load_shift
    for tk in ("speed", "position"):
        c = CFG.with_control(algorithm=1, task=tk)
        r = {kind: robust.survey(c.with_control(speed_estimate=kind), 1, tk,
                                 {"exact": robust.exact_gains(c, 1, tk)})["worst_radius"].value
             for kind in ("accel", "accel_load")}
        assert r["accel_load"] <= max(r["accel"], pole) + 2e-3, (tk, r, pole)
    assert loop.estimator_for(CFG).name == "accel_load" and loop.estimator_for(CFG).nz == 3


def test_raw_estimate_tracks_float():
    """The sequencer model's raw estimate (rtlmodel/ctrl_seq.speed_estimate, Q16.16 counts/Ts)
    against the float form fed with the same quantised angle and current: within the KACC
    rounding (0.5 % of kc |i_q|) and the truncation of the load update (2^-8 count/Ts)."""
    from empc import bitloop, formats
    rng = np.random.default_rng(SEED)
    regs = bitloop.regs_for(CFG, "speed")
    assert regs.load_shift == CFG.speed_load_shift > 0
    est = estimator.SpeedEstimator(CFG)
    st = {"D": 0, "spd_prev": 0}
    lsb_i = CFG.amps_per_lsb / (1 << formats.I_FRAC)
    kc = CFG.speed_correction
    pos, w, worst = 0, 0.0, 0.0
    for k in range(3000):
        if k % 500 == 0:
            i_load = rng.uniform(-8, 8)
        i_q = i_load + rng.normal(0, 0.5)
        w += rng.normal(0, 3.0)                         # a wandering speed, rad/s
        pos += int(round(w * CFG.control.Ts / CFG.rad_per_count))
        iq_raw = int(round(i_q / lsb_i))
        dpos = pos - (st.get("pos_prev", 0))
        st["pos_prev"] = pos
        om, sat = cs.speed_estimate(dpos, iq_raw, regs, st)
        assert not sat
        wf = est.step(pos * CFG.rad_per_count, iq_raw * lsb_i)
        wr = om / (1 << formats.W_FRAC) * CFG.rad_s_per_count_ts
        if k > 0:
            err = abs(wr - wf)
            worst = max(worst, err)
            assert err < 0.005 * kc * 8.5 + 2.0 ** -8 * CFG.rad_s_per_count_ts, (k, wr, wf)
    print("raw vs float speed estimate: max |diff| %.4f rad/s" % worst)


# ------------------------------------------------------------------------------------------------
# control.speed_window = M > 1: the difference over M periods (the RTL: KACC.win in rtl/mx_seq.v; `empc roms`
# refuses a load shift below log2 M - 1: test_roms_refuse_speed_window).
WINDOWS = [2, 4, 8]


def _wcfg(kind, M):
    return CFG.with_control(speed_estimate=kind, speed_window=M)


def test_speed_window_default_is_one():
    assert CFG.control.speed_window == 1
    assert _wcfg("accel_load", 4).speed_correction == 4 * CFG.speed_correction
    assert estimator.state_space(_wcfg("accel_load", 1))["states"] == ("w37_prev", "D_load")


@pytest.mark.parametrize("M", [1] + WINDOWS)
@pytest.mark.parametrize("kind", ["eq37", "accel", "accel_load"])
def test_state_space_matches_step(kind, M):
    """state_space() (the design check's estimator block; M = 1: eq. 37 over one period) equals the
    stepped float estimate; accel_load's load state is stable (pole 1 - 2^-s) and i_q has no DC gain
    to the estimate."""
    rng = np.random.default_rng(SEED)
    cfg = _wcfg(kind, M)
    ss = estimator.state_space(cfg)
    est = estimator.SpeedEstimator(cfg)
    theta = np.cumsum(rng.normal(0, 0.1, 200))
    iq = rng.normal(0, 3, 200)
    est.step(theta[0], iq[0])                                 # history = theta_0: s_j = 0, D
    z = np.zeros(ss["A"].shape[0])
    if kind == "accel_load":
        z[-1] = est.D
    for k in range(1, 200):
        v = np.array([theta[k] - theta[k - 1], iq[k]])
        w_ss = (ss["C"] @ z + ss["D"] @ v).item()
        z = ss["A"] @ z + ss["B"] @ v
        w = est.step(theta[k], iq[k])
        assert abs(w - w_ss) < 1e-9 * (1 + abs(w)), (k, w, w_ss)
    if kind == "accel_load":
        A, B, C, D = ss["A"], ss["B"], ss["C"], ss["D"]
        assert np.max(np.abs(np.linalg.eigvals(A))) < 1.0
        dc = C @ np.linalg.solve(np.eye(A.shape[0]) - A, B[:, 1:2]) + D[:, 1:2]
        assert abs(dc.item()) < 1e-9                          # offset-free under a constant load


@pytest.mark.parametrize("M", WINDOWS)
def test_speed_window_acceleration_and_load(M):
    """The window's lag (M/2) Ts is corrected along an acceleration ("accel"; "accel_load" after D's
    start-up transient), and "accel_load" is offset-free under a constant load."""
    Ts = CFG.control.Ts
    cfg = _wcfg("accel", M)
    kc = cfg.speed_correction
    i = np.full(800, 2.0)
    acc = 2.0 * kc / (M * Ts / 2)
    w = acc * Ts * np.arange(800)

    def run(c, w, i):
        est = estimator.SpeedEstimator(c)
        theta, out = 0.0, []
        for k in range(len(w)):
            if k:
                theta += 0.5 * (w[k - 1] + w[k]) * Ts
            out.append(est.step(theta, i[k]))
        return np.array(out)
    e = run(cfg, w, i) - w
    assert np.max(np.abs(e[M:])) < 1e-6 * w[-1], np.max(np.abs(e[M:]))
    e = run(_wcfg("accel_load", M), w, i) - w
    assert abs(e[-1]) < 1e-3, e[-5:]
    e37 = run(_wcfg("eq37", M), w, i) - w
    assert abs(e37[-1] + acc * M * Ts / 2) < 1e-6 * w[-1]
    wl = np.full(800, 300.0)
    e = run(_wcfg("accel_load", M), wl, np.full(800, 5.0)) - 300.0
    assert abs(e[-1]) < 1e-3 * kc * 5.0, e[-1]


@pytest.mark.parametrize("M", WINDOWS)
def test_speed_window_raw_tracks_float(M):
    """The fixed-point window (ctrl_seq.speed_estimate with win_shift = log2 M, as FixedMPC runs it)
    against the float window fed with the same quantised angle and current."""
    import dataclasses

    from empc import bitloop, formats
    cfg = _wcfg("accel_load", M)
    rng = np.random.default_rng(SEED)
    regs = dataclasses.replace(bitloop.regs_for(cfg, "speed"), win_shift=M.bit_length() - 1)
    est = estimator.SpeedEstimator(cfg)
    st = {"D": 0, "spd_prev": 0}
    lsb_i = cfg.amps_per_lsb / (1 << formats.I_FRAC)
    kc = cfg.speed_correction
    pos, w, hist = 0, 0.0, [0] * M
    for k in range(3000):
        if k % 500 == 0:
            i_load = rng.uniform(-8, 8)
        i_q = i_load + rng.normal(0, 0.5)
        w += rng.normal(0, 3.0)
        pos += int(round(w * cfg.control.Ts / cfg.rad_per_count))
        iq_raw = int(round(i_q / lsb_i))
        om, sat = cs.speed_estimate(pos - hist[0], iq_raw, regs, st)
        hist = hist[1:] + [pos]
        assert not sat
        wf = est.step(pos * cfg.rad_per_count, iq_raw * lsb_i)
        wr = om / (1 << formats.W_FRAC) * cfg.rad_s_per_count_ts
        if k >= M:
            assert abs(wr - wf) < 0.005 * kc * 8.5 + 2.0 ** -8 * cfg.rad_s_per_count_ts, (k, wr, wf)


def test_roms_refuse_speed_window(tmp_path):
    """The RTL implements speed_window = 1..2^WIN_LOG2_MAX (16; KACC.win) with speed_load_shift + 1 >= log2 M:
    `empc roms` (and the RTL's loop model) refuse the largest M with a load shift of log2 M - 2, with one
    line naming the keys, and write nothing; the largest M with the default shift 6 passes the check."""
    from empc import bitloop, cli, roms, scenarios
    from empc import formats as F
    mmax = F.WIN_LOG2_MAX
    big = 1 << mmax
    assert config.RTL_SPEED_WINDOWS == config.SPEED_WINDOWS == tuple(1 << m for m in range(mmax + 1))
    assert big == F.WIN_DEPTH == cs.HIST == 1 << cs.WIN_MAX
    config.require_rtl_speed_window(CFG.with_control(speed_estimate="accel_load", speed_window=big))
    cfg = CFG.with_control(speed_estimate="accel_load", speed_window=big, speed_load_shift=mmax - 2)
    with pytest.raises(config.ConfigError,
                       match=rf"^control\.speed_window = {big} needs control\.speed_load_shift >= {mmax - 1}"):
        roms.generate(cfg, tmp_path / "r")
    assert not (tmp_path / "r").exists()
    assert cli.main(["roms", "--set", "control.speed_estimate=accel_load", "--set", f"control.speed_window={big}",
                     "--set", f"control.speed_load_shift={mmax - 2}", "--out", str(tmp_path / "c")]) != 0
    assert not (tmp_path / "c").exists()
    sc, _ = scenarios.get("speed_steps", cfg)
    with pytest.raises(config.ConfigError, match="control.speed_window"):
        bitloop.simulate(cfg, sc)


def test_speed_window_max_one_source():
    """The largest speed window has one source, formats.WIN_LOG2_MAX: the configuration's choices, the
    sequencer model, the Verilog header (EMPC_WIN_LOG2_MAX, EMPC_WIN_DEPTH, used by rtl/mx_seq.v for the
    history depth, the tap and the clamp: no hand-written depth there), the firmware header and KACC.win's text."""
    import re
    from pathlib import Path
    from empc import fwheader, header, regmap
    from empc import formats as F
    consts = header.flat(CFG)
    assert consts["WIN_LOG2_MAX"] == F.WIN_LOG2_MAX and consts["WIN_DEPTH"] == 1 << F.WIN_LOG2_MAX
    assert fwheader.expected_macros()["EMPC_WIN_LOG2_MAX"] == F.WIN_LOG2_MAX
    key = next(k for k in config.SCHEMA if (k.table, k.name) == ("control", "speed_window"))
    assert key.choices == config.SPEED_WINDOWS
    win = next(f for f in regmap.axis_reg("KACC").fields if f.name == "win")
    assert F.WIN_LOG2_MAX < 1 << win.width and f"act as {F.WIN_LOG2_MAX};" in win.doc
    assert cs.win_eff(7) == cs.win_eff(F.WIN_LOG2_MAX) == F.WIN_LOG2_MAX and cs.win_eff(1) == 1
    rtl = (Path(__file__).resolve().parents[2] / "rtl" / "mx_seq.v").read_text()
    assert "`EMPC_WIN_LOG2_MAX" in rtl and "`EMPC_WIN_DEPTH" in rtl
    assert not re.search(r"reg\s*\[15:0\]\s*sr\b|3'd4|5'd1 << j_win", rtl), "a hand-written window depth in mx_seq.v"
