# SPDX-License-Identifier: MIT
"""What Python writes goes through calder's output policy, and what it reads
is bounded: save() never through a planted link, never over what it must not
replace; ArchiveWriter appends to an archive only; the numpy-only snapshot
reader raises calder's one error type, naming the file, on any bad file."""

import os
import random
import struct
import time
import zlib

import pytest

import calder
from calder import snapshot_reader


def test_save_never_follows_a_link_planted_at_a_temporary_name(tmp_path):
    victim = tmp_path / "victim"
    victim.write_text("victim")
    target = tmp_path / "run.snap"
    os.symlink(victim, str(target) + ".tmp-calder")  # the name save() used to write through
    sim = calder.Simulation("example-2.1")
    sim.run(3)
    sim.save(str(target))
    assert victim.read_text() == "victim"
    assert calder.Simulation.load(str(target)).frame == 3
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.snap", "run.snap.tmp-calder", "victim"]


def test_save_refuses_what_the_policy_protects(tmp_path):
    sim = calder.Simulation("example-2.1")
    protected = tmp_path / "ro.snap"
    protected.write_text("old")
    protected.chmod(0o444)
    with pytest.raises(calder.Error, match="write-protected"):
        sim.save(str(protected))
    assert protected.read_text() == "old"
    os.symlink(tmp_path / "missing", tmp_path / "dangling")
    with pytest.raises(calder.Error, match="symbolic link to a missing file"):
        sim.save(str(tmp_path / "dangling"))
    assert not (tmp_path / "missing").exists()


def test_archive_writer_appends_and_refuses_a_file_that_is_not_an_archive(tmp_path):
    path = tmp_path / "run.archive"
    sim = calder.Simulation("example-2.1")
    with calder.ArchiveWriter(str(path)) as archive:
        archive.append(sim)
    sim.run(5)
    with calder.ArchiveWriter(str(path)) as archive:  # appended after the first
        assert len(archive) == 1
        archive.append(sim)
    assert calder.Archive(str(path)).frames == [0, 5]
    notes = tmp_path / "notes.txt"
    notes.write_text("notes")
    with pytest.raises(calder.Error, match="not a calder archive"):
        calder.ArchiveWriter(str(notes))
    assert notes.read_text() == "notes"


def test_the_reader_raises_calders_error_naming_the_file(tmp_path):
    assert issubclass(snapshot_reader.SnapshotError, calder.Error)
    with pytest.raises(calder.Error, match="missing.snap: can't read"):
        snapshot_reader.read_snapshot(tmp_path / "missing.snap")
    sim = calder.Simulation("example-2.9")
    good = sim.to_bytes()
    # BODY claims four billion columns: refused by its length, not looped over.
    data = bytearray(good)
    (count,) = struct.unpack_from("<I", data, 12)
    at = 16
    for _ in range(count):
        length = struct.unpack_from("<Q", data, at + 8)[0]
        if data[at:at + 4] == b"BODY":
            struct.pack_into("<I", data, at + 16 + 8, 0xFFFFFFFF)
            struct.pack_into("<I", data, at + 4, zlib.crc32(data[at + 16:at + 16 + length]))
        at += 16 + ((length + 7) & ~7)
    path = tmp_path / "columns.snap"
    path.write_bytes(bytes(data))
    start = time.monotonic()
    with pytest.raises(calder.Error, match="columns.snap: section BODY"):
        snapshot_reader.read_snapshot(path)
    assert time.monotonic() - start < 5


def test_any_200_bytes_raise_one_error_type_quickly(tmp_path):
    rng = random.Random(7)
    good = calder.Simulation("example-2.9").to_bytes()
    for k in range(300):
        data = bytearray(good[:200]) if k % 2 else bytearray(rng.randbytes(200))
        for _ in range(rng.randrange(1, 8)):
            data[rng.randrange(len(data))] = rng.randrange(256)
        if k % 3 == 0:
            data[:8] = b"CALDARCH"
        path = tmp_path / f"bad{k}"
        path.write_bytes(bytes(data))
        start = time.monotonic()
        for read in (snapshot_reader.read_snapshot, snapshot_reader.Archive):
            try:
                result = read(path)
                if isinstance(result, snapshot_reader.Archive):
                    for i in range(len(result)):
                        result.snapshot(i)
            except calder.Error as e:
                assert str(path) in str(e)
        assert time.monotonic() - start < 2, f"{path} took too long"
