# SPDX-License-Identifier: MIT
"""Snapshots from Python: a run saved (by the calder command, or by the module's
C++) and loaded in Python goes on with the same bits as a run never stopped;
pickle and copy.deepcopy do the same; archives give any frame alone; and the
numpy-only reader (calder.snapshot_reader) reads what C++ wrote."""

import copy
import pickle
import subprocess

import numpy as np
import pytest

import calder
from calder import snapshot_reader

SEEDS = (0, 1, 42)


def straight(name, seed, frames):
    sim = calder.Simulation(name, seed)
    sim.run(frames)
    return sim


def expect_same(a, b, same_scene=True):
    """The same bits: bodies, fields, generators, clock and mouse (and the
    scene, unless the runs were started with other --frames)."""
    assert calder.state_hash(a.world) == calder.state_hash(b.world)
    for column in ("x", "y", "vx", "vy", "masses", "radii"):
        assert np.array_equal(getattr(a.world, column), getattr(b.world, column))
    assert a.frame == b.frame
    if same_scene:
        assert a.to_bytes() == b.to_bytes()
    sections_a = snapshot_reader.read_sections(a.to_bytes())
    sections_b = snapshot_reader.read_sections(b.to_bytes())
    for tag in ("SIMU", "WRLD", "RAND", "FLDS", "BODY"):
        assert bytes(sections_a[tag]) == bytes(sections_b[tag]), tag


@pytest.mark.parametrize("name", [name for name, _ in calder.builtin_scenes()])
def test_every_scene_saved_by_the_command_goes_on_in_python(name, calder_exe, tmp_path):
    for seed in SEEDS:
        path = tmp_path / f"{name}-{seed}.snap"
        subprocess.run([calder_exe, "run", name, "--frames", "30", "--seed", str(seed),
                        "--save", str(path)], check=True, capture_output=True)
        resumed = calder.Simulation.load(str(path))
        assert resumed.frame == 30
        resumed.run(25)
        expect_same(straight(name, seed, 55), resumed, same_scene=False)


def test_pickle_deepcopy_and_bytes_go_on_bit_for_bit():
    sim = calder.Simulation("exercise-2.7", 42)
    sim.run(25)
    twins = [pickle.loads(pickle.dumps(sim)), copy.deepcopy(sim), copy.copy(sim),
             calder.Simulation.from_bytes(sim.to_bytes())]
    sim.run(40)
    for twin in twins:
        twin.run(40)
        expect_same(sim, twin)


def test_a_world_pickles_with_its_generator():
    world = calder.World(dt=0.5, seed=9)
    world.add(calder.Gravity())
    world.add_body(position=(10, 20), velocity=(1, 0), mass=2.0)
    world.step(7)
    twin = pickle.loads(pickle.dumps(world))
    assert twin.random.random() == world.random.random()
    world.step(10)
    twin.step(10)
    assert calder.state_hash(twin) == calder.state_hash(world)
    assert twin.time == world.time


def test_the_numpy_reader_reads_what_cpp_wrote(tmp_path):
    sim = calder.Simulation("rain", 1)
    sim.run(12)
    path = tmp_path / "rain.snap"
    sim.save(str(path))
    snap = snapshot_reader.read_snapshot(path)
    assert (snap.frame, snap.scene, snap.steps) == (12, "rain", sim.world.step_count)
    assert snap.time == sim.world.time
    for mine, numpy_name in (("x", "x"), ("y", "y"), ("vx", "vx"), ("vy", "vy"),
                             ("masses", "mass"), ("radii", "radius")):
        assert np.array_equal(getattr(sim.world, mine), snap.bodies[numpy_name])
    assert list(snap.bodies) == ["x", "y", "vx", "vy", "ax", "ay", "mass", "radius",
                                 "friction", "drag_area"]


def test_an_archive_gives_any_frame_alone(tmp_path):
    path = str(tmp_path / "run.archive")
    sim = calder.Simulation("example-2.7", 1)
    with calder.ArchiveWriter(path) as archive:
        for _ in range(5):
            archive.append(sim)
            sim.run(7)
    reader = calder.Archive(path)
    assert reader.complete and reader.frames == [0, 7, 14, 21, 28]
    resumed = reader.at_frame(14)
    resumed.run(36)
    expect_same(straight("example-2.7", 1, 50), resumed)
    numpy_archive = snapshot_reader.Archive(path)
    assert numpy_archive.complete and numpy_archive.frames == reader.frames
    assert numpy_archive.snapshot_bytes(3) == reader.snapshot_bytes(3)
    assert numpy_archive.snapshot(numpy_archive.index_of(21)).frame == 21
    # Cut in the middle of its fourth snapshot: the first three remain.
    data = open(path, "rb").read()
    cut = tmp_path / "cut.archive"
    offsets, at = [], 16  # each record: "SNAP", CRC-32, frame, length, then the snapshot
    while data[at:at + 4] == b"SNAP":
        offsets.append(at)
        at += 24 + (int.from_bytes(data[at + 16:at + 24], "little") + 7) // 8 * 8
    assert len(offsets) == 5
    cut.write_bytes(data[:offsets[3] + 100])
    assert calder.Archive(str(cut)).frames == [0, 7, 14]
    cut_numpy = snapshot_reader.Archive(cut)
    assert not cut_numpy.complete and cut_numpy.frames == [0, 7, 14]


def test_bad_snapshots_raise_one_line_naming_the_source(tmp_path):
    data = calder.Simulation("example-2.1", 0).to_bytes()
    flipped = bytearray(data)
    flipped[-12] ^= 0x40
    for bad, words in ((bytes(flipped), "checksum"), (data[:-30], "truncated"),
                       (b"nonsense", "not a calder snapshot")):
        with pytest.raises(calder.Error, match=words) as info:
            calder.Simulation.from_bytes(bad)
        assert "\n" not in str(info.value) and str(info.value).startswith("bytes: ")
        with pytest.raises(snapshot_reader.SnapshotError, match=words):
            snapshot_reader.parse_snapshot(bad, "bytes")
    with pytest.raises(calder.Error, match="custom_force"):
        world = calder.World()
        world.add(calder.CustomForce(force=lambda context, i: (0.0, 0.0)))
        pickle.dumps(world)
