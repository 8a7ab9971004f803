"""A sweep specification and its expansion into cells.

A specification (JSON, or TOML) names `shadowkit eval` options:

    {
      "description": "what the grid is for",
      "fixed":  {"trees": 2000, "size": "640x360", "views": "all"},
      "parameters": {"budget": [2048, 4096]},
      "axes":   {"technique": ["focused", "tsm", "lispsm"], "map-size": [1024, 2048]},
      "derive": {"bias-slope": "2 if technique == 'tsm' else 1"},
      "where":  ["not (technique == 'focused' and map_size == 1024)"]
    }

- `fixed`: options every cell has. `axes`: the grid, one list of values per option (the cells
  are their product, in the order written, the first axis slowest). An axis whose values are
  objects is a *bundle* axis: each value is a set of options with a `label`, e.g. `"set-up":
  [{"label": "csm 4x1024", "technique": "csm", "cascades": 4, "map-size": 1024}, ...]`.
- `parameters`: axes that are not options but names for `derive` and `where` (a texel budget);
  the grid's slowest axes, each cell's value a column of the results.
- `derive`: options computed from the others (in the order written), `where`: conditions a
  cell must meet (expressions.py says what they may use; names take underscores).
- `grids`: a list of such grids (each with its own fixed, parameters, axes, derive, where), whose
  cells are concatenated — set-ups whose parameters differ (TSM's focus, LiSPSM's weight, the
  cascades' lambda) in one sweep. The top level's `fixed`, `derive` and `where` apply to each.
- Option names are `eval`'s flags without the dashes (`map-size` or `map_size`); a flag without
  a value (`stabilize`) takes true or false; a repeatable one (`light`) a list. The sweep writes
  the results, so --json, --csv, --plot, --report, --dump, --error-map, --aliasing-map, --state
  --check and --serve are not options of a cell.

Every problem is a SpecError whose message names the key, raised before any cell runs.
"""
import hashlib
import itertools
import json
import os
import stat

from .expressions import Expression, ExpressionError

# Written by the sweep itself, or not a measurement.
RESERVED = {"json", "csv", "plot", "report", "dump", "error-map", "aliasing-map", "state", "check", "serve", "help"}
TOP_LEVEL = {"description", "fixed", "parameters", "axes", "derive", "where", "grids"}
GRID_KEYS = {"fixed", "parameters", "axes", "derive", "where"}
MAX_CELLS = 1_000_000


class SpecError(ValueError):
    """A one-line description of what is wrong with the specification, naming the key."""


class Cell:
    """One configuration: `options` (eval's flag names → values, derived ones included) and
    `labels` (bundle axis → the chosen value's label)."""

    def __init__(self, options, labels, origins=None):
        self.options = options
        self.labels = labels
        self.origins = origins or {}  # option -> the specification's key that gave it (for errors)

    def arguments(self, takes_value):
        """The cell as `shadowkit eval` arguments (sorted, so equal cells give equal command lines)."""
        args = []
        for name in sorted(self.options):
            value = self.options[name]
            if not takes_value[name]:
                if value:
                    args.append(f"--{name}")
                continue
            for v in value if isinstance(value, list) else [value]:
                args += [f"--{name}", _text(v)]
        return args

    def key(self, fingerprint, files=()):
        """The cell's identity: its options, the program's fingerprint and the content of any file
        an option names (a scene, a path), hashed; re-running a sweep skips keys already measured."""
        identity = {"options": self.options, "fingerprint": fingerprint, "files": list(files)}
        return hashlib.sha256(json.dumps(identity, sort_keys=True).encode()).hexdigest()[:20]

    def __repr__(self):
        return f"Cell({self.options!r}, {self.labels!r})"


def _text(value):
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return str(value)


def load(path):
    """The specification at `path` (.json or .toml) as a dict; SpecError if it does not parse."""
    # As scene::readFile does: opened without waiting on a pipe that has no writer, and its type
    # and size read from the open descriptor before any byte is (/dev/zero would never end).
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except OSError as e:
        raise SpecError(f"{path}: cannot read ({e.strerror})") from None
    with os.fdopen(fd, "rb") as f:
        status = os.fstat(fd)
        if stat.S_ISDIR(status.st_mode):
            raise SpecError(f"{path}: a directory, not a file")
        if not stat.S_ISREG(status.st_mode):
            raise SpecError(f"{path}: a device, pipe or socket, not a file")
        if status.st_size > 4 << 20:
            raise SpecError(f"{path}: larger than 4 MiB: not a sweep specification")
        data = f.read()
    try:
        if path.endswith(".toml"):
            import tomllib

            spec = tomllib.loads(data.decode())
        else:
            spec = json.loads(data)
    except (ValueError, UnicodeDecodeError, RecursionError) as e:
        raise SpecError(f"{path}: not valid {'TOML' if path.endswith('.toml') else 'JSON'} ({e})") from None
    if not isinstance(spec, dict):
        raise SpecError(f"{path}: expected an object with fixed, axes, derive, where")
    return spec


