"""Explicit registry of mechanisms: name -> object with derive(), kernels(dv) and render metadata."""

from . import dh_robots, rsr_wrist, scara_rsr, screw_robots, underactuated_wrist

REGISTRY = {
    underactuated_wrist.NAME: underactuated_wrist,
    **dh_robots.MECHANISMS,
    rsr_wrist.NAME: rsr_wrist,
    scara_rsr.NAME: scara_rsr,
    **screw_robots.MECHANISMS,
}
