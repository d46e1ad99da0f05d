# SPDX-License-Identifier: MIT
"""ias15 from Python: the Pythagorean problem's outcome and energy, the
energy watch on a fixed step that is too long."""
import math

import calder


def test_pythagorean_scene_keeps_energy_and_counts_its_steps():
    sim = calder.Simulation("pythagorean")
    world = sim.world
    assert world.integrator == calder.Integrator.ias15
    watch = calder.EnergyWatch(world, 1e-9)
    assert watch.active
    for _ in range(700):
        sim.step()
        watch.observe(world, sim.frame)
    assert world.time == 70.0
    assert watch.worst_error < 1e-9
    assert watch.first_frame_over == -1
    stats = world.adaptive_stats
    assert 3000 < stats["steps"] < 12000
    assert abs(stats["closest_approach"] / 40 - 4.1e-4) < 0.3e-4


def test_a_long_fixed_step_passes_the_threshold():
    world = calder.World(dt=0.01, integrator=calder.Integrator.rk4, width=10, height=10)
    world.add(calder.MutualAttraction(law=calder.AttractionLaw.newtonian()))
    for (x, y), m in (((1, 3), 3), ((-2, -1), 4), ((1, -1), 5)):
        world.add_body(position=(x, y), mass=m)
    watch = calder.EnergyWatch(world)
    passed = None
    for frame in range(1, 400):
        world.step()
        if watch.observe(world, frame):
            passed = frame
    assert passed is not None and passed == watch.first_frame_over


def test_tolerance_is_a_world_setting():
    world = calder.World(integrator=calder.Integrator.ias15, tolerance=1e-11)
    assert world.tolerance == 1e-11


def test_a_runs_error_is_measured_from_its_first_frame():
    sim = calder.Simulation("figure-eight")
    first = calder.total_energy(sim.world)
    sim.run(50)
    assert calder.start_energy(sim) == first
    now = calder.total_energy(sim.world)
    assert calder.relative_energy_error(first, now) == abs(now - first) / abs(first)
    assert calder.relative_energy_error(first, now) < 1e-12
    assert math.isnan(calder.start_energy(calder.Simulation("example-2.1")))
