"""Shared data for the module's tests: a short simulated drive with one revisit, and the CLI's run of it."""
import os
import subprocess

import pytest


def _cli():
    cli = os.environ.get("REVISIT_CLI", "")
    if not cli or not os.path.exists(cli):
        pytest.skip("REVISIT_CLI is not set to the revisit binary (ctest sets it)")
    return cli


@pytest.fixture(scope="session")
def cli():
    return _cli()


@pytest.fixture(scope="session")
def tiny(tmp_path_factory, cli):
    """The 'tiny' preset cut after its first revisit (scan ~1450 returns to scan ~760), as a KITTI folder."""
    out = tmp_path_factory.mktemp("data") / "tiny"
    subprocess.run([cli, "simulate", "--preset", "tiny", "--scans", "1600", "--out", str(out), "--quiet"], check=True)
    return out


@pytest.fixture(scope="session")
def cli_run(tmp_path_factory, cli, tiny):
    """`revisit run` on the tiny drive with its reference poses."""
    out = tmp_path_factory.mktemp("runs") / "cli"
    subprocess.run([cli, "run", str(tiny), "--poses", "dataset", "--out", str(out), "--quiet"], check=True,
                   stdout=subprocess.DEVNULL)
    return out
