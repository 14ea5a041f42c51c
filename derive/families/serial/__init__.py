"""Serial chains from DH tables (seed 001's wrists and arms, the PUMA-560): chain products, Jacobians, staged
closed-form IK, audit numbers and CasADi functions. Templates: templates/{python,c}/serial.*.jinja."""

from . import dh_robots

MECHANISMS = dict(dh_robots.MECHANISMS)
