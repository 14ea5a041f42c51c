"""The design atlas (wristkin_atlas, docs/atlas.md).

The CI sweep: a small underactuated-wrist sweep on a 2-worker local Dask cluster, checked measure by measure
against a plain serial computation built from tests/reference (its own IK/FK, axes, conditioning and sampling
recipe; nothing from the atlas or the generated code). Then: the same bits for any chunking / worker count /
scheduler, resume after an interruption, the CLI (missing extra, bad arguments, the report), and the 3-RSR
local index against the module's derived Jacobians."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest

pytest.importorskip("distributed")
pytest.importorskip("xarray")
pytest.importorskip("zarr")

import wristkin_atlas  # noqa: E402
from reference import underactuated_wrist as ref  # noqa: E402
from seeding import TEST_SEED, case_rng  # noqa: E402
from wristkin_atlas.mechanisms import Options, mechanism  # noqa: E402

UW_SWEEP = ["alpha1=55:65:2", "beta2=40:46:2"]
UW_SAMPLES = 160
TILT = math.radians(60.0)
THRESHOLD = 0.1
BLOCK = 1024  # the documented sampling block (docs/atlas.md): part of the sample recipe


def _unit(seed: int, stream: int, samples: int) -> np.ndarray:
    """The documented recipe: block b = SeedSequence([seed, stream, b]) -> 1024 x 3 uniforms; concatenated, cut."""
    blocks = [np.random.default_rng(np.random.SeedSequence([seed, stream, b])).random((BLOCK, 3))
              for b in range(math.ceil(samples / BLOCK))]
    return np.concatenate(blocks)[:samples]


def _ref_jacobian_parts(thetas, R, d):
    z1, z2, z3 = ref.base_axes(d), ref.middle_axes(thetas, d), (R @ ref.platform_axes(d).T).T
    x = np.cross(z2, z3)
    g = np.einsum("ij,ij->i", z1, x)
    return x, g


def _ref_inverse_kappa(x, g):
    if np.any(g == 0.0) or abs(np.linalg.det(x)) == 0.0:
        return 0.0
    j = x / g[:, None]
    return 3.0 / (np.linalg.norm(j, "fro") * np.linalg.norm(np.linalg.inv(j), "fro"))


def reference_measures(design_deg: dict, seed: int, samples: int) -> dict:
    """Every measure of one design, serially, from tests/reference."""
    d = ref.as_design({k: math.radians(v) for k, v in design_deg.items()})
    theta0 = ref.home_angle(d)
    x0, g0 = _ref_jacobian_parts((theta0,) * 3, np.eye(3), d)
    home = g0 > 0.0
    up, uj = _unit(seed, 0, samples), _unit(seed, 1, samples)
    n_reach = n_sets = near_inv = near_dir = 0
    lis, best, phis = [], [], []
    for u in up:
        psi, phi = 2 * math.pi * u[0] - math.pi, 2 * math.pi * u[2] - math.pi
        th = math.acos(1 - u[1] * (1 - math.cos(TILT)))  # the platform axis uniform on the cap
        R = ref.rotation_from_euler(psi, th, phi)
        res = ref.ik_reference(R, d)
        assert "indeterminate" not in res.flags
        if not res.triples:
            continue
        n_reach += 1
        pose_li = []
        for t in res.triples:
            x, g = _ref_jacobian_parts(t, R, d)
            li = _ref_inverse_kappa(x, g)
            pose_li.append(li)
            n_sets += 1
            near_inv += min(abs(g)) / math.sin(d.alpha1) < THRESHOLD
            near_dir += abs(np.linalg.det(x)) / np.prod(np.linalg.norm(x, axis=1)) < THRESHOLD
            if np.array_equal(g > 0.0, home):
                phis.append(np.degrees(np.remainder(np.array(t) - theta0 + math.pi, 2 * math.pi) - math.pi))
        lis += pose_li
        best.append(max(pose_li))
    modes = np.zeros(9, dtype=int)
    fk_near = 0
    for u in uj:
        thetas = 2 * math.pi * u
        fk = ref.fk_reference(thetas, d)
        modes[fk.count] += 1
        near = False
        for R in fk.rotations:
            x, _ = _ref_jacobian_parts(thetas, R, d)
            near |= abs(np.linalg.det(x)) / np.prod(np.linalg.norm(x, axis=1)) < THRESHOLD
        fk_near += near
    phis = np.array(phis).reshape(-1, 3)
    if not lis:  # nothing reachable in the sample: the atlas reports NaN
        lis, best, n_sets, phis = [math.nan], [math.nan], math.nan, np.full((1, 3), math.nan)
    return {"reachable": n_reach / samples, "gci": float(np.mean(lis)), "gci_best": float(np.mean(best)),
            "worst_li": float(np.min(lis)), "near_inverse": near_inv / n_sets, "near_direct": near_dir / n_sets,
            "fk_modes": modes / samples, "fk_modes_mean": float(modes @ np.arange(9)) / samples,
            "fk_no_assembly": modes[0] / samples, "fk_near_direct": fk_near / samples,
            "phi_lo": phis.min(axis=0), "phi_hi": phis.max(axis=0)}


@pytest.fixture(scope="module")
def uw_two_workers(tmp_path_factory):
    out = tmp_path_factory.mktemp("atlas_uw")
    opts = Options(threshold=THRESHOLD, tilt_max=TILT)
    ds = wristkin_atlas.run_sweep("underactuated_wrist", UW_SWEEP, out, samples=UW_SAMPLES, seed=TEST_SEED,
                                  options=opts, workers=2, design_chunk=1, progress=False)
    return ds.load(), out


def test_ci_sweep_on_two_workers_matches_the_serial_reference(uw_two_workers):
    ds, _ = uw_two_workers
    default = dict(zip(("alpha1", "alpha2", "beta1", "beta2"), (60.0, 60.0, 30.0, 43.89), strict=True))
    for a1 in ds.alpha1.values:
        for b2 in ds.beta2.values:
            want = reference_measures(dict(default, alpha1=float(a1), beta2=float(b2)), TEST_SEED, UW_SAMPLES)
            got = ds.sel(alpha1=a1, beta2=b2)
            where = f"alpha1={a1}, beta2={b2}"
            # counts: exactly the same solutions found (ratios of the same integers are the same floats)
            for name in ("reachable", "near_inverse", "near_direct", "fk_no_assembly", "fk_near_direct",
                         "fk_modes_mean"):
                assert float(got[name]) == want[name] or (math.isnan(want[name]) and math.isnan(float(got[name]))), (
                    name, where, float(got[name]), want[name])
            np.testing.assert_array_equal(got["fk_modes"].values, want["fk_modes"], err_msg=where)
            # 1/kappa_F: the atlas's closed form vs inv() here; the sum is fixed point (2^-32 per value)
            for name in ("gci", "gci_best", "worst_li"):
                assert float(got[name]) == pytest.approx(want[name], rel=1e-8, abs=1e-9, nan_ok=True), (name, where)
            # Phi_i: the reference's IK roots agree with the C roots to ~1e-10 rad
            np.testing.assert_allclose(got["phi_lo"].values, want["phi_lo"], atol=1e-6, err_msg=where)
            np.testing.assert_allclose(got["phi_hi"].values, want["phi_hi"], atol=1e-6, err_msg=where)


def _same(a, b):
    for name in a.data_vars:
        np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)


@pytest.mark.parametrize("name,sweep", [("underactuated_wrist", ["beta2=40:46:3"]),
                                        ("rsr_wrist", ["phi_min=20:30:2", "phi_max=70:80:2"]),
                                        ("puma560", ["a2=0.3:0.5:3"])])
def test_same_bits_for_any_chunking_and_scheduler(tmp_path, name, sweep, uw_two_workers):
    """2500 samples = 3 blocks: one task per block vs all blocks in one task, 1 vs all designs per task, the
    in-process scheduler vs 2 worker processes."""
    opts = Options(threshold=THRESHOLD, tilt_max=TILT)
    a = wristkin_atlas.run_sweep(name, sweep, tmp_path / "a", samples=2500, seed=TEST_SEED, options=opts,
                                 design_chunk=1, sample_chunk=1024, progress=False).load()
    b = wristkin_atlas.run_sweep(name, sweep, tmp_path / "b", samples=2500, seed=TEST_SEED, options=opts,
                                 design_chunk=4, progress=False, workers=2).load()
    _same(a, b)


def test_interrupted_sweep_resumes_from_stored_chunks(tmp_path):
    opts = Options(threshold=THRESHOLD, tilt_max=TILT)
    kw = dict(samples=300, seed=TEST_SEED, options=opts, design_chunk=1, progress=False)
    assert wristkin_atlas.run_sweep("underactuated_wrist", ["beta2=40:46:4"], tmp_path / "r", max_tasks=2,
                                    **kw) is None
    import zarr

    seconds = zarr.open_group(str(tmp_path / "r" / "partials.zarr"), mode="r")["seconds"][...]
    assert np.isfinite(seconds).sum() == 2  # a stored task's seconds: NaN until it is stored
    resumed = wristkin_atlas.run_sweep("underactuated_wrist", ["beta2=40:46:4"], tmp_path / "r", **kw).load()
    fresh = wristkin_atlas.run_sweep("underactuated_wrist", ["beta2=40:46:4"], tmp_path / "f", **kw).load()
    _same(resumed, fresh)
    opened = wristkin_atlas.open_atlas(tmp_path / "r")
    assert opened["gci"].attrs["units"] == "1" and opened.beta2.attrs["units"] == "deg"
    # other settings in the same folder: refused (exit 2 from the CLI), not mixed
    from wristkin_atlas.runner import StoreMismatch

    with pytest.raises(StoreMismatch):
        wristkin_atlas.run_sweep("underactuated_wrist", ["beta2=40:46:5"], tmp_path / "r", **kw)


def test_cli_writes_store_summary_and_report(tmp_path, capsys):
    from wristkin import cli

    rc = cli.main(["atlas", "underactuated_wrist", "--sweep", "alpha1=55:65:2", "--sweep", "beta2=40:46:2",
                   "--samples", "200", "--tilt-max", "45", "--out", str(tmp_path), "--quiet"])
    assert rc == 0
    text = (tmp_path / "report.md").read_text()
    assert "## Best designs" in text and "140.15 deg" in text and "figures/map_gci.png" in text
    assert (tmp_path / "figures" / "map_gci.png").stat().st_size > 0
    assert (tmp_path / "figures" / "focus_workspace.png").stat().st_size > 0
    assert (tmp_path / "best.csv").read_text().startswith("measure,")


def _report_bytes(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.suffix in (".md", ".html", ".png", ".csv")}


@pytest.mark.parametrize("name,sweep", [("underactuated_wrist", ["alpha1=55:65:2", "beta2=40:46:2"]),
                                        ("puma560", ["a2=0.3:0.5:2", "a3=0.0:0.1:2"])])
def test_report_in_both_formats_names_units_definitions_and_marks_the_seed_design(tmp_path, name, sweep):
    """report.md and a self-contained report.html: every measure with its units and definition, the seed
    (catalogue) design named where the maps star it, the figures embedded; and the same bytes when the outputs are
    written again from the store (deterministic: no timings, no Software metadata, a fixed dpi)."""
    from wristkin_atlas.report import write_outputs

    ds = wristkin_atlas.run_sweep(name, sweep, tmp_path, samples=200, seed=TEST_SEED, progress=False).load()
    write_outputs(tmp_path, ds)
    md, page = (tmp_path / "report.md").read_text(), (tmp_path / "report.html").read_text()
    for var in ds.data_vars.values():
        units, definition = var.attrs["units"], var.attrs["definition"]
        assert f"| {var.name} | {units} |" in md and definition in md, var.name
        assert f"<td>{var.name}</td><td>{units}</td>" in page, var.name
    default = dict(zip(mechanism(name).module.DESIGN_NAMES, mechanism(name).module.DESIGN_DEFAULT, strict=True))
    seed = ("seed design: alpha1 = 60 deg, beta2 = 43.89 deg" if name == "underactuated_wrist" else
            f"seed design: a2 = {default['a2']:g} m, a3 = {default['a3']:g} m")
    assert seed in md and seed in page
    assert "figures/" not in page and page.count("data:image/png;base64,") == md.count("![")
    first = _report_bytes(tmp_path)
    for png in (tmp_path / "figures").glob("*.png"):
        assert b"Software" not in png.read_bytes() and b"atplotlib" not in png.read_bytes()
    write_outputs(tmp_path, wristkin_atlas.open_atlas(tmp_path).load())  # from the store: the same bytes
    assert _report_bytes(tmp_path) == first


@pytest.mark.parametrize("argv", [["nosuch", "--sweep", "a=1:2:2"], ["rsr_wrist", "--sweep", "nosuch=1:2:2"],
                                  ["rsr_wrist", "--sweep", "L=1:2"], ["rsr_wrist"]])
def test_cli_bad_arguments_exit_2(tmp_path, argv, capsys):
    from wristkin import cli

    assert cli.main(["atlas", *argv, "--out", str(tmp_path)]) == 2
    assert "error" in capsys.readouterr().err


def test_cli_without_the_atlas_extra_exits_1_naming_it(tmp_path, monkeypatch, capsys):
    from wristkin import cli

    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed -> ImportError
    rc = cli.main(["atlas", "rsr_wrist", "--sweep", "L=0.05:0.07:2", "--out", str(tmp_path)])
    assert rc == 1
    assert "wristkin[atlas]" in capsys.readouterr().err


def test_rsr_local_index_equals_the_module_jacobians():
    """The atlas's 3-RSR J (v = (sin beta alpha_dot, beta_dot, l_bw_dot / L) -> phi_dot) against the derived
    jacobians(q, pose) (jq phi_dot = jx (alpha, beta, l_bw)_dot), column-scaled to the same v."""
    mech = mechanism("rsr_wrist")
    m = mech.module
    d = m.make_design()
    rng = case_rng(2401)
    checked = 0
    for _ in range(200):
        pose = (rng.uniform(0, 2 * math.pi), rng.uniform(0.05, 1.5), rng.uniform(0.03, 0.1))
        sol = m.ik(pose, d)
        for q in sol:
            jq, jx = m.jacobians(q, pose, d)
            j = (jx / jq[:, None]) @ np.diag([1.0 / math.sin(pose[1]), 1.0, d.params[0]])
            want = 3.0 / (np.linalg.norm(j, "fro") * np.linalg.norm(np.linalg.inv(j), "fro"))
            got, _ = mech.local_index(d, np.array([pose]), np.asarray(q)[None, None, :])
            assert float(got[0, 0]) == pytest.approx(want, rel=1e-9)
            checked += 1
    assert checked > 100


def test_underactuated_local_index_equals_the_module_jacobians():
    mech = mechanism("underactuated_wrist")
    m = mech.module
    d = m.make_design()
    rng = case_rng(2402)
    checked = 0
    # poses are drawn until more than 50 IK sets are checked (about half the poses are reachable: a fixed 100
    # poses gave 48 sets at Haswell seed 866292)
    for _ in range(1000):
        if checked > 50:
            break
        pose = (rng.uniform(-math.pi, math.pi), rng.uniform(0, 0.6), rng.uniform(-math.pi, math.pi))
        sol = m.ik(pose, d)
        for q in sol:
            jq, jx = m.jacobians(q, pose, d)
            j = jx / jq[:, None]
            want = 3.0 / (np.linalg.norm(j, "fro") * np.linalg.norm(np.linalg.inv(j), "fro"))
            got, _ = mech.local_index(d, np.array([pose]), np.asarray(q)[None, None, :])
            assert float(got[0, 0]) == pytest.approx(want, rel=1e-9)
            checked += 1
    assert checked > 50


def test_serial_arm_sweep_closes_ik_on_every_sampled_pose(tmp_path):
    """A serial arm: FK of the joint samples, IK of those poses (all 8 PUMA branches where it is generic)."""
    ds = wristkin_atlas.run_sweep("puma560", ["a2=0.3:0.5:2"], tmp_path, samples=500, seed=TEST_SEED,
                                  progress=False).load()
    assert np.all(ds["ik_closes"].values == 1.0)
    assert np.all(ds["ik_sets_mean"].values > 7.0)
    assert np.all(ds["manipulability_mean"].values > 0.0)


def test_spec_file_is_derived_into_out_then_swept(tmp_path):
    """`wristkin atlas SPEC.toml --free JOINT`: derived once into OUT/derived, the free joint swept; a rerun
    resumes (no second derivation, the same numbers)."""
    from pathlib import Path

    from wristkin import cli

    spec = Path(__file__).parent / "robots" / "iiwa14" / "iiwa14_dh.toml"
    argv = ["atlas", str(spec), "--free", "a3", "--sweep", "a3=-60:60:3", "--samples", "300", "--out",
            str(tmp_path), "--quiet", "--no-report"]
    assert cli.main(argv) == 0
    solver = tmp_path / "derived" / "python" / "iiwa14_dh.py"
    stamp = solver.stat().st_mtime_ns
    first = wristkin_atlas.open_atlas(tmp_path).load()
    assert np.all(first["ik_closes"].values == 1.0) and first.a3.attrs["units"] == "deg"
    # a spec chain's conditioning: its module's jacobian per sample (no C batch in the chain family)
    assert np.all((first["gci"].values > 0.0) & (first["gci"].values <= 1.0))
    assert cli.main(argv) == 0
    assert solver.stat().st_mtime_ns == stamp
    _same(first, wristkin_atlas.open_atlas(tmp_path).load())


def test_existing_cluster_by_scheduler_address_gives_the_same_bits(tmp_path):
    """--scheduler ADDRESS: an already running dask.distributed cluster (here a local one started by the test)."""
    from distributed import LocalCluster

    opts = Options(threshold=THRESHOLD, tilt_max=TILT)
    kw = dict(samples=1500, seed=TEST_SEED, options=opts, progress=False)
    with LocalCluster(n_workers=1, threads_per_worker=2, processes=True, dashboard_address=":0") as cluster:
        address = cluster.scheduler_address
        a = wristkin_atlas.run_sweep("rsr_wrist", ["L=0.05:0.07:3"], tmp_path / "a", scheduler=address,
                                     design_chunk=1, **kw).load()
    b = wristkin_atlas.run_sweep("rsr_wrist", ["L=0.05:0.07:3"], tmp_path / "b", **kw).load()
    _same(a, b)


def test_rsr_swing_feasibility_equals_the_module_workspace():
    """The atlas's vectorised attitude feasibility (swing_all, swing_peak) against the module's exact
    workspace(alpha, beta), for random designs and attitudes."""
    mech = mechanism("rsr_wrist")
    m = mech.module
    rng = case_rng(2403)
    for _ in range(20):
        lo = rng.uniform(-0.5, 1.0)
        d = m.make_design((0.06, lo, lo + rng.uniform(0.3, 2.5), rng.uniform(0.0, 0.05), rng.uniform(0.06, 0.12)))
        alpha, beta = rng.uniform(0, 2 * math.pi, 200), rng.uniform(0, math.pi * 0.95, 200)
        got = mech.feasible(d, alpha, beta)
        want = np.array([m.workspace(a, b, d) is not None for a, b in zip(alpha, beta, strict=True)])
        np.testing.assert_array_equal(got, want)


def test_rsr_c_atlas_batch_equals_the_numpy_path():
    """The generated C's atlas_batch (IK, leg limits, the derived atlas_rates' 1/kappa_F, conditioning and FK counts
    in one C loop) against ik_batch / fk_batch and numpy: the same counts and the same fixed-point sums."""
    mech = mechanism("rsr_wrist")
    m = mech.module
    if m.BACKEND != "c":
        pytest.skip("the C extension is not built (WRISTKIN_BACKEND=numpy)")
    from wristkin_atlas import sampling

    rng = case_rng(2404)
    opts = Options(threshold=0.3, tilt_max=TILT)
    for _ in range(12):
        lo = rng.uniform(-0.5, 1.0)
        d = m.make_design((0.06, lo, lo + rng.uniform(0.3, 2.5), rng.uniform(0.0, 0.05), rng.uniform(0.06, 0.12)))
        up, uj = (sampling.unit_block(TEST_SEED, s, 0, 1024, 3, False) for s in (0, 1))
        got = mech.evaluate(d, up, uj, opts)
        want = mech.evaluate_numpy(d, mech.poses(up, d, opts), mech.joints(uj, d), opts)
        assert got.keys() == want.keys()
        for k in want:
            if k in ("li_sum", "li_best_sum"):  # fixed point: the same kernel in C and numpy, a rounding apart
                assert abs(int(got[k]) - int(want[k])) <= 4 * max(1, got["n_sets"]), k
            elif k == "li_min":  # 1/kappa's absolute error is ~eps (relative eps kappa): an absolute bound
                assert got[k] == pytest.approx(want[k], rel=0.0, abs=1e-12), k
            else:
                np.testing.assert_array_equal(got[k], want[k], err_msg=k)


def test_rsr_c_swing_profile_equals_the_numpy_feasibility():
    """The generated C's max_swing (trigonometry hoisted, cross products for the arcs) against the vectorised
    feasibility that test_rsr_swing_feasibility_equals_the_module_workspace checks against workspace()."""
    mech = mechanism("rsr_wrist")
    m = mech.module
    if m.BACKEND != "c":
        pytest.skip("the C extension is not built (WRISTKIN_BACKEND=numpy)")
    rng = case_rng(2405)
    for tilt in (60.0, 90.0, 180.0):
        opts = Options(tilt_max=math.radians(tilt))
        for _ in range(15):
            lo = rng.uniform(-3.0, 3.0)
            d = m.make_design((0.06, lo, lo + rng.uniform(0.3, 6.0), rng.uniform(0.0, 0.05), rng.uniform(0.06, 0.12)))
            alpha = np.radians(np.arange(opts.swing_bins) * 360.0 / opts.swing_bins)
            beta = np.arange(0.0, tilt + 1e-9, mech.SWING_STEP)
            ok = mech.feasible(d, alpha[:, None], np.radians(beta)[None, :])
            want = np.where(ok.any(axis=1), np.where(ok, beta[None, :], -np.inf).max(axis=1), 0.0)
            np.testing.assert_array_equal(mech.swing_profile(d, opts), want)


SERIAL_ARMS = ["puma560", "scara_wrist", "spherical_wrist", "rpp_wrist", "wrist_1dof", "p1p2p3rarb", "rarararbrb"]


@pytest.mark.parametrize("name", SERIAL_ARMS)
def test_serial_c_conditioning_equals_the_svd_of_the_module_jacobian(name):
    """The generated C's atlas_conditioning (Jacobi eigenvalues of J^T J of the derived Jacobian) against numpy's
    SVD of the module's `jacobian`: the local index sigma_min / sigma_max of diag(I / L_c, I) J agrees within the
    Gram matrix's sqrt(eps) near a singularity (it squares the condition number), 1e-9 elsewhere."""
    mech = mechanism(name)
    m = mech.module
    if m.BACKEND != "c":
        pytest.skip("the C extension is not built (WRISTKIN_BACKEND=numpy)")
    from wristkin_atlas import sampling

    d = m.make_design(m.DESIGN_DEFAULT)
    q = mech.joints(sampling.unit_block(TEST_SEED, 1, 0, 1024, mech.joint_dim, False), d)
    length = mech.characteristic_length(d)
    li = mech.local_index_numpy(d, q, length)
    total, li_min, near = mech.conditioning(d, q, THRESHOLD)
    assert total / 2.0**32 == pytest.approx(li.sum(), abs=len(q) * 1e-8)
    assert li_min == pytest.approx(li.min(), abs=1e-7)
    # a sample within sqrt(eps) of the threshold could fall either side
    assert abs(near - int((li < THRESHOLD).sum())) <= int((abs(li - THRESHOLD) < 1e-7).sum())
    assert np.all((li >= 0.0) & (li <= 1.0))


