"""Scenes: TOML files -> validated :class:`Scene` with typed, range-checked ``--set`` overrides.

A scene file has top-level ``name``, ``kind`` (the problem family, see :mod:`femcheck.problems`),
``description`` and ``tags`` (suites it belongs to), and sections whose keys are addressed with dots:
``geometry.radius``, ``materials.block.E``, ``tolerances.bem.p_max``. The problem kind declares which keys
exist, their type, unit and allowed range; anything else is refused with one line naming the key.
"""
from __future__ import annotations

import difflib
import math
import tomllib
from dataclasses import dataclass, field
from fnmatch import fnmatchcase
from pathlib import Path
from typing import Any

from .errors import InputError
from .materials import Elastic


@dataclass(frozen=True)
class Key:
    """Schema of one scene key: ``kind`` is float | int | bool | str | list | floats; ``lo``/``hi`` bound numbers
    (open bounds unless ``lo_closed``/``hi_closed``); ``choices`` restrict strings or list items."""

    kind: str
    unit: str = "-"
    doc: str = ""
    lo: float | None = None
    hi: float | None = None
    lo_closed: bool = False
    hi_closed: bool = False
    choices: tuple[str, ...] | None = None
    empty_ok: bool = False            # a list key that may be empty (models.contrast)

    def allowed(self) -> str:
        if self.choices is not None:
            return "one of " + ", ".join(self.choices) if self.kind != "list" else \
                "a comma-separated list of " + ", ".join(self.choices)
        if self.kind == "bool":
            return "true or false"
        kind = {"int": "integer", "float": "number", "str": "string"}.get(self.kind, self.kind)
        if self.lo is None and self.hi is None:
            return f"any {kind}"
        left = ("[" if self.lo_closed else "(") + ("-inf" if self.lo is None else f"{self.lo:g}")
        right = ("inf" if self.hi is None else f"{self.hi:g}") + ("]" if self.hi_closed else ")")
        return ("an integer in " if self.kind == "int" else "") + f"{left}, {right}" + \
            ("" if self.unit == "-" else f" {self.unit}")

    def coerce(self, name: str, value: Any) -> Any:
        """Convert (strings from --set included) and range-check; raise InputError naming ``name``."""
        bad = InputError(name, f"{value} is not allowed; allowed: {self.allowed()}")
        if self.kind == "bool":
            if isinstance(value, bool):
                return value
            if isinstance(value, str) and value.lower() in ("true", "false", "1", "0", "yes", "no"):
                return value.lower() in ("true", "1", "yes")
            raise bad
        if self.kind in ("float", "int"):
            if isinstance(value, bool):
                raise bad
            try:
                v = float(value) if self.kind == "float" else int(value)
            except (TypeError, ValueError):
                raise bad from None
            if self.kind == "int" and isinstance(value, float) and not value.is_integer():
                raise bad
            if not math.isfinite(v):
                raise bad
            if self.lo is not None and (v < self.lo or (v == self.lo and not self.lo_closed)):
                raise bad
            if self.hi is not None and (v > self.hi or (v == self.hi and not self.hi_closed)):
                raise bad
            return v
        if self.kind == "str":
            if not isinstance(value, str) or (self.choices and value not in self.choices):
                raise bad
            return value
        if self.kind == "floats":          # a list of numbers, each range-checked (e.g. a paper's table row)
            items = [s.strip() for s in value.split(",")] if isinstance(value, str) else value
            if not isinstance(items, list) or not items:
                raise bad
            return [Key("float", self.unit, lo=self.lo, hi=self.hi, lo_closed=self.lo_closed,
                        hi_closed=self.hi_closed).coerce(name, v) for v in items]
        if self.kind == "list":
            items = [s.strip() for s in value.split(",") if s.strip()] if isinstance(value, str) else value
            if not isinstance(items, list) or not (items or self.empty_ok) or \
                    not all(isinstance(i, str) and i for i in items):
                raise bad
            if self.choices and any(i not in self.choices for i in items):
                unknown = next(i for i in items if i not in self.choices)
                raise InputError(name, f"{unknown!r} is not allowed{did_you_mean(unknown, self.choices)}; "
                                       f"allowed: {self.allowed()}")
            return items
        raise TypeError(f"unknown key kind {self.kind}")


