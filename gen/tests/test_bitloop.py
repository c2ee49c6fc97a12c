"""The bit-accurate axis loop (gen/empc/bitloop.py).

``AxisModel`` is the one per-PWM-period model of the RTL axis: ``bitloop.simulate`` steps it with
the Python plant, the RTL co-simulation (tb/test_closed_loop.py) steps it with what the RTL's
trigger sampled and checks every compare value against it.  Here: its reference sources and its
period bookkeeping, and the closed loop against the float loop within test_scenarios' tolerance.
"""
import numpy as np
import pytest

from empc import bitloop, closedloop as cl, config, design, scenarios
from empc.controllers.explicit import ExplicitMPC
from empc.rtlmodel.ref_gen import RefGen, segments_from_points


def _cfg(name):
    sc, alg = scenarios.get(name)
    return sc, config.default().with_control(algorithm=alg, task=sc.task)


def test_axis_model_needs_one_reference_source():
    sc, cfg = _cfg("load_step")
    p = design.design(cfg, 2, "position")["params"]
    with pytest.raises(ValueError, match="exactly one reference source"):
        bitloop.AxisModel(cfg, p)
    with pytest.raises(ValueError, match="exactly one reference source"):
        bitloop.AxisModel(cfg, p, refgen=RefGen(cfg.control.N), refs=lambda k, t: [0] * (cfg.control.N + 1))


def test_axis_model_refgen_and_refs_agree():
    """The reference generator's model and a function giving the same references per control
    period drive the sequencer model to the same compare values; control periods every M periods."""
    sc, cfg = _cfg("position_alg2")
    c = cfg.control
    p = design.design(cfg, 2, "position")["params"]
    slots = segments_from_points(scenarios.POINTS[sc.name], 1.0 / cfg.rad_per_count, c.Ts)
    gen = RefGen(c.N)
    gen.load_program(slots)
    gen.start(0)
    shadow = RefGen(c.N)
    shadow.load_program(slots)
    shadow.start(0)
    a = bitloop.AxisModel(cfg, p, refgen=gen)
    b = bitloop.AxisModel(cfg, p, refs=lambda k, t: shadow.advance())
    rng = np.random.default_rng(5)
    count, n_control = 0, 0
    for period in range(40 * cfg.pwm_per_control):
        count += int(rng.integers(-3, 4))
        codes = [int(x) for x in cfg.sensors.adc_offset + rng.integers(-200, 200, 3)]
        control = a.control_next
        oa, ob = a.period(count, codes), b.period(count, codes)
        assert oa["control"] == ob["control"] == control
        assert oa["cmp"] == ob["cmp"] and oa["ref_w"] == ob["ref_w"], period
        assert all(0 <= x <= cfg.pwm_half_period for x in oa["cmp"])
        n_control += control
    assert n_control == a.k == 40 and a.periods == 40 * cfg.pwm_per_control
    assert a.last_control["ref_w0"] == a.last_control["ref_w"][0] and a.u == b.u


def test_bitloop_follows_float():
    """The bit-accurate closed loop tracks like the float loop (fitted gains): RMS error and peak
    current within test_scenarios' tolerance (5 %, 15 %)."""
    sc, cfg = _cfg("load_step")
    r = bitloop.simulate(cfg, sc)
    f = cl.simulate(cfg, ExplicitMPC(cfg), sc)
    kw = dict(settle_floor=4 * cfg.rad_per_count, preview=cfg.control.N * cfg.control.Ts)
    mb, mf = cl.metrics(r.trace, sc, **kw), cl.metrics(f, sc, **kw)
    assert len(r.cmp) == round(sc.duration / cfg.control.Ts) * cfg.pwm_per_control
    assert r.cmp.min() >= 0 and r.cmp.max() <= cfg.pwm_half_period
    assert abs(mb["rms_error"] - mf["rms_error"]) <= 0.05 * mf["rms_error"], (mb["rms_error"], mf["rms_error"])
    assert abs(mb["peak_phase_current"] - mf["peak_phase_current"]) <= 0.15 * mf["peak_phase_current"]


