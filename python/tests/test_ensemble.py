# SPDX-License-Identifier: MIT
"""calder.Ensemble on the local cores: the same bits as a plain loop over
calder.Simulation, wherever and in whatever order the members run;
checkpoints that a killed ensemble goes on from; bad input refused before
anything runs, a failing member reported while the others go on."""

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
import warnings

import numpy as np
import pandas
import psutil
import pytest

import calder

SCENE = "exercise-2.16"
FRAMES = 20


def plain_loop(scene_toml_of, members, frames, every=None):
    """The serial loop a user would write by hand: one Simulation per
    member, its diagnostics and state hash read with calder's functions."""
    rows = []
    for index, (seed, parameters) in enumerate(members):
        simulation = calder.Simulation(calder.Scene.parse(scene_toml_of(parameters)), seed)
        wanted = [frames] if every is None else sorted(set(range(0, frames + 1, every)) | {frames})
        for frame in wanted:
            simulation.run(frame - simulation.frame)
            world = simulation.world
            p, c = calder.linear_momentum(world), calder.center_of_mass(world)
            rows.append({"member": index, "seed": seed, **parameters, "frame": frame,
                         "state_hash": np.uint64(calder.state_hash(world)),
                         "kinetic_energy": calder.kinetic_energy(world),
                         "potential_energy": calder.potential_energy(world),
                         "total_energy": calder.total_energy(world),
                         "momentum_x": p.x, "momentum_y": p.y,
                         "angular_momentum": calder.angular_momentum(world),
                         "center_of_mass_x": c.x, "center_of_mass_y": c.y})
    return pandas.DataFrame(rows)


def galaxy_with(parameters):
    """The galaxy's scene text with G replaced by hand (not by SceneEdit)."""
    text = calder.Scene(SCENE).to_toml()
    G = parameters.get("fields[0].law.G", 1)
    assert "law = { G = 1," in text
    return text.replace("law = { G = 1,", f"law = {{ G = {G!r},")


def expect_bits(table, expected):
    assert list(table.columns) == list(expected.columns)
    assert len(table) == len(expected)
    for column in expected.columns:
        a, b = table[column].to_numpy(), expected[column].to_numpy()
        if a.dtype.kind == "f":
            assert np.array_equal(a.view(np.uint64), b.astype(np.float64).view(np.uint64)), column
        else:
            assert np.array_equal(a, b), column


@pytest.mark.parametrize("name", [name for name, _ in calder.builtin_scenes()])
def test_a_scene_edit_gives_the_scene_back_and_every_path_reads_and_sets(name):
    original = calder.Scene(name).to_toml()
    edit = calder.SceneEdit(name)
    assert edit.scene().to_toml() == original  # the TOML writer's round trip
    paths = list(edit.paths())
    assert "world.dt" in paths and "seed" in paths
    for path in paths:
        edit[path] = edit[path]
    assert edit.scene().to_toml() == original
    edit["world.dt"] = 0.25
    assert "dt = 0.25" in edit.scene().to_toml()


def test_import_calder_and_an_ensemble_need_neither_pandas_nor_dask():
    script = textwrap.dedent("""
        import sys
        for name in ("pandas", "dask", "distributed", "xarray", "tqdm"):
            sys.modules[name] = None  # import fails, as where they are not installed
        import calder
        ensemble = calder.Ensemble("example-2.7", seeds=2, frames=3)
        result = next(ensemble.results(workers=1))
        assert result.status == "ran" and len(result.data["state_hash"]) == 1
        try:
            ensemble.run()
        except calder.Error as error:
            print(error)
    """)
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True)
    assert run.stdout == ("Ensemble.run needs pandas (Debian: python3-pandas; "
                          "scripts/setup python installs it)\n")


def test_member_seeds_are_splitmix64():
    # SplitMix64's first output from state 0 is 0xE220A8397B1DCDAF (the
    # reference implementation's published value): its top 32 bits.
    assert calder.member_seed(0, 0) == 0xE220A839
    ensemble = calder.Ensemble(SCENE, seeds=5, seed=7, frames=1)
    assert [m.seed for m in ensemble.members] == [calder.member_seed(7, k) for k in range(5)]
    assert len(set(m.seed for m in ensemble.members)) == 5


