# SPDX-License-Identifier: MIT
"""The rest of the API from Python, against independent truths: p5's
generators, Newton's laws, conservation, images read back."""

import math
import struct
import zlib

import numpy as np
import pytest

import calder
from calder import Vec2


def test_vec2_operators_and_p5_methods():
    a, b = Vec2(3, 4), Vec2(1, -2)
    assert a + b == Vec2(4, 2) and a - b == Vec2(2, 6) and -a == Vec2(-3, -4)
    assert a * 2 == 2 * a == Vec2(6, 8) and a / 2 == Vec2(1.5, 2)
    assert a.mag() == 5.0 and a.mag_sq() == 25.0 and a.dot(b) == -5.0 and a.cross(b) == -10.0
    c = a.copy()
    assert c.normalize() is c and c == Vec2(3 * (1 / 5), 4 * (1 / 5))  # p5 multiplies by 1/len
    assert a == Vec2(3, 4)  # copy() is a new vector
    d = Vec2(3, 4)
    d += Vec2(1, 1)
    assert d == Vec2(4, 5)
    assert Vec2(30, 40).limit(5) == Vec2(3, 4)
    assert tuple(Vec2(7, 8)) == (7.0, 8.0) and Vec2((1, 2)) == Vec2(1, 2)
    assert repr(Vec2(0.1, 2)) == "Vec2(0.1, 2)"
    assert Vec2.from_angle(0.0, 2.0) == Vec2(2, 0)
    assert Vec2(0, 0).heading() == 0.0 and Vec2(1, 1).dist(Vec2(4, 5)) == 5.0


def test_random_is_p5s_lcg():
    rng = calder.Random(0)
    assert rng.random() == 1013904223 / 2**32  # (1664525 * 0 + 1013904223) mod 2^32
    state = rng.state
    assert rng.random() == ((1664525 * state + 1013904223) % 2**32) / 2**32
    rng.random_seed(1)  # p5.js: randomSeed(1); random() x 3
    assert [rng.random() for _ in range(3)] == [0.23645552527159452, 0.3692706737201661,
                                               0.5042420323006809]
    calder.random_seed(1)
    assert calder.random() == 0.23645552527159452
    assert calder.Random(5).random2d().mag() == pytest.approx(1.0, abs=1e-15)
    noise = calder.Noise(3)
    assert 0.0 <= noise.noise(0.5, 1.5) <= 1.0 and noise(0.5, 1.5) == noise.noise(0.5, 1.5)


def test_force_laws_are_the_books():
    assert calder.gravity(Vec2(0, 0.1), 5.0, True) == Vec2(0, 0.1 * 5.0)
    f = calder.friction(Vec2(3, 4), 0.1)
    assert f.mag() == pytest.approx(0.1) and f.dot(Vec2(3, 4)) < 0
    d = calder.drag(Vec2(0, 2), 0.1)
    assert d == Vec2(0, -(0.1 * 2) * 2)
    # attraction, Newton with G = 1: G m M / d^2 towards the source
    force = calder.attraction(Vec2(0, 0), 10, Vec2(3, 4), 2, calder.AttractionLaw.newtonian())
    assert force.mag() == pytest.approx(10 * 2 / 25) and force.dot(Vec2(3, 4)) < 0


def test_newtons_second_law_one_force_at_a_time():
    world = calder.World()
    mover = world.add_mover(mass=4)
    mover.apply_force((2, 0))
    mover.apply_force((0, 4))
    assert mover.acceleration == Vec2(0.5, 1.0)
    mover.update()
    assert mover.velocity == Vec2(0.5, 1.0) and mover.position == Vec2(0.5, 1.0)
    assert mover.acceleration == Vec2(0, 0)


def test_free_fall_is_analytic():
    # Semi-implicit Euler under constant g from rest: y_n = g dt^2 n (n + 1) / 2, exactly
    # representable for these numbers.
    world = calder.World(height=1e9, dt=0.5)
    world.add_body()
    world.add(calder.Gravity(g=(0, 2.0)))
    world.step(40)
    assert world.y[0] == 2.0 * 0.25 * 40 * 41 / 2
    assert world.time == 20.0 and world.step_count == 40


