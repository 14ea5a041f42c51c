"""The underactuated wrist's rates: loop Jacobians, angular velocity and acceleration from joint rates and
back, and Euler-angle rates.

A wristkin runtime source: the underactuated wrist's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants and derived kernels; above the marker, what it reads from them
and from the other sources (uw_stand_in.py: the catalogue's wrist), so that it is linted and tested as it is
(tests/test_uw_runtime.py)."""

from __future__ import annotations

import math

import numpy as np
from uw_design import _design
from uw_orientation import rotation_from_pose
from uw_stand_in import (
    GIMBAL_EPS,
    RATE_MAX,
    SINGULAR_EPS,
    InvalidInput,
    WristkinError,
    _k_euler_rate_matrix,
    _k_jacobian_rates,
    _k_jacobians,
    _vector,
)


# wristkin: inlined from here
# ---------------------------------------------------------------------------- rates
def jacobians(joints, pose, design=None):
    """(jq (3,), jx (3, 3)) with jq * qdot = jx @ w (w = platform angular velocity, base frame)."""
    d = _design(design)
    q = _vector(joints, 3, "joints")
    rot = tuple(rotation_from_pose(pose).ravel())
    j = _k_jacobians(q, rot, d.constants)
    return np.array(j[:3]), np.array(j[3:]).reshape(3, 3)


def _rate(v, what):
    """A rate vector within RATE_MAX (rad/s or rad/s^2): products with the Jacobians stay finite."""
    r = _vector(v, 3, what)
    if not max(abs(x) for x in r) <= RATE_MAX:
        raise InvalidInput(f"{what}: rates must be within {RATE_MAX:g}, got {list(r)}")
    return np.asarray(r)


def _finite_result(x, what):
    if not np.all(np.isfinite(x)):
        raise WristkinError(f"{what}: result not finite (configuration too close to singular)")
    return x


def _solve3(m, rhs, what):
    if abs(np.linalg.det(m)) <= SINGULAR_EPS * max(1.0, float(np.max(np.abs(m)))) ** 3:
        raise WristkinError(f"{what}: configuration is singular")
    return np.linalg.solve(m, rhs)


def angular_velocity(joints, pose, qdot, design=None) -> np.ndarray:
    """w from joint rates: jx w = jq * qdot (fails at a direct singularity)."""
    jq, jx = jacobians(joints, pose, design)
    return _finite_result(_solve3(jx, jq * _rate(qdot, "qdot"), "angular_velocity (direct singularity)"),
                          "angular_velocity")


def joint_rates(joints, pose, w, design=None) -> np.ndarray:
    """qdot from w: qdot_i = (jx w)_i / jq_i (fails at an inverse singularity)."""
    jq, jx = jacobians(joints, pose, design)
    if np.min(np.abs(jq)) <= SINGULAR_EPS:
        raise WristkinError("joint_rates: configuration is at an inverse singularity")
    return _finite_result(jx @ _rate(w, "w") / jq, "joint_rates")


def _rates_terms(joints, pose, qdot, w, design):
    d = _design(design)
    q = _vector(joints, 3, "joints")
    rot = tuple(rotation_from_pose(pose).ravel())
    jr = _k_jacobian_rates(q, rot, _vector(qdot, 3, "qdot"), _vector(w, 3, "w"), d.constants)
    return np.array(jr[:3]), np.array(jr[3:]).reshape(3, 3)


def angular_acceleration(joints, pose, qdot, qddot, design=None) -> np.ndarray:
    """wdot from joint rates and accelerations: jx wdot = jq qddot + jqdot qdot - jxdot w."""
    jq, jx = jacobians(joints, pose, design)
    w = angular_velocity(joints, pose, qdot, design)
    jqd, jxd = _rates_terms(joints, pose, qdot, w, design)
    qd, qdd = _rate(qdot, "qdot"), _rate(qddot, "qddot")
    return _finite_result(_solve3(jx, jq * qdd + jqd * qd - jxd @ w, "angular_acceleration (direct singularity)"),
                          "angular_acceleration")


def joint_accelerations(joints, pose, w, wdot, design=None) -> np.ndarray:
    """qddot from w, wdot: jq qddot = jx wdot + jxdot w - jqdot qdot."""
    jq, jx = jacobians(joints, pose, design)
    qd = joint_rates(joints, pose, w, design)
    jqd, jxd = _rates_terms(joints, pose, qd, w, design)
    return _finite_result((jx @ _rate(wdot, "wdot") + jxd @ _rate(w, "w") - jqd * qd) / jq, "joint_accelerations")


def omega_from_euler_rates(pose, euler_rates) -> np.ndarray:
    e = np.array(_k_euler_rate_matrix(_vector(pose, 3, "pose")), dtype=float).reshape(3, 3)
    return _finite_result(e @ _rate(euler_rates, "euler_rates"), "omega_from_euler_rates")


def euler_rates(pose, w) -> np.ndarray:
    """(psidot, thetadot, phidot) from w; undefined where sin(theta) = 0 (raises)."""
    p = _vector(pose, 3, "pose")
    if abs(math.sin(p[1])) <= GIMBAL_EPS:
        raise WristkinError("euler_rates: sin(theta) = 0, Euler-angle rates are undefined (use w)")
    e = np.array(_k_euler_rate_matrix(p), dtype=float).reshape(3, 3)
    return _finite_result(np.linalg.solve(e, _rate(w, "w")), "euler_rates")