def test_pool_and_serial_equal_the_plain_loop_bit_for_bit():
    seeds = [calder.member_seed(3, k) for k in range(3)]
    vary = {"fields[0].law.G": [0.5, 2.0]}
    ensemble = calder.Ensemble(SCENE, seeds=3, seed=3, vary=vary, frames=FRAMES, every=10)
    members = [(s, {"fields[0].law.G": G}) for G in vary["fields[0].law.G"] for s in seeds]
    expected = plain_loop(galaxy_with, members, FRAMES, every=10)
    expect_bits(ensemble.run(workers=1), expected)
    expect_bits(ensemble.run(workers=2, batch_size=1), expected)
    assert {r.status for r in ensemble.status} == {"ran"}
    # Other processes did the work (how the pool spread it is its own affair).
    assert all(not r.worker.endswith(f":{os.getpid()}") for r in ensemble.status)


def test_a_list_of_combinations_an_edit_function_and_body_columns():
    def heavier_sun(scene, factor):
        scene["fields[0].central.mass"] = 500 * factor

    ensemble = calder.Ensemble(SCENE, vary=[{"factor": 1, "world.dt": 0.5},
                                            {"factor": 3, "world.dt": 0.5}],
                               edit=heavier_sun, frames=5, record=["x", "y", "state_hash"],
                               every=5)
    table = ensemble.run(workers=1)
    assert list(table.columns[:6]) == ["member", "seed", "factor", "world.dt", "frame", "body"]
    assert len(table) == 2 * 2 * 100  # members, frames 0 and 5, bodies
    for member, factor in ((0, 1), (1, 3)):
        text = calder.Scene(SCENE).to_toml().replace("mass = 500", f"mass = {500 * factor}")
        text = text.replace("dt = 1\n", "dt = 0.5\n")
        simulation = calder.Simulation(calder.Scene.parse(text))
        simulation.run(5)
        rows = table[(table.member == member) & (table.frame == 5)]
        assert np.array_equal(rows.x.to_numpy(), simulation.world.x)
        assert np.array_equal(rows.y.to_numpy(), simulation.world.y)
        assert (rows.state_hash == calder.state_hash(simulation.world)).all()


def test_a_function_of_the_world_is_recorded():
    def spread(world):
        return {"r_max": float(np.hypot(world.x, world.y).max())}

    table = calder.Ensemble(SCENE, seeds=[4], frames=3, record=[spread]).run(workers=1)
    simulation = calder.Simulation(SCENE, 4)
    simulation.run(3)
    assert table.r_max.tolist() == [float(np.hypot(simulation.world.x, simulation.world.y).max())]


def test_xarray_dataset():
    dataset = calder.Ensemble(SCENE, seeds=2, vary={"world.dt": [0.5, 1.0]}, frames=4, every=2,
                              record=["state_hash", "x"]).run(workers=1, as_xarray=True)
    assert dict(dataset.sizes) == {"member": 4, "frame": 3, "body": 100}
    assert dataset["x"].dims == ("member", "frame", "body")
    assert dataset["state_hash"].dims == ("member", "frame")
    assert dataset["world.dt"].values.tolist() == [0.5, 0.5, 1.0, 1.0]


# --- bad input ---------------------------------------------------------------


def test_unknown_names_and_values_out_of_range_are_refused_before_anything_runs(tmp_path):
    cases = [
        ({"fields[0].law.g": [1]}, "unknown key 'g' in 'law' (did you mean 'G'?)"),
        ({"wrld.dt": [1]}, "unknown key 'wrld' in the top level (did you mean 'world'?)"),
        ({"world.dt": [1, -1]}, "'world.dt' must be > 0, got -1"),
        ({"fields[3].law.G": [1]}, "the scene has 1 'fields' (indices 0 to 0)"),
        ({"world.dt.x": [1]}, "'world.dt' is a value, not a table"),
        ({"world..dt": [1]}, "is not a key"),
    ]
    for vary, words in cases:
        with pytest.raises(calder.Error, match=None) as caught:
            calder.Ensemble(SCENE, vary=vary, frames=1, checkpoint=tmp_path / "never")
        assert words in str(caught.value), (vary, str(caught.value))
        assert "\n" not in str(caught.value)
    assert not (tmp_path / "never").exists() or not os.listdir(tmp_path / "never")
    with pytest.raises(calder.Error, match="unknown record 'stat_hash' .did you mean 'state_hash'"):
        calder.Ensemble(SCENE, record=["stat_hash"])
    with pytest.raises(calder.Error, match="give seeds or vary 'seed', not both"):
        calder.Ensemble(SCENE, seeds=2, vary={"seed": [1, 2]})


def test_a_checkpoint_folder_that_cannot_be_written_is_refused(tmp_path):
    blocker = tmp_path / "a-file"
    calder.ArchiveWriter(str(blocker)).close()
    with pytest.raises(calder.Error, match=r"checkpoint folder .*a-file/run: can't create it"):
        calder.Ensemble(SCENE, frames=1, checkpoint=blocker / "run")


