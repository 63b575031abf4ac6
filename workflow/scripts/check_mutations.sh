#!/usr/bin/env bash
# make check-mutations: the six deliberate faults of issue 23, mis_weights_apart (next-event
# estimation's MIS weights from the exact density while bs.pdf reports the lobe density: weights that
# no longer sum to one) and issue 42's fresnel_at_theta_l and tangent_flipped, each applied to a
# temporary copy of the tree (marked lines flipped with sed); the named render tests must FAIL in that copy.
#   no_shadow_rays, nee_first_vertex, depth3        lines marked "# MUTATION:<name> <replacement>"
#                                                   in src/brdfs/render/mitsuba/integrator.py
#   frame_rotated_90, uniform_claims_cosine, pdf_scale   switches marked "# MUTATION <name>" in
#                                                   src/brdfs/render/mitsuba/plugins/_common.py
#   mis_weights_apart                               the line marked "# MUTATION:mis_weights_apart" there
#   fresnel_at_theta_l                              (issue 42) every metal reads F at cos theta_L, not at
#                                                   its model's angle: the line so marked there
#   tangent_flipped                                 (issue 42) the model frame's y reversed (anisotropy
#                                                   mirrored): the two lines so marked there
#   clamp_direct, clamp_half_kept                   (issue 42) the caustic clamp also bites direct light;
#                                                   its AOV keeps only half of what it took (integrator.py)
# FAULT=<name> runs only that fault. Prints the table fault -> test -> caught; exits 1 if a fault goes uncaught or its line is missing.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/_temp_copy.sh"
PYTHON=${PYTHON:-$ROOT/.venv/bin/python}
WORK=$(mktemp -d "${TMPDIR:-/tmp}/brdfs-mutations.XXXXXX")
trap 'rm -rf "$WORK"' EXIT

INTEGRATOR=src/brdfs/render/mitsuba/integrator.py
COMMON=src/brdfs/render/mitsuba/plugins/_common.py
T=tests/render/test_integrator.py
# An integrator line "<code>  # MUTATION:<name> <replacement>" becomes "<replacement>" (indent kept).
own() { echo "s/^\( *\)[^#]*# MUTATION:$1 \(.*\)\$/\1\2/"; }

# fault|file|sed expression|tests (space-separated node ids)
FAULTS=(
  "no_shadow_rays|$INTEGRATOR|$(own no_shadow_rays)|$T::test_a_blocker_between_light_and_plate_leaves_the_plate_unlit"
  "nee_first_vertex|$INTEGRATOR|$(own nee_first_vertex)|$T::test_inside_a_glowing_diffuse_sphere_the_radiance_is_the_geometric_series"
  "depth3|$INTEGRATOR|$(own depth3)|$T::test_inside_a_glowing_diffuse_sphere_the_radiance_is_the_geometric_series"
  "frame_rotated_90|$COMMON|s/^FRAME_ROTATED_90 = False/FRAME_ROTATED_90 = True/|$T::test_an_elliptical_patch_highlight_turns_the_right_way_with_the_tangent"
  "uniform_claims_cosine|$COMMON|s/^UNIFORM_CLAIMS_COSINE = False/UNIFORM_CLAIMS_COSINE = True/|$T::test_a_large_near_light_over_a_lambert_plate_gives_rho_e_over_pi"
  "pdf_scale|$COMMON|s/^PDF_SCALE = 1.0 /PDF_SCALE = 1.05 /|$T::test_a_sphere_under_a_constant_sky_returns_sky_times_its_mean_albedo_for_every_plugin[brdfs_phong_cosmin]"
  "mis_weights_apart|$COMMON|$(own mis_weights_apart)|$T::test_the_lobe_mis_density_leaves_a_wide_light_on_a_patch_plate_unbiased"
  "fresnel_at_theta_l|$COMMON|$(own fresnel_at_theta_l)|$T::test_far_light_on_dielectric_coated_plates_gives_f_times_fresnel_at_each_models_angle_times_e"
  "tangent_flipped|$COMMON|$(own tangent_flipped)|$T::test_an_elliptical_patch_highlight_turns_the_right_way_with_the_tangent"
  "clamp_direct|$INTEGRATOR|$(own clamp_direct)|$T::test_the_clamp_keeps_what_it_takes_in_its_aov_and_never_touches_direct_light"
  "clamp_half_kept|$INTEGRATOR|$(own clamp_half_kept)|$T::test_the_clamp_keeps_what_it_takes_in_its_aov_and_never_touches_direct_light"
)

status=0
printf '%-22s %-8s %s\n' fault caught test
for entry in "${FAULTS[@]}"; do
    IFS='|' read -r fault file expr tests <<<"$entry"
    if [ -n "${FAULT:-}" ] && [ "$FAULT" != "$fault" ]; then continue; fi   # FAULT=<name>: only that one
    copy="$WORK/$fault"
    temp_copy "$copy"
    cp -a "$ROOT/tests" "$copy"/
    before=$(sha256sum "$copy/$file")
    sed -i "$expr" "$copy/$file"
    if [ "$(sha256sum "$copy/$file")" = "$before" ]; then
        echo "check-mutations: $fault: no line of $file matches the mutation ($expr)" >&2
        status=1
        continue
    fi
    # the copy's package first on the path (the venv's editable install points at $ROOT/src)
    if (cd "$copy" && PYTHONPATH="$copy/src" "$PYTHON" -m pytest -q -x -p no:xdist -p no:cacheprovider $tests \
            >"$WORK/$fault.log" 2>&1); then
        printf '%-22s %-8s %s\n' "$fault" NO "$tests"
        status=1
    else
        printf '%-22s %-8s %s\n' "$fault" yes "$tests"
        grep -m1 -E '^E +(assert|AssertionError)' "$WORK/$fault.log" | sed 's/^/    /' || true
    fi
    rm -rf "$copy"
done
[ "$status" -eq 0 ] && echo "check-mutations: every fault is caught by a test"
exit "$status"
