"""What the HTML report (``snakemake --report results/report.html``) says about each artifact.

Every table and figure appears in the report under its thesis chapter (the number in its
name; :data:`EXTRA_CHAPTERS` places the ``extra_*`` artifacts), with the caption of
``workflow/report/captions/<name>.rst`` followed by its verdict against the printed
numbers, read from ``results/checks/published_comparison.csv`` when the report is built.

Snakemake renders a caption file with Jinja, without a template loader; the generic
caption ``workflow/report/artifact.rst`` therefore reads the texts from
:func:`context`, which ``workflow/rules/common.smk`` puts under the config key
:data:`CONFIG_KEY` after the configuration has been validated (no rule reads it).
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable
from pathlib import Path

import pandas as pd

from brdfs.pipeline.io import REPO_ROOT

CAPTIONS_DIR = REPO_ROOT / "workflow" / "report" / "captions"
CONFIG_KEY = "_report"

CHAPTERS = {
    1: "Chapter 1: Introduction, survey of BRDFs",
    2: "Chapter 2: Pumping up the albedo function",
    3: "Chapter 3: New simple models for specular materials",
    4: "Chapter 4: Models with fast importance sampling",
    5: "Chapter 5: Central concepts and future directions",
}
#: Category of the checks that belong to no chapter (the integration engine itself).
NUMERICS = "Numerics: accuracy and stability of the integration"

#: The chapter whose numbers an ``extra_*`` artifact examines (None: :data:`NUMERICS`).
EXTRA_CHAPTERS = {
    "extra_metal_a0_readings": 1,
    "extra_he_torrance_albedo": 2,
    "extra_pumping_albedo_phong": 2,
    "extra_pumping_albedo_blinn": 2,
    "extra_chapter3_claims": 3,
    "extra_grazing_divergence": 3,
    "extra_divergence_readings": 3,
    "extra_ward_in_range": 3,
    "extra_work_precision": None,
    "extra_stability_grazing": None,
}

_NUMBERED = re.compile(r"(fig|table)_(\d+)_(\d+)_")


def thesis_number(name: str) -> str | None:
    """``'Figure 2.1'`` for ``fig_2_1_...``, ``'Table 3.2'`` for ``table_3_2_...``, None for extras.

    >>> thesis_number("fig_4_13_inverse_cdf"), thesis_number("extra_ward_in_range")
    ('Figure 4.13', None)
    """
    match = _NUMBERED.match(name)
    if not match:
        return None
    kind = "Figure" if match[1] == "fig" else "Table"
    return f"{kind} {match[2]}.{match[3]}"


def category(name: str) -> str:
    """The report category of an artifact: its thesis chapter.

    >>> category("table_3_2_ward_cmax")
    'Chapter 3: New simple models for specular materials'
    """
    match = _NUMBERED.match(name)
    chapter = int(match[2]) if match else EXTRA_CHAPTERS.get(name, None)
    if chapter is None:
        return NUMERICS if name in EXTRA_CHAPTERS else "Beyond the thesis"
    return CHAPTERS.get(chapter, f"Chapter {chapter}")


def subcategory(name: str) -> str:
    """``'Figures'``, ``'Tables'`` or, for ``extra_*``, ``'Checks beyond the print'``."""
    if name.startswith("fig_"):
        return "Figures"
    if name.startswith("table_"):
        return "Tables"
    return "Checks beyond the print"


def caption(name: str, directory: str | os.PathLike = CAPTIONS_DIR) -> str:
    """The reStructuredText caption of ``name`` (a placeholder if none has been written)."""
    path = Path(directory) / f"{name}.rst"
    if path.is_file():
        return path.read_text(encoding="utf-8").strip()
    return f"*{name}: no caption written yet (add* ``workflow/report/captions/{name}.rst`` *).*"


def _format(value) -> str:
    try:
        return f"{float(value):.6g}"
    except (TypeError, ValueError):
        return str(value)


def _clean(text, limit: int = 400) -> str:
    """One line of plain text safe inside an RST bullet."""
    text = " ".join(str(text).split()).replace("*", "\\*").replace("`", "'").replace("|", "/")
    return text if len(text) <= limit else text[: limit - 3] + "..."


def verdict(name: str, comparison: pd.DataFrame | None, sources: dict[str, Iterable[str]]) -> str:
    """The artifact's verdict against the print, as RST.

    Parameters
    ----------
    name : str
        The artifact.
    comparison : pandas.DataFrame or None
        ``results/checks/published_comparison.csv`` (None when not built yet).
    sources : dict
        For each comparison (``artifact`` column), the artifacts it reads.
    """
    if comparison is None:
        return "*Verdict: results/checks/published_comparison.csv is not built yet.*"
    number = thesis_number(name)
    pattern = re.compile(re.escape(number) + r"\b") if number else None
    rows = comparison[
        comparison["artifact"].map(lambda a: name in sources.get(a, ()))
        | comparison["source"].map(lambda s: bool(pattern and pattern.search(str(s))))
    ]
    if rows.empty:
        return ("**Against the print:** the thesis prints no number for this artifact "
                "(no row in published_comparison.csv); the comparison is by eye, see above.")
    lines = []
    for artifact, group in rows.groupby("artifact", sort=False):
        differs = group[group["verdict"] != "reproduces"]
        lines.append(
            f"* ``{artifact}`` ({_clean(group['source'].iloc[0], 80)}): "
            f"{len(group) - len(differs)} of {len(group)} printed numbers reproduce, {len(differs)} differ."
        )
        if len(differs):
            lines.append("")  # a nested RST list needs a blank line before it
        for _, row in differs.head(6).iterrows():
            lines.append(
                f"  - {_clean(row['model'], 40)} {_clean(row['param_value'], 30)} {_clean(row['quantity'], 40)}: "
                f"printed {_format(row['published'])}, computed {_format(row['computed'])}. {_clean(row['reason'])}"
            )
        if len(differs) > 6:
            lines.append(f"  - ... and {len(differs) - 6} more (see published_comparison.csv).")
        lines.append("")
    return "**Against the print** (results/checks/published_comparison.csv):\n\n" + "\n".join(lines)


def summary(comparison: pd.DataFrame | None) -> str:
    """The overall count of printed numbers that reproduce and differ."""
    if comparison is None:
        return "results/checks/published_comparison.csv is not built yet."
    counts = comparison["verdict"].value_counts()
    return (f"{len(comparison)} printed numbers compared: {counts.get('reproduces', 0)} reproduce, "
            f"{len(comparison) - counts.get('reproduces', 0)} differ (each with its reason and evidence).")


def context(names: Iterable[str], sources: dict[str, Iterable[str]],
            comparison_csv: str | os.PathLike) -> dict:
    """Captions, verdicts and the summary that the report's caption templates read."""
    path = Path(comparison_csv)
    comparison = pd.read_csv(path, dtype=str, keep_default_na=False) if path.is_file() else None
    return {
        "captions": {n: caption(n) for n in names},
        "verdicts": {n: verdict(n, comparison, sources) for n in names},
        "summary": summary(comparison),
    }