def test_mutual_attraction_conserves_momentum():
    world = calder.World(width=1e6, height=1e6, integrator=calder.Integrator.velocity_verlet)
    rng = np.random.default_rng(1)
    n = 20
    world.add_bodies(rng.uniform(0, 500, n), rng.uniform(0, 500, n), vx=rng.normal(size=n),
                     vy=rng.normal(size=n), mass=rng.uniform(1, 5, n))
    world.add(calder.MutualAttraction(law=calder.AttractionLaw.newtonian(1.0, 5.0)))
    p0, e0 = calder.linear_momentum(world), calder.total_energy(world)
    world.step(200)
    p1 = calder.linear_momentum(world)
    assert (p1 - p0).mag() < 1e-12 * max(1.0, p0.mag())
    assert calder.total_energy(world) == pytest.approx(e0, rel=1e-3)
    # the views agree with the diagnostics
    assert calder.kinetic_energy(world) == pytest.approx(
        0.5 * np.sum(world.masses * (world.vx**2 + world.vy**2)), rel=1e-12)


def test_bulk_add_and_set():
    world = calder.World()
    n = 100_000
    ids = world.add_bodies(np.linspace(0, 640, n), np.full(n, 10.0), vy=1.0, mass=2.0,
                           friction=np.where(np.arange(n) % 2 == 0, 0.3, np.nan))
    assert ids == range(0, n) and len(world) == n
    assert world.mass(5) == 2.0 and world.velocity(5) == Vec2(0, 1)
    assert world.friction(0) == 0.3 and world.friction(1) is None
    world.set_velocities(np.zeros(n), np.full(n, -1.0))
    world.step(3)
    assert np.all(world.y == 7.0)


def test_fields_are_live_handles():
    world = calder.World(height=1e9)
    world.add_body()
    gravity = world.add(calder.Gravity(g=(0, 1)))
    assert gravity.attached and not calder.Gravity().attached
    world.step()
    gravity.enabled = False
    world.step()
    assert world.velocity(0) == Vec2(0, 1)
    world.fields[0].enabled = True  # the same field through the list
    world.step()
    assert world.velocity(0) == Vec2(0, 2)
    free = gravity.copy()
    free.g = (0, 5)
    assert gravity.g == Vec2(0, 1)


def test_custom_force_sees_the_context():
    world = calder.World(height=1e9)
    world.add_bodies([0.0, 10.0], [0.0, 0.0], mass=[1.0, 2.0])
    # a spring pulling each body towards x = 5
    world.add(calder.CustomForce(force=lambda c, i: ((5 - c.position(i).x) * c.mass(i), 0)))
    world.step()
    assert world.velocity(0) == Vec2(5, 0) and world.velocity(1) == Vec2(-5, 0)


def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else (b if pb <= pc else c)


def decode_png(data: bytes) -> np.ndarray:
    """An 8-bit RGBA or RGB PNG's pixels (the PNG specification's filters undone)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, chunks = 8, {}
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunks[kind] = chunks.get(kind, b"") + data[pos + 8:pos + 8 + length]
        pos += 12 + length
    width, height, depth, color = struct.unpack(">IIBB", chunks[b"IHDR"][:10])
    assert depth == 8 and color in (2, 6)
    bpp = 4 if color == 6 else 3
    raw, stride = zlib.decompress(chunks[b"IDAT"]), width * bpp
    rows, previous = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = previous[i]
            c = previous[i - bpp] if i >= bpp else 0
            predictor = [0, a, b, (a + b) // 2, paeth(a, b, c)][kind]
            line[i] = (line[i] + predictor) & 0xFF
        rows.append(bytes(line))
        previous = line
    return np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(height, width, bpp)


def test_frames_as_images_png_and_gif(tmp_path):
    simulation = calder.Simulation("example-2.5", seed=1)
    simulation.run(30)
    image = calder.frame_image(simulation)
    assert image.shape == (240, 640, 4) and image.dtype == np.uint8
    assert (image[..., :3] < 200).any() and (image[..., :3] == 255).any()  # bodies on white
    canvas = calder.Canvas(640, 240)
    canvas.draw(simulation)
    assert np.array_equal(canvas.image(), image)
    pixels = decode_png(canvas.encode_png())
    assert np.array_equal(pixels, image[..., :pixels.shape[2]])  # the PNG holds the same image
    canvas.write_png(str(tmp_path / "frame.png"))
    assert (tmp_path / "frame.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    gif = tmp_path / "run.gif"
    count = calder.render_gif(calder.Simulation("example-2.1"), str(gif), frames=20, every=5)
    assert count == 4 and gif.read_bytes()[:6] == b"GIF89a"


def test_help_reads_well():
    doc = calder.World.__doc__
    assert "numpy" in doc and "calder.Error" in doc
    assert "Adds len(x) bodies" in calder.World.add_bodies.__doc__
    assert issubclass(calder.Error, ValueError)
