#!/usr/bin/env python3
"""Benchmark: peak phase current / i_max of every bundled motor's scenarios at the robustness-box corners.

For each configuration in gen/empc/configs/ (empc.corners.MOTORS) and each bundled design (the
[weights.alg<a>.<task>] it has), every scenario of that design (empc.scenarios) at its own control
period, with the plant at ``nominal``, ``corner_a`` (the design check's least-damped box point) and
``corner_b`` (the opposite point), in float (ExplicitMPC, fitted gains) and fixed point (FixedMPC);
and every design at 50 us and at each period the configuration has a control-period table for
([weights.<design>.Ts_<us>us]) on its first step (20 kHz PWM; ``weights``: the table or ``base``).
Scenarios longer than --max-duration (spmsm_002's field_weakening, 12.7 s) are cut to it.

Writes build/reports/current_corners.json: ``runs`` (one entry per motor / design / Ts / scenario /
plant / form: peak |i| / i_max, the time, segment and i_d, i_q of the peak, the plant factors),
``over`` (the runs above the limit, 1.05 i_max), ``worst`` (per motor and design) and the command.

    PYTHONPATH=gen .venv/bin/python flow/current_corners.py [--forms float,fixed] [--motors a,b]
        [--no-tables] [--no-governor] [--json build/reports/current_corners.json] [--table]

One process (about 4 CPU minutes for float and fixed).  ``--no-governor`` runs the same with the
reference governor off (the current limit's contribution; it writes current_corners_nogov.json);
``--table`` prints the markdown table of docs/design.md from existing reports; the bit-accurate loop
(bitloop, the RTL axis model) at the configured Ts: ``--forms bit --no-tables --json
build/reports/current_corners_bit.json`` (120 runs, 93 s CPU).
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from files import REPORTS, ROOT  # noqa: E402

sys.path.insert(0, str(ROOT / "gen"))
from empc import corners  # noqa: E402

MAX_DURATION = 1.0


def _row(motor, design, ts, table, r, cpu):
    return {"motor": motor, "design": design, "Ts": ts, "weights": table, "scenario": r["scenario"],
            "plant": r["plant"], "form": r["form"], "peak": round(r["peak"], 4), "t": round(r["t"], 6),
            "segment": r["segment"], "segment_kind": r["segment_kind"], "i_d": round(r["i_d"], 4),
            "i_q": round(r["i_q"], 4), "adc_range": round(r["adc_range"], 4), "duration": r["duration"],
            "factors": r["factors"], "cpu_s": round(cpu, 2)}


def run(motors, forms, tables=True, governor=True, max_duration=MAX_DURATION, log=print) -> dict:
    rows = []
    t_all = time.process_time()

    def one(motor, cfg, design, table, scen, plant, form, duration):
        t0 = time.process_time()
        r = corners.measure(cfg, scen, plant, form, duration=duration, governor=governor)
        row = _row(motor, design, cfg.control.Ts, table, r, time.process_time() - t0)
        rows.append(row)
        log(f"{motor:13s} {design:14s} {1e6 * cfg.control.Ts:5.0f}us {table:8s} {scen:16s} {plant:9s} {form:6s} "
            f"{row['peak']:6.3f} at {row['t']:.4f} s seg {row['segment']}"
            + ("  > %.2f" % corners.LIMIT if row["peak"] > corners.LIMIT else ""))

    for motor in motors:
        cfg = corners.load(motor)
        for scen, alg, task in corners.scenario_list(cfg):
            for plant in corners.PLANTS:
                for form in forms:
                    one(motor, cfg, f"alg{alg}.{task}", corners.table_of(cfg, alg, task), scen, plant, form,
                        max_duration)
        for ts in (corners.other_ts(motor) if tables else []):
            c = corners.load_ts(motor, ts)
            for (alg, task) in sorted(c.control.weights):
                scen, dur = corners.TS_STEP[(alg, task)]
                for plant in corners.PLANTS:
                    for form in forms:
                        one(motor, c, f"alg{alg}.{task}", corners.table_of(c, alg, task), scen, plant, form, dur)
    over = [r for r in rows if r["peak"] > corners.LIMIT]
    worst = {}
    for r in rows:
        k = f"{r['motor']} {r['design']} {1e6 * r['Ts']:.0f}us"
        if k not in worst or r["peak"] > worst[k]["peak"]:
            worst[k] = {x: r[x] for x in ("peak", "scenario", "plant", "form", "t", "segment")}
    return {"limit": corners.LIMIT, "governor": governor, "forms": list(forms), "max_duration": max_duration,
            "plants": {"nominal": "configured motor", "corner_a": "the design check's least-damped box point",
                       "corner_b": "the opposite point (factors 2 - f)"},
            "cpu_s": round(time.process_time() - t_all, 1), "runs": rows, "over": over, "worst": worst}


def table(reps: list) -> str:
    """Markdown: per motor, design and Ts the largest peak over its scenarios at each plant (float / fixed
    / bit where measured; the reports' runs merged) and the scenario of the largest."""
    rows, order = {}, []
    forms = [f for f in ("float", "fixed", "bit") if any(f in rep["forms"] for rep in reps)]
    limit = reps[0]["limit"]
    for r in (r for rep in reps for r in rep["runs"]):
        k = (r["motor"], r["design"], r["Ts"], r["weights"])
        if k not in rows:
            rows[k] = {}
            order.append(k)
        cell = rows[k].setdefault(r["plant"], {})
        if r["peak"] > cell.get(r["form"], (-1.0, ""))[0]:
            cell[r["form"]] = (r["peak"], r["scenario"])
    out = ["| motor | design | Ts | weights | nominal | corner_a | corner_b | largest in |",
           "|---|---|---|---|---|---|---|---|"]
    for k in order:
        m, d, ts, w = k
        cells, top = [], (-1.0, "")
        for plant in ("nominal", "corner_a", "corner_b"):
            c = rows[k].get(plant, {})
            vals = [c[f][0] for f in forms if f in c]
            txt = " / ".join(f"{v:.2f}" for v in vals)
            cells.append(f"**{txt}**" if vals and max(vals) > limit else txt)
            for f in c.values():
                if f[0] > top[0]:
                    top = (f[0], f"{f[1]} {plant}")
        out.append(f"| {m} | {d} | {1e6 * ts:.0f} us | {w} | " + " | ".join(cells) + f" | {top[1]} |")
    return "\n".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--motors", default=",".join(corners.MOTORS))
    ap.add_argument("--forms", default="float,fixed", help="float, fixed, bit (bit: slow)")
    ap.add_argument("--no-tables", action="store_true", help="only the configured Ts (no 50 us, no tables)")
    ap.add_argument("--no-governor", action="store_true", help="reference governor off (its contribution)")
    ap.add_argument("--max-duration", type=float, default=MAX_DURATION)
    ap.add_argument("--json", type=Path)
    ap.add_argument("--table", action="store_true",
                    help="print the markdown table of the reports (--json, default current_corners.json and "
                         "current_corners_bit.json where present) and stop")
    a = ap.parse_args(argv)
    if a.table:
        paths = [a.json] if a.json else [p for p in (REPORTS / "current_corners.json", REPORTS / "current_corners_bit.json")
                                           if p.exists()]
        print(table([json.loads(p.read_text()) for p in paths]))
        return 0
    rep = run(a.motors.split(","), a.forms.split(","), tables=not a.no_tables, governor=not a.no_governor,
              max_duration=a.max_duration)
    rep["command"] = "PYTHONPATH=gen .venv/bin/python flow/current_corners.py " + " ".join(argv or sys.argv[1:])
    out = a.json or REPORTS / ("current_corners_nogov.json" if a.no_governor else "current_corners.json")
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(rep, indent=1) + "\n")
    print(f"{len(rep['runs'])} runs, {len(rep['over'])} above {corners.LIMIT} i_max, {rep['cpu_s']} s CPU -> {out}")
    for r in sorted(rep["over"], key=lambda r: -r["peak"]):
        print(f"  {r['peak']:.3f}  {r['motor']} {r['design']} {1e6 * r['Ts']:.0f}us {r['weights']} {r['scenario']} "
              f"{r['plant']} {r['form']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
