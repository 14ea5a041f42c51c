"""Description files as their makers ship them, from packages on PyPI (the dev extra installs them): pybullet's
data package (pybullet_data) and the Robotics Toolbox's data package (rtbdata: ROS-Industrial description packages
with their xacro macros). Nothing here is simplified for the test: transmissions, <gazebo> blocks, mimic gripper
fingers, package:// meshes, xacro arguments and $(find) includes are read as they are.

Each derived solver is checked against the independent reference (tests/reference/chain.py: its own URDF reader on
the file, or on the URDF the xacro package expands, with the test naming the packages' folders itself): FK to
1e-12 x the robot's size (the same rigid motions multiplied in another order), IK sets reproduce the pose to
IK_VERIFY_TOL and contain the generating joints to 1e-7 rad (poses drawn with sigma_min / sigma_max > 1e-3, so
rounding moves the joints by at most ~1e-16 / 1e-3)."""

from __future__ import annotations

import importlib.util
import math
import subprocess
import sys
import warnings
from pathlib import Path

import derived_cache
import numpy as np
import pytest
from reference import chain as ref
from seeding import case_rng

from derive import own_robot
from derive.families.chain import urdf as reader

ROOT = Path(__file__).resolve().parent.parent


def _data(package: str) -> Path:
    spec = importlib.util.find_spec(package)
    if spec is None or not spec.submodule_search_locations:
        pytest.fail(f"the corpus package {package} is not installed (it is in the dev extra: make venv)")
    return Path(next(iter(spec.submodule_search_locations)))


def pybullet(rel: str) -> Path:
    return _data("pybullet_data") / rel


def rtb(rel: str) -> Path:
    return _data("rtbdata") / "xacro" / rel


KUKA = "kuka_description"
# id -> (file, derive options, the packages of its $(find) as the test knows them, xacro args, a shipped URDF twin)
CORPUS = {
    "pybullet_panda": (lambda: pybullet("franka_panda/panda.urdf"), {"tip": "panda_hand", "free": "panda_joint7"},
                       {}, {}, None),
    "pybullet_iiwa": (lambda: pybullet("kuka_iiwa/model.urdf"), {"free": "lbr_iiwa_joint_3"}, {}, {}, None),
    "rtb_puma560": (lambda: rtb("unimation_puma560_description/urdf/puma560_robot.urdf"), {}, {}, {}, None),
    "rtb_kr120": (lambda: rtb(f"{KUKA}/kuka_kr120/urdf/kr120r2500pro.urdf"), {"tip": "tool0"}, {}, {}, None),
    "rtb_kr16_xacro": (lambda: rtb(f"{KUKA}/kuka_kr16/urdf/kr16_2.xacro"), {"tip": "tool0"},
                       {"kuka_kr16_support": lambda: rtb(f"{KUKA}/kuka_kr16")}, {},
                       lambda: rtb(f"{KUKA}/kuka_kr16/urdf/kr16_2.urdf")),
    "rtb_iiwa_xacro": (lambda: rtb(f"{KUKA}/kuka_lbr_iiwa/urdf/lbr_iiwa_14_r820.xacro"),
                       {"tip": "tool0", "free": "joint_a1"},  # its a1/a2 axes are 0.44 mm apart
                       {"kuka_lbr_iiwa_support": lambda: rtb(f"{KUKA}/kuka_lbr_iiwa")}, {},
                       lambda: rtb(f"{KUKA}/kuka_lbr_iiwa/urdf/lbr_iiwa_14_r820.urdf")),
    "rtb_panda_xacro": (lambda: rtb("qut_frankie_description/robots/panda_arm_hand.urdf.xacro"),
                        {"tip": "panda_hand", "free": "panda_joint4"},
                        {"qut_frankie_description": lambda: rtb("qut_frankie_description")}, {}, None),
    "rtb_px100_xacro": (lambda: rtb("trossen_descriptions/urdf/px100.urdf.xacro"), {"tip": "px100/ee_arm_link"},
                        {}, {"robot_name": "px100"}, None),
    "rtb_vx300s_xacro": (lambda: rtb("trossen_descriptions/urdf/vx300s.urdf.xacro"), {"tip": "vx300s/ee_arm_link"},
                         {}, {"robot_name": "vx300s"}, None),
}
# the reference's base and tip links, read off the files by hand (derive is given only the tip where a tree has several
# end links: its default base, the tree's root, must be these too)
REFERENCE_LINKS = {
    "pybullet_panda": ("panda_link0", "panda_hand"), "pybullet_iiwa": ("lbr_iiwa_link_0", "lbr_iiwa_link_7"),
    "rtb_puma560": ("link1", "link7"), "rtb_kr120": ("base_link", "tool0"), "rtb_kr16_xacro": ("base_link", "tool0"),
    "rtb_iiwa_xacro": ("base_link", "tool0"), "rtb_panda_xacro": ("panda_link0", "panda_hand"),
    "rtb_px100_xacro": ("px100/base_link", "px100/ee_arm_link"),
    "rtb_vx300s_xacro": ("vx300s/base_link", "vx300s/ee_arm_link"),
}
_SOLVERS: dict = {}


