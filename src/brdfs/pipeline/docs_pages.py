"""The documentation's "thesis recomputed" pages, written from a build's ``results/``.

One reStructuredText page per chapter (and one for the artifacts beyond the thesis), each opening
with the chapter's count of printed numbers that reproduce and differ; then every table of the
chapter with its printed numbers beside ours (verdict, reason, evidence; the differing cells
highlighted), every figure with its caption and verdict, and each artifact linked to its CSV.
An index page holds the counts of all chapters. The Sphinx extension ``docs/_ext/thesis_pages.py``
calls :func:`write_pages` before Sphinx reads the sources, and its directive ``brdfs-artifact``
(the numerics notes) calls :func:`artifact_rst`::

    python -m brdfs.pipeline.docs_pages results docs/recomputed     # the same by hand

Missing files are said so on the page (a partial build gives partial pages, never a crash).
"""

from __future__ import annotations

import dataclasses
import functools
import os
import sys
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from brdfs.pipeline import recomputed, registry
from brdfs.pipeline.report import CAPTIONS_DIR, caption, render_seconds, thesis_number, verdict

if TYPE_CHECKING:
    import pandas as pd

COMPARISON = Path("checks") / "published_comparison.csv"

#: Page names of the categories (``recomputed/<page>.rst``), in :data:`recomputed.CATEGORIES` order.
PAGES = dict(zip(recomputed.CATEGORIES, ("chapter_1", "chapter_2", "chapter_3", "chapter_4", "chapter_5", "beyond")))


@dataclasses.dataclass(frozen=True)
class ResultsTree:
    """A build's ``results/`` directory and the registry's declarations of what is in it.

    Attributes
    ----------
    root : pathlib.Path
        The ``results`` directory (the artifacts' paths are ``<root>/../<artifact.csv>``).
    artifacts : mapping
        ``registry.artifacts()`` (or a test's stand-in: ``chapter``, ``kind``, ``csv``, ``png``).
    sources : mapping
        For each comparison, the artifacts it reads.
    captions_dir : pathlib.Path
        The committed captions (``workflow/report/captions``).
    """

    root: Path
    artifacts: Mapping
    sources: Mapping
    captions_dir: Path = CAPTIONS_DIR

    @classmethod
    def of(cls, root: str | os.PathLike) -> ResultsTree:
        """The tree at ``root`` with the package's registry."""
        return cls(Path(root).resolve(), registry.artifacts(),
                   {name: c.tables for name, c in registry.comparisons().items()})

    def path(self, relative: str) -> Path:
        """The file of an artifact path such as ``results/tables/x.csv``."""
        return self.root / Path(relative).relative_to("results")

    @functools.cached_property
    def comparison(self) -> pd.DataFrame | None:
        """``published_comparison.csv`` as strings (None if not built)."""
        import pandas as pd

        path = self.root / COMPARISON
        return pd.read_csv(path, dtype=str, keep_default_na=False) if path.is_file() else None

    @property
    def chapters(self) -> dict[str, int | None]:
        return {name: a.chapter for name, a in self.artifacts.items()}


def _relative(path: Path, page_dir: Path) -> str:
    return Path(os.path.relpath(path, page_dir)).as_posix()


def _indent(text: str, by: str = "   ") -> str:
    return "\n".join(by + line if line.strip() else "" for line in text.splitlines())


def _raw_html(markup: str) -> str:
    return ".. raw:: html\n\n" + _indent(markup) + "\n"


def _title(text: str, underline: str) -> str:
    return f"{text}\n{underline * len(text)}\n"


def tally_rst(tally: recomputed.Tally) -> str:
    """The count of a chapter's printed numbers, as an RST paragraph."""
    if not tally.printed:
        return "**The thesis prints no number for this chapter's artifacts**; they are compared by eye.\n"
    return (f"**{tally.sentence().rstrip('.')}** (each printed number counted once, under the chapter of the "
            "tables it is computed from; *explained by a reading*: the thesis's own procedure reconstructed, a "
            "misprinted input or Monte Carlo error, see ``published_verdicts.csv``).\n")


