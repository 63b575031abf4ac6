"""The candidate explorer stack that was measured and not taken: a Bokeh server app (``bokeh serve``)
with the same views of one model (GGX) as brdfs explore computes them (brdfs.explore.views): an alpha
slider, θ_L, the albedo curve with its band, the lobe, the lit sphere.  Run by
benchmarks/bench_explorer_stack.py when bokeh is importable; not part of the package.

    bokeh serve benchmarks/explorer_stack/bokeh_app.py --port 5006
"""
import numpy as np
from bokeh.io import curdoc
from bokeh.layouts import column, row
from bokeh.models import ColumnDataSource, Slider
from bokeh.plotting import figure

import brdfs
from brdfs.explore import views

alpha = Slider(title="alpha", start=0.01, end=1.0, value=0.3, step=0.01, name="alpha")
theta = Slider(title="theta_L", start=0, end=90, value=30, step=0.5, name="theta")
albedo_src = ColumnDataSource(dict(x=[], y=[], lo=[], hi=[]), name="albedo")
lobe_src = ColumnDataSource(dict(x=[], y=[]), name="lobe")
sphere_src = ColumnDataSource(dict(image=[]), name="sphere")

p_albedo = figure(width=380, height=250, title="albedo", x_range=(0, 90))
p_albedo.varea("x", "lo", "hi", source=albedo_src, alpha=0.3)
p_albedo.line("x", "y", source=albedo_src)
p_lobe = figure(width=380, height=250, title="lobe", match_aspect=True)
p_lobe.line("x", "y", source=lobe_src)
p_sphere = figure(width=276, height=276, x_range=(0, 1), y_range=(0, 1), title="sphere")
p_sphere.image_rgba("image", x=0, y=0, dw=1, dh=1, source=sphere_src)


def update(parameters_changed=True):
    model = brdfs.model("ggx", alpha=float(alpha.value))
    if parameters_changed or not albedo_src.data["x"]:
        curve = views.albedo_curve(model)
        v, e = np.array(curve["value"], float), np.array(curve["error"], float)
        albedo_src.data = dict(x=curve["theta"], y=v, lo=v - e, hi=v + e)
        update.curve = curve
    lobe = views.lobe(model, float(theta.value))
    t, r = np.radians(lobe["theta_v"]), np.array(lobe["fcos"], float)
    lobe_src.data = dict(x=r * np.sin(t), y=r * np.cos(t))
    rgb = views.sphere_rgb(model, update.curve, float(theta.value), 256)
    rgba = np.dstack([rgb, np.full(rgb.shape[:2], 255, np.uint8)])[::-1].copy()
    sphere_src.data = dict(image=[rgba.view(np.uint32).reshape(rgb.shape[:2])])


update()
alpha.on_change("value", lambda attr, old, new: update(True))
theta.on_change("value", lambda attr, old, new: update(False))
curdoc().add_root(column(row(alpha, theta), row(p_lobe, p_albedo), p_sphere))
