"""What the HTML report (``snakemake --report results/report.html``) says about each artifact.

Every table and figure appears in the report under the thesis chapter its registry decorator
declares (``chapter=``; by default the number in its name), with the caption of
``workflow/report/captions/<name>.rst`` followed by its verdict against the printed numbers.

One caption mechanism: the generic rule's ``report()`` caption is the template
``workflow/report/artifact.rst``, which Snakemake renders with Jinja (without a template loader)
when it writes the report. The template asks :class:`ReportTexts`, which
``workflow/rules/common.smk`` puts under the config key :data:`CONFIG_KEY` (no rule reads it), for
the artifact's caption and verdict. Nothing is read while Snakemake plans the DAG: the committed
caption and ``results/checks/published_comparison.csv`` (the output of ``merge_comparison``, which
the report includes) are read when the report renders them.
"""

from __future__ import annotations

import dataclasses
import functools
import os
import re
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING

from brdfs.pipeline.io import REPO_ROOT

if TYPE_CHECKING:  # pandas is imported when a comparison is read, not when the workflow plans
    import pandas as pd

CAPTIONS_DIR = REPO_ROOT / "workflow" / "report" / "captions"
CONFIG_KEY = "_report"

CHAPTERS = {
    1: "Chapter 1: Introduction, survey of BRDFs",
    2: "Chapter 2: Pumping up the albedo function",
    3: "Chapter 3: New simple models for specular materials",
    4: "Chapter 4: Models with fast importance sampling",
    5: "Chapter 5: Central concepts and future directions",
}
#: Category of the artifacts declared with ``chapter=None``: numerics and extensions beyond the thesis.
NUMERICS = "Beyond the thesis: numerics and extensions"

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


def category(chapter: int | None) -> str:
    """The report category of an artifact declared with ``chapter`` (its registry decorator).

    >>> category(3), category(None)
    ('Chapter 3: New simple models for specular materials', 'Beyond the thesis: numerics and extensions')
    """
    if chapter is None:
        return NUMERICS
    return CHAPTERS.get(chapter, f"Chapter {chapter}")


def subcategory(name: str) -> str:
    """``'Figures'``, ``'Tables'`` or, for ``extra_*``, ``'Checks beyond the print'``."""
    if name.startswith("fig_"):
        return "Figures"
    if name.startswith("table_"):
        return "Tables"
    return "Checks beyond the print"


#: A caption line ``.. include:: shared/<part>.rst``: a paragraph several captions share (the render
#: figures' renderer and outputs), written once under ``captions/shared/`` and expanded by
#: :func:`caption`, so the report and the docs show the same text (neither resolves the directive).
_INCLUDE = re.compile(r"^\.\. include:: +(\S+)[ \t]*$", re.MULTILINE)


def caption(name: str, directory: str | os.PathLike = CAPTIONS_DIR) -> str:
    """The reStructuredText caption of ``name`` (a placeholder if none has been written).

    A line ``.. include:: <path>`` (relative to ``directory``) is replaced by that file's text, which
    may include further files: a fact several captions state is written in one place.
    """
    path = Path(directory) / f"{name}.rst"
    if path.is_file():
        return _expand(path.read_text(encoding="utf-8"), Path(directory)).strip()
    return f"*{name}: no caption written yet (add* ``workflow/report/captions/{name}.rst`` *).*"


#: Where a rendered figure's measured seconds per panel are (``results/renders/<name>/timing.json``,
#: written beside its EXR files by the renders writer; never in the CSV or PNG, which stay byte-identical).
RENDER_TIMING = "results/renders/{name}/timing.json"


def render_priority(name: str, root: str | os.PathLike = REPO_ROOT) -> int:
    """Snakemake's priority of render job ``name``: 1 + its CPU seconds measured by the last build
    (:data:`RENDER_TIMING`, rounded), 1 where there is none or it cannot be read. The workflow runs its
    renders before every other job, longest first: on 2 cores the longest render started last ran alone
    for ~10 s of a forced render rebuild (benchmarks/speed_notes.md, "Session 6: render budget"). It
    orders jobs only; what runs and what it writes never depend on it."""
    import json

    try:
        panels = json.loads((Path(root) / RENDER_TIMING.format(name=name)).read_text(encoding="utf-8"))["panels"]
        return 1 + max(0, round(sum(float(p["cpu_s"]) for p in panels)))
    except (OSError, ValueError, TypeError, KeyError, OverflowError):
        return 1


