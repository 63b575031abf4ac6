"""Sphinx configuration of the brdfs documentation (``make docs``).

The pages under ``recomputed/`` are written from a build's ``results/`` before Sphinx reads the
sources (``_ext/thesis_pages.py``); point it at another build with ``-D brdfs_results=PATH`` or the
environment variable ``BRDFS_RESULTS``.
"""

import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS.parent / "src"))
sys.path.insert(0, str(DOCS / "_ext"))

project = "brdfs"
author = "the brdfs authors"
copyright = "2026, the brdfs authors"
import brdfs  # noqa: E402  (the version is written once, brdfs.__version__)

release = brdfs.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "thesis_pages",
    "model_pages",
    "data_dictionary_page",
]

root_doc = "index"
source_suffix = {".rst": "restructuredtext"}
exclude_patterns = ["_build", "contract.md"]
templates_path = []
# numpydoc renames a References section's citations per page; one cited but not referenced is no error.
suppress_warnings = ["ref.citation"]

# API reference: autosummary writes one page per public module into api/ (generated, not committed).
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": True}
autodoc_typehints = "none"            # numpydoc's Parameters sections carry the types
numpydoc_show_class_members = False   # autodoc lists the members; numpydoc would list them twice
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

html_theme = "alabaster"
html_theme_options = {"page_width": "96%", "body_max_width": "none", "sidebar_width": "230px",
                      "fixed_sidebar": True, "show_powered_by": False}
html_title = "brdfs: Neumann (2001) recomputed"
html_static_path = ["_static"]
# wide tables scroll inside the page instead of being cut (the reason and evidence columns)
html_css_files = ["wide_tables.css"]
html_use_index = True
html_show_sourcelink = False
mathjax_path = "no-mathjax.js"        # no network here: math stays as its TeX source (no CDN script)
