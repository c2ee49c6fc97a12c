"""Configuration validation: bad input stops with an error naming the parameter; nothing is written."""
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from empc import config, design, roms

DEFAULT = tomllib.loads(config.DEFAULT_CONFIG.read_text())


def _with(dotted, value):
    import copy
    d = copy.deepcopy(DEFAULT)
    cur = d
    *head, last = dotted.split(".")
    for k in head:
        cur = cur[k]
    cur[last] = value
    return d


@pytest.mark.parametrize("dotted,value,needle,shown", [
    ("motor.R", -0.64, "motor.R", "-0.64"),
    ("motor.R", 0.0, "motor.R", "0.0"),
    ("motor.Ld", 0, "motor.Ld", "0"),
    ("motor.J", -1e-5, "motor.J", "-1e-05"),
    ("control.N", 0, "control.N", "0"),
    ("control.omega_max", -1300.0, "Omega_e", "-1300.0"),
    ("weights.alg1.speed.Q_yw", [8.0, 0.0, 8.0], "weights.alg1.speed.Q_yw[1]", "0.0"),
    ("weights.alg1.speed.Q_du", [100.0, -1.0], "weights.alg1.speed.Q_du[1]", "-1.0"),
    ("control.Ts", 0.00026, "control.Ts", "0.00026"),
    ("sensors.encoder_cpr", 2.5, "sensors.encoder_cpr", "2.5"),
    ("control.algorithm", 3, "control.algorithm", "3"),
])
def test_bad_values_name_the_parameter(dotted, value, needle, shown):
    with pytest.raises(config.ConfigError) as e:
        config.from_dict(_with(dotted, value))
    assert needle in str(e.value) and shown in str(e.value), str(e.value)


def test_unstable_design_is_rejected_and_nothing_written(tmp_path):
    cfg = config.load(config.DEFAULT_CONFIG.with_name("paper_tables.toml"))
    out = tmp_path / "roms"
    with pytest.raises(design.DesignError) as e:
        roms.generate(cfg, out)
    msg = str(e.value)
    assert "algorithm 2" in msg and "spectral radius" in msg
    assert not out.exists()


def test_cli_reports_error_and_writes_nothing(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(config.DEFAULT_CONFIG.read_text().replace("R = 0.64", "R = -0.64"))
    out = tmp_path / "o"
    r = subprocess.run([sys.executable, "-m", "empc.cli", "roms", "--config", str(bad), "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode != 0
    assert "motor.R" in r.stderr and "-0.64" in r.stderr
    assert not out.exists()


def test_default_config_derived_units():
    cfg = config.default()
    assert cfg.pwm_half_period == 2500 and cfg.pwm_per_control == 5
    assert abs(cfg.volts_per_tick - 36.0 / 2500) < 1e-12
    assert abs(cfg.rad_per_count - 2 * 3.141592653589793 * 4 / 4000) < 1e-12
