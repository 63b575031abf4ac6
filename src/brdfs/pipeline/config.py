"""Load ``config.yaml`` outside Snakemake, validated as the workflow validates it.

The workflow (``workflow/rules/common.smk``) and in-process runs (tests,
``python -m brdfs.pipeline.regression``) validate through :func:`validate_config`: the JSON
schema of ``workflow/schemas/config.schema.yaml`` with default filling (the jsonschema FAQ
recipe Snakemake uses) and what the schema takes from the model classes (:func:`load_schema`: the
model names; beside every ``model`` key, each registered model's parameters with its declared ranges
and choices; the accuracy map's families), so that a model registered with
:func:`brdfs.physics.models.register`, also one defined in a test, needs no edit of the schema. A bad
configuration raises :class:`ConfigError`, whose message is one line naming the key and its
value (``workflow/rules/common.smk`` prints it and stops before any rule runs). Before that, a string
where the schema wants a number is read as YAML 1.2 reads it (``1e-10``, which PyYAML leaves a
string; every scalar of a nested ``--config`` value, which Snakemake leaves a string), and NaN and
+-inf are refused in every numeric field.
"""

from __future__ import annotations

import copy
import functools
import math
import os
import re

import jsonschema
import yaml

from brdfs.pipeline.io import REPO_ROOT

CONFIG_YAML = REPO_ROOT / "config.yaml"
CONFIG_SCHEMA = REPO_ROOT / "workflow" / "schemas" / "config.schema.yaml"


NOT_FINITE = "must be a finite number"


def _validator_filling_defaults(schema: dict) -> jsonschema.protocols.Validator:
    """The schema's validator, filling defaults (the jsonschema FAQ recipe Snakemake uses), and
    refusing NaN and +-inf wherever the schema wants a number or an integer."""
    base = jsonschema.Draft202012Validator
    validate_properties = base.VALIDATORS["properties"]
    validate_type = base.VALIDATORS["type"]

    def set_defaults(validator, properties, instance, subschema):
        for name, property_schema in properties.items() if isinstance(instance, dict) else ():
            if "default" in property_schema:
                instance.setdefault(name, property_schema["default"])
        yield from validate_properties(validator, properties, instance, subschema)

    def finite_type(validator, types, instance, subschema):
        numeric = {"number", "integer"} & set([types] if isinstance(types, str) else types)
        if numeric and isinstance(instance, float) and not math.isfinite(instance):
            yield jsonschema.ValidationError(NOT_FINITE, validator="finite", validator_value=True)
            return
        yield from validate_type(validator, types, instance, subschema)

    return jsonschema.validators.extend(base, {"properties": set_defaults, "type": finite_type})(schema)


# --- strings that are YAML 1.2 scalars -----------------------------------------------------------
# PyYAML (Snakemake's `configfile:`, yaml.safe_load) follows YAML 1.1, which reads `1e-10` as a
# string; `--config` values nested in a mapping or list are parsed by Snakemake with YAML's
# BaseLoader, every scalar a string (`tolerance={rtol: 1.0e-8}` gives {"rtol": "1.0e-8"}), and
# merged by it into the file's sections (a deep merge: the keys not given keep the file's values).
# Where the schema wants a number, an integer, a boolean or null and finds a string, the string is
# read as YAML 1.2 (core schema) reads it, in place, before the validation proper
# (:func:`_read_yaml12_strings`): the one place such strings become values. A string the schema
# wants as a string (a label, `max`) stays a string.

_YAML12 = [  # (regex, conversion): the plain scalars of the YAML 1.2 core schema
    (r"null|Null|NULL|~", lambda s: None),
    (r"true|True|TRUE", lambda s: True),
    (r"false|False|FALSE", lambda s: False),
    (r"[-+]?[0-9]+", int),
    (r"0o[0-7]+", lambda s: int(s[2:], 8)),
    (r"0x[0-9a-fA-F]+", lambda s: int(s[2:], 16)),
    (r"[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?", float),
    (r"[-+]?(\.inf|\.Inf|\.INF)", lambda s: float(s.replace(".", "", 1))),
    (r"\.nan|\.NaN|\.NAN", lambda s: math.nan),
]
_YAML12 = [(re.compile(pattern), convert) for pattern, convert in _YAML12]


def yaml12_scalar(text: str):
    """``text`` as a plain YAML 1.2 scalar: None, a bool, an int, a float, or ``text`` itself."""
    for pattern, convert in _YAML12:
        if pattern.fullmatch(text):
            return convert(text)
    return text


