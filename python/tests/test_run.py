"""revisit.run: the CLI's whole chain, into a run folder byte-identical to the CLI's (timings aside)."""
import json

import pytest

import revisit

# Wall times and memory: the only content that differs between two runs of the same data (docs/formats.md).
TIMED_FILES = {"timings.json", "report/timing.svg", "report/index.html"}
TIMED_KEYS = {"wall_seconds", "peak_rss_kb"}


def without_times(value):
    if isinstance(value, dict):
        # run.json's `files` table holds each file's size and checksum, the timed files' too.
        return {k: without_times(v) for k, v in value.items() if k not in TIMED_KEYS and k not in TIMED_FILES}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def files(root):
    return sorted(p.relative_to(root) for p in root.rglob("*") if p.is_file())


def test_run_writes_the_cli_run_folder(tiny, cli_run, tmp_path):
    out = tmp_path / "python"
    result = revisit.run(str(tiny), out=str(out), poses="dataset")
    assert result["complete"] and result["scans"] == 1600 and result["closures"] >= 1
    assert files(out) == files(cli_run)
    different = []
    for name in files(out):
        ours, theirs = (out / name).read_bytes(), (cli_run / name).read_bytes()
        if ours == theirs or str(name) in TIMED_FILES:
            continue
        if name.suffix == ".json" and without_times(json.loads(ours)) == without_times(json.loads(theirs)):
            continue
        different.append(str(name))
    assert different == []


def test_errors_carry_the_library_message(tmp_path):
    with pytest.raises(revisit.DatasetError, match="missing_dataset"):
        revisit.run(str(tmp_path / "missing_dataset"), out=str(tmp_path / "out"))
    with pytest.raises(revisit.ConfigError, match="empty range"):
        revisit.run("sim:tiny", out=str(tmp_path / "out"), from_scan=10, to_scan=5)
