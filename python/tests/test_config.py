"""load_config: the CLI's resolution (defaults, files or presets, then key=value), the same keys and errors."""
import subprocess

import pytest

import revisit


def cli_config(cli, *args):
    text = subprocess.run([cli, "config", *args], check=True, capture_output=True, text=True).stdout
    return "".join(line + "\n" for line in text.splitlines() if not line.startswith("# revisit configuration"))


def test_defaults_are_what_the_cli_prints(cli):
    assert revisit.load_config().yaml() == cli_config(cli)


def test_presets_and_overrides_resolve_as_config_and_set(cli):
    config = revisit.load_config(files=["kitti"], set={"density.resolution": 0.2, "proximity.enabled": False})
    assert config.yaml() == cli_config(cli, "--config", "kitti", "--set", "density.resolution=0.2",
                                       "--set", "proximity.enabled=false")
    assert config.yaml() != revisit.load_config().yaml()


def test_settings_derived_from_the_data_match_the_cli(cli, tiny):
    derived = revisit.load_config(dataset=str(tiny))
    text = subprocess.run([cli, "config", "--dataset", str(tiny)], check=True, capture_output=True, text=True).stdout
    lines = text.splitlines()
    assert derived.derived, "the tiny drive derives at least its ranges"
    assert ["# derived from the data: " + line for line in derived.derived] == [l for l in lines if l.startswith("# derived")]
    assert derived.yaml() == "".join(line + "\n" for line in lines[1 + len(derived.derived):])


def test_an_unknown_key_is_a_config_error_naming_it():
    with pytest.raises(revisit.ConfigError, match="density.no_such_key"):
        revisit.load_config(set={"density.no_such_key": 1})
    assert issubclass(revisit.ConfigError, ValueError)


def test_a_missing_file_names_it(tmp_path):
    missing = tmp_path / "nope.yaml"
    with pytest.raises(revisit.ConfigError, match="nope.yaml"):
        revisit.load_config(files=[str(missing)])
