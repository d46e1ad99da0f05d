# SPDX-License-Identifier: MIT
"""The golden hashes from Python: every built-in scene, seeds 0, 1 and 42, its
default frames, gives the state hash recorded in tests/golden/state_hashes.txt
(written by the calder command, scripts/golden-hashes), as the C++ builds and
WebAssembly do."""

import pathlib

import pytest

import calder

GOLDEN = pathlib.Path(__file__).resolve().parents[2] / "tests" / "golden" / "state_hashes.txt"


def golden_lines():
    lines = []
    for line in GOLDEN.read_text().splitlines():
        if line and not line.startswith("#"):
            name, seed, frames, recorded = line.split()
            lines.append((name, int(seed), int(frames), recorded))
    return lines


def test_the_file_covers_every_scene_and_three_seeds():
    expected = [(name, seed) for name, _ in calder.builtin_scenes() for seed in (0, 1, 42)]
    assert [(name, seed) for name, seed, _, _ in golden_lines()] == expected


@pytest.mark.parametrize("name,seed,frames,recorded", golden_lines(),
                         ids=[f"{name}-seed{seed}" for name, seed, _, _ in golden_lines()])
def test_state_hash_is_the_golden_one(name, seed, frames, recorded):
    simulation = calder.Simulation(name, seed=seed)
    simulation.run(frames)
    assert simulation.frame == frames
    assert f"{calder.state_hash(simulation.world):016x}" == recorded
