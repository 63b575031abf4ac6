"""config.yaml and the schema are parsed by libyaml (PyYAML's C parser) for speed while the workflow
plans; what a file means, which keys it refuses, and what a syntax error says are PyYAML's own."""

import yaml

from brdfs.pipeline import config
from brdfs.pipeline.config import CONFIG_SCHEMA, CONFIG_YAML, ConfigError, read_config_file


def _pure(path):
    with open(path, encoding="utf-8") as stream:
        return yaml.load(stream, Loader=config._StrictLoader)  # noqa: S506 (a SafeLoader)


def test_the_fast_loader_is_libyamls_where_pyyaml_has_it():
    assert issubclass(config._FastStrictLoader, yaml.CSafeLoader) == yaml.__with_libyaml__


def test_config_yaml_and_the_schema_read_as_pyyamls_own_safe_loader_reads_them():
    assert read_config_file(CONFIG_YAML) == _pure(CONFIG_YAML)
    schema = config._read_schema(str(CONFIG_SCHEMA), CONFIG_SCHEMA.stat().st_mtime_ns)
    assert schema == yaml.safe_load(CONFIG_SCHEMA.read_text(encoding="utf-8"))


# Values PyYAML's YAML 1.1 reading gives (a string 1e-10, octal, sexagesimal, yes/on, anchors, tags).
SCALARS = ("a: 1e-10\nb: 1.0e-10\nc: 0o17\nd: 017\ne: 1:30\nf: yes\ng: on\nh: ~\ni: .inf\nj: 2001-01-01\n"
           "k: &x {p: 1}\nl: *x\nn: !!str 5\no: '1'\n")


def test_scalars_and_anchors_mean_what_pyyaml_reads(tmp_path):
    path = tmp_path / "c.yaml"
    path.write_text(SCALARS)
    assert read_config_file(path) == _pure(path)


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