def artifact_rst(name: str, tree: ResultsTree, page_dir: Path, level: str | None = "-") -> str:
    """One artifact as RST: its title, image, caption, verdict, printed-beside-ours table and data link.

    Parameters
    ----------
    name : str
        A registered artifact.
    tree : ResultsTree
        The build.
    page_dir : pathlib.Path
        The directory of the page it goes into (images and links are relative to it).
    level : str or None
        The underline character of its title (None: no title, for a page that has its own).
    """
    artifact = tree.artifacts[name]
    title = f"{thesis_number(name)}: ``{name}``" if thesis_number(name) else f"``{name}``"
    parts = [f".. _{name}:\n", _title(title, level)] if level else []
    png, csv = tree.path(artifact.png), tree.path(artifact.csv)
    if png.is_file():
        image = f".. image:: {_relative(png, page_dir)}\n   :alt: {name}\n   :width: 100%\n"
    else:
        image = f"*Not built yet:* ``{artifact.png}``.\n"
    comparison = tree.comparison
    rows = None if comparison is None else recomputed.rows_of(name, comparison, tree.sources)
    if rows is not None and not rows.empty:
        against = (f"**Against the print:** {recomputed.Tally.of(rows).sentence()} "
                   "Differing cells are highlighted.\n\n" + _raw_html(recomputed.comparison_table_html(rows)))
    else:
        against = verdict(name, comparison, tree.sources) + "\n"
    text = caption(name, tree.captions_dir) + "\n"
    seconds = render_seconds(name, tree.root.parent)
    if seconds:
        text += "\n" + seconds + "\n"
    # A table reads best as its numbers beside the print, its PNG after; a figure is its image first.
    parts += [text, against, image] if artifact.kind == "table" else [image, text, against]
    if csv.is_file():
        parts.append(f"Data: :download:`{name}.csv <{_relative(csv, page_dir)}>` (tidy, with error columns).\n")
    return "\n".join(parts)


def _style() -> str:
    return _raw_html(f"<style>{recomputed.TABLE_STYLE}</style>")


def chapter_rst(category: str, names: Iterable[str], tree: ResultsTree, page_dir: Path,
                tally: recomputed.Tally) -> str:
    """The page of one category: its count, then its tables, figures and checks."""
    names = list(names)
    groups = (("Tables", [n for n in names if n.startswith("table_")]),
              ("Figures", [n for n in names if n.startswith("fig_")]),
              ("Checks beyond the print", [n for n in names if not n.startswith(("table_", "fig_"))]))
    parts = [_title(category, "="), _style(), tally_rst(tally)]
    parts.append("Contents: " + ", ".join(f":ref:`{thesis_number(n) or n} <{n}>`" for n in names) + ".\n")
    for heading, members in groups:
        if members:
            parts.append(_title(heading, "-"))
            parts += [artifact_rst(n, tree, page_dir, level="~") for n in members]
    return "\n".join(parts)


def summary_rst(tallies: Mapping[str, recomputed.Tally], tree: ResultsTree, pages: str) -> str:
    """Each chapter's count (a table linking the chapter pages, in the directory ``pages`` relative to
    the page that shows it; ``""``: the same directory) and the total."""
    total = recomputed.overall(tree.comparison) if tree.comparison is not None else recomputed.Tally(0, 0)
    lines = []
    if tree.comparison is None:
        lines.append(f"*Not built yet:* ``results/{COMPARISON.as_posix()}`` (run ``make all``).\n")
    lines += [".. list-table::", "   :header-rows: 1", "",
              "   * - chapter", "     - printed numbers", "     - reproduce", "     - explained by a reading",
              "     - differ"]
    for category, tally in tallies.items():
        lines += [f"   * - :doc:`{pages + '/' if pages else ''}{PAGES[category]}`", f"     - {tally.printed}", f"     - {tally.reproduce}",
                  f"     - {tally.explained}", f"     - {tally.differ}"]
    lines += ["   * - **all chapters**", f"     - **{total.printed}**", f"     - **{total.reproduce}**",
              f"     - **{total.explained}**", f"     - **{total.differ}**", ""]
    return "\n".join(lines) + "\n"


