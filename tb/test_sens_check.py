"""cocotb tests of sens_check against empc.rtlmodel.sens_check (bit-exact, every clock), Icarus.

* random: 20000 clocks of random (but decoder-consistent) inputs, RTL == model every clock;
* physical: a rotor trajectory sampled every 0.5 deg electrical (one clock per sample: the
  block has no timing of its own), encoder count and HALL sector with their own latencies
  (encoder 11 clocks, HALL 1003 clocks = sync + 1000-clock debounce), the HALL edges each
  displaced by a fixed random error of up to +-14 deg electrical, +-2 deg HALL hysteresis,
  HALL_OFFSET calibrated within +-8 deg; theta as pos_sense gives it, index-aligned
  (encoder angle + ANGLE_CAL) or in HALL mode (re-based at every HALL edge):
  - healthy drives must never trip: constant speeds 2 .. 3600 rad/s electrical (3x the
    configured Omega_e = 1200) in both directions (1.5 electrical turns each), speed ramps, reversals at and between
    HALL edges, +-10 deg oscillation across an edge, a random walk;
  - faults must trip within the stated travel: swapped HALL pair (A/B) in both theta modes,
    one dead encoder channel (count dithers by +-1), both lines broken (count frozen), HALL
    frozen at a legal code while the rotor turns (both modes).  Stated travel from the fault
    to the trip: swapped pair <= 360 deg electrical, dead channel / broken lines / frozen HALL
    <= 180 deg (two HALL edges).
Seed: EMPC_SEED (default 9090).
"""
from __future__ import annotations

import math
import os
import random

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from empc.rtlmodel.hall_decoder import DEFAULT_MAP, DEFAULT_SEQUENCE
from empc.rtlmodel.sens_check import SensCheck

CPR, P, DW, QS = 4000, 4, 12, 3
SEED = int(os.environ.get("EMPC_SEED", "9090"))
CLK = 1e-8
TAU_ENC, TAU_HALL = 11 * CLK, 1003 * CLK
CPE = CPR // P                                 # counts per electrical turn
INPUTS = ("theta_hi", "theta_valid", "hall_off_hi", "hall_sector", "hall_valid", "hall_change", "pos_q")


class Drv:
    def __init__(self, dut):
        self.dut = dut
        self.m = SensCheck(CPR, P, DW, QS)
        self.n = 0
        self.trips = []
        # the inputs clock() sets, in its order; a write reaches the simulator only when the value changes
        # (an unchanged input written again is no event: the same stimulus, fewer handle writes a clock)
        self._in = [getattr(dut, s) for s in INPUTS]
        self._last = [None] * len(INPUTS)
        self._hall_enc, self._enc_break = dut.hall_enc, dut.enc_break
        self._clock = False

    async def start(self):
        d = self.dut
        if not self._clock:             # one clock per test (a second C clock on clk would fight the first)
            Clock(d.clk, 10, unit="ns", impl="gpi").start()   # C clock: no Python per edge (inputs change at falling edges)
            self._clock = True
        d.rst.value = 1
        for h in self._in:
            h.value = 0
        self._last = [0] * len(INPUTS)
        for _ in range(3):
            await FallingEdge(d.clk)
        d.rst.value = 0
        self.m.reset()

    async def clock(self, theta_hi, theta_valid, hall_off_hi, sector, hall_valid, hall_change, pos):
        d = self.dut
        v = (theta_hi & 0x3F, theta_valid, hall_off_hi & 0x3F, sector, hall_valid, hall_change,
             (pos & ((1 << DW) - 1)) >> QS)
        last = self._last
        for i, x in enumerate(v):
            if last[i] != x:
                last[i] = x
                self._in[i].value = x
        exp = self.m.step(*v)
        await FallingEdge(d.clk)
        self.n += 1
        got = (int(self._hall_enc.value), int(self._enc_break.value))
        assert got == exp, f"clock {self.n}: RTL {got} model {exp} inputs {v}"
        return got


def hall_sector_of(theta_deg, edges, state, hyst=2.0):
    """HALL sector 1..6 with hysteresis: sector k+1 spans [edges[k], edges[k+1]) (deg)."""
    a = theta_deg % 360.0
    sec = state["s"]
    for _ in range(6):
        d_start = ((a - edges[sec - 1] + 180.0) % 360.0) - 180.0     # < 0: below the sector start
        d_end = ((a - edges[sec % 6] + 180.0) % 360.0) - 180.0       # > 0: beyond the sector end
        if d_end > hyst / 2:
            sec = sec % 6 + 1
        elif d_start < -hyst / 2:
            sec = 6 if sec == 1 else sec - 1
        else:
            break
    state["s"] = sec
    return sec


