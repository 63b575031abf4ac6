"""Scenes of Figures 3.9-3.11 and 4.16-4.17 (metals of the new model and of the patch model)."""
from __future__ import annotations

from brdfs.artifacts import _render_figures as rf
from brdfs.render.mitsuba import scenes as msc


def _params(entry):
    """The model parameters of a config entry ``{metal: ..., <parameter>: ...}`` (n, s, ...), with
    the sampler's keys (``strategy``, ``mis_density``) where a figure adds them."""
    return {k: v for k, v in entry.items() if k != "metal"}


def with_sampler(entries, sampler):
    """``entries`` with the figure's sampler keys (``{strategy: ..., mis_density: ...}``) added to each."""
    return [{**entry, **sampler} for entry in entries]


def describe(entries, model="phong_cosmin"):
    """'silver n=20, aluminium n=40, ...' from config entries (panel titles follow the config)."""
    return ", ".join(" ".join([e["metal"], *(f"{k}={v:g}" for k, v in _params(e).items() if not isinstance(v, str))])
                     for e in entries)


def _metal(entry, model="phong_cosmin"):
    return {"metal": entry["metal"], "model": model, **_params(entry)}


def tank_and_spheres(cfg, entries, model, title, base=None):
    """A 'tank' (box + cylinder) behind a row of spheres on a plate (Figs. 3.9, 4.16)."""
    section = cfg[rf.SECTION]
    tank, spheres = entries[0], entries[1:]
    plate = {"diffuse": section["diffuse_reflectance"]} if base is None else _metal(base, model)
    objects = [("floor", rf.floor(), plate), ("tank", rf.tank(0.0, 1.2), _metal(tank, model))]
    for k, (x, entry) in enumerate(zip(rf.row(len(spheres), 2.1), spheres)):
        objects.append((f"sphere {k + 1} {entry['metal']}", rf.sphere(x, -1.4, 0.55), _metal(entry, model)))
    return [rf.Panel(title, objects, rf.THREE_LIGHTS, rf.STREET_CAMERA, aspect=1.6,
                     reference=("floor",) if base is None else ("tank",))]


def row_of_objects(cfg, entries, title, shapes_of, model="phong_cosmin"):
    section = cfg[rf.SECTION]
    objects = [("floor", rf.floor(), {"diffuse": section["diffuse_reflectance"]})]
    for k, (entry, (kind, shape)) in enumerate(zip(entries, shapes_of)):
        objects.append((f"{kind} {k + 1} {entry['metal']}", shape, _metal(entry, model)))
    return [rf.Panel(title, objects, rf.THREE_LIGHTS, rf.STREET_CAMERA)]


def three_teapots():
    """Three teapots, the middle one behind the other two (it mirrors them, as the thesis's does),
    close together so that the framed camera (:func:`~brdfs.artifacts._render_figures.framed_camera`)
    shows them large; :func:`brdfs.render.mitsuba.scenes.teapot` (Newell's teapot, tessellated)."""
    return [("teapot", msc.teapot(-1.25, -0.45, 1.0)), ("teapot", msc.teapot(0.0, 0.6, 1.1)),
            ("teapot", msc.teapot(1.25, -0.45, 1.0))]


def mirror_scene(cfg, entries, title):
    """Fig. 3.11: a gold bust (the stated substitute for Beethoven's head, :func:`~brdfs.render.mitsuba.scenes.head`),
    a copper sphere and a copper pyramid on a near-mirror silver plate, all in frame."""
    head, ball, pyramid, plate = entries
    objects = [("floor (mirror)", rf.floor(), _metal(plate)),
               ("head", msc.head(0.0, 0.6, 1.0), _metal(head)),
               ("sphere", rf.sphere(-2.0, -0.9, 0.6), _metal(ball)),
               ("pyramid", msc.pyramid((2.0, -0.8, 0.0), 0.6, 1.1), _metal(pyramid))]
    camera = {"eye": (0.0, -8.0, 3.4), "target": (0.0, 0.0, 0.7), "fov_deg": 34.0}
    return [rf.Panel(title, objects, rf.THREE_LIGHTS, camera, reference=("head",), aspect=1.6)]