# Keys every problem kind shares. Materials: E > 0, -1 < nu < 0.5 (thermodynamic bounds; 0.5 itself is
# refused because the plane-strain stiffness and the FE Lame constant lambda are then infinite).
def fem_mesh_keys(levels_hi: int, h_contact_lo: float, h_contact_hi: float, h_max_hi: float, zone_doc: str,
                  zone_hi: float, block_unit: str, block_doc: str, block_lo: float, block_hi: float) -> dict[str, Key]:
    """The mesh-family keys shared by the 3D FE models (sizes of the coarsest level; each level divides them by
    ``numerics.fem_ratio``)."""
    return {
        "numerics.fem_levels": Key("int", "-", "FEM mesh levels (>= 3 for Richardson extrapolation)", lo=1,
                                   hi=levels_hi, lo_closed=True, hi_closed=True),
        "numerics.fem_ratio": Key("float", "-", "FEM refinement ratio between levels (2: halving; sqrt(2) gives "
                                  "three levels for the cost of two halvings)", lo=1.1, hi=2.0, lo_closed=True,
                                  hi_closed=True),
        "numerics.fem_h_contact": Key("float", "a_H", "FEM element size over the contact zone, coarsest level",
                                      lo=h_contact_lo, hi=h_contact_hi, lo_closed=True, hi_closed=True),
        "numerics.fem_grading": Key("float", "-", "FEM element growth per unit distance, coarsest level", lo=0.0,
                                    hi=2.0, hi_closed=True),
        "numerics.fem_h_max": Key("float", "a_H", "largest FEM element, coarsest level", lo=0.05, hi=h_max_hi,
                                  hi_closed=True),
        "numerics.fem_contact_zone": Key("float", "a_H", zone_doc, lo=1.05, hi=zone_hi, hi_closed=True),
        "numerics.fem_block": Key("float", block_unit, block_doc, lo=block_lo, hi=block_hi, lo_closed=True,
                                  hi_closed=True),
    }


def fem_line_mesh_keys() -> dict[str, Key]:
    """The mesh-family keys of the 2D plane-strain FE models (frictionless and frictional line contact): sizes
    in Hertz half-widths a_H of the coarsest level, halved per level."""
    return {
        "numerics.fem_levels": Key("int", "-", "FEM mesh levels (>= 3 for Richardson)", lo=1, hi=6,
                                   lo_closed=True, hi_closed=True),
        "numerics.fem_h_contact": Key("float", "a_H", "coarsest element size on the contact / a_H", lo=0.0,
                                      hi=0.5, hi_closed=True),
        "numerics.fem_grading": Key("float", "-", "coarsest mesh growth rate away from the contact", lo=0.0,
                                    hi=1.0, hi_closed=True),
        "numerics.fem_contact_zone": Key("float", "a_H", "candidate contact zone / a_H", lo=1.05, hi=3.0,
                                         hi_closed=True),
        "numerics.fem_block_width": Key("float", "a_H", "block width / a_H", lo=40.0, hi=1000.0, lo_closed=True,
                                        hi_closed=True),
        "numerics.fem_block_depth": Key("float", "a_H", "block depth / a_H", lo=20.0, hi=1000.0, lo_closed=True,
                                        hi_closed=True),
        "numerics.fem_order": Key("int", "-", "element order (P1 or P2)", lo=1, hi=2, lo_closed=True,
                                  hi_closed=True),
        "numerics.fem_formulation": Key("str", "-", "auto: mixed u-p (Taylor-Hood) above nu = 0.45",
                                        choices=("auto", "displacement", "mixed")),
    }


def material_keys(body: str) -> dict[str, Key]:
    return {
        f"materials.{body}.E": Key("float", "Pa", f"Young's modulus of the {body}", lo=0.0),
        f"materials.{body}.nu": Key("float", "-", f"Poisson's ratio of the {body}", lo=-1.0, hi=0.5),
        f"materials.{body}.rigid": Key("bool", "-", f"treat the {body} as rigid (E, nu ignored)"),
    }


