"""Sphinx extension: the "thesis recomputed" pages from a build's ``results/``.

* On ``builder-inited`` it writes ``recomputed/*.rst`` (:func:`brdfs.pipeline.docs_pages.write_pages`)
  from the directory named by the config value ``brdfs_results`` (default: the environment variable
  ``BRDFS_RESULTS``, else ``../results`` beside ``docs/``).
* The directive ``.. brdfs-artifact:: NAME`` puts one artifact (image, caption, verdict, printed
  beside ours, link to its CSV) into a hand-written page, e.g. the numerics notes.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import Directive
from docutils.statemachine import StringList
from sphinx.util.nodes import nested_parse_with_titles


def _results(app) -> Path:
    configured = app.config.brdfs_results or os.environ.get("BRDFS_RESULTS") or "../results"
    return (Path(app.srcdir) / configured).resolve()


def _tree(app):
    from brdfs.pipeline.docs_pages import ResultsTree

    if getattr(app, "_brdfs_tree", None) is None:
        app._brdfs_tree = ResultsTree.of(_results(app))
    return app._brdfs_tree


def write_recomputed_pages(app) -> None:
    from brdfs.pipeline.docs_pages import write_pages

    write_pages(_results(app), Path(app.srcdir) / "recomputed", tree=_tree(app))


class ArtifactDirective(Directive):
    """``.. brdfs-artifact:: NAME``: the artifact without a title (the page has its own)."""

    required_arguments = 1

    def run(self):
        from brdfs.pipeline.docs_pages import artifact_rst

        env = self.state.document.settings.env
        page_dir = Path(env.doc2path(env.docname)).parent
        text = artifact_rst(self.arguments[0], _tree(env.app), page_dir, level=None)
        holder = nodes.container()
        lines = StringList(text.splitlines(), source=f"brdfs-artifact {self.arguments[0]}")
        nested_parse_with_titles(self.state, lines, holder)
        return list(holder.children)


#: A literal or role segment of a docstring line (``code``, :math:`x`, `text`), left as it is.
_LITERAL = re.compile(r"(``.+?``|:[a-z:]+:`[^`]*`|`[^`]*`_{0,2})")
_TABLE_ROW = re.compile(r"^\s*[|+].*[|+]\s*$")


def escape_bars(line: str) -> str:
    """The package's docstrings write |x| for an absolute value, which reStructuredText reads as a
    substitution: outside literals, roles, doctests and table rows, each bar is escaped.
    A bar inside ``a|b`` or :math:`|x|` stays as it is.
    """
    stripped = line.lstrip()
    if "|" not in line or stripped.startswith((">>>", "... ")) or _TABLE_ROW.match(line):
        return line
    parts = _LITERAL.split(line)
    return "".join(part if k % 2 else part.replace("|", "\\|") for k, part in enumerate(parts))


def escape_docstring_bars(app, what, name, obj, options, lines) -> None:
    lines[:] = [escape_bars(line) for line in lines]


def setup(app):
    app.add_config_value("brdfs_results", "", "env")
    app.connect("builder-inited", write_recomputed_pages)
    app.add_directive("brdfs-artifact", ArtifactDirective)
    app.connect("autodoc-process-docstring", escape_docstring_bars, priority=400)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
