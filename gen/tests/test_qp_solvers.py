"""Cross-checks of our QP solvers (issue 7) against quadprog, DAQP and OSQP.

- Goldfarb-Idnani dual active set (qp/goldfarb_idnani.py, paper 002 Algorithm 1):
  random strictly convex feasible QPs and the MPC QPs of 002 recorded in closed loop.
  Tolerances: |z - z_quadprog| <= 1e-8 (1 + |z|), objective gap <= 1e-9 (1 + |f|),
  KKT residuals <= 1e-8; DAQP (its primal tolerance 1e-6): |dz| <= 1e-5 (1 + |z|);
  OSQP (eps 1e-9, polished): |dz| <= 1e-4 (1 + |z|).
- Interior point (qp/ipm.py, paper 001 Algorithm 1): validation mode (decreasing barrier,
  up to 80 iterations) against quadprog on random QPs, |dxi| <= 1e-6 (1 + |xi|); the
  paper's setting (tau = 0.5 fixed, 4 iterations) is measured, not idealised: on random
  unscaled QPs it is a rough approximation (printed); on the CCS-MPCC problems without an
  active constraint its error against the converged solution is below 5 mV in du (asserted);
  with the 4 V voltage circle of 001 Fig. 6 active it is ~1 V (asserted > 0.1 V, printed) and
  the iterate can lie outside the circle - the fixed-tau point needs ~12 iterations (asserted).  The circle
  constraints of 001 eq. 18h/18i are checked against a 256-gon inner polygon solved by quadprog.
Seed: EMPC_SEED (default 7), printed.
"""
import math
import os

import numpy as np
import pytest

quadprog = pytest.importorskip("quadprog")
daqp = pytest.importorskip("daqp")
osqp = pytest.importorskip("osqp")
import scipy.sparse as sp  # noqa: E402

from empc import closedloop as cl  # noqa: E402
from empc.papers import compare  # noqa: E402
from empc.papers.ccs_mpcc import CcsMPCC  # noqa: E402
from empc.papers.online_mpc_gi import OnlineMPC  # noqa: E402
from empc.papers.qp import goldfarb_idnani as gi  # noqa: E402
from empc.papers.qp import ipm  # noqa: E402
from empc.papers.qp.opcount import OpCount  # noqa: E402

SEED = int(os.environ.get("EMPC_SEED", "7"))


def random_qp(rng, n_max=8, m_max=24):
    n = int(rng.integers(1, n_max + 1))
    m = int(rng.integers(1, m_max + 1))
    M = rng.normal(size=(n, n))
    H = M @ M.T + 0.1 * np.eye(n)
    g = rng.normal(size=n) * 3
    W = rng.normal(size=(m, n))
    z0 = rng.normal(size=n) * 0.3
    b = W @ z0 + rng.uniform(0.0, 1.0, size=m)          # strictly feasible at z0
    if m > 2 and rng.random() < 0.2:                    # degenerate: duplicated and scaled rows
        W[-1] = 2.0 * W[0]
        b[-1] = 2.0 * b[0]
    return H, g, W, b


def ref_quadprog(H, g, W, b):
    z, f, *_ = quadprog.solve_qp(H, -g, -W.T, -b, 0)
    return z, f


def ref_daqp(H, g, W, b):
    x, f, flag, info = daqp.solve(H, g, W, b, np.full(b.shape, -1e30), np.zeros(b.shape, dtype=np.intc))
    assert flag == 1, flag
    return np.asarray(x)


def ref_osqp(H, g, W, b):
    s = osqp.OSQP()
    s.setup(sp.csc_matrix(np.triu(H)), g, sp.csc_matrix(W), np.full(b.shape, -np.inf), b, verbose=False,
            eps_abs=1e-9, eps_rel=1e-9, polishing=True, max_iter=200000)
    r = s.solve(raise_error=False)
    return np.asarray(r.x)


