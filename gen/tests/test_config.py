"""Configuration input (issue 14, "Configuration input"): every malformed configuration is refused
with one line naming the key and the allowed range, exit status 2 and no traceback; nothing is
written and the output directory is replaced as a whole.

The malformed configurations are generated from the schema (config.SCHEMA: every key gets a value
of each wrong type, values out of its range, a missing required key, and every table a misspelt
table name and a misspelt key), plus the cases of the issue and derived RTL-field violations.
``build/reports/config_errors.json`` counts them (tried, refused, messages).
"""
import copy
import json
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from empc import config, design, roms

ROOT = Path(__file__).resolve().parents[2]
DEFAULT = tomllib.loads(config.DEFAULT_CONFIG.read_text())
REPORT = ROOT / "build" / "reports" / "config_errors.json"


def _with(d, dotted, value, delete=False):
    d = copy.deepcopy(d)
    cur = d
    *head, last = dotted.split(".")
    for k in head:
        cur = cur.setdefault(k, {})
    if delete:
        cur.pop(last, None)
    else:
        cur[last] = value
    return d


def _base_with_tables(table):
    """The default configuration, with the optional table present so its keys can be tested."""
    d = copy.deepcopy(DEFAULT)
    if table.startswith("weights.") or table in ("weights",):
        return d
    d.setdefault(table, {})
    return d


def _misspell(name: str) -> str:
    if len(name) >= 4:
        return name[:2] + name[3:]            # drop a letter: "position" -> "poition"
    return name + "x"


def schema_cases():
    """(label, dict or raw text, expected key in the message) for every key and table of the schema."""
    cases = []
    for k in config.SCHEMA:
        base = _base_with_tables(k.table)
        if k.table.startswith("weights.alg") and k.table not in {f"weights.alg{a}.{t}" for a in (1, 2)
                                                                   for t in ("speed", "position")}:
            continue
        path = k.path
        wrong = []
        if k.kind == "float":
            wrong = [True, "1.5", [1.0], {"v": 1.0}]
        elif k.kind == "int":
            wrong = [True, 2.5, "4", [4]]
        elif k.kind == "bool":
            wrong = [1, "true", [True]]
        elif k.kind == "str":
            wrong = [1, True, ["x"]]
        elif k.kind.startswith("float["):
            n = int(k.kind[6:-1])
            wrong = [[1.0] * (n + 1), [True] * n, ["1"] * n, 1.0]
        elif k.kind.startswith("bool["):
            n = int(k.kind[5:-1])
            wrong = [[1] * n, [True] * (n + 1), "true"]
        elif k.kind == "str[]":
            wrong = ["alg1.speed", [1], ["alg3.speed"], ["alg1.speed", "alg1.speed"]]
        for v in wrong:
            cases.append((f"{path} = {v!r} (type)", _with(base, path, v), path))
        if k.choices and k.kind != "str[]":
            bad = 99 if k.kind == "int" else "nonsense"
            cases.append((f"{path} = {bad!r} (choice)", _with(base, path, bad), path))
        scalar = k.kind in ("float", "int")
        listn = int(k.kind.split("[")[1][:-1]) if "[" in k.kind and k.kind.startswith("float") else 0
        for lim, out in ((k.lo, lambda x: x - abs(x) * 0.5 - 1), (k.hi, lambda x: x * 2 + 1)):
            if lim is None:
                continue
            v = out(lim)
            if k.kind == "int":
                v = int(v)
            if scalar:
                cases.append((f"{path} = {v!r} (range)", _with(base, path, v), path))
            elif listn:
                cases.append((f"{path}[1] = {v!r} (range)", _with(base, path, [1.0, float(v), 1.0][:listn]
                                                                    + [1.0] * max(0, listn - 3)), f"{path}[1]"))
        if k.lo is not None and k.lo_open and scalar:
            cases.append((f"{path} = {k.lo!r} (boundary)", _with(base, path, k.lo), path))
        if scalar and k.kind == "float":
            cases.append((f"{path} = nan", _with(base, path, float("nan")), path))
        if k.default is config.REQUIRED and k.table in DEFAULT:
            cases.append((f"{path} missing", _with(base, path, None, delete=True), path))
    tables = [t for t in config.TABLES if t in DEFAULT or "." not in t]
    for t in tables:
        base = copy.deepcopy(DEFAULT)
        *head, last = t.split(".")
        parent = base
        for h in head:
            parent = parent[h]
        if last in parent:
            parent[_misspell(last)] = parent.pop(last)
            cases.append((f"[{t}] misspelt", base, _misspell(last)))
        keys = config.keys_of(t)
        if keys:
            name = next(iter(keys))
            d = _base_with_tables(t)
            cur = d
            for h in t.split("."):
                cur = cur.setdefault(h, {})
            cur[_misspell(name) + "z"] = 1.0
            cases.append((f"{t}.{_misspell(name)}z unknown key", d, _misspell(name) + "z"))
        if config.TABLES[t][0]:
            d = copy.deepcopy(DEFAULT)
            d.pop(t)
            cases.append((f"[{t}] missing", d, t))
    return cases


