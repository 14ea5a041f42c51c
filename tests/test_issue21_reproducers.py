"""The reproducers of issue 21 (a user's fuzzing of the catalogue mechanisms), each in Python and C: angles wrapped
against 2 pi itself, IK sets bounded by what FK accepts, the SCARA elbow at long strokes, the folded scara_rsr family
once. (test_reproducers.py holds the earlier issue's; test_fuzz*.py the generic invariants.)"""

from __future__ import annotations

import importlib
import math
import random
import re
from pathlib import Path

import mpmath
import numpy as np
import pytest
import wristkin
from c_solvers import RsrC, RuntimeC, SerialC
from wristkin import _runtime

ROOT = Path(__file__).resolve().parent.parent
WK_ERR_RANGE = -4
STATUS_UNREACHABLE = 1


def serial(name):
    mod = importlib.import_module(f"wristkin.{name}")
    return mod, SerialC(name, mod.N_JOINTS, mod.MAX_IK, len(mod.DESIGN_NAMES))


def reduced(q: float) -> float:
    """q - 2 pi k in [-pi, pi], k the nearest integer, to 2400 bits (a double's reduced angle is at least 4.7e-19,
    and q has up to 1024 integer bits), rounded once to a double."""
    with mpmath.workprec(2400):
        x, two_pi = mpmath.mpf(q), 2 * mpmath.pi
        return float(x - mpmath.nint(x / two_pi) * two_pi)


def _hard_angles():
    """The issue's values, multiples 2^k pi (2^k pi / 2 pi is a power of two: the reduced angle is the rounding of
    the double alone), the double nearest a multiple of pi / 2 (6381956970095103 x 2^797), the ends of the range,
    each boundary of the runtimes' cases (pi, 3 pi) and random magnitudes over every exponent."""
    out = [1e9, 1e16, 1e300, 1.7976931348623157e308, 6381956970095103 * 2.0 ** 797, math.pi,
           math.nextafter(math.pi, 4.0), 2 * math.pi, 3 * math.pi, 9.4, math.nextafter(9.4, 10.0), 5e-324, 0.0]
    out += [2.0 ** k * math.pi for k in range(-3, 1023)]  # 2^1023 pi overflows
    rng = random.Random(21)
    out += [rng.uniform(1.0, 2.0) * 2.0 ** rng.randrange(-4, 1024) for _ in range(1500)]
    return out + [-v for v in out]


def test_wrap_is_the_correctly_reduced_angle_python_and_c():
    """_wrap (Python) and wk_wrap (C) give the correctly rounded reduced angle for every finite double (was:
    remainder(q, 6.283185307179586), |q| x 3.9e-17 off: 2e-8 rad at 1e9, every digit at 1e16; 2 pi itself gave
    0 instead of -2.45e-16); NaN and inf give NaN."""
    c = RuntimeC()
    angles = _hard_angles()
    want = [reduced(q) for q in angles]
    assert [_runtime._wrap(q) for q in angles] == want
    assert [c.wrap(q) for q in angles] == want
    assert list(_runtime._wrap_all(np.array(angles))) == want
    for bad in (math.inf, -math.inf, math.nan):
        assert math.isnan(_runtime._wrap(bad)) and math.isnan(c.wrap(bad))


@pytest.mark.parametrize("q", [1e9, 1e16, 1e300, 2.0 ** 60 * math.pi])
def test_wrist_1dof_fk_of_a_long_angle_is_libm_cos_python_and_c(q):
    """wrist_1dof.fk([1e16]) gave r00 = -0.8755 for cos(1e16) = -0.6262: the joint wrapped against fl(2 pi)."""
    mod, c = serial("wrist_1dof")
    for r00 in (mod.fk([q]).values[0][0], c.fk([q]).values[0][0]):
        assert abs(r00 - math.cos(q)) <= 4 * math.ulp(1.0)


def test_rsr_wrist_ik_of_a_long_azimuth_gives_sets_of_that_azimuth_python_and_c():
    """rsr_wrist.ik([1e16, 0.9, 0.05]) gave 8 sets whose FK had 4 different azimuths (the kernels add the legs' angles
    to alpha, 1e16 + 2 pi / 3 rounds): every set's FK now has the reduced azimuth."""
    mod, c = importlib.import_module("wristkin.rsr_wrist"), RsrC("rsr_wrist")
    alpha = reduced(1e16)
    py, cc = mod.ik([1e16, 0.9, 0.05]), c.ik([1e16, 0.9, 0.05])
    assert py.count == 8 and cc.count == 8 and np.array_equal(py.valid, cc.valid)
    for row in py.values[py.valid]:
        for f in (mod.fk(row).values[0], c.fk(row).values[0]):
            assert abs(f[0] - alpha) < 1e-9 and abs(f[1] - 0.9) < 1e-9 and abs(f[2] - 0.05) < 1e-9


