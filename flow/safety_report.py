"""`make safety`: build/reports/safety.json, the issue-14 safety summary, from the reports the tests wrote.

Inputs (build/reports/, written by the tests; a missing one is named in the report, not invented):
  closed_loop_<run>.json   tb/test_closed_loop.py, one fault co-simulation per cause: latency from the
                           pin event to every bridge output off (clocks), one clear -> outputs on (clocks),
                           peak current before the fault / in the 20 periods after the restart
  formal.json              flow/formal.py: every SymbiYosys task and mutant with its result
  regblock_<block>.json    tb/test_regblock.py: writes tried against the generated register blocks and
                           how many the rules refused (every output compared with the model every clock)
  empc_drv.json            tb/test_empc_drv.py: the RW registers written over the bus with patterns,
                           the writes the map refuses (legal values, unlock) read back unchanged
  config_errors.json       the configuration checker's report (bad configuration files tried / refused;
                           issue 14 "configuration input", ctrl_design branch) if present

Output: build/reports/safety.json; a table on stdout.  Exit status 1 if a cause has no passing
co-simulation or a proof/mutant failed.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

from files import ROOT  # flow/ is on sys.path

REPORTS = ROOT / "build" / "reports"

# FAULT cause -> (co-simulation run in tb/test_closed_loop.py COSIM, pin event the latency is measured from,
# further tests)
CAUSES = {
    "overcurrent": ("overcurrent", "CS fall (conversion start) of the ADC frame with the over-threshold code",
                    ["tb/test_adc_spi.py (every frame, 4 configurations, vs AdcSpiCycle)"]),
    "hall": ("hall", "HALL pins to 000 (illegal code)", ["tb/test_hall_decoder.py"]),
    "encoder": ("encoder", "first simultaneous A/B toggle (illegal quadrature transition)",
                ["tb/test_irc_decoder.py"]),
    "watchdog": ("watchdog", "the watchdog expiry (WDOG_TIMEOUT PWM periods after the last kick)",
                 ["tb/test_watchdog.py"]),
    "dclink": ("dclink", "start of the CPU write of an out-of-range UDC (stale / missing: formal A2, reset)",
               ["tb/test_empc_drv.py (missing UDC after reset)"]),
    "overrun": ("overrun", "the PWM update the control period missed",
                ["tb/test_mx_seq.py (a boundary during a running period)", "tb/test_closed_loop.py (overrun run)"]),
    "adc": ("adc_frame", "CS fall of the first frame with a leading bit 1", ["tb/test_adc_spi.py"]),
    "pstage": ("pstage", "pwr_fault_n falling (3 ns pulse)", ["tb/test_out_kill.py (300 sub-clock pulses)"]),
    "clock": ("clock", "the last fabric clock edge (clock stopped)", ["tb/test_clk_mon.py", "tb/test_out_kill.py"]),
    "coef": (None, "no valid coefficient image, or its control period is not CTRL.pwm_per_control: a state, "
                   "the bridges never switch",
             ["tb/test_mpc_core.py bad_boot, image_checks (43 swap decisions: image checks and the control period)"]),
    "hall_enc": ("hall_enc", "HALL pins two sectors ahead of the encoder angle", ["tb/test_sens_check.py"]),
    "enc_break": ("line_break", "encoder A/B frozen while the rotor turns", ["tb/test_sens_check.py"]),
    "adc_stuck": ("adc_stuck", "CS fall of the first frame with a channel at the rail (overcurrent masked)",
                  ["tb/test_adc_spi.py"]),
    "adc_sum": ("adc_sum", "CS fall of the first frame with |i_a + i_b + i_c| over ADC_SUM_THRESH",
                ["tb/test_adc_spi.py"]),
    "adc_frozen": ("adc_frozen", "CS fall of the first frame of a channel frozen bit-identical",
                   ["tb/test_adc_spi.py"]),
}
# proofs that hold for every cause (the cause vector is free in them) and those of particular causes
PROOFS_ALL = ("axis_periph/prove_pe", "axis_periph/prove_cp", "axis_periph/bmc_pe", "pwm_center/prove_n3",
              "pwm_center/prove_n2", "pwm_center/prove_n1")
PROOFS_CAUSE = {"pstage": ("out_kill/prove", "out_kill/bmc"), "clock": ("out_kill/prove", "out_kill/bmc")}


def _load(name: str):
    p = REPORTS / name
    return json.loads(p.read_text()) if p.exists() else None


def build() -> dict:
    from empc import regmap
    formal = (_load("formal.json") or {}).get("entries", {})
    causes, bad = {}, []
    for f in regmap.FAULT_CAUSES:
        run, event, tests = CAUSES[f.name]
        c = {"fault_bit": f.lsb, "maskable": f.name not in ("pstage", "clock", "coef", "watchdog", "overrun"),
             "pin_event": event, "tests": list(tests)}
        if run:
            # make sim runs some fault runs only as their lockstep copy (tb/test_closed_loop.py LOCKSTEP): same run
            rep = _load(f"closed_loop_{run}.json") or _load(f"closed_loop_{run}_lockstep.json")
            c["co_simulation"] = f"tb/test_closed_loop.py cosim_fault_{run}"
            if rep is None or "fault" not in rep:
                c["co_simulation_result"] = "missing: run tb/test_closed_loop.py"
                bad.append(f"{f.name}: no co-simulation report")
            else:
                fr = rep["fault"]
                c.update({"pin_event_to_outputs_off_clk": fr["pin_event_to_outputs_off_clk"],
                          "stated_bound_clk": fr["stated_bound_clk"],
                          "clear_to_outputs_on_clk": fr["clear_to_outputs_on_clk"],
                          "peak_current_a_before": round(fr["peak_a_before"], 3),
                          "peak_current_a_after_restart": round(fr["peak_a_after_restart"], 3),
                          "fault_bits_latched": fr["fault_bits_latched"],
                          "mismatches_vs_model": rep["mismatches_vs_bit_accurate_model"],
                          "co_simulation_result": "pass"})
                if run == "clock":
                    c["pins_off_after_stop_ns"] = rep.get("kill_path", {}).get("pins_off_after_stop_ns")
                    c["pins_off_oscillator_cycles"] = rep.get("kill_path", {}).get("pins_off_osc_cycles")
                if run == "pstage":
                    c["pins_off_clock_edges"] = rep.get("kill_path", {}).get("pins_off_clock_edges")
        labels = PROOFS_ALL + PROOFS_CAUSE.get(f.name, ())
        c["proofs"] = {lab: ("PASS" if formal[lab]["ok"] else "FAIL") if lab in formal else "not run"
                       for lab in labels}
        bad += [f"{f.name}: proof {lab} {v}" for lab, v in c["proofs"].items() if v != "PASS"]
        causes[f.name] = c
    mutants = {k: v for k, v in formal.items() if v.get("kind") == "mutant"}
    bad += [f"mutant {k} not caught" for k, v in mutants.items() if not v.get("ok")]
    writes = {}
    for p in sorted(REPORTS.glob("regblock_*.json")):
        r = json.loads(p.read_text())
        writes[r["block"]] = {"writes": r["writes"], "refused": r["refused_writes"],
                              "unlocked_writes": r.get("unlocked_writes")}
    drv = _load("empc_drv.json")
    if drv:
        writes["bus (tb/test_empc_drv.py)"] = {"refused": drv["writes_refused_as_the_map_says"]}
    cfg = _load("config_errors.json")
    return {
        "causes": causes,
        "formal": {"tasks": {k: v["sby"] for k, v in formal.items() if v.get("kind") == "proof"},
                   "mutants_caught": sum(1 for v in mutants.values() if v.get("ok")),
                   "mutants": {k: {"what": v.get("what"), "caught": v.get("ok")} for k, v in mutants.items()}},
        "bad_register_writes": {"by_source": writes,
                                "refused_total": sum(w.get("refused", 0) or 0 for w in writes.values())},
        "bad_configurations": cfg if cfg is not None else
        "build/reports/config_errors.json not present (written by the configuration checker of the ctrl_design "
        "branch)",
        "problems": bad,
    }


def main() -> int:
    rep = build()
    REPORTS.mkdir(parents=True, exist_ok=True)
    (REPORTS / "safety.json").write_text(json.dumps(rep, indent=1) + "\n")
    print(f"{'cause':12s} {'pins off (clk)':>15s} {'bound':>7s} {'restart (clk)':>14s} {'peak A before/after':>20s}")
    for name, c in rep["causes"].items():
        lat = c.get("pin_event_to_outputs_off_clk", "-")
        pk = (f"{c['peak_current_a_before']:.2f}/{c['peak_current_a_after_restart']:.2f}"
              if "peak_current_a_before" in c else "-")
        print(f"{name:12s} {lat!s:>15s} {c.get('stated_bound_clk', '-')!s:>7s} "
              f"{c.get('clear_to_outputs_on_clk', '-')!s:>14s} {pk:>20s}")
    print(f"mutants caught: {rep['formal']['mutants_caught']}/{len(rep['formal']['mutants'])}; "
          f"bad register writes refused: {rep['bad_register_writes']['refused_total']}")
    for p in rep["problems"]:
        print(f"safety: {p}", file=sys.stderr)
    print(f"wrote {REPORTS / 'safety.json'}")
    return 1 if rep["problems"] else 0


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT / "gen"))
    raise SystemExit(main())