def _expanded_by_xacro(file: Path, packages: dict, args: dict, tmp: Path) -> Path:
    """The URDF the xacro package itself expands (with $(find) answered from the test's own table)."""
    import xacro
    from xacro import substitution_args

    saved = substitution_args._eval_find, substitution_args._eval_dict["find"]
    substitution_args._eval_find = substitution_args._eval_dict["find"] = lambda pkg: str(packages[pkg]())
    try:
        text = xacro.process_file(str(file), mappings=dict(args)).toxml()
    finally:
        substitution_args._eval_find, substitution_args._eval_dict["find"] = saved
    out = tmp / (file.name.replace(".xacro", "") + ".expanded.urdf")
    out.write_text(text, encoding="utf-8")
    return out


def corpus_solver(key: str, tmp_path_factory):
    if key not in _SOLVERS:
        file, options, packages, args, twin = CORPUS[key]
        file = file()
        tmp = tmp_path_factory.mktemp(key)
        # the reader is given the packages that its own search would not find (kuka's *_support names)
        given = {k: str(v()) for k, v in packages.items() if "support" in k}
        derived_cache.derive(file, tmp / "out", name=key, native=key.startswith("pybullet"),
                         xacro_args=args, packages=given, **options)
        solver = own_robot.import_solver(tmp / "out", key)
        urdf = twin() if twin else file if file.suffix == ".urdf" else _expanded_by_xacro(file, packages, args, tmp)
        _SOLVERS[key] = (solver, ref.urdf_fk(urdf, *REFERENCE_LINKS[key]))
    return _SOLVERS[key]


def _design(m, q):
    return [q[m._FREE]] if m._FREE >= 0 or m._ARM_ANGLE else None


def _gap(a, b, kinds) -> float:
    return max((abs(math.remainder(x - y, 2 * math.pi)) if k == "R" else abs(x - y)) for x, y, k in
               zip(a, b, kinds, strict=True))


@pytest.mark.parametrize("key", sorted(CORPUS))
def test_shipped_description_derives_and_matches_the_reference(key, tmp_path_factory):
    m, r = corpus_solver(key, tmp_path_factory)
    size = max(1.0, float(m.SCALE))
    rng = case_rng(91)
    checked = 0
    while checked < 12:
        q = np.array([rng.uniform(max(lo, -math.pi), min(hi, math.pi)) for lo, hi in r.limits])
        d = _design(m, q)
        T = m.fk_matrix(q, d)
        # the module's FK is the description's to its DESCRIPTION_TOL (rounding, plus a rounded file's difference
        # from the exact geometry derived stages solve: the ROS-Industrial PUMA's 8-decimal angles, 6e-10); rtol
        # 1e-7 for a twin file's own rounding (the KR 16's URDF is 4.9e-12 off its xacro)
        np.testing.assert_allclose(T, r(q), atol=max(1e-12 * size, m.DESCRIPTION_TOL))
        s = np.linalg.svd(m.jacobian(q, d), compute_uv=False)
        if m.N_JOINTS - (1 if m._FREE >= 0 else 0) == 6 and s[-1] / s[0] < 1e-3:
            continue  # near a singularity the joints are determined only to rounding / sigma_min
        sol = m.ik(T, d)
        assert sol.count > 0, (key, sol.reason)
        assert min(_gap(v, q, m.JOINT_KINDS) for v in sol) < 1e-7, key
        for v in sol:
            assert np.max(np.abs(m.fk_matrix(v, d) - T)) <= m.IK_VERIFY_TOL
        checked += 1