def test_long_joint_angles_act_as_their_reduced_angle_everywhere():
    """scara_rsr FK, the underactuated wrist's motor angles and a serial chain's select with a long `previous` see
    the correctly reduced angle (each wrapped with remainder(q, fl(2 pi)) before)."""
    hy, hc = importlib.import_module("wristkin.scara_rsr"), RsrC("scara_rsr")
    q = np.array([1e16, 0.5, 0.05, 1e9, 0.4, 0.5, 0.6])
    qr = np.array([reduced(v) if k == "R" else v for v, k in zip(q, hy.JOINT_KINDS, strict=True)])
    want = hy.fk(qr).values[0]
    assert np.array_equal(hy.fk(q).values[0], want) and np.array_equal(hc.fk(q).values[0], want)
    uw = importlib.import_module("wristkin.underactuated_wrist")
    d = uw.make_design()
    m = uw.motor_angles([1e16, 1e300, 3.0])
    assert abs(m[0] - _runtime._wrap(reduced(1e16) - d.theta0)) <= 1e-15
    assert abs(m[1] - _runtime._wrap(reduced(1e300) - d.theta0)) <= 1e-15
    back = uw.joints_from_motor_angles([1e16, 0.0, 0.0])
    assert abs(back[0] - (reduced(1e16) + d.theta0) % (2 * math.pi)) <= 1e-15
    mod, c = serial("wrist_1dof")
    sol = mod.ik(mod.fk([2.0]).values[0])
    far = 2.0 + 2 * math.pi * 2 ** 40  # the double nearest; its reduced angle is 2.0 + 5.4e-5
    assert mod.select(sol, previous=[far]) == 0 and abs(reduced(far) - 2.0) > 1e-5


