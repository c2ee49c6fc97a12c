"""`empc roms`: coefficient images, limiter table, Verilog header and manifest.

Writes into the output directory:
  coef_boot.hex                 image the core loads at reset (the configuration's algorithm/task)
  coef_alg{1,2}_{speed,position}.hex   every design the configuration has weights for (--all)
  rsqrt.hex                     the voltage limiter's 1/sqrt table (rtlmodel/mpc_core.py)
  empc_formats.vh               formats, layout and configuration constants for the RTL
  empc_regs.vh                  register map (gen/empc/regmap.py)
  manifest.json                 formats, scalings, column layout, fit and quantisation errors
Nothing is written if the configuration or any requested design is invalid.
"""
from __future__ import annotations

import json
from pathlib import Path

from . import __version__, config as config_mod, header, image, mpc, regmap
from .design import design, designs_of
from .rtlmodel import mpc_core as core


def generate(cfg, out: Path, all_designs: bool = True) -> dict:
    out = Path(out)
    results = {k: design(cfg, *k) for k in designs_of(cfg, all_designs)}   # raises before writing anything
    out.mkdir(parents=True, exist_ok=True)
    boot = (cfg.control.algorithm, cfg.control.task)
    consts = header.constants(cfg)
    files = {}
    for (alg, task), r in results.items():
        words = image.encode(r["params"], consts["image"]["IMG_FMT_ID"])
        name = f"coef_alg{alg}_{task}.hex"
        image.write_hex(words, out / name)
        files[f"alg{alg}_{task}"] = name
        if (alg, task) == boot:
            image.write_hex(words, out / "coef_boot.hex")
    image.write_hex(core.RSQRT, out / "rsqrt.hex", digits=5)
    header.write(cfg, out)
    (out / "empc_regs.vh").write_text(regmap.render_vh())
    manifest = {
        "generator": f"empc {__version__}",
        "config": config_mod.display_path(cfg.source),
        "boot": {"algorithm": boot[0], "task": boot[1], "file": "coef_boot.hex"},
        "formats": consts["formats"],
        "header_constants": {**consts["config"], **consts["image"], **consts["core"]},
        "units": header.units(cfg),
        "image_layout": consts["image"],
        "designs": {},
    }
    for (alg, task), r in results.items():
        p, rep = r["params"], r["report"]
        manifest["designs"][f"alg{alg}_{task}"] = {
            "algorithm": alg, "task": task, "N": p.N, "file": files[f"alg{alg}_{task}"],
            "gains": list(mpc.GAIN_NAMES[alg]),
            "n_polynomials": rep["n_polynomials"], "n_coefficients": rep["n_coefficients"],
            "ncols": p.ncols, "ws": p.ws, "wn_min": p.wn_min, "wn_max": p.wn_max, "u_max": p.u_max,
            "w_norm_rad_s": rep["w_norm_rad_s"], "ebar_lim_raw": rep["ebar_lim_raw"],
            "columns": rep["columns"],
            "fit_error": {"worst_rel": rep["fit_worst_rel"], "worst_du_ticks": rep["fit_worst_du_ticks"],
                          "per_gain": rep["fit"]},
            "quantisation_error": {"worst_du_ticks": rep["quant_worst_du_ticks"],
                                   "worst_rel_of_peak": rep["quant_worst_rel_of_peak"],
                                   "per_gain": rep["quantisation"]},
            "stability": r["stability"],
            "coefficients": {"p0_p1_p2_shift": p.coef, "col_sig": p.col_sig, "col_shift": p.col_shift},
        }
    (out / "manifest.json").write_text(json.dumps(manifest, indent=1) + "\n")
    return manifest