def test_serial_sweep_reports_gci_and_singularity_proximity(tmp_path):
    ds = wristkin_atlas.run_sweep("scara_wrist", ["a2=0.2:0.4:3"], tmp_path, samples=600, seed=TEST_SEED,
                                  progress=False).load()
    for name in ("gci", "worst_li", "near_singular"):
        v = ds[name].values
        assert np.all((v >= 0.0) & (v <= 1.0)), name
        assert ds[name].attrs["units"] == "1" and ds[name].attrs["definition"]
    assert np.all(ds["worst_li"].values <= ds["gci"].values)


def test_scara_rsr_sweep_has_its_wrist_measures_and_the_arms_reach(tmp_path):
    """scara_rsr: the 3-RSR wrist's measures on its own design equal an rsr_wrist sweep's (the same samples), and
    the arm's: IK closes on every FK-sampled pose, and the reach grows with the second link."""
    kw = dict(samples=600, seed=TEST_SEED, progress=False)
    ds = wristkin_atlas.run_sweep("scara_rsr", ["L2=0.2:0.3:2", "phi_max=70:80:2"], tmp_path / "h", **kw).load()
    m = mechanism("scara_rsr").module
    fixed = dict(zip(m.DESIGN_NAMES, m.DESIGN_DEFAULT, strict=True))
    wrist = [f"{n}={fixed[n]!r}" if n not in ("phi_min", "phi_max") else f"{n}={math.degrees(fixed[n])!r}"
             for n in ("L", "phi_min", "lbw_min", "lbw_max")]
    w = wristkin_atlas.run_sweep("rsr_wrist", ["phi_max=70:80:2"], tmp_path / "w", designs=wrist, **kw).load()
    for name in ("reachable", "gci", "worst_li", "near_inverse", "fk_modes_mean", "swing_all", "swing_peak"):
        for l2 in ds.L2.values:
            np.testing.assert_array_equal(ds[name].sel(L2=l2).values, w[name].values, err_msg=name)
    assert np.all(ds["ik_closes"].values == 1.0) and np.all(ds["arm_assembles"].values > 0.5)
    reach = ds["reach_max"].values
    assert np.all(reach[1] > reach[0]) and np.all(reach <= 0.25 + 0.3 + 0.2)
    assert ds["reach_max"].attrs["units"] == "m" and "3-RSR wrist" in ds["gci"].attrs["definition"]


