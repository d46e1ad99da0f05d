# SPDX-License-Identifier: MIT
"""World(device="gpu"): the rain's steps on calder::gpu (a Vulkan device; in CI,
lavapipe), close to the CPU's; calder.devices() lists what Vulkan sees."""

import numpy as np
import pytest

import calder


def rain(device, arithmetic=calder.Arithmetic.float32, n=2000):
    world = calder.World(boundary=calder.Boundary.bounce(0.9, True), arithmetic=arithmetic,
                         device=device)
    rng = np.random.default_rng(1)
    mass = rng.uniform(0.5, 3.0, n)
    world.add_bodies(rng.uniform(0, 640, n), rng.uniform(0, 240, n), mass=mass, radius=2 * mass)
    world.add(calder.Gravity(g=(0, 0.1), scale_by_mass=True))
    world.add(calder.Drag(c=0.01))
    return world


def test_the_rain_on_the_gpu_stays_close_to_the_cpu():
    if not calder.gpu_built():  # CALDER_WITH_GPU=OFF: asking for the GPU is an error
        with pytest.raises(calder.Error, match="without calder::gpu"):
            rain("gpu")
        return
    if not calder.devices():
        pytest.fail("no Vulkan device: World(device='gpu') can't run (is calder::gpu built?)")
    cpu, gpu = rain("cpu"), rain("gpu")
    cpu.step(40)
    gpu.step(40)
    # float32 on both, differing in rounding only (tests/test_gpu.cpp: < 1e-3 px).
    assert np.max(np.abs(np.asarray(gpu.y) - np.asarray(cpu.y))) < 1e-2
    # ... and not the CPU's bits: the steps ran on the device.
    assert not np.array_equal(np.asarray(gpu.y), np.asarray(cpu.y))


def test_a_bad_device_or_the_book_arithmetic_is_an_error():
    with pytest.raises(calder.Error, match="device must be"):
        calder.World(device="tpu")
    with pytest.raises(calder.Error, match="device 'gpu:999'|no Vulkan device"):
        calder.World(device="gpu:999", arithmetic=calder.Arithmetic.float32)
    if calder.gpu_built():
        with pytest.raises(calder.Error, match="book"):
            calder.World(device="gpu")
