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
import io
import math
import os
import re

import jsonschema
import yaml

from brdfs.pipeline.io import REPO_ROOT

CONFIG_YAML = REPO_ROOT / "config.yaml"
CONFIG_SCHEMA = REPO_ROOT / "workflow" / "schemas" / "config.schema.yaml"


NOT_FINITE = "must be a finite number"


def _is_integer(checker, instance) -> bool:
    """An int and only an int: 121.0 is no grid size (JSON Schema's own "integer" admits it)."""
    return isinstance(instance, int) and not isinstance(instance, bool)


def _validator_filling_defaults(schema: dict) -> jsonschema.protocols.Validator:
    """The schema's validator, filling defaults (the jsonschema FAQ recipe Snakemake uses),
    refusing NaN and +-inf wherever the schema wants a number or an integer, an integer that is a
    float, and what the keywords of :data:`MEANING_KEYWORDS` say."""
    base = jsonschema.Draft202012Validator
    validate_properties = base.VALIDATORS["properties"]
    validate_type = base.VALIDATORS["type"]
    checker = base.TYPE_CHECKER.redefine("integer", _is_integer)

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

    keywords = {"properties": set_defaults, "type": finite_type, **MEANING_KEYWORDS}
    return jsonschema.validators.extend(base, keywords, type_checker=checker)(schema)


# --- what the schema says beyond JSON Schema ----------------------------------------------------
# Keywords of config.schema.yaml that say what a job would otherwise reject only when it runs. Each
# yields an error at the offending key (its path below the object the keyword stands on).

def _error(path, value, reason: str) -> jsonschema.ValidationError:
    return jsonschema.ValidationError(reason, path=list(path), instance=value)


def _increasing(validator, wanted, instance, schema):
    """``increasing: true``: an array whose every item is larger than the one before."""
    if wanted and isinstance(instance, list):
        for k in range(1, len(instance)):
            if _is_number(instance[k]) and _is_number(instance[k - 1]) and not instance[k] > instance[k - 1]:
                yield _error([k], instance[k], f"must be larger than the item before it ({instance[k - 1]!r})")
                return


def _ordered(validator, pairs, instance, schema):
    """``ordered: [[lo, hi], ...]``: the value of key ``lo`` below that of key ``hi``."""
    for lo, hi in pairs if isinstance(instance, dict) else ():
        a, b = instance.get(lo), instance.get(hi)
        if _is_number(a) and _is_number(b) and not a < b:
            yield _error([hi], b, f"must be larger than {lo} ({a!r})")


def _multiples_of(validator, spec, instance, schema):
    """``multiplesOf: {divisor: key, fields: [...]}``: every integer of the fields (an integer, a list
    of them, or a mapping of either) is a multiple of the value of key ``divisor``."""
    divisor = instance.get(spec["divisor"]) if isinstance(instance, dict) else None
    if not _is_integer(None, divisor) or divisor <= 0:
        return
    for field in spec["fields"]:
        for path, value in _integers(instance.get(field), [field]):
            if value % divisor:
                yield _error(path, value, f"must be a multiple of {spec['divisor']} ({divisor})")
                return


def _integers(node, path):
    if _is_integer(None, node):
        yield path, node
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, value in items:
        yield from _integers(value, [*path, key])


def _sum_at_most(validator, spec, instance, schema):
    """``sumAtMost: {fields: [...], limit: x}``: the fields' values (the largest item of a list) add up
    to at most ``limit`` (e.g. a plastic's a_s + max(r, g, b) <= 1: it reflects no more than it receives)."""
    if not isinstance(instance, dict) or not all(f in instance for f in spec["fields"]):
        return
    parts = [max(v) if isinstance(v, list) and v else v for v in (instance[f] for f in spec["fields"])]
    if all(_is_number(p) for p in parts) and sum(parts) > spec["limit"]:
        names = " + ".join(f"max({f})" if isinstance(instance[f], list) else f for f in spec["fields"])
        yield _error([spec["fields"][0]], instance[spec["fields"][0]],
                     f"{names} = {sum(parts):g} must be <= {spec['limit']:g}")


def _datasets_of(validator, spec, instance, schema):
    """``datasetsOf``: optical-constants data sets (:data:`brdfs.physics.optical_constants.DATASETS`)
    of a metal. ``{field: metal}``: the field (a name or a list of them) names data sets of ``metal``,
    or of the metal the object's key ``<key>`` names when ``metal`` is ``$<key>``; ``$keys``: each
    key is a metal, its value a data set of it."""
    from brdfs.physics.optical_constants import DATASETS

    if not isinstance(instance, dict):
        return
    pairs = ([(k, k) for k in instance] if spec == "$keys" else
             [(f, instance.get(m[1:]) if m.startswith("$") else m) for f, m in spec.items()])
    for field, metal in pairs:
        if field not in instance or metal not in DATASETS:
            continue
        names = instance[field]
        for path, name in ([([field, k], v) for k, v in enumerate(names)] if isinstance(names, list)
                           else [([field], names)]):
            if name not in DATASETS[metal]:
                yield _error(path, name, f"no data set of {metal}; known: {', '.join(DATASETS[metal])}")


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