def _option_name(key, where, takes_value):
    name = key.replace("_", "-")
    if name in RESERVED:
        raise SpecError(f"{where}.{key}: not a cell's option (the sweep writes the results and runs eval itself)")
    if name not in takes_value:
        raise SpecError(f"{where}.{key}: not an option of shadowkit eval")
    return name


def _check_value(value, where, name, takes_value):
    if not takes_value[name]:
        if not isinstance(value, bool):
            raise SpecError(f"{where}: --{name} is a flag: give true or false, not {value!r}")
        return value
    values = value if isinstance(value, list) and name == "light" else [value]
    for v in values:
        if isinstance(v, (dict, list)) or v is None:
            raise SpecError(f"{where}: expected a number or a string for --{name}, got {json.dumps(v)}")
        if isinstance(v, str) and (not v or v.startswith("-") and not _is_number(v)):
            raise SpecError(f"{where}: {v!r} is not a value for --{name}")
    return value


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def _options(mapping, where, takes_value):
    if not isinstance(mapping, dict):
        raise SpecError(f"{where}: expected an object of options")
    out = {}
    for key, value in mapping.items():
        name = _option_name(key, where, takes_value)
        out[name] = _check_value(value, f"{where}.{key}", name, takes_value)
    return out


def expand(spec, takes_value, source="spec"):
    """The cells of `spec` (a dict from load), in grid order. `takes_value` is
    program.eval_options(): which names are options and which of them take a value."""
    if not isinstance(spec, dict):
        raise SpecError(f"{source}: expected an object with fixed, axes, derive, where")
    if "grids" not in spec:
        return _expand_grid(spec, takes_value, source)
    grids = spec["grids"]
    if not isinstance(grids, list) or not grids:
        raise SpecError("grids: expected a non-empty list of grids (objects with axes, fixed, ...)")
    for key in ("axes", "parameters"):
        if key in spec:
            raise SpecError(f"{key}: with grids, each grid has its own {key}")
    unknown = set(spec) - TOP_LEVEL
    if unknown:
        raise SpecError(f"{source}: unknown key '{sorted(unknown)[0]}' (a specification has "
                        f"{', '.join(sorted(TOP_LEVEL))})")
    top_fixed, top_derive = spec.get("fixed", {}), spec.get("derive", {})
    top_where = spec.get("where", [])
    if not isinstance(top_fixed, dict) or not isinstance(top_derive, dict):
        raise SpecError("fixed, derive: expected objects")
    top_where = [top_where] if isinstance(top_where, str) else top_where
    if not isinstance(top_where, list):
        raise SpecError("where: expected a list of conditions")
    cells = []
    for i, grid in enumerate(grids):
        if not isinstance(grid, dict):
            raise SpecError(f"grids[{i}]: expected an object with axes, fixed, parameters, derive, where")
        unknown = set(grid) - GRID_KEYS
        if unknown:
            raise SpecError(f"grids[{i}]: unknown key '{sorted(unknown)[0]}' (a grid has "
                            f"{', '.join(sorted(GRID_KEYS))})")
        fixed = grid.get("fixed", {})
        if not isinstance(fixed, dict):
            raise SpecError(f"grids[{i}].fixed: expected an object of options")
        both = set(fixed) & set(top_fixed)
        if both:
            raise SpecError(f"grids[{i}].fixed.{sorted(both)[0]}: also in the top level's fixed")
        derive, where = grid.get("derive", {}), grid.get("where", [])
        if not isinstance(derive, dict):
            raise SpecError(f"grids[{i}].derive: expected an object of option: \"expression\"")
        where = [where] if isinstance(where, str) else where
        if not isinstance(where, list):
            raise SpecError(f"grids[{i}].where: expected a list of conditions")
        merged = {"fixed": {**top_fixed, **fixed}, "parameters": grid.get("parameters", {}),
                  "axes": grid.get("axes", {}), "derive": {**top_derive, **derive}, "where": [*top_where, *where]}
        try:
            cells += _expand_grid(merged, takes_value, source)
        except SpecError as e:
            raise SpecError(f"grids[{i}].{e}") from None
        if len(cells) > MAX_CELLS:
            raise SpecError(f"grids: more than {MAX_CELLS} cells (split the sweep)")
    return cells


