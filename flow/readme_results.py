"""Render the README's results tables from the JSON reports under build/reports/.

Usage: .venv/bin/python flow/readme_results.py            print every table (markdown)
       .venv/bin/python flow/readme_results.py --write    replace the marked blocks in README.md

A block in README.md is ``<!-- BEGIN NAME -->`` ... ``<!-- END NAME -->`` (NAME one of TABLES);
``--write`` rewrites the text between the markers and leaves everything else alone.  A table whose
reports do not exist yet is left as it is (the script says which command produces them).
Producers: `make sim` (sim_*.json, closed_loop_<co-simulation>.json, mpc_core.json vectors),
`make sim-full` (closed_loop_<soak run>.json), `make bench` (mpc_core.json resources: flow/synth.py
--top mpc_core --summary),
`make synth` (synth.json), `empc compare` (compare.json; `--quick` in make sim: compare_quick/),
`empc check --scenarios --config gen/empc/configs/<motor>.toml` (design_<motor>.json).
`--write` also copies the PNG figures the README shows (docs/img/NAME.png) from build/reports/NAME.png.
"""
from __future__ import annotations

import json
import re
import shutil
import sys
from pathlib import Path

from files import REPORTS as R, ROOT  # flow/ is on sys.path


def fmt(v, nd=3):
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.{nd}g}"
    return str(v)


def _load(p: Path):
    return json.loads(p.read_text()) if p.exists() else None


