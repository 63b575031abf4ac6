"""The thesis recomputed, as a reader sees it: each artifact's printed numbers beside ours.

One home for what the HTML report (``workflow/rules/report.smk``) and the documentation
(:mod:`brdfs.pipeline.docs_pages`) both show, read from a build's ``results/``:

* which rows of ``results/checks/published_comparison.csv`` belong to an artifact
  (:func:`rows_of`: the comparisons that read its CSV, or whose ``source`` names its thesis number);
* the count of printed numbers that reproduce and differ, per artifact (:func:`landing`) and per
  chapter (:func:`chapter_tallies`: from the rows the chapter's artifacts list, each printed number
  once in the chapter) and overall (:func:`overall`);
* the printed number beside ours as an HTML table whose differing cells are marked
  (:func:`comparison_table_html`), and an artifact's tidy CSV as an HTML table (:func:`data_table_html`).

Pure functions of DataFrames and the registry's declarations; pandas is imported by the callers.
"""

from __future__ import annotations

import dataclasses
import html
import re
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING

from brdfs.pipeline.report import CHAPTERS, NUMERICS, category, thesis_number

if TYPE_CHECKING:
    import pandas as pd

REPRODUCES = "reproduces"

#: The report's and the documentation's categories, in reading order.
CATEGORIES = (*CHAPTERS.values(), NUMERICS)

#: Class of a ``<td>`` whose printed number and ours differ (styled by :data:`TABLE_STYLE`).
DIFFERS_CLASS = "differs"

TABLE_STYLE = """
table.brdfs { border-collapse: collapse; font-size: 0.9em; margin: 0.5em 0 1.5em 0; }
table.brdfs th, table.brdfs td { border: 1px solid #ccc; padding: 2px 6px; vertical-align: top; text-align: left; }
table.brdfs th { background: #eee; }
table.brdfs td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
table.brdfs td.differs { background: #ffd7b5; font-weight: bold; }
table.brdfs tr.differs td.verdict { color: #b34700; font-weight: bold; }
table.brdfs tr.reproduces td.verdict { color: #2e7d32; }
table.brdfs td.reason { min-width: 18em; max-width: 30em; }
table.brdfs td.evidence { min-width: 10em; max-width: 16em; overflow-wrap: anywhere; }
div.brdfs-scroll { overflow-x: auto; max-width: 100%; }
"""


@dataclasses.dataclass(frozen=True)
class Tally:
    """How many printed numbers were compared; how many reproduce as printed, how many a reading
    explains (the thesis's procedure reconstructed, a misprinted input, Monte Carlo error, a reading
    of a small group: ``published.READING_VERDICTS``), and how many differ."""

    printed: int
    reproduce: int
    explained: int = 0

    @property
    def differ(self) -> int:
        """The printed numbers that neither reproduce nor have a reading."""
        return self.printed - self.reproduce - self.explained

    @classmethod
    def of(cls, rows: pd.DataFrame) -> Tally:
        """The tally of comparison ``rows`` (``verdict`` column)."""
        from brdfs.pipeline.published import READING_VERDICTS

        return cls(len(rows), int((rows["verdict"] == REPRODUCES).sum()),
                   int(rows["verdict"].isin(READING_VERDICTS).sum()))

    def __add__(self, other: Tally) -> Tally:
        return Tally(self.printed + other.printed, self.reproduce + other.reproduce, self.explained + other.explained)

    def sentence(self) -> str:
        """``'12 printed numbers: 9 reproduce, 2 explained by a reading, 1 differ.'``

        >>> Tally(12, 9, 2).sentence(), Tally(3, 3).sentence(), Tally(0, 0).sentence()
        ('12 printed numbers: 9 reproduce, 2 explained by a reading, 1 differ.', '3 printed numbers: 3 reproduce, 0 differ.', 'No printed number.')
        """
        if not self.printed:
            return "No printed number."
        noun = "number" if self.printed == 1 else "numbers"
        explained = f"{self.explained} explained by a reading, " if self.explained else ""
        return f"{self.printed} printed {noun}: {self.reproduce} reproduce, {explained}{self.differ} differ."


