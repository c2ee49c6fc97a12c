"""Coefficient ROMs, Verilog header and manifest (``empc roms``)."""
from __future__ import annotations

import json
from pathlib import Path

from . import header


def generate(cfg, out: Path) -> dict:
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    header.write(cfg, out)
    manifest = {"config": cfg.source}
    (out / "manifest.json").write_text(json.dumps(manifest, indent=2) + "\n")
    return manifest
