"""The serial-arm layer shared by the serial families (derive/families/serial: DH chains; derive/families/screw:
finite-screw chains): stages and their kernels (stages.py), the templates' typed views (views.py), the mechanism
base (mechanism.py) and the CasADi functions (casadi_functions.py). Not a family: it names none, and families
share it instead of importing each other (tests/test_architecture.py)."""
