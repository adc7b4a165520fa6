"""Shared settings: hypothesis runs deterministically (a fixed seed via derandomize) and briefly."""

from hypothesis import settings

settings.register_profile("shadowlab", derandomize=True, max_examples=200, deadline=None)
settings.load_profile("shadowlab")
