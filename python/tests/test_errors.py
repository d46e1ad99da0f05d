# SPDX-License-Identifier: MIT
"""Bad arguments from Python raise calder.Error (a ValueError) or TypeError
with the words of the C++ API: the cases of tests/test_world.cpp,
test_fields.cpp, test_vec2.cpp, test_random.cpp, test_forces.cpp,
test_scene_file.cpp and test_render.cpp."""

import math

import numpy as np
import pytest

import calder

NAN, INF = math.nan, math.inf


def one_body_world():
    world = calder.World()
    world.add_body()
    return world


W = one_body_world

CASES = [
    # WorldValidation.BodyDefinitions
    (lambda: W().add_body(mass=0.0), ["World::add_body", "mass"]),
    (lambda: W().add_body(mass=-1.0), ["World::add_body", "mass"]),
    (lambda: W().add_body(mass=NAN), ["World::add_body", "mass"]),
    (lambda: W().add_body(mass=INF), ["World::add_body", "mass"]),
    (lambda: W().add_body(position=(NAN, 0)), ["World::add_body", "position"]),
    (lambda: W().add_body(velocity=(0, NAN)), ["World::add_body", "velocity"]),
    (lambda: W().add_body(radius=-1.0), ["World::add_body", "radius"]),
    (lambda: W().add_body(radius=NAN), ["World::add_body", "radius"]),
    (lambda: W().add_body(friction=-0.1), ["World::add_body", "friction"]),
    (lambda: W().add_body(drag_area=NAN), ["World::add_body", "drag_area"]),
    (lambda: W().add_mover(mass=0.0), ["mass"]),
    # SettersAndForcesKeepTheStateFinite
    (lambda: W().mover(0).apply_force((NAN, 0)), ["World::apply_force", "force"]),
    (lambda: W().mover(0).apply_force((0, INF)), ["World::apply_force", "force"]),
    (lambda: setattr(W().mover(0), "position", (NAN, 0)), ["World::set_position", "position"]),
    (lambda: setattr(W().mover(0), "velocity", (0, INF)), ["World::set_velocity", "velocity"]),
    (lambda: W().set_mass(0, 0.0), ["World::set_mass", "mass"]),
    (lambda: W().set_mass(0, NAN), ["World::set_mass", "mass"]),
    (lambda: W().set_radius(0, -2.0), ["World::set_radius", "radius"]),
    (lambda: W().set_radius(0, NAN), ["World::set_radius", "radius"]),
    (lambda: W().set_friction(0, -1.0), ["World::set_friction", "friction"]),
    (lambda: W().set_drag_area(0, -1.0), ["World::set_drag_area", "drag_area"]),
    # WorldDefinitionAndDt
    (lambda: calder.World(width=0.0), ["World", "width"]),
    (lambda: calder.World(width=-640.0), ["World", "width"]),
    (lambda: calder.World(height=0.0), ["World", "height"]),
    (lambda: calder.World(height=NAN), ["World", "height"]),
    (lambda: calder.World(dt=0.0), ["World", "dt"]),
    (lambda: calder.World(dt=-1.0), ["World", "dt"]),
    (lambda: calder.World(dt=NAN), ["World", "dt"]),
    (lambda: calder.World(boundary=calder.Boundary.bounce(-0.5)), ["World", "restitution"]),
    (lambda: setattr(W(), "dt", 0.0), ["World::set_dt", "dt"]),
    (lambda: setattr(W(), "dt", -0.1), ["World::set_dt", "dt"]),
    (lambda: setattr(W(), "dt", NAN), ["World::set_dt", "dt"]),
    (lambda: setattr(W(), "dt", INF), ["World::set_dt", "dt"]),
    (lambda: setattr(W(), "boundary", calder.Boundary.bounce(-1.0)), ["restitution"]),
    (lambda: setattr(W(), "boundary", calder.Boundary.bounce(NAN)), ["restitution"]),
    # BadBodyIds
    (lambda: W().position(7), ["World::position", "7"]),
    (lambda: W().velocity(7), ["World::velocity"]),
    (lambda: W().acceleration(7), ["World::acceleration"]),
    (lambda: W().mass(7), ["World::mass"]),
    (lambda: W().radius(7), ["World::radius"]),
    (lambda: W().apply_force(7, (1, 0)), ["World::apply_force"]),
    (lambda: W().update(7), ["World::update"]),
    (lambda: W().set_position(7, (0, 0)), ["World::set_position"]),
    (lambda: W().apply_boundary(7), ["World::apply_boundary"]),
    (lambda: W().touching(7, calder.Edge.bottom), ["World::touching"]),
    (lambda: W().mover(7), ["World::mover"]),
    (lambda: W().mover(-1), ["World::mover"]),
    # NegativeStepCount
    (lambda: W().step(-1), ["World::step", "count"]),
    # FieldValidation.RejectsABadParameterOfEachField (at construction, and by add)
    (lambda: calder.Gravity(g=(0, NAN)), ["gravity", "g"]),
    (lambda: calder.Wind(force=(INF, 0)), ["wind", "force"]),
    (lambda: calder.NoiseWind(rate=NAN), ["noise_wind", "rate"]),
    (lambda: calder.Helium(lift=NAN), ["helium", "lift"]),
    (lambda: calder.Fan(reach=0.0), ["fan", "reach"]),
    (lambda: calder.EdgeForce(margin=-1.0), ["edge_force", "margin"]),
    (lambda: calder.Friction(mu=-0.1), ["friction", "mu"]),
    (lambda: calder.Liquid(region=calder.Rect(0, 0, -1, 10)), ["liquid", "region.w"]),
    (lambda: calder.Drag(c=-0.01), ["drag", "c"]),
    (lambda: calder.Lift(coefficient=INF), ["lift", "coefficient"]),
    (lambda: calder.Attractor(mass=0.0), ["attractor", "mass"]),
    (lambda: calder.MutualAttraction(law=calder.AttractionLaw.book(1.0, 30.0, 25.0)),
     ["mutual_attraction", "min"]),
    (lambda: W().add(calder.CustomForce()), ["World::add", "custom_force", "force"]),
    # Vec2
    (lambda: calder.Vec2(1, 2).div(0.0), ["Vec2::div"]),
    (lambda: calder.Vec2(1, 2) / -0.0, ["division by zero"]),
    # Random, Noise, map_range, constrain
    (lambda: calder.Random().random_seed(NAN), ["random_seed"]),
    (lambda: calder.Random().random_seed(INF), ["must be finite"]),
    (lambda: calder.Random().random_seed(-INF), ["got -inf"]),
    (lambda: calder.Random().random(NAN), ["random"]),
    (lambda: calder.Random().random(INF), ["max"]),
    (lambda: calder.Random().random(NAN, 1.0), ["min"]),
    (lambda: calder.Random().random(0.0, INF), ["max"]),
    (lambda: calder.Random().random_gaussian(NAN, 1.0), ["mean"]),
    (lambda: calder.Random().random_gaussian(0.0, INF), ["sd"]),
    (lambda: calder.Noise().noise(NAN), ["noise"]),
    (lambda: calder.Noise().noise(0.0, INF), ["must be finite"]),
    (lambda: calder.Noise().noise_detail(0, 0.5), ["noise_detail"]),
    (lambda: calder.Noise().noise_detail(-3, 0.5), ["octaves"]),
    (lambda: calder.Noise().noise_detail(65, 0.5), ["octaves", "64"]),
    (lambda: calder.Noise().noise_detail(4, NAN), ["falloff"]),
    (lambda: calder.map_range(1.0, 2.0, 2.0, 0.0, 1.0), ["map_range"]),
    (lambda: calder.map_range(NAN, 0.0, 1.0, 0.0, 1.0), ["value"]),
    (lambda: calder.constrain(0.5, NAN, 1.0), ["low"]),
    # AttractionLaw
    (lambda: calder.AttractionLaw(min=30.0, max=25.0), ["min", "max"]),
    (lambda: calder.AttractionLaw(G=NAN), ["G"]),
    (lambda: calder.AttractionLaw(softening=-1.0), ["softening"]),
    # Scenes and rendering
    (lambda: calder.Scene.parse("frames = -1", "t.toml"), ["t.toml", "frames"]),
    (lambda: calder.Scene("no-such-scene"), ["no-such-scene"]),
    (lambda: calder.Canvas(0, 240), ["Canvas"]),
    (lambda: calder.Canvas(640, -1), ["Canvas"]),
    (lambda: calder.Canvas(640, 240, 0.0), ["Canvas"]),
    (lambda: calder.Canvas(640, 240, NAN), ["Canvas"]),
    (lambda: calder.GifWriter("/nonexistent-dir/x.gif", 100, 100, 30), ["x.gif"]),
    (lambda: calder.Simulation("example-2.5").run(-1), ["Simulation.run", "frames"]),
    # Bulk calls: all or nothing, the failing body named
    (lambda: W().add_bodies([0, 1, 2], [0, 0, 0], mass=[1, 0, 1]),
     ["World::add_bodies: body 1", "World::add_body", "mass"]),
    (lambda: W().set_positions([NAN], [0]), ["World::set_position", "position"]),
]