# The cases of the issue and derived RTL-field violations (dict, expected text in the message)
ISSUE_CASES = [
    ("[weights.alg2.postion] misspelt", None, "postion"),
    ("adc_offset = 99999", _with(DEFAULT, "sensors.adc_offset", 99999), "sensors.adc_offset"),
    ("Ts = 2000 PWM periods", _with(DEFAULT, "control.Ts", 0.1), "control.Ts"),
    ("p = true", _with(DEFAULT, "motor.p", True), "motor.p"),
    ("N = true", _with(DEFAULT, "control.N", True), "control.N"),
    ("R as a string", _with(DEFAULT, "motor.R", "0.64"), "motor.R"),
    ("Udc as a string", _with(DEFAULT, "inverter.Udc", "36"), "inverter.Udc"),
    ("f_pwm 5 kHz: PWM half period 10000 clocks beyond the 18-bit voltage format",
     _with(_with(DEFAULT, "inverter.f_pwm", 5000.0), "control.Ts", 0.001), "inverter.f_pwm"),
    ("f_pwm 100 kHz: half period 500 clocks < the control computation",
     _with(_with(DEFAULT, "inverter.f_pwm", 100000.0), "control.Ts", 0.0002), "inverter.f_pwm"),
    ("omega_max beyond the 32-bit speed word", _with(DEFAULT, "control.omega_max", 5.0e6), "control.omega_max"),
    ("dead time 300 clocks > 8-bit DEAD_TIME", _with(DEFAULT, "inverter.dead_time", 3e-6), "inverter.dead_time"),
    ("i_max beyond the ADC range", _with(DEFAULT, "control.i_max", 30.0), "control.i_max"),
    ("tiny J: KACC beyond its 18-bit field", _with(DEFAULT, "motor.J", 1e-10), "KACC"),
    ("Ts not a whole number of PWM periods", _with(DEFAULT, "control.Ts", 0.00026), "control.Ts"),
    ("empty Omega_e", _with(DEFAULT, "control.omega_max", -1300.0), "Omega_e"),
    ("encoder_cpr beyond the 17-bit multiplier", _with(DEFAULT, "sensors.encoder_cpr", 1 << 20), "sensors.encoder_cpr"),
    ("motor = 5 (a value instead of a table)", {**copy.deepcopy(DEFAULT), "motor": 5}, "motor"),
    ("integrate all false", _with(DEFAULT, "weights.alg2.speed.integrate", [False, False, False]), "integrate"),
    ("weights for the boot design missing", _with(_with(DEFAULT, "control.algorithm", 2), "weights.alg2",
                                                  None, delete=True), "weights.alg2"),
    ("unknown top-level key", {**copy.deepcopy(DEFAULT), "motr": {"R": 1.0}}, "motr"),
    # control-period weight tables [weights.alg<a>.<task>.Ts_<us>us] (docs/design.md)
    ("control-period table misnamed", _with(DEFAULT, "weights.alg1.position.Ts50", {"Q_du": [1.0, 1.0]}),
     "Ts_<microseconds>us"),
    ("control-period table for 0 us", _with(DEFAULT, "weights.alg1.position.Ts_0us", {"Q_du": [1.0, 1.0]}), "Ts_0us"),
    ("control-period table: unknown key", _with(DEFAULT, "weights.alg1.position.Ts_50us", {"Q_dv": [1.0, 1.0]}),
     "Ts_50us.Q_dv"),
    ("control-period table: negative weight", _with(DEFAULT, "weights.alg1.position.Ts_50us", {"Q_du": [1.0, -1.0]}),
     "Ts_50us.Q_du"),
    ("control-period table: Q_du of 3", _with(DEFAULT, "weights.alg2.speed.Ts_50us", {"Q_du": [1.0, 1.0, 1.0]}),
     "Ts_50us.Q_du"),
    ("control-period table: empty", _with(DEFAULT, "weights.alg1.position.Ts_50us", {}), "Ts_50us"),
    ("control-period table: a table inside", _with(DEFAULT, "weights.alg1.position.Ts_50us", {"Q_du": {"x": 1.0}}),
     "Ts_50us.Q_du"),
    ("two tables for one control period", _with(_with(DEFAULT, "weights.alg1.position.Ts_50us", {"Q_du": [1.0, 1.0]}),
                                                "weights.alg1.position.Ts_050us", {"Q_du": [2.0, 2.0]}), "Ts_050us"),
    ("control-period table without weights to change",
     _with(DEFAULT, "weights.alg1.position", {"Ts_50us": {"Q_du": [1.0, 1.0]}}), "has no weights"),
    ("control-period table: speed_window 3", _with(DEFAULT, "weights.alg1.position.Ts_50us", {"speed_window": 3}),
     "Ts_50us.speed_window"),
    ("control-period table: integrate all false at its Ts",
     _with(_with(DEFAULT, "weights.alg2.speed.Ts_50us", {"integrate": [False, False, False]}), "control.Ts", 50e-6),
     "Ts_50us.integrate"),
]


