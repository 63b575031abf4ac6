"""Scenes of the rendered figures as Mitsuba 3 scene dictionaries: shapes, lights, sky, camera.

World coordinates have z up; the floor is the plane z = 0. A scene is assembled from
:class:`SceneObject` s (a label, one or more shape *parts* and a BSDF dictionary), :class:`Light` s,
an optional constant sky and a :class:`Camera`. Every part becomes one Mitsuba shape named
``<label>#<k>`` and the object's BSDF carries the label as its id; the integrator's ``id`` AOV
numbers the BSDFs, and :func:`object_labels` maps them back to the labels.

Point lights become small spherical area emitters (the caustics of diffuse → near-mirror → light
paths are then reachable by BSDF sampling and weighted by MIS, instead of being unreachable; the
integrator's ``caustics`` property, ``renders.caustics``, may still drop them): a
sphere of radius r and radiance L_e radiates the intensity I = L_e π r² in every direction, so a
point light of intensity I becomes L_e = I / (π r²), with r = :data:`LIGHT_RADIUS`.

Geometry where the thesis has it: real pyramids (a five-vertex mesh, 2.8 and 3.11), the tank as a
box hull with a capped cylinder turret and a barrel, a *head substitute* (Fig. 3.11's Beethoven
bust: a sphere on a capped cylindrical neck on a box plinth, a bust's silhouette), and
:func:`teapot` — the Utah teapot tessellated from Newell's Bézier patches (:mod:`.geometry`).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from brdfs.render.mitsuba import geometry

#: Radius of the spherical emitter a point light becomes (scene size ~ 1-10).
LIGHT_RADIUS = 0.12
#: Shape types Mitsuba builds from a dictionary; "mesh" parts are built by :func:`_mesh`.
DICT_SHAPES = ("sphere", "rectangle", "cube", "cylinder", "disk")


@dataclass(frozen=True)
class Light:
    """An isotropic point light of radiant intensity ``intensity`` (per channel or scalar)."""

    position: tuple
    intensity: object


@dataclass(frozen=True)
class Camera:
    """Pinhole camera at ``eye`` looking at ``target``, vertical field of view ``fov_deg``."""

    eye: tuple
    target: tuple
    width: int
    height: int
    fov_deg: float = 30.0
    up: tuple = (0.0, 0.0, 1.0)


@dataclass(frozen=True)
class SceneObject:
    """A labelled object: shape parts (dicts of :func:`sphere`, :func:`box`, ...) and one BSDF dict."""

    label: str
    parts: tuple
    bsdf: dict


@dataclass(frozen=True)
class Scene:
    objects: tuple
    lights: tuple = ()
    sky: object = None                 # constant sky radiance (per channel or scalar), or None
    background_visible: bool = True    # camera rays that miss see the sky (else black)
    point_lights: bool = False         # lights as Mitsuba "point" emitters (delta), not small spheres
    extra: dict = field(default_factory=dict)


# --- shapes (parts) -------------------------------------------------------------------------------

def sphere(center, radius) -> tuple:
    return ({"type": "sphere", "center": [float(c) for c in center], "radius": float(radius)},)


def floor(half_size=4.0) -> tuple:
    """The square [−half_size, half_size]² of the plane z = 0, normal +z."""
    return ({"type": "rectangle", "scale": [half_size, half_size, 1.0], "translate": [0.0, 0.0, 0.0]},)


def box(center, half_extent) -> tuple:
    return ({"type": "cube", "scale": [float(h) for h in half_extent], "translate": [float(c) for c in center]},)


def capped_cylinder(base, radius, height) -> tuple:
    """A vertical cylinder on ``base`` (x, y, z) with a disk lid (Mitsuba's cylinder is open)."""
    x, y, z = (float(c) for c in base)
    return ({"type": "cylinder", "p0": [x, y, z], "p1": [x, y, z + height], "radius": float(radius)},
            {"type": "disk", "scale": [radius, radius, 1.0], "translate": [x, y, z + height]})


def pyramid(center, half_base, height) -> tuple:
    """A square pyramid standing on z = center[2]: five vertices, four sides and a two-triangle base."""
    x, y, z = (float(c) for c in center)
    h = float(half_base)
    vertices = [[x - h, y - h, z], [x + h, y - h, z], [x + h, y + h, z], [x - h, y + h, z], [x, y, z + height]]
    faces = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4], [0, 2, 1], [0, 3, 2]]
    return ({"type": "mesh", "vertices": vertices, "faces": faces},)


def tank(x, y, scale=1.0) -> tuple:
    """The tank: a box hull, a capped cylinder turret on it and a horizontal barrel (a thin box)."""
    s = float(scale)
    hull = box((x, y, 0.35 * s), (0.9 * s, 0.55 * s, 0.35 * s))
    turret = capped_cylinder((x, y, 0.7 * s), 0.35 * s, 0.3 * s)
    barrel = box((x - 0.75 * s, y, 0.85 * s), (0.45 * s, 0.06 * s, 0.06 * s))
    return hull + turret + barrel


def head(x, y, scale=1.0) -> tuple:
    """Substitute for Fig. 3.11's Beethoven head: a bust (sphere on a capped neck on a box plinth)."""
    s = float(scale)
    plinth = box((x, y, 0.2 * s), (0.55 * s, 0.55 * s, 0.2 * s))
    neck = capped_cylinder((x, y, 0.4 * s), 0.3 * s, 0.45 * s)
    skull = sphere((x, y, 1.3 * s), 0.6 * s)
    return plinth + neck + skull


