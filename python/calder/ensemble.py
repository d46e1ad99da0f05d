# SPDX-License-Identifier: MIT
"""Ensembles and parameter sweeps: many runs of one scene, on the local
cores or on any Dask cluster, checkpointed, the same bits wherever they run.

    import calder
    ensemble = calder.Ensemble("exercise-2.16", seeds=100,
                               vary={"fields[0].law.G": [0.5, 1, 2]},
                               frames=300, record=["diagnostics", "state_hash"])
    table = ensemble.run()                  # a pandas DataFrame
    table = ensemble.run(client=client)     # on a dask.distributed cluster

Members: every combination of the values in `vary` (a grid, the last name
changing fastest), each with every seed of `seeds`; member i is the
(i // len(seeds))-th combination with the (i % len(seeds))-th seed. A
member's result depends only on the scene, its parameters and its seed,
never on the worker, the order or the number of workers. See
python/README.md ("Ensembles").
"""

from __future__ import annotations

import inspect
import itertools
import os
import pickle
import sys
import uuid
import warnings
from typing import Any, Callable, Dict, Iterable, Iterator, List, Optional, Sequence, Union

from ._calder import ArchiveWriter, Error, Scene, Simulation
from .ensemble_member import (BODY_COLUMNS, DIAGNOSTICS, Member, MemberResult, Plan,
                              pool_initializer, pool_run_batch, run_batch, run_member)
from .scene_edit import SceneEdit, parse_path

__all__ = ["Ensemble", "member_seed"]

_MASK64 = (1 << 64) - 1


def member_seed(ensemble_seed: int, index: int) -> int:
    """The k-th derived seed of an ensemble seed: the top 32 bits of
    SplitMix64's output (Steele, Lea and Flood, OOPSLA 2014) for the state
    ensemble_seed * 2**32 + index. Both are in [0, 2**32)."""
    for name, value in (("ensemble seed", ensemble_seed), ("index", index)):
        if not isinstance(value, int) or not 0 <= value < 1 << 32:
            raise Error(f"member_seed: {name} must be an integer in [0, 2**32) (got {value!r})")
    z = ((ensemble_seed << 32 | index) + 0x9E3779B97F4A7C15) & _MASK64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & _MASK64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & _MASK64
    return (z ^ (z >> 31)) >> 32


def _values(name: str, given: Any) -> list:
    if isinstance(given, (str, bytes, dict)) or not isinstance(given, Iterable):
        return [given]
    values = list(given)
    if not values:
        raise Error(f"Ensemble: vary {name!r} has no values")
    return values


def _pandas():
    try:
        import pandas
    except ImportError:
        raise Error("Ensemble.run needs pandas (Debian: python3-pandas; "
                    "scripts/setup python installs it)") from None
    return pandas


