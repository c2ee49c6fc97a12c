"""Every constant the RTL takes from Python, in one table, and the header ``empc_formats.vh`` written from it.

:func:`constants` is the table: the macros ``EMPC_<NAME>`` of ``empc_formats.vh`` and the constant
sections of ``manifest.json`` (``formats``, ``header_constants``, ``image_layout``) are all written from
it, so no constant reaches the RTL by another way.  Sources, one section each:

  formats   word widths and fractional bits (``gen/empc/formats.py``: every upper-case int there)
  config    raw-unit values of the motor configuration (:func:`config_constants`)
  image     coefficient-image layout (``gen/empc/image.py``)
  core      MPC-core signal and input-word maps, horizon, boot design (``gen/empc/rtlmodel/mpc_core.py``)

The register map has its own generated header (``empc_regs.vh``, from ``gen/empc/regmap.py``).
RTL modules `include the header and take their parameter defaults from the macros;
``gen/tests/test_header.py`` checks that every ``EMPC_*`` macro the RTL uses is defined by one of the two.
"""
from __future__ import annotations

import math
from pathlib import Path

from . import __version__, formats, image
from .config import display_path
from .rtlmodel import mpc_core as core

FORMATS = {name: value for name, value in vars(formats).items() if name.isupper() and isinstance(value, int)}

IMAGE = {
    "IMG_MAGIC": image.MAGIC, "IMG_LAYOUT": image.LAYOUT, "IMG_DEPTH": image.DEPTH, "IMG_A_CFG": image.A_CFG,
    "IMG_A_WS": image.A_WS, "IMG_A_WNMIN": image.A_WNMIN, "IMG_A_WNMAX": image.A_WNMAX, "IMG_A_UMAX": image.A_UMAX,
    "IMG_A_EBAR": image.A_EBAR, "IMG_A_USED": image.A_USED, "IMG_A_CSUM": image.A_CSUM, "IMG_A_FMT": image.A_FMT,
    "IMG_A_COLS": image.A_COLS,
    "IMG_A_GAINS": image.A_GAINS, "IMG_USED": image.USED,
    "IMG_CFG_PERIOD_LSB": image.CFG_PERIOD_LSB, "IMG_CFG_PERIOD_BITS": image.CFG_PERIOD_BITS,
}


def speed_correction_raw(cfg) -> tuple[int, int]:
    """(KACC, KACC_SHIFT): omega_raw += rshift_round(KACC * i_q_raw, KACC_SHIFT) (see Config.speed_correction)."""
    k = cfg.speed_correction * (cfg.amps_per_lsb / (1 << formats.I_FRAC)) * (1 << formats.W_FRAC) / cfg.rad_s_per_count_ts
    if k == 0:
        return 0, 0
    shift = max(0, min(31, formats.OPW - 2 - math.ceil(math.log2(abs(k)))))
    return int(round(k * (1 << shift))), shift


def u_max_v(cfg) -> int:
    """Voltage limit |u| <= Udc/sqrt(3) in PWM ticks (Q.4) at the nominal DC link."""
    return int(math.floor(cfg.pwm_half_period / math.sqrt(3.0) * (1 << formats.V_FRAC)))


def field_weakening_raw(cfg) -> dict[str, int]:
    """Field weakening in raw units: the d-current reference offset is -n * 2^FW_SHIFT (Q.4 ADC
    LSB), n = 0 .. FW_NMAX (register FW; 0 = off) moved by one per control period by the core's
    flags; FW_R2_HI / LO: thresholds on the limiter's r >> FW_R_SHIFT (register FW_R2)."""
    from .rtlmodel.mpc_core import FW_R_SHIFT
    c = cfg.control
    fw = c.field_weakening
    q = (1 << formats.I_FRAC) / cfg.amps_per_lsb
    um = u_max_v(cfg)
    # (the field widths of FW_R2, FW.nmax and the shift are checked by config.check_rtl_limits)
    hi = int(math.floor((fw.u_hi * um) ** 2)) >> FW_R_SHIFT
    lo = int(math.floor((fw.u_lo * um) ** 2)) >> FW_R_SHIFT
    shift = max(0, int(round(math.log2(max(fw.step * c.i_max * q, 1.0)))))
    nmax = int(round(fw.i_max_frac * c.i_max * q / (1 << shift))) if fw.enable else 0
    return {"FW_SHIFT": shift, "FW_NMAX": nmax, "FW_R2_HI": hi, "FW_R2_LO": lo}


def field_weakening_si(cfg) -> tuple[float, float]:
    """(step, limit) of the d-current offset in A, as the raw counter realises them."""
    f = field_weakening_raw(cfg)
    step = (1 << f["FW_SHIFT"]) * cfg.amps_per_lsb / (1 << formats.I_FRAC)
    return step, f["FW_NMAX"] * step


def governor_raw(cfg, task: str | None = None) -> dict[str, int]:
    """Reference-governor words of ``task`` (default: the boot design's): GOV_* and IQ_HOLD."""
    from . import governor
    g = governor.raw_params(cfg, task or cfg.control.task)
    return {"GOV_EN": int(g["enable"]), "GOV_KSH": g["ksh"], "GOV_VMAX_LO": g["vmax"] & 0xFFFFFFFF,
            "GOV_VMAX_HI": g["vmax"] >> 32, "GOV_A_LO": g["a"] & 0xFFFFFFFF, "GOV_A_HI": g["a"] >> 32,
            "IQ_HOLD": governor.hold_current_raw(cfg) if g["enable"] else 0}


