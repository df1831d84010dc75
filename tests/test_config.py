"""Configuration discovery and rule selection, ruff-style."""

from __future__ import annotations

import pytest

from val3check.config import ConfigError, Settings, find_config, load_settings
from val3check.diagnostics import Severity


def test_longest_prefix_wins():
    s = Settings(select=["F"], ignore=["F1"], extend_select=["F101"])
    assert s.enabled("F001")
    assert not s.enabled("F102")
    assert s.enabled("F101")  # the more specific select beats the family ignore
    assert not s.enabled("L001")


def test_default_selects_everything():
    assert Settings().enabled("S123")


def test_pyproject_section_found_walking_up(tmp_path):
    (tmp_path / "pyproject.toml").write_text('[tool.val3check]\nignore = ["l001"]\nfail-on = "warning"\n')
    deep = tmp_path / "a" / "b"
    deep.mkdir(parents=True)
    found = find_config(str(deep))
    assert found == str(tmp_path / "pyproject.toml")
    s = load_settings(found)
    assert s.ignore == ["L001"] and s.fail_on == "warning"
    assert not s.enabled("L001")


def test_pyproject_without_section_is_skipped(tmp_path):
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "x"\n')
    sub = tmp_path / "app"
    sub.mkdir()
    (sub / "val3check.toml").write_text('select = ["F"]\n')
    assert find_config(str(sub)) == str(sub / "val3check.toml")
    assert find_config(str(tmp_path)) is None or find_config(str(tmp_path)) != str(tmp_path / "pyproject.toml")


def test_per_file_ignores_are_relative_to_the_config(tmp_path):
    (tmp_path / "val3check.toml").write_text('[per-file-ignores]\n"legacy/**" = ["F1"]\n')
    s = load_settings(str(tmp_path / "val3check.toml"))
    assert not s.enabled("F101", str(tmp_path / "legacy" / "App" / "start.pgx"))
    assert s.enabled("F101", str(tmp_path / "new" / "App" / "start.pgx"))
    assert s.enabled("F004", str(tmp_path / "legacy" / "App" / "start.pgx"))


def test_severity_override_and_disk_roots(tmp_path):
    (tmp_path / "val3check.toml").write_text('disk-roots = ["libs"]\n[severity]\nL001 = "error"\n')
    s = load_settings(str(tmp_path / "val3check.toml"))
    assert s.severity == {"L001": Severity.ERROR}
    assert s.disk_roots == [str(tmp_path / "libs")]


@pytest.mark.parametrize(
    "text,fragment",
    [
        ("select = 3\n", "list of strings"),
        ('fail-on = "sometimes"\n', "fail-on"),
        ('colour = "red"\n', "unknown option"),
        ("select = [\n", "cannot read"),
        ('[severity]\nF101 = "fatal"\n', "severity"),
    ],
)
def test_bad_configuration_is_a_clear_error(tmp_path, text, fragment):
    (tmp_path / "val3check.toml").write_text(text)
    with pytest.raises(ConfigError, match=fragment):
        load_settings(str(tmp_path / "val3check.toml"))


def test_unknown_selection_is_reported():
    s = Settings(select=["F", "Q9"], ignore=["F1"])
    assert s.unknown_codes(["F001", "F101"]) == ["Q9"]


def test_target_key(tmp_path):
    from val3check.language.target import TargetSpec

    cfg = tmp_path / "val3check.toml"
    cfg.write_text('target = "cs8 s7.11"\n')
    assert load_settings(str(cfg)).target == TargetSpec("CS8", "s7.11")
    cfg.write_text('target = "CS9"\n')
    assert load_settings(str(cfg)).target == TargetSpec("CS9", None)
    cfg.write_text('select = ["F"]\n')
    assert load_settings(str(cfg)).target is None  # default: each project file's version


@pytest.mark.parametrize("value,words", [
    ('"CS10"', "unknown word 'CS10'"),
    ('"CS8 s8.13"', "CS8 controllers run VAL 3 s5 to s7, not s8.13"),
    ('"CS9 s7.11"', "CS9 controllers run VAL 3 s8, not s7.11"),
    ('"CS8 CS9"', "two controllers"),
    ('""', "must be a controller and/or a VAL 3 version"),
    ('7', "must be a controller and/or a VAL 3 version"),
])
def test_bad_target_is_a_clear_configuration_error(tmp_path, value, words):
    cfg = tmp_path / "val3check.toml"
    cfg.write_text(f"target = {value}\n")
    with pytest.raises(ConfigError) as exc:
        load_settings(str(cfg))
    assert words in str(exc.value) and str(cfg) in str(exc.value)


@pytest.mark.parametrize("text,ours", [
    ('[tool.val3check]\nignore = ["L001"]\n', True),
    ('[tool . val3check . severity]\nL001 = "error"\n', True),
    ('[tool]\nval3check = { ignore = ["L001"] }\n', True),
    ('[project]\nname = "val3check"\n[project.scripts]\nval3check = "val3check.cli:main"\n', False),
    ('[tool.ruff]\nline-length = 120\n', False),
])
def test_pyproject_is_parsed_only_when_it_may_hold_our_section(tmp_path, text, ours):
    (tmp_path / "pyproject.toml").write_text(text)
    assert (find_config(str(tmp_path)) == str(tmp_path / "pyproject.toml")) is ours
