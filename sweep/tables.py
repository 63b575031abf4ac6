"""Compute, once, the tables the sweep's pumped and Kulla–Conty models are built with, and store them
(``tests/data/sweep_tables.json``): the truths integrate the model as built with exactly these tables,
so they do not move when the engine that tabulated them changes.  This is the only module of the
sweep that uses :mod:`brdfs.numerics` (its table factory), and only here.

    python -m sweep.tables [--seed N]
"""
from __future__ import annotations

import argparse
import json

from brdfs.numerics.tables import build as build_model, pump
from brdfs.physics.models import MODELS

from sweep.cells import FAMILIES, TABLES, cells, needs_table, table_key, table_to_json
from sweep.config import config_seed


def _table(family, kwargs):
    if family.pumped is None:
        return build_model(family.model, **kwargs).energy
    base = MODELS[family.model](**kwargs)
    try:
        return pump(base, family.pumped).table
    except RuntimeError:                   # the factory's default 1e-9 is out of reach: ask for less
        return pump(base, family.pumped, target_rtol=1e-7, engine_rtol=1e-10).table


def compute(seed: int) -> dict:
    out = {}
    seen = set()
    for family_name, params, _ in cells(seed):
        family = next(f for f in FAMILIES if f.name == family_name)
        key = table_key(family, params)
        if not needs_table(family) or key in seen:
            continue
        seen.add(key)
        kwargs = {**family.fixed_dict, **params}
        try:
            table = _table(family, kwargs)
        except RuntimeError as exc:        # a table the factory cannot make: its cells stay unjudged
            print(key, "no table:", exc, flush=True)
            continue
        out[key] = table_to_json(table)
        print(key, table.error, flush=True)
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=None)
    args = parser.parse_args(argv)
    tables = compute(config_seed() if args.seed is None else args.seed)
    TABLES.write_text(json.dumps(tables, indent=0, sort_keys=True) + "\n")


if __name__ == "__main__":
    main()
