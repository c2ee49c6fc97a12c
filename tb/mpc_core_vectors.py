"""Test support for mpc_core: stimulus generation, a vectorised twin of the core model, file I/O.

``update_batch`` is a numpy (int64) re-implementation of
:func:`empc.rtlmodel.mpc_core.update` for many input vectors sharing one coefficient
bank.  It exists only to make 100k-vector comparisons fast; the scalar model stays
the specification and tb/test_mpc_core.py checks the twin against it vector by vector.
All intermediate values fit int64 (largest: shifted products < 2^51).
"""
from __future__ import annotations

import numpy as np

from empc import formats as F
from empc import image
from empc.rtlmodel import mpc_core as core

SW = core.SIG_W
OPW = F.OPW
OP_MAX = core.OP_MAX
UW = F.U_W
ACCW = F.ACCW



# ----------------------------------------------------------------------------- helpers
def _rr(x, n: int):
    """rshift_round for numpy int64 (n < 0: left shift, as formats.rshift_round)."""
    if n <= 0:
        return x << (-n)
    return (x + (1 << (n - 1))) >> n


def lsh(v: int, n: int) -> int:
    """v << n for the omega that maps to wn = v (n = ws may be -1: a right shift then)."""
    return v << n if n >= 0 else v >> -n


def _sat(x, w: int):
    return np.clip(x, -(1 << (w - 1)), (1 << (w - 1)) - 1)


def empty_inputs(n: int, N: int) -> dict:
    return {
        "y": np.zeros((n, 3), np.int64), "omega": np.zeros(n, np.int64), "dx": np.zeros((n, 5), np.int64),
        "wref": np.zeros((n, N + 1, 3), np.int64), "u_prev": np.zeros((n, 2), np.int64),
        "ebar_prev": np.zeros((n, 3), np.int64),
    }


def concat(*xs: dict) -> dict:
    return {k: np.concatenate([x[k] for x in xs]) for k in xs[0]}


def take(x: dict, idx) -> dict:
    return {k: v[idx] for k, v in x.items()}


def to_inputs(x: dict, i: int) -> core.Inputs:
    """Vector i as the scalar model's Inputs (Python ints)."""
    return core.Inputs(
        y=tuple(int(v) for v in x["y"][i]), omega=int(x["omega"][i]), dx=tuple(int(v) for v in x["dx"][i]),
        wref=tuple(tuple(int(v) for v in w) for w in x["wref"][i]),
        u_prev=tuple(int(v) for v in x["u_prev"][i]), ebar_prev=tuple(int(v) for v in x["ebar_prev"][i]))


def input_word_arrays(x: dict, N: int) -> tuple[list[int], np.ndarray]:
    """Input-buffer words of all vectors: (addresses, values (n, len(addresses)) int64).

    Vectorised :func:`core.input_words` (same word map ``core.IN_*``; test_batch_model checks
    the two agree).
    """
    cols = [(core.IN_Y + o, x["y"][:, o]) for o in range(3)]
    cols.append((core.IN_OMEGA, x["omega"]))
    cols += [(core.IN_DX + k, x["dx"][:, k]) for k in range(5)]
    cols += [(core.IN_UPREV + i, x["u_prev"][:, i]) for i in range(2)]
    cols += [(core.IN_EBAR + o, x["ebar_prev"][:, o]) for o in range(3)]
    cols += [(core.IN_WREF + 3 * m + o, x["wref"][:, m, o]) for m in range(N + 1) for o in range(3)]
    return [a for a, _ in cols], np.stack([v for _, v in cols], axis=1).astype(np.int64)


def outputs_of(o: core.Outputs) -> dict:
    return {"u": list(o.u), "du": list(o.du), "u_raw": list(o.u_raw), "ebar": list(o.ebar), "wn": o.wn,
            "flags": o.flags}


