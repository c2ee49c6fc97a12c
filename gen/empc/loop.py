"""The control loop as built, linearised at one speed: plant, sensors, speed estimate, delay, law.

``loop_matrix(cfg, plant_motor, omega_e, algorithm, task, gains)`` is the transition
matrix of the sampled loop (one control period Ts per step) with zero references and
zero load, frozen at the electrical speed ``omega_e`` (the plant's cross-coupling terms
and the gain scheduling both use it).  What it models, in the order of one period:

* plant: the dq model of eq. 5 with the *plant's* parameters (``plant_motor``, e.g. a
  corner of the robustness box), states [i_d, i_q, w_e, theta_e]; the load torque is an
  unmeasured constant input (no state);
* sampling: i_d, i_q and the encoder angle at the centre of the last PWM period of the
  control period (the ADC trigger);
* speed estimate: a linear block with its own states (:class:`Estimator`, below), the
  one ``control.speed_estimate`` selects;
* law: eqs. 23-24 (algorithm 1) or 25-27 (algorithm 2, second integrator on the outputs
  ``integrate`` selects) with the gains given (exact, fitted or quantised, in SI);
* computation and PWM update delay: u_k takes effect at the next PWM boundary, half a PWM
  period after the sample, and holds until half a PWM period after the next sample (the
  held u_dq is re-modulated every PWM period with the angle one period ahead, so it is
  constant in the dq frame; the residual rotation within a PWM period, w Tpwm / 2, is
  below 3 % at any configured speed and left out).

Sensor quantisation (eq. 38 for the encoder, the ADC LSB for the currents) enters as
additive noise at the sampler; :func:`noise_gain` gives the RMS of i_q and of u that
uniform quantisation noise drives through the loop (the "chatter" figure).

Estimator interface (the speed estimates plug in here): a discrete linear block
run once per control period, before the law,

    z_{k+1} = A z_k + B v_k + Bu u_k
    omega_k = C z_k + D v_k                      (rad/s, electrical)

with the measured inputs v_k = [i_d, i_q, theta_e, u_d(k-1), u_q(k-1)] (SI: A, rad, V;
u(k-1) is the voltage the law produced in the previous period) and u_k the law's output
of this period (for observers that predict one period ahead).  Register a constructor
``f(cfg) -> Estimator`` in :data:`ESTIMATORS` under the ``control.speed_estimate`` name;
the matrices are designed from the configuration's nominal motor (the plant may differ).
The three estimates of the RTL (eq37, accel, accel_load) come from their one linear form,
``estimator.state_space`` (:func:`from_state_space`), the same the float controller steps
(``estimator.SpeedEstimator``) and the sequencer computes in raw units.
The estimator must be shift invariant in theta (a constant angle offset gives omega = 0
in steady state), which every speed estimate from an incremental encoder is.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import expm

from . import model

NV = 5                                   # estimator inputs: i_d, i_q, theta, u_d(k-1), u_q(k-1)
V_ID, V_IQ, V_TH, V_UD, V_UQ = range(NV)
NP = 4                                   # plant states kept: i_d, i_q, w_e, theta_e


@dataclass
class Estimator:
    """Linear speed estimate (see the module docstring for the interface)."""
    name: str
    A: np.ndarray            # (nz, nz)
    B: np.ndarray            # (nz, NV)
    Bu: np.ndarray           # (nz, 2)
    C: np.ndarray            # (1, nz)
    D: np.ndarray            # (1, NV)
    doc: str = ""

    @property
    def nz(self) -> int:
        return self.A.shape[0]


def from_state_space(cfg, name: str | None = None) -> Estimator:
    """The speed estimate of ``control.speed_estimate`` (or ``name``) as this interface's block, from
    its one linear form :func:`empc.estimator.state_space` (inputs: the angle difference over the
    period and i_q; states after it): the angle memory theta_{k-1} is prepended, so that
    dtheta_k = theta_k - theta_{k-1} (the encoder's count difference; the estimator's states then
    see no common angle shift).  Used for every estimate: eq. 37, accel and accel_load."""
    from . import estimator as est_mod
    if name is not None and name != cfg.control.speed_estimate:
        cfg = cfg.with_control(speed_estimate=name)
    ss = est_mod.state_space(cfg)
    Ae, Be, Ce, De = (np.asarray(ss[k], dtype=float) for k in "ABCD")
    ne = Ae.shape[0]
    nz = 1 + ne
    A = np.zeros((nz, nz)); B = np.zeros((nz, NV)); C = np.zeros((1, nz)); D = np.zeros((1, NV))
    # z = [theta_{k-1}, estimator states];  dtheta = theta_k - z0
    B[0, V_TH] = 1.0
    A[1:, 0] = -Be[:, 0]
    A[1:, 1:] = Ae
    B[1:, V_TH] = Be[:, 0]
    B[1:, V_IQ] = Be[:, 1]
    C[0, 0] = -De[0, 0]
    C[0, 1:] = Ce[0]
    D[0, V_TH] = De[0, 0]
    D[0, V_IQ] = De[0, 1]
    doc = {"eq37": "backward difference of the encoder angle (eq. 37)",
           "accel": "eq. 37 + (Ts/2) 1.5 p^2 psi / J * i_q",
           "accel_load": "eq. 37 + (Ts/2) 1.5 p^2 psi / J * i_q less the load estimate (estimator.py)"}
    kind = cfg.control.speed_estimate
    return Estimator(kind, A, B, np.zeros((nz, 2)), C, D, doc.get(kind, ""))


def estimator_eq37(cfg) -> Estimator:
    """Eq. 37: omega_k = (theta_k - theta_{k-1}) / Ts (one state: theta_{k-1})."""
    return from_state_space(cfg, "eq37")


def estimator_accel(cfg) -> Estimator:
    """Eq. 37 plus the half-period acceleration term (Ts/2) 1.5 p^2 psi / J i_q (Config.speed_correction)."""
    return from_state_space(cfg, "accel")


def estimator_accel_load(cfg) -> Estimator:
    """accel less the load estimate D (states theta_{k-1}, w37_{k-1}, D_{k-1}; estimator.py)."""
    return from_state_space(cfg, "accel_load")


ESTIMATORS = {"eq37": estimator_eq37, "accel": estimator_accel, "accel_load": estimator_accel_load}


def estimator_for(cfg) -> Estimator:
    name = cfg.control.speed_estimate
    try:
        return ESTIMATORS[name](cfg)
    except KeyError:
        raise ValueError(f"control.speed_estimate = {name!r} has no loop model (estimators: "
                         f"{', '.join(ESTIMATORS)})") from None


def plant_delayed(motor, omega_e: float, Ts: float, delay: float):
    """Sampled plant with the input delayed by ``delay`` (< Ts): x+ = Ad x + B0 u_k + B1 u_{k-1}.

    States [i_d, i_q, w_e, theta_e] (the load torque is not a state here)."""
    A, Bc = model.continuous(motor, omega_e)
    A, Bc = A[:NP, :NP], Bc[:NP]
    n, m = NP, Bc.shape[1]

    def zoh(t):
        M = np.zeros((n + m, n + m))
        M[:n, :n] = A
        M[:n, n:] = Bc
        E = expm(M * t)
        return E[:n, :n], E[:n, n:]
    A1, G1 = zoh(Ts - delay)          # u_k acts for Ts - delay at the end of the period
    A0, G0 = zoh(delay)               # u_{k-1} acts for delay at the start
    Ad = A1 @ A0
    return Ad, G1, A1 @ G0


@dataclass
class Loop:
    T: np.ndarray                       # transition matrix
    names: list                         # state names
    idx: dict = field(default_factory=dict)   # block -> slice
    invariant: np.ndarray | None = None       # structural eigenvector (speed task: common angle shift)
    Bn: np.ndarray | None = None        # noise input matrix: [theta noise, i_d noise, i_q noise]
    Cu: np.ndarray | None = None        # u_k = Cu s (+ Dn n)
    Dn: np.ndarray | None = None
    Br: np.ndarray | None = None        # reference input: s+ = T s + Br r (r: constant i_d, i_q, speed/angle refs)
    Dr: np.ndarray | None = None        # u_k = Cu s + Dr r
    Gu: np.ndarray | None = None        # reference-driven du_k enters s+ through Gu
    Ge: np.ndarray | None = None        # ... and the aggregated-error increment E w_k through Ge
    Kw: np.ndarray | None = None        # (N, 2, 3): du_k += sum_j Kw[j] w_{k+1+j}
    Kew: np.ndarray | None = None       # du_k += Kew w_k (algorithm 2, through ebar)
    Ew: np.ndarray | None = None        # ebar increment E w_k


_ONES: dict = {}


def _ones(N: int) -> np.ndarray:
    """1 (x) I_3 (3N x 3): the same output over the horizon."""
    if N not in _ONES:
        _ONES[N] = np.kron(np.ones((N, 1)), np.eye(3))
    return _ONES[N]


def law(cfg, algorithm: int, task: str, g: dict, estimator: Estimator | None = None) -> Loop:
    """The loop without the plant rows (the estimator, the law and their memories): what does not
    depend on the plant, shared by every plant of the robustness box (:func:`with_plant`)."""
    c = cfg.control
    est = estimator or estimator_for(cfg)
    C = model.output_matrix(task)[:, :NP]           # outputs of the measured state x = [i_d, i_q, w, th]
    K_dx = g["K_dx"][:, :NP]
    ny, nu, N = 3, 2, c.N
    ones = _ones(N)
    if algorithm == 1:
        Kx = -(g["K_e"] @ ones @ C) - K_dx
        E_int = np.zeros((0, ny))
        Ke = np.zeros((nu, 0))
    else:
        K_y = np.array(g["K_y"], dtype=float)
        if task == "position":
            # the core sees angles relative to theta_k (Y[angle] = 0, W_rel = w - theta): the angle
            # feedback is the sum of the K_WL angle columns (= K_y's for exact gains, not after the fit)
            K_y[:, 2] = g["K_WL"].reshape(2, N, 3)[:, :, 2].sum(axis=1)
        Kx = -(K_y @ C) - K_dx
        integ = [o for o in range(ny) if np.any(g["K_ebar"][:, o] != 0)]
        if len(integ) <= nu:
            E_int = np.eye(ny)[integ]                    # states: the integrated ebar components
            Ke = g["K_ebar"][:, integ]
        else:                                            # zeta = K_ebar ebar: the third direction is neutral
            E_int = g["K_ebar"]
            Ke = np.eye(nu)
    # constant reference r (3 outputs) over the whole horizon: W = 1 (x) r, w_k = r
    Kr = (g["K_e"] @ ones) if algorithm == 1 else (g["K_WL"] @ ones)
    ne, nz = E_int.shape[0], est.nz
    # state s = [p (4), z (nz), u_{k-1} (2), x_{k-1} (4), ebar (ne)]
    sizes = {"p": NP, "z": nz, "u": nu, "xp": NP, "e": ne}
    idx, o = {}, 0
    for k, n in sizes.items():
        idx[k] = slice(o, o + n)
        o += n
    n = o
    # measured inputs v = Mv s + Nv noise; noise n = [theta, i_d, i_q]
    Mv = np.zeros((NV, n)); Nv = np.zeros((NV, 3))
    Mv[V_ID, idx["p"].start + 0] = 1.0
    Mv[V_IQ, idx["p"].start + 1] = 1.0
    Mv[V_TH, idx["p"].start + 3] = 1.0
    Mv[V_UD, idx["u"].start + 0] = 1.0
    Mv[V_UQ, idx["u"].start + 1] = 1.0
    Nv[V_TH, 0] = Nv[V_ID, 1] = Nv[V_IQ, 2] = 1.0
    # omega_hat = Ce z + De v
    Mw = np.zeros((1, n)); Mw[:, idx["z"]] = est.C
    Mw = Mw + est.D @ Mv
    Nw = est.D @ Nv
    # measured state x_k = [i_d, i_q, omega_hat, theta]
    Mx = np.zeros((NP, n)); Nx = np.zeros((NP, 3))
    Mx[0] = Mv[V_ID]; Mx[1] = Mv[V_IQ]; Mx[2] = Mw[0]; Mx[3] = Mv[V_TH]
    Nx[0] = Nv[V_ID]; Nx[1] = Nv[V_IQ]; Nx[2] = Nw[0]; Nx[3] = Nv[V_TH]
    # ebar_k = ebar_{k-1} - E_int C x_k
    Me = np.zeros((ne, n)); Me[:, idx["e"]] = np.eye(ne)
    Me = Me - E_int @ C @ Mx
    Ne = -E_int @ C @ Nx
    # u_k = u_{k-1} + Kx x_k + K_dx x_{k-1} + Ke ebar_k
    Mu = np.zeros((nu, n)); Mu[:, idx["u"]] = np.eye(nu)
    Mu[:, idx["xp"]] += K_dx
    Mu = Mu + Kx @ Mx + Ke @ Me
    Nu = Kx @ Nx + Ke @ Ne
    Re = E_int                                   # ebar_k += E_int r
    Ru = Kr + Ke @ Re                            # u_k += Ru r
    T = np.zeros((n, n)); Bn = np.zeros((n, 3))
    T[idx["z"], idx["z"]] = est.A
    T[idx["z"]] += est.B @ Mv + est.Bu @ Mu
    Bn[idx["z"]] = est.B @ Nv + est.Bu @ Nu
    T[idx["u"]] = Mu
    Bn[idx["u"]] = Nu
    T[idx["xp"]] = Mx
    Bn[idx["xp"]] = Nx
    T[idx["e"]] = Me
    Bn[idx["e"]] = Ne
    Gu = np.zeros((n, nu))                       # where a reference-driven du goes (plant rows: with_plant)
    Gu[idx["z"]] = est.Bu
    Gu[idx["u"]] = np.eye(nu)
    Ge = np.zeros((n, ne)); Ge[idx["e"]] = np.eye(ne)
    Br = Gu @ Ru + Ge @ Re
    Kw = (g["K_e"] if algorithm == 1 else g["K_WL"]).reshape(nu, N, ny).transpose(1, 0, 2)   # N blocks (2, 3)
    names = (["i_d", "i_q", "w_e", "theta_e"] + [f"z{j}" for j in range(nz)] + ["u_d(k-1)", "u_q(k-1)"]
             + ["i_d(k-1)", "i_q(k-1)", "w_hat(k-1)", "theta(k-1)"] + [f"ebar{j}" for j in range(ne)])
    inv = None
    if task == "speed":
        # a common angle shift (plant theta, the estimator's angle memory, theta(k-1)) changes nothing
        # (the speed task does not feed the angle back); checked on the assembled loop
        v = np.zeros(n)
        v[idx["p"].start + 3] = 1.0
        v[idx["xp"].start + 3] = 1.0
        if nz:
            e_th = np.zeros(NV); e_th[V_TH] = 1.0
            v[idx["z"]] = np.linalg.solve(np.eye(nz) - est.A, est.B @ e_th)
        inv = v
    lp = Loop(T, names, idx, inv, Bn, Mu, Nu, Br, Ru, Gu, Ge, Kw, Ke @ E_int, E_int)
    lp.Nu, lp.Ru = Nu, Ru
    return lp


def with_plant(lw: Loop, Ad: np.ndarray, B0: np.ndarray, B1: np.ndarray) -> Loop:
    """The loop :func:`law` with the plant rows of (Ad, B0, B1) (one plant)."""
    p, u = lw.idx["p"], lw.idx["u"]
    T = lw.T.copy()
    T[p, p] = Ad
    T[p, u] += B1
    T[p] += B0 @ lw.Cu
    Bn = lw.Bn.copy(); Bn[p] = B0 @ lw.Nu
    Gu = lw.Gu.copy(); Gu[p] = B0
    Br = lw.Br.copy(); Br[p] = B0 @ lw.Ru
    lp = Loop(T, lw.names, lw.idx, lw.invariant, Bn, lw.Cu, lw.Dn, Br, lw.Dr, Gu, lw.Ge, lw.Kw, lw.Kew, lw.Ew)
    if lp.invariant is not None and np.max(np.abs(T @ lp.invariant - lp.invariant)) > 1e-6 * max(1.0, np.max(np.abs(T))):
        lp.invariant = None
    return lp


def loop(cfg, plant_motor, omega_e: float, algorithm: int, task: str, g: dict,
         estimator: Estimator | None = None, delay: float | None = None) -> Loop:
    """The loop as built (module docstring).  ``g``: gains in SI units with the paper's signs."""
    delay = 0.5 / cfg.inverter.f_pwm if delay is None else delay
    Ad, B0, B1 = plant_delayed(plant_motor, omega_e, cfg.control.Ts, delay)
    return with_plant(law(cfg, algorithm, task, g, estimator), Ad, B0, B1)


