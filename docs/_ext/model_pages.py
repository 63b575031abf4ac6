"""Sphinx extension: the model reference, one page per registered model, written from the model classes.

On ``builder-inited`` it writes ``models/index.rst`` and ``models/<name>.rst`` with their figures in
``models/_generated/`` (generated, not committed), from the package alone (not from ``results/``):

* the class's docstring (its formula, with the thesis's or the paper's equation number), its chapter
  and its claims (reciprocity, energy conservation);
* a table of its parameters: declared range, choices or text (``param_texts``), default, the ``typical`` and ``narrowest``
  examples and the range the generic tests draw from;
* lobe plots at the typical example: f in the plane of incidence at θ_L = 0°, 30°, 60° (log scale),
  and the same as a polar plot;
* its albedo a(θ) against the incidence angle (:func:`brdfs.albedo`, rtol 1e-8) with the error
  band, and the error itself on a log scale;
* its samplers with their chi-square p-values (:func:`brdfs.numerics.chi2.chi2_test`, 20,000
  samples at θ = 45°, seed fixed);
* a 64 × 64 render of a sphere under a sky and a point light by the package's numpy path tracer,
  through the model's own sampler, cached in ``_build/model_renders/<version>/`` per model and
  package version (a docs rebuild does not render again).

Models registered by a plugin package (entry points ``brdfs.models``) get their pages too.
"""
from __future__ import annotations

import dataclasses
import re
import shutil
import time
import warnings
from pathlib import Path

import numpy as np
from thesis_pages import escape_bars

ANGLES_LOBE = (0.0, 30.0, 60.0)
CHI2_THETA = 45.0
CHI2_SAMPLES = 20_000
RENDER_SIZE = 64
RENDER_SPP = 32


def _first_paragraph(cls) -> str:
    doc = (cls.__doc__ or cls.name).strip()
    return " ".join(line.strip() for line in doc.split("\n\n")[0].splitlines())


def _rst_escape(text: str) -> str:
    return text.replace("*", r"\*").replace("|", r"\|").replace("_", r"\_")


def _value(value) -> str:
    if value is None:
        return "None"
    if callable(value):
        return f"a function ({getattr(value, '__name__', 'callable')})"
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)


def _parameter_rows(cls):
    import dataclasses

    defaults = {f.name: (f.default if f.default is not dataclasses.MISSING else "required")
                for f in dataclasses.fields(cls)}
    rows = []
    for key in cls.param_columns():
        if key in cls.param_choices:
            allowed = ", ".join(map(str, cls.param_choices[key]))
        elif key in cls.param_ranges:
            allowed = cls.param_ranges[key].text()
        else:
            allowed = getattr(cls, "param_texts", {}).get(key, "(see the class)")
        draw = cls.test_range(key) if key in cls.param_ranges else None
        drawn = "" if draw is None else (f"{draw.lo:g} … {draw.hi:g}" + (" (log)" if draw.log else "")
                                         + (", 0" if draw.zero else "") + (", None" if draw.none else ""))
        rows.append([key, allowed, _value(defaults.get(key)), _value(cls.examples.get("typical", {}).get(key, "")),
                     _value(cls.examples.get("narrowest", {}).get(key, "")), drawn])
    return rows


def _list_table(header, rows, widths=None) -> list[str]:
    lines = [".. list-table::", "   :header-rows: 1"]
    if widths:
        lines.append(f"   :widths: {' '.join(map(str, widths))}")
    lines.append("")
    for row in [header, *rows]:
        lines.append(f"   * - {_rst_escape(str(row[0])) or ' '}")
        lines += [f"     - {_rst_escape(str(cell)) or ' '}" for cell in row[1:]]
    return lines + [""]


def _plane_directions(theta_v_deg):
    t = np.radians(theta_v_deg)
    return np.stack([np.sin(t), np.zeros_like(t), np.cos(t)], -1)