# ----------------------------------------------------------------------------- batch model
def update_batch(p: core.Params, x: dict) -> dict:
    """Vectorised :func:`core.update` (same semantics, int64 arrays; see module docstring)."""
    n = len(x["omega"])
    y = x["y"]
    wref = x["wref"]
    flags = np.zeros(n, np.int64)
    fb = core.FLAG_BITS

    def flag(name, mask):
        nonlocal flags
        flags = flags | (np.asarray(mask).astype(np.int64) << fb[name])

    # 1. wn
    wr = _rr(x["omega"], p.ws)
    wn0 = np.clip(wr, -OP_MAX, OP_MAX)
    lo = max(min(p.wn_min, OP_MAX), -OP_MAX)
    hi = max(min(p.wn_max, OP_MAX), -OP_MAX)
    wn = np.minimum(np.maximum(wn0, lo), hi)
    flag("wn_clamp", (wn != wr) | (lo > hi))
    # 2. ebar
    ebar = x["ebar_prev"].copy()
    if p.algorithm == 2:
        for o in range(3):
            inc = wref[:, 0, o] - y[:, o]
            lim = min(p.ebar_lim[o], core.EBAR_LIM_MAX)     # stored clamped, as in the scalar model
            inc_c = np.clip(inc, -lim, lim)
            flag("ebar_inc", inc_c != inc)
            v = x["ebar_prev"][:, o] + inc_c
            s = _sat(v, SW)
            flag("ebar", s != v)
            ebar[:, o] = s
    # 3. signals (lazily per index)
    pos = p.task == "position"
    Nh = max(0, min(p.N, core.N_MAX, wref.shape[1] - 1))
    zero = np.zeros(n, np.int64)

    def signal(sig):
        if sig < core.SIG_E:
            m, o = sig // 3 + 1, sig % 3
            if m > Nh:
                return zero, None
            v = wref[:, m, o] - (y[:, 2] if (pos and o == 2) else 0)
        elif sig < core.SIG_Y:
            m, o = (sig - core.SIG_E) // 3 + 1, (sig - core.SIG_E) % 3
            if m > Nh:
                return zero, None
            v = wref[:, m, o] - y[:, o]
        elif sig < core.SIG_EBAR:
            o = sig - core.SIG_Y
            return (zero if (pos and o == 2) else y[:, o]), None
        elif sig < core.SIG_DX:
            return ebar[:, sig - core.SIG_EBAR], None
        elif sig < core.N_SIGNALS:
            return x["dx"][:, sig - core.SIG_DX], None
        else:
            return zero, None
        s = _sat(v, SW)
        return s, s != v

    ncols = min(p.ncols, core.MAX_COLS)
    cols = []
    for j in range(ncols):
        s, m = signal(p.col_sig[j])
        if m is not None:
            flag("signal", m)
        a0 = _rr(s, p.col_shift[j])
        a = _sat(a0, OPW)
        flag("operand", a != a0)
        cols.append(a)
    du = np.zeros((n, 2), np.int64)
    u_raw = np.zeros((n, 2), np.int64)
    for i in range(2):
        acc = np.zeros(n, np.int64)
        for j in range(ncols):
            p0, p1, p2, sh = p.coef[i][j]
            p0, p1, p2 = (F.sat(v, OPW) for v in (p0, p1, p2))
            h0 = p1 + _rr(p2 * wn, OPW - 1)
            h = _sat(h0, OPW)
            k0 = p0 + _rr(h * wn, OPW - 1)
            k = _sat(k0, OPW)
            flag("gain", (h != h0) | (k != k0))
            t0 = (k * cols[j]) << sh
            t = _sat(t0, ACCW)
            flag("term", t != t0)
            acc0 = acc + t
            acc = _sat(acc0, ACCW)
            flag("acc", acc != acc0)
        d0 = _rr(acc, F.ACC_FRAC - F.U_FRAC)
        d = _sat(d0, UW)
        flag("du", d != d0)
        u0 = x["u_prev"][:, i] + d
        u = _sat(u0, UW)
        flag("u", u != u0)
        du[:, i] = d
        u_raw[:, i] = u
    # 6. limiter
    umax = min(max(p.u_max, 0), OP_MAX)
    sh = F.U_FRAC - F.V_FRAC
    u18 = _sat(_rr(u_raw, sh), OPW)
    r = u18[:, 0] * u18[:, 0] + u18[:, 1] * u18[:, 1]
    lim = r > umax * umax
    flag("limit", lim)
    m = np.where(lim, r, 1 << 36)
    z = np.zeros(n, np.int64)
    for _ in range(20):
        small = m < (1 << 36)
        m = np.where(small, m << 2, m)
        z = z + small
    T = np.array(core.RSQRT, np.int64)[m >> (38 - core.RSQRT_BITS)]
    f = np.minimum((umax * T) >> (18 - z), OP_MAX)
    prod = u18 * f[:, None]
    q = np.where(prod < 0, -((-prod) >> (OPW - 1)), prod >> (OPW - 1))
    u_out = np.where(lim[:, None], q << sh, u_raw)
    return {"u": u_out, "du": du, "u_raw": u_raw, "ebar": ebar, "wn": wn, "flags": flags}


