#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A notebook in a script: run two bodies in orbit (the physical law,
velocity Verlet), then plot the trajectory and the energy over time with
matplotlib, saving two PNGs. Each block below is a notebook cell.

    python3 python/examples/plot_trajectory_energy.py --out /tmp/calder
"""

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")  # files, no window
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import calder  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", default=".", help="folder for the two PNGs")
parser.add_argument("--steps", type=int, default=3000)
args = parser.parse_args()
out = pathlib.Path(args.out)
out.mkdir(parents=True, exist_ok=True)

# %% A heavy sun and a light planet on a near-circular orbit: v = sqrt(G M / r).
world = calder.World(width=1000, height=1000, dt=0.5,
                     integrator=calder.Integrator.velocity_verlet)
sun_mass, radius = 1000.0, 200.0
speed = np.sqrt(sun_mass / radius)
world.add_bodies(x=[500.0, 500.0 + radius], y=[500.0, 500.0], vx=[0.0, 0.0],
                 vy=[-speed / 1000.0, speed], mass=[sun_mass, 1.0])
world.add(calder.MutualAttraction(law=calder.AttractionLaw.newtonian(G=1.0, softening=1.0)))

# %% Step and record: the views x, y show the live state; copy them each step.
time = np.empty(args.steps + 1)
xy = np.empty((args.steps + 1, 2, 2))
energy = np.empty(args.steps + 1)
for k in range(args.steps + 1):
    if k:
        world.step()
    time[k] = world.time
    xy[k] = np.stack([world.x, world.y], axis=1)
    energy[k] = calder.total_energy(world)

# %% The trajectory.
fig, ax = plt.subplots(figsize=(5, 5))
ax.plot(xy[:, 1, 0], xy[:, 1, 1], lw=0.8, label="planet")
ax.plot(xy[:, 0, 0], xy[:, 0, 1], "o", ms=3, label="sun")
ax.set_aspect("equal")
ax.invert_yaxis()  # canvas y points down
ax.set(title="Two bodies, velocity Verlet", xlabel="x", ylabel="y")
ax.legend()
fig.tight_layout()
fig.savefig(out / "trajectory.png", dpi=100)

# %% The energy over time: bounded oscillation, no drift (a symplectic integrator).
relative = (energy - energy[0]) / abs(energy[0])
fig, ax = plt.subplots(figsize=(6, 3))
ax.plot(time, relative, lw=0.8)
ax.set(title="Total energy, relative change", xlabel="time (frames)", ylabel="(E - E0) / |E0|")
fig.tight_layout()
fig.savefig(out / "energy.png", dpi=100)

print(f"largest relative energy change: {np.max(np.abs(relative)):.2e}")
print(f"wrote {out / 'trajectory.png'} and {out / 'energy.png'}")
