"""The diagrams are fit to print: no label sits on a drawn line, arrowhead, marker or on another
label, and no legend covers data.

Every check is done in display coordinates after a draw: a text's (or legend's) window extent,
padded by :data:`PAD_PX`, must not contain any point of a drawn line or arrow outline (densified
to ~1 px steps), nor any marker of a line or a scatter, nor overlap another text's extent.
Filled areas without an edge (the shaded solid angles, lenses, patches) may carry labels.
"""
from __future__ import annotations

import importlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.figure  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.patches import FancyArrowPatch  # noqa: E402
from matplotlib.text import Annotation  # noqa: E402

from brdfs.pipeline import registry  # noqa: E402
from brdfs.pipeline.config import load_config  # noqa: E402

#: The diagrams of issue 23's "Diagrams fit to print" (Figs. 1.1–1.4, 4.1, 4.2, 4.4, 4.7, 4.8, 5.1).
DIAGRAMS = ("fig_1_1_surface_elements", "fig_1_2_point_light_pupil", "fig_1_3_integral_schemes",
            "fig_1_4_notation", "fig_4_1_brdf_geometry", "fig_4_2_base_circle_relations",
            "fig_4_4_circle_intersection", "fig_4_7_sampling_circles_apart",
            "fig_4_8_sampling_circles_intersect", "fig_5_1_patch_based_brdf")
#: Clearance a label keeps from lines and other labels [display px at the figure's dpi].
PAD_PX = 1.0


@pytest.fixture(scope="module")
def cfg():
    return load_config()


def drawn_figure(name, cfg, monkeypatch):
    """The figure an artifact's ``plot`` saves (captured instead of written, after
    :func:`brdfs.pipeline.plotting.savefig` has added its automatic legends), drawn."""
    captured = []
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", lambda fig, *args, **kw: captured.append(fig))
    df = registry.get_artifact(name).compute(cfg, {})
    importlib.import_module(f"brdfs.artifacts.{name}").plot(df, "unused.png")
    (fig,) = captured
    FigureCanvasAgg(fig)  # savefig closed the figure; a fresh canvas draws it again
    fig.draw_without_rendering()  # lays out texts and arrows without rasterising
    return fig


def _densify(xy, step=1.0):
    """Points along the polyline ``xy`` (display px) at most ``step`` apart."""
    if len(xy) < 2:
        return xy
    seg = np.diff(xy, axis=0)
    n = np.maximum(1, np.ceil(np.hypot(*seg.T) / step)).astype(int)
    parts = [xy[i] + seg[i] * np.linspace(0, 1, k, endpoint=False)[:, None] for i, k in enumerate(n)]
    return np.vstack([*parts, xy[-1:]])


def ink_points(ax):
    """``[(zorder, points)]``: display-px points of everything drawn as a line in ``ax`` (lines,
    markers, scatters, arrows' shafts and heads, edged patches) with the drawing's zorder."""
    pts = []
    for line in ax.get_lines():
        if not line.get_visible():
            continue
        xy = line.get_transform().transform(line.get_xydata())
        xy = xy[np.isfinite(xy).all(1)]
        if line.get_linestyle() not in ("None", "none", "", " ") and line.get_linewidth() > 0:
            pts.append((line.get_zorder(), _densify(xy)))
        if line.get_marker() not in (None, "None", "none", "", " "):
            pts.append((line.get_zorder(), xy))
    for coll in ax.collections:
        offsets = coll.get_offsets()
        if len(offsets) and coll.get_visible():
            pts.append((coll.get_zorder(), coll.get_offset_transform().transform(offsets)))
    arrows = [(t.get_zorder(), t.arrow_patch) for t in ax.texts
              if isinstance(t, Annotation) and t.arrow_patch is not None]
    arrows += [(p.get_zorder(), p) for p in ax.patches if isinstance(p, FancyArrowPatch)]
    for zorder, arrow in arrows:
        path = arrow.get_transform().transform_path(arrow.get_path())
        for poly in path.to_polygons(closed_only=False):
            pts.append((zorder, _densify(poly)))
    for patch in ax.patches:
        if isinstance(patch, FancyArrowPatch) or patch.get_linewidth() == 0 or not patch.get_visible():
            continue
        if patch.get_edgecolor()[3] == 0:
            continue
        path = patch.get_transform().transform_path(patch.get_path())
        for poly in path.to_polygons(closed_only=False):
            pts.append((patch.get_zorder(), _densify(poly)))
    return pts


