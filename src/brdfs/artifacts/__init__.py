"""One module per thesis table or figure (or ``extra_*`` artifact); ``_*.py`` are helpers shared by several.

The modules register themselves with :mod:`brdfs.pipeline.registry` on import.
"""
