"""Gains of eqs. 23-28 against independent derivations.

1. Brute force: the predictions are built by simulating the incremental model
   forward (no prediction matrices), the cost (21)/(22) is evaluated as a plain
   function of dU, its Hessian and gradient are recovered from function values
   (exact for a quadratic), and a generic QP solver (quadprog, Goldfarb-Idnani)
   minimises it.  The first move must equal the explicit law's du.
2. The CLI contract: `empc gains --json` prints the same numbers with the documented keys and shapes.
"""
import json
import os
import subprocess
import sys

import numpy as np
import pytest
import quadprog

from empc import config, model, mpc

SEED = int(os.environ.get("EMPC_SEED", "20261122"))
CFG = config.default()


def cost_function(cfg, alg, task, omega, x_k, dx_k, y_k, W, ebar_k):
    c = cfg.control
    N = c.N
    w = c.weights_for(alg, task)
    C = model.output_matrix(task)
    Ad, Bd = model.discrete(cfg.motor, omega, c.Ts)
    qyw, qdy, qdu, qyp = (np.asarray(v, float) ** 2 for v in (w.Q_yw, w.Q_dy, w.Q_du, w.Q_yp))
    D = np.asarray(w.integrate, dtype=float)       # outputs carrying the second integrator

    def J(dU):
        dU = dU.reshape(N, 2)
        dx = dx_k.copy()
        y = y_k.copy()
        eb = ebar_k.copy()
        total = 0.0
        for j in range(N):
            dx = Ad @ dx + Bd @ dU[j]
            dy = C @ dx
            y = y + dy
            if alg == 1:
                r = y - W[j]
            else:
                r = y - W[j] - eb           # (22): y_{k+j} - w_{k+j} - ebar_{k+j-1}
                eb = eb + D * (W[j] - y)    # ebar_{k+j} = ebar_{k+j-1} + w_{k+j} - y_{k+j} (integrated outputs)
                total += (y - W[j]) @ (qyp * (y - W[j]))   # Q_yp: the errors themselves (0: the paper's cost)
            total += r @ (qyw * r) + dy @ (qdy * dy) + dU[j] @ (qdu * dU[j])
        return total
    return J


def qp_first_move(J, n):
    """Recover H, f of the quadratic J from function values, solve min with quadprog."""
    J0 = J(np.zeros(n))
    E = np.eye(n)
    Ji = np.array([J(E[i]) for i in range(n)])
    H = np.zeros((n, n))
    for i in range(n):
        for j in range(i, n):
            H[i, j] = H[j, i] = J(E[i] + E[j]) - Ji[i] - Ji[j] + J0
    f = Ji - J0 - 0.5 * np.diag(H)          # J = 1/2 x'Hx + f'x + J0
    sol = quadprog.solve_qp(H, -f)[0]        # quadprog: min 1/2 x'Gx - a'x
    return sol[:2], H


def _with_q_yp(cfg, ts=None):
    """Algorithm 2 designs with a proportional weight Q_yp (and at 50 us: the control period it is for)."""
    from dataclasses import replace
    if ts:
        cfg = config.load(None, {"control.Ts": ts})
    ws = dict(cfg.control.weights)
    for task in ("speed", "position"):
        w = ws[(2, task)]
        ws[(2, task)] = replace(w, Q_yp=(0.5 * w.Q_yw[0], 0.0, 3.0 * w.Q_yw[2]))
    return cfg.with_control(weights=ws)


@pytest.mark.parametrize("alg", [1, 2, "2p"])
@pytest.mark.parametrize("task", ["speed", "position"])
def test_gains_match_brute_force_qp(alg, task):
    CFG = config.default() if alg != "2p" else _with_q_yp(None, 50e-6)
    alg = 2 if alg == "2p" else alg
    rng = np.random.default_rng(SEED + 10 * alg + (task == "position"))
    c = CFG.control
    n_points = 12
    worst = 0.0
    for _ in range(n_points):
        omega = rng.uniform(c.omega_min, c.omega_max)
        x_k = np.array([rng.normal(0, 2), rng.normal(0, 2), omega, rng.uniform(-50, 50), 0.0])
        dx_k = np.array([rng.normal(0, 0.3), rng.normal(0, 0.3), rng.normal(0, 20), omega * c.Ts, 0.0])
        C = model.output_matrix(task)
        y_k = C @ x_k
        W = y_k + rng.normal(0, 1, (c.N, 3)) * np.array([1.0, 1.0, 30.0 if task == "speed" else 1.0])
        ebar = rng.normal(0, 1, 3) * np.asarray(c.weights_for(2, task).integrate) if alg == 2 else np.zeros(3)
        J = cost_function(CFG, alg, task, omega, x_k, dx_k, y_k, W, ebar)
        du_qp, _ = qp_first_move(J, 2 * c.N)
        g = mpc.gains(CFG.motor, c, omega, alg, task)
        if alg == 1:
            du = g["K_e"] @ (W.reshape(-1) - np.tile(y_k, c.N)) - g["K_dx"] @ dx_k
        else:
            # (25) is applied before (26): the law receives ebar_k; here ebar is already ebar_k
            du = g["K_ebar"] @ ebar + g["K_WL"] @ W.reshape(-1) - g["K_y"] @ y_k - g["K_dx"] @ dx_k
        err = np.max(np.abs(du - du_qp)) / max(1e-9, np.max(np.abs(du_qp)))
        worst = max(worst, err)
        assert err < 1e-6, f"alg {alg} {task} omega {omega:.1f}: law {du} vs QP {du_qp}"
    print(f"seed {SEED}: alg {alg} {task}: {n_points} random points, worst relative difference {worst:.2e}")