# --------------------------------------------------------------------------------------------- the reader
def _top_level_joints(path: Path) -> list[tuple[str, str]]:
    import xml.etree.ElementTree as ET

    return [(j.get("name"), j.get("type")) for j in ET.parse(path).getroot().findall("joint")]


@pytest.mark.parametrize("rel", ["xarm/xarm6_with_gripper.urdf", "xarm/xarm6_robot.urdf", "franka_panda/panda.urdf",
                                 "kuka_iiwa/model.urdf"])
def test_only_top_level_joints_are_read(rel):
    """<joint> elements inside <transmission> / <gazebo> are not joints (xarm6_with_gripper: 21 <joint> tags, 14
    joints)."""
    path = pybullet(rel)
    model = reader.load_model(path)
    assert sorted((j.name, j.type) for j in model.joints.values()) == sorted(_top_level_joints(path))
    if "gripper" in rel:
        assert path.read_text().count("<joint") > len(model.joints)


def test_a_mimic_finger_off_the_chain_is_ignored_and_on_the_chain_named_with_what_to_do():
    path = pybullet("franka_panda/panda.urdf")
    chain, info = reader.read(path, tip="panda_hand")
    assert chain.n == 7 and info["tip_link"] == "panda_hand"
    with pytest.raises(reader.URDFError) as err:
        reader.read(path, tip="panda_rightfinger")
    line = next(i for i, t in enumerate(path.read_text().splitlines(), 1) if 'name="panda_finger_joint2"' in t)
    text = str(err.value)
    assert f"{path}: line {line}: <joint name=\"panda_finger_joint2\">" in text
    assert "mimics joint 'panda_finger_joint1'" in text and "--tip panda_hand" in text


def test_errors_name_the_file_the_element_and_the_line(tmp_path):
    src = pybullet("kuka_iiwa/model.urdf").read_text()
    bad = src.replace('<axis xyz="0 0 1"/>', '<axis xyz="0 0 one"/>', 1)
    assert bad != src
    f = tmp_path / "iiwa_bad.urdf"
    f.write_text(bad)
    line = next(i for i, t in enumerate(bad.splitlines(), 1) if "0 0 one" in t)
    with pytest.raises(reader.URDFError, match=rf"iiwa_bad.urdf: line {line}: <axis>: xyz: expected 3 finite"):
        reader.read(f)
    f.write_text(src.replace("</robot>", "<joint name='x'></robot>"))
    with pytest.raises(reader.URDFError, match=r"iiwa_bad.urdf: line \d+: not well-formed XML"):
        reader.read(f)


def test_a_fixed_joint_with_a_zero_axis_is_folded_without_a_warning(tmp_path):
    src = (ROOT / "tests/robots/ur5e/ur5e.urdf").read_text()
    assert 'type="fixed"' in src
    f = tmp_path / "ur5e_zero_axis.urdf"
    f.write_text(src.replace('type="fixed">', 'type="fixed"><axis xyz="0 0 0"/>'))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        chain, _ = reader.read(f, "base_link", "tool0")
        again, _ = reader.read(ROOT / "tests/robots/ur5e/ur5e.urdf", "base_link", "tool0")
    np.testing.assert_array_equal(chain.axes, again.axes)


