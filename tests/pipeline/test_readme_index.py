"""README's artifact index agrees with the registry (brdfs.pipeline.readme_index)."""

import re
from types import SimpleNamespace

import pytest

from brdfs.pipeline import readme_index, registry
from brdfs.pipeline.io import REPO_ROOT


def test_readmes_artifact_index_is_the_one_generated_from_the_registry():
    text = (REPO_ROOT / "README.md").read_text(encoding="utf-8")
    expected = readme_index.index_markdown(registry.artifacts(), registry.comparisons())
    listed = set(re.findall(r"^\| [^|]* \| `([a-z0-9_]+)` \|", readme_index.current_section(text), re.M))
    missing, unknown = set(registry.artifacts()) - listed, listed - set(registry.artifacts())
    assert not missing and not unknown, (f"README's index lacks {sorted(missing)} and lists unknown {sorted(unknown)}; "
                                         "run python -m brdfs.pipeline.readme_index --write README.md")
    assert readme_index.current_section(text) == expected, "README's index is stale: run --write README.md"


def test_the_index_lists_every_artifact_once_under_its_chapter():
    declared = {
        "table_3_2_ward_cmax": SimpleNamespace(chapter=3, csv="results/tables/table_3_2_ward_cmax.csv",
                                               png="results/tables/table_3_2_ward_cmax.png"),
        "extra_accuracy_map": SimpleNamespace(chapter=None, csv="results/figures/extra_accuracy_map.csv",
                                              png="results/figures/extra_accuracy_map.png"),
    }
    text = readme_index.index_markdown(declared, {"ward_cmax": SimpleNamespace(tables=("table_3_2_ward_cmax",))})
    chapter_3, beyond = text.split("**Beyond the thesis")
    assert "| Table 3.2 | `table_3_2_ward_cmax` | `tables/table_3_2_ward_cmax.{csv,png}` | `ward_cmax` |" in chapter_3
    assert "`extra_accuracy_map`" in beyond and "`extra_accuracy_map`" not in chapter_3
    assert text.startswith("2 artifacts")


def test_replacing_the_section_keeps_the_rest_of_the_readme_and_refuses_missing_markers():
    text = f"intro\n{readme_index.BEGIN}\nold\n{readme_index.END}\ntail\n"
    assert readme_index.replace_section(text, "new\n") == f"intro\n{readme_index.BEGIN}\nnew\n{readme_index.END}\ntail\n"
    with pytest.raises(ValueError, match="markers"):
        readme_index.replace_section("no markers", "new\n")
