"""The render jobs' order: longest first by the last build's measured CPU seconds (report.render_priority)."""

import json
import re
from pathlib import Path

from brdfs.pipeline import report
from brdfs.pipeline.io import REPO_ROOT


def _timing(root: Path, name: str, cpu: list[float]) -> None:
    path = root / report.RENDER_TIMING.format(name=name)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps({"figure": name, "panels": [{"panel": k, "title": "t", "wall_s": 2 * c, "cpu_s": c}
                                                            for k, c in enumerate(cpu)]}), encoding="utf-8")


def test_a_render_measured_longer_gets_a_higher_priority_than_any_other_job(tmp_path):
    _timing(tmp_path, "long", [12.4, 14.0])
    _timing(tmp_path, "short", [3.2])
    assert report.render_priority("long", tmp_path) == 1 + 26
    assert report.render_priority("short", tmp_path) == 1 + 3
    _timing(tmp_path, "instant", [0.1])
    assert report.render_priority("instant", tmp_path) == 1      # still above the other jobs' 0


def test_an_unbuilt_or_damaged_timing_gives_the_plain_render_priority(tmp_path):
    assert report.render_priority("absent", tmp_path) == 1
    path = tmp_path / report.RENDER_TIMING.format(name="damaged")
    path.parent.mkdir(parents=True)
    for text in ("{not json", '{"panels": [{"cpu_s": "x"}]}', '{"figure": "damaged"}', "[]", '{"panels": {"a": 1}}',
                 '{"panels": [{"cpu_s": NaN}]}', '{"panels": [{"cpu_s": Infinity}]}'):
        path.write_text(text, encoding="utf-8")
        assert report.render_priority("damaged", tmp_path) == 1, text


def test_the_render_rule_takes_its_priority_from_render_priority_and_other_jobs_stay_at_zero():
    rule = (REPO_ROOT / "workflow" / "rules" / "artifacts.smk").read_text(encoding="utf-8")
    line = re.search(r"^\s*priority:.*$", rule, re.M)[0]
    assert "report_text.render_priority(wc.name" in line and line.rstrip().endswith("else 0"), line