def test_bitloop_speed_window_at_50us():
    """The design's speed window in the RTL's loop model: the BLWR233D algorithm-2 position design at 50 us
    has speed_window = 8 in its Ts_50us table (KACC.win = 3: CtrlSeq with the position history, bit-exact
    with rtl/mx_seq.v in tb/test_mx_seq.py; test_motors.test_closed_loop_at_50us_speed_window's design and
    bounds) and tracks like the fixed-point controller: RMS error within 10 % + 1 count, peak phase current
    <= 1.05 i_max, u_q tail RMS <= 0.25 u_max (M = 1: 0.37, the quantisation chatter the window removes)."""
    from empc import corners
    cfg = corners.load("blwr233d", **{"control.Ts": 50e-6, "inverter.f_pwm": corners.TS_PWM})
    assert bitloop.regs_for(cfg, "position", 2).win_shift == 3 and bitloop.regs_for(cfg, "speed", 1).win_shift == 0
    sc, c, tr_x, _ = corners.simulate(cfg, "position_alg2", "nominal", "fixed", 0.06)
    r = bitloop.simulate(c, sc)
    res = cfg.rad_per_count
    kw = dict(settle_floor=4 * res, preview=cfg.control.N * cfg.control.Ts)
    mb, mx = cl.metrics(r.trace, sc, **kw), cl.metrics(tr_x, sc, **kw)
    _, t0, t1, _, _ = sc.segments[0]
    tail = (r.trace.t >= t0 + 0.7 * (t1 - t0)) & (r.trace.t < t1 - cfg.control.N * cfg.control.Ts)
    uq_tail = float(np.std(r.trace.u_q[tail]) / cfg.u_max)
    peak = float(np.max(r.trace.i_phase_peak) / cfg.control.i_max)
    print("bitloop M = 8:", {"rms": mb["rms_error"], "rms_fixed": mx["rms_error"], "uq_tail": uq_tail, "peak": peak})
    assert abs(mb["rms_error"] - mx["rms_error"]) <= 0.10 * mx["rms_error"] + res, (mb["rms_error"], mx["rms_error"])
    assert peak <= 1.05 and uq_tail <= 0.25, (peak, uq_tail)


@pytest.mark.parametrize("plant", ["corner_a", "corner_b"])
def test_bitloop_speed_window_load_at_box_corners(plant):
    """control.speed_window = 4 (KACC.win = 2) off the nominal path: the EC 45 flat's algorithm-2 speed design at
    250 us (its design check passes with the window's lag) in the RTL's loop model, the plant at the robustness
    box's corners (corner_a: the design check's least-damped point, L +30 %, R -30 %, J -30 %, psi +20 %;
    corner_b: the opposite), load_speed's rated-current load torque 0.10-0.25 s at the held speed: the speed
    holds without offset under the load (mean error < 0.05 count per Ts, test_scenarios' bound), the load
    current is on (i_q = I / psi factor within 12 %, the EC 45's friction), i_d stays near 0, every step
    settles (to max(2 %, one count per Ts)) within 40 ms, peak |i| <= 1.05 i_max."""
    from empc import corners
    cfg = corners.load("ec45flat_24v", **{"control.speed_window": 4})
    sc, c, tr, f = corners.simulate(cfg, "load_speed", plant, "bit")
    assert bitloop.regs_for(c, "speed").win_shift == 2 and sc.task == "speed"
    assert f is not None and [abs(f[k] - 1.0) for k in ("L", "R", "J", "psi")] == pytest.approx([0.3, 0.3, 0.3, 0.2]), f
    res, I = c.rad_s_per_count_ts, c.ratings.current
    held = (tr.t >= 0.18) & (tr.t < 0.25)                 # under the load, after its step (as test_alg2_load)
    y = tr.output("speed")
    offset = float(np.mean(y[held] - tr.ref[held, 2]))
    iq, id_ = float(np.mean(tr.i_q[held])) * f["psi"] / I, float(np.mean(tr.i_d[held])) / I
    m = cl.metrics(tr, sc, settle_floor=res, preview=c.control.N * c.control.Ts)
    peak = float(np.max(tr.i_phase_peak) / c.control.i_max)
    print(f"bitloop M = 4 at {plant} {f}: offset {offset:.3f} rad/s (count/Ts {res:.2f}), i_q x psi {iq:.3f} I, "
          f"i_d {id_:.4f} I, settle {m['settling_time_max']}, peak {peak:.3f} i_max")
    assert abs(offset) < 0.05 * res, offset
    assert abs(iq - 1.0) < 0.12 and abs(id_) < 0.1, (iq, id_)
    assert m["unsettled_steps"] == 0 and m["settling_time_max"] <= 0.04, m["settling_time_max"]
    assert peak <= 1.05, peak
