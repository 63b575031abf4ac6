"""The data dictionary (issue 43): every column of every result CSV has exactly one entry in docs/contract.md
with a unit and a meaning, no entry is unused, and the dictionary shipped in the package is the one the
contract generates (brdfs.pipeline.data_dictionary)."""

import gzip
import io
from pathlib import Path

import pandas as pd
import pytest

from brdfs.pipeline import data_dictionary as dd


@pytest.fixture(scope="module")
def generated() -> pd.DataFrame:
    return dd.generate()


def test_every_column_of_every_result_csv_resolves_to_one_contract_entry_with_a_unit_and_a_meaning(generated):
    baseline = sorted(dd.RESULTS_BASELINE.rglob("*.csv.gz"))
    headers = {p: pd.read_csv(p, nrows=0).columns for p in baseline}
    assert generated["file"].nunique() == len(baseline) >= 80
    assert len(generated) == sum(len(h) for h in headers.values())
    units, entries = dd.parse(dd.CONTRACT.read_text(encoding="utf-8"))
    assert set(generated["unit"]) <= set(units) and generated["meaning"].str.len().min() > 10
    assert not generated.duplicated(["file", "column"]).any()
    row = generated.set_index(["file", "column"]).loc[("results/tables/table_4_1_exponential_patch.csv",
                                                       "C_max_integrated_err")]
    assert row["unit"] == "sr^-1" and "`C_max_integrated`" in row["meaning"]   # as <x>, twice over


def test_the_dictionary_shipped_in_the_package_is_the_one_the_contract_generates(generated):
    assert dd.PACKAGED.is_file(), "python -m brdfs.pipeline.data_dictionary writes it"
    shipped = dd.load()
    assert shipped.equals(generated.astype(str)), "the shipped dictionary differs from docs/contract.md: " \
                                                  "python -m brdfs.pipeline.data_dictionary"


# --- the checks themselves, on a small contract ------------------------------------------------------

CONTRACT = """# Output contract

## Data dictionary
Prose.

| unit | meaning |
|---|---|
| `1` | dimensionless |
| `deg` | degrees |
| `label` | a name |

| group | files |
|---|---|
| `angles` | `tables/table_*` |

| column | files | unit | meaning |
|---|---|---|---|
| `<x>_err` | `*` | as <x> | the error of <x> |
| `model` | `*` | label | the model |
| `theta_deg` | angles | deg | the incidence angle |
| `albedo` | `*` | 1 | the albedo \\| a ratio |
| `albedo` | `figures/fig_*` | 1 | a plotted albedo |

## Next section
| column | files | unit | meaning |
|---|---|---|---|
| `ignored` | `*` | 1 | not part of the dictionary |
"""


def write_results(root: Path, tables: dict[str, dict]) -> Path:
    for name, data in tables.items():
        path = root / f"{name}.csv.gz"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(gzip.compress(pd.DataFrame(data).to_csv(index=False).encode()))
    return root


@pytest.fixture
def results(tmp_path) -> Path:
    return write_results(tmp_path / "results", {
        "tables/table_1_1_x": {"model": ["a"], "theta_deg": [0.0], "albedo": [0.5], "albedo_err": [1e-9]},
        "figures/fig_1_1_y": {"model": ["a"], "albedo": [0.25]},
    })


def generate(tmp_path: Path, contract: str, results: Path) -> pd.DataFrame:
    (tmp_path / "contract.md").write_text(contract, encoding="utf-8")
    return dd.generate(tmp_path / "contract.md", results)


def test_a_good_contract_gives_one_row_per_column_with_patterns_groups_and_named_files_first(tmp_path, results):
    df = generate(tmp_path, CONTRACT, results).set_index(["file", "column"])
    assert len(df) == 6
    err = df.loc[("results/tables/table_1_1_x.csv", "albedo_err")]
    assert (err["unit"], err["meaning"], err["dtype"]) == ("1", "the error of `albedo`", "float")
    assert df.loc[("results/tables/table_1_1_x.csv", "albedo"), "meaning"] == "the albedo | a ratio"
    assert df.loc[("results/figures/fig_1_1_y.csv", "albedo"), "meaning"] == "a plotted albedo"
    assert df.loc[("results/tables/table_1_1_x.csv", "theta_deg"), "unit"] == "deg"


