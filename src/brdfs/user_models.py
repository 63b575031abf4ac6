"""Models from outside the package: a user's module or ``.py`` file, and installed plugins.

A model is registered by :func:`brdfs.physics.models.register` when its module is imported; this
module imports such modules for the front doors that cannot (the command line's ``--import``, the
explorer):

* :func:`import_models` (``brdfs --import MODULE_OR_FILE``): a module name importable from the
  current directory or ``sys.path``, or the path of a ``.py`` file;
* :func:`load_entry_points`: every entry point of the group :data:`ENTRY_POINT_GROUP`
  (``brdfs.models``) of the installed distributions, whose object is a module that registers its
  models when imported, or a model class (registered here if it is not yet).

Both return the names of the models they registered and refuse with one ``ValueError`` line naming
the module, the file or the entry point.

>>> import brdfs.user_models as um
>>> um.import_models("no/such/file.py")
Traceback (most recent call last):
...
ValueError: --import 'no/such/file.py': no such file
"""
from __future__ import annotations

import importlib
import importlib.metadata
import importlib.util
import os
import sys
from pathlib import Path

#: The entry-point group through which an installed package registers its models.
ENTRY_POINT_GROUP = "brdfs.models"


def _registry() -> dict:
    from brdfs.physics.models import MODELS
    return MODELS


def _is_file_spec(spec: str) -> bool:
    return spec.endswith(".py") or os.sep in spec or (os.altsep is not None and os.altsep in spec)


def _module_name_for(path: Path) -> str:
    """The stem of the file (``my_model``) unless another module already has that name."""
    name = path.stem if path.stem.isidentifier() else "brdfs_user_model"
    taken = sys.modules.get(name)
    if taken is None or Path(getattr(taken, "__file__", "") or "").resolve() == path:
        return name
    suffix = 1
    while f"{name}_{suffix}" in sys.modules:
        suffix += 1
    return f"{name}_{suffix}"


def _import_file(spec: str):
    path = Path(spec).expanduser().resolve()
    if not path.is_file():
        raise ValueError(f"--import {spec!r}: no such file")
    name = _module_name_for(path)
    if name in sys.modules:                       # imported before: its models are registered
        return sys.modules[name]
    module_spec = importlib.util.spec_from_file_location(name, path)
    if module_spec is None or module_spec.loader is None:
        raise ValueError(f"--import {spec!r}: not a Python module")
    module = importlib.util.module_from_spec(module_spec)
    sys.modules[name] = module                    # dataclasses look the module up while it runs
    try:
        module_spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[name]
        raise
    return module


def _import_module(spec: str):
    cwd = os.getcwd()
    added = cwd not in sys.path
    if added:                                     # a module beside the user, as `python -m` finds it
        sys.path.insert(0, cwd)
    try:
        return importlib.import_module(spec)
    except ModuleNotFoundError as exc:
        if exc.name and spec.startswith(exc.name):
            raise ValueError(f"--import {spec!r}: no module named {exc.name!r} "
                             f"(give a module on sys.path or the path of a .py file)") from None
        raise
    finally:
        if added:
            sys.path.remove(cwd)


def _failure(what: str, exc: BaseException) -> ValueError:
    first = str(exc).splitlines()[0] if str(exc) else ""
    return ValueError(f"{what}: {type(exc).__name__}{': ' + first if first else ''}")


def import_models(spec: str) -> list[str]:
    """Import a module by name or a ``.py`` file by path; return the names of the models it registered.

    A module imported before is not imported again (its models are registered already): the answer
    is then the empty list.  Any error while importing is one ``ValueError`` line naming ``spec``.
    """
    spec = str(spec).strip()
    if not spec:
        raise ValueError("--import '': expected a module name or the path of a .py file")
    before = set(_registry())
    try:
        _import_file(spec) if _is_file_spec(spec) else _import_module(spec)
    except ValueError as exc:
        if str(exc).startswith("--import"):
            raise
        raise _failure(f"--import {spec!r}", exc) from None
    except Exception as exc:  # noqa: BLE001 -- a user's module may raise anything: one line, named
        raise _failure(f"--import {spec!r}", exc) from None
    return [name for name in _registry() if name not in before]


def _register_object(obj) -> None:
    from brdfs.physics.models import BRDF, register
    if isinstance(obj, type) and issubclass(obj, BRDF) and _registry().get(obj.name) is not obj:
        register(obj)


def load_entry_points(group: str = ENTRY_POINT_GROUP) -> list[str]:
    """Load every entry point of ``group``: a module (registering its models as it is imported) or a
    model class (registered here).  Returns the names of the models registered."""
    before = set(_registry())
    for entry in importlib.metadata.entry_points(group=group):
        try:
            _register_object(entry.load())
        except Exception as exc:  # noqa: BLE001 -- a broken plugin: one line naming it
            raise _failure(f"entry point {entry.name!r} ({entry.value}) of group {group!r}", exc) from None
    return [name for name in _registry() if name not in before]


__all__ = ["ENTRY_POINT_GROUP", "import_models", "load_entry_points"]