# ----------------------------------------------------------------------------- stimulus
def _smag(rng, n, width, scale_bits=None):
    """Signed values of random magnitude: sign * U(0, 2^b) with b log-uniform up to width-1."""
    top = width - 1
    b = rng.integers(0, top + 1, n) if scale_bits is None else np.full(n, scale_bits)
    mag = np.floor(rng.random(n) * (2.0 ** b)).astype(np.int64)
    v = np.where(rng.random(n) < 0.5, -mag, mag)
    return np.clip(v, -(1 << top), (1 << top) - 1)


def _full(rng, n, width):
    return rng.integers(-(1 << (width - 1)), 1 << (width - 1), n, dtype=np.int64)


def random_inputs(rng, n: int, p: core.Params, N: int) -> dict:
    """Random vectors: 40 % realistic operating points, 30 % per-field mix, 15 % log-uniform, 15 % full range.

    realistic: currents, speeds, references, increments and u_prev in the ranges a running
    drive produces (the limiter and the saturations are then rare);  mix: every field
    independently realistic, log-uniform magnitude, uniform full range or an extreme (port
    min / max);  log-uniform: sign * U(0, 2^b), b uniform over the port width;  full: uniform
    over the port range.  Position task: y2 and the angle references are multi-turn Q32.8
    counts (saturated to SIG_W); speed task: Q16.16 speeds (32 bit).
    """
    pos = p.task == "position"
    x = empty_inputs(n, N)
    w_top = lsh(1 << (OPW - 1), p.ws)         # |omega| that maps to wn = 1.0
    mode = rng.choice(4, n, p=[0.4, 0.3, 0.15, 0.15])

    def pick(real, width):
        real = _sat(real, width)
        c = rng.integers(0, 8, n)
        lg = _smag(rng, n, width)
        fu = _full(rng, n, width)
        ex = np.where(rng.random(n) < 0.5, -(1 << (width - 1)), (1 << (width - 1)) - 1)
        mixed = np.where(c < 4, real, np.where(c < 6, lg, np.where(c < 7, fu, ex)))
        return np.select([mode == 0, mode == 1, mode == 2], [real, mixed, lg], fu)

    for o in range(2):
        x["y"][:, o] = pick(_smag(rng, n, 14), OPW)
    x["omega"] = pick(rng.integers(-w_top, w_top + 1, n), F.W_W)
    if pos:
        x["y"][:, 2] = pick(rng.integers(-(1 << (SW - 2)), 1 << (SW - 2), n), SW)
    else:
        x["y"][:, 2] = pick(x["omega"] + _smag(rng, n, 12), F.W_W)
    for m in range(N + 1):
        for o in range(2):
            x["wref"][:, m, o] = pick(x["y"][:, o] + _smag(rng, n, 13), SW)
        x["wref"][:, m, 2] = pick(x["y"][:, 2] + _smag(rng, n, 17 if pos else 19), SW)
    for k, b in enumerate((11, 11, 17, 15, 0)):
        x["dx"][:, k] = pick(_smag(rng, n, b + 1), SW)
    for i in range(2):
        x["u_prev"][:, i] = pick(_smag(rng, n, 20), UW)
    for o, b in enumerate((14, 14, 17 if pos else 21)):
        x["ebar_prev"][:, o] = pick(_smag(rng, n, b + 1), SW)
    return x


