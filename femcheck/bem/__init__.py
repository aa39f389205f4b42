"""Boundary-integral (half-space / half-plane) contact models."""