def check_gi(H, g, W, b, z_ref, f_ref, tol=1e-8):
    r = gi.solve(H, g, W, b)
    assert r.optimal, r.status
    k = gi.kkt_residual(H, g, W, b, r.z, r.lam)
    scale = 1.0 + np.max(np.abs(z_ref))
    assert np.max(np.abs(r.z - z_ref)) <= tol * scale, (r.z, z_ref)
    f = 0.5 * r.z @ H @ r.z + g @ r.z
    assert abs(f - f_ref) <= 1e-9 * (1 + abs(f_ref)), (f, f_ref)
    assert max(k.values()) <= 1e-8 * (1 + np.max(np.abs(g)) + np.max(np.abs(b))), k
    return r


def test_gi_random_vs_quadprog_daqp_osqp():
    rng = np.random.default_rng(SEED)
    n_qp, n_osqp = 3000, 300
    worst = {"quadprog": 0.0, "daqp": 0.0, "osqp": 0.0}
    active = 0
    for k in range(n_qp):
        H, g, W, b = random_qp(rng)
        zq, fq = ref_quadprog(H, g, W, b)
        r = check_gi(H, g, W, b, zq, fq)
        active += len(r.active)
        sc = 1.0 + np.max(np.abs(zq))
        worst["quadprog"] = max(worst["quadprog"], np.max(np.abs(r.z - zq)) / sc)
        zd = ref_daqp(H, g, W, b)
        worst["daqp"] = max(worst["daqp"], np.max(np.abs(r.z - zd)) / sc)
        assert np.max(np.abs(r.z - zd)) <= 1e-5 * sc
        if k < n_osqp:
            zo = ref_osqp(H, g, W, b)
            worst["osqp"] = max(worst["osqp"], np.max(np.abs(r.z - zo)) / sc)
            assert np.max(np.abs(r.z - zo)) <= 1e-4 * sc
    print(f"seed {SEED}: GI on {n_qp} random QPs (n<=8, m<=24, {active} active constraints in total); "
          f"worst relative |dz|: {worst}")


def test_gi_infeasible_and_unconstrained():
    # x >= 1 and x <= -1: infeasible
    r = gi.solve(np.eye(1), np.zeros(1), np.array([[-1.0], [1.0]]), np.array([-1.0, -1.0]))
    assert r.status == "infeasible"
    # inactive constraints: the unconstrained minimum, no iteration
    H = np.diag([2.0, 1.0])
    g = np.array([-2.0, 1.0])
    r = gi.solve(H, g, np.array([[1.0, 0.0]]), np.array([10.0]))
    assert r.optimal and r.iterations == 0 and np.allclose(r.z, [1.0, -1.0])
    # a constraint that becomes blocking and must be dropped again (drop path)
    rng = np.random.default_rng(SEED + 1)
    drops = 0
    for _ in range(500):
        H, g, W, b = random_qp(rng, n_max=4, m_max=12)
        zq, fq = ref_quadprog(H, g, W, b)
        drops += check_gi(H, g, W, b, zq, fq).drops
    assert drops > 0, "the constraint-drop (Givens) path was never exercised"
    print(f"GI infeasibility detected; {drops} constraint drops exercised on 500 QPs")


def test_ipm_validation_mode_vs_quadprog_and_paper_mode_accuracy():
    rng = np.random.default_rng(SEED + 2)
    n = 800
    errs, errs4 = [], []
    for _ in range(n):
        H, g, W, b = random_qp(rng, n_max=6, m_max=16)
        zq, _ = ref_quadprog(H, g, W, b)
        cons = ipm.linear(W, -b)
        r = ipm.solve(H, g, cons, tau=1.0, tau_decrease=0.3, max_iter=80, threshold=1e-10)
        sc = 1.0 + np.max(np.abs(zq))
        errs.append(np.max(np.abs(r.xi - zq)) / sc)
        r4 = ipm.solve(H, g, cons)                      # 001 Algorithm 1 as published
        errs4.append(np.max(np.abs(r4.xi - zq)) / sc)
    assert max(errs) <= 1e-6, max(errs)
    print(f"seed {SEED}: IPM validation mode on {n} random QPs: worst relative |dxi| {max(errs):.2e}; "
          f"paper mode (tau=0.5, 4 it.) on the same unscaled QPs: median {np.median(errs4):.3f}, "
          f"95th percentile {np.percentile(errs4, 95):.3f} relative error (an approximation, as 001 states)")


