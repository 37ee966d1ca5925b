"""Reading models from TOML files (the format of ``shared/design.md``).

Numbers are exact: decimal literals are read as written (``0.3`` is 3/10), and
strings are restricted arithmetic expressions (:mod:`symtmm.expr`) over
numbers, parameters, ``pi`` and ``sqrt``. Nothing in a file is executed.

Examples
--------
>>> text = '''
... [parameters]
... K = 100
... [[beam]]
... name = "a"
... EI = 1
... m = 1
... L = 1
... left = "clamped"
... right = "free"
... [[beam]]
... name = "b"
... EI = 1
... m = 1
... L = 1
... left = "clamped"
... right = "free"
... [[spring]]
... between = ["a", "b"]
... x = 0.5
... k = "K/2"
... '''
>>> model = loads(text)
>>> model.resolved().springs[0].k
50
"""

from __future__ import annotations

import sys
from decimal import Decimal

import sympy as sp

from .elements.theories import THEORIES
from .errors import ModelError
from .expr import ExpressionError, exact_number, parameter_symbol, parse_expression, substitute
from .limits import MAX_FILE_BYTES, MAX_PARAMETER_DEPTH
from .model import (
    GROUND,
    Attachment,
    Beam,
    Layer,
    Mass,
    Model,
    RigidBody,
    Spring,
    check_size,
    oscillator,
    rod,
)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["load", "loads", "from_dict", "parse_assignment"]

_TOP = {"title", "parameters", "beam", "rod", "spring", "mass", "rigid", "joint", "oscillator",
        "layer", "member", "node"}
_BEAM_REQUIRED = ("name", "EI", "m", "L", "left", "right")
_BEAM_OPTIONAL = ("x0", "kw", "theory", "N", "rhoI", "kGA")
_ROD_REQUIRED = ("name", "EA", "m", "L", "left", "right")
_ROD_OPTIONAL = ("x0", "kw", "GJ", "rhoIp")
#: spring kinds a model file may name on rods, and the kind of the state slot they act on
ROD_SPRING_KINDS = {"axial": "translational", "torsional": "rotational"}
_RIGID_REQUIRED = ()
_RIGID_OPTIONAL = ("name", "attach", "M", "J", "xc", "hinged", "springs", "k", "c")
_JOINT_REQUIRED = ("ends",)
_JOINT_OPTIONAL = ("name", "kind", "M", "J")
#: kinds of joint: all ends rigidly together, or pinned to a common point
JOINT_KINDS = ("rigid", "hinge")
_SPRING_REQUIRED = ("between", "x", "k")
_SPRING_OPTIONAL = ("c", "kind")
_MASS_REQUIRED = ("beam", "x", "M")
_MASS_OPTIONAL = ("J",)
_LAYER_REQUIRED = ("between", "k")
_LAYER_OPTIONAL = ("c", "from", "to")
_MEMBER_REQUIRED = ("name", "from", "EI", "m")
_MEMBER_OPTIONAL = ("to", "angle", "L", "EA", "inextensible")
_NODE_REQUIRED = ("at",)
_NODE_OPTIONAL = ("name", "support", "hinge", "M", "J", "kx", "ky", "ktheta", "cx", "cy",
                  "ctheta", "angle")
_OSCILLATOR_REQUIRED = ("x", "M", "k")
_OSCILLATOR_OPTIONAL = ("name", "beam", "between", "c")


