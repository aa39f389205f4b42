"""femcheck: cross-check fast rolling-bearing contact models against finite-element references.

Python API::

    import femcheck
    res = femcheck.run("hertz-line", {"load.per_length": 2e6}, models=["analytic", "bem"])
    res.models["bem"].quantities["p_max"]      # Pa
"""
from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("femcheck")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0+unknown"


def run(scene, overrides=None, models=None, **kwargs):
    """Run a scene (built-in name or TOML path) with dotted-key ``overrides``; see :func:`femcheck.runner.run`."""
    from .runner import run as _run

    return _run(scene, overrides=overrides, models=models, **kwargs)


__all__ = ["run", "__version__"]