def test_a_failing_member_is_reported_and_the_others_go_on():
    ensemble = calder.Ensemble(SCENE, vary={"world.dt": [1.0, 1e200, 0.5]}, frames=3)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        table = ensemble.run(workers=2)
    messages = [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)]
    assert len(messages) == 1
    assert "member 1 (world.dt=1e+200, seed=0) failed: World::step: body" in messages[0]
    assert table.member.tolist() == [0, 2]
    status = ensemble.table()
    assert status.status.tolist() == ["ran", "failed", "ran"]
    assert "non-finite position" in status.error[1]
    with pytest.raises(calder.Error, match="1 of 3 members failed; first: member 1"), \
            warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ensemble.run(workers=1, errors="raise")


# --- checkpoints ---------------------------------------------------------------


def test_a_killed_ensemble_started_again_runs_only_the_unfinished_members(tmp_path):
    folder = tmp_path / "checkpoint"
    spec = dict(seeds=6, frames=300, every=50, checkpoint=str(folder), checkpoint_every=10)
    # The whole ensemble in another process, killed (SIGKILL) in the middle
    # of a member once two members have finished.
    script = textwrap.dedent(f"""
        import calder
        calder.Ensemble({SCENE!r}, **{spec!r}).run(workers=1, progress=False)
    """)
    child = subprocess.Popen([sys.executable, "-c", script])
    finished = []
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and child.poll() is None:
        archives = []
        for path in sorted(folder.glob("member-*.archive")) if folder.is_dir() else []:
            try:
                archives.append((path, calder.Archive(str(path))))
            except calder.Error:  # just created, its header not yet written
                pass
        done = [path for path, archive in archives if archive.complete]
        running = [archive for _, archive in archives if not archive.complete]
        if len(done) >= 2 and running and max(running[0].frames, default=0) >= 20:
            os.kill(child.pid, signal.SIGKILL)
            finished = done
            break
        time.sleep(0.005)
    child.wait()
    assert child.returncode == -signal.SIGKILL, "the ensemble ended before it could be killed"

    ensemble = calder.Ensemble(SCENE, **spec)
    table = ensemble.run(workers=1)
    status = ensemble.table()
    assert (status.status == "finished before").sum() == len(finished)
    assert (status.status == "resumed").sum() == 1
    resumed = status[status.status == "resumed"]
    assert resumed.resumed_from.iloc[0] >= 20
    assert (status.status == "ran").sum() == 6 - len(finished) - 1

    uninterrupted = calder.Ensemble(SCENE, **{**spec, "checkpoint": None}).run(workers=1)
    expect_bits(table, uninterrupted)

    # Once more: every member is read from its checkpoint, nothing runs.
    again = calder.Ensemble(SCENE, **spec)
    expect_bits(again.run(workers=2), uninterrupted)
    assert set(again.table().status) == {"finished before"}


def test_a_pool_worker_killed_mid_member_is_replaced_and_the_member_resumed(tmp_path):
    spec = dict(seeds=4, frames=300, every=100, checkpoint=str(tmp_path), checkpoint_every=10)
    ensemble = calder.Ensemble(SCENE, **spec)
    killed = []

    def kill_the_worker_writing_a_member():
        # The pool's worker that has an archive open, past frame 20 and not
        # near its end, is killed (SIGKILL), by its pid.
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and not killed:
            for path in tmp_path.glob("member-*.archive"):
                try:
                    archive = calder.Archive(str(path))
                except calder.Error:
                    continue
                if archive.complete or not 20 <= max(archive.frames, default=0) <= 200:
                    continue
                for process in psutil.process_iter(["pid"]):
                    try:
                        if any(f.path == str(path) for f in process.open_files()):
                            os.kill(process.pid, signal.SIGKILL)
                            killed.append(process.pid)
                            return
                    except (psutil.NoSuchProcess, psutil.AccessDenied):
                        pass
            time.sleep(0.005)

    killer = threading.Thread(target=kill_the_worker_writing_a_member)
    killer.start()
    table = ensemble.run(workers=2, batch_size=1)
    killer.join()
    assert killed, "no member was caught in the middle"
    status = ensemble.table()
    assert "failed" not in set(status.status) and len(status) == 4
    resumed = status[status.status == "resumed"]
    # The killed member goes on from frame 20 or later; a member the broken
    # pool stopped beside it goes on from its own last checkpoint, whatever it was.
    assert (resumed.resumed_from >= 20).any()
    assert (resumed.resumed_from % 10 == 0).all() and (resumed.resumed_from >= 10).all()
    expect_bits(table, calder.Ensemble(SCENE, **{**spec, "checkpoint": None}).run(workers=1))