def load(path, overrides: dict | None = None) -> Model:
    """Read a model file.

    Parameters
    ----------
    path : str or Path
    overrides : dict, optional
        Parameter values replacing the file's (``--set NAME=VALUE``): numbers
        or expression strings.

    Raises
    ------
    ModelError
        With the file, the field and the problem.
    """
    source = str(path)
    try:
        with open(path, "rb") as fh:
            # one byte more than allowed tells a file that is too large without reading it all
            data = fh.read(MAX_FILE_BYTES + 1)
        if len(data) > MAX_FILE_BYTES:
            raise ModelError(f"the file is larger than {MAX_FILE_BYTES} bytes", source=source)
        text = data.decode("utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise ModelError(f"cannot read the file: {reason}", source=source) from None
    return loads(text, overrides, source=source)


def loads(text: str, overrides: dict | None = None, source: str = "<string>") -> Model:
    """Read a model from TOML text (see :func:`load`)."""
    try:
        data = tomllib.loads(text, parse_float=Decimal)
    except tomllib.TOMLDecodeError as exc:
        raise ModelError(f"not valid TOML: {exc}", source=source) from None
    except RecursionError:
        # the TOML reader descends once per level of nested arrays and inline tables
        raise ModelError("not valid TOML here: arrays or inline tables nested too deeply",
                         source=source) from None
    except ValueError:
        # Python's limit on converting long digit strings to integers
        raise ModelError("not valid TOML here: an integer with more than 4300 digits",
                         source=source) from None
    try:
        return _build(data, overrides or {}, source)
    except ModelError as exc:
        raise exc.with_source(source) from None


def from_dict(data: dict, overrides: dict | None = None, source: str = "<dict>") -> Model:
    """A model from a plain dict laid out as a model file (``{"beam": [{...}], ...}``).

    Values may be numbers (a float means its shortest decimal: ``0.3`` is 3/10) or
    expression strings; the checks and messages are those of :func:`load`.
    """
    if not isinstance(data, dict):
        raise ModelError(f"expected a dict laid out as a model file, got {_kind(data)}",
                         source=source)
    try:
        return _build(data, overrides or {}, source)
    except ModelError as exc:
        raise exc.with_source(source) from None
    except RecursionError:
        raise ModelError("nested too deeply", source=source) from None


def parse_assignment(text: str) -> tuple[str, str]:
    """Split ``NAME=VALUE`` (the argument of ``--set``).

    Examples
    --------
    >>> parse_assignment("K=1e3")
    ('K', '1e3')
    """
    name, sep, value = text.partition("=")
    name, value = name.strip(), value.strip()
    if not sep or not name or not value:
        raise ModelError(f"--set expects NAME=VALUE, got {text!r}", field="--set")
    return name, value


def _number(value, field: str, resolve=None) -> sp.Expr:
    try:
        if isinstance(value, str):
            return parse_expression(value, resolve)
        if isinstance(value, (int, Decimal, float)) and not isinstance(value, bool):
            return exact_number(value)
    except ExpressionError as exc:
        raise ModelError(str(exc), field=field) from None
    raise ModelError(f"expected a number or an expression string, got {_kind(value)}", field=field)


def _kind(value) -> str:
    return {bool: "a boolean", list: "a list", dict: "a table"}.get(type(value),
                                                                     type(value).__name__)


def _check_keys(table, required, optional, where):
    if not isinstance(table, dict):
        raise ModelError(f"expected a table, got {_kind(table)}", field=where)
    for key in required:
        if key not in table:
            raise ModelError(f"missing field '{key}'", field=where)
    for key in table:
        if key not in required and key not in optional:
            raise ModelError(f"unknown field '{key}'", field=f"{where}.{key}")


def _parameters(raw: dict, overrides: dict) -> dict:
    """Parameter expressions as written, references to other parameters kept as symbols.

    Keeping the references (``k = "K*EI/L**3"`` stays in ``K``) is what lets
    ``--set K=...``, ``Model.with_parameters`` and ``--symbolic K`` reach the
    parameters defined in terms of ``K``; :class:`Model` resolves them.
    """
    if not isinstance(raw, dict):
        raise ModelError(f"expected a table, got {_kind(raw)}", field="parameters")
    texts = dict(raw)
    texts.update(overrides)
    values: dict = {}
    active: list = []

    def parse(name):
        if name in values:
            return
        if name in active:
            raise ModelError("parameters refer to each other in a circle: "
                             + " -> ".join(active + [name]), field=f"parameters.{name}")
        if len(active) >= MAX_PARAMETER_DEPTH:
            # each level is a level of recursion here and in Model's resolution
            raise ModelError(f"defined through a chain of more than {MAX_PARAMETER_DEPTH} other "
                             "parameters", field=f"parameters.{active[0]}")
        active.append(name)
        field = f"override {name}" if name in overrides else f"parameters.{name}"

        def reference(other):
            if other not in texts:
                return None
            parse(other)   # parsed first: a circle is reported where it closes
            return parameter_symbol(other)
        values[name] = _number(texts[name], field, reference)
        active.pop()

    for name in texts:
        parse(name)
    return values


def _level_fields(raw, where: str, required, optional, stiffness) -> tuple:
    """``(name, where, fields)`` of a ``[[beam]]`` or ``[[rod]]`` table: its keys checked,
    its name and ends strings, ``fields`` its numbers ``stiffness`` (e.g. ``EI, m, L``),
    ``x0`` and ``kw``; ``where`` names the table with its name (``beam[2] (upper)``)."""
    _check_keys(raw, required, optional, where)
    name = raw["name"]
    if not isinstance(name, str):
        raise ModelError(f"expected a string, got {_kind(name)}", field=f"{where}.name")
    where = f"{where} ({name})"
    for k in ("left", "right"):
        if not isinstance(raw[k], str):
            raise ModelError(f"expected a string, got {_kind(raw[k])}", field=f"{where}.{k}")
    fields = {k: _number(raw[k], f"{where}.{k}") for k in stiffness}
    fields["x0"] = _number(raw.get("x0", 0), f"{where}.x0")
    fields["kw"] = _number(raw.get("kw", 0), f"{where}.kw")
    return name, where, fields


def _build(data: dict, overrides: dict, source: str) -> Model:
    for key in data:
        if key not in _TOP:
            raise ModelError(f"unknown field '{key}'", field=key)
    title = data.get("title", "")
    if not isinstance(title, str):
        raise ModelError("expected a string", field="title")
    if data.get("beam") is None and data.get("rod") is None and data.get("member") is None:
        raise ModelError("missing field (at least one [[beam]], [[rod]] or [[member]] table)",
                         field="beam")
    beams_raw = _array_of_tables(data, "beam")
    rods_raw = _array_of_tables(data, "rod")
    springs_raw = _array_of_tables(data, "spring")
    # the budgets first: nothing is parsed for a model that is too large anyway
    tables = [data.get(t, []) for t in ("mass", "rigid", "joint", "oscillator")]
    attachments = sum(_points_in(t) for group in tables[1:] if isinstance(group, list)
                      for t in group)
    layers_raw = _array_of_tables(data, "layer")
    attachments += 2 * len(layers_raw)
    raw_params = data.get("parameters", {})
    members_raw = _array_of_tables(data, "member")
    nodes_raw = _array_of_tables(data, "node")
    attachments += 4 * len(members_raw)
    n_masses = len(tables[0]) if isinstance(tables[0], list) else 0
    check_size(len(beams_raw) + len(rods_raw) + 2 * len(members_raw),
               len(springs_raw) + n_masses + attachments,
               len(raw_params) if isinstance(raw_params, dict) else 0)

    params = _parameters(data.get("parameters", {}), overrides)
    declared = data.get("parameters", {})
    known_names = set(declared) if isinstance(declared, dict) else set()

    beams = []
    for i, raw in enumerate(beams_raw, 1):
        name, where, fields = _level_fields(raw, f"beam[{i}]", _BEAM_REQUIRED, _BEAM_OPTIONAL,
                                            ("EI", "m", "L"))
        fields["N"] = _number(raw.get("N", 0), f"{where}.N")
        theory = raw.get("theory", "euler-bernoulli")
        if not isinstance(theory, str):
            raise ModelError(f"expected a string, got {_kind(theory)}", field=f"{where}.theory")
        for needed in THEORIES.get(theory, ()):
            if needed not in raw:
                raise ModelError(f"missing field '{needed}' (theory = \"{theory}\" needs it)",
                                 field=where)
        if "rhoI" in raw:
            fields["rhoI"] = _number(raw["rhoI"], f"{where}.rhoI")
        if "kGA" in raw:
            fields["kGA"] = _number(raw["kGA"], f"{where}.kGA")
        try:
            beams.append(Beam(name, left=raw["left"], right=raw["right"], theory=theory,
                              **fields))
        except ModelError as exc:
            raise ModelError(exc.message, field=_rename(exc.field, where)) from None
        for value in fields.values():
            known_names |= {s.name for s in value.free_symbols}

    rods = set()
    for i, raw in enumerate(rods_raw, 1):
        name, where, fields = _level_fields(raw, f"rod[{i}]", _ROD_REQUIRED, _ROD_OPTIONAL,
                                            ("EA", "m", "L"))
        for k in ("GJ", "rhoIp"):
            if k in raw:
                fields[k] = _number(raw[k], f"{where}.{k}")
        try:
            beams.append(rod(name, left=raw["left"], right=raw["right"], **fields))
        except ModelError as exc:
            raise ModelError(exc.message, field=_rename(exc.field, where)) from None
        rods.add(name)
        for value in fields.values():
            known_names |= {s.name for s in value.free_symbols}

    springs = []
    for i, raw in enumerate(springs_raw, 1):
        where = f"spring[{i}]"
        _check_keys(raw, _SPRING_REQUIRED, _SPRING_OPTIONAL, where)
        between = _pair(raw, where, '["upper", "lower"] or ["upper", "ground"]')
        fields = {k: _number(raw[k], f"{where}.{k}") for k in ("x", "k")}
        fields["c"] = _number(raw.get("c", 0), f"{where}.c")
        kind = raw.get("kind", "translational")
        if not isinstance(kind, str):
            raise ModelError(f"expected a string, got {_kind(kind)}", field=f"{where}.kind")
        if kind in ROD_SPRING_KINDS:
            if not all(end in rods or end == "ground" for end in between):
                raise ModelError(f"kind = \"{kind}\" is for springs on rods", field=f"{where}.kind")
            kind = ROD_SPRING_KINDS[kind]
        try:
            springs.append(Spring(between[0], between[1], kind=kind, **fields))
        except ModelError as exc:
            raise ModelError(exc.message, field=_rename(exc.field, where)) from None
        for value in fields.values():
            known_names |= {s.name for s in value.free_symbols}

    masses_raw = _array_of_tables(data, "mass")
    masses = []
    for i, raw in enumerate(masses_raw, 1):
        where = f"mass[{i}]"
        _check_keys(raw, _MASS_REQUIRED, _MASS_OPTIONAL, where)
        if not isinstance(raw["beam"], str):
            raise ModelError(f"expected a beam name, got {_kind(raw['beam'])}",
                             field=f"{where}.beam")
        fields = {k: _number(raw[k], f"{where}.{k}") for k in ("x", "M")}
        fields["J"] = _number(raw.get("J", 0), f"{where}.J")
        try:
            masses.append(Mass(raw["beam"], **fields))
        except ModelError as exc:
            raise ModelError(exc.message, field=_rename(exc.field, where)) from None
        for value in fields.values():
            known_names |= {s.name for s in value.free_symbols}

    layers = []
    for i, raw in enumerate(layers_raw, 1):
        where = f"layer[{i}]"
        _check_keys(raw, _LAYER_REQUIRED, _LAYER_OPTIONAL, where)
        between = _pair(raw, where, '["upper", "lower"]', "beam names")
        fields = {"k": _number(raw["k"], f"{where}.k"), "c": _number(raw.get("c", 0), f"{where}.c")}
        for key, attr in (("from", "x0"), ("to", "x1")):
            if key in raw:
                fields[attr] = _number(raw[key], f"{where}.{key}")
        try:
            layers.append(Layer(between[0], between[1], **fields))
        except ModelError as exc:
            raise ModelError(exc.message, field=_rename(exc.field, where)) from None
        for value in fields.values():
            known_names |= {s.name for s in value.free_symbols}

    geometry: set = set()
    frame_fields: dict = {}
    frame_levels, frame_bodies, links = _frame(members_raw, nodes_raw, params, geometry,
                                               frame_fields)
    beams += frame_levels
    bodies, body_fields = _bodies(data, {b.name: b for b in beams}, known_names)
    bodies += frame_bodies
    body_fields.update({b.name: frame_fields[b.name] for b in frame_bodies
                        if b.name in frame_fields})
    oscillators, oscillator_fields = _oscillators(data, {b.name for b in beams}, known_names,
                                                  {b.name for b in bodies})
    bodies += oscillators
    body_fields.update(oscillator_fields)

    names = {b.name for b in beams}
    for i, mass in enumerate(masses, 1):
        if mass.beam not in names:
            raise ModelError(f"unknown beam '{mass.beam}'", field=f"mass[{i}].beam")
    for i, spring in enumerate(springs, 1):
        for end in (spring.a, spring.b):
            if end != GROUND and end not in names:
                raise ModelError(f"unknown beam '{end}'", field=f"spring[{i}].between")
    for name in overrides:
        if name not in known_names:
            raise ModelError(f"'{name}' is not a parameter of this model", field=f"override {name}")
    try:
        return Model(tuple(beams), tuple(springs), params, title, source, tuple(masses),
                     tuple(bodies), tuple(layers), links, tuple(geometry))
    except ModelError as exc:
        raise ModelError(exc.message, field=_spring_field(exc.field, springs, beams, masses,
                                                          body_fields, layers,
                                                          frame_fields)) from None


def _pair(raw: dict, where: str, example: str, what: str = "names") -> list:
    """The field ``between`` of a table: two names (one clear line otherwise)."""
    between = raw["between"]
    if (not isinstance(between, list) or len(between) != 2
            or not all(isinstance(b, str) for b in between)):
        raise ModelError(f"expected two {what}, e.g. {example}", field=f"{where}.between")
    return between


def _attachment_point(text, beams: dict, where: str):
    """``"beam.left"``, ``"beam.right"`` or ``"beam@x"`` as ``(beam, x)``."""
    if not isinstance(text, str):
        raise ModelError(f'expected a point such as "a.right" or "a@0.5", got {_kind(text)}',
                         field=where)
    if "@" in text:
        name, _, x_text = text.partition("@")
        name = name.strip()
        x = _number(x_text.strip(), where)
    else:
        name, dot, end = text.strip().rpartition(".")
        if not dot or end not in ("left", "right"):
            raise ModelError(f'{text!r} is not a point: write "beam.left", "beam.right" or '
                             '"beam@x"', field=where)
        x = None
    if name not in beams:
        raise ModelError(f"unknown beam '{name}'", field=where)
    if x is None:
        beam = beams[name]
        x = beam.x0 if end == "left" else beam.x0 + beam.L
    return name, x


def _points_in(table) -> int:
    """How many points a body, joint or oscillator table holds (for the size budget)."""
    if not isinstance(table, dict):
        return 0
    count = 0
    for key in ("attach", "ends", "between", "springs"):
        value = table.get(key)
        count += len(value) if isinstance(value, list) else 0
    return count + (1 if "beam" in table else 0)


def _array_of_tables(data: dict, name: str) -> list:
    """The ``[[name]]`` tables of a model file (an empty list where there are none)."""
    raw = data.get(name, [])
    if not isinstance(raw, list):
        raise ModelError(f"expected an array of tables: write [[{name}]]", field=name)
    return raw


def _frame(members_raw: list, nodes_raw: list, params: dict, used: set, fields: dict) -> tuple:
    """The ``[[member]]`` and ``[[node]]`` tables of a planar frame as levels and joints
    (:func:`symtmm.frame.frame_parts`). A frame's geometry takes the parameters' values
    (it fixes which ends meet), its stiffnesses and masses stay expressions. ``used``
    gathers the parameters the geometry took; ``fields`` maps the model's names of the
    frame's levels and joints to the file's tables (``member[2] (b)``, ``node[1]``)."""
    from .frame import AXIAL_SUFFIX, Member, Node, frame_parts

    symbols = {parameter_symbol(name): value for name, value in params.items()}

    def geometry(value, field):
        expr = _number(value, field, lambda name: parameter_symbol(name)
                       if name in params else None)
        for _ in range(MAX_PARAMETER_DEPTH + 1):
            values = {s: v for s, v in symbols.items() if s in expr.free_symbols and v is not None}
            if not values:
                break
            used.update(s.name for s in values)
            try:
                expr = substitute(expr, values)
            except ExpressionError as exc:
                raise ModelError(str(exc), field=field) from None
        if not expr.is_number:
            raise ModelError("must be a number: a frame's geometry takes parameters with a "
                             "value only", field=field)
        return expr

    def pair(value, field):
        if not isinstance(value, list) or len(value) != 2:
            raise ModelError("expected a point [x, y]", field=field)
        return tuple(geometry(v, field) for v in value)

    members = []
    for i, raw in enumerate(members_raw, 1):
        where = f"member[{i}]"
        _check_keys(raw, _MEMBER_REQUIRED, _MEMBER_OPTIONAL, where)
        name = raw["name"]
        if not isinstance(name, str):
            raise ModelError(f"expected a string, got {_kind(name)}", field=f"{where}.name")
        where = f"{where} ({name})"
        start = pair(raw["from"], f"{where}.from")
        if "to" in raw:
            for k in ("angle", "L"):
                if k in raw:
                    raise ModelError("give either to = [x, y], or angle and L", field=f"{where}.{k}")
            end = pair(raw["to"], f"{where}.to")
        else:
            if "angle" not in raw or "L" not in raw:
                raise ModelError("missing field 'to' (or 'angle' in degrees and 'L')",
                                 field=where)
            angle = geometry(raw["angle"], f"{where}.angle")
            length = geometry(raw["L"], f"{where}.L")
            if not length.is_positive:
                raise ModelError("must be positive", field=f"{where}.L")
            a = angle * sp.pi / 180
            end = (start[0] + length * sp.cos(a), start[1] + length * sp.sin(a))
        inextensible = raw.get("inextensible", False)
        if not isinstance(inextensible, bool):
            raise ModelError("expected true or false", field=f"{where}.inextensible")
        if inextensible == ("EA" in raw):
            raise ModelError("give EA, or inextensible = true" if not inextensible else
                             "an inextensible member has no EA", field=f"{where}.EA")
        EA = None if inextensible else _number(raw["EA"], f"{where}.EA")
        try:
            members.append(Member(name, start, end, EI=_number(raw["EI"], f"{where}.EI"), EA=EA,
                                  m=_number(raw["m"], f"{where}.m")))
        except ModelError as exc:
            raise ModelError(exc.message, field=_rename(exc.field, where)) from None
    nodes = []
    for i, raw in enumerate(nodes_raw, 1):
        where = f"node[{i}]"
        _check_keys(raw, _NODE_REQUIRED, _NODE_OPTIONAL, where)
        name = raw.get("name")
        if name is not None and not isinstance(name, str):
            raise ModelError(f"expected a string, got {_kind(name)}", field=f"{where}.name")
        support = raw.get("support", "free")
        if not isinstance(support, str):
            raise ModelError(f"expected a string, got {_kind(support)}", field=f"{where}.support")
        springs = {}
        for label in ("X", "Y", "Theta"):
            k, c = (f"{kind}{label.lower()}" for kind in ("k", "c"))
            if k in raw or c in raw:
                springs[label] = (_number(raw.get(k, 0), f"{where}.{k}"),
                                  _number(raw.get(c, 0), f"{where}.{c}"))
        try:
            nodes.append(Node(pair(raw["at"], f"{where}.at"), support,
                              raw.get("hinge", False),
                              *(_number(raw.get(k, 0), f"{where}.{k}") for k in ("M", "J")),
                              name=name, springs=springs or None,
                              angle=geometry(raw["angle"], f"{where}.angle")
                              if "angle" in raw else None))
        except ModelError as exc:
            raise ModelError(exc.message, field=_rename(exc.field, where)) from None
    if not members:
        if nodes:
            raise ModelError("a node belongs to a frame: no [[member]] is given", field="node")
        return [], [], ()
    for i, member in enumerate(members, 1):
        fields[member.name] = fields[member.name + AXIAL_SUFFIX] = f"member[{i}] ({member.name})"
    try:
        levels, bodies, links = frame_parts(members, nodes)
    except ModelError as exc:
        field = exc.field or ""
        for member in members:
            if field.startswith(f"member '{member.name}'"):
                field = fields[member.name] + field[len(f"member '{member.name}'"):]
        raise ModelError(exc.message, field=field or None) from None
    for body in bodies:
        for j, node in enumerate(nodes, 1):
            if (body.xc, body.yc) == tuple(node.at):
                fields[body.name] = f"node[{j}]"
    return list(levels), list(bodies), links


def _bodies(data: dict, beams: dict, known_names: set) -> tuple:
    """The ``[[rigid]]`` bodies and the ``[[joint]]`` tables, as rigid bodies.

    Returns the bodies and, by body name, the file's name of its table (``rigid[2]``).
    """
    out, where_of = [], {}
    for table, required, optional in (("rigid", _RIGID_REQUIRED, _RIGID_OPTIONAL),
                                      ("joint", _JOINT_REQUIRED, _JOINT_OPTIONAL)):
        raw_list = _array_of_tables(data, table)
        for i, raw in enumerate(raw_list, 1):
            where = f"{table}[{i}]"
            _check_keys(raw, required, optional, where)
            name = raw.get("name", f"{table}{i}")
            if not isinstance(name, str):
                raise ModelError(f"expected a string, got {_kind(name)}", field=f"{where}.name")
            key = "attach" if table == "rigid" else "ends"
            springs = raw.get("springs", []) if table == "rigid" else []
            if not isinstance(springs, list):
                raise ModelError('expected a list of points, e.g. ["a@0.2", "a@0.8"]',
                                 field=f"{where}.springs")
            points = raw.get(key, [])
            if not isinstance(points, list) or not (points or springs):
                raise ModelError('expected a list of points, e.g. ["a.right", "b@0.5"]'
                                 + (" (or springs = [...])" if table == "rigid" else ""),
                                 field=f"{where}.{key}")
            located = [_attachment_point(p, beams, f"{where}.{key}") for p in points]
            elastic = [_attachment_point(p, beams, f"{where}.springs") for p in springs]
            if table == "rigid" and not springs and ("k" in raw or "c" in raw):
                raise ModelError("k and c belong to springs = [...] points",
                                 field=f"{where}.{'k' if 'k' in raw else 'c'}")
            if springs and "k" not in raw:
                raise ModelError("missing field 'k' (the stiffness of the springs)",
                                 field=f"{where}.k")
            ks = _per_beam(raw.get("k"), len(springs), f"{where}.k", "spring") if springs else []
            cs = _per_beam(raw.get("c", 0), len(springs), f"{where}.c", "spring") \
                if springs else []
            if table == "rigid":
                hinged_raw = raw.get("hinged", [])
                if not isinstance(hinged_raw, list):
                    raise ModelError("expected a list of points", field=f"{where}.hinged")
                hinged = set()
                for p in hinged_raw:
                    if p not in points:
                        raise ModelError(f"{p!r} is not one of the attach points",
                                         field=f"{where}.hinged")
                    hinged.add(p)
                flags = [p in hinged for p in points]
            else:
                kind = raw.get("kind", "rigid")
                if kind not in JOINT_KINDS:
                    raise ModelError(f"unknown kind {kind!r} (use one of {', '.join(JOINT_KINDS)})",
                                     field=f"{where}.kind")
                flags = [kind == "hinge"] * len(points)
                xs = [x for _, x in located]
                if any(sp.simplify(x - xs[0]) != 0 for x in xs[1:]):
                    raise ModelError("the ends of a joint must meet at one x; a body spanning a "
                                     "distance is a [[rigid]]", field=f"{where}.ends")
            fields = {k: _number(raw.get(k, 0), f"{where}.{k}") for k in ("M", "J")}
            if table == "rigid" and "xc" in raw:
                fields["xc"] = _number(raw["xc"], f"{where}.xc")
            try:
                body = RigidBody(name, tuple(Attachment(b, x, h) for (b, x), h
                                            in zip(located, flags))
                                 + tuple(Attachment(b, x, k=k, c=c) for (b, x), k, c
                                         in zip(elastic, ks, cs)), **fields)
            except ModelError as exc:
                raise ModelError(exc.message, field=_rename(exc.field, where)) from None
            out.append(body)
            where_of[body.name] = where
            for value in (list(fields.values()) + [x for _, x in located + elastic]
                          + ks + cs):
                known_names |= {sym.name for sym in sp.sympify(value).free_symbols}
    return out, where_of


def _oscillators(data: dict, beams: set, known_names: set, taken: set) -> tuple:
    """The ``[[oscillator]]`` tables (sprung masses) as bodies held by springs.

    ``beam = "a"`` carries it; ``between = ["a", "b"]`` joins it to two beams, each
    by its own spring and dashpot (``k`` and ``c`` a value for both, or a list of two).
    """
    raw_list = _array_of_tables(data, "oscillator")
    out, where_of = [], {}
    for i, raw in enumerate(raw_list, 1):
        where = f"oscillator[{i}]"
        _check_keys(raw, _OSCILLATOR_REQUIRED, _OSCILLATOR_OPTIONAL, where)
        if ("beam" in raw) == ("between" in raw):
            raise ModelError('give either beam = "a" or between = ["a", "b"]', field=where)
        if "beam" in raw:
            on, key = [raw["beam"]], "beam"
        else:
            on, key = raw["between"], "between"
            if not isinstance(on, list) or len(on) != 2:
                raise ModelError('expected two beam names, e.g. ["upper", "lower"]',
                                 field=f"{where}.between")
        for name in on:
            if not isinstance(name, str):
                raise ModelError(f"expected a beam name, got {_kind(name)}", field=f"{where}.{key}")
            if name not in beams:
                raise ModelError(f"unknown beam '{name}'", field=f"{where}.{key}")
        if len(set(on)) != len(on):
            raise ModelError("the two beams must differ", field=f"{where}.between")
        name = raw.get("name", f"oscillator{i}")
        if not isinstance(name, str):
            raise ModelError(f"expected a string, got {_kind(name)}", field=f"{where}.name")
        if name in taken:
            raise ModelError(f"duplicate body name '{name}'", field=f"{where}.name")
        taken.add(name)

        x, M = _number(raw["x"], f"{where}.x"), _number(raw["M"], f"{where}.M")
        ks = _per_beam(raw.get("k"), len(on), f"{where}.k")
        cs = _per_beam(raw.get("c", 0), len(on), f"{where}.c")
        try:
            body = oscillator(name, on, x, M, ks, cs)
        except ModelError as exc:
            raise ModelError(exc.message, field=_rename(exc.field, where)) from None
        out.append(body)
        where_of[name] = where
        for value in [x, M, *ks, *cs]:
            known_names |= {sym.name for sym in sp.sympify(value).free_symbols}
    return out, where_of


def _per_beam(value, count: int, where: str, per: str = "beam") -> list:
    """A value for every beam (or spring): one for all, or a list of one each."""
    if isinstance(value, list):
        if len(value) != count:
            raise ModelError(f"expected one value per {per} ({count})", field=where)
        return [_number(v, where) for v in value]
    return [_number(value, where)] * count


def _rename(field: str | None, where: str) -> str:
    """Replace the model's own field prefix by the file's (``beam[2] (lower).EI``)."""
    if not field:
        return where
    attr = field.rsplit(".", 1)[-1]
    return f"{where}.{attr}"


def _spring_field(field: str | None, springs, beams, masses=(), bodies=None,
                  layers=(), members=None) -> str | None:
    """Name fields by their position in the file, as the user wrote them (``members``:
    a frame's level names -> its member's table)."""
    if not field:
        return field
    for name, where in (members or {}).items():
        for kind in ("beam", "rod"):
            if field.startswith(f"{kind} '{name}'."):
                return f"{where}." + field.rsplit(".", 1)[-1]
    for i, la in enumerate(layers, 1):
        # (the model names a layer by its beams in the file's order)
        if field.startswith(f"layer {la.a}-{la.b}"):
            return f"layer[{i}]" + field[len(f"layer {la.a}-{la.b}"):]
    for name, where in (bodies or {}).items():
        if field.startswith(f"body '{name}'."):
            attr = field.rsplit(".", 1)[-1]
            if where.startswith("oscillator") and attr in ("attach", "springs"):
                attr = "x"                  # (an oscillator's one point is its x)
            return f"{where}.{attr}"
    for i, s in enumerate(springs, 1):
        if field.startswith(f"spring {s.a}-{s.b}."):
            return f"spring[{i}]." + field.rsplit(".", 1)[-1]
    for i, p in enumerate(masses, 1):
        if field.startswith(f"mass on {p.beam}."):
            return f"mass[{i}]." + field.rsplit(".", 1)[-1]
    for i, b in enumerate(beams, 1):
        if field.startswith(f"beam '{b.name}'."):
            return f"beam[{i}] ({b.name})." + field.rsplit(".", 1)[-1]
    return field
