"""Sphinx extension: the data dictionary of the results' CSVs as a page, ``data_dictionary.rst``.

On ``builder-inited`` it writes the page (generated, not committed) from the package alone
(:func:`brdfs.pipeline.data_dictionary.rst_page`): the dictionary shipped in the wheel, which
``tests/pipeline/test_data_dictionary.py`` holds equal to what ``docs/contract.md`` generates, and the
contract's units. One table per CSV; the wide tables scroll inside the page (``_static/wide_tables.css``).
"""
from __future__ import annotations

from pathlib import Path

PAGE = "data_dictionary.rst"


def write_data_dictionary_page(app) -> None:
    from brdfs.pipeline import data_dictionary

    text = data_dictionary.rst_page()
    path = Path(app.srcdir) / PAGE
    if not path.is_file() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def setup(app):
    app.connect("builder-inited", write_data_dictionary_page)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
