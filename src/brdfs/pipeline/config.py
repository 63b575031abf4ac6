"""Load ``config.yaml`` outside Snakemake, validated as the workflow validates it.

The Snakefile validates with ``snakemake.utils.validate``; this module applies
the same JSON schema with the same default filling (the jsonschema FAQ recipe
Snakemake uses), so in-process runs (tests, ``python -m brdfs.pipeline.regression``) see
the same configuration as the pipeline.
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


def validate_config(config: dict, schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """Validate ``config`` in place, filling the schema's defaults.

    Raises
    ------
    jsonschema.ValidationError
        Naming the offending key and value.
    """
    with open(schema_path, encoding="utf-8") as stream:
        schema = yaml.safe_load(stream)
    _validator_filling_defaults(schema).validate(config)
    return config


def load_config(path: str | os.PathLike = CONFIG_YAML, schema_path: str | os.PathLike = CONFIG_SCHEMA) -> dict:
    """Read and validate a configuration file (default: the repository's ``config.yaml``)."""
    with open(path, encoding="utf-8") as stream:
        config = yaml.safe_load(stream)
    return validate_config(config, schema_path)