def _ccs_qps(u_limit=None, n_max=400):
    """CCS-MPCC QPs recorded in closed loop (scenario 2 quick, optionally a small voltage circle)."""
    rec = []

    class Rec(CcsMPCC):
        def problem(self, *a, **k):
            out = super().problem(*a, **k)
            if len(rec) < n_max:
                rec.append(out)
            return out
    case = compare.case_s2(True) if u_limit is None else compare.case_vlimit(True, u_limit)
    cfg = case.cfg
    ctl = Rec(cfg) if u_limit is None else Rec(cfg, u_limit=u_limit)
    cl.simulate(cfg, compare.NoPreview(ctl), case.scenario, dead_time=case.dead_time)
    return rec


def _polygon_qp(H, f, cons, sides=256, outer=False):
    """Inner (vertices on the circle) or outer (facets tangent) polygon of every circle row -> quadprog."""
    C, d = [], []
    for i in range(cons.m):
        P = cons.P[i]
        if P is None:
            C.append(cons.C[i]); d.append(cons.d[i])
            continue
        # h = 1/2 xi'P xi + c'xi + d0 = |a + M xi|^2 / s^2 - 1 with P = 2 M'M / s^2: recover the affine map
        ev, V = np.linalg.eigh(P / 2.0)
        keep = ev > 1e-12 * ev.max()
        Msc = (V[:, keep] * np.sqrt(ev[keep])).T                 # rows span P/2 = Msc' Msc
        a = np.linalg.lstsq(Msc.T, cons.C[i] / 2.0, rcond=None)[0]
        r2 = a @ a - cons.d[i]
        for k in range(sides):
            th = 2 * math.pi * (k + 0.5) / sides
            n = np.zeros(Msc.shape[0]); n[0], n[-1] = math.cos(th), math.sin(th)
            # n'(a + Msc xi) <= sqrt(r2) cos(pi/sides)
            C.append(n @ Msc); d.append(n @ a - math.sqrt(r2) * (1.0 if outer else math.cos(math.pi / sides)))
    C, d = np.array(C), np.array(d)
    z, *_ = quadprog.solve_qp(H, -f, -C.T, d, 0)
    return z