def _postion():
    d = copy.deepcopy(DEFAULT)
    d["weights"]["alg2"]["postion"] = d["weights"]["alg2"].pop("position")
    return d


RAW_CASES = [   # text files that are not valid configurations at all
    ("not TOML", "R = = 1\n", "not valid TOML"),
    ("empty file", "", "is missing"),
    ("binary", b"\xff\xfe\x00bad", "cannot read"),
]


def all_cases():
    out = []
    for label, d, needle in ISSUE_CASES:
        out.append((label, _postion() if d is None else d, needle))
    return out + schema_cases()


def test_default_configs_are_accepted():
    for p in sorted(config.DEFAULT_CONFIG.parent.glob("*.toml")):
        cfg = config.load(p)
        assert cfg.control.weights and cfg.ratings.current > 0, p


def test_every_malformed_configuration_is_refused_with_one_line():
    cases = all_cases()
    assert len(cases) >= 150, len(cases)
    refused, messages, accepted = 0, [], []
    for label, d, needle in cases:
        try:
            config.from_dict(d)
        except config.ConfigError as e:
            msg = str(e)
            refused += 1
            messages.append({"case": label, "message": msg})
            assert "\n" not in msg, (label, msg)
            assert needle in msg, (label, needle, msg)
            continue
        accepted.append(label)
    assert not accepted, accepted
    REPORT.parent.mkdir(parents=True, exist_ok=True)
    prev = json.loads(REPORT.read_text()) if REPORT.exists() else {}
    rep = {"tried": len(cases) + prev.get("cli", {}).get("tried", 0),
           "refused": refused + prev.get("cli", {}).get("refused", 0),
           "in_process": {"tried": len(cases), "refused": refused}, "cli": prev.get("cli", {}),
           "generated_from_schema": len(cases) - len(ISSUE_CASES), "issue_cases": len(ISSUE_CASES),
           "messages": messages}
    REPORT.write_text(json.dumps(rep, indent=1) + "\n")
    print(f"{refused} of {len(cases)} malformed configurations refused ({len(ISSUE_CASES)} from the issue, "
          f"{len(cases) - len(ISSUE_CASES)} generated from the schema); report {REPORT}")


def _cli(*args, cwd=None):
    env = dict(os.environ)
    env.pop("EMPC_DEBUG", None)
    return subprocess.run([sys.executable, "-m", "empc.cli", *args], capture_output=True, text=True, cwd=cwd, env=env)