def elastic(params: dict[str, Any], body: str) -> Elastic:
    """The Elastic of ``materials.<body>`` from a flat parameter dict (E, nu ignored when rigid)."""
    return Elastic(float(params.get(f"materials.{body}.E", 1.0)), float(params.get(f"materials.{body}.nu", 0.0)),
                   bool(params.get(f"materials.{body}.rigid", False)))


def check_body_pair(params: dict[str, Any], bodies: tuple[str, str]) -> None:
    """Elastic bodies need E and nu; at least one of the two must be elastic."""
    for body in bodies:
        if not params.get(f"materials.{body}.rigid", False):
            for k in (f"materials.{body}.E", f"materials.{body}.nu"):
                if k not in params:
                    raise InputError(k, f"required for an elastic {body} (or set materials.{body}.rigid = true)")
    if all(params.get(f"materials.{b}.rigid", False) for b in bodies):
        raise InputError(f"materials.{bodies[1]}.rigid", "both bodies rigid: at least one must be elastic")


def model_keys(names: tuple[str, ...]) -> dict[str, Key]:
    """The ``models.*`` keys of a kind whose models are ``names``: ``run`` (what runs), ``references`` (what
    the others are compared against) and ``contrast`` (models shown for contrast, not expected to be valid in
    this scene: a candidate model that leaves its tolerance fails the scene, a contrast model is reported as
    "not valid here" without failing it). Every compared (model, quantity) of a built-in scene carries a
    tolerance ``tolerances.<model>.<quantity>``; a contrast model's tolerance is the band it is judged by."""
    return {
        "models.run": Key("list", "-", "models to run", choices=names),
        "models.references": Key("list", "-", "models every other model is compared against", choices=names),
        "models.contrast": Key("list", "-", "models shown as contrasts (not expected to be valid here)",
                               choices=names, empty_ok=True),
    }


def tolerance_key(doc: str) -> Key:
    return Key("float", "-", doc, lo=0.0, hi=1.0, hi_closed=True)


@dataclass
class Scene:
    """A validated scene: flat ``params`` dict of dotted keys -> values, plus its schema."""

    name: str
    kind: str
    description: str
    tags: list[str]
    params: dict[str, Any]
    schema: dict[str, Key] = field(repr=False)
    source: str = ""
    # ``[tolerances.exceptions]``: "model.quantity" -> why that band is deliberately wider than the quantity moves
    # over the scene's stress sweep (femcheck.band_check); not a parameter, never in a model's key
    band_exceptions: dict[str, str] = field(default_factory=dict)

    def __getitem__(self, key: str) -> Any:
        return self.params[key]

    def get(self, key: str, default: Any = None) -> Any:
        return self.params.get(key, default)

    def section(self, prefix: str) -> dict[str, Any]:
        """Keys under ``prefix.`` with the prefix stripped."""
        n = len(prefix) + 1
        return {k[n:]: v for k, v in self.params.items() if k.startswith(prefix + ".")}

    def material(self, body: str) -> Elastic:
        return elastic(self.params, body)

    @property
    def builtin(self) -> bool:
        """A scene shipped in femcheck/scenes (its references are stored with the package's)."""
        path = builtin_scene_files().get(self.name)
        return path is not None and bool(self.source) and Path(self.source).resolve() == path.resolve()

    def with_overrides(self, overrides: dict[str, Any]) -> "Scene":
        """A new validated scene; an override of ``None`` removes the key (e.g. radius -> Rx, Ry), and setting
        one key of a group of alternatives (the kind's ``ALTERNATIVES``) removes the others."""
        merged = _apply_overrides(self.kind, self.params, overrides)
        # an exception follows its band; a band removed by the overrides takes its exception with it
        kept = {k: v for k, v in self.band_exceptions.items() if f"tolerances.{k}" in merged}
        return build_scene(self.name, self.kind, modified(self.description, overrides), self.tags, merged,
                           self.source, kept)


