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
    """Node-to-surface contact, penalty enforced: pressure p = ``stiffness`` * overclosure (Pa/m); ``tension``
    (Pa) the small tension CalculiX keeps at large clearance (its linear law's sigma_inf). ``friction``: Coulomb
    coefficient mu (0: frictionless); ``stick_slope`` (Pa/m): CalculiX's tangential penalty lambda (shear
    traction per unit elastic slip before sliding). ``name``: the surface interaction's name."""

    slave: str
    master: str
    stiffness: float
    tension: float
    friction: float = 0.0
    stick_slope: float = 0.0
    name: str = "SI"

    @property
    def formulation(self) -> str:
        law = "frictionless" if self.friction == 0.0 else \
            f"Coulomb friction mu = {self.friction:g} (stick slope {self.stick_slope:.4g} Pa/m)"
        return f"node-to-surface {self.slave} on {self.master}, penalty (linear pressure-overclosure), {law}"


@dataclass
class RigidIndenter:
    """A rigid body driven by reference node ``ref`` (0-based column) and, for CalculiX, rotation node ``rot``
    (rotations held: the deck fixes them); ``dof`` the loaded translational dof (3 in 3D, 2 in 2D). Its nodes
    are ``nset``: the elements ``elset`` of a meshed rigid indenter, or (``elset`` None) nodes of a deformable
    body's face made rigid (Abaqus ``TIE NSET``). Node sets ``NREF<name>`` / ``NROT<name>`` hold ref / rot."""

    nset: str
    elset: str | None
    ref: int
    rot: int
    dof: int
    name: str = ""

    @property
    def ref_set(self) -> str:
        return f"NREF{self.name}"

    @property
    def rot_set(self) -> str:
        return f"NROT{self.name}"


@dataclass
class Spring:
    """A linear spring (SPRING2) of ``stiffness`` (N/m) between dof ``dof`` of node columns ``a`` and ``b``."""

    a: int
    b: int
    dof: int
    stiffness: float
    elset: str


@dataclass
class Step:
    """One static step under the deck's fixed conditions: ``displacements`` (node column, dof, value m)
    prescribed, ``loads`` (node column, dof, value N) concentrated forces (``full``: applied at full value from
    the step's start, else ramped over the step), ``new`` drops the previous step's prescribed displacements
    (OP=NEW), ``increment`` the first increment (fraction of the step), ``comment`` one line, ``remove`` element
    sets taken out of the model at the step's start (``*MODEL CHANGE, TYPE=ELEMENT, REMOVE``), ``grow_below``
    (optional) the Newton iteration count of two consecutive increments below which the increment grows (the
    time-incrementation control I_G, default 4 in both codes)."""

    comment: str
    displacements: list[tuple[int, int, float]] = field(default_factory=list)
    loads: list[tuple[int, int, float]] = field(default_factory=list)
    full: bool = True
    new: bool = False
    increment: float = 1.0
    max_increments: int = 200
    remove: list[str] = field(default_factory=list)
    grow_below: int | None = None


@dataclass
class Deck:
    """Everything an Abaqus/CalculiX deck of a contact scene holds. ``push`` (m): the indenter's prescribed
    displacement in step 1 (establishes contact, so that step 2 starts from a non-singular state); ``force``
    (N): the load of step 2 on the reference node (the scene's load on the modelled part); ``info``: what the
    writer puts in the heading and the caller reports. ``contacts``, ``rigid`` and ``steps`` add further contact
    pairs, rigid bodies and replace the two default steps (push, then load) when given; ``prints`` the
    ``.dat`` tables (node set, variable, totals only); ``notes`` extra heading lines; ``equations`` linear
    constraints sum c_i u(node_i, dof_i) = 0, each a list of (node column, dof, c), the first term eliminated;
    ``springs`` linear springs between two nodes' dofs."""

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
    contacts: list[Contact] = field(default_factory=list)
    rigid: list[RigidIndenter] = field(default_factory=list)
    steps: list[Step] = field(default_factory=list)
    prints: list[tuple[str, str, bool]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    equations: list[list[tuple[int, int, float]]] = field(default_factory=list)
    springs: list[Spring] = field(default_factory=list)

    @property
    def n_nodes(self) -> int:
        return self.points.shape[1]

    @property
    def last_element_id(self) -> int:
        return max(int(b.ids[-1]) for b in self.blocks)

    @property
    def all_contacts(self) -> list[Contact]:
        return [self.contact, *self.contacts]

    @property
    def all_rigid(self) -> list[RigidIndenter]:
        return [self.indenter, *self.rigid]

    def load_steps(self) -> list[Step]:
        """The steps: ``steps`` when given, else push (step 1) and the load at full value (step 2)."""
        if self.steps:
            return self.steps
        ri = self.indenter
        return [Step("step 1: push the indenter by the prescribed approach", [(ri.ref, ri.dof, -self.push)],
                     increment=0.5),
                Step("step 2: release the push, the scene's load at full value (load control)",
                     loads=[(ri.ref, ri.dof, -self.force)], new=True)]

    def dat_prints(self) -> list[tuple[str, str, bool]]:
        return self.prints or [(self.indenter.ref_set, "U", False), ("NBOTTOM", "RF", True)]
