"""The bottom layer: the shared value type (:mod:`.estimate`) and the vectorised adaptive
Gauss–Kronrod driver (:mod:`.gauss_kronrod`), used by both :mod:`brdfs.physics` and :mod:`brdfs.numerics`.

Imports nothing else of the package.
"""
