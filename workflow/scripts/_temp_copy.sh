# Sourced by the check scripts: a clean copy of the workflow in a new temporary directory.
# temp_copy DIR: copies what a build reads (no results/, no .snakemake/) into DIR.
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
SNAKEMAKE=${SNAKEMAKE:-snakemake}
# A few cheap artifacts, one job each (as every artifact, in every mode): Table 1.2, Figure 5.1 and the two pumping tables (the crash
# check catches one of them running); override with TARGETS=...
TARGETS=${TARGETS:-results/tables/table_1_2_metal_reflectance.png results/figures/fig_5_1_patch_based_brdf.png \
results/tables/extra_pumping_albedo_phong.png results/tables/extra_pumping_albedo_blinn.png}

temp_copy() {
    mkdir -p "$1"
    (cd "$ROOT" && cp -a Snakefile config.yaml pyproject.toml workflow data src profiles "$1"/)
    rm -rf "$1"/src/*.egg-info
    find "$1" -name __pycache__ -type d -prune -exec rm -rf {} +
}

# The bytes of every CSV, PNG and EXR under results/ but its logs and timings (results/logs, results/benchmarks),
# one "sha256  path" a line.
fingerprint() {
    (cd "$1" && find results \( -path results/logs -o -path results/benchmarks \) -prune -o -type f \
        \( -name '*.csv' -o -name '*.png' -o -name '*.exr' \) -not -name '.*' -print | LC_ALL=C sort | xargs sha256sum)
}
