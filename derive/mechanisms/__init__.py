"""Explicit registry of mechanisms: name -> module with derive(), kernels(dv) and render metadata."""

from . import underactuated_wrist

REGISTRY = {
    underactuated_wrist.NAME: underactuated_wrist,
}