class Rotor:
    """Sensor signals of a rotor trajectory (electrical degrees)."""

    def __init__(self, rng, hall_err=14.0, cal_err=8.0, theta0=None):
        self.rng = rng
        self.edges = [60.0 * k + rng.uniform(-hall_err, hall_err) for k in range(6)]
        self.hall_off = rng.uniform(-cal_err, cal_err)            # calibration error of HALL_OFFSET
        self.cal = rng.uniform(-cal_err, cal_err)                 # of ANGLE_CAL
        self.theta0 = rng.uniform(0, 360) if theta0 is None else theta0
        self.hstate = {"s": 1}
        hall_sector_of(self.theta0, self.edges, self.hstate, hyst=0.0)
        self.hall_map = list(range(7))           # true sector -> reported sector (fault injection)
        self.hall_frozen = None
        self.enc_mode = "ok"                      # ok | dither | frozen
        self.enc_frozen = None
        self.dither = 0

    def count(self, theta_deg):
        c = math.floor(theta_deg / 360.0 * CPE)
        if self.enc_mode == "ok":
            return c
        if self.enc_frozen is None:
            self.enc_frozen = c
            self.last_c = c
        if self.enc_mode == "dither" and c != self.last_c:
            self.dither ^= 1                      # one channel dead: +-1 per remaining edge
            self.last_c = c
        return self.enc_frozen + (self.dither if self.enc_mode == "dither" else 0)

    def sector(self, theta_deg):
        if self.hall_frozen is not None:
            return self.hall_frozen
        return self.hall_map[hall_sector_of(theta_deg, self.edges, self.hstate)]


async def run_traj(drv, rotor, traj, aligned, label, expect=None, fault_at=None, limit_deg=None):
    """traj: list of (theta_deg, omega_rad_s).  expect None: no trip allowed; 'hall_enc' /
    'enc_break' / 'any': a trip after sample fault_at within limit_deg of travel."""
    await drv.start()
    hall_off_hi = round(rotor.hall_off / 360.0 * 64) & 0x3F
    prev_sec = None
    base = None
    pos_base = 0
    trav = 0.0
    first = None
    kinds = set()
    for i, (th, om) in enumerate(traj):
        if fault_at is not None and i == fault_at:
            trav = 0.0
        lag_e = math.degrees(abs(om) * TAU_ENC) * (1 if om >= 0 else -1)
        lag_h = math.degrees(abs(om) * TAU_HALL) * (1 if om >= 0 else -1)
        pos = rotor.count(th - lag_e)
        sec = rotor.sector(th - lag_h)
        change = int(prev_sec is not None and sec != prev_sec)
        # theta as pos_sense gives it
        if aligned:
            theta = (pos * 360.0 / CPE + rotor.cal) % 360.0
        else:
            if base is None or change:
                if base is None:
                    base = 60.0 * (sec - 1) + 30.0
                else:
                    d = (sec - prev_sec) % 6
                    base = 60.0 * (sec - 1) if d == 1 else 60.0 * sec if d == 5 else 60.0 * (sec - 1) + 30.0
                base += rotor.hall_off
                pos_base = pos
            theta = (base + (pos - pos_base) * 360.0 / CPE) % 360.0
        th_hi = int(theta / 360.0 * 64) & 0x3F
        he, eb = await drv.clock(th_hi, 1, hall_off_hi, sec, 1, change, pos)
        if i > 0:
            trav += abs(th - traj[i - 1][0])
        prev_sec = sec
        if he or eb:
            kinds |= {"hall_enc"} if he else set()
            kinds |= {"enc_break"} if eb else set()
            if first is None:
                first = (i, round(trav, 1))
            if expect is None:
                raise AssertionError(f"{label}: healthy drive tripped ({'hall_enc' if he else 'enc_break'}) at sample "
                                     f"{i}, theta {th:.1f} deg, omega {om:.0f} rad/s")
    if expect is not None:
        assert first is not None and first[0] >= (fault_at or 0), f"{label}: no trip"
        assert expect == "any" or expect in kinds, f"{label}: tripped {kinds}, expected {expect}"
        assert limit_deg is None or first[1] <= limit_deg, f"{label}: trip after {first[1]} deg > {limit_deg}"
    return first, kinds


def const(theta0, omega, turns, step=0.5):
    n = int(turns * 360 / step)
    s = step if omega >= 0 else -step
    return [(theta0 + k * s, omega) for k in range(n)]


@cocotb.test()
async def random_inputs(dut):
    rng = random.Random(SEED)
    drv = Drv(dut)
    await drv.start()
    sec, pos, th = 1, 0, 0
    for _ in range(20000):
        valid = int(rng.random() < 0.95)
        change = 0
        if valid and rng.random() < 0.05:
            new = rng.choice([s for s in range(1, 7) if s != sec])
            change, sec = 1, new
        pos = (pos + rng.choice([0, 0, 1, -1, 40, -40, 90, rng.randrange(-300, 300)])) & 0xFFFF
        th = (th + rng.randrange(-5, 6)) & 0x3F
        await drv.clock(th, int(rng.random() < 0.97), rng.randrange(64), sec, valid, change, pos)
    dut._log.info("random: %d clocks bit-exact (seed %d, EMPC_SEED)", drv.n, SEED)


