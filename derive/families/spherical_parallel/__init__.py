"""Spherical parallel wrists (seed 000: the underactuated 3-RRR wrist with 2 motors and a sensed passive
branch): the derivation (spherical trigonometry, IK coefficients, the degree-8 FK eliminant), its audit numbers
and CasADi functions. Templates: templates/{python,c}/underactuated_wrist.*.jinja."""

from . import underactuated_wrist

MECHANISMS = {underactuated_wrist.NAME: underactuated_wrist}