def _apply_overrides(kind: str, params: dict[str, Any], overrides: dict[str, Any]) -> dict[str, Any]:
    """``params`` updated with ``overrides``. A kind may declare ``ALTERNATIVES``: groups of options of which a
    scene gives one, an option being a key or a tuple of keys given together (``layer.thickness`` or
    ``layer.h_over_a``; the load and speed or the Moes groups ``ehl.M``, ``ehl.L``). Overriding a key of one
    option drops the keys of the other options that the overrides do not name: the input given last wins, so
    ``--set layer.h_over_a=0.1`` works on a scene written with a thickness, and ``--set load.normal=...`` on a scene
    written with Moes groups is never silently replaced by them."""
    from .problems import problem

    merged = dict(params)
    for group in getattr(problem(kind), "ALTERNATIVES", ()):
        options = [(o,) if isinstance(o, str) else tuple(o) for o in group]
        for i, option in enumerate(options):
            if any(k in overrides for k in option):
                for other in options[:i] + options[i + 1:]:
                    for k in other:
                        if k not in overrides:
                            merged.pop(k, None)
    merged.update(overrides)
    return {k: v for k, v in merged.items() if v is not None}


MODIFIED = "Modified by "


def modified(description: str, overrides: dict[str, Any]) -> str:
    """``description`` headed by the overrides that change the physics (not the choice of models), so that a
    scene run with ``--set`` never shows the shipped text as if its numbers still held."""
    physics = {k: v for k, v in overrides.items() if not k.startswith(("models.", "tolerances."))}
    if not physics:
        return description
    head = ", ".join(f"{k} = {'(removed)' if v is None else v}" for k, v in physics.items())
    if description.startswith(MODIFIED):           # a second round of overrides: one heading
        description = description.partition("\n")[2]
    return f"{MODIFIED}{head}: the description below is of the scene as written; its numbers may not hold.\n" \
        + description