def plants_delayed(motors: list, omega_e: float, Ts: float, delay: float):
    """:func:`plant_delayed` for many plants at once: stacks (P, 4, 4), (P, 4, 2), (P, 4, 2)."""
    n, m = NP, 2
    M1 = np.zeros((len(motors), n + m, n + m))
    for k, mo in enumerate(motors):
        A, Bc = model.continuous(mo, omega_e)
        M1[k, :n, :n] = A[:NP, :NP]
        M1[k, :n, n:] = Bc[:NP]
    E1 = expm(M1 * (Ts - delay))
    E0 = expm(M1 * delay)
    A1, G1 = E1[:, :n, :n], E1[:, :n, n:]
    A0, G0 = E0[:, :n, :n], E0[:, :n, n:]
    return A1 @ A0, G1, A1 @ G0


def eigenvalues_batch(lw: Loop, Ad, B0, B1) -> np.ndarray:
    """Eigenvalues (P, n or n - 1) of the loop :func:`law` with each plant of the stacks (the unit
    eigenvalue of a common angle shift removed in the speed task)."""
    p, u = lw.idx["p"], lw.idx["u"]
    P = Ad.shape[0]
    T = np.broadcast_to(lw.T, (P,) + lw.T.shape).copy()
    T[:, p, p] = Ad
    T[:, p, u] += B1
    T[:, p, :] += B0 @ lw.Cu
    if lw.invariant is not None:
        v = lw.invariant / np.linalg.norm(lw.invariant)
        Q = _complement(v)
        T = Q.T @ T @ Q
    return np.linalg.eigvals(T)


