#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""What calling calder from Python costs, against the same work in C++, in one run.

    python3 python/bench/bench_python.py [--cpp build/python/calder_python_bench_cpp]

(with PYTHONPATH=build/python). Three workloads, best of 2 x --repeat each,
one thread each side: step() on a 10-body world (calls per second), step(1000)
on the rain scene's drops with 10^5 bodies (body-steps per second), adding
10^5 bodies from arrays into an emptied world (bodies per second; the fastest
of ADD_TRIES adds per repetition). The state hashes of both sides
must agree: the same work was done. Not a test: timings are the machine's.
"""

import argparse
import json
import os
import pathlib
import subprocess
import time

import numpy as np

import calder

SMALL_CALLS = 200_000
RAIN_STEPS = 1000
RAIN_BODIES = 100_000
ADD_TRIES = 10  # adds (~2 ms each) per repetition, the fastest kept: a shared machine preempts
WIDTH, HEIGHT = 6400.0, 2400.0


def drops(n, width, height):
    """The rain scene's drops, drawn in the same order as bench_cpp.cpp: the
    columns x, y, vx, vy, mass, radius, made once (as the C++ side's vectors)."""
    rng = calder.Random(1)
    x, y, mass = np.empty(n), np.empty(n), np.empty(n)
    for i in range(n):
        x[i], y[i], mass[i] = rng.random(width), rng.random(height), rng.random(0.5, 3.0)
    vx, vy = np.zeros(n), np.zeros(n)
    vx[:] = vy[:] = 0.0  # written, as std::vector writes its zeros (no untouched pages)
    return x, y, vx, vy, mass, mass * 2.0


def rain(columns, width, height, add_fields=True):
    world = calder.World(width=width, height=height, threads=1,
                         boundary=calder.Boundary.bounce(0.9, True, calder.Edges(top=False)))
    world.add_bodies(*columns)
    if add_fields:
        world.add(calder.Gravity(g=(0, 0.1), scale_by_mass=True))
        world.add(calder.Drag(c=0.01))
    return world


def python_side(ten, many):
    """One repetition of the three workloads; the rates and the state hashes."""
    small = rain(ten, 640.0, 240.0)
    step = small.step
    start = time.perf_counter()
    for _ in range(SMALL_CALLS):
        step()
    small_time = time.perf_counter() - start
    small_hash = calder.state_hash(small)

    # Added again into the emptied world: its memory is mapped already, so
    # this times the adding, not the system's page faults.
    added = rain(many, WIDTH, HEIGHT, add_fields=False)
    add_time = float("inf")
    for _ in range(ADD_TRIES):
        added.clear_bodies()
        start = time.perf_counter()
        added.add_bodies(*many)
        add_time = min(add_time, time.perf_counter() - start)

    added.add(calder.Gravity(g=(0, 0.1), scale_by_mass=True))
    added.add(calder.Drag(c=0.01))
    start = time.perf_counter()
    added.step(RAIN_STEPS)
    rain_time = time.perf_counter() - start
    rain_hash = calder.state_hash(added)
    return {
        "step_calls_per_s": SMALL_CALLS / small_time,
        "rain_body_steps_per_s": RAIN_BODIES * RAIN_STEPS / rain_time,
        "add_bodies_per_s": RAIN_BODIES / add_time,
        "small_hash": small_hash,
        "rain_hash": rain_hash,
    }


def main():
    here = pathlib.Path(calder.__file__).resolve().parent.parent
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cpp", default=os.environ.get(
        "CALDER_PYTHON_BENCH_CPP", str(here / "calder_python_bench_cpp")))
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()

    # Both sides run --repeat repetitions in one process (the later ones warm:
    # memory already mapped), twice in turn so that both see the same load
    # on a shared machine; each side keeps its best.
    ten, many = drops(10, 640.0, 240.0), drops(RAIN_BODIES, WIDTH, HEIGHT)
    cpp, py = {}, {}
    for _ in range(2):
        runs = [json.loads(subprocess.run([args.cpp, str(args.repeat)], check=True,
                                          capture_output=True, text=True).stdout)]
        runs_py = [python_side(ten, many) for _ in range(args.repeat)]
        for best, side in ((cpp, runs), (py, runs_py)):
            for one in side:
                for key, value in one.items():
                    best[key] = max(best.get(key, value), value) if key.endswith("_s") else value
    for key in ("small_hash", "rain_hash"):
        if cpp[key] != py[key]:
            raise SystemExit(f"bench_python: {key} differs (C++ {cpp[key]}, Python {py[key]}): "
                             "the two sides did different work")

    step_overhead_us = (1 / py["step_calls_per_s"] - 1 / cpp["step_calls_per_s"]) * 1e6
    print(f"load: {os.getloadavg()[0]:.1f} (1-minute average, {os.cpu_count()} cores)")
    print(f"{'workload':<42} {'C++':>12} {'Python':>12} {'Python/C++':>11}")
    rows = [
        ("step() on 10 bodies (calls/s)", "step_calls_per_s"),
        ("step(1000), rain, 10^5 bodies (body-steps/s)", "rain_body_steps_per_s"),
        ("add 10^5 bodies from arrays (bodies/s)", "add_bodies_per_s"),
    ]
    for label, key in rows:
        print(f"{label:<42} {cpp[key]:>12.4g} {py[key]:>12.4g} {py[key] / cpp[key]:>10.3f}x")
    print(f"step(): {step_overhead_us:.3f} us more per call from Python (target: <= 1 us)")
    print("state hashes equal on both sides: the same work")


if __name__ == "__main__":
    main()
