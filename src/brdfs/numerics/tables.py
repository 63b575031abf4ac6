"""The model factory above the physics layer: models that need tables receive them when they are built.

A model of :mod:`brdfs.physics.models` that divides by or subtracts an albedo names the tables it
needs (:meth:`~brdfs.physics.models.base.BRDF.table_requests`: field -> a
:class:`~brdfs.physics.tables.TableRequest`), and the physics layer computes none (built there without
its table, such a model raises :class:`~brdfs.physics.tables.MissingTable`).  Here each request is
tabulated by the engine (:func:`brdfs.numerics.pumping.tabulate_albedo`), once per process (cached by
the request, a value), and handed to the model:

* :func:`build` (the package's front door :func:`brdfs.model`): a model by its name, e.g.
  ``build("ggx", alpha=0.3, compensation="kulla_conty")`` (Kulla–Conty's E table);
* :func:`pump`: a model pumped once (sec. 2.3, :class:`brdfs.physics.models.pumped.Pumped`) with the
  albedo table of the model it pumps;
* :func:`seed`: put a table read from an artifact's CSV into the cache, so that a figure reuses the
  table an upstream artifact computed instead of computing it again.
"""
from __future__ import annotations

import numpy as np

from brdfs.numerics.arguments import ArgumentError, check_model_call
from brdfs.numerics.pumping import tabulate_albedo
from brdfs.physics.models import MODELS
from brdfs.physics.models import model as plain_model
from brdfs.physics.models.pumped import Pumped
from brdfs.physics.tables import AlbedoTable, TableRequest

#: Tables by request: computed once per process, or seeded (:func:`seed`) from an artifact's CSV.
_TABLES: dict[TableRequest, AlbedoTable] = {}


def tabulate(request: TableRequest) -> AlbedoTable:
    """The table of ``request`` (:func:`brdfs.numerics.pumping.tabulate_albedo`), cached."""
    if request not in _TABLES:
        _TABLES[request] = tabulate_albedo(request.model, request.edges, target_rtol=request.target_rtol,
                                           engine_rtol=request.engine_rtol, degree=request.degree,
                                           model_rtol=request.model_rtol)
    return _TABLES[request]


def seed(request: TableRequest, table: AlbedoTable) -> None:
    """Use ``table`` (e.g. read back from the CSV of the artifact that computed it) for ``request``."""
    _TABLES[request] = table


def build(name: str, **params):
    """The model ``name`` with ``params`` and every table it needs (:func:`tabulate`), e.g.
    ``build("ggx", alpha=0.5, compensation="kulla_conty")``; a model that needs none is built as
    :func:`brdfs.physics.models.model` builds it.

    >>> f = build("beckmann", alpha=0.5, compensation="kulla_conty")
    >>> f.energy is not None and f.params == {"alpha": 0.5, "G2": "height_correlated",
    ...     "compensation": "kulla_conty", "ior_re": None, "ior_im": 0.0}
    True
    """
    check_model_call(name, params)
    cls = MODELS.get(name)
    requests = cls.table_requests(**params) if cls is not None else {}
    tables = {field: tabulate(request) for field, request in requests.items() if params.get(field) is None}
    return plain_model(name, **{**params, **tables})


def pump(base, correction: str = "g1", target_rtol: float = 1e-9, engine_rtol: float = 1e-11) -> Pumped:
    """``base`` pumped once with ``correction`` (eq. 2.20 ``'g1'`` or 2.21 ``'g2'``), dividing by its
    albedo tabulated on [0, 1] in cos θ to ``target_rtol`` on engine values at ``engine_rtol``; a
    parameter beyond the model's ``pumping_ranges`` is refused in one line before any work."""
    for key, interval in base.pumping_ranges.items():
        value = getattr(base, key)
        if not interval.contains(value):
            raise ArgumentError(f"pump(): {key} = {value!r}: the albedo table of {base.name} reaches {key} <= "
                                f"{interval.hi:g} at its target (pieces of degree 256 miss 1e-9 beyond); "
                                f"pump a model with {key} <= {interval.hi:g}")
    edges = pump_edges(base)
    degree = _PIECE_DEGREE if len(edges) > 2 else TableRequest.degree
    table = tabulate(TableRequest(base, edges, degree=degree, target_rtol=target_rtol, engine_rtol=engine_rtol))
    return Pumped(base, table, correction)


#: The starting degree of each graded piece of :func:`pump_edges` (doubled where the check misses):
#: a piece spans a factor 2 in x on the lobe's scale, where degree 16 overshoots the target by 20-40x.
#: Against albedo() at rtol 1e-12 on 400 angles (Phong n = 512, 5000, 6210; Blinn n = 400, 730.5;
#: targets 1e-6 and 1e-9) the tables' true error stays at 0.02-0.10 of the error they report, as at
#: degree 16 (0.01-0.15), and they build in 0.5-0.6 of the time (Phong n = 512 at 1e-6: 0.69 -> 0.35 s).
_PIECE_DEGREE = 8


def pump_edges(base) -> tuple[float, ...]:
    """The pieces in x = cos θ of ``base``'s albedo table: [0, 1] whole, or for a lobe narrower than
    1/16 (its half-weight angle β½, from :attr:`lobe`) pieces at x = β½/4, β½/2, β½, 2β½, … 16β½, where a(x)
    turns toward grazing on the scale of the lobe (one piece of degree 256 missed 1e-9 for Blinn
    n = 373.8 and 730.5, and Phong n = 6210 ran past 120 s; in pieces they take 0.6–1.4 s).  The
    thesis's exponents (n ≤ 150) keep the single piece and their tables."""
    lobe = base.lobe
    if lobe is None or not hasattr(lobe, "angle"):
        return (0.0, 1.0)
    cos_b, sin_b = lobe.angle(np.float64(0.5))
    half = float(np.arctan2(sin_b, cos_b))
    if not 0.0 < 16.0 * half < 1.0:
        return (0.0, 1.0)
    return (0.0, *(k * half for k in (0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0)), 1.0)


#: The package's front door :func:`brdfs.model` is :func:`build`.
model = build