def render_seconds(name: str, root: str | os.PathLike = REPO_ROOT) -> str:
    """RST: the measured render seconds of each panel of ``name`` in this build (``root`` /
    :data:`RENDER_TIMING`), or "" where the figure renders nothing or is not built."""
    import json

    path = Path(root) / RENDER_TIMING.format(name=name)
    if not path.is_file():
        return ""
    panels = json.loads(path.read_text(encoding="utf-8"))["panels"]
    cells = "; ".join(f"panel {p['panel']} ({_clean(p['title'], 60)}) {p['wall_s']:.1f} s wall, {p['cpu_s']:.1f} CPU-s"
                      for p in panels)
    return (f"*Measured in this build* (one thread per render; the first panel also compiles the kernels; "
            f"from ``{RENDER_TIMING.format(name=name)}``): {cells}.")


def _expand(text: str, directory: Path, seen: tuple = ()) -> str:
    """``text`` with every ``.. include::`` line replaced by the (expanded) text of its file."""
    def include(match):
        path = (directory / match[1]).resolve()
        if path in seen:
            raise ValueError(f"caption include cycle: {' -> '.join(map(str, (*seen, path)))}")
        if not path.is_file():
            raise FileNotFoundError(f"caption include {match[1]!r}: no file {path}")
        return _expand(path.read_text(encoding="utf-8"), directory, (*seen, path)).strip()

    return _INCLUDE.sub(include, text)


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
    from brdfs.pipeline.recomputed import rows_of   # it imports this module's categories

    if comparison is None:
        return "*Verdict: results/checks/published_comparison.csv is not built yet.*"
    rows = rows_of(name, comparison, sources)
    if rows.empty:
        return ("**Against the print:** the thesis prints no number for this artifact "
                "(no row in published_comparison.csv); the comparison is by eye, see above.")
    lines = []
    for artifact, group in rows.groupby("artifact", sort=False):
        differs = group[group["verdict"] != "reproduces"]
        kinds = ", ".join(f"{n} {v}" for v, n in differs["verdict"].value_counts().items())
        lines.append(
            f"* ``{artifact}`` ({_clean(group['source'].iloc[0], 80)}): "
            f"{len(group) - len(differs)} of {len(group)} printed numbers reproduce"
            + (f"; {kinds}." if kinds else ".")
        )
        if len(differs):
            lines.append("")  # a nested RST list needs a blank line before it
        for _, row in differs.head(6).iterrows():
            lines.append(
                f"  - {_clean(row['model'], 40)} {_clean(row['param_value'], 30)} {_clean(row['quantity'], 40)}: "
                f"printed {_format(row['published'])}, computed {_format(row['computed'])} ({row['verdict']}). "
                f"{_clean(row['reason'])}"
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
    rest = ", ".join(f"{n} {v}" for v, n in counts.items() if v != "reproduces")
    return (f"{len(comparison)} printed numbers compared: {counts.get('reproduces', 0)} reproduce"
            + (f", {rest}" if rest else "") + " (each with its reason and evidence).")


def _link(text: str, target: str, targets: set[str]) -> str:
    """An RST reference to the report's result ``target`` (the file name), or plain text if absent."""
    return f"`{_clean(text, 80)} <{target}_>`_" if target in targets else _clean(text, 80)


def landing(table: pd.DataFrame | None, chapters: pd.DataFrame | None, targets: set[str]) -> str:
    """The landing table as RST: per chapter its count of printed numbers that reproduce and differ,
    then each artifact with printed numbers (linked to its figure and its HTML table in the report),
    then the chapter's other artifacts, linked.

    Parameters
    ----------
    table : pandas.DataFrame or None
        ``results/report/landing.csv`` (None when not built yet).
    chapters : pandas.DataFrame or None
        ``results/report/chapters.csv``: each category's count, every printed number once.
    targets : set of str
        The file names of the report's results (what an RST reference can link to).
    """
    if table is None or chapters is None:
        return "*The landing table (results/report/landing.csv, rule report_pages) is not built yet.*"
    lines = []
    for _, chapter in chapters.iterrows():
        members = table[table["category"] == chapter["category"]]
        if members.empty:
            continue
        count = (f"{chapter['printed']} printed numbers: {chapter['reproduce']} reproduce, "
                 f"{chapter.get('explained', 0)} explained by a reading, {chapter['differ']} differ."
                 if int(chapter["printed"]) else "The thesis prints no number for these artifacts.")
        lines += [f"**{_clean(chapter['category'], 100)}.** {count}", ""]
        compared = members[members["printed"].astype(int) > 0]
        if len(compared):
            lines += [".. list-table::", "   :header-rows: 1", "",
                      "   * - artifact", "     - printed numbers", "     - reproduce", "     - explained by a reading",
                      "     - differ", "     - printed beside ours"]
            for _, row in compared.iterrows():
                page = f"{row['artifact']}.html"
                lines += [f"   * - {_link(row['thesis'] or row['artifact'], Path(row['png']).name, targets)}",
                          f"     - {row['printed']}", f"     - {row['reproduce']}", f"     - {row.get('explained', 0)}",
                          f"     - {row['differ']}",
                          f"     - {_link('HTML table', page, targets) if page in targets else '(figure)'}"]
            lines.append("")
        others = members[members["printed"].astype(int) == 0]
        if len(others):
            links = ", ".join(_link(r["thesis"] or r["artifact"], Path(r["png"]).name, targets)
                              for _, r in others.iterrows())
            lines += [f"Without printed numbers: {links}.", ""]
    return "\n".join(lines) + "\n"


@dataclasses.dataclass(frozen=True)
class ReportTexts:
    """The captions, verdicts and summary the report's caption templates show, read when rendered.

    Built while Snakemake plans (it reads nothing then); the templates call :meth:`caption`,
    :meth:`verdict` and :meth:`summary` when ``snakemake --report`` renders them.

    Attributes
    ----------
    sources : dict
        For each comparison (``artifact`` column), the artifacts it reads.
    comparison_csv : str
        ``results/checks/published_comparison.csv``.
    captions_dir : str
        The committed captions, ``workflow/report/captions``.
    landing_csv, chapters_csv : str
        ``results/report/landing.csv`` and ``chapters.csv``, the landing table the rule
        ``report_pages`` writes (per artifact, per chapter).
    root : str
        The directory holding ``results/`` (the rendered figures' measured seconds, :func:`render_seconds`).
    """

    sources: dict
    comparison_csv: str
    captions_dir: str = str(CAPTIONS_DIR)
    landing_csv: str = "results/report/landing.csv"
    chapters_csv: str = "results/report/chapters.csv"
    root: str = "."

    def caption(self, name: str) -> str:
        """:func:`caption` of ``name`` (the committed file), then its measured render seconds if any
        (:func:`render_seconds`)."""
        return "\n\n".join(filter(None, (caption(name, self.captions_dir), render_seconds(name, self.root))))

    def verdict(self, name: str) -> str:
        """:func:`verdict` of ``name`` against the comparison as it is now."""
        return verdict(name, _comparison(self.comparison_csv), self.sources)

    def summary(self) -> str:
        """:func:`summary` of the comparison as it is now."""
        return summary(_comparison(self.comparison_csv))

    def landing(self, files: Iterable = ()) -> str:
        """:func:`landing` of the landing table as it is now, linking the report's ``files``."""
        return landing(_comparison(self.landing_csv), _comparison(self.chapters_csv), {f.target for f in files})


def _comparison(path: str | os.PathLike) -> pd.DataFrame | None:
    path = Path(path)
    if not path.is_file():
        return None
    return _read_comparison(str(path.resolve()), path.stat().st_mtime_ns)


@functools.lru_cache(maxsize=4)
def _read_comparison(path: str, mtime_ns: int) -> pd.DataFrame:
    import pandas as pd

    return pd.read_csv(path, dtype=str, keep_default_na=False)


def comparison_html(comparison: pd.DataFrame) -> str:
    """``published_comparison.csv`` as a standalone HTML page (the report shows it in a frame).

    One section per group of printed numbers (``artifact``, with its ``source``), each a table of
    :func:`brdfs.pipeline.recomputed.comparison_table_html`: the printed digits beside ours, the
    verdict within the first seven columns (on screen at 1400 px), the differing cells marked;
    every row of the comparison, HTML-escaped, deterministic.
    """
    import html as html_lib

    from brdfs.pipeline import recomputed   # it imports this module's categories

    sections = []
    for artifact, rows in comparison.groupby("artifact", sort=False):
        sources = "; ".join(dict.fromkeys(str(s) for s in rows["source"]))
        sections.append(f"<h2>{html_lib.escape(str(artifact))} <small>({html_lib.escape(sources)})</small></h2>\n"
                        f"<p>{recomputed.Tally.of(rows).sentence()}</p>\n" + recomputed.comparison_table_html(rows))
    return recomputed.page_html("Every printed number against the recomputation",
                                f"<p>{html_lib.escape(summary(comparison))}</p>\n" + "\n".join(sections))