def _masks(text) -> float:
    """The zorder below which a text hides the ink under it: its own if it stands on an opaque
    ground (a bbox patch with an opaque face), else none."""
    ground = text.get_bbox_patch()
    return text.get_zorder() if ground is not None and ground.get_facecolor()[3] == 1 else -np.inf


def labels(ax):
    """``[(text, padded display extent, masking zorder)]`` of the visible, non-empty texts of ``ax``
    (not its title)."""
    renderer = ax.figure.canvas.get_renderer()
    out = []
    for t in ax.texts:
        if t.get_visible() and t.get_text().strip():
            out.append((t.get_text(), t.get_window_extent(renderer).padded(PAD_PX), _masks(t)))
    return out


def _inside(points, bbox):
    return (points[:, 0] > bbox.x0) & (points[:, 0] < bbox.x1) & (points[:, 1] > bbox.y0) & (points[:, 1] < bbox.y1)


def layout_faults(fig) -> list[str]:
    """Every label on ink, label on label, and legend on data of ``fig``, as readable lines."""
    faults = []
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        ink = ink_points(ax)
        texts = labels(ax)
        for text, box, masks in texts:
            hits = sum(int(_inside(points, box).sum()) for zorder, points in ink if zorder >= masks)
            if hits:
                faults.append(f"label {text!r} sits on {hits} px of drawn lines/markers")
        for i, (a, box_a, _) in enumerate(texts):
            for b, box_b, _ in texts[i + 1:]:
                if box_a.overlaps(box_b):
                    faults.append(f"labels {a!r} and {b!r} overlap")
        legend = ax.get_legend()
        if legend is not None:
            box = legend.get_window_extent(renderer)
            hits = sum(int(_inside(points, box).sum()) for _, points in ink)
            if hits:
                faults.append(f"the legend covers {hits} px of data")
    return faults


@pytest.mark.parametrize("name", DIAGRAMS)
def test_diagram_labels_sit_clear_of_lines_markers_and_each_other(name, cfg, monkeypatch):
    fig = drawn_figure(name, cfg, monkeypatch)
    try:
        assert layout_faults(fig) == []
    finally:
        plt.close(fig)


def _light_arrow(ax):
    """The light's star and the one orange arrow (L) of a diagram's axes: (source, tail, head)."""
    (source,) = [ln.get_xydata()[0] for ln in ax.get_lines() if ln.get_marker() == "*"]
    (light,) = [t for t in ax.texts if isinstance(t, Annotation) and t.arrow_patch is not None
                and t.arrow_patch.get_edgecolor()[:3] == matplotlib.colors.to_rgb("tab:orange")]
    return source, np.asarray(light.xyann, float), np.asarray(light.xy, float)


@pytest.mark.parametrize("name", ["fig_1_2_point_light_pupil", "fig_1_3_integral_schemes"])
def test_light_arrows_point_from_the_surface_to_the_light(name, cfg, monkeypatch):
    """L is the direction *to* the light: in every panel its arrow starts on the surface (y = 0) and
    ends nearer the light's star than it starts."""
    fig = drawn_figure(name, cfg, monkeypatch)
    try:
        for ax in fig.axes:
            source, tail, head = _light_arrow(ax)
            assert abs(tail[1]) < 1e-12                                           # starts on the surface
            assert np.linalg.norm(source - head) < np.linalg.norm(source - tail)  # and ends toward the light
    finally:
        plt.close(fig)


def test_fig_1_4_draws_every_angle_as_a_labelled_arc_delta_too(cfg, monkeypatch):
    fig = drawn_figure("fig_1_4_notation", cfg, monkeypatch)
    try:
        (ax,) = fig.axes
        names = {t.get_text() for t in ax.texts}
        assert {"θ$_L$", "θ$_V$", "α", "φ", "δ"} <= names
        green = [ln for ln in ax.get_lines() if ln.get_marker() in (None, "None", "none", "")
                 and matplotlib.colors.to_rgb(ln.get_color()) == matplotlib.colors.to_rgb("tab:green")]
        assert green                                                       # the arc of δ = ∠(N, H)
    finally:
        plt.close(fig)