def _cli_inprocess(*args):
    """`empc` in this process (same code path as the console script): (exit status, stderr)."""
    import contextlib
    import io
    from empc import cli
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        rc = cli.main(list(args))
    return rc, err.getvalue()


def test_cli_refuses_malformed_files_exit_2_no_traceback(tmp_path):
    """Every case as a file through `empc roms` (in process: exit status 2, one line on stderr, no
    exception escapes), three of them in a subprocess (the real exit status, no traceback); the
    output directory is untouched."""
    out = tmp_path / "roms"
    out.mkdir()
    (out / "marker.txt").write_text("earlier output\n")
    cases = [(ISSUE_CASES[0][0], _dump(_postion()), "postion")]
    cases += [(label, _dump(d), needle) for label, d, needle in ISSUE_CASES[1:] + schema_cases()]
    cases += RAW_CASES
    lines = []
    for i, (label, text, needle) in enumerate(cases):
        f = tmp_path / f"bad{i}.toml"
        f.write_bytes(text if isinstance(text, bytes) else text.encode())
        rc, err = _cli_inprocess("roms", "--config", str(f), "--out", str(out))
        err = err.strip()
        assert rc == 2, (label, rc, err)
        assert len(err.splitlines()) == 1, (label, err)
        assert err.startswith("empc: error:") and needle in err, (label, needle, err)
        lines.append({"case": label, "message": err})
    for i in (0, 3, len(cases) - 1):                 # the console script itself
        r = _cli("roms", "--config", str(tmp_path / f"bad{i}.toml"), "--out", str(out))
        assert r.returncode == 2 and "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert sorted(p.name for p in out.iterdir()) == ["marker.txt"]
    rep = json.loads(REPORT.read_text()) if REPORT.exists() else {"tried": 0, "refused": 0}
    rep["cli"] = {"tried": len(cases), "refused": len(lines), "exit_status": 2, "messages": lines}
    ip = rep.get("in_process", {"tried": 0, "refused": 0})
    rep["tried"], rep["refused"] = ip["tried"] + len(cases), ip["refused"] + len(lines)
    REPORT.parent.mkdir(parents=True, exist_ok=True)
    REPORT.write_text(json.dumps(rep, indent=1) + "\n")


def _toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, float):
        return "nan" if v != v else repr(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + "}"
    return str(v)


def _dump(d: dict, prefix: str = "") -> str:
    """A minimal TOML writer (every dict is a table) for the test files."""
    lines = [f"{k} = {_toml_value(v)}" for k, v in d.items() if not isinstance(v, dict)]
    out = "\n".join(lines) + ("\n" if lines else "")
    for k, v in d.items():
        if isinstance(v, dict):
            name = f"{prefix}{k}"
            out += f"\n[{name}]\n" + _dump(v, name + ".")
    return out


def test_dump_roundtrip():
    assert tomllib.loads(_dump(DEFAULT)) == DEFAULT


def test_bad_value_message_names_key_value_and_range():
    with pytest.raises(config.ConfigError) as e:
        config.from_dict(_with(DEFAULT, "motor.R", -0.64))
    assert str(e.value) == "motor.R = -0.64: out of range; allowed: a number > 0 ohm"
    with pytest.raises(config.ConfigError) as e:
        config.from_dict(_postion())
    assert "unknown table [weights.alg2.postion]; did you mean 'position'?" in str(e.value)
    with pytest.raises(config.ConfigError) as e:
        config.from_dict(_with(DEFAULT, "control.Ts", 0.1))
    assert "control.Ts = 0.1" in str(e.value) and "1 .. 255" in str(e.value), str(e.value)


def test_unstable_design_is_rejected_and_nothing_written(tmp_path):
    cfg = config.load(config.DEFAULT_CONFIG.with_name("paper_tables.toml"))
    out = tmp_path / "roms"
    with pytest.raises(design.DesignError) as e:
        roms.generate(cfg, out)
    msg = str(e.value)
    assert "fails the design check" in msg and "omega_e" in msg and "plant" in msg
    assert not out.exists()


def test_output_directory_replaced_atomically(tmp_path):
    """An earlier configuration's files never survive; a failed run leaves the directory as it was."""
    out = tmp_path / "roms"
    roms.generate(config.default(), out)                       # four designs
    assert (out / "coef_alg2_position.hex").exists()
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    with pytest.raises(design.DesignError):
        roms.generate(config.load(config.DEFAULT_CONFIG.with_name("paper_tables.toml")), out)
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    roms.generate(config.default(), out, all_designs=False)    # the boot design only
    names = sorted(p.name for p in out.iterdir())
    assert "coef_alg2_position.hex" not in names and "coef_boot.hex" in names, names
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".roms")], list(tmp_path.iterdir())


