"""Fixed-point quantisation of the fitted gain polynomials into the core's raw units.

Gains are emitted so that the RTL multiplies raw signals (ADC LSB, encoder
counts, counts per Ts) and accumulates PWM ticks: no conversion in the datapath.
Each column j gets an operand right shift c_j (from the signal's useful range)
and each gain (i, j) a product left shift s_ij chosen so the largest of
|p0|, |p1|, |p2|, |p1 + p2 wn| and |k(wn)| over Omega_e uses the full 18-bit
mantissa (per-gain power-of-two scaling).  A gain that would need s_ij above
MAX_PROD_SHIFT (large gains: short Ts, small ADC LSB) takes it from its column
instead: c_j goes down (to MIN_SIG_SHIFT = -1, a left shift of the operand) as far as
the column's useful range allows, and both rows' s_ij with it; the term is the same.  See rtlmodel/mpc_core.py for the
arithmetic these numbers feed.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import fit as fit_mod
from . import formats as F
from . import image
from .mpc import ebar_step_limits
from .rtlmodel import mpc_core as core

MAX_PROD_SHIFT = (1 << F.PROD_SHIFT_BITS) - 1
MIN_SIG_SHIFT, MAX_SIG_SHIFT = image.SHIFT_MIN, image.SHIFT_MAX  # what the image's biased field holds


class QuantisationError(ValueError):
    pass


@dataclass
class Column:
    name: str          # e.g. "E[m=1,o=2]"
    sig: int           # index into the core's signal vector
    gain: str          # K_e, K_dx, ...
    gain_col: int
    sign: int          # the law's sign (stored coefficients include it)
    output: int        # 0 i_d, 1 i_q, 2 speed/angle; 3, 4 for dx angle/torque
    kind: str          # "E", "W", "Y", "EBAR", "DX"


def columns(algorithm: int, N: int) -> list[Column]:
    cols = []
    dx_out = [0, 1, 2, 3, 4]
    if algorithm == 1:
        for m in range(1, N + 1):
            for o in range(3):
                cols.append(Column(f"E[{m},{o}]", core.SIG_E + 3 * (m - 1) + o, "K_e", 3 * (m - 1) + o, +1, o, "E"))
    else:
        for o in range(3):
            cols.append(Column(f"EBAR[{o}]", core.SIG_EBAR + o, "K_ebar", o, +1, o, "EBAR"))
        for m in range(1, N + 1):
            for o in range(3):
                cols.append(Column(f"W[{m},{o}]", core.SIG_WREL + 3 * (m - 1) + o, "K_WL", 3 * (m - 1) + o, +1, o, "W"))
        for o in range(3):
            cols.append(Column(f"Y[{o}]", core.SIG_Y + o, "K_y", o, -1, o, "Y"))
    for n in range(5):
        cols.append(Column(f"DX[{n}]", core.SIG_DX + n, "K_dx", n, -1, dx_out[n], "DX"))
    return cols


def signal_scale(cfg, task: str, output: int, kind: str) -> float:
    """SI units per raw LSB of a signal of this output."""
    if output in (0, 1):
        return cfg.amps_per_lsb / (1 << F.I_FRAC)
    if kind == "DX":
        if output == 2:
            return cfg.rad_s_per_count_ts / (1 << F.W_FRAC)
        if output == 3:
            return cfg.rad_per_count / (1 << F.TH_FRAC)
        return 1e-6   # load torque increment: not measured, always 0 in the RTL
    if task == "speed":
        return cfg.rad_s_per_count_ts / (1 << F.W_FRAC)
    return cfg.rad_per_count / (1 << F.TH_FRAC)


def ws_for(cfg) -> int:
    c = cfg.control
    top = max(abs(c.omega_min), abs(c.omega_max)) / cfg.rad_s_per_count_ts * (1 << F.W_FRAC)
    return max(0, math.ceil(math.log2(top + 1)) - (F.OPW - 1))


def w_norm_rtl(cfg, ws: int) -> float:
    """The speed (rad/s) that maps to wn = 1.0 in the core."""
    return cfg.rad_s_per_count_ts * 2.0 ** (ws + F.OPW - 1 - F.W_FRAC)


def _bits(x: float) -> int:
    return max(0, math.ceil(math.log2(max(x, 1.0) + 1)))


def build(cfg, algorithm: int | None = None, task: str | None = None, gain_fit=None):
    """Quantise the design for (algorithm, task); returns (Params, report)."""
    c = cfg.control
    algorithm = algorithm or c.algorithm
    task = task or c.task
    if c.N > core.N_MAX:
        raise QuantisationError(f"control.N={c.N} exceeds the core's N_MAX={core.N_MAX}")
    ws = ws_for(cfg)
    if ws > MAX_SIG_SHIFT:
        raise QuantisationError(f"scheduling shift ws={ws} exceeds {MAX_SIG_SHIFT} (|omega| over Omega_e does not fit "
                                f"{F.W_W}-bit Q.{F.W_FRAC}: reduce control.omega_max/omega_min)")
    wnorm = w_norm_rtl(cfg, ws)
    gf = gain_fit or fit_mod.fit(cfg, algorithm, task, w_norm=wnorm)
    if abs(gf.w_norm - wnorm) > 1e-9 * wnorm:
        raise QuantisationError("gain fit must use the core's speed normalisation (fit.fit(..., w_norm=w_norm_rtl))")
    one = (1 << (F.OPW - 1))
    wn_min = max(-(one - 1), int(math.ceil(c.omega_min / wnorm * one)))
    wn_max = min(one - 1, int(math.floor(c.omega_max / wnorm * one)))
    s_grid = np.linspace(wn_min / one, wn_max / one, 257)
    acc_per_volt = (1 << F.ACC_FRAC) / cfg.volts_per_tick
    u_max_v = cfg.u_max
    speed_top = max(abs(c.omega_min), abs(c.omega_max))
    cols = columns(algorithm, c.N)
    fitted = [gf.evaluate(w) for w in gf.omega_grid]          # the fit on the design grid, once
    col_shift, coef = [], [[], []]
    quant = []
    for col in cols:
        scale = signal_scale(cfg, task, col.output, col.kind)
        K = gf.coeffs[col.gain][:, :, col.gain_col] * col.sign      # (3, 2 rows) SI
        k_exact = gf.profiles[col.gain][:, :, col.gain_col] * col.sign
        # useful operand range (raw LSB): beyond it the term alone exceeds 4x the voltage limit
        if col.output in (0, 1):
            phys = float(1 << (F.OPW - 1))
        elif col.output == 4:
            phys = float(1 << (F.OPW - 1))
        elif task == "speed" or col.output == 2:
            phys = 2.0 * speed_top / (cfg.rad_s_per_count_ts / (1 << F.W_FRAC))
        else:
            phys = 4.0 * math.pi / scale          # two electrical turns of position error
        kmax_si = float(np.max(np.abs(k_exact)))
        if col.kind in ("W", "Y") and task == "speed":
            rng = phys                             # these terms cancel pairwise: keep the full range
        else:
            useful = 4.0 * u_max_v / kmax_si / scale if kmax_si > 0 else phys
            rng = min(phys, useful)
        cj_range = _bits(rng) - (F.OPW - 1)          # smallest shift at which the useful range fits
        cj = min(MAX_SIG_SHIFT, max(0, cj_range))
        if col.kind == "DX" and col.output == 3:
            # the angle increment is the speed times Ts: in steady motion its term is cancelled by the
            # reference terms, so "useful" (the term alone) understates its range; cover Omega_e where
            # the product-shift field allows (premo algorithm 2 position: 0.39 rad per period clipped
            # the speed at 1570 of 3000 rad/s, 2.5 i_max in position_large), else fall back to cj_range
            cj = min(MAX_SIG_SHIFT, max(cj, _bits(speed_top * c.Ts / scale) - (F.OPW - 1)))
        ps = [K[:, i] * scale * acc_per_volt for i in range(2)]        # acc LSB per signal LSB
        cmaxs = []
        for p in ps:
            h = p[1] + p[2] * s_grid
            k = p[0] + s_grid * h
            cmaxs.append(max(abs(p[0]), abs(p[1]), abs(p[2]), float(np.max(np.abs(h))), float(np.max(np.abs(k)))))

        def prod_shift(cmax, c):
            if cmax == 0:
                return 0
            return max(0, math.ceil(math.log2(cmax * 2.0 ** c / (one - 1) * (1 + 1e-12))))
        over = max(prod_shift(cm, cj) for cm in cmaxs) - MAX_PROD_SHIFT
        if over > 0:            # take the excess from the operand (same term, less operand range)
            cj = max(cj - over, MIN_SIG_SHIFT, min(cj, cj_range))
        col_shift.append(cj)
        for i in range(2):
            p, cmax = ps[i], cmaxs[i]
            k = p[0] + s_grid * (p[1] + p[2] * s_grid)
            s = prod_shift(cmax, cj)
            if s > MAX_PROD_SHIFT:
                raise QuantisationError(
                    f"gain {col.gain}[{i},{col.gain_col}] needs product shift {s} > {MAX_PROD_SHIFT} "
                    f"with operand shift {cj} (>= {max(MIN_SIG_SHIFT, min(cj, cj_range))}: the operand's useful "
                    f"range): coefficient too large for the accumulator format (ACC_FRAC={F.ACC_FRAC})")
            q = [int(round(v * 2.0 ** (cj - s))) for v in p]
            q = [max(min(v, one - 1), -(one - 1)) for v in q]
            coef[i].append((q[0], q[1], q[2], s))
            # errors over Omega_e, as gains (SI) and as their effect on du at the operand's full range
            kq = np.array([_eval_int(q, int(round(sv * one))) for sv in s_grid]) * 2.0 ** (s - cj)
            to_si = 1.0 / (scale * acc_per_volt)
            peak = float(np.max(np.abs(k_exact[:, i])))
            q_err = float(np.max(np.abs(kq - k))) * to_si
            f_dev = np.abs(np.array([fw[col.gain][i, col.gain_col] * col.sign for fw in fitted]) - k_exact[:, i])
            f_err = float(np.max(f_dev))
            f_at = float(gf.omega_grid[int(np.argmax(f_dev))])
            range_si = min(rng, (one - 1) * 2.0 ** cj) * scale
            quant.append({"gain": col.gain, "row": i, "col": col.gain_col, "peak_si": peak,
                          "unused": col.kind == "DX" and col.output == 4,
                          "quant_abs_si": q_err, "quant_rel": q_err / peak if peak else 0.0,
                          "fit_abs_si": f_err, "fit_rel": f_err / peak if peak else 0.0, "fit_worst_omega": f_at,
                          "operand_range_si": range_si,
                          "quant_du_ticks": q_err * range_si / cfg.volts_per_tick,
                          "fit_du_ticks": f_err * range_si / cfg.volts_per_tick,
                          "mantissa_bits": _bits(max(abs(v) for v in q)) + 1 if any(q) else 0})
    ebar_lim_si = ebar_step_limits(cfg, task)
    ebar_lim = tuple(int(round(ebar_lim_si[o] / signal_scale(cfg, task, o, "EBAR"))) for o in range(3))
    params = core.Params(
        algorithm=algorithm, task=task, N=c.N, ws=ws, wn_min=wn_min, wn_max=wn_max,
        u_max=int(math.floor(cfg.pwm_half_period / math.sqrt(3.0) * (1 << F.V_FRAC))),
        ebar_lim=ebar_lim, col_sig=[col.sig for col in cols], col_shift=col_shift, coef=coef)
    report = {
        "w_norm_rad_s": wnorm, "ws": ws, "wn_min": wn_min, "wn_max": wn_max,
        "columns": [{"name": col.name, "sig": col.sig, "gain": col.gain, "gain_col": col.gain_col,
                     "sign": col.sign, "shift": cs, "si_per_lsb": signal_scale(cfg, task, col.output, col.kind)}
                    for col, cs in zip(cols, col_shift)],
        "quantisation": quant,
        "quant_worst_du_ticks": max(qq["quant_du_ticks"] for qq in quant if not qq["unused"]),
        "fit_worst_du_ticks": max(qq["fit_du_ticks"] for qq in quant if not qq["unused"]),
        "quant_worst_rel_of_peak": max(qq["quant_rel"] for qq in quant if not qq["unused"]),
        "fit": gf.report,
        "fit_worst_rel": gf.report["worst_rel"],
        "n_polynomials": gf.n_polynomials,
        "n_coefficients": gf.n_coefficients,
        "ebar_lim_raw": list(ebar_lim),
    }
    return params, report, gf


def _eval_int(q, wn: int) -> int:
    """Integer gain evaluation exactly as the core does it (without saturation)."""
    p0, p1, p2 = q
    h = p1 + F.rshift_round(p2 * wn, F.OPW - 1)
    return p0 + F.rshift_round(h * wn, F.OPW - 1)


def gains_si(cfg, params, omega: float) -> dict:
    """The gains the core applies at the electrical speed ``omega`` (rad/s), back in SI units
    with the paper's signs (the design check runs the loop with them).

    Evaluated exactly as rtlmodel/mpc_core.py does (scheduling speed rounded to Q1.17 and
    clamped to [wn_min, wn_max], 18-bit saturation of h and k); the operand shift c_j is
    folded back into the gain (its rounding is a quantisation noise, not a gain).
    """
    task = params.task
    one = 1 << (F.OPW - 1)
    wnorm = w_norm_rtl(cfg, params.ws)
    wn = int(round(omega / wnorm * one))
    wn = min(max(wn, params.wn_min), params.wn_max)
    acc_per_volt = (1 << F.ACC_FRAC) / cfg.volts_per_tick
    N = params.N
    shapes = {"K_e": (2, 3 * N), "K_dx": (2, 5), "K_ebar": (2, 3), "K_WL": (2, 3 * N), "K_y": (2, 3)}
    return _gains_si(cfg, params, wn, acc_per_volt, shapes)


def _gains_si(cfg, params, wn: int, acc_per_volt: float, shapes: dict) -> dict:
    out = {}
    for j, (col, cj) in enumerate(zip(columns(params.algorithm, params.N), params.col_shift)):
        K = out.setdefault(col.gain, np.zeros(shapes[col.gain]))
        scale = signal_scale(cfg, params.task, col.output, col.kind)
        for i in range(2):
            p0, p1, p2, s = params.coef[i][j]
            p0, p1, p2 = F.sat(p0, F.OPW), F.sat(p1, F.OPW), F.sat(p2, F.OPW)
            h = F.sat(p1 + F.rshift_round(p2 * wn, F.OPW - 1), F.OPW)
            k = F.sat(p0 + F.rshift_round(h * wn, F.OPW - 1), F.OPW)
            K[i, col.gain_col] = k * 2.0 ** (s - cj) / (scale * acc_per_volt) * col.sign
    return out
