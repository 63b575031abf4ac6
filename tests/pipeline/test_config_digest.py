"""A rule's config param is a digest of its canonical config subset (registry.config_digest)."""

import copy

from brdfs.pipeline import registry

CONFIG = {
    "seed": 7,
    "tolerance": {"rtol": 1e-10, "atol": 1e-14},
    "ward_cmax": {"m": [0.4, 0.2, 0.1], "grid": {"points": 64, "kind": "gauss"}},
    "unread": {"x": 1},
}


def reordered(value):
    """``value`` with the keys of every mapping in reverse order (lists unchanged)."""
    if isinstance(value, dict):
        return {key: reordered(value[key]) for key in reversed(list(value))}
    return value


def test_the_digest_ignores_key_order_at_every_depth():
    again = reordered(CONFIG)
    assert list(again) != list(CONFIG) and list(again["ward_cmax"]["grid"]) != list(CONFIG["ward_cmax"]["grid"])
    assert registry.config_digest(again, ("ward_cmax",)) == registry.config_digest(CONFIG, ("ward_cmax",))


def test_the_digest_changes_with_any_value_the_rule_reads_and_with_list_order():
    before = registry.config_digest(CONFIG, ("ward_cmax",))
    for edit in (lambda c: c["ward_cmax"]["grid"].update(points=65), lambda c: c["tolerance"].update(rtol=1e-9),
                 lambda c: c.update(seed=8), lambda c: c["ward_cmax"]["m"].reverse()):
        changed = copy.deepcopy(CONFIG)
        edit(changed)
        assert registry.config_digest(changed, ("ward_cmax",)) != before


def test_the_digest_ignores_sections_the_rule_does_not_read_and_names_those_it_does():
    changed = copy.deepcopy(CONFIG)
    changed["unread"]["x"] = 2
    digest = registry.config_digest(changed, ("ward_cmax",))
    assert digest == registry.config_digest(CONFIG, ("ward_cmax",))
    names, _, hexdigest = digest.partition("@")
    assert names == "seed,tolerance,ward_cmax" and len(hexdigest) == 16 and "0.4" not in digest