def _expand_grid(spec, takes_value, source):
    unknown = set(spec) - (TOP_LEVEL - {"grids"})
    if unknown:
        raise SpecError(f"{source}: unknown key '{sorted(unknown)[0]}' (a specification has "
                        f"{', '.join(sorted(TOP_LEVEL))})")
    fixed = _options(spec.get("fixed", {}), "fixed", takes_value)
    axes = spec.get("axes", {})
    if not isinstance(axes, dict):
        raise SpecError("axes: expected an object of option: [values]")
    parameters = spec.get("parameters", {})
    if not isinstance(parameters, dict):
        raise SpecError("parameters: expected an object of name: [values]")
    axis_values = []  # per axis: [(options, label or None)]
    bundles = []  # axes whose cells carry a label: bundles and parameters
    for key, values in parameters.items():
        if key.replace("_", "-") in takes_value:
            raise SpecError(f"parameters.{key}: is an option of shadowkit eval (make it an axis)")
        if not key.isidentifier():
            raise SpecError(f"parameters.{key}: a parameter's name is a name in expressions (letters, digits, _)")
        if not isinstance(values, list) or not values:
            raise SpecError(f"parameters.{key}: expected a non-empty list of values")
        if any(isinstance(v, (dict, list)) or v is None for v in values):
            raise SpecError(f"parameters.{key}: values are numbers or strings")
        bundles.append(key)
        axis_values.append([({}, v) for v in values])
    for key, values in axes.items():
        if not isinstance(values, list):
            raise SpecError(f"axes.{key}: expected a list of values")
        if not values:
            raise SpecError(f"axes.{key}: is empty (an empty axis makes no cell)")
        if all(isinstance(v, dict) for v in values):
            choices, labels = [], set()
            for i, v in enumerate(values):
                where = f"axes.{key}[{i}]"
                label = v.get("label")
                if not isinstance(label, str) or not label:
                    raise SpecError(f"{where}: a bundle needs a \"label\" naming it")
                if label in labels:
                    raise SpecError(f"{where}: label '{label}' is used twice")
                labels.add(label)
                choices.append((_options({k: x for k, x in v.items() if k != "label"}, where, takes_value), label))
            bundles.append(key)
            axis_values.append(choices)
            continue
        if any(isinstance(v, dict) for v in values):
            raise SpecError(f"axes.{key}: mixes bundles (objects) and plain values")
        name = _option_name(key, "axes", takes_value)
        if name in fixed:
            raise SpecError(f"axes.{key}: also in fixed (an option is either fixed or an axis)")
        if len({json.dumps(v) for v in values}) != len(values):
            raise SpecError(f"axes.{key}: a value is listed twice")
        axis_values.append([({name: _check_value(v, f"axes.{key}[{i}]", name, takes_value)}, None)
                            for i, v in enumerate(values)])
    derive = spec.get("derive", {})
    if not isinstance(derive, dict):
        raise SpecError("derive: expected an object of option: \"expression\"")
    derived = []
    for key, text in derive.items():
        name = _option_name(key, "derive", takes_value)
        try:
            derived.append((key, name, Expression(text)))
        except ExpressionError as e:
            raise SpecError(f"derive.{key}: {e}") from None
    where = spec.get("where", [])
    if isinstance(where, str):
        where = [where]
    if not isinstance(where, list):
        raise SpecError("where: expected a list of conditions")
    conditions = []
    for i, text in enumerate(where):
        try:
            conditions.append(Expression(text))
        except ExpressionError as e:
            raise SpecError(f"where[{i}]: {e}") from None

    total = 1
    for values in axis_values:
        total *= len(values)
    if total > MAX_CELLS:
        raise SpecError(f"axes: {total} cells is more than {MAX_CELLS} (split the sweep)")
    cells, kept_by = [], [0] * len(conditions)
    for combination in itertools.product(*axis_values):
        options, labels = dict(fixed), {}
        origins = {name: f"fixed.{name}" for name in fixed}
        for axis, (chosen, label) in zip([*parameters, *axes], combination):
            for name, value in chosen.items():
                if name in options and options[name] != value:
                    raise SpecError(f"axes.{axis}: --{name} is also given by {origins[name]} for one cell "
                                    f"({options[name]!r} and {value!r})")
                options[name] = value
                origins[name] = f"axes.{axis}"
            if label is not None:
                labels[axis] = label
        names = {n.replace("-", "_"): v for n, v in options.items()}
        names.update({b.replace("-", "_"): labels[b] for b in bundles})
        for key, name, expression in derived:
            try:
                value = expression.evaluate(names)
            except ExpressionError as e:
                raise SpecError(f"derive.{key}: {e}") from None
            options[name] = _check_value(value, f"derive.{key}", name, takes_value)
            origins[name] = f"derive.{key}"
            names[name.replace("-", "_")] = value
        ok = True
        for i, condition in enumerate(conditions):
            try:
                keep = bool(condition.evaluate(names))
            except ExpressionError as e:
                raise SpecError(f"where[{i}]: {e}") from None
            if not keep:
                ok = False
                break
            kept_by[i] += 1
        if ok:
            cells.append(Cell(options, labels, origins))
    if not cells:
        if conditions:
            first = next((i for i, k in enumerate(kept_by) if k == 0), len(conditions) - 1)
            raise SpecError(f"where[{first}]: '{conditions[first].text}' leaves no cell of the grid")
        raise SpecError(f"{source}: no cell (give axes or fixed options)")
    return cells


def files_named(cell, base="."):
    """(option, sha256) of every file a cell's options name (a scene, a path, a sun path), so a
    changed file changes the cell's key."""
    out = []
    for name in ("scene", "path", "sun-path"):
        value = cell.options.get(name)
        if isinstance(value, str) and os.path.isfile(os.path.join(base, value)):
            with open(os.path.join(base, value), "rb") as f:
                out.append((name, hashlib.sha256(f.read()).hexdigest()[:16]))
    return out