@pytest.mark.parametrize("name,sweep", [("underactuated_wrist", ["beta2=40:46:3"]),
                                        ("rsr_wrist", ["phi_min=20:30:2", "phi_max=70:80:2"]),
                                        ("scara_wrist", ["a2=0.2:0.4:3"]), ("scara_rsr", ["L2=0.2:0.3:2"])])
def test_grid_sampling_gives_the_same_bits_for_any_chunking_and_workers(tmp_path, name, sweep):
    """--grid: a regular lattice of cell centres (side = round(N^(1/dim)), first coordinate slowest) instead of
    random samples; 2500 requested -> 14^3 = 2744 points (3 blocks) for a wrist. One task per block and design vs
    all blocks and designs in one task on 2 worker processes: the same store; and the grid differs from the random
    sample (the flag reaches the tasks)."""
    from wristkin_atlas import sampling

    opts = Options(threshold=THRESHOLD, tilt_max=TILT)
    kw = dict(samples=2500, seed=TEST_SEED, options=opts, progress=False, grid=True)
    a = wristkin_atlas.run_sweep(name, sweep, tmp_path / "a", design_chunk=1, sample_chunk=1024, **kw).load()
    b = wristkin_atlas.run_sweep(name, sweep, tmp_path / "b", design_chunk=16, workers=2, **kw).load()
    _same(a, b)
    dim = mechanism(name).joint_dim
    side = sampling.grid_side(2500, dim)
    assert a.attrs["sampling"] == "grid" and a.attrs["samples_per_design"] == side ** dim
    u = np.concatenate([sampling.unit_block(0, 1, k, 2500, dim, True) for k in range(sampling.blocks(2500, dim, True))])
    assert len(u) == side ** dim and np.array_equal(np.unique(u[:, 0]), (np.arange(side) + 0.5) / side)
    kw["grid"] = False
    r = wristkin_atlas.run_sweep(name, sweep, tmp_path / "r", **kw).load()
    assert r.attrs["sampling"] == "random"
    assert not np.array_equal(r["gci"].values, a["gci"].values, equal_nan=True)


