"""The shared kinematics layer of every serial-arm robot (the catalogue's DH and finite-screw chains and a user's
URDF / DH / POE robot alike): the product-of-exponentials form and its one numeric Rodrigues / twist exponential
(poe.py), line geometry (geometry.py), the geometric planner that finds an IK decomposition from the axes
(planner.py) and the SymPy proofs of the subproblem formulas the solvers evaluate (subproblems.py). It names no
family; families import it, never each other's copies."""
