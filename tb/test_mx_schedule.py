"""Tests of the four-axis planning tools behind docs/four_axes.md (fast: no Yosys).

flow/mx_schedule.py   schedule of the shared engine: latency budget, stagger, every Ts combination
(seq_timeline, the bit-serial ctrl_seq's timeline that docs/four_axes.md 4.1 starts from,
was retired with ctrl_seq: its figures were measured at d212ea6 and, after issue 15, on ctrl_int:
trigger -> cmp_load 981 clk, 574 engine clocks without the ADC sample, 256 with it, sweep 511.)

The figures asserted here are the ones docs/four_axes.md quotes; a change of the timing table or of
today's sequencer that moves them fails here first.
"""
from __future__ import annotations

import dataclasses
import re
from pathlib import Path


import mx_budget as B
import mx_schedule as S

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "four_axes.md"


def test_alu_list_schedule():
    t = S.TIMING
    # a dependent chain takes alu_lat per op; independent ops issue one per clock
    last, rdy = S.alu_span([("a", (), "op"), ("b", ("a",), "op"), ("c", (), "wr")], t)
    assert rdy["a"] == t.alu_lat and rdy["b"] == 2 * t.alu_lat and rdy["c"] == 2 and last == 2 * t.alu_lat
    last, rdy = S.alu_span([("k", ("x",), "shift")], t, {"x": 3})
    assert rdy["k"] == 3 + 1 + t.kshift


def test_single_axis_latency_budget():
    """Last ADC bit -> cmp_load: the sum of the budget table's rows, <= 300 for every core size."""
    t = S.TIMING
    for ncols, lat in ((23, 245), (64, 286)):
        r = S.simulate([S.AxisCfg(ncols=ncols)], t)
        shape = S.job_shape(S.AxisCfg(ncols=ncols), t)
        rows = ((t.adc_valid - t.adc_last_bit) + 1 + t.xf_front + shape.dep_alu + 1 + shape.core + 1
                + t.xf_mod + 1)
        assert r.latency_last_bit[0] == rows == lat <= 300
        assert r.overruns == 0 and r.ref_late == 0


def test_stagger_keeps_single_axis_latency():
    """Worst case (every axis a control period every PWM period): each axis's latency is the
    single-axis figure, no unit is ever waited for; without the stagger the fourth axis queues
    behind three others and misses the 300-clock requirement (the check can fail)."""
    single = S.simulate([S.AxisCfg()]).latency_last_bit[0]
    for na in range(1, 5):
        r = S.simulate([S.AxisCfg() for _ in range(na)])
        assert set(r.latency_last_bit.values()) == {single}
        assert r.conflicts == 0 and r.overruns == 0
    r = S.simulate([S.AxisCfg() for _ in range(4)], offsets=[0, 0, 0, 0])
    assert r.conflicts > 0 and max(r.latency_last_bit.values()) > 300


def test_stagger_offsets():
    t = S.TIMING
    assert S.stagger(4, t) == [0, 1258, 2516, 3774]          # 17 frames of 74 clocks
    assert S.stagger(2, t) == [0, 2516]
    for na in range(1, 5):
        g = S.adc_grid_check(na, t)
        assert g["mid_grid"] and g["rephase_ok"]
        gd = S.adc_grid_check(na, S.DUAL_TIMING, dual=True)
        assert gd["mid_grid"] and gd["grid_periodic"]


def test_windows_disjoint_and_mutant():
    for na in range(1, 5):
        ok, w = S.windows_disjoint(na)
        assert ok, w["min_gap"]
    # a stagger of 2 frames instead of 17 puts two axes' jobs on top of each other
    bad = dataclasses.replace(S.TIMING, tf=74)
    orig = S.stagger
    try:
        S.stagger = lambda naxes, t, dual=False: [a * 148 for a in range(naxes)]
        assert not S.windows_disjoint(4, bad)[0]
    finally:
        S.stagger = orig


def test_every_ts_combination_quick():
    rep = S.run_all(quick=True)
    sw = rep["sweep"]
    assert sw["combinations"] > 1500
    assert sw["overruns"] == 0 and sw["conflicts"] == 0 and sw["worst_latency_last_bit"] <= 300
    assert rep["sync_4"]["ref_late"] == 0 and rep["dual_4"]["overruns"] == 0
    assert rep["dual_sync_4"]["ref_late"] == 0 and rep["dual_sync_4"]["overruns"] == 0


def test_doc_quotes_the_schedule():
    """The latency figures in docs/four_axes.md are the simulator's."""
    text = DOC.read_text()
    r = S.simulate([S.AxisCfg()])
    assert f"**{r.latency_last_bit[0]} clocks**" in text
    assert re.search(rf"\b{S.simulate([S.AxisCfg(ncols=64)]).latency_last_bit[0]}\b", text)


def test_doc_quotes_the_budget(tmp_path):
    """docs/four_axes.md 8 quotes flow/mx_budget.py's current NAXES = 4 total (measured blocks in)."""
    assert B.main(["--json", str(tmp_path / "b.json")]) == 0
    c = B.current(B.SHARED, 4)
    assert c["lut_flat"] == B.total(B.SHARED, 4)["lut_flat"] + sum(r["measured"] - r["estimate"] for r in c["rows"])
    # every measured block replaces its estimate: a row that matches no MEASURED entry is a typo here
    assert {r["basis"] for r in c["rows"]} == {src for _, src in B.MEASURED.values()}
    text = DOC.read_text()
    assert f"**{c['lut_flat']} LUT,\n    {c['lut_pct']} %: {c['over_cap']} over the 90 % cap**" in text
