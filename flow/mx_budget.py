"""Area budget of the four-axis drive (issue 16; docs/four_axes.md, "Area").

Adds up, block by block, what NAXES = 4 costs replicated (today's mpc_axis four times) and in the
shared design of docs/four_axes.md, on one basis: Yosys `synth_xilinx -family xc6s` per-instance
LUT6 of the hierarchical run (`flow/synth.py --top mpc_axis --hier`), converted to the flattened
`make synth` figure with the ratio measured on today's axis (2299 flat / 2556 hierarchical).

Every row says where its number comes from:
  m     measured on main (c1fdc11), flow/synth.py --top mpc_axis --hier
  m14   measured on issue 14's branches (safety_adc: adc_spi OOC 300 LUT / 559 FF; safety_trip:
        mpc_axis --hier, core +36, fault 21, sens_check 37)
  m15   measured on issue 15's branch (ctrl_law: mpc_axis --hier, core +22, ref_gen 206, regs 220,
        ctrl_seq 278, mpc_axis local 146)
  p     area probe of a design decision (scratch RTL synthesised out of context, see the doc):
        mpc_core with 8 banks and 4 input buffers in the same block RAMs: 1195 and 1198 LUT (two runs)
        vs 1118 flat,
        7.5 RAMB16 both; out_route (16 outputs, ADC / encoder / HALL input selects): 374 LUT
  e     estimate (a cap for the work package that builds it; the doc gives the breakdown)

MEASURED holds the out-of-context figures (`flow/synth.py --top <block>`, flat) of the blocks that
have landed for NAXES axes; "current" replaces each such row's estimate by its measurement (rows
measured only at NAXES = 1 keep the estimate's increment from 1 to NAXES). The budget is then the
estimate of the rows not yet built plus what was built, and the caps of docs/four_axes.md 1.3 stay
the plan it was drawn against.

    .venv/bin/python flow/mx_budget.py [--json build/reports/mx_budget.json]
"""
from __future__ import annotations

import argparse
import json
import sys
from dataclasses import asdict, dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from files import REPORTS  # noqa: E402

LUTS, FFS, DSPS, RAMBS = 5720, 11440, 16, 32
LUT_CAP = int(0.9 * LUTS)          # issue 16: NAXES = 4 <= 90 % of the LUTs
FLAT_PER_HIER = 2299 / 2556        # m: mpc_axis flat / hierarchical (main)


@dataclass(frozen=True)
class Row:
    block: str
    kind: str          # "shared" (one instance), "axis" (per axis), "top"
    lut: int           # hierarchical LUT6 of one instance (shared rows: at NAXES = 4), after issues 14 and 15
    ff: int
    dsp: int
    ramb: float
    basis: str
    note: str = ""
    lut1: int | None = None     # shared rows whose size grows with NAXES: the NAXES = 1 figure
    ff1: int | None = None      # (linear in between)

    def at(self, naxes: int) -> tuple[int, int]:
        """(LUT, FF) of this row in a build with ``naxes`` axes (per-axis rows: all axes)."""
        if self.kind == "axis":
            return naxes * self.lut, naxes * self.ff
        l1 = self.lut if self.lut1 is None else self.lut1
        f1 = self.ff if self.ff1 is None else self.ff1
        return (round(l1 + (self.lut - l1) * (naxes - 1) / 3), round(f1 + (self.ff - f1) * (naxes - 1) / 3))


# one axis as it will be once issues 14 and 15 have landed (what NAXES = 4 replicates)
TODAY = [
    Row("mpc_core", "axis", 1166 + 36 + 22, 1262 + 15 + 2, 6, 7.5, "m, m14, m15"),
    Row("ctrl_seq (local)", "axis", 262 + 11 + 16, 775 + 6 + 96, 0, 2, "m, m14, m15"),
    Row("xform", "axis", 124, 387, 1, 2.5, "m"),
    Row("ref_gen", "axis", 110 + 3 + 96, 179 + 65, 0, 1, "m, m14, m15"),
    Row("axis_status", "axis", 33 - 1, 60, 0, 1, "m, m15"),
    Row("axis_regs", "axis", 190 + 30 + 30, 600 + 117 + 112, 0, 0, "m, m14, m15"),
    Row("adc_spi", "axis", 300, 559, 0, 0, "m14"),
    Row("pos_sense", "axis", 214, 196, 1, 0.5, "m"),
    Row("pwm_center", "axis", 89, 129, 0, 0, "m"),
    Row("irc_decoder", "axis", 84, 172, 0, 0, "m"),
    Row("hall_decoder", "axis", 55, 51, 0, 0, "m"),
    Row("fault_ctrl", "axis", 21, 12, 0, 0, "m14"),
    Row("sens_check", "axis", 37, 24, 0, 0, "m14"),
    Row("mpc_axis (local glue)", "axis", 146 + 20, 60, 0, 0, "m15, e (issue 14 gating +20)"),
    Row("bus, global regs, watchdog, TIME, IRQ", "top", 92, 362, 0, 0, "m (2391 - 2299 flat)"),
    Row("out_kill, clk_mon", "top", 15 + 6, 11 + 14, 0, 0, "m14 (6 outputs)"),
]

