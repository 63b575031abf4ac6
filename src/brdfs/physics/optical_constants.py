"""TEMPORARY STAND-IN (branch ``render``) for the spectral helper's optical-constant loader.

The lead drops this file when merging the ``spectral`` branch, whose module of the same name
provides ``complex_index(metal, wavelength_nm, dataset=None) -> complex ndarray`` from measured
data. Only the call signature is relied upon by :mod:`brdfs.numerics.render`.

The values below are the complex indices n + ik of the luxpop database as shipped with
Mitsuba 3 (``data/ior/<metal>.eta.spd`` / ``.k.spd``), linearly interpolated at the eight
wavelength-bin centres 405, 455, ..., 755 nm the renders use; other wavelengths are linearly
interpolated between these points (enough for a stand-in, not for Figure 3.7).
"""
from __future__ import annotations

import numpy as np

_WAVELENGTHS_NM = np.arange(405.0, 760.0, 50.0)
_TABLE = {
    "gold": ([1.6497, 1.4643, 0.7714, 0.333, 0.2121, 0.1653, 0.1607, 0.1705],
             [1.9586, 1.861, 1.9443, 2.7778, 3.0156, 3.1911, 4.0368, 4.6483]),
    "silver": ([0.1727, 0.1476, 0.1299, 0.123, 0.1256, 0.14, 0.1436, 0.1454],
               [2.0111, 2.5191, 2.964, 3.3803, 3.7677, 4.1699, 4.5604, 4.9359]),
    "copper": ([1.1769, 1.1627, 1.1319, 0.9111, 0.3502, 0.2133, 0.2157, 0.2386],
               [2.1532, 2.4152, 2.5869, 2.5836, 3.0138, 3.6968, 4.206, 4.6497]),
    "aluminium": ([0.5025, 0.6321, 0.7854, 0.981, 1.2211, 1.5053, 1.8799, 2.4435],
                  [4.9202, 5.5297, 6.1375, 6.7474, 7.3122, 7.8464, 8.3582, 8.617]),
}


def complex_index(metal: str, wavelength_nm, dataset=None) -> np.ndarray:
    """n + ik of ``metal`` at ``wavelength_nm`` (stand-in; see the module docstring)."""
    try:
        n, k = _TABLE[metal]
    except KeyError:
        raise ValueError(f"complex_index: unknown metal {metal!r}; known: {sorted(_TABLE)}") from None
    lam = np.asarray(wavelength_nm, float)
    return np.interp(lam, _WAVELENGTHS_NM, n) + 1j * np.interp(lam, _WAVELENGTHS_NM, k)