_Q_CACHE: dict = {}


def _complement(v: np.ndarray) -> np.ndarray:
    key = v.tobytes()
    if key not in _Q_CACHE:
        _Q_CACHE[key] = np.linalg.svd(np.eye(len(v)) - np.outer(v, v))[0][:, :len(v) - 1]
    return _Q_CACHE[key]




def eigenvalues(lp: Loop) -> np.ndarray:
    """Eigenvalues of the loop without the structural unit eigenvalue of a common angle shift."""
    T = lp.T
    if lp.invariant is not None:
        v = lp.invariant / np.linalg.norm(lp.invariant)
        Q = _complement(v)          # orthonormal basis of the complement of v: the quotient space
        T = Q.T @ T @ Q
    return np.linalg.eigvals(T)


def radius(lp: Loop) -> tuple[float, float]:
    """(spectral radius, frequency of the dominant eigenvalue in Hz at the loop's Ts: caller scales)."""
    ev = eigenvalues(lp)
    i = int(np.argmax(np.abs(ev)))
    return float(np.abs(ev[i])), float(abs(np.angle(ev[i])))


def noise_gain(lp: Loop, sigma: np.ndarray) -> dict:
    """Stationary RMS of i_q and |u| driven by white noise of std ``sigma`` = [theta, i_d, i_q] at the
    sampler (uniform quantisation: LSB / sqrt(12)).  inf if the loop is unstable."""
    from scipy.linalg import solve_discrete_lyapunov
    T, Bn = lp.T, lp.Bn
    if lp.invariant is not None:
        v = lp.invariant / np.linalg.norm(lp.invariant)
        Q = _complement(v)
        T, Bn = Q.T @ T @ Q, Q.T @ Bn
        Cq = np.zeros((1, T.shape[0]))
        sel = np.zeros(lp.T.shape[0]); sel[lp.idx["p"].start + 1] = 1.0
        Cq = (sel @ Q)[None, :]
        Cu = lp.Cu @ Q
    else:
        Cq = np.zeros((1, T.shape[0])); Cq[0, lp.idx["p"].start + 1] = 1.0
        Cu = lp.Cu
    if np.max(np.abs(np.linalg.eigvals(T))) >= 1.0:
        return {"i_q_rms": math.inf, "u_rms": math.inf}
    W = np.diag(np.asarray(sigma, dtype=float) ** 2)
    P = solve_discrete_lyapunov(T, Bn @ W @ Bn.T)
    iq = float(np.sqrt(max(0.0, (Cq @ P @ Cq.T)[0, 0])))
    U = Cu @ P @ Cu.T + lp.Dn @ W @ lp.Dn.T
    return {"i_q_rms": iq, "u_rms": float(np.sqrt(max(0.0, np.trace(U))))}


