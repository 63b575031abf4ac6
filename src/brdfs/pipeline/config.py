"""Load ``config.yaml`` outside Snakemake, validated as the workflow validates it.

The workflow (``workflow/rules/common.smk``) and in-process runs (tests,
``python -m brdfs.pipeline.regression``) validate through :func:`validate_config`: the JSON
schema of ``workflow/schemas/config.schema.yaml`` with default filling (the jsonschema FAQ
recipe Snakemake uses) and the model names taken from the model classes. A bad
configuration raises :class:`ConfigError`, whose message is one line naming the key and its
value (``workflow/rules/common.smk`` prints it and stops before any rule runs).
"""

from __future__ import annotations

import os

import jsonschema
import yaml

from brdfs.pipeline.io import REPO_ROOT

CONFIG_YAML = REPO_ROOT / "config.yaml"
CONFIG_SCHEMA = REPO_ROOT / "workflow" / "schemas" / "config.schema.yaml"


def _validator_filling_defaults(schema: dict) -> jsonschema.protocols.Validator:
    base = jsonschema.Draft202012Validator
    validate_properties = base.VALIDATORS["properties"]

    def set_defaults(validator, properties, instance, subschema):
        for name, property_schema in properties.items():
            if "default" in property_schema:
                instance.setdefault(name, property_schema["default"])
        yield from validate_properties(validator, properties, instance, subschema)

    return jsonschema.validators.extend(base, {"properties": set_defaults})(schema)


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


def load_schema(schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """The config schema, with the enum of model names filled in from the model classes."""
    from brdfs.physics.models import MODELS

    with open(schema_path, encoding="utf-8") as stream:
        schema = yaml.safe_load(stream)
    schema.setdefault("$defs", {}).setdefault("model_name", {"type": "string"})["enum"] = sorted(MODELS)
    return schema


def validate_config(config: dict, schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """Validate ``config`` in place, filling the schema's defaults.

    Raises
    ------
    ConfigError
        One line naming the offending key and value (the jsonschema error is its ``__cause__``).
    """
    schema = load_schema(schema_path)
    if not isinstance(config, dict):
        raise ConfigError(f"Error validating config file: (top level) = {_short(config)}: must be a mapping")
    try:
        _validator_filling_defaults(schema).validate(config)
    except jsonschema.ValidationError as error:
        raise ConfigError(describe_error(error)) from error
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
