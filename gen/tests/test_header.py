"""The constant table (gen/empc/header.py) is complete and is the only source of empc_formats.vh and
of the manifest's constant sections.

Every ``EMPC_*`` macro the Verilog uses (rtl/, tb/hdl/, formal/) must be defined by the table or by the
register header (gen/empc/regmap.py); a macro used but defined nowhere fails here, before Verilog does.
"""
import json
import re
from pathlib import Path

import pytest

from empc import config, header, regmap, roms

ROOT = Path(__file__).resolve().parents[2]
VERILOG = [p for d in ("rtl", "tb/hdl", "formal") for p in sorted((ROOT / d).glob("*"))
           if p.suffix in (".v", ".vh", ".sv")]
USE = re.compile(r"`(EMPC_\w+)")
DEFINE = re.compile(r"^\s*`define\s+(EMPC_\w+)", re.M)


def _strip_comments(text: str) -> str:
    return re.sub(r"/\*.*?\*/", " ", re.sub(r"//[^\n]*", "", text), flags=re.S)


def _used(files=VERILOG) -> dict[str, str]:
    """{macro: first file using it} over the Verilog sources (comments ignored, local `defines excluded)."""
    used, local = {}, set()
    for p in files:
        text = _strip_comments(p.read_text())
        local |= set(DEFINE.findall(text))
        for m in USE.findall(text):
            used.setdefault(m, p.name)
    return {m: f for m, f in used.items() if m not in local}


@pytest.fixture(scope="module")
def cfg():
    return config.default()


def _defined(cfg) -> tuple[set, set]:
    return {f"EMPC_{k}" for k in header.flat(cfg)}, set(DEFINE.findall(regmap.render_vh()))


def _missing(cfg, files=VERILOG) -> dict[str, str]:
    table, regs = _defined(cfg)
    return {m: f for m, f in _used(files).items() if m not in table | regs}


def test_every_macro_the_rtl_uses_is_defined(cfg):
    table, regs = _defined(cfg)
    assert not table & regs, f"defined by both the constant table and the register map: {sorted(table & regs)}"
    used = _used()
    assert len(used) > 50, f"grep found only {len(used)} EMPC_* macros in {len(VERILOG)} files"
    missing = _missing(cfg)
    assert not missing, f"EMPC_* macros used by the RTL but defined by no table: {missing}"
    n_tab = sum(1 for m in used if m in table)
    print(f"{len(used)} EMPC_* macros used in {len(VERILOG)} Verilog files: {n_tab} from the constant table, "
          f"{len(used) - n_tab} from the register map")


def test_table_sections(cfg):
    t = header.constants(cfg)
    assert list(t) == ["formats", "config", "image", "core"]
    assert t["formats"]["OPW"] == 18 and t["image"]["IMG_MAGIC"] == 0x454D5043
    assert t["core"]["N"] == cfg.control.N and t["config"]["PWM_HALF_PERIOD"] == cfg.pwm_half_period
    names = [k for s in t.values() for k in s]
    assert len(names) == len(set(names))
    assert all(isinstance(v, int) for s in t.values() for v in s.values())


def test_header_and_manifest_from_the_table(cfg, tmp_path):
    """empc_formats.vh defines exactly the table; the manifest's constant sections are the table's sections."""
    roms.generate(cfg, tmp_path, all_designs=False)
    t = header.constants(cfg)
    assert header.read(tmp_path / "empc_formats.vh") == header.flat(cfg)
    man = json.loads((tmp_path / "manifest.json").read_text())
    assert man["formats"] == t["formats"] and man["image_layout"] == t["image"]
    assert man["header_constants"] == {**t["config"], **t["image"], **t["core"]}


def test_grep_catches_a_missing_macro(cfg, tmp_path):
    """Mutant: a Verilog file using an undefined macro fails the check (one in a comment does not)."""
    bad = tmp_path / "bad.v"
    bad.write_text("// `EMPC_IN_A_COMMENT\nmodule bad; localparam X = `EMPC_NOT_IN_ANY_TABLE + `EMPC_OPW; endmodule\n")
    assert _missing(cfg, VERILOG + [bad]) == {"EMPC_NOT_IN_ANY_TABLE": "bad.v"}


