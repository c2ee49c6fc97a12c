"""Report files written whole or not at all.

Two pytest-xdist workers may write the same report at once, and a reader (a test, `make readme`)
must never see a truncated file: write a private temporary file beside the target, then rename.
"""
from __future__ import annotations

import os
from pathlib import Path


def write_atomic(path: str | Path, data: bytes | str) -> None:
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_bytes(data.encode() if isinstance(data, str) else data)
    os.replace(tmp, path)