def teapot(x, y, scale=1.0) -> tuple:
    """The Utah teapot tessellated from Newell's patches (:func:`.geometry.teapot_part`)."""
    return geometry.teapot_part(x, y, scale)


# --- assembly -------------------------------------------------------------------------------------

def _transform(part):
    import mitsuba as mi

    return mi.ScalarTransform4f().translate(part["translate"]).scale(part["scale"])


def _mesh(mi, name, part, bsdf):
    props = mi.Properties()
    props["bsdf"] = bsdf
    return geometry.mitsuba_mesh(name, part["vertices"], part["faces"], part.get("normals"), props)


def _shape(mi, name, part, bsdf):
    if part["type"] == "mesh":
        return _mesh(mi, name, part, bsdf)
    if part["type"] not in DICT_SHAPES:
        raise ValueError(f"shape part type = {part['type']!r}: not one of {DICT_SHAPES + ('mesh',)}")
    out = {k: v for k, v in part.items() if k not in ("scale", "translate")}
    if "scale" in part:
        out["to_world"] = _transform(part)
    out["bsdf"] = bsdf
    return out


def _spectrum(value):
    """A constant emitter/texture value: scalar -> gray, sequence of 3 -> unbounded RGB."""
    values = np.broadcast_to(np.asarray(value, float), (3,))
    return {"type": "srgb", "color": [float(v) for v in values], "unbounded": True}


def light_radiance(intensity, radius=LIGHT_RADIUS):
    """L_e of the spherical emitter that radiates ``intensity`` (I = L_e π r², module docstring)."""
    return np.asarray(intensity, float) / (np.pi * radius * radius)


def camera_dict(camera: Camera, rfilter="box", sampler="independent", crop=None) -> dict:
    """The perspective sensor of ``camera``; ``crop`` = (x, y, width, height) renders only that window
    of the film (Mitsuba's crop window: the same rays as the full film's pixels there)."""
    import mitsuba as mi

    film = {"type": "hdrfilm", "width": int(camera.width), "height": int(camera.height),
            "pixel_format": "rgb", "rfilter": {"type": rfilter}}
    if crop is not None:
        x, y, width, height = (int(v) for v in crop)
        film.update(crop_offset_x=x, crop_offset_y=y, crop_width=width, crop_height=height)
    return {"type": "perspective", "fov": float(camera.fov_deg), "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(origin=list(camera.eye), target=list(camera.target),
                                                       up=list(camera.up)),
            "film": film, "sampler": {"type": sampler}}


def _key(label: str, k: int) -> str:
    """The scene key of part k of an object (Mitsuba reserves '.' in keys)."""
    return f"{label.replace('.', '_')}#{k}"


def to_dict(scene: Scene, camera: Camera, integrator: dict, sampler: str = "independent") -> dict:
    """The Mitsuba scene dictionary (objects, light spheres, sky, camera with Mitsuba's ``sampler``, integrator)."""
    import mitsuba as mi

    out = {"type": "scene", "integrator": dict(integrator), "sensor": camera_dict(camera, sampler=sampler)}
    for obj in scene.objects:
        bsdf = mi.load_dict(obj.bsdf)
        bsdf.set_id(obj.label)
        for k, part in enumerate(obj.parts):
            out[_key(obj.label, k)] = _shape(mi, _key(obj.label, k), part, bsdf)
    black = mi.load_dict({"type": "diffuse", "reflectance": _spectrum(0.0)})
    black.set_id("light")
    for k, light in enumerate(scene.lights):
        if scene.point_lights:
            out[f"light#{k}"] = {"type": "point", "position": [float(c) for c in light.position],
                                 "intensity": _spectrum(light.intensity)}
            continue
        out[f"light#{k}"] = {"type": "sphere", "center": [float(c) for c in light.position],
                             "radius": LIGHT_RADIUS, "bsdf": black,
                             "emitter": {"type": "area", "radiance": _spectrum(light_radiance(light.intensity))}}
    if scene.sky is not None:
        out["sky"] = {"type": "constant", "radiance": _spectrum(scene.sky)}
    if not scene.background_visible:
        out["integrator"]["hide_emitters"] = True
    return out


def load(scene: Scene, camera: Camera, integrator: dict, sampler: str = "independent"):
    """The loaded Mitsuba scene; each object's BSDF keeps its label as id (:func:`object_labels`)."""
    import mitsuba as mi

    loaded = mi.load_dict(to_dict(scene, camera, integrator, sampler))
    labels = {_key(obj.label, 0).split("#")[0]: obj.label for obj in scene.objects}
    labels["light"] = "light"
    for shape in loaded.shapes():
        key = shape.id().split("#")[0] if "#" in shape.id() else None
        if key in labels:
            shape.bsdf().set_id(labels[key])
    return loaded


def object_labels(mitsuba_scene) -> dict[int, str]:
    """{AOV id: object label} of a loaded scene (the BSDFs' ids; light spheres: ``"light"``)."""
    from brdfs.render.mitsuba.integrator import scene_bsdfs

    return {k + 1: bsdf.id() for k, bsdf in enumerate(scene_bsdfs(mitsuba_scene))}