def test_default_config_derived_units():
    cfg = config.default()
    assert cfg.pwm_half_period == 2500 and cfg.pwm_per_control == 5
    assert abs(cfg.volts_per_tick - 36.0 / 2500) < 1e-12
    assert abs(cfg.rad_per_count - 2 * 3.141592653589793 * 4 / 4000) < 1e-12


def test_per_unit_weights_roundtrip_and_bases():
    cfg = config.default()
    for (alg, task), w in cfg.control.weights.items():
        back = config.weights_si(config.weights_pu(w, cfg.bases(task)), cfg.bases(task))
        for a, b in zip(back.Q_yw + back.Q_dy + back.Q_du, w.Q_yw + w.Q_dy + w.Q_du):
            assert abs(a - b) <= 1e-12 * abs(b)
    # a configuration without [weights] gets the built-in per-unit defaults
    d = copy.deepcopy(DEFAULT)
    d.pop("weights")
    c2 = config.from_dict(d)
    assert c2.control.weight_units == "pu" and set(c2.control.weights) == set(config.DEFAULT_WEIGHTS_PU)


def _ts(d, ts):
    return config.from_dict(_with(d, "control.Ts", ts))


def _without_ts_tables(d):
    d = copy.deepcopy(d)
    for alg in d["weights"].values():
        if isinstance(alg, dict):
            for design_table in alg.values():
                for name in [k for k in design_table if k.startswith("Ts_")]:
                    design_table.pop(name)
    return d


def test_control_period_tables_select_by_ts():
    """[weights.<design>.Ts_<us>us] replaces the keys it gives when control.Ts is its period, and only then;
    the other keys come from the design's table; a design of weights.designs takes the defaults under it."""
    plain = _without_ts_tables(DEFAULT)
    d = _with(plain, "weights.alg1.position.Ts_50us", {"Q_du": [7.875, 7.875]})
    d = _with(d, "weights.alg2.speed.Ts_50us", {"Q_du": [1.0, 2.0], "Q_yp": [0.0, 0.0, 5.0]})
    base = config.from_dict(DEFAULT)
    at250, at50 = _ts(d, 250e-6), _ts(d, 50e-6)
    assert at250.control.weights == base.control.weights and at250.control.weight_tables == {}
    assert at50.control.weight_tables == {(1, "position"): "weights.alg1.position.Ts_50us",
                                          (2, "speed"): "weights.alg2.speed.Ts_50us"}
    w, w0 = at50.weights_pu(1, "position"), _ts(plain, 50e-6).weights_pu(1, "position")
    assert w.Q_du == pytest.approx((7.875, 7.875)) and w.Q_yw == pytest.approx(w0.Q_yw) and w.Q_dy == pytest.approx(w0.Q_dy)
    w2 = at50.weights_pu(2, "speed")
    assert w2.Q_du == pytest.approx((1.0, 2.0)) and w2.Q_yp == pytest.approx((0.0, 0.0, 5.0))
    assert w2.integrate == (False, False, True) and w2.ebar_step_max[2] == pytest.approx(0.05776)
    assert _ts(d, 100e-6).control.weight_tables == {}
    # over the defaults of weights.designs
    e = _with(_with(plain, "weights.designs", ["alg1.speed"]), "weights.alg1.speed", {"Ts_50us": {"Q_du": [9.0, 9.0]}})
    assert _ts(e, 50e-6).weights_pu(1, "speed").Q_du == pytest.approx((9.0, 9.0))
    assert _ts(e, 250e-6).weights_pu(1, "speed").Q_du == pytest.approx(config.DEFAULT_WEIGHTS_PU[(1, "speed")].Q_du)
    # the bundled default: tables for 50 us, none used at its own 250 us
    assert config.default().control.weight_tables == {}
    assert set(_ts(DEFAULT, 50e-6).control.weight_tables) == {(1, "speed"), (1, "position"), (2, "speed"),
                                                               (2, "position")}


