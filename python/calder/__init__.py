# SPDX-License-Identifier: MIT
"""calder: the physics of chapter 2 (Forces) of The Nature of Code, for Python.

Bodies with mass moving under forces by Newton's laws, in the book's
vocabulary (World, Mover, apply_force, Gravity, Liquid, Attractor), with
p5.js's arithmetic to the last bit. The engine is C++ (the extension module
calder._calder); this package re-exports it and adds a few helpers.

    import calder
    world = calder.World(boundary=calder.Boundary.bounce())
    world.add_body(position=(320, 30))
    world.add(calder.Gravity(g=(0, 0.1)))
    world.step(100)
    world.y          # read-only numpy view of every body's y

Many runs of one scene (seeds, parameter grids), on the local cores or a
Dask cluster, checkpointed: calder.Ensemble (python/README.md, "Ensembles").

Errors: calder.Error (a ValueError) with calder's message.
"""

from __future__ import annotations

from . import _calder
from ._calder import *  # noqa: F401,F403  (the engine's API)
from ._calder import Canvas, GifWriter, Simulation, Error, SceneFileError  # noqa: F401
from .ensemble import Ensemble, member_seed  # noqa: F401  (pandas and Dask only when run)
from .scene_edit import SceneEdit  # noqa: F401

__all__ = [name for name in dir(_calder) if not name.startswith("_")] + [
    "frame_image",
    "render_gif",
    "Ensemble",
    "member_seed",
    "SceneEdit",
]


def frame_image(simulation: Simulation, scale: float = 1.0, style=None):
    """The simulation's current frame as a numpy array (height, width, 4) of uint8 RGBA."""
    scene = simulation.scene
    canvas = Canvas(int(scene.width), int(scene.height), scale)
    canvas.draw(simulation, style)
    return canvas.image()


def render_gif(simulation: Simulation, path: str, frames: int, fps: float = 30.0,
               every: int = 1, scale: float = 1.0, style=None) -> int:
    """Runs frames frames of the simulation, writing every every-th to a GIF; returns the count."""
    if every < 1:
        raise Error(f"render_gif: every must be >= 1 (got {every})")
    scene = simulation.scene
    canvas = Canvas(int(scene.width), int(scene.height), scale)
    with GifWriter(path, canvas.pixel_width, canvas.pixel_height, fps) as gif:
        for _ in range(frames):
            simulation.step()
            if simulation.frame % every == 0:
                canvas.draw(simulation, style)
                gif.add_frame(canvas)
        count = gif.frame_count
    return count
