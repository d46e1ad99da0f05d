# SPDX-License-Identifier: MIT
"""Simulation.set_bodies, FixedStep, TrajectoryWriter and format_number against
C++ truth: `calder run --state` / `--trajectory` (the same bits and bytes), and
exact arithmetic where the step is a power of two."""

import io
import math
import re
import struct
import subprocess

import numpy as np
import pytest

import calder

SEED = 5
FRAMES = 60


def bodies(n, seed=1):
    """Bodies inside the book's 640 x 240 canvas, moving a little."""
    rng = np.random.default_rng(seed)
    return {
        "x": rng.uniform(20, 620, n), "y": rng.uniform(20, 200, n),
        "vx": rng.uniform(-2, 2, n), "vy": rng.uniform(-2, 2, n),
        "mass": rng.uniform(0.5, 4, n), "radius": rng.uniform(2, 20, n),
    }


def write_state(path, columns):
    """A --state CSV; repr() is Python's shortest exact form, read back by strtod."""
    names = ["x", "y", "vx", "vy", "mass", "radius"]
    rows = zip(*(columns[name] for name in names))
    path.write_text(",".join(names) + "\n" +
                    "".join(",".join(repr(float(v)) for v in row) + "\n" for row in rows))


def calder_run(exe, *arguments):
    return subprocess.run([exe, "run", *arguments], check=True, capture_output=True,
                          text=True).stdout


def printed_hash(out):
    match = re.search(r"state hash\s*:?\s*([0-9a-f]{16})", out)
    assert match, out
    return int(match.group(1), 16)


def bits(array):
    return [struct.pack("<d", v) for v in np.asarray(array, dtype=float)]


# --- Simulation.set_bodies ------------------------------------------------------

# calder run --state gives each body the friction and drag area of the scene's
# first body group; from Python they are given (a wrong one changes the hash:
# exercise 2.6 has a Friction field, exercise 2.9 drag).
@pytest.mark.parametrize("scene, friction, drag_area", [
    ("example-2.5", None, 1.0),
    ("exercise-2.6", 0.01, 1.0),
    ("exercise-2.9", None, 0.8),
])
def test_set_bodies_runs_as_calder_run_state(calder_exe, tmp_path, scene, friction, drag_area):
    columns = bodies(12)
    state = tmp_path / "state.csv"
    write_state(state, columns)
    simulation = calder.Simulation(scene, seed=SEED)
    simulation.set_bodies(**columns, friction=friction, drag_area=drag_area)
    assert len(simulation.world) == 12
    simulation.run(FRAMES)
    expected = printed_hash(calder_run(calder_exe, scene, "--seed", str(SEED), "--frames",
                                       str(FRAMES), "--state", str(state)))
    assert calder.state_hash(simulation.world) == expected


def test_set_bodies_round_trips_every_column():
    simulation = calder.Simulation("example-2.5", seed=SEED)
    columns = bodies(7)
    frictions = np.array([0.1, math.nan, 0.2, 0.0, math.nan, 0.5, 0.3])
    areas = np.linspace(0.5, 2.0, 7)
    simulation.set_bodies(**columns, friction=frictions, drag_area=areas)
    world = simulation.world
    for name, view in (("x", world.x), ("y", world.y), ("vx", world.vx), ("vy", world.vy),
                       ("mass", world.masses), ("radius", world.radii)):
        assert bits(view) == bits(columns[name]), name
    assert bits(world.drag_areas) == bits(areas)
    assert [world.friction(i) for i in range(7)] == [0.1, None, 0.2, 0.0, None, 0.5, 0.3]
    assert simulation.frame == 0  # the frame count and the fields stay
    assert len(world.fields) == len(calder.Simulation("example-2.5").world.fields)


def test_set_bodies_takes_numbers_for_all_bodies_and_lists():
    simulation = calder.Simulation("example-2.1")
    simulation.set_bodies([10.0, 20.0, 30.0], 50, vy=1, mass=2.0)
    world = simulation.world
    assert list(world.x) == [10.0, 20.0, 30.0]
    assert list(world.y) == [50.0] * 3
    assert list(world.vy) == [1.0] * 3
    assert list(world.masses) == [2.0] * 3
    assert list(world.radii) == [0.0] * 3  # the defaults of World.add_bodies
    assert [world.friction(i) for i in range(3)] == [None] * 3
    # Empty arrays: no bodies (not one body of defaults).
    simulation.set_bodies(np.array([]), [], mass=2.0)
    assert len(simulation.world) == 0
    with pytest.raises(calder.Error, match=r"^Simulation\.set_bodies: x is empty but y has 2 "
                                           r"values"):
        simulation.set_bodies([], [1.0, 2.0])


