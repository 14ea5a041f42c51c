"""3-RSR (2R1T) symmetric parallel wrists and the SCARA + 3-RSR hybrid (seed 002): mirror-plane geometry, the
wrist's derivation, the hybrid built on it, audit numbers and CasADi functions. Templates:
templates/{python,c}/{rsr_wrist,scara_rsr}.*.jinja and the rsr_* partials."""

from . import rsr_wrist, scara_rsr

MECHANISMS = {rsr_wrist.NAME: rsr_wrist, scara_rsr.NAME: scara_rsr}