def test_design_speed_window():
    """A design table's speed_window (here a Ts_50us table's) is that design's M; control.speed_window is
    the M of the others.  cfg.control.speed_window is the M of the design cfg runs (algorithm, task):
    with_control(algorithm / task) follows it, for_design gives it for another design, and
    with_control(speed_window=M) sets M for every design; the speed correction follows M."""
    d = _with(_with(_without_ts_tables(DEFAULT), "weights.alg1.position.Ts_50us", {"speed_window": 4}),
              "control.speed_window", 2)
    at50, at250 = _ts(d, 50e-6), _ts(d, 250e-6)
    c = at50.control
    assert c.speed_windows == {(1, "position"): 4} and c.window_of(1, "position") == 4 and c.window_of(2, "speed") == 2
    assert (c.algorithm, c.task) == (1, "speed") and c.speed_window == 2 and c.speed_window_default == 2
    assert at250.control.speed_windows == {} and at250.control.window_of(1, "position") == 2
    assert at50.with_control(task="position").control.speed_window == 4
    assert at50.with_control(task="position").with_control(algorithm=2).control.speed_window == 2
    f = at50.for_design(1, "position")
    assert f.control.speed_window == 4 and (f.control.algorithm, f.control.task) == (1, "speed")
    assert at50.for_design(1, "speed") is at50
    every = at50.with_control(speed_window=8)
    assert every.control.speed_windows == {} and every.control.window_of(1, "position") == 8
    assert f.speed_correction == pytest.approx(4 * at50.with_control(speed_window=1).speed_correction)
    # in a design's own (not per-Ts) table too
    e = config.from_dict(_with(_without_ts_tables(DEFAULT), "weights.alg2.speed.speed_window", 16))
    assert e.control.speed_windows == {(2, "speed"): 16} and e.control.window_of(1, "speed") == 1
    # the RTL's limit names the table: M = 16 needs speed_load_shift >= 3
    bad = config.from_dict(_with(_with(d, "weights.alg2.speed.Ts_50us", {"speed_window": 16}),
                                 "control.speed_load_shift", 2) | {"control": {**d["control"], "Ts": 50e-6,
                                                                               "speed_load_shift": 2}})
    with pytest.raises(config.ConfigError, match=r"^weights\.alg2\.speed\.Ts_50us\.speed_window = 16 needs "
                                                 r"control\.speed_load_shift >= 3 \(is 2\)"):
        config.require_rtl_speed_window(bad)
    # the bundled BLWR233D: M = 8 for three of its 50 us designs, none at its own 250 us
    b50 = _ts(DEFAULT, 50e-6).control
    assert b50.speed_windows == {(1, "position"): 8, (2, "speed"): 8, (2, "position"): 8} and b50.speed_window == 1
    assert config.default().control.speed_windows == {}


def test_per_ts_table_in_the_manifest(tmp_path):
    d = _with(_with(_without_ts_tables(DEFAULT), "weights.alg1.position.Ts_50us", {"Q_du": [7.875, 7.875],
                                                                                  "speed_window": 4}),
              "control.Ts", 50e-6)
    p = tmp_path / "c.toml"
    p.write_text(_dump(d))
    cfg = config.load(p)
    man = roms.generate(cfg, tmp_path / "out", all_designs=True, force=True)
    assert man["designs"]["alg1_position"]["weights_table"] == "weights.alg1.position.Ts_50us"
    assert "weights_table" not in man["designs"]["alg1_speed"]
    # KACC per design (the firmware writes it with the design's image); the header resets to the boot design's
    k1, k4 = man["designs"]["alg1_speed"]["kacc"], man["designs"]["alg1_position"]["kacc"]
    assert (k1["win"], k1["speed_window"], k4["win"], k4["speed_window"]) == (0, 1, 2, 4)
    assert k4["kacc"] / 2 ** k4["shift"] == pytest.approx(4 * k1["kacc"] / 2 ** k1["shift"], rel=1e-4), (k1, k4)
    assert man["header_constants"]["KACC_WIN"] == 0 and man["header_constants"]["KACC"] == k1["kacc"]
