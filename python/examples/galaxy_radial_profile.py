#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The galaxy of exercise 2.16 over 100 seeds, as a calder.Ensemble on a Dask
cluster: its radial profile (stars per unit area at each distance from the
sun) at the start and after the run, with the spread between seeds, plotted
with matplotlib.

    python3 python/examples/galaxy_radial_profile.py --out /tmp/calder

Runs on a LocalCluster of two worker processes here; on any cluster by
changing the one line that makes the client (see CLUSTER below), e.g.
Client("tcp://scheduler:8786"), or dask_jobqueue.SLURMCluster(...). With
--checkpoint DIR (a folder every worker sees), a worker that dies costs
only the frames since its member's last snapshot, and running the script
again skips what finished.
"""

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")  # files, no window
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import calder  # noqa: E402


def surface_density(table, frame, edges):
    """Stars per unit area in each ring [edges[k], edges[k+1]), one row per
    seed: a (seeds, rings) array."""
    rows = table[table.frame == frame]
    radius = np.hypot(rows.x.to_numpy(), rows.y.to_numpy()).reshape(-1, 100)
    counts = np.stack([np.histogram(r, edges)[0] for r in radius])
    return counts / (np.pi * (edges[1:] ** 2 - edges[:-1] ** 2))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=".", help="folder for the PNG")
    parser.add_argument("--seeds", type=int, default=100)
    parser.add_argument("--frames", type=int, default=600)
    parser.add_argument("--checkpoint", default=None, help="a folder for the members' archives")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    from distributed import Client, LocalCluster

    # CLUSTER: the one line to change for another cluster.
    client = Client(LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None))

    # Each member: the galaxy with its own seed (100 seeds derived from
    # seed 0), the stars' positions at the first and the last frame.
    ensemble = calder.Ensemble("exercise-2.16", seeds=args.seeds, frames=args.frames,
                               every=args.frames, record=["x", "y"],
                               checkpoint=args.checkpoint)
    table = ensemble.run(client=client)
    client.close()

    edges = np.linspace(0, 300, 31)
    middles = (edges[:-1] + edges[1:]) / 2
    figure, axes = plt.subplots(figsize=(7, 4.2))
    for frame, colour in ((0, "tab:blue"), (args.frames, "tab:red")):
        density = surface_density(table, frame, edges)
        mean = density.mean(axis=0)
        spread = density.std(axis=0)
        axes.plot(middles, mean, color=colour, label=f"frame {frame}")
        axes.fill_between(middles, mean - spread, mean + spread, color=colour, alpha=0.2)
    axes.set_xlabel("distance from the sun (pixels)")
    axes.set_ylabel("stars per square pixel")
    axes.set_title(f"Exercise 2.16's galaxy, {args.seeds} seeds (mean and one standard "
                   "deviation)", fontsize=10)
    axes.legend()
    figure.tight_layout()
    path = out / "galaxy_radial_profile.png"
    figure.savefig(path, dpi=100)
    stars = table[table.frame == args.frames]
    print(f"{len(ensemble)} members, {len(stars)} stars at frame {args.frames}; "
          f"median distance {np.median(np.hypot(stars.x, stars.y)):.1f} px; wrote {path}")


if __name__ == "__main__":  # worker processes import this file: run only as a script
    main()