@cocotb.test()
async def physical(dut):
    rng = random.Random(SEED + 1)
    drv = Drv(dut)
    n_ok = 0
    # healthy: constant speeds both ways, both theta modes
    for aligned in (True, False):
        for omega in (2.0, 50.0, 400.0, 1200.0, 3600.0, -2.0, -400.0, -1200.0, -3600.0):
            r = Rotor(rng)
            await run_traj(drv, r, const(r.theta0, omega, 1.5), aligned, f"healthy {omega} rad/s aligned={aligned}")
            n_ok += 1
        # ramps and reversals
        r = Rotor(rng)
        traj, th, om = [], r.theta0, 0.0
        for k in range(3000):                       # accelerate to 3600, decelerate, reverse
            om = 3600.0 * math.sin(2 * math.pi * k / 3000)
            th += 0.5 * (1 if om >= 0 else -1) * min(1.0, abs(om) / 200 + 0.05)
            traj.append((th, om))
        await run_traj(drv, r, traj, aligned, f"healthy ramp/reversal aligned={aligned}")
        n_ok += 1
        r = Rotor(rng)
        e = r.edges[2] + 360.0 * 3
        traj = []
        for rep in range(6):                        # +-10 deg oscillation across a HALL edge
            traj += [(e - 10 + 0.5 * k, 30.0) for k in range(40)] + [(e + 10 - 0.5 * k, -30.0) for k in range(40)]
        traj += [(e + rng.uniform(-1.5, 1.5), 0.5) for _ in range(200)]   # chatter inside the hysteresis
        await run_traj(drv, r, traj, aligned, f"healthy oscillation at an edge aligned={aligned}")
        n_ok += 1
        r = Rotor(rng)
        traj, th = [], r.theta0
        for k in range(2400):                       # random walk with random reversals
            th += rng.choice([0.5, 0.5, 0.5, -0.5]) if k % 200 < 100 else rng.choice([-0.5, -0.5, -0.5, 0.5])
            traj.append((th, 300.0 * (1 if traj and th >= traj[-1][0] else -1)))
        await run_traj(drv, r, traj, aligned, f"healthy random walk aligned={aligned}")
        n_ok += 1
    dut._log.info("healthy: %d trajectories, no trip (%d clocks so far)", n_ok, drv.n)
    res = {}
    # faults: after one healthy electrical turn the fault appears; travel limits in electrical degrees
    for aligned in (True, False):
        for omega in (400.0, -1200.0):
            mode = "aligned" if aligned else "HALL mode"
            r2 = Rotor(rng)
            traj = const(r2.theta0, omega, 3)
            half = len(traj) // 3
            # swapped HALL pair A/B: the codes of sectors read through the swapped wiring
            swap = {}
            for s in range(1, 7):
                code = DEFAULT_SEQUENCE[s - 1]
                sw = (code & 4) | ((code & 1) << 1) | ((code & 2) >> 1)
                swap[s] = DEFAULT_MAP[sw]
            r2.hall_map = [0] + [swap[s] for s in range(1, 7)]
            res[f"swapped HALL pair, {mode}, {omega}"] = await run_traj(
                drv, r2, traj, aligned, f"swapped pair {mode} {omega}", expect="hall_enc", fault_at=0, limit_deg=360)
            for kind, em in (("dead channel", "dither"), ("broken lines", "frozen")):
                r3 = Rotor(rng)

                tr = const(r3.theta0, omega, 3)
                orig = r3.count
                cnt = {"i": 0}

                def count(theta, _o=orig, _r=r3, _c=cnt, _em=em):
                    _c["i"] += 1
                    if _c["i"] > half:
                        _r.enc_mode = _em
                    return _o(theta)
                r3.count = count
                res[f"{kind}, {mode}, {omega}"] = await run_traj(
                    drv, r3, tr, aligned, f"{kind} {mode} {omega}", expect="enc_break" if not aligned else "any",
                    fault_at=half, limit_deg=180)
            r4 = Rotor(rng)
            tr = const(r4.theta0, omega, 3)
            orig_s = r4.sector
            cs = {"i": 0}

            def sector(theta, _o=orig_s, _r=r4, _c=cs):
                _c["i"] += 1
                v = _o(theta)
                if _c["i"] == half:
                    _r.hall_frozen = v
                return v
            r4.sector = sector
            res[f"HALL frozen, {mode}, {omega}"] = await run_traj(
                drv, r4, tr, aligned, f"HALL frozen {mode} {omega}", expect="hall_enc", fault_at=half, limit_deg=180)
    for k, v in res.items():
        dut._log.info("%s: first trip at sample %s after %s deg of travel, kinds %s", k, v[0][0], v[0][1], sorted(v[1]))
    dut._log.info("physical: %d healthy trajectories without a trip, %d fault cases tripped, %d clocks bit-exact",
                  n_ok, len(res), drv.n)


@pytest.mark.cost(3)           # seconds on an idle core (make sim starts the costliest first)
def test_sens_check():
    from runner import run
    run(toplevel="sens_check", test_module="test_sens_check", parameters={"CPR": CPR, "POLE_PAIRS": P, "DW": DW, "QS": QS})
