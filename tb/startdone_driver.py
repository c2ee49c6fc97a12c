"""Shared cocotb driver for the start/done blocks of the transform chain
(clarke, park, inv_park, inv_clarke, min_sub, duty_scale).

Protocol checked on every clock cycle:
  * ``start`` in cycle c with ``busy`` low is accepted; ``done`` is high in exactly cycle
    c + latency and nowhere else; ``busy`` is high in cycles c+1 .. c+latency-1 and low otherwise;
  * a ``start`` while busy (driven here with random garbage inputs) is ignored: the result
    belongs to the accepted request and no extra ``done`` follows;
  * a new ``start`` in the done cycle is accepted (back-to-back operation);
  * outputs and ``sat`` change only with ``done`` (``sat`` is a pulse, low when ``done`` is low).

Convention: inputs written in loop iteration k are seen by the DUT in cycle k; values read
right after ``await RisingEdge`` in iteration k are the registers during cycle k.
"""
from __future__ import annotations

import random
from typing import Callable

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge


async def setup(dut, inputs: list[str]) -> None:
    """Start the clock, hold reset for 3 cycles with start = 0 and all inputs 0."""
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    dut.rst.value = 1
    dut.start.value = 0
    for name in inputs:
        getattr(dut, name).value = 0
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.rst.value = 0
    await RisingEdge(dut.clk)


def _read(dut, outputs: dict[str, bool]) -> tuple:
    return tuple(getattr(dut, n).value.to_signed() if signed else int(getattr(dut, n).value)
                 for n, signed in outputs.items())


async def run_ops(dut, ops: list[dict], outputs: dict[str, bool], latency: int, rng: random.Random,
                  garbage: Callable[[random.Random], dict], gap_prob: float = 0.25,
                  spurious_prob: float = 0.15) -> list[tuple]:
    """Run every request in ``ops`` (dicts input name -> int) through the DUT.

    ``outputs`` maps output port names to signedness; returns one tuple
    (outputs..., sat) per request, read in its done cycle.  Random idle gaps between
    requests (``gap_prob``), otherwise the next request starts in the done cycle; random
    ignored starts with ``garbage(rng)`` inputs while busy (``spurious_prob`` per cycle).
    """
    outs = dict(outputs)
    outs["sat"] = False
    results: list[tuple] = []
    nxt = 0
    issue = None          # cycle of the accepted request in flight
    held = _read(dut, outs)
    cyc = 0
    while len(results) < len(ops):
        in_flight = issue is not None and cyc < issue + latency
        done_cycle = issue is not None and cyc == issue + latency
        new_issue = None
        if not in_flight and nxt < len(ops) and rng.random() >= gap_prob:
            for k, v in ops[nxt].items():
                getattr(dut, k).value = v
            dut.start.value = 1
            new_issue = cyc
        elif in_flight and rng.random() < spurious_prob:
            for k, v in garbage(rng).items():
                getattr(dut, k).value = v
            dut.start.value = 1
        else:
            dut.start.value = 0
            if rng.random() < 0.5:      # inputs are don't-care outside the start cycle
                for k, v in garbage(rng).items():
                    getattr(dut, k).value = v
        await RisingEdge(dut.clk)
        done, busy = int(dut.done.value), int(dut.busy.value)
        vals = _read(dut, outs)
        if done_cycle:
            assert done == 1, f"no done {latency} cycles after the start in cycle {issue}"
            assert busy == 0, "busy still high in the done cycle"
            results.append(vals)
            held = vals[:-1] + (0,)
            issue = None
        else:
            assert done == 0, f"unexpected done in cycle {cyc} (request in cycle {issue})"
            assert vals[-1] == 0, "sat high without done"
            assert vals == held, f"outputs changed without done in cycle {cyc}"
            if in_flight:
                assert busy == (1 if cyc > issue else 0), f"busy={busy} in cycle {cyc}, request in cycle {issue}"
            else:
                assert busy == 0, f"busy high while idle in cycle {cyc}"
        if new_issue is not None:
            issue = new_issue
            nxt += 1
        cyc += 1
    dut.start.value = 0
    # nothing more may come out
    for _ in range(latency + 2):
        await RisingEdge(dut.clk)
        assert int(dut.done.value) == 0 and int(dut.busy.value) == 0, "extra done/busy after the last request"
    return results


async def check_reset(dut, op: dict, outputs: list[str], inputs: list[str]) -> None:
    """Reset in the middle of a request: the request is dropped (no done), outputs read 0."""
    for k, v in op.items():
        getattr(dut, k).value = v
    dut.start.value = 1
    await RisingEdge(dut.clk)
    dut.start.value = 0
    await RisingEdge(dut.clk)
    dut.rst.value = 1
    await RisingEdge(dut.clk)
    dut.rst.value = 0
    for _ in range(40):
        await RisingEdge(dut.clk)
        assert int(dut.done.value) == 0 and int(dut.busy.value) == 0 and int(dut.sat.value) == 0
        for n in outputs:
            assert int(getattr(dut, n).value) == 0, f"{n} not cleared by reset"
