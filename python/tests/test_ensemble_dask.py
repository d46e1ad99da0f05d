# SPDX-License-Identifier: MIT
"""calder.Ensemble on a real dask.distributed LocalCluster (two worker
processes on loopback): the same bits as the serial loop, and a worker
killed by its pid in the middle of the ensemble costs nothing but time:
every member completes with the same bits, the killed worker's member goes
on from its last snapshot."""

import os
import pathlib
import signal
import threading
import time

import pytest

import calder
from distributed import Client, LocalCluster

from test_ensemble import SCENE, expect_bits, galaxy_with, plain_loop


@pytest.fixture(scope="module")
def client():
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           host="127.0.0.1", dashboard_address=None, silence_logs=40)
    with cluster, Client(cluster) as client:
        yield client


def test_the_cluster_gives_the_serial_loops_bits(client):
    seeds = [calder.member_seed(11, k) for k in range(4)]
    vary = {"fields[0].law.G": [1.0, 1.5]}
    ensemble = calder.Ensemble(SCENE, seeds=4, seed=11, vary=vary, frames=20)
    members = [(s, {"fields[0].law.G": G}) for G in vary["fields[0].law.G"] for s in seeds]
    expect_bits(ensemble.run(client=client, batch_size=1), plain_loop(galaxy_with, members, 20))
    pids = {f":{pid}" for pid in client.run(os.getpid).values()}
    assert all(r.worker[r.worker.rindex(":"):] in pids for r in ensemble.status)
    # Batched as by default (about four batches per worker): the same bits.
    expect_bits(ensemble.run(client=client), plain_loop(galaxy_with, members, 20))


def _archives(folder: pathlib.Path):
    found = []
    for path in sorted(folder.glob("member-*.archive")):
        try:
            archive = calder.Archive(str(path))
        except calder.Error:  # just created, its header not yet written
            continue
        found.append((path, archive.complete, max(archive.frames, default=-1)))
    return found


def test_a_worker_killed_mid_ensemble_costs_nothing_but_time(client, tmp_path):
    folder = tmp_path / "checkpoint"
    spec = dict(seeds=6, frames=300, every=100, checkpoint=str(folder), checkpoint_every=10)
    ensemble = calder.Ensemble(SCENE, **spec)
    pids = client.run(os.getpid)  # {worker address: pid}
    killed = []

    def kill_one_worker_mid_member():
        # Once both workers are in the middle of a member (each has saved
        # a snapshot past frame 20, none is near its end), kill one.
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            running = [frame for _, complete, frame in _archives(folder) if not complete]
            if len(running) == 2 and all(20 <= frame <= 200 for frame in running):
                pid = sorted(pids.values())[0]
                os.kill(pid, signal.SIGKILL)
                killed.append(pid)
                return
            time.sleep(0.002)

    killer = threading.Thread(target=kill_one_worker_mid_member)
    killer.start()
    table = ensemble.run(client=client, batch_size=1)
    killer.join()
    assert killed, "no moment came with both workers in the middle of a member"

    status = ensemble.table()
    assert len(status) == 6 and "failed" not in set(status.status)
    resumed = status[status.status == "resumed"]
    assert len(resumed) >= 1, status
    assert (resumed.resumed_from >= 20).all()
    assert not any(w.endswith(f":{killed[0]}") for w in resumed.worker)
    expect_bits(table, calder.Ensemble(SCENE, **{**spec, "checkpoint": None}).run(workers=1))
    client.wait_for_workers(2)