def _flatten(d: dict, prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(_flatten(v, key + "."))
        else:
            out[key] = v
    return out


def did_you_mean(word: str, candidates) -> str:
    """`` (did you mean 'x'?)`` for the closest of ``candidates`` to a misspelt ``word``, else ``""``."""
    close = difflib.get_close_matches(word, list(candidates), n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _show_hint(name: str, source: str) -> str:
    """The ``femcheck show`` command that lists a scene's keys: by name for a built-in scene, else by path."""
    builtin = builtin_scene_files().get(name)
    return f"femcheck show {name}" if builtin is not None and str(builtin) == source or not source \
        else f"femcheck show {source}"


def lookup_key(schema: dict[str, Key], key: str) -> Key | None:
    if key in schema:
        return schema[key]
    for pattern, spec in schema.items():
        if "*" in pattern and fnmatchcase(key, pattern):
            return spec
    return None


def build_scene(name: str, kind: str, description: str, tags: list[str], raw: dict[str, Any],
                source: str = "", band_exceptions: dict[str, str] | None = None) -> Scene:
    """Type- and range-check every key against the kind's schema, then the kind's cross-key checks; each band
    exception must name a tolerance of the scene and say why."""
    from .problems import problem

    prob = problem(kind)
    schema = prob.SCHEMA
    params: dict[str, Any] = {}
    for key, value in raw.items():
        spec = lookup_key(schema, key)
        if spec is None:
            known = [k for k in schema if "*" not in k] + list(prob.DEFAULTS)
            raise InputError(key, f"unknown key for a {kind} scene{did_you_mean(key, known)}; see "
                                  f"`{_show_hint(name, source)}` for the keys")
        params[key] = spec.coerce(key, value)
    for key, default in prob.DEFAULTS.items():
        params.setdefault(key, default)
    if "models.contrast" in schema:
        params.setdefault("models.contrast", [])
        _check_models(params, getattr(prob, "MODEL_NAMES", ()))
    missing = [k for k in prob.REQUIRED if k not in params]
    if missing:
        raise InputError(missing[0], "required key is missing")
    prob.validate(params)
    exceptions = dict(band_exceptions or {})
    for key, why in exceptions.items():
        where = f"tolerances.exceptions.{key}"
        if f"tolerances.{key}" not in params:
            given = [k.split(".", 1)[1] for k in params if k.startswith("tolerances.")]
            raise InputError(where, f"names no tolerance of this scene{did_you_mean(key, given)}; an exception "
                                    "explains a band the scene gives (\"model.quantity\" = \"why\")")
        if not isinstance(why, str) or not why.strip():
            raise InputError(where, "must be a non-empty string saying why the band is wider than the quantity "
                                    "moves over the scene's stress sweep")
    return Scene(name, kind, description, list(tags), params, schema, source, exceptions)


def _check_models(params: dict[str, Any], names: tuple[str, ...]) -> None:
    """A contrast is not a reference; a tolerance names a model of the kind (or ``<model>@finest``)."""
    both = set(params["models.contrast"]) & set(params.get("models.references", ()))
    if both:
        raise InputError("models.contrast", f"{sorted(both)[0]!r} is also a reference; a reference is what the "
                                            "others are judged against, it cannot be a contrast")
    for key in params:
        if key.startswith("tolerances.") and names:
            model = key.split(".")[1].strip('"').partition("@")[0]
            if model not in names:
                raise InputError(key, f"{model!r} is not a model of this kind{did_you_mean(model, names)}; "
                                      f"allowed: {', '.join(names)} (or <model>@finest)")


def parse_overrides(items: list[str]) -> dict[str, str]:
    """``["load.per_length=2e6", ...]`` -> dict; the values stay strings and are converted by the schema."""
    out: dict[str, str] = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key.strip():
            raise InputError("--set", f"{item!r} is not KEY=VALUE (e.g. --set load.per_length=2e6)")
        out[key.strip()] = value.strip()
    return out


def builtin_scene_files() -> dict[str, Path]:
    root = Path(__file__).parent / "scenes"
    return {p.stem: p for p in sorted(root.glob("*.toml"))}


def load_scene(scene: str | Path, overrides: dict[str, Any] | None = None) -> Scene:
    """Load a built-in scene by name, or a TOML file by path, and apply ``overrides`` (dotted keys)."""
    files = builtin_scene_files()
    path = files.get(str(scene)) or Path(scene)
    if not path.is_file():
        if isinstance(scene, Path) or "/" in str(scene) or str(scene).endswith(".toml"):
            raise InputError("scene", f"no such file: {scene}")
        raise InputError("scene", f"{scene!r} is neither a built-in scene{did_you_mean(str(scene), files)} "
                                  f"nor a TOML file; allowed: {', '.join(sorted(files))} or a path")
    try:
        data = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as err:
        raise InputError("scene", f"{path}: invalid TOML ({err})") from None
    meta = {k: data.pop(k) for k in ("name", "kind", "description", "tags") if k in data}
    if "kind" not in meta:
        raise InputError("kind", f"{path}: a scene needs a top-level kind")
    tolerances = data.get("tolerances")
    exceptions = tolerances.pop("exceptions", {}) if isinstance(tolerances, dict) else {}
    if not isinstance(exceptions, dict):
        raise InputError("tolerances.exceptions", 'must be a table of "model.quantity" = "why"')
    written = _flatten(data)
    _refuse_quoted_numbers(str(meta["kind"]), written, path)
    raw = _apply_overrides(str(meta["kind"]), written, overrides or {})
    return build_scene(str(meta.get("name", path.stem)), str(meta["kind"]),
                       modified(str(meta.get("description", "")), overrides or {}), list(meta.get("tags", [])), raw,
                       str(path), exceptions)


def _refuse_quoted_numbers(kind: str, written: dict[str, Any], path: Path) -> None:
    """A number or a truth value written as a string in a scene file (``normal = "1000"``) is an error, not
    converted: in TOML a quoted value is text (``--set`` values are text by nature and are converted)."""
    from .problems import problem

    schema = problem(kind).SCHEMA
    for key, value in written.items():
        spec = lookup_key(schema, key)
        if spec is not None and spec.kind in ("float", "int", "bool") and isinstance(value, str):
            raise InputError(key, f"{value!r} is a string in {path.name}; allowed: {spec.allowed()}, written "
                                  "without quotes")


def builtin_tags() -> dict[str, list[str]]:
    """Scene name -> its tags, read from the built-in scene files without building the scenes (fast: for
    listing suites and refusing an unknown one)."""
    out = {}
    for name, path in builtin_scene_files().items():
        try:
            out[name] = list(tomllib.loads(path.read_text()).get("tags", []))
        except tomllib.TOMLDecodeError:
            out[name] = []
    return out
