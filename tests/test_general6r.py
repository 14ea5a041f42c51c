"""The general 6R by elimination (derive/kinematics/general6r.py + runtime/python/general6r.py) against the
independent multistart reference (tests/reference/chain.py: Levenberg-Marquardt from many starts on a POE product
of its own): random 6R arms with no two axes parallel or meeting, a UR5e whose wrist_1 axis is tilted by 10
degrees, the xArm6 as pybullet ships it, and the Panda with joint 1 or 3 held (the arms the planner refuses)."""

from __future__ import annotations

import dataclasses
import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from reference import chain as ref
from seeding import case_rng

from derive.families.chain import urdf
from derive.kinematics import general6r as g6
from derive.kinematics.dh_frames import dh_from_chain
from derive.kinematics.planner import NoClosedForm, find_plan
from derive.kinematics.poe import Chain, reduce_free, rot

ROOT = Path(__file__).resolve().parent.parent


def _runtime():
    spec = importlib.util.spec_from_file_location("general6r_runtime", ROOT / "runtime/python/general6r.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


G6 = _runtime()


def random_arm(rng, reach=0.4):
    """Six axes in general position: random directions and points (no neighbours within 0.05 of parallel)."""
    while True:
        axes = np.array([v / np.linalg.norm(v) for v in rng.normal(size=(6, 3))])
        if min(np.linalg.norm(np.cross(axes[i], axes[i + 1])) for i in range(5)) > 0.05:
            break
    points = rng.normal(size=(6, 3)) * reach
    home = np.eye(4)
    home[:3, :3] = rot(axes[0], rng.uniform(-3, 3)) @ rot(axes[3], rng.uniform(-3, 3))
    home[:3, 3] = rng.normal(size=3) * reach
    return Chain("arm", tuple(f"j{i + 1}" for i in range(6)), ("R",) * 6, axes, points, home)


def reference_of(chain: Chain) -> ref.PoeChain:
    """The same numbers read by the reference's own POE product (twists (w, -w x p), its own exponential)."""
    twists = [(a, -np.cross(a, p)) for a, p in zip(chain.axes, chain.points, strict=True)]
    return ref.PoeChain(chain.name, twists, chain.home, np.eye(4), np.eye(4), chain.joint_names,
                        ("revolute",) * chain.n, [-math.pi] * chain.n, [math.pi] * chain.n)


def tilted_ur5e() -> Chain:
    ur, _ = urdf.read(ROOT / "tests/robots/ur5e/ur5e.urdf", "base_link", "tool0")
    axes = ur.axes.copy()
    n = np.cross(axes[3], axes[4])
    axes[3] = rot(n / np.linalg.norm(n), math.radians(10.0)) @ axes[3]
    return dataclasses.replace(ur, axes=axes)


def _distance(a, b) -> float:
    return float(np.max(np.abs(ref.wrap_angle(np.asarray(a) - np.asarray(b)))))


def _check_pose(chain, labelling, reference, q, fixed=None, seed=0):
    """The generating joints among the sets, every reference solution among them, none spurious."""
    free = sorted(fixed or {})
    solver = reduce_free(chain, free[0], q[free[0]]) if free else chain
    T = reference(q)
    sols = g6.solve(solver, labelling, T)
    full = [np.insert(s, free[0], q[free[0]]) if free else s for s in sols]
    # the generating joints: within eps / sigma_min of J (the conditioning of the pose -> joints map)
    jac = reference.jacobian(q)
    smin = np.linalg.svd(np.delete(jac, free, axis=1) if free else jac, compute_uv=False)[-1]
    assert min(_distance(q, s) for s in full) < 1e-9 + 1e-13 / smin
    expected = ref.ik_all(reference, chain.n, T, starts=120, seed=seed, fixed=fixed)
    for x in expected:  # none missed
        assert min(_distance(x, s) for s in full) < 1e-6, (x, full)
    for s in full:  # none spurious
        assert ref.pose_error(reference(s), T) < 1e-9
    assert len(sols) <= 16


def test_the_fourteen_equations_are_linear_in_x_and_y_for_every_6r():
    """Raghavan and Roth's structure, proven for symbolic DH constants: after reducing c^2 + s^2 = 1 (a Groebner
    basis in lex order, so the normal form is unique), no monomial outside (c3, s3, 1) x X or Y + 1 is left."""
    assert g6.structure_violations() == []
    eq = g6.general_equations()
    assert len(eq.left) == len(eq.right) == 14


def test_the_run_time_equations_are_the_symbolic_ones():
    """The coefficients the solvers interpolate at run time (three angles per joint) equal the general symbolic
    equations specialised to the robot's DH constants (same loop, read in DH frames)."""
    rng = case_rng(600)
    for _ in range(3):
        chain = random_arm(rng)
        dh = dh_from_chain(chain)
        el = g6.derive_elimination(dh)
        fq, fr = sp.lambdify(g6.POSE_LP, el.Q, "numpy"), sp.lambdify(g6.POSE_LP, el.r, "numpy")
        pose = chain.fk(rng.uniform(-math.pi, math.pi, 6))
        f = np.linalg.inv(dh.base) @ pose @ np.linalg.inv(dh.end)
        # the DH loop: Rz(t1) K1 ... Rz(t5) K5 Rz(t6) K6 = I with K_i = Tz Tx Rx of link i, K6 = F^-1
        links = [dh.constant_link(i) for i in range(5)] + [np.linalg.inv(f)]
        P, Q, r = G6.g6_equations(links)
        lp = (*f[:3, 2], *f[:3, 3])
        np.testing.assert_allclose(Q, np.array(fq(*lp), float), atol=1e-12)
        np.testing.assert_allclose(r, np.array(fr(*lp), float).ravel(), atol=1e-12)
        # P's tensor over (1, c, s) of t3, t4, t5 against P0, P1, P2 over X
        parts = (("s", "s"), ("s", "c"), ("c", "s"), ("c", "c"), ("s", "1"), ("c", "1"), ("1", "s"), ("1", "c"),
                 ("1", "1"))
        idx = {"1": 0, "c": 1, "s": 2}
        for k3 in range(3):
            for col, (a, b) in enumerate(parts):
                np.testing.assert_allclose(P[:, k3, idx[a], idx[b]], el.P[k3, :, col], atol=1e-12)
        # the derivation's own check of the same (an audit step), within its stated tolerance
        assert g6.symbolic_mismatch(chain, rng) <= 1e-12


def _eigenvalues_and_rounding(m):
    """(eigenvalues of m, eps |m|_2 kappa of each): kappa = |left| |right| / |left^H right| from the eigenvector
    matrix and its inverse, Wilkinson's first-order bound on an eigenvalue's move under rounding of m."""
    w, v = np.linalg.eig(m)
    left = np.linalg.inv(v)
    kappa = np.linalg.norm(left, axis=1) * np.linalg.norm(v, axis=0)
    return w, float(np.finfo(float).eps) * np.linalg.norm(m, 2) * kappa


@pytest.mark.parametrize("case", ["random", "ur5e_tilted"])
def test_the_hidden_t3_determinant_has_the_factor_one_plus_x_squared_to_the_fourth(case):
    """The deflation's premise (runtime/python/general6r.py's docstring), for random arms (no real combination free
    of t3, d0 = 0) and the tilted UR5e (d0 = 1) at random poses and labellings: the combinations mu = a + i b (and
    the real r0) of the six equations have no 1/z part (z = e^(i t3)) to rounding, M(+-i) has a 4-dimensional null
    space, and the 16 eigenvalues of the deflated matrix are the 24 x 24 companion's other than the eight at +-i,
    each to what both computations' rounding allows: eps |A| kappa(lambda) of each matrix (Wilkinson's first-order
    bound, kappa from the eigenvectors), 8 of it, plus 1e-8 relative (a flat 1e-8 failed on 2 % of Haswell seeds,
    kappa ~ 1e4 on companions of norm 1e5). The companion keeps (1 + x^2)^4's eigenvalues, two 4-fold ones at +-i
    that its rounding spreads by (eps |comp|)^(1/4) ~ 1e-3, and an eigenvalue r from them moves by about that to the
    fourth over r^3 (2.7e-8 at r = 0.006, Haswell seed 231773): within |x^2 + 1| <= 0.1 of them a deflated eigenvalue
    is checked on the polynomial itself instead, M(x) = a x^2 + b x + c singular to its rounding."""
    rng = case_rng(605)
    chains = [random_arm(rng) for _ in range(4)] if case == "random" else [tilted_ur5e()] * 4
    seen_d0 = set()
    for chain in chains:
        frames = G6.g6_z_frames(chain.axes, chain.points)
        pose = chain.fk(rng.uniform(-math.pi, math.pi, 6))
        loop = G6.g6_loop_links(frames, chain.home, pose)
        links = G6.g6_labelled(loop, *((2, True) if case == "ur5e_tilted" else
                                       (int(rng.integers(6)), bool(rng.integers(2)))))[0]
        P, Q, r = G6.g6_equations(links)
        n = np.linalg.svd(Q)[0][:, 8:].T
        t6 = np.einsum("fe,eabc->fabc", n, G6._g6_with_constant(P, r))
        basis = G6.g6_deflation_basis(n)
        r0, ab, _ = basis
        seen_d0.add(r0.shape[1])
        mu = np.hstack([ab[:6] + 1j * ab[6:], r0])
        one_over_z = np.einsum("ek,eab->kab", mu, t6[:, 1] + 1j * t6[:, 2])
        assert np.max(np.abs(one_over_z)) <= 1e-13 * np.max(np.abs(t6))
        phi = float(rng.uniform(-math.pi, math.pi))
        a, b, c = G6._g6_matrix_polynomial(t6, 0, phi)
        sv = np.linalg.svd(c - a + 1j * b, compute_uv=False)
        assert sv[-4] <= 1e-13 * sv[0] and sv[-5] > 1e-6 * sv[0]
        comp = np.zeros((24, 24))
        comp[:12, 12:] = np.eye(12)
        comp[12:, :12] = -np.linalg.solve(a, c)
        comp[12:, 12:] = -np.linalg.solve(a, b)
        full, kfull = _eigenvalues_and_rounding(comp)
        keep = np.abs(full * full + 1.0) > 1e-4
        full, kfull = full[keep], kfull[keep]
        deflated, kdef = _eigenvalues_and_rounding(G6._g6_deflated_matrix(t6, basis, phi)[0])
        assert len(full) == len(deflated) == 16
        for x, rx in zip(deflated, kdef, strict=True):  # each matched to its own (distinct nearest) companion's
            k = int(np.argmin(np.abs(full - x)))
            if abs(x * x + 1.0) > 0.1:
                assert abs(full[k] - x) <= 1e-8 * (1.0 + abs(x)) + 8.0 * (rx + kfull[k]), (x, full[k])
            else:
                sv = np.linalg.svd(a * x * x + b * x + c, compute_uv=False)
                assert sv[-1] <= 1e-12 * sv[0], (x, sv[-1] / sv[0])
            full, kfull = np.delete(full, k), np.delete(kfull, k)
    assert seen_d0 == ({0} if case == "random" else {1})


def test_dh_frames_reproduce_the_chain():
    rng = case_rng(601)
    for _ in range(10):
        chain = random_arm(rng)
        dh = dh_from_chain(chain)
        for q in rng.uniform(-math.pi, math.pi, size=(10, 6)):
            np.testing.assert_allclose(dh.fk(q), chain.fk(q), atol=1e-13)


@pytest.mark.parametrize("robot", range(4))
def test_every_solution_of_a_random_general_6r(robot):
    rng = case_rng(602 + robot)
    chain = random_arm(rng)
    with pytest.raises(NoClosedForm):
        find_plan(chain)
    labelling = g6.choose_labelling(chain, rng)
    reference = reference_of(chain)
    for _ in range(3):
        _check_pose(chain, labelling, reference, rng.uniform(-math.pi, math.pi, 6), seed=int(rng.integers(1 << 30)))


@pytest.mark.parametrize("name", ["ur5e_tilted", "xarm6"])
def test_every_solution_of_real_arms_the_planner_refuses(name):
    """Parallel neighbours make the first labelling's equations dependent (M(x) singular for every x): another
    reading of the loop is chosen, from the sampled regularity."""
    rng = case_rng(610)
    if name == "xarm6":
        import pybullet_data

        chain, _ = urdf.read(Path(pybullet_data.getDataPath()) / "xarm/xarm6_robot.urdf")
    else:
        chain = tilted_ur5e()
    with pytest.raises(NoClosedForm):
        find_plan(chain)
    labelling = g6.choose_labelling(chain, rng)
    reference = reference_of(chain)
    for _ in range(3):
        _check_pose(chain, labelling, reference, rng.uniform(-math.pi, math.pi, 6), seed=int(rng.integers(1 << 30)))


@pytest.mark.parametrize("free", [0, 2])
def test_the_panda_with_a_free_joint_the_planner_refuses(free):
    """Joint 1 or 3 held: no decomposition; the general 6R solves the rest for any held value (the labelling is
    chosen over several)."""
    from derive.families.chain import description
    from derive.spec import Spec

    path = ROOT / "tests/robots/panda/panda_dh.toml"
    import tomllib

    chain = description.read(Spec(tomllib.loads(path.read_text()), path)).chain
    rng = case_rng(620 + free)
    with pytest.raises(NoClosedForm):
        find_plan(reduce_free(chain, free, 0.7))
    labelling = g6.choose_labelling(reduce_free(chain, free, 0.7), rng)
    reference = reference_of(chain)
    for _ in range(3):
        q = rng.uniform(-2.5, 2.5, 7)
        _check_pose(chain, labelling, reference, q, fixed={free: q[free]}, seed=int(rng.integers(1 << 30)))



def test_the_elimination_reads_the_panda_with_joint5_held_past_a_singular_leading_coefficient():
    """Joint 5 held: at one phi the deflated leading coefficient is exactly singular (numpy's solve raised
    LinAlgError inside ik, and derive crashed with "Singular matrix"); the next phi serves. The held chain keeps a
    spherical shoulder, where the elimination degenerates and may miss solutions (Haswell kernels, seed 3: a pose
    missed), so `wristkin derive` solves this arm by a decomposition (planned at a held value other than 0), and
    this checks only that the elimination reads it without raising and returns verified sets."""
    from derive.families.chain import description
    from derive.spec import Spec

    path = ROOT / "tests/robots/panda/panda_dh.toml"
    import tomllib

    chain = description.read(Spec(tomllib.loads(path.read_text()), path)).chain
    rng = case_rng(625)
    labelling = g6.choose_labelling([reduce_free(chain, 4, v) for v in (0.0, 0.7, -1.9, 2.6)], rng)
    reference = reference_of(chain)
    for _ in range(3):
        q = rng.uniform(-2.5, 2.5, 7)
        solver = reduce_free(chain, 4, q[4])
        T = reference(q)
        for s in g6.solve(solver, labelling, T):
            assert np.max(np.abs(solver.fk(s) - T)) <= 1e-9


# ------------------------------------------------------------------------------------------------ the C twin
@pytest.fixture(scope="module")
def clib():
    import ctypes

    import cbuild

    c_dir = ROOT / "runtime/c"
    so = cbuild.load(cbuild.compile_shared([c_dir / "wk_general6r.c", c_dir / "wk_eigen.c"], [c_dir],
                                           name="wk_general6r"))
    dp = np.ctypeslib.ndpointer(dtype=np.float64, flags="C_CONTIGUOUS")
    so.wk_g6_z_frames.argtypes = [dp, dp, dp]
    so.wk_g6_z_frames.restype = None
    so.wk_g6_solve.argtypes = [dp, dp, dp, ctypes.c_int, ctypes.c_int, ctypes.c_int, dp, ctypes.c_int]
    so.wk_g6_solve.restype = ctypes.c_int
    return so


def _c_solve(clib, chain, labelling, pose):
    """The C candidates, verified and merged as the Python's are (derive/kinematics/general6r.solve)."""
    frames = np.zeros((6, 16))
    clib.wk_g6_z_frames(np.ascontiguousarray(chain.axes, dtype=float),
                        np.ascontiguousarray(chain.points, dtype=float), frames)
    out = np.zeros((64, 6))
    n = clib.wk_g6_solve(frames, np.ascontiguousarray(chain.home, dtype=float), np.ascontiguousarray(pose),
                         labelling.shift, int(labelling.reverse), labelling.hidden, out, 64)
    assert n >= 0
    sols: list = []
    for q in out[:n]:  # refined by Newton steps in C already: verified, not polished again
        if np.max(np.abs(chain.fk(q) - pose)) <= 1e-9 and all(_distance(q, s) > 1e-6 for s in sols):
            sols.append(ref.wrap_angle(q))
    return sols


@pytest.mark.parametrize("case", ["random", "ur5e_tilted"])
def test_the_c_elimination_gives_the_python_sets(clib, case):
    """C (wk_general6r.c, with wk_eigen.c's quadratic eigenproblem) and Python (numpy) give the same solutions,
    the generating joints among them, for random general arms and the tilted UR5e."""
    rng = case_rng(630)
    chains = [random_arm(rng) for _ in range(3)] if case == "random" else [tilted_ur5e()]
    for chain in chains:
        labelling = g6.choose_labelling(chain, rng)
        for _ in range(4):
            q = rng.uniform(-math.pi, math.pi, 6)
            pose = chain.fk(q)
            c_sets, py_sets = _c_solve(clib, chain, labelling, pose), g6.solve(chain, labelling, pose)
            assert len(c_sets) == len(py_sets)
            for s in c_sets:
                assert min(_distance(s, p) for p in py_sets) < 1e-9
            smin = np.linalg.svd(chain.jacobian(q), compute_uv=False)[-1]
            assert min(_distance(q, s) for s in c_sets) < 1e-9 + 1e-13 / smin


@pytest.mark.c_only  # no numpy result enters: the repeated passes on other kernels skip it
def test_the_c_elimination_under_asan_ubsan():
    """Random arms through all 36 labellings (a degenerate one among them for arms with parallel neighbours),
    hostile poses and arguments: no sanitizer report, no write past max_out, finite candidates only."""
    import subprocess

    import cbuild
    from seeding import TEST_SEED

    probe = subprocess.run([cbuild.compiler(), "-fsanitize=address,undefined", "-x", "c", "-", "-o", "/dev/null"],
                           input="int main(void){return 0;}", capture_output=True, text=True)
    if probe.returncode != 0:
        pytest.skip("compiler has no ASan/UBSan runtime")
    c_dir = ROOT / "runtime/c"
    exe = cbuild.compile_executable([ROOT / "tests/c/general6r_sanitize.c", c_dir / "wk_general6r.c",
                                     c_dir / "wk_eigen.c"], [c_dir, ROOT / "tests/c"], "general6r_sanitize",
                                    extra_flags=cbuild.SANITIZE_FLAGS)
    run = subprocess.run([str(exe), str(TEST_SEED)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.startswith("ok ")
    assert "runtime error" not in run.stderr and "AddressSanitizer" not in run.stderr


# ------------------------------------------------------------------------------------------ near-singular poses
def _singular_joints(chain, rng):
    """Joints where det J changes sign along a random line in joint space, bisected to rounding: there two IK
    solutions meet (the pose is on the boundary between poses with n and n - 2 real solutions)."""
    while True:
        q0, d = rng.uniform(-math.pi, math.pi, 6), rng.normal(size=6)
        lams = np.linspace(-1.0, 1.0, 41)
        dets = [np.linalg.det(chain.jacobian(q0 + lam * d)) for lam in lams]
        for k in range(40):
            if np.sign(dets[k]) != np.sign(dets[k + 1]):
                lo, hi, flo = lams[k], lams[k + 1], dets[k]
                for _ in range(60):
                    mid = 0.5 * (lo + hi)
                    fm = np.linalg.det(chain.jacobian(q0 + mid * d))
                    lo, flo, hi = (mid, fm, hi) if np.sign(fm) == np.sign(flo) else (lo, flo, mid)
                return q0 + 0.5 * (lo + hi) * d


def _double_root_allowance(chain, q, pose, delta=None) -> float:
    """How well a double root q is determined. Along J's null direction v the pose moves as kappa h^2 / 2 along the
    left null direction u0 (the first-order term vanishes, and a pose change inside J's range is undone by a
    transverse move of the joints: so only u0's component counts), so every joint vector within sqrt(2 delta /
    kappa) of q reproduces the pose to its rounding delta ~ eps (1 + |p|_1): that is the conditioning,
    sqrt(eps)-level. kappa from the pose change at h = 1e-4 as a 6-vector (position, rotation vector: J's rows).
    A factor 10 over sqrt(delta / kappa) covers the max-norm over joints and Newton stopping where the pose error
    reaches rounding (measured: up to 1.7 over 18 poses of 6 random arms). `delta`: another pose error than
    rounding (the multistart's tolerance: how far its points at the double root may lie)."""
    u, _, vt = np.linalg.svd(chain.jacobian(q))
    h = 1e-4
    moved = chain.fk(q + h * vt[-1])
    r = moved[:3, :3] @ pose[:3, :3].T
    change = np.concatenate([moved[:3, 3] - pose[:3, 3], 0.5 * np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0],
                                                                          r[1, 0] - r[0, 1]])])
    kappa = 2.0 * abs(float(u[:, -1] @ change)) / h**2
    if delta is None:
        delta = np.finfo(float).eps * (1.0 + float(np.sum(np.abs(pose[:3, 3]))))
    return 10.0 * math.sqrt(delta / kappa)