MEANING_KEYWORDS = {"increasing": _increasing, "ordered": _ordered, "multiplesOf": _multiples_of,
                    "sumAtMost": _sum_at_most, "datasetsOf": _datasets_of}


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


#: Keys that moved, by their old path: an old config gets one line naming the new place.
MOVED_KEYS = {"renders.clamp": "renders.<preset>.clamp (a clamp per preset)"}


def _closest(key: str, known: list) -> str:
    """What an unknown ``key`` may have meant, in a few words: the nearest of ``known``, else a few of them."""
    import difflib

    near = difflib.get_close_matches(key, known, n=1, cutoff=0.8)
    return f"did you mean {near[0]}?" if near else f"must be one of {', '.join(known[:3])}, ... ({len(known)} names)"


def describe_error(error: jsonschema.ValidationError) -> str:
    """One line naming the offending key and its value, and what the schema wants."""
    path = list(error.absolute_path)
    value, reason = error.instance, None
    if error.validator == "additionalProperties" and isinstance(value, dict):
        unknown = sorted(set(value) - set(error.schema.get("properties", {})))
        if unknown:
            path.append(unknown[0])
            moved = MOVED_KEYS.get(_key(path))
            value, reason = value[unknown[0]], "unknown key" + (f"; it moved to {moved}" if moved else "")
    elif error.validator == "required" and isinstance(value, dict):
        missing = [k for k in error.validator_value if k not in value] or [error.message.split("'")[1]]
        return f"Error validating config file: {_key([*path, missing[0]])} is missing (required)"
    elif "propertyNames" in error.absolute_schema_path:     # a key the mapping does not take
        names = error.validator_value if error.validator == "enum" else []
        hint = _closest(str(value), names) if names else "the keys are names (strings)"
        return f"Error validating config file: {_key([*path, str(value)])}: unknown key; {hint}"
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


def _fill_render_figures(schema: dict) -> None:
    """The enum of ``$defs/render_figure`` from the registry: the artifacts that read the renders
    section (:attr:`.registry.Artifact.renders`), so that a new render figure needs no edit of the schema."""
    from brdfs.pipeline import registry

    names = sorted(name for name, artifact in registry.artifacts().items() if artifact.renders)
    schema.setdefault("$defs", {}).setdefault("render_figure", {"type": "string"})["enum"] = names


