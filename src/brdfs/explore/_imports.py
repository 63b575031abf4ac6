"""``brdfs explore --import MODULE_OR_FILE``: the user's own models, registered by importing them.

THE SEAM FOR ISSUE 43.  Issue 43 adds a global ``brdfs --import`` and a public loader module; when it
lands, :func:`import_models` becomes a call of that loader and nothing else of the explorer changes.
Until then this is the whole loader: a dotted module name is imported, a path to a ``.py`` file is
executed as a module of its own; either registers its models with
:func:`brdfs.physics.models.register` as it is imported.
"""
from __future__ import annotations

import importlib
import importlib.util
import sys
from pathlib import Path


def import_models(spec: str) -> list[str]:
    """Import ``spec`` (a module name, or a path to a Python file) and return the names of the models
    it registered.  Raises ``ValueError`` with one line naming ``spec`` when it cannot be imported."""
    from brdfs.physics.models import MODELS
    before = set(MODELS)
    path = Path(spec)
    try:
        if spec.endswith(".py") or path.is_file():
            if not path.is_file():
                raise ValueError(f"--import {spec!r}: no such file")
            name = f"brdfs_user_{path.stem}"
            module_spec = importlib.util.spec_from_file_location(name, path)
            module = importlib.util.module_from_spec(module_spec)
            sys.modules[name] = module
            module_spec.loader.exec_module(module)
        else:
            importlib.import_module(spec)
    except ValueError:
        raise
    except Exception as err:                       # the user's code: any error, reported in one line
        raise ValueError(f"--import {spec!r}: {type(err).__name__}: {err}") from None
    return [name for name in MODELS if name not in before]
