"""Initial gaps h(x, y) (m) between two surfaces, x = rolling direction, y = roller axis.

Every profile is a plain function returning a callable ``gap(X, Y)`` on arrays. Where there is no surface to
touch (beyond a roller's ends) the gap is +inf; contact solvers treat such cells as excluded.
"""
from .profiles import height_map, paraboloid, roller, sphere

__all__ = ["height_map", "paraboloid", "roller", "sphere"]