def test_rpp_wrist_ik_returns_no_stroke_fk_rejects_python_and_c():
    """rpp_wrist.ik of a pose 1e6 m out with the flange pointing back returned d3 = 1e6 + 0.1, which fk rejects
    (WK_ERR_RANGE): IK now drops such sets and says why; both languages unreachable."""
    mod, c = serial("rpp_wrist")
    t = np.eye(4)
    t[:3, :3] = [[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]
    t[:3, 3] = [1e6, 0.0, 0.0]
    py, cc = mod.ik(t), c.ik(t)
    assert py.status == STATUS_UNREACHABLE and py.count == 0 and "beyond LENGTH_MAX" in py.reason
    assert cc.rc == 0 and cc.status == STATUS_UNREACHABLE and cc.count == 0
    with pytest.raises(mod.InvalidInput):
        mod.fk([0.0, 0.0, 1e6 + 0.1, 0.0, 0.0, 0.0])
    assert c.fk([0.0, 0.0, 1e6 + 0.1, 0.0, 0.0, 0.0]).rc == WK_ERR_RANGE
    t[:3, 3] = [1e6 - 1.0, 0.0, 0.0]  # inside: the sets are found and fk takes them
    py, cc = mod.ik(t), c.ik(t)
    assert py.count >= 1 and cc.count == py.count
    for row in py.values[py.valid]:
        assert c.fk(row).rc == 0 and mod.fk(row).count == 1


@pytest.mark.parametrize("pz", [1e308, -1e308, 2e6, -2e6])
def test_scara_rsr_ik_of_a_stroke_beyond_length_max_is_unreachable_python_and_c(pz):
    """scara_rsr.ik accepted pz = 1e308 and returned 16 sets with d3 = -1e308 (fk: WK_ERR_RANGE)."""
    hy, hc = importlib.import_module("wristkin.scara_rsr"), RsrC("scara_rsr")
    pose = hy.fk([0.3, 1.0, 0.05, 0.2, 0.4, 0.5, 0.6]).values[0].copy()
    pose[11] = pz
    py, cc = hy.ik(pose), hc.ik(pose)
    assert py.status == STATUS_UNREACHABLE and py.count == 0 and "beyond LENGTH_MAX" in py.reason
    assert cc.rc == 0 and cc.status == STATUS_UNREACHABLE and cc.count == 0


@pytest.mark.parametrize("stroke", [6.5e5, -6.5e5, 1e5, 9.9e5])
def test_scara_wrist_keeps_the_elbow_at_long_strokes_python_and_c(stroke):
    """scara_wrist with a1 = 1e-4: ik(fk(q)) at d3 = 6.5e5 was unreachable (the distance stage's C held
    -d3^2 / 2 + (pz - d4 r22)^2 / 2, whose rounding, 1e-4 m^2, swallowed a1 a2 = 3e-5); both elbows now, the
    generating set among them."""
    mod, c = serial("scara_wrist")
    params = [1e-4, 0.3, 0.1]
    d = mod.make_design(params)
    _, cd = c.design(params)
    q = np.array([0.3, -1.78, stroke, 0.2])
    t = mod.fk(q, d).values[0]
    py, cc = mod.ik(t, d), c.ik(t, cd)
    assert py.count == 2 and cc.count == 2 and np.array_equal(py.valid, cc.valid)
    assert min(float(np.max(np.abs(np.array([_runtime._wrap(x) for x in v - q])))) for v in py) < 1e-6


def test_scara_rsr_folded_on_axis_1_returns_the_family_once_python_and_c():
    """L1 = L2 (the default) and theta2 = pi put the flange on axis 1: theta1 is free and theta2 = +pi and -pi are
    one angle; IK returned the family twice (16 rows, theta1 + theta4 equal). Now 8 rows (one per wrist leg word),
    each flagged indeterminate, C and Python set for set."""
    hy, hc = importlib.import_module("wristkin.scara_rsr"), RsrC("scara_rsr")
    q = [0.3, math.pi, 0.05, 0.2, 0.4, 0.5, 0.6]
    pose = hy.fk(q).values[0]
    py, cc = hy.ik(pose), hc.ik(pose)
    assert py.count == 8 and cc.count == 8 and np.array_equal(py.valid, cc.valid)
    assert np.all(py.flags[py.valid] & hy.FLAG_INDETERMINATE) and np.array_equal(py.flags, cc.flags)
    sums = {round(_runtime._wrap(v[0] + v[3]), 9) for v in py}
    assert sums == {round(_runtime._wrap(q[0] + q[3]), 9)}


LIMIT = re.compile(r"[A-Z][A-Z0-9_]*(_MAX|_MIN|_MARGIN)|ROTATION_TOL")


def _spellings(v) -> set[str]:
    """How a limit's value may be written: 1e6, 1e-3, 1e+06, 0.001, 1000000.0."""
    short = f"{v:.0e}".replace("e+0", "e").replace("e-0", "e-").replace("e+", "e")
    return {short, f"{v:g}", repr(float(v))}


def _api_sections() -> dict[str, str]:
    """docs/API.md's '###' sections by the mechanisms their heading names."""
    text = (ROOT / "docs" / "API.md").read_text()
    out = {}
    for part in text.split("\n### ")[1:]:
        heading = part.splitlines()[0]
        for name in wristkin.MECHANISMS:
            if name in heading:
                out[name] = part
    return out


@pytest.mark.parametrize("name", sorted(wristkin.MECHANISMS))
def test_every_limit_a_module_exports_is_in_api_md_and_its_c_header(name):
    """Issue 21 found limits enforced but written nowhere (scara_rsr's stroke, the wrist's RATE_MAX, the 3-RSR
    design rules): every limit constant of every catalogue module is in its docs/API.md section as `NAME` = value
    and in its C header's comment as NAME = value, with the module's value."""
    mod = importlib.import_module(f"wristkin.{name}")
    section = _api_sections()[name]
    header = (ROOT / "generated" / "c" / f"{name}.h").read_text()
    limits = [n for n in dir(mod) if LIMIT.fullmatch(n) and isinstance(getattr(mod, n), float)]
    assert limits, "a module without limit constants"
    for n in limits:
        spelled = _spellings(getattr(mod, n))
        assert any(f"`{n}` = {s}" in section for s in spelled), f"docs/API.md ({name}) does not state {n}"
        assert any(f"{n} = {s}" in header for s in spelled), f"{name}.h does not state {n}"


def test_scara_wrist_distance_stage_is_free_of_the_stroke():
    """The derivation's side of the elbow fix: the theta2 stage's coefficients no longer hold d3 (its square
    cancelled against the target's height in floating point); the stroke was substituted and cancelled in the
    algebra."""
    from derive.catalogue import registry

    spec = registry()["scara_wrist"].spec
    d3 = spec.joints[2]
    (stage,) = [st for st in spec.stages if st.kind == "trig_linear"]
    assert all(d3 not in sp_expr.free_symbols for sp_expr in stage.exprs)