def _is_of(value, kind: str) -> bool:
    if kind == "null":
        return value is None
    if kind == "boolean":
        return isinstance(value, bool)
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return False
    return kind in ("number", "integer")   # an integer field's 2.5 is reported as the number it is


def _type_errors(errors):
    for error in errors:
        if error.validator == "type":
            yield error
        yield from _type_errors(error.context or ())


def _read_yaml12_strings(validator, config: dict) -> list:
    """Replace, in ``config``, every string where the schema wants a number, an integer, a boolean
    or null by its YAML 1.2 reading, if that reading is of a wanted type (also inside ``oneOf``).
    Returns the validation errors that remain (in jsonschema's order; none: valid)."""
    for _ in range(100):   # each pass reads every string the previous passes exposed
        changed = False
        errors = list(validator.iter_errors(config))
        for error in _type_errors(errors):
            path = list(error.absolute_path)
            if not isinstance(error.instance, str) or not path:
                continue
            wanted = [error.validator_value] if isinstance(error.validator_value, str) else error.validator_value
            value = yaml12_scalar(error.instance)
            if value is error.instance or not any(_is_of(value, kind) for kind in wanted):
                continue
            node = config
            for part in path[:-1]:
                node = node[part]
            if node[path[-1]] is error.instance:
                node[path[-1]] = value
                changed = True
        if not changed:
            return errors
    return errors


def _first_non_finite(node, path=()):
    """The path and value of the first NaN or +-inf anywhere in ``node``, or None."""
    if isinstance(node, float) and not math.isfinite(node):
        return path, node
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, value in items:
        if (found := _first_non_finite(value, (*path, key))) is not None:
            return found
    return None


class ConfigError(ValueError):
    """An invalid configuration; the message is one line naming the key and the value."""


def _key(path) -> str:
    """``grazing.fig_2_1_models[0].model`` from a jsonschema path."""
    out = ""
    for part in path:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out or "(top level)"


