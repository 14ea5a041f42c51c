"""Reusable first-principles steps shared by mechanisms."""
