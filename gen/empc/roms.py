"""`empc roms`: coefficient images, limiter table, Verilog header and manifest.

Writes into the output directory:
  coef_boot.hex                 image the core loads at reset (the configuration's algorithm/task)
  coef_alg{1,2}_{speed,position}.hex   every design the configuration has weights for (--all)
  rsqrt.hex                     the voltage limiter's 1/sqrt table (rtlmodel/mpc_core.py)
  empc_formats.vh               formats, layout and configuration constants for the RTL
  empc_regs.vh                  register map (gen/empc/regmap.py)
  empc_designs.h                the designs for the firmware (gen/empc/fwdesigns.py): per design its image
                                words, control period and KACC word (the manifest's designs.<d>.kacc)
  manifest.json                 formats, scalings, column layout, fit and quantisation errors
Nothing is written if the configuration or any requested design is invalid (a design that fails
the robust design check is written only with ``force``), and the directory is replaced as a
whole (written into a temporary directory next to it, then renamed): files of an earlier
configuration never survive, and a failure leaves the previous directory untouched.
"""
from __future__ import annotations

import json
import os
import shutil
import tempfile
from pathlib import Path

from . import __version__, config as config_mod, fwdesigns, header, image, mpc, regmap
from .design import design, designs_of
from .rtlmodel import mpc_core as core


def generate(cfg, out: Path, all_designs: bool = True, force: bool = False) -> dict:
    final = Path(out)
    config_mod.require_rtl_speed_window(cfg)
    results = {k: design(cfg, *k, force=force) for k in designs_of(cfg, all_designs)}   # raises before writing
    final.parent.mkdir(parents=True, exist_ok=True)
    out = Path(tempfile.mkdtemp(prefix=f".{final.name}.tmp-", dir=final.parent))
    try:
        manifest = _write(cfg, out, results, all_designs)
        _replace_dir(out, final)
    except BaseException:
        shutil.rmtree(out, ignore_errors=True)
        raise
    return manifest


def _replace_dir(new: Path, final: Path) -> None:
    """Put the directory ``new`` in place of ``final`` (two renames; ``final`` is never half written)."""
    os.chmod(new, 0o755)
    old = None
    if final.exists() or final.is_symlink():
        old = Path(tempfile.mkdtemp(prefix=f".{final.name}.old-", dir=final.parent))
        os.rmdir(old)
        os.rename(final, old)
    os.rename(new, final)
    if old is not None:
        if old.is_dir() and not old.is_symlink():
            shutil.rmtree(old, ignore_errors=True)
        else:
            old.unlink()


def _write(cfg, out: Path, results: dict, all_designs: bool) -> dict:
    boot = (cfg.control.algorithm, cfg.control.task)
    consts = header.constants(cfg)
    files, images = {}, {}
    for (alg, task), r in results.items():
        words = image.encode(r["params"], consts["image"]["IMG_FMT_ID"], period=cfg.pwm_per_control)
        name = f"coef_alg{alg}_{task}.hex"
        image.write_hex(words, out / name)
        files[f"alg{alg}_{task}"] = name
        images[f"alg{alg}_{task}"] = words
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
        "ratings": {"current_A": cfg.ratings.current, "voltage_V": cfg.ratings.voltage,
                    "speed_rad_s_electrical": cfg.ratings.speed, "position_rad_electrical": cfg.ratings.position,
                    "derived": list(cfg.ratings.derived)},
        "weight_units": cfg.control.weight_units,
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
            "weights_si": _weights_dict(cfg.control.weights[(alg, task)]),
            "weights_pu": _weights_dict(cfg.weights_pu(alg, task)),
            "coefficients": {"p0_p1_p2_shift": p.coef, "col_sig": p.col_sig, "col_shift": p.col_shift},
        }
        manifest["designs"][f"alg{alg}_{task}"]["kacc"] = kacc_fields(cfg.for_design(alg, task))
        if (alg, task) in cfg.control.weight_tables:      # a control-period table gave (some of) the weights
            manifest["designs"][f"alg{alg}_{task}"]["weights_table"] = cfg.control.weight_tables[(alg, task)]
    (out / fwdesigns.NAME).write_text(fwdesigns.render(manifest, images))
    (out / "manifest.json").write_text(json.dumps(manifest, indent=1) + "\n")
    return manifest


def kacc_fields(cfg) -> dict:
    """KACC's fields (regmap) for a design (``cfg.for_design``): the firmware writes them with the design's
    image; the header's reset values are the boot design's.  ``speed_window`` is M = 2^win; ``word`` the
    register word of the fields (regmap ``Reg.pack``; empc_designs.h builds it from the same fields)."""
    c = header.config_constants(cfg)          # the header's own KACC constants, for this design
    f = {"kacc": c["KACC"], "load_shift": c["KACC_LOAD_SHIFT"], "shift": c["KACC_SHIFT"], "win": c["KACC_WIN"]}
    return {**f, "speed_window": cfg.control.speed_window, "word": regmap.axis_reg("KACC").pack(f)}


def _weights_dict(w) -> dict:
    d = {"Q_yw": list(w.Q_yw), "Q_dy": list(w.Q_dy), "Q_du": list(w.Q_du),
         "ebar_step_max": list(w.ebar_step_max), "integrate": list(w.integrate)}
    if any(w.Q_yp):
        d["Q_yp"] = list(w.Q_yp)
    return d
