#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Example 2.9, n bodies, the Python way: ten bodies of random mass attract
one another, updated one after another as the book's loop does
(UpdateOrder.sequential). Prints the momentum (not conserved by the
sequential order, conserved by the simultaneous one) and writes a GIF.

    python3 python/examples/example_2_9_n_bodies.py --out /tmp/calder
"""

import argparse
import pathlib

import calder


def build(seed=0, order=calder.UpdateOrder.sequential):
    world = calder.World(width=640, height=240, seed=seed, update_order=order)
    rng = world.random
    for _ in range(10):  # new Body(random(width), random(height), random(0.1, 2))
        x, y, mass = rng.random(640.0), rng.random(240.0), rng.random(0.1, 2.0)
        world.add_body(position=(x, y), mass=mass, radius=mass * 8.0)
    world.add(calder.MutualAttraction(law=calder.AttractionLaw.book(1.0, 5.0, 25.0)))
    return world


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=".", help="folder for example_2_9.gif")
    parser.add_argument("--frames", type=int, default=300)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    for order in (calder.UpdateOrder.sequential, calder.UpdateOrder.simultaneous):
        world = build(args.seed, order)
        p0 = calder.linear_momentum(world)
        world.step(args.frames)
        drift = (calder.linear_momentum(world) - p0).mag()
        print(f"{order.name:>12}: momentum changed by {drift:.3g} over {args.frames} frames")

    world = build(args.seed)
    canvas = calder.Canvas(640, 240, 0.5)
    with calder.GifWriter(str(out / "example_2_9.gif"), canvas.pixel_width,
                          canvas.pixel_height, 30) as gif:
        for frame in range(1, args.frames + 1):
            world.step()
            if frame % 3 == 0:
                canvas.draw_world(world, frame=frame)
                gif.add_frame(canvas)
    print(f"wrote {out / 'example_2_9.gif'}")


if __name__ == "__main__":
    main()