def test_add_bodies_of_empty_arrays_adds_none():
    world = calder.World()
    world.add_body()
    assert world.add_bodies(np.array([]), np.array([]), mass=3.0) == range(1, 1)
    assert len(world) == 1
    with pytest.raises(calder.Error, match=r"^World\.add_bodies: vx is empty but x has 3 values"):
        world.add_bodies([1.0, 2.0, 3.0], 0.0, vx=[])
    assert len(world) == 1


def test_set_bodies_is_all_or_nothing_with_calders_words():
    simulation = calder.Simulation("example-2.5", seed=SEED)
    before = calder.state_hash(simulation.world)
    count = len(simulation.world)
    with pytest.raises(calder.Error, match=r"^Simulation\.set_bodies: body 2: "
                                           r"World::add_body: mass must be > 0 \(got -1\)"):
        simulation.set_bodies([1, 2, 3], [1, 2, 3], mass=[1, 1, -1])
    with pytest.raises(calder.Error, match=r"^Simulation\.set_bodies: y has 2 values, "
                                           r"expected 3, 1 or none"):
        simulation.set_bodies([1, 2, 3], [1, 2])
    with pytest.raises(calder.Error, match=r"body 0: .*position"):
        simulation.set_bodies([math.nan], [0.0])
    with pytest.raises(TypeError, match=r"^Simulation\.set_bodies: x must be a number or a "
                                        r"1-D array of numbers"):
        simulation.set_bodies(np.zeros((2, 2)), 0.0)
    assert len(simulation.world) == count
    assert calder.state_hash(simulation.world) == before


def test_set_bodies_with_a_view_alive_raises_and_changes_nothing():
    # The world's arrays are replaced: a view of the old ones would read freed memory.
    simulation = calder.Simulation("example-2.5", seed=SEED)
    x = simulation.world.x
    kept = x.copy()
    with pytest.raises(calder.Error, match=r"^Simulation\.set_bodies: 1 numpy view"):
        simulation.set_bodies([1.0], [2.0])
    assert bits(x) == bits(kept)
    del x
    simulation.set_bodies([1.0], [2.0])
    assert list(simulation.world.x) == [1.0]


# --- TrajectoryWriter and format_number ----------------------------------------------

@pytest.mark.parametrize("scene", ["example-2.1", "exercise-2.16"])
def test_trajectory_writer_writes_calder_runs_bytes(calder_exe, tmp_path, scene):
    path = tmp_path / "cpp.csv"
    calder_run(calder_exe, scene, "--seed", str(SEED), "--frames", str(FRAMES),
               "--trajectory", str(path))
    simulation = calder.Simulation(scene, seed=SEED)
    out = io.StringIO()
    writer = calder.TrajectoryWriter(out)
    writer.write(0, simulation.world)  # frame 0: after setup
    for frame in range(1, FRAMES + 1):
        simulation.step()
        writer.write(frame, simulation.world)
    assert out.getvalue() == path.read_text()


def test_a_trajectory_reads_back_to_the_same_bits(tmp_path):
    simulation = calder.Simulation("example-2.5", seed=SEED)
    simulation.run(40)
    path = tmp_path / "t.csv"
    with open(path, "w", encoding="ascii") as out:
        writer = calder.TrajectoryWriter(out)
        writer.write(40, simulation.world)
    lines = path.read_text().splitlines()
    assert lines[0] == "frame,body,x,y,vx,vy"
    rows = [line.split(",") for line in lines[1:]]
    world = simulation.world
    assert [int(r[0]) for r in rows] == [40] * len(world)
    assert [int(r[1]) for r in rows] == list(range(len(world)))
    for column, view in zip(range(2, 6), (world.x, world.y, world.vx, world.vy)):
        assert bits([float(r[column]) for r in rows]) == bits(view)


def test_trajectory_writer_needs_a_text_stream():
    with pytest.raises(TypeError, match=r"^TrajectoryWriter: out must have write\(str\)"):
        calder.TrajectoryWriter(42)


