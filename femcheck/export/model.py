"""The format-neutral content of an exported deck: what the scene builder decides and the writer spells.

Node and element numbers in the deck are 1-based: node ``i`` of ``Deck.points`` (column) is deck node i + 1;
element ids are numbered block after block. Units SI (m, N, Pa).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class ElementBlock:
    """Elements of one type in one element set: ``cells`` (k, M) 0-based node columns; ``first_id`` the deck id
    of the first element; ``material`` the name of its section's material."""

    type: str
    cells: np.ndarray
    elset: str
    material: str
    first_id: int = 1

    @property
    def ids(self) -> np.ndarray:
        return self.first_id + np.arange(self.cells.shape[1])


@dataclass
class Surface:
    """An element-face surface: (element ids, face numbers 1..) pairs."""

    name: str
    elements: np.ndarray
    faces: np.ndarray


@dataclass
class Fixed:
    """Homogeneous boundary condition: the degrees of freedom ``dofs`` (1-based) of node set ``nset`` are 0."""

    nset: str
    dofs: tuple[int, ...]


@dataclass
class Contact:
    """Frictionless node-to-surface contact, penalty enforced: pressure p = ``stiffness`` * overclosure (Pa/m);
    ``tension`` (Pa) the small tension CalculiX keeps at large clearance (its linear law's sigma_inf)."""

    slave: str
    master: str
    stiffness: float
    tension: float
    formulation: str = "node-to-surface, penalty (linear pressure-overclosure), frictionless"


@dataclass
class RigidIndenter:
    """The indenter's elements form one rigid body driven by reference node ``ref`` (0-based column) and, for
    CalculiX, rotation node ``rot``; ``dof`` the loaded translational dof (3 in 3D, 2 in 2D)."""

    nset: str
    elset: str
    ref: int
    rot: int
    dof: int


@dataclass
class Deck:
    """Everything an Abaqus/CalculiX deck of a contact scene holds. ``push`` (m): the indenter's prescribed
    displacement in step 1 (establishes contact, so that step 2 starts from a non-singular state); ``force``
    (N): the load of step 2 on the reference node (the scene's load on the modelled part); ``contact_dof``: the
    normal direction (3 or 2); ``info``: what the writer puts in the heading and the caller reports."""

    title: str
    dim: int
    points: np.ndarray
    blocks: list[ElementBlock]
    nsets: dict[str, np.ndarray]
    surfaces: list[Surface]
    materials: dict[str, tuple[float, float]]
    fixed: list[Fixed]
    contact: Contact
    indenter: RigidIndenter
    push: float
    force: float
    info: dict = field(default_factory=dict)

    @property
    def n_nodes(self) -> int:
        return self.points.shape[1]