def rows_of(name: str, comparison: pd.DataFrame, sources: Mapping[str, Iterable[str]]) -> pd.DataFrame:
    """The comparison rows about artifact ``name``.

    A row belongs to ``name`` when its comparison (``artifact`` column) reads ``name``'s CSV
    (``sources``), or when its ``source`` names ``name``'s thesis number (Table 1.1's rows are
    compared under Table 3.1, as ``'Table 3.1 (= Table 1.1)'``).

    Parameters
    ----------
    name : str
        A registered artifact.
    comparison : pandas.DataFrame
        ``results/checks/published_comparison.csv``.
    sources : mapping
        For each comparison, the artifacts it reads (``registry.comparisons()[c].tables``).
    """
    number = thesis_number(name)
    pattern = re.compile(re.escape(number) + r"\b") if number else None
    reads = comparison["artifact"].map(lambda a: name in sources.get(a, ()))
    names = comparison["source"].map(lambda s: bool(pattern and pattern.search(str(s))))
    return comparison[reads | names]


def chapter_tallies(comparison: pd.DataFrame, sources: Mapping[str, Iterable[str]],
                    chapters: Mapping[str, int | None]) -> dict[str, Tally]:
    """Each category's :class:`Tally`, computed from the rows its artifacts list: the union of
    :func:`rows_of` over the category's artifacts, each printed number once within the category.

    A printed number listed under artifacts of two chapters (Table 1.1's, which the thesis prints
    again as Table 3.1's Blinn column) counts in both, so the chapters need not add up to the whole
    comparison: :func:`overall` is that. Every category of :data:`CATEGORIES` is present, in order.
    """
    members: dict[str, set] = {c: set() for c in CATEGORIES}
    for name, chapter in chapters.items():
        members.setdefault(category(chapter), set()).update(rows_of(name, comparison, sources).index)
    return {c: Tally.of(comparison.loc[sorted(members[c])]) for c in CATEGORIES}


def overall(comparison: pd.DataFrame) -> Tally:
    """The whole comparison's :class:`Tally`, each printed number once."""
    return Tally.of(comparison)


@dataclasses.dataclass(frozen=True)
class LandingRow:
    """One line of the landing table: an artifact, its category, its files and its tally."""

    name: str
    category: str
    csv: str
    png: str
    tally: Tally

    @property
    def label(self) -> str:
        """``'Table 3.2'``, or the name of an ``extra_*`` artifact."""
        return thesis_number(self.name) or self.name


def landing(artifacts: Mapping, comparison: pd.DataFrame | None,
            sources: Mapping[str, Iterable[str]]) -> list[LandingRow]:
    """One :class:`LandingRow` per artifact, by category (:data:`CATEGORIES`) then thesis number.

    ``artifacts`` maps names to the registry's declarations (``chapter``, ``csv``, ``png``);
    with ``comparison`` None every tally is empty.
    """
    rows = []
    for name, artifact in artifacts.items():
        if comparison is None:
            tally = Tally(0, 0)
        else:
            tally = Tally.of(rows_of(name, comparison, sources))
        rows.append(LandingRow(name, category(artifact.chapter), artifact.csv, artifact.png, tally))
    return sorted(rows, key=lambda r: (CATEGORIES.index(r.category) if r.category in CATEGORIES else 99,
                                       _reading_order(r.name)))


def _reading_order(name: str) -> tuple:
    """Tables, then figures, by thesis number; then the rest by name."""
    match = re.match(r"(table|fig)_(\d+)_(\d+)_", name)
    if match:
        return (0 if match[1] == "table" else 1, int(match[2]), int(match[3]), name)
    return (2, 0, 0, name)


def number_text(value) -> str:
    """A printed or computed number as a short string (``'1.62046'``; non-numbers unchanged).

    >>> number_text("1.6204616"), number_text("<=1 and >0.85"), number_text("")
    ('1.62046', '<=1 and >0.85', '')
    """
    text = str(value)
    try:
        return f"{float(text):.6g}"
    except ValueError:
        return text


def _cell(text, css: str = "") -> str:
    attribute = f' class="{css}"' if css else ""
    return f"<td{attribute}>{html.escape(str(text))}</td>"