def test_a_checkpoint_of_another_ensemble_is_refused(tmp_path):
    calder.Ensemble(SCENE, seeds=[1], frames=2, checkpoint=tmp_path).run(workers=1)
    other = calder.Ensemble(SCENE, seeds=[2], frames=2, checkpoint=tmp_path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert other.run(workers=1).empty
    assert "holds another scene than member 0" in str(caught[0].message)


# --- calder sweep ------------------------------------------------------------------


def test_calder_sweep_gives_the_ensembles_numbers(calder_exe, tmp_path):
    vary = {"fields[0].law.G": [0.5, 1 / 3], "world.integrator": ["semi_implicit_euler", "rk4"]}
    ensemble = calder.Ensemble(SCENE, seeds=[0, 7], vary=vary, frames=12, every=6)
    expected = ensemble.run(workers=1)
    output = tmp_path / "sweep.csv"
    subprocess.run([calder_exe, "sweep", SCENE, "--seeds", "0,7", "--frames", "12", "--every", "6",
                    "--set", "fields[0].law.G=0.5,0.3333333333333333",
                    "--set", "world.integrator=semi_implicit_euler,rk4",
                    "--output", str(output), "--jobs", "2"], check=True, capture_output=True)
    table = pandas.read_csv(output, dtype={"state_hash": np.uint64}, float_precision="round_trip")
    expect_bits(table, expected)
    # Seeds as a parameter: the seed column holds them, on both sides.
    by_seed = calder.Ensemble(SCENE, vary={"seed": [4, 9]}, frames=3).run(workers=1)
    subprocess.run([calder_exe, "sweep", SCENE, "--set", "seed=4,9", "--frames", "3",
                    "--output", str(output)], check=True)
    expect_bits(pandas.read_csv(output, dtype={"state_hash": np.uint64},
                                float_precision="round_trip"), by_seed)
    assert by_seed.seed.tolist() == [4, 9]
    # Body columns, one row per body, as the ensemble's.
    bodies = calder.Ensemble("example-2.7", seeds=[3], frames=5, record=["bodies"]).run(workers=1)
    subprocess.run([calder_exe, "sweep", "example-2.7", "--seeds", "3", "--frames", "5",
                    "--record", "bodies", "--output", str(output)], check=True)
    expect_bits(pandas.read_csv(output, float_precision="round_trip"), bodies)


@pytest.mark.parametrize("arguments, words", [
    (["--set", "fields[0].law.g=1"], "calder: --set fields[0].law.g=1: unknown key 'g' in 'law' "
                                     "(did you mean 'G'?)"),
    (["--set", "world.dt=1,-1"], "calder: --set world.dt=-1: 'world.dt' must be > 0, got -1"),
    (["--set", "fields[4].law.G=1"], "the scene has 1 'fields' (indices 0 to 0)"),
    (["--set", "world.dt"], "--set: expected KEY=V1,V2,..."),
    (["--seeds", "9-2"], "--seeds: the range '9-2' ends before it starts"),
    (["--record", "stat_hash"], "(did you mean 'state_hash'?)"),
    (["--every", "0"], "--every: expected an integer >= 1"),
])
def test_calder_sweep_refuses_bad_input_with_one_line_and_exit_2(calder_exe, tmp_path, arguments,
                                                                  words):
    output = tmp_path / "never.csv"
    run = subprocess.run([calder_exe, "sweep", SCENE, "--frames", "2", *arguments,
                          "--output", str(output)], capture_output=True, text=True)
    assert run.returncode == 2
    assert words in run.stderr and run.stderr.count("\n") == 1, run.stderr
    assert not output.exists()


def test_calder_sweep_parquet_is_refused_and_a_failing_member_reported(calder_exe, tmp_path):
    run = subprocess.run([calder_exe, "sweep", SCENE, "--output", str(tmp_path / "t.parquet")],
                         capture_output=True, text=True)
    assert run.returncode == 2 and "writes no parquet" in run.stderr
    output = tmp_path / "t.csv"
    run = subprocess.run([calder_exe, "sweep", SCENE, "--frames", "3",
                          "--set", "world.dt=1,1e200,0.5", "--output", str(output)],
                         capture_output=True, text=True)
    assert run.returncode == 1
    lines = run.stderr.splitlines()
    assert lines[0].startswith("calder: sweep: member 1 (world.dt=1e200, seed 0) failed: frame 1: "
                               "World::step: body 0 has a non-finite position")
    assert lines[1] == (f"calder: sweep: 1 of 3 members failed (each reported above); the others "
                        f"are in {output}")
    assert pandas.read_csv(output).member.tolist() == [0, 2]