def test_bench_finds_its_atlas_tables_with_the_repository_root_first_on_sys_path(monkeypatch):
    """`make bench` died at its atlas step (AttributeError: tables): `import atlas` in bench/run.py found the
    repository's atlas/ package, not bench/atlas.py, once bench/dh.py had put the root ahead of bench/."""
    import importlib.util
    from pathlib import Path

    root = Path(__file__).resolve().parent.parent
    monkeypatch.syspath_prepend(str(root / "bench"))
    monkeypatch.syspath_prepend(str(root))  # as bench/dh.py leaves it
    monkeypatch.delitem(sys.modules, "atlas", raising=False)
    spec = importlib.util.spec_from_file_location("wristkin_bench_run", root / "bench" / "run.py")
    run = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(run)
    assert callable(run.atlas_bench().tables)


def test_underactuated_c_atlas_batch_equals_the_numpy_path():
    """The generated C's atlas_home_batch (IK, the derived loop Jacobians' 1/kappa_F, conditioning, the home
    working mode's Phi range and FK counts in one C loop) against ik_batch / fk_batch and numpy."""
    mech = mechanism("underactuated_wrist")
    m = mech.module
    if m.BACKEND != "c":
        pytest.skip("the C extension is not built (WRISTKIN_BACKEND=numpy)")
    from wristkin_atlas import sampling

    rng = case_rng(2406)
    opts = Options(threshold=0.3, tilt_max=1.2)
    checked = 0
    for _ in range(10):
        d = mech.make_design(np.radians([rng.uniform(45, 75), rng.uniform(45, 75), rng.uniform(20, 40),
                                         rng.uniform(35, 55)]))
        if d is None:
            continue
        up, uj = (sampling.unit_block(TEST_SEED, s, 0, 1024, 3, False) for s in (0, 1))
        got = mech.evaluate(d, up, uj, opts)
        want = mech.evaluate_numpy(d, mech.poses(up, opts), mech.joints(uj, d), mech.home_mode(d), opts)
        assert got.keys() == want.keys()
        for k in want:
            if k in ("li_sum", "li_best_sum"):  # fixed point: two derivations of the same J, a rounding apart
                assert abs(int(got[k]) - int(want[k])) <= 4 * max(1, got["n_sets"]), k
            elif k == "li_min":  # 1/kappa's absolute error is ~eps (relative eps kappa): an absolute bound
                assert got[k] == pytest.approx(want[k], rel=0.0, abs=1e-12), k
            elif k in ("phi_lo", "phi_hi"):  # the same IK values; a set with g_i within rounding of 0 could flip
                np.testing.assert_allclose(got[k], want[k], atol=1e-9, err_msg=k)
            else:
                np.testing.assert_array_equal(got[k], want[k], err_msg=k)
        checked += 1
    assert checked >= 5
