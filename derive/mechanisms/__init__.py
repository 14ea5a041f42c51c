"""Explicit registry of mechanisms: name -> object with derive(), kernels(dv) and render metadata."""

from . import dh_robots, screw_robots, underactuated_wrist

REGISTRY = {
    underactuated_wrist.NAME: underactuated_wrist,
    **dh_robots.MECHANISMS,
    **screw_robots.MECHANISMS,
}
