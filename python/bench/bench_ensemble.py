#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Members per second of a calder.Ensemble: the serial loop, the local
process pool and a Dask LocalCluster, for members of about 0.01 s, 0.1 s
and 1 s, in one run.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/bench_ensemble.py [--workers 2]

A member is the galaxy of exercise 2.16 (100 bodies under mutual attraction)
run for as many frames as take the member's length on this machine
(measured first). Each mode runs the same members and must give the same
table (checked); its overhead is the time it lost against the ideal, the
serial loop's time divided by the workers:

    overhead = time * workers / serial time - 1

(0 is perfect; it counts the pool's or the scheduler's cost, pickling, the
slowest worker's tail, and the machine's other load). On a machine that
other work shares, that figure mostly measures the other work; the second,

    outside members = 1 - (sum of the members' own seconds) / (time * workers)

is the share of the workers' time not spent inside a member (the
scheduler, transfers, building the table, the tail), which the machine's
load changes much less. The cluster's start is measured apart, once. Not a
test: timings are the machine's.
"""

import argparse
import os
import time

import calder

SCENE = "exercise-2.16"


def frames_for(seconds: float) -> int:
    simulation = calder.Simulation(SCENE)
    simulation.world.threads = 1
    start = time.perf_counter()
    simulation.run(300)
    per_frame = (time.perf_counter() - start) / 300
    return max(1, round(seconds / per_frame))


def _inside(ensemble) -> float:
    return sum(result.seconds for result in ensemble.status)


def timed(ensemble, **run):
    start = time.perf_counter()
    table = ensemble.run(progress=False, **run)
    return time.perf_counter() - start, table


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--seconds", type=float, default=8.0,
                        help="serial seconds of members per member length (default 8)")
    arguments = parser.parse_args()
    workers = arguments.workers

    from distributed import Client, LocalCluster

    start = time.perf_counter()
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           host="127.0.0.1", dashboard_address=None, silence_logs=40)
    client = Client(cluster)
    client.wait_for_workers(workers)
    cluster_start = time.perf_counter() - start

    print(f"calder.Ensemble: {SCENE}, {workers} workers, {os.cpu_count()} cores; "
          f"the LocalCluster started in {cluster_start:.2f} s (not counted below)")
    print()
    print("| member | members | mode | seconds | members/s | overhead vs serial | outside members |")
    print("|---|---|---|---|---|---|---|")
    for length in (0.01, 0.1, 1.0):
        frames = frames_for(length)
        count = max(2 * workers, round(arguments.seconds / length))
        ensemble = calder.Ensemble(SCENE, seeds=count, frames=frames,
                                   record=["state_hash", "kinetic_energy"])
        serial, expected = timed(ensemble, workers=1)
        modes = [("serial loop", serial, 1, _inside(ensemble))]
        pool, table = timed(ensemble, workers=workers)
        assert table.equals(expected), "the local pool's table differs"
        modes.append((f"local pool, {workers} processes", pool, workers, _inside(ensemble)))
        dask, table = timed(ensemble, client=client)
        assert table.equals(expected), "the cluster's table differs"
        modes.append((f"LocalCluster, {workers} workers", dask, workers, _inside(ensemble)))
        per_member = serial / count
        for name, seconds, used, inside in modes:
            overhead = "(reference)" if used == 1 else f"{seconds * used / serial - 1:+.1%}"
            outside = 1 - inside / (seconds * used)
            print(f"| {per_member:.3f} s ({frames} frames) | {count} | {name} | {seconds:.2f} | "
                  f"{count / seconds:.1f} | {overhead} | {outside:.1%} |", flush=True)
    client.close()
    cluster.close()


if __name__ == "__main__":
    main()
