"""The front door plans once, runs each route once and merges (issue 41): the (model, θ) pairs are
grouped by model once per call, each route runs once on all of its elements (in chunks of at most
``ENGINE_CHUNK``), the argument checks import nothing of the numerics above them, and the engine's
chunk loop reports its progress to whoever listens."""
import ast
import inspect

import numpy as np

from brdfs.numerics import albedo as front_door
from brdfs.numerics import arguments
from brdfs.physics.models import model


def _counting(monkeypatch, owner, name):
    calls = []
    real = getattr(owner, name)

    def counted(*args, **kwargs):
        calls.append(args)
        return real(*args, **kwargs)

    monkeypatch.setattr(owner, name, counted)
    return calls


def test_the_pairs_are_grouped_by_model_once_per_call(monkeypatch):
    grouped = _counting(monkeypatch, front_door, "indices_by_model")
    front_door.albedo(model("cook_torrance", m=0.1), [0.0, 45.0, 90.0], rtol=1e-6)
    assert len(grouped) == 1
    grouped.clear()
    ggx, phong = model("ggx", alpha=0.3), model("phong", n=20.0)
    front_door.albedo_pairs([ggx, phong, ggx, phong], np.array([10.0, 20.0, 30.0, 90.0]), rtol=1e-6)
    assert len(grouped) == 1


def test_each_route_runs_once_on_all_of_its_elements_whatever_their_models(monkeypatch):
    seen = []
    route = front_door.ENGINE_ROUTES["azimuthal"]
    monkeypatch.setitem(front_door.ENGINE_ROUTES, "azimuthal",
                        lambda models, theta, **kw: (seen.append(theta.copy()), route(models, theta, **kw))[1])
    models = [model("phong", n=20.0), model("blinn", n=20.0), model("ward", m=0.1)]
    theta = np.array([10.0, 20.0, 30.0, 40.0, 50.0, 60.0])
    est = front_door.albedo_pairs([models[k % 3] for k in range(6)], theta, rtol=1e-6)
    assert len(seen) == 1 and list(seen[0]) == list(theta)          # one run, in the call's order
    assert set(est.route) == {"engine/azimuthal"}


def test_a_route_runs_in_chunks_of_bounded_size(monkeypatch):
    theta, brdf = np.linspace(0.0, 89.0, 30), model("phong", n=20.0)
    whole = front_door.albedo(brdf, theta, rtol=1e-8)
    sizes = []
    route = front_door.ENGINE_ROUTES["azimuthal"]
    monkeypatch.setattr(front_door, "ENGINE_CHUNK", 7)
    monkeypatch.setitem(front_door.ENGINE_ROUTES, "azimuthal",
                        lambda models, theta, **kw: (sizes.append(theta.size), route(models, theta, **kw))[1])
    chunked = front_door.albedo(brdf, theta, rtol=1e-8)
    assert sizes == [7, 7, 7, 7, 2]
    assert set(chunked.status) == {"converged"}
    assert np.all(np.abs(chunked.value - whole.value) <= chunked.error + whole.error)


def test_the_chunk_loop_reports_progress_to_a_listener():
    heard = []
    with front_door.reporting_progress(lambda done, total: heard.append((done, total))):
        front_door.albedo(model("phong", n=20.0), np.linspace(0.0, 89.0, 30), rtol=1e-6)
    front_door.albedo(model("phong", n=20.0), [10.0], rtol=1e-6)          # nobody listens: nothing heard
    assert heard and heard[-1] == (30, 30) and all(d <= t for d, t in heard)


def test_the_argument_checks_import_nothing_of_the_numerics_above_them():
    """arguments.py imported albedo.py back (a circle); now the front door passes its methods in."""
    tree = ast.parse(inspect.getsource(arguments))
    imported = [n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    imported += [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    assert not [m for m in imported if m and m.startswith("brdfs.numerics")]


def test_the_tolerance_is_checked_first_and_carried_as_one_value():
    tol = arguments.Tolerance.checked(1e-8, None)
    assert tol == arguments.Tolerance(1e-8, arguments.DEFAULT_ATOL)
    assert np.array_equal(tol.target(np.array([1.0, 0.0])), [1e-8, arguments.DEFAULT_ATOL])
    try:
        front_door.albedo("phong", 30.0, rtol=-1.0)                     # two bad arguments: rtol first
    except arguments.ArgumentError as err:
        assert "rtol = -1.0" in str(err)