@pytest.mark.parametrize(("edit", "message"), [
    (("| `model` | `*` | label | the model |\n", ""), "column 'model' has no entry"),
    (("| `theta_deg` | angles |", "| `theta_deg` | `figures/*` |"), "column 'theta_deg' has no entry"),
    (("| `albedo` | `*` | 1 |", "| `albedo` | `*` |  |"), "needs a column, files, a unit and a meaning"),
    (("| `model` | `*` | label |", "| `model` | `*` | kg |"), "unit 'kg' is not in the units table"),
    (("| `model` | `*` | label |", "| `model` | `*` | as <x> |"), "needs a pattern with <x>"),
    (("| `albedo` | `*` | 1 | the albedo \\| a ratio |\n", ""), "column 'albedo' has no entry"),
    (("| `model` | `*` | label | the model |\n",
      "| `model` | `*` | label | the model |\n| `albedo` | `figures/*` | 1 | again |\n"), "'albedo' has 2 entries"),
    (("| `model` | `*` | label | the model |\n",
      "| `model` | `*` | label | the model |\n| `spp` | `*` | 1 | samples |\n"), "no column of any CSV uses"),
    (("| `<x>_err` | `*` |", "| `<x>_error` | `*` |"), "column 'albedo_err' has no entry"),
])
def test_the_dictionary_refuses_a_contract_that_does_not_describe_the_csvs(tmp_path, results, edit, message):
    assert edit[0] in CONTRACT
    with pytest.raises(dd.DictionaryError, match=message):
        generate(tmp_path, CONTRACT.replace(*edit), results)


def test_a_new_column_in_a_csv_is_refused_until_the_contract_names_it(tmp_path, results):
    write_results(results, {"figures/fig_1_1_y": {"model": ["a"], "albedo": [0.25], "spp": [4]}})
    with pytest.raises(dd.DictionaryError, match=r"fig_1_1_y.csv: column 'spp' has no entry"):
        generate(tmp_path, CONTRACT, results)


def test_the_check_fails_when_the_shipped_dictionary_differs_from_the_contract(tmp_path, results, monkeypatch):
    (tmp_path / "contract.md").write_text(CONTRACT, encoding="utf-8")
    monkeypatch.setattr(dd, "CONTRACT", tmp_path / "contract.md")
    monkeypatch.setattr(dd, "PACKAGED", tmp_path / "data_dictionary.csv")
    assert dd.main([str(results)]) == 0 and dd.main(["--check", str(results)]) == 0
    changed = CONTRACT.replace("the incidence angle", "the angle of incidence")
    (tmp_path / "contract.md").write_text(changed, encoding="utf-8")
    assert dd.main(["--check", str(results)]) == 1


def test_the_documentation_page_has_one_table_per_csv_and_is_valid_restructuredtext(generated):
    import docutils.core
    import docutils.nodes

    page = dd.rst_page(generated)
    assert page.count("\n.. list-table::") == generated["file"].nunique() + 1   # and the units
    sample = generated[generated["file"].isin(["results/checks/published_comparison.csv",
                                               "results/figures/extra_accuracy_map.csv"])]
    doctree = docutils.core.publish_doctree(
        dd.rst_page(sample).replace(":doc:", ""), settings_overrides={"report_level": 2, "halt_level": 5, "warning_stream": io.StringIO()})
    problems = [n.astext() for n in doctree.findall(docutils.nodes.system_message)]
    assert not problems, problems
    text = doctree.astext()
    assert "|engine − reference| / the engine's reported error" in text and "`" not in text
    assert dd.rst_text("a *b, `c_d` and e_ |f|") == r"a \*b, ``c_d`` and e\_ \|f\|"
