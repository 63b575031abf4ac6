"""The sweep's seed: config.yaml's ``seed``."""
from __future__ import annotations

from pathlib import Path

import yaml

CONFIG = Path(__file__).resolve().parents[1] / "config.yaml"


def config_seed(path=CONFIG) -> int:
    return int(yaml.safe_load(Path(path).read_text())["seed"])
