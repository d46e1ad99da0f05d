# SPDX-License-Identifier: MIT
"""One member of an ensemble, run where it is sent (this process, a pool
worker, a Dask worker), and its checkpoint.

A member is a scene file's text (its parameters and seed already in it) and
a number of frames; what it records depends on nothing else, so it gives the
same bits on any worker. With a checkpoint folder, the member appends a
snapshot (docs/SNAPSHOTS.md) to an archive of its own at frame 0, at every
frame it records, every `checkpoint_every` frames and at its last frame.
Each attempt writes a new archive, ``member-000007.0.archive``,
``member-000007.1.archive``, ...: an attempt that was killed leaves its
snapshots readable (up to the last complete one), and the next attempt goes
on from the latest snapshot before which every recorded frame has its
snapshot. The records of those earlier frames are measured again from their
snapshots, which hold every bit of the state: the same numbers as measured
live.
"""

from __future__ import annotations

import dataclasses
import glob
import os
import re
import socket
import time
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from ._calder import (Archive, ArchiveWriter, Error, Scene, Simulation, angular_momentum,
                      center_of_mass, kinetic_energy, linear_momentum, potential_energy,
                      state_hash, total_energy)

# What "diagnostics" records: each a column of one number per recorded frame.
DIAGNOSTICS = ("kinetic_energy", "potential_energy", "total_energy", "momentum_x", "momentum_y",
               "angular_momentum", "center_of_mass_x", "center_of_mass_y")
# Body columns, by their name in the result and the World's view.
BODY_COLUMNS = {"x": "x", "y": "y", "vx": "vx", "vy": "vy", "mass": "masses", "radius": "radii"}


def _diagnostic(name: str, world) -> float:
    if name == "kinetic_energy":
        return kinetic_energy(world)
    if name == "potential_energy":
        return potential_energy(world)
    if name == "total_energy":
        return total_energy(world)
    if name.startswith("momentum_"):
        p = linear_momentum(world)
        return p.x if name.endswith("x") else p.y
    if name == "angular_momentum":
        return angular_momentum(world)
    c = center_of_mass(world)
    return c.x if name.endswith("x") else c.y


@dataclasses.dataclass(frozen=True)
class Plan:
    """What every member of one ensemble shares (sent with each batch)."""
    scalars: Tuple[str, ...]                    # state_hash and diagnostics, in order
    functions: Tuple[Tuple[str, Callable], ...]  # (name, f(world)) user records
    bodies: Tuple[str, ...]                     # body columns recorded, per body
    every: Optional[int]                        # record every this many frames (None: last only)
    checkpoint: Optional[str] = None            # folder of the members' archives
    checkpoint_every: Optional[int] = None
    threads: int = 1                            # each member's World.threads


@dataclasses.dataclass(frozen=True)
class Member:
    index: int
    seed: int
    parameters: Dict[str, Any]
    scene_toml: str
    frames: int


@dataclasses.dataclass
class MemberResult:
    """What a member sent back: its records (columns of equal length:
    frame, body if bodies are recorded, then the recorded columns), or the
    error that stopped it. status: "ran", "resumed" (from the snapshot of
    frame resumed_from), "finished before" (read from its checkpoint) or
    "failed"."""
    index: int
    status: str
    data: Dict[str, np.ndarray]
    resumed_from: int = 0
    error: str = ""
    seconds: float = 0.0
    worker: str = ""


def record_frames(frames: int, every: Optional[int]) -> List[int]:
    if every is None:
        return [frames]
    return sorted(set(range(0, frames + 1, every)) | {frames})


def snapshot_frames(frames: int, plan: Plan) -> List[int]:
    frames_set = set(record_frames(frames, plan.every)) | {0, frames}
    if plan.checkpoint_every:
        frames_set |= set(range(0, frames + 1, plan.checkpoint_every))
    return sorted(frames_set)


class _Records:
    def __init__(self, plan: Plan):
        self.plan = plan
        self.rows: List[Tuple[int, Dict[str, Any], Optional[Dict[str, np.ndarray]]]] = []

    def add(self, frame: int, world) -> None:
        values: Dict[str, Any] = {}
        for name in self.plan.scalars:
            values[name] = state_hash(world) if name == "state_hash" else _diagnostic(name, world)
        for name, function in self.plan.functions:
            result = function(world)
            if isinstance(result, dict):
                for key, value in result.items():
                    values[str(key)] = _number(value, name)
            else:
                values[name] = _number(result, name)
        bodies = None
        if self.plan.bodies:
            bodies = {c: np.array(getattr(world, BODY_COLUMNS[c]), copy=True)
                      for c in self.plan.bodies}
        self.rows.append((frame, values, bodies))

    def columns(self) -> Dict[str, np.ndarray]:
        self.rows.sort(key=lambda row: row[0])
        if not self.rows:
            return {"frame": np.zeros(0, np.int64)}
        names = list(self.rows[0][1])
        counts = [len(next(iter(b.values()))) if b else 1 for _, _, b in self.rows]
        data: Dict[str, np.ndarray] = {
            "frame": np.repeat(np.array([r[0] for r in self.rows], np.int64), counts)}
        if self.plan.bodies:
            data["body"] = np.concatenate([np.arange(n, dtype=np.int64) for n in counts])
        for name in names:
            values = [r[1].get(name, np.nan) for r in self.rows]
            dtype = np.uint64 if name == "state_hash" else None
            data[name] = np.repeat(np.array(values, dtype=dtype), counts)
        for column in self.plan.bodies:
            data[column] = np.concatenate([r[2][column] for r in self.rows])
        return data


