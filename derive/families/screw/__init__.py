"""Serial chains as finite-screw products (seed 003's 3T2R robots): the screw triangle product, its checks
against products of 4x4 transforms, the seed's numbers, and the staged IK; rendered through the serial family's
templates."""

from . import screw_robots

MECHANISMS = dict(screw_robots.MECHANISMS)
