"""`empc compare --quick` (issue 7): the reference controllers of papers 001/002 against our explicit MPC.

Runs the quick comparison once (module fixture; writes build/reports/compare_quick/compare.{json,md}
and the plots) and asserts properties of the results:
- under +-30 % L/R mismatch (and the 0.5 us dead time of 001's bench) DB-MPCC-I, CCS-MPCC and our
  explicit MPC are offset-free (|mean error| < 0.05 A) while the absolute deadbeat (eqs. 8-9) keeps
  an offset > 0.3 A; the printed eq. (10) law is offset-free too (it is incremental; see the report);
- no controller commands |u| > Udc/sqrt3 (or the 4 V circle of 001 Fig. 6) in any scenario;
- 001 scenario 2: every offset-free controller reaches 90 % of the i_q step within 1 ms;
- field weakening (002): the 002 MPC reaches 320 rad/s with i_d < -1 A and |u| >= 0.9 Udc/sqrt3,
  and 150 rad/s (below base speed) is reached without field weakening first;
- our bit-accurate RTL model follows the float explicit MPC (same figures within tolerance);
- the RTL latency column comes from the core's model (mpc_core.latency: LATENCY_BASE + ncols of the design).
Solver agreement (GI = quadprog etc.) is in test_qp_solvers.py.
"""
import fcntl
import json
import math
import os
from pathlib import Path

import pytest

from empc.fileio import write_atomic
from empc.papers import compare

# quick results go beside the full report, not over it (`empc compare` writes build/reports/compare.*)
OUT = Path(os.environ.get("EMPC_COMPARE_OUT", "build/reports/compare_quick"))


@pytest.fixture(scope="module")
def rep(testrun_uid):
    # pytest-xdist spreads this module's tests over both workers and each would build the module
    # fixture (24 s): the first worker runs the comparison, the other waits on the lock and reads the
    # compare.json of the same test run (the run's uid is in the file; an older file is never reused).
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / ".fixture.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            d = json.loads((OUT / "compare.json").read_text())
        except (OSError, ValueError):
            d = {}
        if d.get("testrun_uid") == testrun_uid:
            return d
        r = compare.run(quick=True, out=OUT)
        d = json.loads((OUT / "compare.json").read_text())
        d["testrun_uid"] = testrun_uid
        write_atomic(OUT / "compare.json", json.dumps(d, indent=1) + "\n")
    print(f"quick comparison: {len(r['cases'])} cases, {sum(len(c['runs']) for c in r['cases'].values())} "
          f"closed-loop runs in {r['wall_s']:.1f} s -> {OUT}/compare.md")
    return r


@pytest.mark.cost(25)          # the module fixture's comparison (24 s): started with the long tests
def test_outputs_written(rep):
    d = json.loads((OUT / "compare.json").read_text())
    assert set(d["cases"]) == set(rep["cases"])
    md = (OUT / "compare.md").read_text()
    for key, c in rep["cases"].items():
        assert (OUT / c["plot"]).stat().st_size > 10000, key
        assert c["title"] in md
        for label in c["runs"]:
            assert f"| {label} |" in md


@pytest.mark.parametrize("key", ["mismatch_p30", "mismatch_m30"])
def test_offset_free_under_mismatch(rep, key):
    runs = rep["cases"][key]["runs"]
    for label in ("DB-MPCC-I", "CCS-MPCC (IPM)", "ours: explicit MPC alg.1", "ours: RTL bit-accurate",
                  "DB-MPCC eq.10"):
        ss = runs[label]["ss_error_dq"]
        assert max(abs(v) for v in ss) < 0.05, (key, label, ss)
    ss_abs = runs["DB-MPCC eq.8-9"]["ss_error_dq"]
    assert max(abs(v) for v in ss_abs) > 0.3, ss_abs
    print(key, {k: [round(v, 4) for v in m["ss_error_dq"]] for k, m in runs.items()})


def test_voltage_limit_respected(rep):
    n = 0
    for key, c in rep["cases"].items():
        for label, m in c["runs"].items():
            assert m["u_violations"] == 0, (key, label, m["u_max_ratio"])
            n += 1
    print(f"{n} runs, none above the voltage circle")