#: The columns of :func:`comparison_table_html`: header, CSS class, the cell's text from a row.
COMPARISON_COLUMNS = (
    ("model", "", lambda row: row.get("model", "")),
    ("parameter", "", lambda row: _parameter(row)),
    ("quantity", "", lambda row: row.get("quantity", "")),
    ("printed", "num printed", lambda row: row.get("published", "")),     # the digits as printed
    ("ours", "num ours", lambda row: number_text(row.get("computed", ""))),
    ("± error", "num", lambda row: number_text(row.get("computed_err", ""))),
    ("verdict", "verdict", lambda row: row.get("verdict", "")),
    ("reason", "reason", lambda row: _reason(row)),
    ("evidence", "evidence", lambda row: row.get("evidence", "")),
)

#: The cells marked when a row's printed number and ours differ.
MARKED_WHEN_DIFFERING = ("printed", "ours")


def _parameter(row) -> str:
    """``'n = 128'`` (or the value alone when no parameter is named)."""
    name, value = str(row.get("param", "") or ""), str(row.get("param_value", "") or "")
    return f"{name} = {value}" if name and value else name or value


def _reason(row) -> str:
    """The reason, followed by the reading that reproduces the print, where one does."""
    reason, reading = str(row.get("reason", "") or ""), str(row.get("reading", "") or "")
    if not reading:
        return reason
    value = str(row.get("value_under_reading", "") or "")
    stop = "" if not reason or reason.rstrip().endswith((".", "!", "?")) else "."
    return f"{reason}{stop} Reading that reproduces the print: {reading}" + (f" ({number_text(value)})." if value else ".")


def comparison_table_html(rows: pd.DataFrame) -> str:
    """The printed numbers beside ours as an HTML ``<table class="brdfs">`` (in a scrolling box).

    One row per printed number, the printed digits verbatim; when it differs, the printed and the
    computed cells carry the class :data:`DIFFERS_CLASS` (and the row the class ``differs``);
    every value is HTML-escaped.
    """
    head = "".join(f"<th>{html.escape(header)}</th>" for header, _, _ in COMPARISON_COLUMNS)
    body = []
    for _, row in rows.iterrows():
        differs = row["verdict"] != REPRODUCES
        cells = []
        for header, css, text in COMPARISON_COLUMNS:
            marked = differs and header in MARKED_WHEN_DIFFERING
            cells.append(_cell(text(row), " ".join(filter(None, (css, DIFFERS_CLASS if marked else "")))))
        verdict = DIFFERS_CLASS if differs else REPRODUCES
        body.append(f'<tr class="{verdict}">' + "".join(cells) + "</tr>")
    return (f'<div class="brdfs-scroll"><table class="brdfs comparison">\n<thead><tr>{head}</tr></thead>\n<tbody>\n'
            + "\n".join(body) + "\n</tbody>\n</table></div>")


def data_table_html(df: pd.DataFrame, max_rows: int = 60) -> str:
    """The first ``max_rows`` rows of an artifact's tidy CSV as an HTML table (numbers shortened)."""
    head = "".join(f"<th>{html.escape(str(c))}</th>" for c in df.columns)
    body = []
    for _, row in df.head(max_rows).iterrows():
        body.append("<tr>" + "".join(_cell(number_text(v), "num") for v in row) + "</tr>")
    more = (f'\n<p class="more">{len(df) - max_rows} more rows in the CSV.</p>' if len(df) > max_rows else "")
    return (f'<table class="brdfs data">\n<thead><tr>{head}</tr></thead>\n<tbody>\n'
            + "\n".join(body) + "\n</tbody>\n</table>" + more)


def page_html(title: str, body: str) -> str:
    """A standalone HTML page (the report shows it in a frame), styled by :data:`TABLE_STYLE`."""
    return ("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">"
            f"<title>{html.escape(title)}</title>"
            f"<style>body {{ font-family: sans-serif; font-size: 13px; margin: 1em; }}{TABLE_STYLE}</style>"
            f"</head><body>\n<h1>{html.escape(title)}</h1>\n{body}\n</body></html>\n")


