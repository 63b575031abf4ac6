"""Atomic outputs, exact CSV round trips, deterministic PNGs."""

import numpy as np
import pandas as pd
import pytest

from brdfs.pipeline import io
from brdfs.pipeline import plotting


def test_failed_write_leaves_no_partial_output(tmp_path):
    target = tmp_path / "out" / "table.csv"
    with pytest.raises(RuntimeError):
        with io.atomic_output(target) as tmp:
            tmp.write_text("half a tab")
            raise RuntimeError("computation failed")
    assert not target.exists() and list(target.parent.iterdir()) == []


def test_failed_write_keeps_the_previous_output(tmp_path):
    target = tmp_path / "table.csv"
    target.write_text("old")
    with pytest.raises(RuntimeError):
        with io.atomic_output(target) as tmp:
            tmp.write_text("new")
            raise RuntimeError
    assert target.read_text() == "old"


def test_csv_round_trip_is_exact(tmp_path):
    values = np.random.default_rng(0).random(1000) * np.logspace(-300, 300, 1000)
    df = pd.DataFrame({"name": ["a"] * 1000, "value": values})
    io.write_csv(df, tmp_path / "t.csv")
    assert io.read_csv(tmp_path / "t.csv").equals(df)
    assert io.roundtrip_csv(df).equals(df)


def test_logged_writes_messages_and_the_traceback(tmp_path):
    log = tmp_path / "logs" / "rule.log"
    with pytest.raises(ValueError):
        with io.logged(log) as logger:
            logger.info("starting")
            print("from print")
            raise ValueError("bad input")
    text = log.read_text()
    assert "starting" in text and "from print" in text and "ValueError: bad input" in text


def draw(path):
    fig, ax = plotting.new_axes("theta [deg]", "albedo")
    x = np.linspace(0, 90, 50)
    ax.plot(x, np.cos(np.radians(x)), label="cos")
    plotting.savefig(fig, path)


def test_pngs_are_deterministic_and_labelled(tmp_path):
    draw(tmp_path / "a.png")
    draw(tmp_path / "b.png")
    assert (tmp_path / "a.png").read_bytes() == (tmp_path / "b.png").read_bytes()
    assert b"Software" not in (tmp_path / "a.png").read_bytes()


def test_table_png_is_deterministic(tmp_path):
    df = pd.DataFrame({"metal": ["gold"], "printed": ["81.5"], "computed": [81.5407]})
    plotting.save_table_png(df, tmp_path / "a.png", "Table")
    plotting.save_table_png(df, tmp_path / "b.png", "Table")
    assert (tmp_path / "a.png").read_bytes() == (tmp_path / "b.png").read_bytes()


def test_csv_floats_stay_exact_after_a_library_sets_legacy_print_options(tmp_path):
    """colour-science sets numpy's legacy='1.13' print options on import, under which pandas
    writes 12 digits; write_csv pins the options."""
    import numpy as np
    import pandas as pd

    from brdfs.pipeline import io

    df = pd.DataFrame({"value": [0.30000000000000004, 1 / 3]})
    with np.printoptions(legacy="1.13"):
        io.write_csv(df, tmp_path / "t.csv")
    assert io.read_csv(tmp_path / "t.csv")["value"].tolist() == df["value"].tolist()


def test_importing_colour_through_the_package_leaves_numpy_print_options_alone():
    import numpy as np

    from brdfs.physics.spectral_colour import colour_module

    before = np.get_printoptions()
    colour_module()
    assert np.get_printoptions() == before
