# Sourced by the check scripts: a clean copy of the workflow in a new temporary directory.
# temp_copy DIR: copies what a build reads (no results/, no .snakemake/) into DIR.
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
SNAKEMAKE=${SNAKEMAKE:-snakemake}
# A few cheap artifacts (a table with its comparison, figures of chapters 3 and 4); override with TARGETS=...
TARGETS=${TARGETS:-results/tables/table_1_2_metal_reflectance.png results/figures/fig_3_2_p_model_ratio.png \
results/figures/fig_4_13_inverse_cdf.png results/figures/fig_4_3_basic_brdf.png results/checks/published/metal_a0.csv}

temp_copy() {
    mkdir -p "$1"
    (cd "$ROOT" && cp -a Snakefile config.yaml pyproject.toml workflow data src profiles "$1"/)
    rm -rf "$1"/src/*.egg-info
    find "$1" -name __pycache__ -type d -prune -exec rm -rf {} +
}

# The bytes of every CSV and PNG under results/ (tables, figures, checks), one "sha256  path" a line.
fingerprint() {
    (cd "$1" && find results/tables results/figures results/checks -type f \( -name '*.csv' -o -name '*.png' \) \
        -not -name '.*' | LC_ALL=C sort | xargs sha256sum)
}