def lobe_figure(brdf, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    theta_v = np.linspace(-89.5, 89.5, 721)       # signed: negative on the side of L, positive toward R
    V = _plane_directions(-theta_v)
    fig = plt.figure(figsize=(8.4, 3.2))
    ax = fig.add_subplot(1, 2, 1)
    polar = fig.add_subplot(1, 2, 2, projection="polar")
    for theta_l in ANGLES_LOBE:
        L = _plane_directions(np.array(theta_l))
        f = brdf(np.broadcast_to(L, V.shape), V)
        ax.semilogy(theta_v, np.where(f > 0, f, np.nan), label=f"θ_L = {theta_l:g}°")
        peak = np.nanmax(f) if np.any(f > 0) else 1.0
        polar.plot(np.radians(theta_v), f / peak, label=f"{theta_l:g}°")
    top = ax.get_ylim()[1]
    ax.set_ylim(max(ax.get_ylim()[0], top * 1e-8), top)       # eight decades below the peak
    ax.set_xlabel("θ_V in the plane of incidence [deg] (mirror side > 0)")
    ax.set_ylabel("f(L, V) [1/sr]")
    ax.legend(fontsize=7, loc="best")
    ax.set_title("BRDF in the plane of incidence")
    polar.set_theta_zero_location("N")
    polar.set_theta_direction(-1)                  # the mirror side (θ_V > 0) on the right, as on the left
    polar.set_yticklabels([])
    polar.set_thetamin(-90)
    polar.set_thetamax(90)
    polar.set_title("f / max f (polar)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def albedo_figure(brdf, path: Path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import brdfs

    theta = np.linspace(0.0, 89.0, 30)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        est = brdfs.albedo(brdf, theta, rtol=1e-8, warn=False)
    value, error = np.asarray(est.value), np.asarray(est.error)
    fig, (ax, ax_err) = plt.subplots(1, 2, figsize=(8.4, 3.0))
    ax.plot(theta, value, color="C0", label="a(θ)")
    ax.fill_between(theta, value - error, value + error, color="C0", alpha=0.3, label="± error bound")
    ax.set_xlabel("incidence angle θ [deg]")
    ax.set_ylabel("albedo a(θ)")
    ax.legend(fontsize=8)
    ax_err.semilogy(theta, np.maximum(error, 1e-17), color="C3")
    ax_err.set_xlabel("incidence angle θ [deg]")
    ax_err.set_ylabel("reported error bound")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return theta, value, error, np.asarray(est.status)


def chi2_rows(brdf):
    from brdfs.numerics.chi2 import chi2_test

    rows = []
    for strategy in brdf.strategies:
        try:
            r = chi2_test(brdf, CHI2_THETA, strategy=strategy, n_samples=CHI2_SAMPLES, seed=20010101)
            rows.append([strategy, f"{CHI2_THETA:g}°", f"{r.statistic:.1f}", r.dof, f"{r.p_value:.3g}",
                         f"{r.pdf_mass:.4f}"])
        except Exception as exc:  # noqa: BLE001 -- a page says why, and the build goes on
            rows.append([strategy, f"{CHI2_THETA:g}°", "", "", f"not run: {str(exc).splitlines()[0][:60]}", ""])
    return rows


def render_sphere(brdf, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from brdfs.render import materials, shapes, tracer

    scene = tracer.Scene([tracer.SceneObject(shapes.Sphere((0, 0, 0), 1.0), materials.specular(brdf, 1), "sphere")],
                         lights=[tracer.PointLight((4.0, -6.0, 5.0), np.full(1, 40.0))], sky=np.full(1, 0.25),
                         background=np.full(1, 0.05))
    camera = tracer.Camera((0, -8, 1.5), (0, 0, 0), RENDER_SIZE, RENDER_SIZE, fov_deg=18)
    image = tracer.render(scene, camera, spp=RENDER_SPP, depth=2, seed=1)
    radiance = np.asarray(image.radiance)[..., 0]
    tone = radiance / (1.0 + radiance)                          # Reinhard
    plt.imsave(path, np.clip(tone, 0, 1) ** (1 / 2.2), cmap="gray", vmin=0, vmax=1)


def _cached_render(brdf, name, cache: Path, out: Path) -> str:
    cached = cache / f"{name}.png"
    if not cached.is_file():
        cache.mkdir(parents=True, exist_ok=True)
        try:
            render_sphere(brdf, cached)
        except Exception as exc:  # noqa: BLE001
            return f"(not rendered: {str(exc).splitlines()[0][:80]})"
    shutil.copyfile(cached, out)
    return ""


def model_page(name, cls, out_dir: Path, cache: Path) -> str:
    gen = out_dir / "_generated"
    brdf = cls.example("typical")
    lobe_figure(brdf, gen / f"{name}_lobe.png")
    theta, value, error, status = albedo_figure(brdf, gen / f"{name}_albedo.png")
    samplers = chi2_rows(brdf)
    render_note = _cached_render(brdf, name, cache, gen / f"{name}_render.png")
    claims = [f"chapter {cls.chapter} of the thesis" if cls.chapter else "beyond the thesis",
              "reciprocal" if cls.reciprocal else "not reciprocal",
              "claims a(θ) ≤ 1" if cls.conserves_energy else "makes no energy claim"]
    typical = ", ".join(f"{k} = {_value(v)}" for k, v in cls.examples.get("typical", {}).items()) or "its defaults"
    title = f"``{name}``"
    lines = [f".. _model-{name}:", "", title, "=" * len(title), "", escape_bars(_first_paragraph(cls)), "",
             f"*{'; '.join(claims)}.* Class :class:`{cls.__module__}.{cls.__qualname__}`; "
             f"``brdfs.model({name!r}, ...)``.", "",
             f"**Explore it:** run ``brdfs explore`` (:doc:`../guide/explorer`), then open "
             f"`http://127.0.0.1:8123/#left={name} <http://127.0.0.1:8123/#left={name}>`_: its parameters, lobe, "
             "certified albedo, lit sphere and slice, live.", "", "Parameters", "----------", ""]
    lines += _list_table(["parameter", "declared range or choices", "default", "typical", "narrowest", "tests draw"],
                         _parameter_rows(cls)) if cls.param_columns() else ["No parameters.", ""]
    lines += ["Lobe", "----", "", f"At the typical example ({typical}).", "",
              f".. image:: _generated/{name}_lobe.png", f"   :alt: {name}: lobe plots", "",
              "Albedo", "------", "",
              f"a(θ) by ``brdfs.albedo`` (rtol 1e-8) at the typical example; the band is the reported error bound "
              f"(largest {np.nanmax(error):.2g}, {int(np.sum(status == 'converged'))} of {status.size} angles converged).",
              "", f".. image:: _generated/{name}_albedo.png", f"   :alt: {name}: albedo against incidence angle", "",
              "Samplers", "--------", "",
              f"Chi-square test of each sampler against its pdf ({CHI2_SAMPLES:,} samples at θ = {CHI2_THETA:g}°, "
              f"fixed seed; ``brdfs chi2 {name}``).", ""]
    lines += _list_table(["strategy", "θ", "χ²", "dof", "p-value", "pdf mass"], samplers)
    lines += ["Render", "------", "",
              f"A sphere under a sky and a point light, {RENDER_SIZE} × {RENDER_SIZE} pixels at {RENDER_SPP} "
              "samples per pixel, by the package's numpy path tracer through the model's own sampler.", ""]
    lines += [render_note, ""] if render_note else [f".. image:: _generated/{name}_render.png",
                                                     f"   :alt: {name}: rendered sphere", "   :width: 192px", ""]
    return "\n".join(lines)


# --- the Mitsuba plugin reference ---------------------------------------------------------------

_READS = re.compile(r'(read_float\(props, |props\.get\()"(\w+)"')


def _reads(source):
    """(name, type, default source text) of every ``read_float(props, "name"[, default])`` and
    ``props.get("name", default)`` in ``source`` (the default up to its balancing parenthesis)."""
    for match in _READS.finditer(source):
        depth, end = 1, match.end()
        while depth and end < len(source):
            depth += {"(": 1, ")": -1}.get(source[end], 0)
            end += 1
        default = source[match.end():end - 1].lstrip(", ").strip()
        yield match.group(2), ("float" if match.group(1).startswith("read") else "string"), default


def _plugin_parameters(cls, twin):
    """(name, type, default, meaning) of the scene keys of plugin ``cls``: its model's parameters as the
    plugin reads them (read_float / props.get in its source), its extra keys and the common ones."""
    import inspect

    from brdfs.render.mitsuba.plugins._common import COMMON_PARAMETERS, ModelBSDF

    found = {}
    for klass in reversed([k for k in cls.__mro__ if issubclass(k, ModelBSDF) and k is not ModelBSDF]):
        source = inspect.getsource(klass)
        for name, kind, default in _reads(source):
            found.setdefault(name, (kind, default.strip('"') or "required"))
        for name in getattr(klass, "parameters", ()):
            found.setdefault(name, ("float", "the model's"))
    rows = []
    for name, (kind, default) in found.items():
        if name in cls.extra_parameters or name in COMMON_PARAMETERS:
            continue
        field = (twin.__dataclass_fields__.get(name) if twin is not None else None)
        if field is not None and default == "the model's":
            default = "required" if field.default is dataclasses.MISSING else (
                "the model's (computed)" if field.default is None else repr(field.default))
        elif field is not None and field.default is None and re.fullmatch(r"[\d.]+", default):
            default = "none"
        if twin is not None and name in twin.param_choices:
            meaning = "one of " + ", ".join(f"``{c}``" for c in twin.param_choices[name])
        elif twin is not None and name in twin.param_ranges:
            meaning = f"the model's parameter, in {twin.param_ranges[name].text()}"
        else:
            meaning = "the model's parameter"
        plain = default in ("required", "none") or default.startswith("the model's")
        rows.append([f"``{name}``", kind, default if plain else f"``{default.replace('self.', '')}``",
                     meaning])
    weight = cls.weight_name
    for name, (kind, default, meaning) in {**cls.extra_parameters, **COMMON_PARAMETERS}.items():
        if name == "specular" and weight != "specular":
            name, meaning = weight, "the lobe's weight (the material's albedo)"
        rows.append([f"``{name}``", kind, default, meaning])
    return rows


def plugin_reference(out_dir: Path) -> str:
    """RST: one section per Mitsuba plugin, with its parameter table and the render of its model."""
    import mitsuba as mi

    from brdfs.physics.models import MODELS
    from brdfs.render.mitsuba.plugins import plugin_classes

    if mi.variant() is None:
        mi.set_variant("scalar_rgb")
    lines = []
    for registered, cls in plugin_classes().items():
        twin = MODELS.get(cls.name)
        title = f"``{registered}``"
        lines += [title, "-" * len(title), "", escape_bars(" ".join((cls.__doc__ or "").split("\n\n")[0].split())), ""]
        if twin is not None:
            lines += [f"The twin of the package's model :ref:`{cls.name} <model-{cls.name}>`; samplers: "
                      + ", ".join(f"``{s}``" for s in cls.strategies) + ".", ""]
        lines += _list_table_raw(["key", "type", "default", "meaning"], _plugin_parameters(cls, twin))
        if twin is not None and (out_dir / "_generated" / f"{cls.name}_render.png").is_file():
            lines += [f".. image:: /models/_generated/{cls.name}_render.png", f"   :alt: {cls.name}",
                      "   :width: 160px", ""]
    return "\n".join(lines) + "\n"


def _list_table_raw(header, rows) -> list[str]:
    lines = [".. list-table::", "   :header-rows: 1", "   :widths: 18 10 14 58", ""]
    for row in [header, *rows]:
        lines.append(f"   * - {row[0]}")
        lines += [f"     - {cell or ' '}" for cell in row[1:]]
    return lines + [""]


def write_model_pages(app) -> None:
    import brdfs
    from brdfs.physics.models import MODELS
    from brdfs.user_models import load_entry_points

    load_entry_points()
    out_dir = Path(app.srcdir) / "models"
    gen = out_dir / "_generated"
    gen.mkdir(parents=True, exist_ok=True)
    cache = Path(app.srcdir) / "_build" / "model_renders" / brdfs.__version__
    start = time.perf_counter()
    names = list(MODELS)
    for name in names:
        (out_dir / f"{name}.rst").write_text(model_page(name, MODELS[name], out_dir, cache))
    index = ["Model reference", "===============", "",
             f"One page per registered model ({len(names)}), written from the model classes when the documentation "
             "is built: formula, parameters, lobe, albedo with its error, samplers with their chi-square "
             "p-values, a render.", "", ".. toctree::", "   :maxdepth: 1", ""]
    index += [f"   {name}" for name in names]
    (out_dir / "index.rst").write_text("\n".join(index) + "\n")
    (out_dir / "plugins.inc").write_text(plugin_reference(out_dir))
    print(f"model_pages: {len(names)} pages in {time.perf_counter() - start:.1f} s")


def setup(app):
    app.connect("builder-inited", write_model_pages)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