def _number(value: Any, name: str) -> Any:
    if isinstance(value, (bool, int, float, np.integer, np.floating)):
        return value
    raise Error(f"record {name!r} must return a number or a dict of numbers "
                f"(got {type(value).__name__})")


_ARCHIVE_HEADER_BYTES = 16  # docs/SNAPSHOTS.md, "Archives"


def archive_path(folder: str, index: int, attempt: int) -> str:
    return os.path.join(folder, f"member-{index:06d}.{attempt}.archive")


def _attempts(folder: str, index: int) -> List[Tuple[int, str]]:
    found = []
    for path in glob.glob(os.path.join(glob.escape(folder), f"member-{index:06d}.*.archive")):
        match = re.search(r"\.(\d+)\.archive$", path)
        if match:
            found.append((int(match.group(1)), path))
    return sorted(found)


def _resume(plan: Plan, member: Member, scene: Scene, records: _Records
            ) -> Tuple[Optional[Simulation], int, bool, int]:
    """The member's checkpoint: (the simulation to go on from or None, its
    frame, whether the member had finished, the next attempt's number)."""
    attempts = _attempts(plan.checkpoint, member.index)
    snapshots: Dict[int, Tuple[Archive, int]] = {}
    for _, path in attempts:
        if os.path.getsize(path) < _ARCHIVE_HEADER_BYTES:
            continue  # an attempt killed before its archive's header was written
        archive = Archive(path)
        for i, frame in enumerate(archive.frames):
            snapshots.setdefault(frame, (archive, i))
    next_attempt = attempts[-1][0] + 1 if attempts else 0
    if 0 not in snapshots:
        return None, 0, False, next_attempt
    archive, i = snapshots[0]
    if archive.simulation(i).scene.to_toml() != scene.to_toml():
        raise Error(f"checkpoint {attempts[0][1]} holds another scene than member "
                    f"{member.index} {member.parameters or ''}; give another folder, or empty it")
    wanted = record_frames(member.frames, plan.every)
    usable = 0
    for frame in sorted(f for f in snapshots if f <= member.frames):
        if all(f in snapshots for f in wanted if f <= frame):
            usable = frame
    for frame in wanted:
        if frame <= usable:
            archive, i = snapshots[frame]
            records.add(frame, archive.simulation(i).world)
    if usable == member.frames:
        return None, usable, True, next_attempt
    archive, i = snapshots[usable]
    return archive.simulation(i), usable, False, next_attempt


def run_member(plan: Plan, member: Member) -> MemberResult:
    """Runs one member here; a calder.Error (its own bad parameter, a step
    that fails, a record function that raises) comes back as a failed
    result, not an exception."""
    start = time.perf_counter()
    worker = f"{socket.gethostname()}:{os.getpid()}"
    records = _Records(plan)
    status, resumed_from = "ran", 0
    try:
        scene = Scene.parse(member.scene_toml, "<scene>")
        simulation, writer = None, None
        if plan.checkpoint:
            simulation, resumed_from, finished, attempt = _resume(plan, member, scene, records)
            if finished:
                return MemberResult(member.index, "finished before", records.columns(),
                                    resumed_from, "", time.perf_counter() - start, worker)
            if resumed_from > 0:
                status = "resumed"
            else:  # nothing past the start: begin afresh
                simulation = None
            writer = ArchiveWriter(archive_path(plan.checkpoint, member.index, attempt))
        wanted = set(record_frames(member.frames, plan.every))
        saved = set(snapshot_frames(member.frames, plan)) if writer is not None else set()
        if simulation is None:
            simulation = Simulation(scene)
            records.rows.clear()
            simulation.world.threads = plan.threads
            if 0 in wanted:
                records.add(0, simulation.world)
            if writer is not None:
                writer.append(simulation)
        simulation.world.threads = plan.threads
        for stop in sorted(f for f in wanted | saved if f > simulation.frame):
            simulation.run(stop - simulation.frame)
            if stop in wanted:
                records.add(stop, simulation.world)
            if stop in saved:
                writer.append(simulation)
        if writer is not None:
            writer.close()
        return MemberResult(member.index, status, records.columns(), resumed_from, "",
                            time.perf_counter() - start, worker)
    except Exception as error:  # noqa: BLE001 - any failure is this member's, reported with it
        message = str(error) if isinstance(error, Error) else f"{type(error).__name__}: {error}"
        return MemberResult(member.index, "failed", {}, resumed_from, message,
                            time.perf_counter() - start, worker)


def run_batch(plan: Plan, members: Sequence[Member]) -> List[MemberResult]:
    """Runs members one after another (a Dask task, a pool task)."""
    return [run_member(plan, member) for member in members]


# A pool worker's plan, sent once when the worker starts (pool_initializer).
_POOL_PLAN: Optional[Plan] = None


def pool_initializer(plan_bytes: bytes) -> None:
    import pickle
    global _POOL_PLAN
    _POOL_PLAN = pickle.loads(plan_bytes)


def pool_run_batch(members: Sequence[Member]) -> List[MemberResult]:
    assert _POOL_PLAN is not None
    return run_batch(_POOL_PLAN, members)
