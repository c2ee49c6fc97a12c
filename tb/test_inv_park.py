"""inv_park: bit-exact vs empc.rtlmodel.inv_park (random + corners), float accuracy bounds,
start/done protocol, reset (shared procedure: tb/test_park.py rotation_test)."""
from __future__ import annotations

import os

import cocotb

from test_park import rotation_test

SEED = int(os.environ.get("EMPC_SEED", 3401))


def test_inv_park():
    from runner import run
    run(toplevel="inv_park", test_module="test_inv_park")


@cocotb.test()
async def random_and_corners(dut):
    await rotation_test(dut, True, ("u_d", "u_q"), ("u_alpha", "u_beta"), SEED)
