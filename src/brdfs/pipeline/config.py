"""Load ``config.yaml`` outside Snakemake, validated as the workflow validates it.

The workflow (``workflow/rules/common.smk``) and in-process runs (tests,
``python -m brdfs.pipeline.regression``) validate through :func:`validate_config`: the JSON
schema of ``workflow/schemas/config.schema.yaml`` with default filling (the jsonschema FAQ
recipe Snakemake uses) and the model names taken from the model classes.
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
    jsonschema.ValidationError
        Naming the offending key and value.
    """
    _validator_filling_defaults(load_schema(schema_path)).validate(config)
    return config


def load_config(path: str | os.PathLike = CONFIG_YAML, schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """Read and validate a configuration file (default: the repository's ``config.yaml``)."""
    with open(path, encoding="utf-8") as stream:
        config = yaml.safe_load(stream)
    return validate_config(config, schema_path)


class ConfigError(ValueError):
    """A configuration that does not satisfy the schema; its message is one line."""


def check_config(config: dict, schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """:func:`validate_config`, with a failure reported as one line naming the key and the value.

    Raises
    ------
    ConfigError
        ``Error validating config file: config['a']['b'] = <value>: <reason>``.
    """
    try:
        return validate_config(config, schema_path)
    except jsonschema.ValidationError as error:
        key = "config" + "".join(f"[{p!r}]" for p in error.absolute_path)
        raise ConfigError(f"Error validating config file: {key} = {error.instance!r}: {error.message}") from None