def test_current_step_speed(rep):
    runs = rep["cases"]["s2_iq_step"]["runs"]
    for label, m in runs.items():
        if max(abs(v) for v in m["ss_error_dq"]) < 0.1:
            assert m["t90"] is not None and m["t90"] < 1e-3, (label, m.get("t90"))
    # 002's MPC has no disturbance model: in the current-control role it keeps an offset
    assert max(abs(v) for v in runs["online MPC 002 (GI)"]["ss_error_dq"]) > 0.3


def test_field_weakening(rep):
    c = rep["cases"]["fw_002"]
    m = c["runs"]["online MPC 002 (GI) + PI + FW"]
    assert abs(m["fw_final_speed_mech"] - 320.0) < 0.01 * 320.0, m["fw_final_speed_mech"]
    assert m["fw_final_i_d"] < -1.0, m["fw_final_i_d"]
    assert m["fw_final_u_ratio"] >= 0.9, m["fw_final_u_ratio"]
    assert m["fw_t_reach_150"] is not None and m["fw_t_reach_320"] > m["fw_t_reach_150"]
    for label, r in c["runs"].items():
        assert abs(r["fw_final_speed_mech"] - 320.0) < 0.02 * 320.0, (label, r["fw_final_speed_mech"])
        assert r["fw_final_i_d"] < -1.0, label
    # the current constraint polygon/circle of the MPCs holds (up to a sample of overshoot)
    assert m["i_peak"] < 1.05 * 20.0, m["i_peak"]
    assert c["runs"]["CCS-MPCC (IPM) + PI + FW"]["i_peak"] < 1.05 * 20.0


def test_rtl_model_follows_float(rep):
    for key in ("s2_iq_step", "mismatch_p30", "000_speed_steps"):
        runs = rep["cases"][key]["runs"]
        f = next(m for k, m in runs.items() if k.startswith("ours: explicit"))
        x = runs["ours: RTL bit-accurate"]
        if f.get("ss_error_dq"):
            assert all(abs(a - b) < 0.01 for a, b in zip(f["ss_error_dq"], x["ss_error_dq"])), key
        assert abs(f["rise_time"] - x["rise_time"]) <= 2 * rep["cases"][key]["Ts"], key
        assert abs((f["overshoot_pct"] or 0) - (x["overshoot_pct"] or 0)) < 3.0, key


def test_rtl_latency_from_model(rep):
    """Latency = the model's LATENCY_BASE + ncols of the design actually built (the RTL is checked against
    the same function in tb/test_mpc_core.py), for every design of the report and other horizons."""
    from empc import config, design
    from empc.rtlmodel import mpc_core as core
    cfg = config.default()
    for key, lat in rep["rtl_latency"].items():
        alg, task = int(key[3]), key.split("_")[1]
        ncols = design.design(cfg, alg, task)["params"].ncols
        assert lat["cycles"] == core.LATENCY_BASE + ncols and lat["source"] == "gen/empc/rtlmodel/mpc_core.py", key
    assert rep["rtl_latency"]["alg1_speed"]["cycles"] == 38 + 17 and rep["rtl_latency"]["alg2_speed"]["cycles"] == 38 + 23
    for N in (1, 2, 6, 8):
        assert compare.rtl_latency(1, "speed", N)["cycles"] == core.LATENCY_BASE + 3 * N + 5
        assert compare.rtl_latency(2, "position", N)["cycles"] == core.LATENCY_BASE + 3 * N + 11
    md = (OUT / "compare.md").read_text()
    assert "alg1_speed 55" in md, "compare.md does not state the model's latency"


def test_explicit_ops_count():
    o = compare.explicit_ops(1, 4)
    # 17 columns: 2 x 17 polynomials (2 mul + 2 add), 2 x 17 products and sums
    assert o.mul >= 2 * 17 * 2 + 2 * 17 and o.flops < 400
    assert compare.explicit_ops(2, 4).flops > o.flops
    assert math.isfinite(o.flops)