def landing_table_html(rows: Iterable[LandingRow], link=lambda row: None) -> str:
    """The landing table: artifact, printed numbers, reproduce, differ, and a link to each.

    ``link(row)`` gives the ``href`` of an artifact (None: its name without a link).
    """
    head = "".join(f"<th>{h}</th>" for h in ("category", "artifact", "printed numbers", "reproduce",
                                               "explained by a reading", "differ"))
    body = []
    for row in rows:
        href = link(row)
        label = html.escape(row.label) + ("" if row.label == row.name else f" <code>{html.escape(row.name)}</code>")
        anchor = f'<a href="{html.escape(href)}">{label}</a>' if href else label
        differ = _cell(row.tally.differ, "num differs" if row.tally.differ else "num")
        body.append(f"<tr>{_cell(row.category)}<td>{anchor}</td>{_cell(row.tally.printed, 'num')}"
                    f"{_cell(row.tally.reproduce, 'num')}{_cell(row.tally.explained, 'num')}{differ}</tr>")
    return (f'<table class="brdfs landing">\n<thead><tr>{head}</tr></thead>\n<tbody>\n'
            + "\n".join(body) + "\n</tbody>\n</table>")


def landing_frame(rows: Iterable[LandingRow]) -> pd.DataFrame:
    """The landing table as a tidy DataFrame (``results/report/landing.csv``)."""
    import pandas as pd

    return pd.DataFrame(
        [{"artifact": r.name, "thesis": thesis_number(r.name) or "", "category": r.category,
          "printed": r.tally.printed, "reproduce": r.tally.reproduce, "explained": r.tally.explained,
          "differ": r.tally.differ,
          "csv": r.csv, "png": r.png} for r in rows],
        columns=["artifact", "thesis", "category", "printed", "reproduce", "explained", "differ", "csv", "png"],
    )


def chapters_frame(tallies: Mapping[str, Tally]) -> pd.DataFrame:
    """Each category's :class:`Tally` as a tidy DataFrame (``results/report/chapters.csv``)."""
    import pandas as pd

    return pd.DataFrame([{"category": c, "printed": t.printed, "reproduce": t.reproduce, "explained": t.explained,
                          "differ": t.differ} for c, t in tallies.items()],
                        columns=["category", "printed", "reproduce", "explained", "differ"])


def chapter_table_html(tallies: Mapping[str, Tally], total: Tally) -> str:
    """Each category's count of printed numbers that reproduce and differ, with the total (each
    printed number once: :func:`overall`)."""
    body = [f"<tr>{_cell(c)}{_cell(t.printed, 'num')}{_cell(t.reproduce, 'num')}{_cell(t.explained, 'num')}"
            f"{_cell(t.differ, 'num differs' if t.differ else 'num')}</tr>"
            for c, t in (*tallies.items(), ("All chapters", total))]
    return ('<table class="brdfs chapters">\n<thead><tr><th>chapter</th><th>printed numbers</th>'
            "<th>reproduce</th><th>explained by a reading</th><th>differ</th></tr></thead>\n<tbody>\n" + "\n".join(body) + "\n</tbody>\n</table>")


def landing_page_html(rows: Iterable[LandingRow], tallies: Mapping[str, Tally], total: Tally) -> str:
    """``results/report/landing.html``: the chapter counts, then every artifact's."""
    return page_html(
        "The thesis recomputed: printed numbers against ours",
        "<p>Every number the thesis prints is compared with the recomputation "
        "(<code>results/checks/published_comparison.csv</code>). Per chapter, each printed number once:</p>\n"
        + chapter_table_html(tallies, total)
        + "\n<p>Per artifact (Table 1.1's numbers are compared under Table 3.1 and counted for both):</p>\n"
        + landing_table_html(rows),
    )


def table_page_html(name: str, rows: pd.DataFrame, data: pd.DataFrame) -> str:
    """A table artifact as HTML: its printed numbers beside ours (differing cells marked), then its data."""
    title = f"{thesis_number(name) or name}: printed beside recomputed"
    if rows.empty:
        compared = "<p>The thesis prints no number for this table; its data follow.</p>"
    else:
        compared = (f"<p>{Tally.of(rows).sentence()} Differing cells are marked.</p>\n"
                    + comparison_table_html(rows))
    return page_html(title, f"<p><code>{html.escape(name)}</code></p>\n{compared}\n"
                            f"<h2>The data (<code>{html.escape(name)}.csv</code>)</h2>\n" + data_table_html(data))
