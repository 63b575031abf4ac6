"""Fig. 2.8's limb-profile chart, drawn inside compute, has the same pixels whatever matplotlib style the
process holds: a job alone draws it before brdfs.pipeline.plotting is imported, one forked from
``make all``'s pre-loaded parent after (the PNGs differed before the chart set the project's style)."""

from __future__ import annotations

import matplotlib
import numpy as np
import pandas as pd

from brdfs.artifacts import fig_2_8_pumping_render as fig
from brdfs.pipeline import plotting


def _profile() -> pd.DataFrame:
    theta = np.linspace(5.0, 85.0, 9)
    rows = [{"panel": k, "theta_v_deg": t, "luminance": 0.5 + 0.1 * k - 0.003 * t, "luminance_err": 0.01}
            for k in range(2) for t in theta]
    return pd.DataFrame(rows)


def test_the_limb_chart_does_not_depend_on_the_styles_the_process_imported():
    titles = ["n = 20", "n = 5000"]
    with matplotlib.rc_context(matplotlib.rcParamsDefault):
        plain = fig.profile_chart(_profile(), titles)
    with matplotlib.rc_context({**matplotlib.rcParamsDefault, **plotting.STYLE}):      # after plotting's import
        styled = fig.profile_chart(_profile(), titles)
    assert plain.shape == (fig.CHART_PX[1], fig.CHART_PX[0], 3)
    np.testing.assert_array_equal(plain, styled)
