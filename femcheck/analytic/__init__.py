"""Closed-form contact solutions."""