SHARED = [
    Row("mpc_core, 8 banks, 4 input buffers", "shared", 1166 + 36 + 22 + 80 + 10, 1262 + 17 + 82 + 4, 6, 7.5,
        "m, m14, m15, p (+77 / +80 LUT in two runs, +82 FF, same RAMs), e (+10 boot into 4 banks)",
        lut1=1166 + 36 + 22, ff1=1262 + 17),
    Row("mx_seq: word ALU sequencer, axis state RAM, job queue", "shared", 300, 500, 1, 1, "e",
        "operand stages 50, ALU / saturation 25, shifter 5, microprogram and waits 40, "
        "4 per-axis timing blocks 80, job queue 20, status / buffer write 30, theta / flags 50",
        lut1=240, ff1=380),
    Row("xform (unchanged)", "shared", 124, 387, 1, 2.5, "m"),
    Row("ref_gen, per-axis state and delay line in block RAM", "shared", 209 + 40, 250, 0, 1.5, "m15, e (+40)",
        lut1=209 + 10, ff1=244),
    Row("axis_status, word-parallel counters", "shared", 32 + 40, 80, 0, 1, "m, e (+40)",
        "one RAMB16 for the status words, counters and register read-back of 4 axes"),
    Row("axis register block", "shared", 330, 800, 0, 0, "e",
        "decode 50, periphery registers in FF (write enables 4 x 40), RO read path 80, RAM read 40",
        lut1=170, ff1=260),
    Row("adc_spi: one frame engine, time-shared serial pass, per-axis checks", "shared", 420, 1780, 0, 0,
        "m14 (300 for one axis), e (+40 per further axis: OC compares, check flags; accumulators in FF)",
        lut1=300, ff1=559),
    Row("pos_sense: one reducer / alignment engine, one angle DSP, per-axis state", "shared", 214 + 70 + 40, 500,
        1, 0.5, "m (214), e (+70 state muxes, +10 per axis)", lut1=214, ff1=196),
    Row("engine glue (issue 15 field weakening, governor hold)", "shared", 100, 60, 0, 0, "m15 (84), e"),
    Row("axis glue (bridges_on, status bits, fault gating)", "axis", 40, 50, 0, 0, "e"),
    Row("pwm_center (carrier offset at reset)", "axis", 89, 129, 0, 0, "m"),
    Row("irc_decoder", "axis", 84, 172, 0, 0, "m"),
    Row("hall_decoder", "axis", 55, 51, 0, 0, "m"),
    Row("fault_ctrl", "axis", 21, 12, 0, 0, "m14"),
    Row("sens_check", "axis", 37, 24, 0, 0, "m14"),
    Row("bus, global regs, watchdog, TIME, IRQ, routing registers", "top", 92 + 10, 362 + 20, 0, 0, "m, e",
        lut1=92, ff1=362),
    Row("out_kill (32 pins), clk_mon", "top", 40 + 6, 35 + 14, 0, 0, "m14 scaled (15 LUT for 6 pins), e",
        lut1=21, ff1=25),
    Row("out_route: 16 outputs, ADC / encoder / HALL selects, phase check", "top", 374 + 25, 160 + 20, 0, 0,
        "p (374), e (+25 mapped-phase scan); NAXES = 1 builds without it (ROUTE = 0)", lut1=0, ff1=0),
]


# Out-of-context measurements (flat LUT of `flow/synth.py --top <block>`) of blocks built for NAXES axes:
# row-name prefix -> {naxes: LUT}, and where the figure comes from (docs/blocks/<block>.md).
MEASURED = {
    "mpc_core": ({1: 1164, 4: 1264}, "docs/blocks/mpc_core.md, piece 1"),
    "mx_seq": ({1: 685, 4: 1058}, "docs/blocks/mx_seq.md, piece 5's sequencer (several axes)"),
    "ref_gen": ({1: 212, 4: 323}, "docs/blocks/ref_gen.md, piece 2a"),
    "axis_status": ({1: 114, 4: 239}, "docs/blocks/axis_status.md, piece 2b"),
    "pos_sense": ({1: 214, 4: 409}, "docs/blocks/pos_sense.md, piece 4b (speed outputs open, as in mpc_axis)"),
    "adc_spi": ({1: 290, 4: 946}, "docs/blocks/adc_spi.md, piece 4 (serial pass per axis)"),
    "out_route": ({4: 387}, "docs/blocks/out_route.md, piece 3"),
    # the routing select registers in global_regs: +106 LUT in a build that routes (docs/four_axes.md 8)
    "bus, global regs": ({4: 92 + 106}, "docs/four_axes.md 8: global_regs +106 LUT with routing"),
}


