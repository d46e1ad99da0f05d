#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Example 2.1, Forces, the Python way: gravity pulls a mover down; wind
pushes it right while the mouse is pressed (here: frames 100 to 160, as in
the p5.js reference). Writes the last frame as a PNG and prints where the
mover ended up.

    python3 python/examples/example_2_1_forces.py --out /tmp/calder
"""

import argparse
import pathlib

import calder

WIND_FRAMES = range(100, 161)


def build():
    """The sketch's setup(): a canvas 640 x 240, one mover of mass 1 at (320, 30)."""
    world = calder.World(width=640, height=240,
                         boundary=calder.Boundary.bounce(1.0, False, calder.Edges(top=False)))
    mover = world.add_mover(position=(320, 30), mass=1)
    world.add(calder.Gravity(g=(0, 0.1)))
    wind = world.add(calder.Wind(force=(0.1, 0), enabled=False))  # a live handle
    return world, mover, wind


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=".", help="folder for example_2_1.png")
    parser.add_argument("--frames", type=int, default=600)
    args = parser.parse_args()

    world, mover, wind = build()
    for frame in range(1, args.frames + 1):  # draw(), once a frame
        wind.enabled = frame in WIND_FRAMES  # if (mouseIsPressed) mover.applyForce(wind)
        world.step()

    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    canvas = calder.Canvas(640, 240)
    canvas.draw_world(world, frame=args.frames)
    canvas.write_png(str(out / "example_2_1.png"))
    print(f"frame {args.frames}: position {mover.position}, velocity {mover.velocity}")
    print(f"wrote {out / 'example_2_1.png'}")


if __name__ == "__main__":
    main()