def sim_table() -> str | None:
    rows = ["| scenario | run | RMS error | max overshoot % | settling s | ramp error (mean abs) | peak phase current A | peak abs(i_dq) A | limiter active (periods) | sim ms / wall s |",
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name in ("speed_steps", "speed_alg2", "position_alg1", "position_alg2", "load_step",
                 "speed_limit", "position_large", "load_speed", "field_weakening"):
        r = _load(R / f"sim_{name}.json")
        if r is None:
            continue
        for run, m in r["runs"].items():
            rows.append(f"| {name} | {run} | {fmt(m['rms_error'])} | {fmt(m['overshoot_pct_max'])} | "
                        f"{fmt(m['settling_time_max'])} | {fmt(m['ramp_error_mean_abs'])} | "
                        f"{fmt(m['peak_phase_current'])} | {fmt(m.get('peak_current'))} | {m['saturations']} | "
                        f"{fmt(m['sim_ms_per_wall_s'])} |")
    return "\n".join(rows) if len(rows) > 2 else None


def cosim_table() -> str | None:
    rows = ["| co-simulation | simulated ms | compare sets checked | mismatches vs model | max latency control / other period (clk) | RTL vs float RMS error (rel.) | sim ms / wall s | sim ms / CPU s | clocks / CPU s |",
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for p in sorted(R.glob("closed_loop_*.json")):
        # proofs of the core's clock gating, same runs: the row of the plain run, or of the lockstep copy where
        # make sim runs only that (tb/test_closed_loop.py LOCKSTEP)
        if p.stem.endswith("_lockstep") and p.with_name(p.name.replace("_lockstep", "")).exists():
            continue
        r = json.loads(p.read_text())
        if "axes" in r:             # closed_loop_4axes.json (tb/test_closed_loop_4axes.py): a row per axis
            for a in r["axes"]:
                lm = a["detail"].get("latency_max_cycles") or {}
                rows.append(f"| 4axes: {a['axis']} {a['name']} ({fmt(a['Ts_us'])} us) | {fmt(r['simulated_ms'])} | "
                            f"{a['compare_sets_checked']} | {a['mismatches']} | "
                            f"{lm.get('control', '-')} / {lm.get('modulation', '-')} | "
                            f"{fmt(a.get('rms_error_rtl_vs_float_rel'))} | {fmt(r['simulated_ms'] / r['wall_s'])} | "
                            f"{fmt(r['sim_ms_per_cpu_s'])} | {fmt(r['simulated_ms'] * 1e5 / r['cpu_s'])} |")
            continue
        lm = r.get("latency_max_cycles")
        lat = f"{lm['control']} / {lm['modulation']}" if lm else r["latency_adc_trigger_to_pwm_update_cycles"]
        rows.append(f"| {r['scenario']} | {fmt(r['simulated_ms'])} | {r['compare_sets_checked']} | "
                    f"{r['mismatches_vs_bit_accurate_model']} | {lat} | "
                    f"{fmt(r.get('rms_error_rtl_vs_float_rel'))} | {fmt(r['sim_ms_per_wall_s'])} | "
                    f"{fmt(r.get('sim_ms_per_cpu_s'))} | {fmt(r.get('clocks_per_cpu_s'))} |")
    return "\n".join(rows) if len(rows) > 2 else None


def core_table() -> str | None:
    r = _load(R / "mpc_core.json")
    if r is None or "stream_jobs" not in r:
        return None
    rows = ["| image | vectors (corner cases) | mismatches | latency (clk) |", "| --- | --- | --- | --- |"]
    for j in r["stream_jobs"]:
        rows.append(f"| {j['name']} | {j['vectors']} ({j.get('corners', '-')}) | {j['mismatches']} | {j.get('latency', '-')} |")
    rows.append(f"| **all** (seed {r.get('seed')}) | {r['vectors']} | {r['mismatches']} | |")
    out = "\n".join(rows)
    if "lut" in r:
        lat = r.get("latency_cycles")
        lat = ", ".join(f"{k} {v}" for k, v in lat.items()) if isinstance(lat, dict) else fmt(lat)
        out += ("\n\nCore alone (`make bench`: `flow/synth.py --top mpc_core`, the timing proxy of `make synth`): "
                f"{r['lut']} LUT, {r['ff']} FF, {r['dsp48a1']} DSP48A1, {fmt(r['ramb16'])} RAMB16 (RAMB8 = 0.5); "
                f"latency {lat} cycles ({r.get('latency_formula', '')}); timing proxy "
                f"{fmt(r.get('clock_mhz'))} MHz (target {r.get('clock_mhz_target', 100)}).")
    return out


def compare_table() -> str | None:
    # `empc compare` writes build/reports/compare.json (full); make sim's quick run a subdirectory
    for d in ("", "compare/", "compare_quick/"):
        r = _load(R / f"{d}compare.json")
        if r is not None:
            break
    else:
        return None
    cases = r["cases"]
    rows = [f"From `build/reports/{d}compare.json` ({'quick' if r.get('quick') else 'full'} run, "
            f"`empc compare{' --quick' if r.get('quick') else ''}`).", "",
            "| case | controller | rise ms | overshoot % | ss error | ripple d / q A | flops per step (mean) |",
            "| --- | --- | --- | --- | --- | --- | --- |"]
    for key in ("s2_iq_step", "mismatch_p30", "s1_speed", "000_speed_steps"):
        c = cases.get(key)
        if c is None:
            continue
        for name, m in c["runs"].items():
            rise = m.get("rise_time")
            sse = m.get("ss_error_dq", m.get("ss_error"))
            sse_s = " / ".join(fmt(x) for x in sse) if isinstance(sse, list) else fmt(sse)
            rip = m.get("ripple_dq")
            rows.append(f"| {key} | {name} | {fmt(rise * 1e3 if rise is not None else None, 2)} | "
                        f"{fmt(m.get('overshoot_pct'), 2)} | {sse_s} | "
                        f"{' / '.join(fmt(x) for x in rip) if rip else '-'} | {fmt(m.get('flops_mean'), 4)} |")
    return "\n".join(rows)


def synth_table() -> str | None:
    r = _load(R / "synth.json")
    if r is None:
        return None
    cap, res, util = r["capacity"], r["resources"], r["utilisation_pct"]
    rows = ["| resource | used | XC6SLX9 | % | budget |", "| --- | --- | --- | --- | --- |"]
    for k, name in (("lut", "LUT6 cells (logic + LUT-RAM + INV)"), ("ff", "flip-flops"), ("dsp48a1", "DSP48A1"),
                    ("ramb16", "RAMB16 (RAMB8 = 0.5)"), ("iob", "IOB")):
        if k in res:
            b = (r.get("budget") or {}).get(k, "-")
            rows.append(f"| {name} | {fmt(res[k])} | {fmt(cap.get(k, '-'))} | {fmt(util.get(k), 3)} | {b} |")
    t = r.get("timing") or {}
    out = "\n".join(rows)
    if t:
        out += (f"\n\nTiming proxy (no placement, rough -2 delays): worst register-to-register path "
                f"{fmt(t.get('worst_path_ns'))} ns ({t.get('worst_path_lut_levels')} LUT levels, end "
                f"`{t.get('worst_path_endpoint')}`), est. fmax {fmt(t.get('est_fmax_mhz'))} MHz (target {fmt(t.get('target_mhz'))}, "
                f"budget {(r.get('budget') or {}).get('fmax_mhz', '-')}); "
                f"max LUT levels register to register {t.get('max_lut_levels')}.")
    return out


MOTORS = ("blwr233d", "ipmsm_001", "spmsm_002", "ec45flat_24v", "premo_320v")


def motors_table() -> str | None:
    """Bundled motors: ratings, worst radius / damping over the robustness box and Omega_e (all
    designs, configured Ts), fit error, the Ts variants, scenario figures (`empc check --scenarios`)."""
    rows = ["| motor | Udc V | P W | J kg m^2 | i_max A | Ts us | designs pass (Ts / 250 / 50 us) | worst radius (bound; where) "
            "| worst damping (where) | worst fit % | speed_steps fixed: RMS err, peak A | position_alg1 fixed: RMS err, peak A |",
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name in MOTORS:
        r = _load(R / f"design_{name}.json")
        if r is None:
            continue
        v = r["variants"]
        conf = v.get("configured", {})
        ds = conf.get("designs", {})
        if not ds:
            continue
        wr = max((d for d in ds.values() if "worst_radius" in d), key=lambda d: d["worst_radius"]["value"] - d["radius_bound"])
        wz = min((d for d in ds.values() if "worst_damping" in d), key=lambda d: d["worst_damping"]["value"])
        fit = max(d.get("fit_worst", {}).get("fit_rel", 0.0) for d in ds.values())

        def npass(label):
            dd = v.get(label, {}).get("designs", {})
            return f"{sum(1 for d in dd.values() if d.get('passed'))}/{len(dd)}" if dd else "-"
        sc = r.get("scenarios", {})

        def scen(n):
            m = sc.get(n, {}).get("fixed")
            return f"{fmt(m['rms_error'])}, {fmt(m['peak_phase_current'])}" if isinstance(m, dict) else "-"
        rows.append(f"| {r['motor']} | {fmt(r['Udc_V'])} | {fmt(r['ratings']['power_W'])} | {fmt(r['J_kg_m2'])} | "
                    f"{fmt(r['i_max_A'])} | {fmt(1e6 * conf['Ts'])} | {npass('configured')} / {npass('Ts_250us')} / "
                    f"{npass('Ts_50us')} | {wr['worst_radius']['value']:.5f} ({wr['radius_bound']:.5f}; "
                    f"{wr['worst_radius']['plant']}, {wr['worst_radius']['omega_e']:.0f} rad/s) | "
                    f"{wz['worst_damping']['value']:.3f} ({wz['worst_damping']['plant']}, "
                    f"{wz['worst_damping']['omega_e']:.0f} rad/s, {wz['worst_damping']['freq_hz']:.0f} Hz) | "
                    f"{100 * fit:.1f} | {scen('speed_steps')} | {scen('position_alg1')} |")
    return "\n".join(rows) if len(rows) > 2 else None


TABLES = {"RESULTS_TABLE": sim_table, "COSIM_TABLE": cosim_table, "CORE_TABLE": core_table,
          "COMPARE_TABLE": compare_table, "SYNTH_TABLE": synth_table, "MOTORS_TABLE": motors_table}


def write_readme(path: Path = ROOT / "README.md") -> list[str]:
    text = path.read_text()
    done = []
    for name, fn in TABLES.items():
        body = fn()
        if body is None:
            print(f"{name}: no report yet, left as it is", file=sys.stderr)
            continue
        pat = re.compile(rf"(<!-- BEGIN {name} -->\n).*?(<!-- END {name} -->)", re.S)
        if not pat.search(text):
            print(f"{name}: no <!-- BEGIN {name} --> block in {path.name}", file=sys.stderr)
            continue
        text = pat.sub(lambda m: m.group(1) + body + "\n" + m.group(2), text)
        done.append(name)
    path.write_text(text)
    done += copy_figures(text)
    return done


def copy_figures(text: str) -> list[str]:
    """The README's figures live in docs/img (committed); copy the ones build/reports has."""
    done = []
    for rel in re.findall(r"!\[[^\]]*\]\((docs/img/[^)]+\.png)\)", text):
        src = R / Path(rel).name
        if src.exists():
            dst = ROOT / rel
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(src, dst)
            done.append(rel)
        else:
            print(f"{rel}: no {src.relative_to(ROOT)} yet, left as it is", file=sys.stderr)
    return done


if __name__ == "__main__":
    if "--write" in sys.argv[1:]:
        print("updated:", ", ".join(write_readme()) or "nothing")
    else:
        for name, fn in TABLES.items():
            print(f"## {name}\n{fn() or '(no report yet)'}\n")
