"""Print the README's results tables (markdown) from the JSON reports under build/reports/.

Usage: python sim/readme_results.py   (after `make sim`; paste into README.md)
"""
import json
from pathlib import Path

R = Path("build/reports")


def fmt(v, nd=3):
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.{nd}g}"
    return str(v)


def sim_table() -> str:
    rows = ["| scenario | run | RMS error | max overshoot % | settling s | ramp error (mean abs) | peak phase A | limiter active | sim ms / wall s |",
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name in ("speed_steps", "speed_alg2", "position_alg1", "position_alg2", "load_step"):
        p = R / f"sim_{name}.json"
        if not p.exists():
            continue
        r = json.loads(p.read_text())
        for run, m in r["runs"].items():
            rows.append(f"| {name} | {run} | {fmt(m['rms_error'])} | {fmt(m['overshoot_pct_max'])} | "
                        f"{fmt(m['settling_time_max'])} | {fmt(m['ramp_error_mean_abs'])} | "
                        f"{fmt(m['peak_phase_current'])} | {m['saturations']} | {fmt(m['sim_ms_per_wall_s'])} |")
    return "\n".join(rows)


def cosim_table() -> str:
    rows = ["| co-simulation | simulated ms | compare sets checked | mismatches vs model | max latency control / other period (clk) | RTL vs float RMS error (rel.) | sim ms / wall s |",
            "| --- | --- | --- | --- | --- | --- | --- |"]
    for p in sorted(R.glob("closed_loop_*.json")):
        r = json.loads(p.read_text())
        lm = r.get("latency_max_cycles")
        lat = f"{lm['control']} / {lm['modulation']}" if lm else r["latency_adc_trigger_to_pwm_update_cycles"]
        rows.append(f"| {r['scenario']} | {fmt(r['simulated_ms'])} | {r['compare_sets_checked']} | "
                    f"{r['mismatches_vs_bit_accurate_model']} | {lat} | "
                    f"{fmt(r.get('rms_error_rtl_vs_float_rel'))} | {fmt(r['sim_ms_per_wall_s'])} |")
    return "\n".join(rows)


if __name__ == "__main__":
    print(sim_table())
    print()
    print(cosim_table())