def stagger_constants(cfg) -> dict[str, int]:
    """Carrier stagger (docs/four_axes.md D4, section 3.1): PWM_STAGGER_<n> = the PHASE step of pwm_center
    between neighbouring axes of an n-axis build (axis a: PHASE = a * PWM_STAGGER_<n>), a whole number of
    the ADC's frames (adc_spi's default frame period at this PWM period)."""
    from .rtlmodel.adc_spi import AdcSpiParams
    from .rtlmodel.pwm_center import stagger_step
    tf = AdcSpiParams(half_period=cfg.pwm_half_period, pcnt_w=16).tf    # (TF does not depend on P or PCNT_W)
    out = {f"PWM_STAGGER_{n}": stagger_step(n, cfg.pwm_half_period, tf) for n in (2, 3, 4)}
    for n in (2, 3, 4):
        if (n - 1) * out[f"PWM_STAGGER_{n}"] >= 2 * cfg.pwm_half_period:
            raise ValueError(f"carrier stagger of {n} axes beyond one PWM period")
    return out


def config_constants(cfg) -> dict[str, int]:
    """Integer constants the RTL needs from the configuration (raw units)."""
    p = cfg.motor.p
    cpr = cfg.sensors.encoder_cpr
    kacc, kacc_shift = speed_correction_raw(cfg)
    return {
        "KACC": kacc,
        "KACC_SHIFT": kacc_shift,
        "KACC_LOAD_SHIFT": cfg.speed_load_shift,
        "KACC_WIN": cfg.control.speed_window.bit_length() - 1,
        **field_weakening_raw(cfg),
        **governor_raw(cfg),
        "CLK_HZ": int(round(cfg.f_clk)),
        "PWM_HALF_PERIOD": cfg.pwm_half_period,
        "PWM_PER_CONTROL": cfg.pwm_per_control,
        **stagger_constants(cfg),
        "ENC_CPR": cpr,
        "POLE_PAIRS": p,
        "ADC_OFFSET": cfg.sensors.adc_offset,
        # voltage limit |u| <= Udc/sqrt(3) in PWM ticks (Q.4) at the nominal DC link
        "U_MAX_V": u_max_v(cfg),
    }


def core_constants(cfg) -> dict[str, int]:
    """MPC-core maps of the model, the configuration's horizon N and the boot image's design."""
    c = cfg.control
    return {"SIG_W": core.SIG_W, "N_MAX": core.N_MAX, "MAX_COLS": core.MAX_COLS, "RSQRT_BITS": core.RSQRT_BITS,
            "SIG_WREL": core.SIG_WREL, "SIG_E": core.SIG_E, "SIG_Y": core.SIG_Y, "SIG_EBAR": core.SIG_EBAR,
            "SIG_DX": core.SIG_DX, "N": c.N,
            "IN_Y": core.IN_Y, "IN_OMEGA": core.IN_OMEGA, "IN_DX": core.IN_DX, "IN_UPREV": core.IN_UPREV,
            "IN_EBAR": core.IN_EBAR, "IN_WREF": core.IN_WREF, "IN_WORDS": core.IN_WORDS,
            "BOOT_ALGORITHM": c.algorithm, "BOOT_TASK_POSITION": 1 if c.task == "position" else 0,
            **{f"FLAG_{name.upper()}": bit for name, bit in core.FLAG_BITS.items()}}       # core flags bits


def units(cfg) -> dict[str, float]:
    """Raw-unit scalings of the configuration (manifest ``units``; part of the format fingerprint)."""
    return {"volts_per_tick": cfg.volts_per_tick, "amps_per_lsb": cfg.amps_per_lsb,
            "rad_per_count_electrical": cfg.rad_per_count, "rad_s_per_count_per_ts": cfg.rad_s_per_count_ts}


def constants(cfg) -> dict[str, dict[str, int]]:
    """The table: {section: {NAME: value}} with the sections ``formats``, ``config``, ``image``, ``core``.
    ``image`` ends with IMG_FMT_ID, the build's format fingerprint (image.format_id of every other
    constant and the units): an image must carry it to be accepted (rtl/mpc_boot.v)."""
    table = {"formats": dict(FORMATS), "config": config_constants(cfg), "image": dict(IMAGE),
             "core": core_constants(cfg)}
    table["image"]["IMG_FMT_ID"] = image.format_id(
        {k: v for consts in table.values() for k, v in consts.items()}, units(cfg))
    seen: dict[str, str] = {}
    for section, consts in table.items():
        for name in consts:
            if name in seen:
                raise ValueError(f"constant {name} defined twice ({seen[name]}, {section})")
            seen[name] = section
    return table


def flat(cfg) -> dict[str, int]:
    """Every constant of the table, one dict (what ``empc_formats.vh`` defines)."""
    return {k: v for consts in constants(cfg).values() for k, v in consts.items()}


def render(cfg) -> str:
    consts = flat(cfg)
    lines = [
        "// Generated by `empc roms` (empc %s) from %s. Do not edit:" % (__version__, display_path(cfg.source)),
        "// regenerate with `make roms` (formats: gen/empc/formats.py).",
        "`ifndef EMPC_FORMATS_VH",
        "`define EMPC_FORMATS_VH",
    ]
    for k in sorted(consts):
        lines.append(f"`define EMPC_{k} {int(consts[k])}")
    lines.append("`endif")
    return "\n".join(lines) + "\n"


def write(cfg, out_dir: Path) -> Path:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / "empc_formats.vh"
    path.write_text(render(cfg))
    return path


def read(path: Path) -> dict[str, int]:
    """Parse a generated header back (tests use it to check RTL and models agree)."""
    out = {}
    for line in Path(path).read_text().splitlines():
        if line.startswith("`define EMPC_") and len(line.split()) == 3:
            _, name, value = line.split()
            out[name[len("EMPC_"):]] = int(value)
    return out