_HTML_STYLE = """
body { font-family: sans-serif; font-size: 12px; margin: 1em; }
table { border-collapse: collapse; }
th, td { border: 1px solid #ccc; padding: 2px 4px; vertical-align: top; text-align: left; }
th { background: #eee; position: sticky; top: 0; }
tr.differs td { background: #fff3e0; }
tr.reproduces td { background: #f1f8e9; }
td.reason, td.evidence { min-width: 24em; max-width: 40em; }
"""


def comparison_html(comparison: pd.DataFrame) -> str:
    """``published_comparison.csv`` as a standalone HTML page (the report shows it in a frame).

    One row per printed number, coloured by verdict, every column shown; deterministic.
    """
    import html as html_lib

    columns = list(comparison.columns)
    head = "".join(f"<th>{html_lib.escape(c)}</th>" for c in columns)
    body = []
    for _, row in comparison.iterrows():
        cells = "".join(
            f'<td class="{html_lib.escape(c)}">{html_lib.escape(str(row[c]))}</td>' for c in columns
        )
        body.append(f'<tr class="{html_lib.escape(str(row.get("verdict", "")))}">{cells}</tr>')
    return (
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>published_comparison</title>"
        f"<style>{_HTML_STYLE}</style></head><body>\n<p>{html_lib.escape(summary(comparison))}</p>\n"
        f"<table>\n<thead><tr>{head}</tr></thead>\n<tbody>\n" + "\n".join(body) + "\n</tbody></table>\n</body></html>\n"
    )
