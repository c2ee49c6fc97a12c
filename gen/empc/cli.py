"""`empc` command line: gains, fit, roms, simulate (see README)."""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from . import config as config_mod


def _load(args):
    return config_mod.load(args.config)


def cmd_roms(args) -> int:
    from . import roms
    cfg = _load(args)
    roms.generate(cfg, Path(args.out))
    print(f"wrote coefficient ROMs, empc_formats.vh and manifest.json to {args.out}")
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="empc", description=__doc__)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("roms", help="write coefficient ROMs, Verilog header and manifest")
    r.add_argument("--config", help="TOML configuration (default: BLWR233D, paper 000)")
    r.add_argument("--out", required=True)
    r.set_defaults(func=cmd_roms)
    args = ap.parse_args(argv)
    try:
        return args.func(args)
    except config_mod.ConfigError as e:
        print(f"empc: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
