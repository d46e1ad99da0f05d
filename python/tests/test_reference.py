# SPDX-License-Identifier: MIT
"""Example 2.1 written with World in Python matches p5.js bit for bit."""

import csv

import numpy as np

import calder

PRESSED = range(100, 161)  # draw() numbers with the mouse held (scenario.json)


def read_reference(folder):
    with open(folder / "example_2_1_forces" / "trajectory.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    # p5's numbers are written in the shortest form that reads back to the same double.
    return np.array([[float(r[k]) for k in ("x", "y", "vx", "vy")] for r in rows])


def example_2_1():
    # Gravity (0, 0.1) always, wind (0.1, 0) while the mouse is pressed; the
    # mover bounces off the left, right and bottom edges (not the top).
    world = calder.World(width=640, height=240,
                         boundary=calder.Boundary.bounce(1.0, False, calder.Edges(top=False)))
    world.add_body(position=(320, 30), mass=1)
    world.add(calder.Gravity(g=(0, 0.1)))
    wind = world.add(calder.Wind(force=(0.1, 0), enabled=False))
    return world, wind


def test_example_2_1_matches_p5_bit_for_bit(reference_dir):
    reference = read_reference(reference_dir)
    world, wind = example_2_1()
    states = [(world.x[0], world.y[0], world.vx[0], world.vy[0])]
    for frame in range(1, len(reference)):
        wind.enabled = frame in PRESSED  # the live handle switches the world's wind
        world.step()
        states.append((world.x[0], world.y[0], world.vx[0], world.vy[0]))
    got = np.array(states)
    assert got.shape == reference.shape == (601, 4)
    assert np.array_equal(got.view(np.uint64), reference.view(np.uint64))  # the same bits


def test_example_2_1_book_style_with_a_mover(reference_dir):
    # The sketch's own loop: applyForce, update, checkEdges on a Mover.
    reference = read_reference(reference_dir)
    world = calder.World(boundary=calder.Boundary.bounce(1.0, False, calder.Edges(top=False)))
    mover = world.add_mover(position=(320, 30), mass=1)
    gravity, wind = calder.Vec2(0, 0.1), calder.Vec2(0.1, 0)
    for frame in range(1, len(reference)):
        mover.apply_force(gravity)
        if frame in PRESSED:
            mover.apply_force(wind)
        mover.update()
        mover.check_edges()
        p, v = mover.position, mover.velocity
        assert (p.x, p.y, v.x, v.y) == tuple(reference[frame]), frame


def test_a_wrong_world_is_caught(reference_dir):
    # Without the wind the trajectory leaves the reference: the comparison means something.
    reference = read_reference(reference_dir)
    world, wind = example_2_1()
    world.step(200)
    assert abs(world.x[0] - reference[200][0]) > 1e-3


def load_example(name):
    import importlib.util
    import pathlib
    path = pathlib.Path(__file__).resolve().parents[1] / "examples" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_examples_2_5_and_2_9_written_in_python_are_the_built_in_scenes():
    # The built-in scenes are checked against p5.js by the C++ tests; the
    # Python examples draw the same world from the same seed and step it
    # to the same bits (no mouse: the scenes' scripted clicks are left out).
    for name, scene, frames in (("example_2_5_fluid_resistance", "example-2.5", 200),
                                ("example_2_9_n_bodies", "example-2.9", 200)):
        for seed in (0, 11):
            world = load_example(name).build(seed)
            simulation = calder.Simulation(scene, seed=seed)
            assert calder.state_hash(world) == calder.state_hash(simulation.world), name
            world.step(frames)
            for _ in range(frames):
                simulation.step(mouse_pressed=False)
            assert calder.state_hash(world) == calder.state_hash(simulation.world), name
