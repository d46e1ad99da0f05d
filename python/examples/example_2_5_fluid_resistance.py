#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Example 2.5, Fluid resistance, the Python way: nine movers of random mass
fall into a liquid that fills the bottom half of the canvas. The movers are
added in one call from numpy arrays; the masses are drawn from the world's
p5-compatible generator in the sketch's order, so a seed gives the sketch's
world. Writes an animated GIF and a chart of each mover's depth over time.

    python3 python/examples/example_2_5_fluid_resistance.py --out /tmp/calder
"""

import argparse
import pathlib

import numpy as np

import calder


def build(seed=0):
    world = calder.World(width=640, height=240, seed=seed,
                         boundary=calder.Boundary.bounce(0.9, True, calder.Edges(
                             left=False, right=False, top=False, bottom=True)))
    masses = np.array([world.random.random(0.5, 3.0) for _ in range(9)])  # random(0.5, 3)
    world.add_bodies(x=40.0 + 70.0 * np.arange(9), y=0.0, mass=masses, radius=masses * 8.0)
    world.add(calder.Liquid(region=calder.Rect(0, 120, 640, 120), c=0.1))
    world.add(calder.Gravity(g=(0, 0.1), scale_by_mass=True))  # the same fall for every mass
    return world


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=".", help="folder for the GIF and the chart")
    parser.add_argument("--frames", type=int, default=240)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    world = build(args.seed)
    depth = np.empty((args.frames + 1, len(world)))
    depth[0] = world.y  # a read-only view, copied into the table
    canvas = calder.Canvas(640, 240, 0.5)
    style = calder.RenderStyle()
    with calder.GifWriter(str(out / "example_2_5.gif"), canvas.pixel_width,
                          canvas.pixel_height, 30) as gif:
        for frame in range(1, args.frames + 1):
            world.step()
            depth[frame] = world.y
            if frame % 4 == 0:
                canvas.draw_world(world, style, frame)
                gif.add_frame(canvas)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 3.5))
    for i, mass in enumerate(world.masses):
        ax.plot(depth[:, i], label=f"m = {mass:.2f}")
    ax.axhline(120, color="steelblue", linestyle="--", label="liquid surface")
    ax.invert_yaxis()
    ax.set(xlabel="frame", ylabel="y (pixels, down)", title="Example 2.5: falling into a liquid")
    ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    fig.savefig(out / "example_2_5_depth.png", dpi=100)
    print(f"heaviest mover ends at y = {depth[-1, np.argmax(world.masses)]:.3f}")
    print(f"wrote {out / 'example_2_5.gif'} and {out / 'example_2_5_depth.png'}")


if __name__ == "__main__":
    main()