def _short(value, limit: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


_REASONS = {
    "type": lambda v: f"must be of type {v}",
    "minimum": lambda v: f"must be >= {v}",
    "exclusiveMinimum": lambda v: f"must be > {v}",
    "maximum": lambda v: f"must be <= {v}",
    "exclusiveMaximum": lambda v: f"must be < {v}",
    "enum": lambda v: "must be one of " + ", ".join(map(str, v)),
    "const": lambda v: f"must be {v}",
    "pattern": lambda v: f"must match {v}",
    "minItems": lambda v: "must not be empty" if v == 1 else f"needs at least {v} items",
}


def describe_error(error: jsonschema.ValidationError) -> str:
    """One line naming the offending key and its value, and what the schema wants."""
    path = list(error.absolute_path)
    value, reason = error.instance, None
    if error.validator == "additionalProperties" and isinstance(value, dict):
        unknown = sorted(set(value) - set(error.schema.get("properties", {})))
        if unknown:
            path.append(unknown[0])
            value, reason = value[unknown[0]], "unknown key"
    elif error.validator == "required" and isinstance(value, dict):
        missing = [k for k in error.validator_value if k not in value]
        return f"Error validating config file: {_key([*path, missing[0]])} is missing (required)"
    elif error.validator in _REASONS:
        reason = _REASONS[error.validator](error.validator_value)
    if reason is None:
        reason = error.message.splitlines()[0]
        reason = reason if len(reason) <= 100 else reason[:97] + "..."
    return f"Error validating config file: {_key(path)} = {_short(value)}: {reason}"


MODEL_REF = "#/$defs/model_name"


def _parameter_schema(classes, key: str) -> dict | None:
    """The schema of parameter ``key`` from the models that declare it: the union of their choices
    (:attr:`BRDF.param_choices`) or the hull of their ranges (:attr:`BRDF.param_ranges`); None if
    none declares it (e.g. a callable)."""
    choices = [c for cls in classes for c in cls.param_choices.get(key, ())]
    names = ", ".join(cls.name for cls in classes)
    if choices:
        return {"description": f"Parameter {key} of {names} (the models' declared choices).",
                "enum": list(dict.fromkeys(choices))}
    ranges = [cls.param_ranges[key] for cls in classes if key in cls.param_ranges]
    if not ranges:
        return None
    node = {"description": f"Parameter {key} of {names} (the models' declared range).", "type": "number"}
    lo, hi = min(r.lo for r in ranges), max(r.hi for r in ranges)
    if lo > float("-inf"):
        node["exclusiveMinimum" if all(r.lo_open for r in ranges if r.lo == lo) else "minimum"] = lo
    if hi < float("inf"):
        node["exclusiveMaximum" if all(r.hi_open for r in ranges if r.hi == hi) else "maximum"] = hi
    return node


def _model_entries(node):
    """Every object schema under ``node`` that names a model (a ``model`` property referring to
    ``$defs/model_name``): where a model's parameters stand beside its name."""
    if isinstance(node, dict):
        props = node.get("properties")
        if isinstance(props, dict) and props.get("model", {}).get("$ref") == MODEL_REF:
            yield props
        for value in node.values():
            yield from _model_entries(value)
    elif isinstance(node, list):
        for value in node:
            yield from _model_entries(value)


def _fill_from_models(schema: dict, models: dict) -> None:
    """What the schema takes from the model classes, so that a registered model (also one defined in
    a test) needs no edit of the schema: the enum of model names; beside every ``model`` key, each
    registered model's parameters the schema does not describe yet (from their declared ranges and
    choices); and the accuracy map's families (:attr:`BRDF.accuracy_families`)."""
    schema.setdefault("$defs", {}).setdefault("model_name", {"type": "string"})["enum"] = sorted(models)
    by_key: dict[str, list] = {}
    for cls in models.values():
        for key in cls.param_columns():
            by_key.setdefault(key, []).append(cls)
    for props in _model_entries(schema):
        for key, classes in by_key.items():
            if key not in props and (node := _parameter_schema(classes, key)) is not None:
                props[key] = node
    grids = schema.get("properties", {}).get("accuracy_map", {}).get("properties", {})
    for grid in ("reduced", "full"):
        families = grids.get(grid, {}).get("properties", {}).get("families", {}).get("properties")
        if families is None:
            continue
        for cls in models.values():
            for family, (key, _fixed) in cls.accuracy_families.items():
                if family not in families:
                    items = _parameter_schema([cls], key) or {"description": f"Values of {key}.", "type": "number"}
                    families[family] = {"description": f"Values of {key} of the family {family} ({cls.name}).",
                                        "type": "array", "minItems": 1, "items": items}


def load_schema(schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """The config schema, with what it takes from the model classes filled in (:func:`_fill_from_models`)."""
    from brdfs.physics.models import MODELS

    path = os.fspath(schema_path)
    schema = copy.deepcopy(_read_schema(path, os.stat(path).st_mtime_ns))
    _fill_from_models(schema, MODELS)
    return schema


@functools.lru_cache(maxsize=8)
def _read_schema(path: str, mtime_ns: int) -> dict:
    """The schema file as parsed (cached while the file is unchanged; callers copy it)."""
    with open(path, encoding="utf-8") as stream:
        return yaml.safe_load(stream)


def validate_config(config: dict, schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """Validate ``config`` in place, filling the schema's defaults.

    Strings where the schema wants a number (``1e-10`` from PyYAML, every scalar of a nested
    ``--config`` value) are first read as YAML 1.2 reads them; NaN and +-inf are refused in every
    numeric field.

    Raises
    ------
    ConfigError
        One line naming the offending key and value (the jsonschema error is its ``__cause__``).
    """
    schema = load_schema(schema_path)
    if not isinstance(config, dict):
        raise ConfigError(f"Error validating config file: (top level) = {_short(config)}: must be a mapping")
    errors = _read_yaml12_strings(_validator_filling_defaults(schema), config)
    if errors:
        raise ConfigError(describe_error(errors[0])) from errors[0]
    # Every number the schema types is finite (above); this holds any other NaN or inf too.
    if (found := _first_non_finite(config)) is not None:
        raise ConfigError(f"Error validating config file: {_key(found[0])} = {_short(found[1])}: {NOT_FINITE}")
    return config


def load_config(path: str | os.PathLike = CONFIG_YAML, schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """Read and validate a configuration file (default: the repository's ``config.yaml``)."""
    with open(path, encoding="utf-8") as stream:
        config = yaml.safe_load(stream)
    return validate_config(config, schema_path)


def check_config(config: dict, schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """:func:`validate_config` (kept for its callers): a failure is one line naming the key and the value.

    Raises
    ------
    ConfigError
        ``Error validating config file: a.b[0].c = <value>: <reason>``.
    """
    return validate_config(config, schema_path)