def load_schema(schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """The config schema, with what it takes from the model classes (:func:`_fill_from_models`) and
    the registry's render figures (:func:`_fill_render_figures`) filled in."""
    from brdfs.physics.models import MODELS

    path = os.fspath(schema_path)
    schema = copy.deepcopy(_read_schema(path, os.stat(path).st_mtime_ns))
    _fill_from_models(schema, MODELS)
    _fill_render_figures(schema)
    return schema


@functools.lru_cache(maxsize=8)
def _read_schema(path: str, mtime_ns: int) -> dict:
    """The schema file as parsed (cached while the file is unchanged; callers copy it): by libyaml's
    parser where PyYAML has it (the same safe construction as ``yaml.safe_load``, 3x faster on the schema;
    PyYAML's own parser where the text has a tab: :func:`_loader_for`)."""
    with open(path, encoding="utf-8") as stream:
        text = stream.read()
    loader = _loader_for(text, _FAST_SAFE_LOADER, yaml.SafeLoader)
    return yaml.load(_named(text, path), Loader=loader)  # noqa: S506 (a SafeLoader)


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
    _check_model_entries(config)
    _check_render_figures(config)
    return config


def _check_render_figures(config: dict) -> None:
    """``renders.<preset>``'s per-figure settings mean something for their figure (its ``panels`` read
    with this config, :func:`brdfs.artifacts._render_figures.figure_facts`): the ways of spending
    samples exclude each other (``crop_spp``, ``object_spp``, ``adaptive``: one of them); none is given
    to a figure whose panels ignore it (noise-free panels at their own spp; a clamp where every panel is
    direct light only); a ``figure_spp`` list has one entry per panel; an ``object_spp`` figure's labels
    are its objects' with each count at least the figure's ``spp`` (every panel's, where ``figure_spp``
    lists one per panel), so that the listed object has that count in every panel."""
    renders = config.get("renders") or {}
    presets = [(preset, settings) for preset, settings in renders.items()
               if isinstance(settings, dict) and {"spp", "passes"} <= set(settings)]
    if not presets:
        return
    from brdfs.artifacts._render_figures import SAMPLING_SETTINGS, figure_facts

    for preset, settings in presets:
        ways = {way: {name for name, value in (settings.get(way) or {}).items() if value}
                for way in ("crop_spp", "object_spp", "adaptive")}
        for name in sorted(set().union(*ways.values())):
            given = [way for way in ways if name in ways[way]]
            if len(given) > 1:
                raise ConfigError(f"Error validating config file: renders.{preset}.{given[-1]}.{name}: the figure also "
                                  f"has renders.{preset}.{given[0]}.{name} = {_short(settings[given[0]][name])}; give one of them")
    given = [(preset, settings, setting, name, value) for preset, settings in presets
             for setting in (*SAMPLING_SETTINGS, "clamp") for name, value in (settings.get(setting) or {}).items() if value]
    if not given:
        return
    facts = {name: figure_facts(name, config) for name in dict.fromkeys(g[3] for g in given)}
    for preset, settings, setting, name, value in given:
        path, fact = f"renders.{preset}.{setting}.{name}", facts[name]
        if (why := fact.ignores(setting)) is not None:
            raise ConfigError(f"Error validating config file: {path} = {_short(value)}: {name} does not use it: {why}")
        if setting == "figure_spp" and isinstance(value, list) and len(value) != fact.panels:
            raise ConfigError(f"Error validating config file: {path} = {_short(value)}: needs one entry per panel "
                              f"({fact.panels} panel{'s' * (fact.panels != 1)})")
        if setting != "object_spp":
            continue
        film = max(_as_list(settings.get("figure_spp", {}).get(name, settings["spp"])))
        for label, spp in value.items():
            if label not in fact.labels:
                raise ConfigError(f"Error validating config file: {path}.{label} = {spp!r}: not an object of {name} "
                                  f"(its objects: {', '.join(map(repr, fact.labels))})")
            if spp < film:
                raise ConfigError(f"Error validating config file: {path}.{label} = {spp!r}: below the figure's spp "
                                  f"({film}); an object's window never lowers the film's count")


def _as_list(value) -> list:
    return list(value) if isinstance(value, (list, tuple)) else [value]


#: Keys of a model entry (``{model: phong, n: 150, theta_deg: 60}``) that are not the model's parameters.
NOT_PARAMETERS = ("model", "theta_deg", "label")


def _model_entries_of(node, path=()):
    """The path and value of every mapping in ``node`` that names a model (a ``model`` key)."""
    if isinstance(node, dict) and isinstance(node.get("model"), str):
        yield path, node
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, value in items:
        yield from _model_entries_of(value, (*path, key))


def _check_model_entries(config: dict) -> None:
    """Every model entry as :func:`brdfs.model` checks its call: the model's own parameter names
    (another model's parameter is refused), its required parameters, and each value in the range or
    among the choices its class declares (the schema admits any registered model's parameter)."""
    from brdfs.numerics.arguments import ArgumentError, check_model_call

    for path, entry in _model_entries_of(config):
        params = {k: v for k, v in entry.items() if k not in NOT_PARAMETERS}
        try:
            check_model_call(entry["model"], params)
        except ArgumentError as error:
            # "model('phong'): m = 0.1: unknown parameter; ..." -> "<path>.m = 0.1: unknown parameter; ..."
            detail = str(error).split(": ", 1)[1]
            raise ConfigError(f"Error validating config file: {_key(path)}.{detail} (model {entry['model']})") from None


# --- reading a configuration file ----------------------------------------------------------------

#: PyYAML's safe loader on libyaml's parser (C) where PyYAML was built with it: the same nodes, marks
#: and safe construction (Python) as ``yaml.SafeLoader``, parsed 3-5x faster.
_FAST_SAFE_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


class _RefusingDuplicateKeys:
    """A loader mixin refusing a key given twice in one mapping, which PyYAML reads as "the last one wins"."""

    def construct_mapping(self, node, deep=False):
        lines: dict = {}
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=True)
            line = key_node.start_mark.line + 1
            if isinstance(key, (str, int, float, bool)) and key in lines:
                raise ConfigError(f"{key_node.start_mark.name}:{line}: duplicate key {key!r} "
                                  f"(lines {lines[key]} and {line}); give each key once")
            lines.setdefault(key, line) if isinstance(key, (str, int, float, bool)) else None
        return super().construct_mapping(node, deep)


class _StrictLoader(_RefusingDuplicateKeys, yaml.SafeLoader):
    """PyYAML's safe loader (what Snakemake reads config.yaml with), refusing duplicate keys: its
    syntax errors say what they found (``found character '\\t'``, ``found undefined alias 'x'``)."""


