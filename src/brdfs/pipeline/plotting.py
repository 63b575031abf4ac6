"""One figure style for every artifact, and deterministic PNG output.

Importing this module selects the non-interactive Agg backend and applies
:data:`STYLE`. Every PNG is written by :func:`savefig` at :data:`DPI` with no
software tag in its metadata, so the same figure gives the same bytes run
after run.
"""

from __future__ import annotations

import os

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (after selecting the backend)
import pandas as pd  # noqa: E402

#: Resolution of every PNG.
DPI = 150

#: The project's figure style (matplotlib rcParams).
STYLE = {
    "figure.figsize": (6.4, 4.2),
    "font.size": 9,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "legend.frameon": False,
    "lines.linewidth": 1.4,
}
matplotlib.rcParams.update(STYLE)


def new_axes(xlabel: str, ylabel: str, title: str = "") -> tuple[plt.Figure, plt.Axes]:
    """A figure with one labelled axes, in the project style.

    Parameters
    ----------
    xlabel, ylabel : str
        Axis labels, with units.
    title : str, optional
        Axes title.
    """
    fig, ax = plt.subplots()
    ax.set(xlabel=xlabel, ylabel=ylabel, title=title)
    return fig, ax


def savefig(fig: plt.Figure, path: str | os.PathLike) -> None:
    """Save ``fig`` as a deterministic PNG and close it.

    Axes with labelled artists get a legend.
    """
    for ax in fig.axes:
        handles, _ = ax.get_legend_handles_labels()
        if handles and ax.get_legend() is None:
            ax.legend()
    try:
        fig.savefig(path, format="png", dpi=DPI, metadata={"Software": None}, bbox_inches="tight", pad_inches=0.1)
    finally:
        plt.close(fig)


def save_table_png(df: pd.DataFrame, path: str | os.PathLike, title: str, float_format: str = "{:.6g}") -> None:
    """Render a table (typically published beside computed) as a PNG.

    Parameters
    ----------
    df : pandas.DataFrame
        The table as it should read; column names become the header.
    path : str or os.PathLike
        The PNG to write.
    title : str
        Title above the table (the thesis's table number and caption).
    float_format : str, optional
        Format of float cells; other cells are shown with ``str``.
    """
    cells = [
        [float_format.format(v) if isinstance(v, float) else str(v) for v in row] for row in df.itertuples(index=False)
    ]
    fig, ax = plt.subplots(figsize=(1.2 * len(df.columns), 0.25 * (len(df) + 2)))
    ax.axis("off")
    ax.set_title(title, loc="left")
    table = ax.table(cellText=cells, colLabels=[str(c) for c in df.columns], loc="upper left", cellLoc="right")
    table.auto_set_font_size(False)
    table.set_fontsize(8)
    table.auto_set_column_width(range(len(df.columns)))
    for (row, _), cell in table.get_celld().items():
        cell.set_linewidth(0.3)
        if row == 0:
            cell.set_text_props(weight="bold")
    savefig(fig, path)
