"""``microslip sweep --scheduler``: a real LocalCluster, a worker lost mid-sweep, same file."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

from microslip.cli.main import main

distributed = pytest.importorskip("distributed")


def _kill_once_plugin(marker: str) -> Any:
    """A worker plugin whose worker dies (os._exit) as it starts the first sweep task.

    The marker file, created exclusively, makes sure this happens once in the whole cluster.
    Defined in a function so that cloudpickle ships the class by value to the workers.
    """

    class KillOnce(distributed.WorkerPlugin):
        name = "kill-once"

        def __init__(self, path: str) -> None:
            self.path = path

        def transition(self, key: Any, start: str, finish: str, **kwargs: Any) -> None:
            if finish != "executing" or not str(key).startswith("microslip-"):
                return
            try:
                fd = os.open(self.path, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
            except FileExistsError:
                return
            os.close(fd)
            os._exit(1)

    return KillOnce(marker)


@pytest.mark.slow
def test_cluster_run_loses_no_result_and_matches_local(tmp_path: Path) -> None:
    args = ["sweep", "--model", "tip", "--preset", "table2-tip", "--amplitude-range", "100",
            "8000", "--cases", "400", "--sample", "friction=normal:0.8:0.04", "--samples", "25",
            "--seed", "9", "--increments", "100", "--chunk-size", "1000", "--no-progress"]
    local = tmp_path / "local.csv"
    assert main([*args, "--out", str(local)]) == 0
    marker = tmp_path / "killed"
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        client.register_plugin(_kill_once_plugin(str(marker)))
        remote = tmp_path / "remote.csv"
        assert main([*args, "--out", str(remote), "--scheduler", cluster.scheduler_address,
                     "--retries", "2"]) == 0
    assert marker.exists(), "no worker was lost: the plugin did not fire"
    assert remote.read_bytes() == local.read_bytes()


@pytest.mark.slow
def test_cluster_sweep_on_a_contact_matches_local(tmp_path: Path) -> None:
    """A stick slope and a pressure law reach the workers (the layer kernel runs there)."""
    args = ["sweep", "--model", "centre", "--amplitude-range", "50", "300", "--cases", "40",
            "--increments", "100", "--chunk-size", "16", "--stick-slope", "1e4",
            "--pressure-law", "power:2:3", "--no-progress"]
    local = tmp_path / "local.csv"
    assert main([*args, "--out", str(local)]) == 0
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        remote = tmp_path / "remote.csv"
        assert main([*args, "--out", str(remote), "--scheduler", cluster.scheduler_address]) == 0
    assert remote.read_bytes() == local.read_bytes()


def test_unreachable_scheduler_is_one_line(tmp_path: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    import dask

    out = tmp_path / "x.csv"
    with dask.config.set({"distributed.comm.timeouts.connect": "1s"}):
        rc = main(["sweep", "--model", "tip", "--preset", "table1", "--increments", "10",
                   "--scheduler", "tcp://127.0.0.1:9", "--out", str(out), "--no-progress"])
    err = capsys.readouterr().err
    assert rc == 1 and err.count("\n") == 1
    assert "cannot connect to the Dask scheduler at 'tcp://127.0.0.1:9'" in err
    assert not out.exists()
