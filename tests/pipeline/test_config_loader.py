"""config.yaml and the schema are parsed by libyaml (PyYAML's C parser) for speed while the workflow
plans; what a file means, which keys it refuses, and what a syntax error says are PyYAML's own."""

import os

import pytest
import yaml

from brdfs.pipeline import config
from brdfs.pipeline.config import CONFIG_SCHEMA, CONFIG_YAML, ConfigError, read_config_file


def _pure(path):
    with open(path, encoding="utf-8") as stream:
        return yaml.load(stream, Loader=config._StrictLoader)  # noqa: S506 (a SafeLoader)


def _libyaml_only(monkeypatch):
    """PyYAML's own parser fails wherever it is used: what is then read was read by libyaml."""
    if not yaml.__with_libyaml__:
        pytest.skip("PyYAML is built without libyaml: there is no fast path")

    class Refused(yaml.SafeLoader):
        def __init__(self, stream):
            raise AssertionError("read by PyYAML's own parser, not libyaml's")

    monkeypatch.setattr(config, "_StrictLoader", Refused)
    monkeypatch.setattr(config.yaml, "SafeLoader", Refused)


@pytest.mark.skipif(not yaml.__with_libyaml__, reason="PyYAML is built without libyaml")
def test_the_fast_loader_is_libyamls_where_pyyaml_has_it():
    assert issubclass(config._FastStrictLoader, yaml.CSafeLoader)


def test_config_yaml_and_the_schema_read_by_libyaml_as_pyyamls_own_safe_loader_reads_them(monkeypatch):
    expected_config = _pure(CONFIG_YAML)
    expected_schema = yaml.safe_load(CONFIG_SCHEMA.read_text(encoding="utf-8"))
    _libyaml_only(monkeypatch)
    assert read_config_file(CONFIG_YAML) == expected_config
    assert config._read_schema.__wrapped__(str(CONFIG_SCHEMA), 0) == expected_schema


# Values PyYAML's YAML 1.1 reading gives (a string 1e-10, octal, sexagesimal, yes/on, anchors, tags).
SCALARS = ("a: 1e-10\nb: 1.0e-10\nc: 0o17\nd: 017\ne: 1:30\nf: yes\ng: on\nh: ~\ni: .inf\nj: 2001-01-01\n"
           "k: &x {p: 1}\nl: *x\nn: !!str 5\no: '1'\n")


def test_scalars_and_anchors_read_by_libyaml_mean_what_pyyaml_reads(tmp_path, monkeypatch):
    path = tmp_path / "c.yaml"
    path.write_text(SCALARS)
    expected = _pure(path)
    _libyaml_only(monkeypatch)
    assert read_config_file(path) == expected


# Tabs libyaml takes as separators, which PyYAML (and so Snakemake) refuses: (text, line, column).
TABS = [("seed:\t20010101\n", 1, 6), ("a: [1,\t2]\n", 1, 7), ("a: 1\t# c\n", 1, 5), ("a\t: 1\n", 1, 2),
        ("a:\n\t- 1\n", 2, 1), ("a:\n  -\t1\n", 2, 4)]


@pytest.mark.parametrize(("text", "line", "column"), TABS)
def test_a_tab_pyyaml_refuses_is_refused_with_pyyamls_message(tmp_path, text, line, column):
    path = tmp_path / "c.yaml"
    path.write_text(text)
    with pytest.raises(ConfigError) as error:
        read_config_file(path)
    assert str(error.value) == (f"{path}:{line}:{column}: YAML syntax error: "
                                "found character '\\t' that cannot start any token")


def test_a_tab_in_a_quoted_scalar_or_a_comment_is_read(tmp_path):
    path = tmp_path / "c.yaml"
    path.write_text('a: "x\ty"\nb: \'p\tq\'  # c\td\n')
    assert read_config_file(path) == {"a": "x\ty", "b": "p\tq"} == _pure(path)


@pytest.mark.skipif(not os.path.isdir("/dev/fd"), reason="no /dev/fd")
def test_a_file_is_read_once_so_a_pipe_reports_its_syntax_error():
    # what ``--configfile <(...)`` passes: /dev/fd/N, readable once
    read_end, write_end = os.pipe()
    os.write(write_end, b"a: [1, 2\n")
    os.close(write_end)
    try:
        with pytest.raises(ConfigError, match=r"/dev/fd/\d+:2:1: YAML syntax error: expected ',' or ']'"):
            read_config_file(f"/dev/fd/{read_end}")
    finally:
        os.close(read_end)




def test_duplicate_keys_stay_refused_by_the_fast_loader_nested_and_in_flow_mappings(tmp_path):
    for text, message in [("a: 1\nb:\n  c: 2\n  c: 3\n", ":4: duplicate key 'c' (lines 3 and 4)"),
                          ("a: {x: 1, y: 2, x: 3}\n", ":1: duplicate key 'x' (lines 1 and 1)"),
                          ("- {k: 1}\n- 2\n", None)]:
        path = tmp_path / "c.yaml"
        path.write_text(text)
        for load in (lambda p: yaml.load(p.open(), Loader=config._FastStrictLoader), _pure):  # noqa: S506
            if message is None:
                assert load(path) == [{"k": 1}, 2]
                continue
            try:
                load(path)
            except ConfigError as error:
                assert str(error) == f"{path}{message}; give each key once"
            else:
                raise AssertionError(f"{text!r} was read")


def test_a_syntax_error_says_what_pyyamls_own_parser_found(tmp_path):
    # libyaml says "found character that cannot start any token" and "found undefined alias"
    for text, found in [("a:\n\t- 1\n", "found character '\\t' that cannot start any token"),
                        ("a: *nowhere\n", "found undefined alias 'nowhere'"),
                        ("a: [1, 2\n", "expected ',' or ']', but got '<stream end>'")]:
        path = tmp_path / "c.yaml"
        path.write_text(text)
        try:
            read_config_file(path)
        except ConfigError as error:
            assert found in str(error) and str(error).startswith(f"{path}:"), str(error)
        else:
            raise AssertionError(f"{text!r} was read")