@pytest.mark.parametrize("task", ["speed", "position"])
def test_paper_integrators_all_outputs(task):
    """The paper's variant (all three outputs integrated) against the same brute force."""
    from dataclasses import replace
    cfg = config.load(config.DEFAULT_CONFIG.with_name("paper_tables.toml"))
    c = cfg.control
    rng = np.random.default_rng(SEED)
    omega = 300.0
    x_k = np.array([0.3, -1.0, omega, 2.0, 0.0])
    dx_k = np.array([0.1, -0.2, 5.0, omega * c.Ts, 0.0])
    C = model.output_matrix(task)
    y_k = C @ x_k
    W = y_k + rng.normal(0, 1, (c.N, 3))
    ebar = rng.normal(0, 1, 3)
    J = cost_function(cfg, 2, task, omega, x_k, dx_k, y_k, W, ebar)
    du_qp, _ = qp_first_move(J, 2 * c.N)
    g = mpc.gains(cfg.motor, c, omega, 2, task)
    du = g["K_ebar"] @ ebar + g["K_WL"] @ W.reshape(-1) - g["K_y"] @ y_k - g["K_dx"] @ dx_k
    np.testing.assert_allclose(du, du_qp, rtol=1e-6, atol=1e-9)


@pytest.mark.parametrize("q_yp", [False, True])
def test_alg2_translation_invariance(q_yp):
    """Sum of the K_WL blocks equals K_y (exact), which the RTL relies on for relative angles (also with
    the proportional weight Q_yp, which keeps the law's form)."""
    cfg = _with_q_yp(CFG, 50e-6) if q_yp else CFG
    for omega in np.linspace(cfg.control.omega_min, cfg.control.omega_max, 7):
        g = mpc.gains(cfg.motor, cfg.control, omega, 2, "position")
        blocks = g["K_WL"].reshape(2, cfg.control.N, 3).sum(axis=1)
        np.testing.assert_allclose(blocks, g["K_y"], rtol=1e-9, atol=1e-12)


def test_q_yp_zero_is_the_paper_cost_and_positive_adds_proportional_action():
    """Q_yp = 0 gives the gains of eq. 26-28 bit for bit; Q_yp > 0 raises the law's proportional gain on
    the task output (K_y - K_WL's first-block share) without changing K_ebar's sign."""
    from dataclasses import replace
    c = CFG.control
    for task in ("speed", "position"):
        w = c.weights_for(2, task)
        g0 = mpc.gains(CFG.motor, c, 100.0, 2, task)
        gz = mpc.gains(CFG.motor, c, 100.0, 2, task, weights=replace(w, Q_yp=(0.0, 0.0, 0.0)))
        for k in g0:
            assert np.array_equal(g0[k], gz[k])
        gp = mpc.gains(CFG.motor, c, 100.0, 2, task, weights=replace(w, Q_yp=(0.0, 0.0, 3.0 * w.Q_yw[2])))
        # the q-voltage's response to the task output now (y_k) grows relative to its integral gain
        assert abs(gp["K_y"][1, 2] / gp["K_ebar"][1, 2]) > 1.5 * abs(g0["K_y"][1, 2] / g0["K_ebar"][1, 2])


def test_cli_gains_json_contract():
    for alg, keys in ((1, {"K_e": (2, 12), "K_dx": (2, 5)}),
                      (2, {"K_ebar": (2, 3), "K_WL": (2, 12), "K_y": (2, 3), "K_dx": (2, 5)})):
        out = subprocess.run([sys.executable, "-m", "empc.cli", "gains", "--algorithm", str(alg), "--task", "position",
                              "--omega", "321.5", "--json"], capture_output=True, text=True, check=True).stdout
        d = json.loads(out)
        assert set(d) == set(keys)
        g = mpc.gains(CFG.motor, CFG.control, 321.5, alg, "position")
        for k, shape in keys.items():
            a = np.array(d[k])
            assert a.shape == shape
            np.testing.assert_allclose(a, g[k], rtol=1e-12)


def test_zoh_matches_integration():
    """Augmented-exponential ZOH equals integrating the continuous model with a held input."""
    from scipy.integrate import solve_ivp
    for omega in (-900.0, 0.0, 700.0):
        A, B = model.continuous(CFG.motor, omega)
        Ad, Bd = model.discrete(CFG.motor, omega, CFG.control.Ts)
        x0 = np.array([0.5, -1.0, 200.0, 0.3, 0.01])
        u = np.array([3.0, -2.0])
        sol = solve_ivp(lambda t, x: A @ x + B @ u, (0, CFG.control.Ts), x0, rtol=1e-11, atol=1e-12)
        np.testing.assert_allclose(Ad @ x0 + Bd @ u, sol.y[:, -1], rtol=1e-8, atol=1e-9)