@pytest.mark.parametrize("call,words", CASES, ids=[", ".join(w) for _, w in CASES])
def test_bad_argument_raises_calders_message(call, words):
    with pytest.raises(calder.Error) as caught:
        call()
    assert isinstance(caught.value, ValueError)
    message = str(caught.value)
    assert "\n" not in message
    for word in words:
        assert word in message


def test_scene_file_errors_are_a_subclass_naming_file_and_line(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('name = "x"\nframes = "many"\n')
    with pytest.raises(calder.SceneFileError) as caught:
        calder.Simulation(str(path))
    assert isinstance(caught.value, calder.Error)
    assert "bad.toml" in str(caught.value) and "frames" in str(caught.value)


def test_wrong_types_raise_type_error():
    world = one_body_world()
    with pytest.raises(TypeError):
        world.add_body(mass="heavy")
    with pytest.raises(TypeError):
        world.add(42)
    with pytest.raises(TypeError):
        calder.Gravity(gee=(0, 1))
    with pytest.raises(TypeError):
        calder.Vec2((1, 2, 3))
    with pytest.raises(TypeError):
        world.add_bodies(np.zeros((2, 2)), np.zeros(2))
    with pytest.raises(ValueError):
        world.add_bodies(np.zeros(3), np.zeros(2))


def test_a_failed_call_changes_nothing():
    world = one_body_world()
    with pytest.raises(calder.Error):
        world.add_bodies([0, 1, 2], [0, 0, 0], mass=[1, 1, -1])
    assert len(world) == 1
    with pytest.raises(calder.Error):
        world.set_positions([5.0], [NAN])
    assert world.position(0) == calder.Vec2(0, 0)
    wind = world.add(calder.Wind())
    with pytest.raises(calder.Error, match="wind"):
        wind.force = (NAN, 0)
    assert wind.force == calder.Vec2(0.1, 0)


def test_a_custom_force_returning_nan_or_raising_leaves_the_world_as_it_was():
    world = one_body_world()
    world.set_velocity(0, (1, 0))
    force = world.add(calder.CustomForce(force=lambda context, i: (NAN, 0)))
    with pytest.raises(calder.Error, match="custom_force"):
        world.step()
    assert world.position(0) == calder.Vec2(0, 0) and world.step_count == 0

    def broken(context, index):
        raise RuntimeError("user code failed")

    force.force = broken
    with pytest.raises(RuntimeError, match="user code failed"):
        world.step(5)
    assert world.step_count == 0
    force.force = lambda context, i: "not a vector"
    with pytest.raises(calder.Error, match="must return a Vec2"):
        world.step()


def test_an_unknown_scene_is_the_commands_message(calder_exe, tmp_path, monkeypatch):
    # calder.load_scene's rule and message, the command's: a typo's suggestion,
    # a scene file of the folder among the candidates.
    import subprocess
    monkeypatch.chdir(tmp_path)
    (tmp_path / "three.toml").write_text('name = "three"\n')
    for name in ["example2.7", "three", "nosuch"]:
        with pytest.raises(calder.Error) as raised:
            calder.Scene(name)
        run = subprocess.run([calder_exe, "run", name], capture_output=True, text=True)
        assert run.returncode == 2
        assert str(raised.value) == run.stderr.strip().removeprefix("calder: "), name


def test_displayed_energy_is_bounded_and_says_when_it_estimates():
    def world_of(count, field):
        world = calder.World()
        rng = calder.Random(5)
        for _ in range(count):
            world.add_body(position=(rng.random(640.0), rng.random(360.0)), mass=1.0)
        world.add(field)
        return world

    small = world_of(100, calder.MutualAttraction())
    energy = calder.displayed_energy(small)
    assert energy.exact and energy.kinetic == calder.kinetic_energy(small)
    assert energy.potential == pytest.approx(calder.potential_energy(small), rel=1e-12)
    assert energy.total == energy.kinetic + energy.potential
    # 800 bodies: 319,600 pairs, past the budget of 2^18: a sampled estimate.
    big = world_of(800, calder.MutualAttraction())
    estimate = calder.displayed_energy(big)
    assert not estimate.exact
    assert estimate.potential == pytest.approx(calder.potential_energy(big), rel=0.05)
    assert calder.displayed_energy(big, max_pairs=1 << 20).exact
    # A custom attraction law has no potential: the kinetic energy alone, and why.
    custom = calder.MutualAttraction(law=calder.AttractionLaw(custom=lambda d, m1, m2: 1.0))
    none = calder.displayed_energy(world_of(3, custom))
    assert none.potential is None and none.total == none.kinetic and none.exact
    assert "potential" in none.why_not