class Ensemble:
    """Many members of one scene: seeds times a grid of parameters.

    scene: a built-in scene's name, a scene file's path, a calder.Scene or a
    calder.SceneEdit.
    seeds: None (the scene's own seed), an int N (N seeds derived from
    `seed` by member_seed(seed, k), k = 0..N-1: the same N for every
    combination, so that combinations are compared on the same initial
    conditions), or a list of seeds used as they are.
    vary: {path: values} (a grid) or a list of {path: value} (one member's
    parameters each). A path is a scene parameter ("world.dt",
    "fields[0].law.G", "bodies[0].count": calder.scene_edit) or the name of a
    parameter of `edit`.
    edit: edit(scene_edit, **its_parameters), changing a copy of the scene
    (a calder.SceneEdit: edit["world.dt"] = 0.5) for its vary names.
    frames: frames per member (default: the scene's frames).
    record: what to record, any of "state_hash", "diagnostics" (the columns
    of calder.ensemble_member.DIAGNOSTICS, each also by name), "bodies" (the
    body columns x, y, vx, vy, mass, radius, each also by name, one row per
    body), and functions of the World (returning a number, column named
    after the function, or a dict of numbers); or {name: function}.
    every: record every this many frames (and frame 0 and the last);
    default: the last frame only.
    checkpoint: a folder (that every worker can see) for the members'
    archives: a member killed goes on from its last snapshot, and an
    ensemble run again skips its finished members.
    checkpoint_every: a snapshot every this many frames (default: a tenth
    of the frames), besides the recorded frames.
    threads: World.threads of each member (1: the cores go to members).

    Every name and value is checked here, before anything runs: an unknown
    parameter (with calder's "did you mean"), a value out of range, a record
    that can't be measured, a checkpoint folder that can't be written.
    """

    def __init__(self, scene: Union[str, Scene, SceneEdit], *, seeds: Any = None, seed: int = 0,
                 vary: Union[None, Dict[str, Any], Sequence[Dict[str, Any]]] = None,
                 edit: Optional[Callable[..., Any]] = None, frames: Optional[int] = None,
                 record: Any = ("state_hash", "diagnostics"), every: Optional[int] = None,
                 checkpoint: Optional[Union[str, os.PathLike]] = None,
                 checkpoint_every: Optional[int] = None, threads: int = 1):
        base = SceneEdit(scene if not isinstance(scene, (str, os.PathLike)) else str(scene))
        self.scene_name = base.name
        self.seeds = self._seeds(seeds, seed)
        combinations = self._combinations(vary)
        self.parameter_names = list(dict.fromkeys(k for c in combinations for k in c))
        if "seed" in self.parameter_names and seeds is not None:
            raise Error("Ensemble: give seeds or vary 'seed', not both")
        edit_names = self._edit_names(edit)
        for name in self.parameter_names:
            if name not in edit_names:
                self._check_path(base, name, edit_names)
        for name, value in (("frames", frames), ("every", every),
                            ("checkpoint_every", checkpoint_every)):
            if value is not None and (not isinstance(value, int) or isinstance(value, bool)
                                      or value < (0 if name == "frames" else 1)):
                raise Error(f"Ensemble: {name} must be an integer >= "
                            f"{0 if name == 'frames' else 1} (got {value!r})")
        if not isinstance(threads, int) or threads < 0:
            raise Error(f"Ensemble: threads must be an integer >= 0 (got {threads!r})")
        self.members: List[Member] = []
        for combination in combinations:
            # Read once per combination; the seeds only change the scene's seed.
            built = self._combination_scene(base, combination, edit, edit_names)
            for member_seed_value in self.seeds:
                if member_seed_value is not None:
                    built.seed = member_seed_value
                member_frames = built.frames if frames is None else frames
                self.members.append(Member(len(self.members), built.seed, combination,
                                           built.to_toml(), member_frames))
        self.frames = frames
        folder = self._checkpoint_folder(checkpoint)
        self.plan = self._plan(record, every, folder, checkpoint_every, threads)
        self._check_records()
        self.status: List[MemberResult] = []

    # --- members -------------------------------------------------------------

    @staticmethod
    def _seeds(seeds: Any, seed: int) -> List[Optional[int]]:
        if seeds is None:
            return [None]
        if isinstance(seeds, bool):
            raise Error(f"Ensemble: seeds must be a count or a list of seeds (got {seeds!r})")
        if isinstance(seeds, int):
            if seeds < 1:
                raise Error(f"Ensemble: seeds must be >= 1 (got {seeds})")
            return [member_seed(seed, k) for k in range(seeds)]
        values = list(seeds)
        for value in values:
            if not isinstance(value, int) or isinstance(value, bool) or not 0 <= value < 1 << 32:
                raise Error(f"Ensemble: a seed must be an integer in [0, 2**32) (got {value!r})")
        if not values:
            raise Error("Ensemble: seeds is empty")
        return values

    @staticmethod
    def _combinations(vary: Any) -> List[Dict[str, Any]]:
        if vary is None:
            return [{}]
        if isinstance(vary, dict):
            names = list(vary)
            grids = [_values(name, vary[name]) for name in names]
            return [dict(zip(names, values)) for values in itertools.product(*grids)]
        if isinstance(vary, (list, tuple)) and all(isinstance(c, dict) for c in vary):
            if not vary:
                raise Error("Ensemble: vary is an empty list")
            return [dict(c) for c in vary]
        raise Error("Ensemble: vary must be {path: values} or a list of {path: value} "
                    f"(got {type(vary).__name__})")

    @staticmethod
    def _edit_names(edit: Optional[Callable]) -> List[str]:
        if edit is None:
            return []
        if not callable(edit):
            raise Error("Ensemble: edit must be a function edit(scene, **parameters)")
        parameters = list(inspect.signature(edit).parameters.values())[1:]
        return [p.name for p in parameters
                if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]

    @staticmethod
    def _check_path(base: SceneEdit, name: str, edit_names: List[str]) -> None:
        try:
            parse_path(name)
        except Error as error:
            hint = f" nor a parameter of edit ({', '.join(edit_names)})" if edit_names else ""
            raise Error(f"Ensemble: vary {name!r} is not a scene parameter{hint}: {error}") from None

    def _combination_scene(self, base: SceneEdit, combination: Dict[str, Any],
                           edit: Optional[Callable], edit_names: List[str]) -> Scene:
        index = len(self.members)
        scene = SceneEdit(base)
        for name, value in combination.items():
            if name not in edit_names:
                try:
                    scene[name] = value
                except Error as error:
                    raise Error(f"Ensemble: vary {name!r} = {value!r}: {error}") from None
        if edit is not None:
            own = {k: v for k, v in combination.items() if k in edit_names}
            try:
                edit(scene, **own)
            except Error as error:
                raise Error(f"Ensemble: edit{own or ''} of member {index}: {error}") from None
        described = ", ".join(f"{k}={v!r}" for k, v in combination.items())
        return scene.scene(f"Ensemble: member {index} ({described or 'the scene'})"
                           if combination else "Ensemble")

    # --- records and checkpoints --------------------------------------------------

    def _plan(self, record: Any, every: Optional[int], folder: Optional[str],
              checkpoint_every: Optional[int], threads: int) -> Plan:
        scalars, functions, bodies = [], [], []
        items: List[Any] = list(record.items()) if isinstance(record, dict) else (
            [record] if isinstance(record, str) or callable(record) else list(record))
        for item in items:
            if isinstance(item, tuple) and len(item) == 2 and callable(item[1]):
                functions.append((str(item[0]), item[1]))
            elif callable(item):
                functions.append((getattr(item, "__name__", "record"), item))
            elif item == "diagnostics":
                scalars += [d for d in DIAGNOSTICS if d not in scalars]
            elif item == "state_hash" or item in DIAGNOSTICS:
                scalars += [item] if item not in scalars else []
            elif item == "bodies":
                bodies += [c for c in BODY_COLUMNS if c not in bodies]
            elif item in BODY_COLUMNS:
                bodies += [item] if item not in bodies else []
            else:
                import difflib
                known = ["state_hash", "diagnostics", "bodies", *DIAGNOSTICS, *BODY_COLUMNS]
                near = difflib.get_close_matches(str(item), known, n=1)
                hint = f" (did you mean '{near[0]}'?)" if near else ""
                raise Error(f"Ensemble: unknown record {item!r}{hint}; records are "
                            f"{', '.join(known)} or functions of the World")
        if not (scalars or functions or bodies):
            raise Error("Ensemble: record names nothing to record")
        if checkpoint_every is None and folder is not None:
            longest = max(m.frames for m in self.members)
            checkpoint_every = max(1, longest // 10)
        return Plan(tuple(scalars), tuple(functions), tuple(bodies), every, folder,
                    checkpoint_every, threads)

    def _check_records(self) -> None:
        """Measures member 0's first frame, so that a record that can't be
        measured (a potential of a custom law, a function that raises) is an
        error now, not in every member."""
        from .ensemble_member import _Records
        simulation = Simulation(Scene.parse(self.members[0].scene_toml, "<scene>"))
        try:
            _Records(self.plan).add(0, simulation.world)
        except Exception as error:  # noqa: BLE001 - reported as the bad record it is
            raise Error(f"Ensemble: recording member 0's first frame failed: {error}") from None

    @staticmethod
    def _checkpoint_folder(checkpoint: Any) -> Optional[str]:
        if checkpoint is None:
            return None
        folder = os.path.abspath(os.fspath(checkpoint))
        try:
            os.makedirs(folder, exist_ok=True)
        except OSError as error:
            raise Error(f"Ensemble: checkpoint folder {folder}: can't create it: "
                        f"{error.strerror}") from None
        # Written as members write: an archive, then removed.
        probe = os.path.join(folder, f".probe-{os.getpid()}-{uuid.uuid4().hex[:8]}.archive")
        try:
            ArchiveWriter(probe).close()
        except Error as error:
            raise Error(f"Ensemble: checkpoint folder {folder} is not writable: {error}") from None
        os.remove(probe)
        return folder

    # --- running --------------------------------------------------------------

    def __len__(self) -> int:
        return len(self.members)

    def results(self, client: Any = None, workers: Optional[int] = None,
                batch_size: Optional[int] = None, progress: Optional[bool] = None
                ) -> Iterator[MemberResult]:
        """Runs the members, yielding each member's MemberResult as it
        finishes (in any order). client: a dask.distributed Client (else the
        local cores); workers: processes of the local pool (default: the
        cores; 1 runs the members here, one after another)."""
        bar = _progress_bar(len(self.members), progress)
        self.status = []
        try:
            if client is not None:
                stream = _dask_results(client, self.plan, self.members, batch_size)
            else:
                count = workers if workers is not None else (os.cpu_count() or 1)
                if not isinstance(count, int) or count < 1:
                    raise Error(f"Ensemble.run: workers must be >= 1 (got {workers!r})")
                stream = (_serial_results(self.plan, self.members) if count == 1 else
                          _pool_results(self.plan, self.members, count, batch_size))
            for result in stream:
                self.status.append(result)
                if bar is not None:
                    bar.update(1)
                if result.status == "failed":
                    member = self.members[result.index]
                    warnings.warn(f"calder.Ensemble: member {result.index} "
                                  f"({_described(member)}) failed: {result.error}",
                                  RuntimeWarning, stacklevel=3)
                yield result
        finally:
            if bar is not None:
                bar.close()
        self.status.sort(key=lambda r: r.index)

    def run(self, client: Any = None, workers: Optional[int] = None,
            batch_size: Optional[int] = None, progress: Optional[bool] = None,
            as_xarray: bool = False, errors: str = "warn"):
        """Runs every member; returns a pandas DataFrame with a row per
        member and recorded frame (and body, when bodies are recorded):
        member, seed, the vary names, frame, [body], the records; sorted by
        member, frame and body. as_xarray=True gives an xarray Dataset
        (dimensions member, frame[, body]). A failed member is reported (a
        RuntimeWarning with its parameters and error; Ensemble.table() lists
        it) and leaves no rows; errors="raise" raises calder.Error at the
        end if any failed."""
        if errors not in ("warn", "raise"):
            raise Error(f"Ensemble.run: errors must be 'warn' or 'raise' (got {errors!r})")
        pandas = _pandas()
        if as_xarray:
            _xarray()
        done = [r for r in self.results(client, workers, batch_size, progress)
                if r.status != "failed"]
        failed = [r for r in self.status if r.status == "failed"]
        if failed and errors == "raise":
            raise Error(f"Ensemble: {len(failed)} of {len(self.members)} members failed; first: "
                        f"member {failed[0].index} ({_described(self.members[failed[0].index])})"
                        f": {failed[0].error}")
        table = self._table(pandas, sorted(done, key=lambda r: r.index))
        return self._to_xarray(table) if as_xarray else table

    def table(self):
        """The members and how they went (after run): member, seed, the vary
        names, status, resumed_from, error, seconds, worker."""
        pandas = _pandas()
        rows = []
        for result in self.status:
            member = self.members[result.index]
            rows.append({"member": member.index, "seed": member.seed, **member.parameters,
                         "status": result.status, "resumed_from": result.resumed_from,
                         "error": result.error, "seconds": result.seconds,
                         "worker": result.worker})
        return pandas.DataFrame(rows)

    def _table(self, pandas, results: List[MemberResult]):
        """One DataFrame of the members' columns (in member order; within a
        member its rows are already by frame and body)."""
        import numpy as np
        counts = [len(r.data["frame"]) for r in results]
        members = [self.members[r.index] for r in results]
        columns: Dict[str, Any] = {
            "member": np.repeat(np.array([m.index for m in members], np.int64), counts),
            "seed": np.repeat(np.array([m.seed for m in members], np.int64), counts)}
        for name in self.parameter_names:
            if name == "seed":
                continue  # the seed column holds it
            values = [m.parameters.get(name) for m in members]
            repeated = np.empty(len(values), dtype=object)
            repeated[:] = values
            columns[name] = pandas.Series(np.repeat(repeated, counts).tolist())
        names = list(results[0].data) if results else ["frame"]
        for name in names:
            parts = [r.data[name] for r in results]
            columns[name] = np.concatenate(parts) if parts else np.zeros(0, np.int64)
        return pandas.DataFrame(columns)

    def _to_xarray(self, table):
        _xarray()  # its message, if missing
        per_member = ["seed", *(n for n in self.parameter_names if n != "seed")]
        keys = ["member", "frame"] + (["body"] if self.plan.bodies else [])
        members = table.drop_duplicates("member").set_index("member")[per_member]
        scalars = [c for c in table.columns if c not in keys + per_member]
        dataset = table.set_index(keys)[scalars].to_xarray()
        if self.plan.bodies:
            per_frame = [c for c in scalars if c not in self.plan.bodies]
            for name in per_frame:
                dataset[name] = dataset[name].isel(body=0, drop=True)
        return dataset.assign_coords({n: ("member", members[n].to_numpy()) for n in per_member})


def _described(member: Member) -> str:
    parts = [f"{k}={v!r}" for k, v in member.parameters.items()]
    return ", ".join(parts + [f"seed={member.seed}"])


def _xarray():
    try:
        import xarray
    except ImportError:
        raise Error("Ensemble.run(as_xarray=True) needs xarray (Debian: python3-xarray)") from None
    return xarray


def _progress_bar(total: int, wanted: Optional[bool]):
    if wanted is False:
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        if wanted:
            raise Error("Ensemble.run(progress=True) needs tqdm (Debian: python3-tqdm)") from None
        return None
    if wanted is None and not sys.stderr.isatty():
        return None
    return tqdm(total=total, unit="member", desc="calder ensemble")


def _batches(members: Sequence[Member], slots: int, batch_size: Optional[int]
             ) -> List[List[Member]]:
    """Members in batches: by default about four per worker slot, so that a
    task's cost to the scheduler (a few ms on Dask) is spread over many
    members while the slots stay evenly busy to the end."""
    if batch_size is None:
        batch_size = max(1, -(-len(members) // (4 * max(1, slots))))
    if not isinstance(batch_size, int) or batch_size < 1:
        raise Error(f"Ensemble.run: batch_size must be >= 1 (got {batch_size!r})")
    return [list(members[i:i + batch_size]) for i in range(0, len(members), batch_size)]


def _serial_results(plan: Plan, members: Sequence[Member]) -> Iterator[MemberResult]:
    for member in members:
        yield run_member(plan, member)


def _serialized(plan: Plan) -> bytes:
    # cloudpickle (which Dask brings) also sends lambdas and functions of
    # __main__; plain pickle takes module-level functions.
    try:
        import cloudpickle
        return cloudpickle.dumps(plan)
    except ImportError:
        try:
            return pickle.dumps(plan)
        except (pickle.PicklingError, AttributeError, TypeError) as error:
            raise Error(f"Ensemble: the records can't be sent to worker processes ({error}); "
                        "use module-level functions, or install cloudpickle") from None


def _pool_results(plan: Plan, members: Sequence[Member], workers: int,
                  batch_size: Optional[int]) -> Iterator[MemberResult]:
    """A local process pool (forkserver: no threads of this process are
    inherited). A pool whose worker dies is started again for the members
    not yet back (each goes on from its checkpoint, if any), up to 3 times."""
    import concurrent.futures
    import multiprocessing
    from concurrent.futures.process import BrokenProcessPool

    plan_bytes = _serialized(plan)
    method = "forkserver" if "forkserver" in multiprocessing.get_all_start_methods() else "spawn"
    pending = {m.index: m for m in members}
    for _ in range(4):
        context = multiprocessing.get_context(method)
        with concurrent.futures.ProcessPoolExecutor(
                max_workers=workers, mp_context=context, initializer=pool_initializer,
                initargs=(plan_bytes,)) as pool:
            futures = [pool.submit(pool_run_batch, batch)
                       for batch in _batches(list(pending.values()), workers, batch_size)]
            broken = False
            for future in concurrent.futures.as_completed(futures):
                try:
                    results = future.result()
                except BrokenProcessPool:  # a worker died: its batch, and those queued, again
                    broken = True
                    continue
                for result in results:
                    del pending[result.index]
                    yield result
            if not broken:
                return
    raise Error(f"Ensemble: the local pool's workers died 4 times; {len(pending)} members "
                "did not finish")


def _dask_results(client: Any, plan: Plan, members: Sequence[Member],
                  batch_size: Optional[int]) -> Iterator[MemberResult]:
    """Batches on a dask.distributed client, streamed back as they finish.
    A task whose worker dies is run again by Dask on another worker; its
    members go on from their checkpoints."""
    try:
        from distributed import as_completed
    except ImportError:
        raise Error("Ensemble.run(client=...) needs dask.distributed "
                    "(Debian: python3-distributed)") from None
    slots = sum(client.nthreads().values()) or 1
    token = uuid.uuid4().hex[:8]
    batches = _batches(members, slots, batch_size)
    futures = [client.submit(run_batch, plan, batch, key=f"calder-members-{token}-{i}",
                             pure=False) for i, batch in enumerate(batches)]
    batch_of = {future.key: batch for future, batch in zip(futures, batches)}
    try:
        for future in as_completed(futures):
            try:
                results = future.result()
            except Exception as error:  # noqa: BLE001 - e.g. KilledWorker: its members failed
                message = f"{type(error).__name__}: {error}"
                results = [MemberResult(m.index, "failed", {}, error=message)
                           for m in batch_of[future.key]]
            for result in results:
                yield result
    finally:
        client.cancel(futures)