def test_format_number_is_shortest_and_exact():
    assert calder.format_number(0.1) == "0.1"
    assert calder.format_number(30.599999999999998) == "30.599999999999998"
    assert calder.format_number(0.1 + 0.2) == "0.30000000000000004"
    assert calder.format_number(1e-300) == "1e-300"
    assert calder.format_number(2.0) == "2"
    assert [calder.format_number(v) for v in (math.nan, math.inf, -math.inf)] == [
        "nan", "inf", "-inf"]
    rng = np.random.default_rng(3)
    for value in np.concatenate([rng.normal(0, 1e3, 200), rng.uniform(-1e-8, 1e-8, 50)]):
        text = calder.format_number(float(value))
        assert float(text) == value
        # Python's repr is the shortest exact form too: no more significant digits.
        digits = len(re.sub(r"e.*|[-.]|^0+", "", repr(float(value))).lstrip("0"))
        assert len(re.sub(r"e.*|[-.]", "", text).lstrip("0")) <= digits


# --- FixedStep ---------------------------------------------------------------------
# 4 steps per second: a step is 0.25 s, and eighths of a second add up exactly.

def test_fixed_step_counts_whole_steps_and_carries_the_rest():
    world = calder.World()
    world.add_body(velocity=(1.0, 0.0))
    pacer = calder.FixedStep(4.0)
    assert pacer.steps_per_second == 4.0
    assert pacer.advance(world, 0.125) == 0
    assert pacer.alpha == 0.5
    assert pacer.advance(world, 0.125) == 1
    assert pacer.alpha == 0.0
    assert pacer.advance(world, 0.875) == 3
    assert pacer.alpha == 0.5
    assert world.step_count == 4
    assert world.position(0) == calder.Vec2(4.0, 0.0)  # 4 steps of dt 1 at speed 1
    pacer.reset()
    assert pacer.alpha == 0.0
    assert pacer.advance(world, 0.0) == 0


def test_fixed_step_drops_a_backlog_beyond_max_steps():
    world = calder.World()
    pacer = calder.FixedStep(4.0, max_steps=3)
    assert pacer.advance(world, 10.0) == 3  # 40 steps due, 3 run
    assert pacer.alpha == 0.0  # the rest dropped
    assert pacer.advance(world, 0.0) == 0
    assert world.step_count == 3
    pacer.steps_per_second = 8.0
    assert pacer.advance(world, 0.25) == 2


def test_fixed_step_steps_a_simulation_as_run_does():
    paced = calder.Simulation("example-2.5", seed=SEED)
    run = calder.Simulation("example-2.5", seed=SEED)
    pacer = calder.FixedStep(4.0, max_steps=8)
    steps = sum(pacer.advance(paced, 0.375) for _ in range(20))  # 1.5 steps each
    assert steps == 30
    assert paced.frame == 30  # the scripted frames, mouse included
    run.run(30)
    assert calder.state_hash(paced.world) == calder.state_hash(run.world)


def test_fixed_step_calls_a_function_per_step():
    calls = []
    pacer = calder.FixedStep(4.0)
    assert pacer.advance(lambda: calls.append(1), 0.75) == 3
    assert len(calls) == 3

    def failing():
        raise RuntimeError("stop")
    with pytest.raises(RuntimeError, match="stop"):
        pacer.advance(failing, 0.25)


def test_fixed_step_bad_arguments_raise_with_calders_words():
    with pytest.raises(calder.Error, match=r"^FixedStep: steps_per_second must be > 0"):
        calder.FixedStep(0.0)
    with pytest.raises(calder.Error, match=r"^FixedStep: steps_per_second must be finite"):
        calder.FixedStep(math.nan)
    with pytest.raises(calder.Error, match=r"^FixedStep: max_steps must be >= 1 \(got 0\)"):
        calder.FixedStep(60.0, 0)
    pacer = calder.FixedStep()
    world = calder.World()
    with pytest.raises(calder.Error, match=r"^FixedStep::advance: elapsed_seconds must be >= 0"):
        pacer.advance(world, -0.1)
    with pytest.raises(calder.Error, match=r"^FixedStep::advance: elapsed_seconds"):
        pacer.advance(world, math.nan)
    with pytest.raises(calder.Error, match=r"^FixedStep::set_steps_per_second: steps_per_second"):
        pacer.steps_per_second = -1.0
    with pytest.raises(TypeError, match=r"^FixedStep\.advance: target must be a World, a "
                                        r"Simulation or a callable"):
        pacer.advance(3, 1.0)
    assert pacer.steps_per_second == 60.0
    assert world.step_count == 0