def current(rows: list[Row], naxes: int) -> dict:
    """Flat LUT at ``naxes``: the estimate with every measured row replaced by its measurement."""
    est = total(rows, naxes)["lut_flat"]
    delta, used = 0, []
    for r in rows:
        for prefix, (meas, src) in MEASURED.items():
            if not r.block.startswith(prefix):
                continue
            lut_n, _ = r.at(naxes)
            if naxes in meas:
                m = meas[naxes]
            else:                                   # measured at NAXES = 1 only: add the estimated growth
                m = meas[1] + lut_n - r.at(1)[0]
            delta += m - lut_n
            used.append({"block": r.block, "estimate": lut_n, "measured": m, "basis": src})
    lut = est + delta
    return {"lut_flat": lut, "lut_pct": round(100 * lut / LUTS, 1), "over_cap": lut - LUT_CAP, "rows": used}


def total(rows: list[Row], naxes: int) -> dict:
    out = {"lut": 0, "ff": 0, "dsp": 0, "ramb": 0.0}
    for r in rows:
        k = naxes if r.kind == "axis" else 1
        lut, ff = r.at(naxes)
        out["lut"] += lut
        out["ff"] += ff
        out["dsp"] += k * r.dsp
        out["ramb"] += k * r.ramb
    out["lut_flat"] = round(out["lut"] * FLAT_PER_HIER)
    out["lut_pct"] = round(100 * out["lut_flat"] / LUTS, 1)
    out["ff_flat"] = round(out["ff"] * 3852 / 4171)          # m: FF flat / hierarchical of mpc_axis
    return out


def check(t: dict) -> list[str]:
    bad = []
    if t["lut_flat"] > LUT_CAP:
        bad.append(f"LUT {t['lut_flat']} > {LUT_CAP} (90 %)")
    if t["dsp"] > DSPS:
        bad.append(f"DSP48A1 {t['dsp']} > {DSPS}")
    if t["ramb"] > RAMBS:
        bad.append(f"RAMB16 {t['ramb']} > {RAMBS}")
    if t["ff_flat"] > FFS:
        bad.append(f"FF {t['ff_flat']} > {FFS}")
    return bad


def table(rows: list[Row], naxes: int) -> str:
    lines = [f"| block | kind | LUT, NAXES = 1 | LUT, NAXES = {naxes} | FF, NAXES = {naxes} | DSP | RAMB16 | basis |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        k = naxes if r.kind == "axis" else 1
        l1, _ = r.at(1)
        ln, fn = r.at(naxes)
        lines.append(f"| {r.block} | {r.kind} | {l1} | {ln} | {fn} | {k * r.dsp} | {k * r.ramb:g} | {r.basis} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", default=str(REPORTS / "mx_budget.json"))
    a = ap.parse_args(argv)
    rep = {"replicated": {n: total(TODAY, n) for n in (1, 4)},
           "shared": {n: total(SHARED, n) for n in (1, 2, 3, 4)},
           "lut_cap": LUT_CAP, "flat_per_hier": FLAT_PER_HIER,
           "rows_today": [asdict(r) for r in TODAY], "rows_shared": [asdict(r) for r in SHARED]}
    # the second-line lever: pos_sense replicated instead of shared
    alt = [r for r in SHARED if not r.block.startswith("pos_sense")] + [r for r in TODAY if r.block == "pos_sense"]
    rep["replicated_pos_sense_instead"] = True
    rep["shared_pos_sense_replicated"] = total(alt, 4)
    rep["current"] = {n: current(SHARED, n) for n in (4,)}
    rep["problems"] = check(rep["shared"][4])
    Path(a.json).parent.mkdir(parents=True, exist_ok=True)
    Path(a.json).write_text(json.dumps(rep, indent=1) + "\n")
    print(table(SHARED, 4))
    print()
    print(table(TODAY, 4))
    for k in ("replicated", "shared"):
        for n, t in rep[k].items():
            print(f"{k} NAXES={n}: {t}")
    print(f"shared, pos_sense replicated, NAXES=4: {rep['shared_pos_sense_replicated']}")
    c = rep["current"][4]
    print(f"current NAXES=4 (measured blocks in): {c['lut_flat']} LUT flat ({c['lut_pct']} %), "
          f"{c['over_cap']:+d} against the cap {LUT_CAP}")
    print("problems:", rep["problems"] or "none")
    return 1 if rep["problems"] else 0


if __name__ == "__main__":
    raise SystemExit(main())
