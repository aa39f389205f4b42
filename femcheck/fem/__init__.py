"""Finite-element reference models (Gmsh meshes, scikit-fem assembly, own contact algorithms)."""