# ---- the format fingerprint (image.format_id): Ts out, every real format / scaling difference in ----
CONFIGS = sorted(Path(config.__file__).with_name("configs").glob("*.toml"))
PERIODS = (1, 2, 3, 5, 8)         # control periods (PWM periods) tried per bundled configuration


def _ts_variants(path):
    """{PWM periods per control period: Config} of a bundled configuration at its PWM frequency (the ones
    the configuration's own limits accept)."""
    out = {}
    base = config.load(path)
    for m in PERIODS:
        try:
            out[m] = base if m == base.pwm_per_control else config.load(path, {"control.Ts": m / base.inverter.f_pwm})
        except ValueError:        # outside the configuration's RTL limits at that Ts (e.g. speed in counts per Ts)
            pass
    return out


@pytest.mark.parametrize("path", CONFIGS, ids=lambda p: p.stem)
def test_format_id_ts_independent(path):
    """Another control period Ts of the same build keeps the fingerprint (the image records its period in
    CFG[23:16] instead), and every header constant that differs between the Ts variants is one that
    image.FMT_EXCLUDE leaves out (register reset values for the build's Ts, PWM_PER_CONTROL)."""
    from empc import image
    var = _ts_variants(path)
    assert len(var) >= 3, f"{path.name}: only periods {sorted(var)} load"
    flats = {m: header.flat(c) for m, c in var.items()}
    ids = {m: f["IMG_FMT_ID"] for m, f in flats.items()}
    assert len(set(ids.values())) == 1, f"{path.name}: fingerprints per period {ids}"
    ref = flats[min(flats)]
    for m, f in flats.items():
        diff = {k for k in set(f) | set(ref) if f.get(k) != ref.get(k)}
        assert diff <= set(image.FMT_EXCLUDE), f"{path.name} at {m} PWM periods: {sorted(diff - set(image.FMT_EXCLUDE))}"
        assert all(f[k] == ref[k] for k in header.FORMATS)
    # the period is the image's: the roms of two periods differ in CFG[23:16] (and the gains), not in A_FMT
    assert {m: c.pwm_per_control for m, c in var.items()} == {m: m for m in var}


def _fp(path, overrides=None) -> int:
    return header.flat(config.load(path, overrides))["IMG_FMT_ID"]


# a real format or scaling change: another fingerprint (key, factor or value)
FORMAT_CHANGES = (("motor.p", lambda c: c.motor.p + 1), ("sensors.encoder_cpr", lambda c: c.sensors.encoder_cpr * 2),
                  ("sensors.adc_amps_per_lsb", lambda c: c.sensors.adc_amps_per_lsb * 1.25),
                  ("inverter.Udc", lambda c: c.inverter.Udc * 1.1), ("fpga.f_clk", lambda c: c.f_clk * 0.8),
                  ("inverter.f_pwm", lambda c: c.inverter.f_pwm * 0.5))


@pytest.mark.parametrize("path", CONFIGS, ids=lambda p: p.stem)
def test_format_id_other_format(path):
    """Another motor (pole pairs), encoder, ADC scaling, DC link, clock or PWM frequency gives another
    fingerprint: what a word means still differs (at least four of the six changes load per configuration)."""
    base = config.load(path)
    own = _fp(path)
    n = 0
    for key, fn in FORMAT_CHANGES:
        v = fn(base)
        ov = {key: v}
        if key == "inverter.f_pwm":            # keep Ts a whole number of PWM periods
            ov["control.Ts"] = max(1, base.pwm_per_control // 2) / v
        try:
            other = _fp(path, ov)
        except ValueError:
            continue
        assert other != own, f"{path.name}: {key} = {v} keeps the fingerprint {own:#x}"
        n += 1
    assert n >= 4, f"{path.name}: only {n} format changes load"


def test_format_id_bundled_configs_differ():
    """The bundled configurations (motors, encoders, inverters) have pairwise different fingerprints."""
    ids = {p.stem: _fp(p) for p in CONFIGS}
    assert len(set(ids.values())) == len(ids), ids