def corner_inputs(p: core.Params, N: int, rng) -> tuple[dict, list[str]]:
    """Named corner vectors: zero, full scale of every field, speeds, limiter circle, ebar clamps."""
    vecs, names = [], []
    maxv = {"y": [(1 << 17) - 1, (1 << 17) - 1, (1 << (SW - 1)) - 1], "omega": (1 << 31) - 1}

    def add(name, **kw):
        x = empty_inputs(1, N)
        for k, v in kw.items():
            x[k][0] = v
        vecs.append(x)
        names.append(name)

    add("zero")
    fs = {"y": maxv["y"], "omega": maxv["omega"], "dx": [(1 << (SW - 1)) - 1] * 5,
          "wref": [[(1 << (SW - 1)) - 1] * 3] * (N + 1), "u_prev": [(1 << 23) - 1] * 2, "ebar_prev": [(1 << (SW - 1)) - 1] * 3}
    for sgn, nm in ((1, "+fs"), (-1, "-fs")):
        def scale(v, s=sgn):
            a = np.array(v, np.int64)
            return a if s > 0 else -a - 1
        add(f"all{nm}", **{k: scale(v) for k, v in fs.items()})
        for k, v in fs.items():
            add(f"{k}{nm}", **{k: scale(v)})
        # references full scale, measurements opposite: maximal errors
        add(f"err{nm}", y=-scale(fs["y"]) - 1, wref=scale(fs["wref"]))
    # scheduling speed: 0, +-edge of Omega_e, just beyond, int32 extremes
    w_one = lsh(1 << (OPW - 1), p.ws)
    ulp = lsh(1, p.ws) or 1
    for om in (0, 1, -1, w_one - 1, -(w_one - 1), w_one, -w_one, w_one * 2, -(w_one * 2), (1 << 31) - 1, -(1 << 31),
               lsh(p.wn_max, p.ws), lsh(p.wn_max, p.ws) + ulp, lsh(p.wn_min, p.ws), lsh(p.wn_min, p.ws) - ulp):
        add(f"omega={om}", omega=om, y=[100, -100, om])
    # limiter: u exactly on / inside / outside the circle along the axes and at many angles
    umax = min(p.u_max, OP_MAX)
    sh = F.U_FRAC - F.V_FRAC
    for ud, uq in ((umax, 0), (0, umax), (-umax, 0), (0, -umax), (umax + 1, 0), (0, -umax - 1), (umax, 1)):
        add(f"circle({ud},{uq})", u_prev=[ud << sh, uq << sh])
    for a, b in _pythagorean(umax):
        add(f"on-circle({a},{b})", u_prev=[a << sh, -b << sh])
    for k in range(720):
        ang = 2 * np.pi * k / 720
        R = umax * (1.0 + 3.0 * (k % 7) / 6.0) * (1 << sh)
        if k % 11 == 0:
            R = (1 << 23) - 1                       # far outside (u18 saturates)
        add(f"angle{k}", u_prev=[int(R * np.cos(ang)), int(R * np.sin(ang))])
    # ebar: increment clamp and ebar saturation
    for o in range(3):
        for s in (1, -1):
            wr = np.zeros((N + 1, 3), np.int64)
            wr[0, o] = s * ((1 << (SW - 1)) - 1)
            eb = np.zeros(3, np.int64)
            eb[o] = s * ((1 << (SW - 1)) - 1)
            add(f"ebar_inc[{o}]{s:+d}", wref=wr)
            add(f"ebar_sat[{o}]{s:+d}", wref=wr, ebar_prev=eb)
            lim = p.ebar_lim[o]
            for d in (lim - 1, lim, lim + 1):
                wr2 = np.zeros((N + 1, 3), np.int64)
                wr2[0, o] = s * d
                add(f"ebar_lim[{o}]{s * d:+d}", wref=wr2)
    return concat(*vecs), names


