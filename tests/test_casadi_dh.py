"""CasADi functions of the DH chains (generated/casadi/<chain>.casadi) vs the independent reference."""

from __future__ import annotations

import importlib
import math
from pathlib import Path

import numpy as np
import pytest
from reference import dh as ref
from seeding import case_rng

from derive.casadi_export import load_casadi

ROOT = Path(__file__).resolve().parent.parent
CHAINS = ["puma560", "rpp_wrist", "scara_wrist", "spherical_wrist", "wrist_1dof"]


@pytest.mark.parametrize("name", CHAINS)
def test_casadi_fk_and_jacobian_match_reference(name):
    fns = load_casadi(ROOT / "generated" / "casadi" / f"{name}.casadi")
    p = np.array(importlib.import_module(f"wristkin.{name}").DESIGN_DEFAULT)
    kinds = [r[4] for r in ref.MECHANISMS[name]["rows"]]
    rng = case_rng(9)
    for _ in range(20):
        q = np.array([rng.uniform(-math.pi, math.pi) if k == "R" else rng.uniform(-0.5, 0.5) for k in kinds])
        T = np.array(fns[f"{name}_fk"](q, p))
        J = np.array(fns[f"{name}_jacobian"](q, p))
        np.testing.assert_allclose(T, ref.fk(name, q)[:3], atol=1e-12)
        np.testing.assert_allclose(J, ref.geometric_jacobian(name, q), atol=1e-12)
        # CasADi's own AD of the position equals the linear rows of the derived geometric Jacobian
        np.testing.assert_allclose(np.array(fns[f"{name}_position_jacobian_ad"](q, p)), J[:3], atol=1e-12)
