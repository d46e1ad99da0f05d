# SPDX-License-Identifier: MIT
"""numpy views of the body arrays can never read freed memory.

The policy (python/README.md): each access of world.x (y, vx, vy, masses,
radii, frictions, drag_areas) returns a new read-only view; while one is
alive the world refuses to gain bodies. Run under AddressSanitizer by the
sanitizer phase of CI, where a read of freed memory would abort.
"""

import gc
import threading

import numpy as np
import pytest

import calder


def world_of(n):
    world = calder.World()
    world.add_bodies(np.arange(n, dtype=float), np.zeros(n), vx=1.0)
    return world


def test_views_are_zero_copy_live_and_read_only():
    world = world_of(4)
    x = world.x
    assert x.tolist() == [0.0, 1.0, 2.0, 3.0]
    world.step(2)
    assert x.tolist() == [2.0, 3.0, 4.0, 5.0]  # the same memory, the new state
    assert not x.flags.writeable and not x.flags.owndata
    with pytest.raises(ValueError):
        x[0] = 1.0
    with pytest.raises(ValueError):
        x.flags.writeable = True  # numpy refuses: the base is not writable memory
    assert np.shares_memory(x, world.x)


def test_growing_with_a_view_alive_raises_and_changes_nothing():
    world = world_of(3)
    x = world.x
    before = x.copy()
    with pytest.raises(calder.Error, match="numpy view"):
        world.add_body(position=(9, 9))
    with pytest.raises(calder.Error, match="numpy view"):
        world.add_bodies(np.zeros(1000), np.zeros(1000))
    with pytest.raises(calder.Error, match="numpy view"):
        world.add_mover()
    assert len(world) == 3
    assert np.array_equal(x, before)


def test_after_the_views_die_growth_works_and_new_views_read_new_data():
    world = world_of(3)
    x = world.x
    del x
    gc.collect()
    assert world.live_views == 0
    # Enough bodies to move the arrays many times over.
    world.add_bodies(np.full(100_000, 7.0), np.zeros(100_000))
    x = world.x
    assert x.shape == (100_003,) and x[-1] == 7.0 and x[0] == 0.0


def test_derived_arrays_keep_the_view_counted():
    world = world_of(8)
    evens = world.x[::2]  # a view of the view: numpy keeps the base chain alive
    assert world.live_views == 1
    with pytest.raises(calder.Error):
        world.add_body()
    del evens
    gc.collect()
    assert world.live_views == 0
    world.add_body()


def test_a_view_keeps_its_world_alive():
    world = world_of(5)
    y = world.vx
    del world
    gc.collect()
    assert y.tolist() == [1.0] * 5  # the world's memory is still there


def test_a_view_of_a_simulation_world_keeps_the_simulation_alive():
    simulation = calder.Simulation("example-2.5", seed=1)
    y = simulation.world.y
    count = len(y)
    del simulation
    gc.collect()
    assert len(y) == count and np.all(np.isfinite(y))


def test_reset_bodies_with_a_view_alive_keeps_the_memory():
    # Simulation.reset_bodies rebuilds the same number of bodies in place:
    # the view shows the new bodies.
    simulation = calder.Simulation("example-2.5", seed=1)
    y = simulation.world.y
    start = y.copy()
    simulation.run(50)
    assert not np.array_equal(y, start)
    simulation.reset_bodies()
    assert np.array_equal(y, start)


def test_clear_bodies_with_a_view_alive_frees_nothing():
    world = world_of(4)
    x = world.x
    world.clear_bodies()
    assert len(world) == 0 and len(world.x) == 0
    assert x.shape == (4,)  # still readable: clearing keeps the memory


def test_field_handles_after_clear_fields_raise():
    world = world_of(1)
    wind = world.add(calder.Wind())
    world.clear_fields()
    with pytest.raises(calder.Error, match="clear_fields"):
        wind.enabled = False
    with pytest.raises(calder.Error, match="clear_fields"):
        _ = wind.force
    gravity = world.add(calder.Gravity())  # a new field, the old handle still stale
    with pytest.raises(calder.Error):
        _ = wind.enabled
    assert gravity.enabled


def test_a_custom_force_cannot_grow_or_keep_its_context():
    world = world_of(2)
    kept = []

    def grow(context, index):
        kept.append(context)
        world.add_body()
        return (0, 0)

    world.add(calder.CustomForce(force=grow))
    with pytest.raises(calder.Error, match="stepping in another thread"):
        world.step()
    assert len(world) == 2 and world.step_count == 0
    with pytest.raises(calder.Error, match="valid only during"):
        kept[0].position(0)


def test_a_custom_force_cannot_change_fields_while_stepping():
    world = world_of(1)
    wind = world.add(calder.Wind())

    def meddle(context, index):
        wind.enabled = False
        return (0, 0)

    world.add(calder.CustomForce(force=meddle))
    with pytest.raises(calder.Error, match="wind: the world is stepping"):
        world.step()
    assert wind.enabled and world.step_count == 0


def test_step_releases_the_gil():
    world = calder.World()
    world.add(calder.Gravity())
    world.add_bodies(np.zeros(20_000), np.zeros(20_000))
    started = threading.Event()

    def run():
        started.set()
        world.step(3000)

    thread = threading.Thread(target=run)
    thread.start()
    started.wait()
    spins = 0
    while thread.is_alive():
        spins += 1  # runs only if the stepping thread let go of the GIL
    thread.join()
    assert world.step_count == 3000
    assert spins > 1000


def test_a_reset_that_would_move_the_arrays_is_refused_while_a_view_is_alive():
    # After set_bodies with fewer bodies than the scene, a reset rebuilds more
    # bodies than the arrays hold: they would move under the view.
    sim = calder.Simulation("example-2.5")  # nine movers; a press resets them
    sim.set_bodies([1.0, 2.0], [3.0, 4.0])
    x = sim.world.x
    with pytest.raises(calder.Error, match="numpy view"):
        sim.reset_bodies()
    with pytest.raises(calder.Error, match="numpy view"):
        sim.step(mouse_pressed=True)
    with pytest.raises(calder.Error, match="numpy view"):
        sim.run(1)
    assert x.tolist() == [1.0, 2.0] and sim.world.body_count == 2  # nothing changed
    del x
    gc.collect()
    sim.reset_bodies()  # no view: allowed, the nine are back
    assert sim.world.body_count == 9
    y = sim.world.y
    sim.reset_bodies()  # as many as the arrays hold: they stay, allowed
    sim.step(mouse_pressed=True)
    assert y.shape == (9,)
