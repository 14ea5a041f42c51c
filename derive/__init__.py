"""wristkin derivation pipeline: mechanism -> verified SymPy derivation -> generated solvers."""

__version__ = "0.1.0"
