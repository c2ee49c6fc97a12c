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

import numpy as np

from . import __version__, config as config_mod, fit as fit_mod, formats, header, image, mpc, quantise, regmap
from .rtlmodel import mpc_core as core


class DesignError(config_mod.ConfigError):
    pass


def check_stability(cfg, algorithm: int, task: str, gf=None, points: int = 25) -> dict:
    """Spectral radius of the frozen-speed loop on a grid over Omega_e, exact and fitted gains."""
    c = cfg.control
    grid = np.linspace(c.omega_min, c.omega_max, points)
    worst = {"exact": 0.0, "fitted": 0.0}
    for w in grid:
        rho = mpc.spectral_radius(cfg.motor, c, float(w), algorithm, task)
        worst["exact"] = max(worst["exact"], rho)
        if rho >= 1.0:
            raise DesignError(
                f"algorithm {algorithm} / {task}: closed loop unstable at omega_e={w:.1f} rad/s "
                f"(spectral radius {rho:.4f} >= 1) with weights.alg{algorithm}.{task} = "
                f"{c.weights_for(algorithm, task)}")
        if gf is not None:
            g = gf.evaluate(float(w))
            rho_f = mpc.spectral_radius(cfg.motor, c, float(w), algorithm, task, g=g)
            worst["fitted"] = max(worst["fitted"], rho_f)
            if rho_f >= 1.0:
                raise DesignError(
                    f"algorithm {algorithm} / {task}: loop with the fitted polynomial gains unstable at "
                    f"omega_e={w:.1f} rad/s (spectral radius {rho_f:.4f})")
    worst["grid_points"] = points
    return worst


def design(cfg, algorithm: int, task: str) -> dict:
    ws = quantise.ws_for(cfg)
    gf = fit_mod.fit(cfg, algorithm, task, w_norm=quantise.w_norm_rtl(cfg, ws))
    stab = check_stability(cfg, algorithm, task, gf)
    params, rep, gf = quantise.build(cfg, algorithm, task, gain_fit=gf)
    return {"params": params, "report": rep, "fit": gf, "stability": stab}


def designs_of(cfg, all_designs: bool) -> list[tuple[int, str]]:
    boot = (cfg.control.algorithm, cfg.control.task)
    out = [boot]
    if all_designs:
        out += [k for k in sorted(cfg.control.weights) if k != boot]
    return out


def generate(cfg, out: Path, all_designs: bool = True) -> dict:
    out = Path(out)
    results = {k: design(cfg, *k) for k in designs_of(cfg, all_designs)}   # raises before writing anything
    out.mkdir(parents=True, exist_ok=True)
    boot = (cfg.control.algorithm, cfg.control.task)
    extra = dict(image.CONSTANTS)
    extra.update({"SIG_W": core.SIG_W, "N_MAX": core.N_MAX, "MAX_COLS": core.MAX_COLS, "RSQRT_BITS": core.RSQRT_BITS,
                  "SIG_WREL": core.SIG_WREL, "SIG_E": core.SIG_E, "SIG_Y": core.SIG_Y, "SIG_EBAR": core.SIG_EBAR,
                  "SIG_DX": core.SIG_DX, "N": cfg.control.N,
                  "IN_Y": core.IN_Y, "IN_OMEGA": core.IN_OMEGA, "IN_DX": core.IN_DX, "IN_UPREV": core.IN_UPREV,
                  "IN_EBAR": core.IN_EBAR, "IN_WREF": core.IN_WREF, "IN_WORDS": core.IN_WORDS,
                  "BOOT_ALGORITHM": boot[0], "BOOT_TASK_POSITION": 1 if boot[1] == "position" else 0})
    units = {"volts_per_tick": cfg.volts_per_tick, "amps_per_lsb": cfg.amps_per_lsb,
             "rad_per_count_electrical": cfg.rad_per_count, "rad_s_per_count_per_ts": cfg.rad_s_per_count_ts}
    extra["IMG_FMT_ID"] = image.format_id({**formats.FORMAT_CONSTANTS, **header.config_constants(cfg), **extra}, units)
    files = {}
    for (alg, task), r in results.items():
        words = image.encode(r["params"], extra["IMG_FMT_ID"])
        name = f"coef_alg{alg}_{task}.hex"
        image.write_hex(words, out / name)
        files[f"alg{alg}_{task}"] = name
        if (alg, task) == boot:
            image.write_hex(words, out / "coef_boot.hex")
    image.write_hex(core.RSQRT, out / "rsqrt.hex", digits=5)
    header.write(cfg, out, extra)
    (out / "empc_regs.vh").write_text(regmap.render_vh())
    manifest = {
        "generator": f"empc {__version__}",
        "config": config_mod.display_path(cfg.source),
        "boot": {"algorithm": boot[0], "task": boot[1], "file": "coef_boot.hex"},
        "formats": formats.FORMAT_CONSTANTS,
        "header_constants": {**header.config_constants(cfg), **extra},
        "units": units,
        "image_layout": image.CONSTANTS,
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