@pytest.mark.parametrize("backend", ["numpy", "c"])
def test_at_a_double_root_the_generating_joints_are_returned_once(request, backend):
    """Poses where two real solutions of a general-6R arm merge (det J = 0 at the generating joints): the generating
    joints are returned within the double root's conditioning (_double_root_allowance), the double root once where
    that conditioning is below the merge tolerance (a near-cusp, kappa -> 0, is determined only to ~1e-5 rad: two
    sets there are both the double root), every set verifies and every solution of the independent multistart
    reference is among them. Before the refinement kept stepping while Newton's steps contracted, a double root's
    two candidates stopped ~7e-7 apart on either side of it (the first Newton step raises the pose error there):
    14x the allowance and two sets for one solution; and before G6_REAL_TOL = 1e-4 a double root split into a
    complex pair by rounding lost the generating set."""
    clib = request.getfixturevalue("clib") if backend == "c" else None
    rng = case_rng(640)
    for arm in range(6):
        chain = random_arm(rng)
        labelling = g6.choose_labelling(chain, rng)
        reference = reference_of(chain)
        for case in range(3):
            q = _singular_joints(chain, rng)
            pose = chain.fk(q)
            sets = _c_solve(clib, chain, labelling, pose) if clib else g6.solve(chain, labelling, pose)
            allowance = _double_root_allowance(chain, q, pose)
            assert min(_distance(q, s) for s in sets) <= allowance
            for s in sets:
                assert ref.pose_error(reference(s), pose) < 1e-9
            # every set near the double root is it, to its conditioning; where that is below the merge tolerance
            # (1e-6, a fold with kappa ~0.1 or more), it is returned once
            near = [s for s in sets if _distance(s, q) < 1e-4]
            assert all(_distance(s, q) <= allowance for s in near)
            assert len(near) == 1 or allowance > 5e-7, "a double root returned twice"
            # the reference keeps a point at pose error < 1e-10, which at the double root allows sqrt(2e-10 /
            # kappa) ~ 3e-5 rad, near a cusp (kappa -> 0) more (1.5e-3 at test seed 88213): its points within that
            # of q stand for the double root, checked against q itself above
            window = max(1e-3, _double_root_allowance(chain, q, pose, 2.0 * ref.POSE_TOL))
            for x in ref.ik_all(reference, 6, pose, starts=60, seed=3 * arm + case):
                assert _distance(x, q) < window or min(_distance(x, s) for s in sets) < 1e-6, (x, window)
