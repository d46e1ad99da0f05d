# SPDX-License-Identifier: MIT
"""Every built-in scene run from Python gives the state hash `calder run` prints."""

import re
import subprocess

import pytest

import calder

SEED = 7
FRAMES = 90  # enough for the scripted mouse of the book's scenes to act (presses from frame 10)


def calder_run_hash(exe: str, scene: str, seed: int, frames: int) -> int:
    out = subprocess.run([exe, "run", scene, "--seed", str(seed), "--frames", str(frames)],
                         check=True, capture_output=True, text=True).stdout
    match = re.search(r"state hash\s*:?\s*([0-9a-f]{16})", out)
    assert match, out
    return int(match.group(1), 16)


@pytest.mark.parametrize("name", [name for name, _ in calder.builtin_scenes()])
def test_state_hash_equals_calder_run(calder_exe, name):
    simulation = calder.Simulation(name, seed=SEED)
    before = calder.state_hash(simulation.world)
    simulation.run(FRAMES)
    assert simulation.frame == FRAMES
    assert calder.state_hash(simulation.world) == calder_run_hash(calder_exe, name, SEED, FRAMES)
    if len(simulation.world) > 0:
        assert calder.state_hash(simulation.world) != before  # the scene moved


def test_scene_file_and_frame_by_frame_agree(calder_exe, tmp_path):
    # A scene written out as a file runs as the built-in one; stepping frame by
    # frame (the scripted mouse included) equals run().
    scene = calder.Scene("example-2.5")
    path = tmp_path / "scene.toml"
    path.write_text(scene.to_toml())
    from_file = calder.Simulation(str(path), seed=3)
    stepped = calder.Simulation("example-2.5", seed=3)
    from_file.run(120)
    for _ in range(120):
        stepped.step()
    assert calder.state_hash(from_file.world) == calder.state_hash(stepped.world)
    assert calder.state_hash(from_file.world) == calder_run_hash(calder_exe, str(path), 3, 120)


def test_a_different_seed_changes_the_hash():
    a = calder.Simulation("example-2.5", seed=1)
    b = calder.Simulation("example-2.5", seed=2)
    assert calder.state_hash(a.world) != calder.state_hash(b.world)