def step_response(lp: Loop, r, steps: int, k0: int = 0) -> dict:
    """Response of the loop (from rest, nominal-model references) to a reference step ``r`` (3:
    i_d, i_q, speed or angle) at sample ``k0``; the law sees it N periods ahead (its reference
    window W_k = w_{k+1..k+N}), as in the scenarios.  Plant states at the samples and u_k."""
    n = lp.T.shape[0]
    s = np.zeros(n)
    r = np.asarray(r, dtype=float)
    N = lp.Kw.shape[0]
    P, U = np.zeros((steps, NP)), np.zeros((steps, 2))
    ps = lp.idx["p"]
    with np.errstate(over="ignore", invalid="ignore"):     # an unstable candidate diverges: inf/nan, no warning
        return _step(lp, r, steps, k0, s, N, P, U, ps)


def _step(lp, r, steps, k0, s, N, P, U, ps):
    for k in range(steps):
        P[k] = s[ps]
        du = sum(lp.Kw[j] @ r for j in range(N) if k + 1 + j >= k0)
        wk = r if k >= k0 else np.zeros(3)
        du = du + lp.Kew @ wk
        U[k] = lp.Cu @ s + du
        s = lp.T @ s + lp.Gu @ du + lp.Ge @ (lp.Ew @ wk)
    return {"i_d": P[:, 0], "i_q": P[:, 1], "w_e": P[:, 2], "theta_e": P[:, 3], "u": U}