def _pythagorean(r: int, limit: int = 8) -> list[tuple[int, int]]:
    """Integer points (a, b) with a^2 + b^2 == r^2, a, b > 0 (a few)."""
    out = []
    for a in range(1, r):
        b2 = r * r - a * a
        b = int(np.sqrt(b2))
        while b * b > b2:
            b -= 1
        while (b + 1) * (b + 1) <= b2:
            b += 1
        if b * b == b2:
            out.append((a, b))
            if len(out) >= limit:
                break
    return out


# ----------------------------------------------------------------------------- random images
def random_image(rng, N: int, fmt_id: int = 0, valid: bool = True, period: int = 1) -> tuple[list[int], core.Params]:
    """An image with random (also out-of-range) field values, and its decoded Params.

    valid: a header the RTL accepts for a build with horizon N and fingerprint fmt_id
    (image.check: algorithm 1 or 2, N, ncols <= 64, reserved bits 0); else also other
    algorithms, horizons, ncols up to 127 and bit 7 set (for the model alone: the RTL refuses
    such an image, and the clamps it would apply are then only reachable from a bad boot image).
    period: the control period field (CFG[23:16]; the core accepts a swap only at the axis's pwm_per_control).
    """
    w = [0] * image.DEPTH
    alg = int(rng.integers(1, 3)) if valid else int(rng.integers(0, 4))
    task = int(rng.integers(0, 2))
    Nimg = N if valid else int(rng.integers(0, 16))
    ncols = int(rng.integers(0, 65)) if valid or rng.random() >= 0.2 else int(rng.integers(0, 128))
    w[image.A_MAGIC] = image.MAGIC
    w[image.A_CFG] = (image.LAYOUT << 24) | (period << image.CFG_PERIOD_LSB) | (alg << 13) | (task << 12) | (Nimg << 8) | ncols \
        | ((0 if valid else int(rng.integers(0, 2))) << 7)
    w[image.A_FMT] = fmt_id
    w[image.A_WS] = int(rng.integers(0, 1 << 32))
    r32 = lambda: int(rng.integers(0, 1 << 32))

    def s18ish():
        c = rng.random()
        if c < 0.1:
            return r32()                                 # anything: saturated when written
        b = int(rng.integers(0, 18))
        return int(rng.integers(-(1 << b), 1 << b)) & 0xFFFFFFFF
    wmin, wmax = s18ish(), s18ish()
    w[image.A_WNMIN], w[image.A_WNMAX] = wmin, wmax
    w[image.A_UMAX] = r32() if rng.random() < 0.2 else int(rng.integers(0, 1 << 17))
    for o in range(3):
        w[image.A_EBAR + o] = r32() if rng.random() < 0.3 else int(rng.integers(0, 1 << 24))
    for j in range(core.MAX_COLS):
        w[image.A_COLS + j] = r32() if rng.random() < 0.1 else (int(rng.integers(0, 32)) << 8) | int(rng.integers(0, 64))
        for i in range(2):
            base = image.A_GAINS + 4 * (core.MAX_COLS * i + j)
            w[base:base + 3] = [s18ish(), s18ish(), s18ish()]
            w[base + 3] = r32() if rng.random() < 0.1 else int(rng.integers(0, 16))
    w[image.A_USED] = image.USED
    w[image.A_CSUM] = image.checksum(w)
    return w, image.decode(w)