def test_ipm_on_ccs_mpcc_problems():
    for u_limit in (None, 4.0):
        rec = _ccs_qps(u_limit)
        errs, gaps, viols, poly, kkt, act, infeasible, pgap, e12 = [], [], [], [], [], 0, 0, [], []
        for H, f, cons in rec:
            r4 = ipm.solve(H, f, cons)
            assert np.all(np.isfinite(r4.xi))
            try:
                zp = _polygon_qp(H, f, cons)
            except ValueError:          # quadprog: constraints inconsistent (see the print below)
                infeasible += 1
                continue
            rc = ipm.solve(H, f, cons, tau=1.0, tau_decrease=0.2, max_iter=80, threshold=1e-10)
            J = lambda x: 0.5 * x @ H @ x + f @ x   # noqa: E731
            k = ipm.kkt_error(H, f, cons, rc.xi, rc.mu)
            kkt.append(max(k.values()))
            hc = cons.value(rc.xi, OpCount())
            act += int(np.any(hc > -1e-6))
            errs.append(np.max(np.abs(r4.xi - rc.xi)))
            e12.append(np.max(np.abs(ipm.solve(H, f, cons, max_iter=12).xi - rc.xi)))
            gaps.append(J(r4.xi) - J(rc.xi))
            viols.append(np.max(cons.value(r4.xi, OpCount())))
            poly.append(np.max(np.abs(zp - rc.xi)))
            zo = _polygon_qp(H, f, cons, outer=True)
            Jc, Jp, Jo = J(rc.xi), J(zp), J(zo)
            # sandwich: outer polygon (relaxation) <= circle <= inner polygon (restriction)
            tol = 1e-9 * (1 + abs(Jc))
            assert Jo - tol <= Jc <= Jp + tol, (Jo, Jc, Jp)
            pgap.append(Jp - Jo)
        assert max(kkt) < 1e-8, max(kkt)
        # 256-gon inner polygon: radius within 0.008 %, but an optimum on a facet may slide along it
        # by up to one facet (2 pi R / 256 = 0.1 V for R = 4 V); the objective is the sharper check
        assert max(poly) < 0.1, max(poly)
        assert np.all(np.isfinite(pgap))
        lim = "Udc/sqrt3" if u_limit is None else f"{u_limit} V"
        print(f"CCS-MPCC QPs ({lim}): {len(rec)} problems, {infeasible} infeasible (the incremental "
              f"prediction from a large current increment cannot be stopped inside the voltage circle; the "
              f"4-iteration IPM still returns a finite point and u is projected on the circle), "
              f"{act} of the feasible ones with an active constraint at the optimum; "
              f"converged IPM KKT <= {max(kkt):.1e}, vs 256-gon quadprog max |dxi| {max(poly):.2e} V "
              f"(objective within [outer 256-gon, inner 256-gon], width <= {max(pgap):.1e}); "
              f"paper mode (tau=0.5, 4 it.): max |dxi - xi*| {max(errs) * 1e3:.2f} mV (median "
              f"{np.median(errs) * 1e3:.2f}), objective excess max {max(gaps):.2e}, max h(xi) {max(viols):.2e} "
              f"(h > 0: outside a constraint; the controller projects u on the circle); same tau with 12 "
              f"iterations: median {np.median(e12) * 1e3:.2f} mV, 95th percentile {np.percentile(e12, 95) * 1e3:.1f} mV")
        if u_limit is None:
            # no active constraint: 4 iterations are enough (fixed-barrier bias below 5 mV)
            assert max(errs) < 5e-3
        else:
            # active circles: 4 iterations are NOT enough (measured, reported); the fixed-tau
            # central point itself is close to the optimum, reached in ~12 iterations
            assert act > 0.5 * len(errs)
            assert np.median(errs) > 0.1          # documents the shortfall of the paper's 4 iterations
            assert np.median(e12) < 5e-3 and np.percentile(e12, 95) < 0.05


def test_gi_on_online_mpc_problems():
    rec = []

    class Rec(OnlineMPC):
        def step(self, meas):
            u = super().step(meas)
            g, b, res, W = self.last_qp
            rec.append((self.H, g, W, b, res))
            return u
    case = compare.case_fw(True)
    cfg = case.cfg
    from empc.papers.cascade import Cascade
    fw = case.controllers[0][1]().fw
    ctl = Cascade(Rec(cfg), cfg, T_slow=1e-3, field_weakening=fw)
    sc = cl.Scenario("fw_short", "speed", 0.1, case.scenario.profile)
    cl.simulate(cfg, ctl, sc)
    n_act = 0
    worst = 0.0
    for H, g, W, b, res in rec[::3]:
        zq, fq = ref_quadprog(H, g, W, b)
        r = check_gi(H, g, W, b, zq, fq, tol=1e-7)
        n_act += int(len(r.active) > 0)
        worst = max(worst, float(np.max(np.abs(r.z - zq))))
        zd = ref_daqp(H, g, W, b)
        assert np.max(np.abs(r.z - zd)) <= 1e-5 * (1 + np.max(np.abs(zq)))
    assert n_act > 20, n_act
    print(f"GI on {len(rec[::3])} recorded 002 MPC QPs ({n_act} with active constraints): "
          f"max |z - z_quadprog| {worst:.2e} V, DAQP within 1e-5")