def index_rst(tallies: Mapping[str, recomputed.Tally], tree: ResultsTree, page_dir: Path) -> str:
    """The index of the pages: each chapter's count and the whole comparison's, then every artifact's."""
    lines = [_title("The thesis recomputed", "="),
             "Every table and figure of the thesis, recomputed from its equations, chapter by chapter; every "
             "number it prints beside ours. A number *reproduces* when ours, rounded to the printed digits, "
             "equals the print (an exact expression: within our error bound; a claim: it holds). Otherwise a "
             "declared search over the thesis's own procedures (quadrature rules and steps, grids, printing rules, "
             "constants, inputs in their rounding box, Monte Carlo) looks for a reading that explains it, accepted "
             "for a group only above a placebo; what no reading explains *differs*, naming its family and closest "
             "reading (see :doc:`../contract`).\n"]
    lines += [summary_rst(tallies, tree, ""), ".. toctree::", "   :maxdepth: 1", ""]
    lines += [f"   {page}" for page in PAGES.values()]
    lines += ["", _title("Every artifact", "-"),
              "Each artifact's own count (Table 1.1's numbers are compared under Table 3.1 and counted for both); "
              "the link goes to its figure, caption and verdict, the CSV to its data.", "",
              ".. list-table::", "   :header-rows: 1", "",
              "   * - artifact", "     - chapter", "     - printed numbers", "     - reproduce",
              "     - explained by a reading", "     - differ", "     - data"]
    for row in recomputed.landing(tree.artifacts, tree.comparison, tree.sources):
        csv = tree.path(row.csv)
        data = f":download:`CSV <{_relative(csv, page_dir)}>`" if csv.is_file() else "not built"
        lines += [f"   * - :ref:`{row.label} <{row.name}>`", f"     - :doc:`{PAGES[row.category]}`",
                  f"     - {row.tally.printed}", f"     - {row.tally.reproduce}", f"     - {row.tally.explained}",
                  f"     - {row.tally.differ}",
                  f"     - {data}"]
    return "\n".join(lines) + "\n"


def write_pages(results: str | os.PathLike, out_dir: str | os.PathLike,
                tree: ResultsTree | None = None) -> list[Path]:
    """Write ``index.rst`` and one page per category into ``out_dir``; return the pages written.

    A page whose text is unchanged is not rewritten (Sphinx then does not reread it).
    """
    tree = tree or ResultsTree.of(results)
    out_dir = Path(out_dir).resolve()
    out_dir.mkdir(parents=True, exist_ok=True)
    comparison = tree.comparison
    if comparison is None:
        tallies = {c: recomputed.Tally(0, 0) for c in recomputed.CATEGORIES}
    else:
        tallies = recomputed.chapter_tallies(comparison, tree.sources, tree.chapters)
    order = [r.name for r in recomputed.landing(tree.artifacts, None, {})]
    pages = {"index": index_rst(tallies, tree, out_dir)}
    # Included by the front page (docs/index.rst); not a page of its own (.inc is no source suffix).
    snippets = {"summary.inc": summary_rst(tallies, tree, out_dir.name)}
    for category, page in PAGES.items():
        names = [n for n in order if recomputed.category(tree.artifacts[n].chapter) == category]
        pages[page] = chapter_rst(category, names, tree, out_dir, tallies[category])
    written = []
    for path, text in [*((out_dir / f"{page}.rst", text) for page, text in pages.items()),
                       *((out_dir / name, text) for name, text in snippets.items())]:
        if not path.is_file() or path.read_text(encoding="utf-8") != text:
            path.write_text(text, encoding="utf-8")
        written.append(path)
    return written


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print("usage: python -m brdfs.pipeline.docs_pages RESULTS_DIR OUT_DIR", file=sys.stderr)
        return 2
    for path in write_pages(argv[1], argv[2]):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