class _FastStrictLoader(_RefusingDuplicateKeys, _FAST_SAFE_LOADER):
    """:class:`_StrictLoader` on libyaml's parser: the same values and duplicate-key errors; a syntax
    error is read again by :class:`_StrictLoader` for its message (libyaml's says less)."""


def _loader_for(text: str, fast: type, pure: type) -> type:
    """``fast`` (on libyaml's parser) unless ``text`` has a tab: libyaml takes a tab as a separator
    (``a:\t1``, ``[1,\t2]``, ``a\t: 1``, ``1\t# c``) where PyYAML, and so Snakemake, refuses it."""
    return pure if "\t" in text else fast


def _load_strictly(path: str | os.PathLike) -> object:
    """The YAML document of ``path`` (read once: a FIFO or ``/dev/fd/N`` has one reading) by
    :class:`_FastStrictLoader`, or by :class:`_StrictLoader` where the text has a tab; a YAML error is
    the one :class:`_StrictLoader` raises (or its value, should PyYAML's own parser accept what libyaml
    refused)."""
    with open(path, encoding="utf-8") as stream:
        text = stream.read()
    loader = _loader_for(text, _FastStrictLoader, _StrictLoader)
    try:
        return yaml.load(_named(text, path), Loader=loader)  # noqa: S506 (a SafeLoader)
    except yaml.YAMLError:
        if loader is _StrictLoader:
            raise
        return yaml.load(_named(text, path), Loader=_StrictLoader)  # noqa: S506 (a SafeLoader)


def _named(text: str, path: str | os.PathLike) -> io.StringIO:
    """``text`` as a stream named ``path``, the name the loaders' marks (and error messages) give."""
    stream = io.StringIO(text)
    stream.name = os.fspath(path)
    return stream


def read_config_file(path: str | os.PathLike) -> dict:
    """The mapping of a YAML configuration file, as Snakemake reads it, or a :class:`ConfigError`
    whose one line names the file and what is wrong: not found, a YAML syntax error (with its line
    and column), a duplicate key (with both lines), empty, or not a mapping of sections."""
    try:
        config = _load_strictly(path)
    except (FileNotFoundError, IsADirectoryError, PermissionError) as error:
        raise ConfigError(f"config file {os.fspath(path)}: cannot be read ({error.strerror})") from None
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        where = f"{os.fspath(path)}:{mark.line + 1}:{mark.column + 1}" if mark else os.fspath(path)
        context = error.context_mark
        opened = (f" ({error.context} at line {context.line + 1}, column {context.column + 1})"
                  if error.context and context and context is not mark else "")
        raise ConfigError(f"{where}: YAML syntax error: {error.problem or error.context}{opened}") from None
    except yaml.YAMLError as error:
        raise ConfigError(f"{os.fspath(path)}: YAML syntax error: {str(error).splitlines()[0]}") from None
    if config is None:
        raise ConfigError(f"config file {os.fspath(path)} is empty: it must map each section to its values")
    if not isinstance(config, dict):
        raise ConfigError(f"config file {os.fspath(path)} is a {type(config).__name__}, not a mapping of "
                          "sections to their values")
    return config


def load_config(path: str | os.PathLike = CONFIG_YAML, schema_path: str | os.PathLike = CONFIG_SCHEMA,
                overrides: tuple[str | os.PathLike, ...] = ()) -> dict:
    """Read and validate a configuration file (default: the repository's ``config.yaml``), each of
    ``overrides`` deep-merged into it as Snakemake merges ``--configfile`` files."""
    config = read_config_file(path)
    for override in overrides:
        _deep_update(config, read_config_file(override))
    return validate_config(config, schema_path)


def _deep_update(config: dict, other: dict) -> None:
    """Snakemake's merge of a ``--configfile`` into the config (snakemake.utils.update_config)."""
    for key, value in other.items():
        if isinstance(value, dict) and isinstance(config.get(key), dict):
            _deep_update(config[key], value)
        else:
            config[key] = value


def main(argv: list[str] | None = None) -> int:
    """``python -m brdfs.pipeline.config [FILE ...]``: validate config.yaml with the files merged in
    (``make all CONFIGFILE=...`` runs this first); one line and exit status 1 when it is invalid."""
    import sys

    files = list(sys.argv[1:] if argv is None else argv)
    try:
        load_config(overrides=tuple(files))
    except ConfigError as error:
        print(error, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())


def check_config(config: dict, schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """:func:`validate_config` (kept for its callers): a failure is one line naming the key and the value.

    Raises
    ------
    ConfigError
        ``Error validating config file: a.b[0].c = <value>: <reason>``.
    """
    return validate_config(config, schema_path)