def test_xacro_arguments_and_packages(tmp_path):
    px = rtb("trossen_descriptions/urdf/px100.urdf.xacro")
    chain, info = reader.read(px, tip="px100/ee_arm_link", xacro_args={"robot_name": "px100"})
    assert info["base_link"] == "px100/base_link" and chain.n == 4
    kr6 = rtb(f"{KUKA}/kuka_kr6/urdf/kr6r700sixx.xacro")
    with pytest.raises(reader.URDFError, match=r"\$\(find kuka_kr6_support\).*--package kuka_kr6_support=DIR"):
        reader.read(kr6, tip="tool0")
    chain, _ = reader.read(kr6, tip="tool0", packages={"kuka_kr6_support": rtb(f"{KUKA}/kuka_kr6")})
    assert chain.n == 6
    with pytest.raises(reader.URDFError, match="is for .xacro files"):
        reader.read(pybullet("kuka_iiwa/model.urdf"), xacro_args={"a": "1"})


def _cli(*args, cwd=ROOT):
    return subprocess.run([sys.executable, "-m", "derive.cli", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=300)


def test_cli_names_options_and_the_free_joints_that_work(tmp_path):
    panda = pybullet("franka_panda/panda.urdf")
    # no --free: the cheapest choice (a decomposition before the general 6R elimination), said with the others
    r = _cli("derive", panda, "--tip", "panda_hand", "--out", tmp_path / "p", "--no-native")
    assert r.returncode == 0 and "Traceback" not in r.stderr, r.stderr
    text = " ".join((tmp_path / "p" / "python" / "panda.py").read_text().split())
    assert "free joint panda_joint4 chosen (no --free given)" in text
    others = "the other choices that work: panda_joint5, panda_joint6, panda_joint7, panda_joint1"
    assert others in text.replace("' '", "")
    # a joint the planner refuses to hold (no decomposition is left): the general 6R solves the rest
    r = _cli("derive", panda, "--tip", "panda_hand", "--free", "panda_joint1", "--out", tmp_path / "q",
             "--no-native")
    assert r.returncode == 0, r.stderr
    held1 = own_robot.import_solver(tmp_path / "q", "panda", backend="numpy")
    assert "general 6R by elimination" in held1.DECOMPOSITION
    r = _cli("derive", rtb(f"{KUKA}/kuka_kr6/urdf/kr6r900sixx.xacro"), "--tip", "tool0", "--package",
             f"kuka_kr6_support={rtb(f'{KUKA}/kuka_kr6')}", "--out", tmp_path / "k", "--no-native")
    assert r.returncode == 0, r.stderr
    r = _cli("derive", rtb("trossen_descriptions/urdf/px100.urdf.xacro"), "--xacro-arg", "robot_name=px100",
             "--tip", "px100/ee_arm_link", "--out", tmp_path / "x", "--no-native")
    assert r.returncode == 0, r.stderr
    r = _cli("derive", panda, "--xacro-arg", "novalue", "--out", tmp_path / "p")
    assert r.returncode == 2 and "--xacro-arg 'novalue': expected NAME=VALUE" in r.stderr


def test_a_derivation_check_that_fails_is_a_one_line_refusal(monkeypatch, capsys, tmp_path):
    """A robot whose derivation fails a check (the Panda with joint6 held once failed the elimination's audit) is
    refused in one line naming the step, exit 1, no traceback: it was an AssertionError's traceback."""
    from derive import cli, own_robot
    from derive.model import CheckFailed

    def fail(*_args, **_kwargs):
        raise CheckFailed("derivation step 'g6_solutions' failed its checks: ['no pose of 16 where ...']")
    monkeypatch.setattr(own_robot, "derive", fail)
    src = Path(__file__).parent / "robots" / "panda" / "panda_dh.toml"
    assert cli.main(["derive", str(src), "--out", str(tmp_path)]) == cli.EXIT_FAILED
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "refused" in err and "g6_solutions" in err and "Traceback" not in err
