# SPDX-License-Identifier: MIT
"""Read calder snapshots and archives with numpy alone (no calder needed).

The format is docs/SNAPSHOTS.md's: little-endian, a 16-byte header, then
sections (tag, CRC-32, length, payload padded to 8 bytes). The body columns
are plain float64 arrays at 8-byte-aligned offsets, so they come back as
numpy views of the file's bytes, without copying:

    from calder.snapshot_reader import read_snapshot, Archive
    snap = read_snapshot("run.snap")
    snap.frame, snap.time, snap.bodies["x"]
    archive = Archive("rain.archive")
    archive.frames                      # the frame of each snapshot
    archive.snapshot(archive.index_of(120)).bodies["vy"]   # reads that one only

Every problem (a file that can't be read, a truncated or corrupted file,
another version) raises SnapshotError, whose one-line message names the file
and the problem. Inside the calder package it is a calder.Error (calder's one
error type); copied where calder isn't built, a ValueError.
"""

from __future__ import annotations

import contextlib
import os
import struct
import zlib
from dataclasses import dataclass, field

import numpy as np

try:  # inside the calder package: calder's one error type
    from ._calder import Error as _Base
except ImportError:  # copied where calder isn't built
    _Base = ValueError

SNAPSHOT_MAGIC = b"CALDSNAP"
ARCHIVE_MAGIC = b"CALDARCH"
ARCHIVE_END = b"CALDAEND"
VERSION = 2  # the newest snapshot version; 1 and 2 are read (2 adds ADPT)
ARCHIVE_VERSION = 1
TAGS = ("SCEN", "SIMU", "WRLD", "RAND", "FLDS", "BODY", "ADPT")
_RECORD = struct.Struct("<4sIqQ")  # an archive record: tag, CRC-32, frame, length
MAX_SNAPSHOT_BYTES = 2 << 30  # the largest snapshot read (calder's max_snapshot_bytes)
MAX_FRAMES = 10_000_000


class SnapshotError(_Base):
    """A file that is not a valid calder snapshot or archive, or can't be read."""


@contextlib.contextmanager
def _reading(source: str):
    """Whatever goes wrong while reading `source` becomes one SnapshotError."""
    try:
        yield
    except SnapshotError:
        raise
    except OSError as e:
        raise SnapshotError(f"{source}: can't read: {e.strerror or e}") from None
    except (struct.error, ValueError, IndexError, OverflowError, UnicodeError, MemoryError) as e:
        raise SnapshotError(f"{source}: corrupted ({type(e).__name__}: {e})") from None


def _padded(n: int) -> int:
    return (n + 7) & ~7


@dataclass
class Snapshot:
    """A snapshot's contents as numpy sees them."""

    sections: dict = field(repr=False)  # tag -> memoryview of its payload
    bodies: dict = field(repr=False)  # column name -> float64 array (x, y, vx, vy, ax, ay, ...)
    frame: int  # frames stepped (0 for a world's snapshot)
    time: float
    steps: int
    scene: str | None  # the scene's name (None for a world's snapshot)


def read_sections(data, source: str = "snapshot") -> dict:
    """The sections of a snapshot's bytes, each checked against its CRC-32."""
    with _reading(source):
        return _read_sections(data, source)


def _read_sections(data, source: str) -> dict:
    view = memoryview(data)
    if view[:8] == ARCHIVE_MAGIC:
        raise SnapshotError(f"{source}: an archive of snapshots, not one snapshot (use Archive)")
    if len(view) < 16 or view[:8] != SNAPSHOT_MAGIC:
        raise SnapshotError(f"{source}: not a calder snapshot (no CALDSNAP at its start)")
    version, count = struct.unpack_from("<II", view, 8)
    if not 1 <= version <= VERSION:
        raise SnapshotError(f"{source}: snapshot format version {version}; "
                            f"this reader reads versions 1 to {VERSION}")
    sections, at = {}, 16
    for s in range(count):
        if len(view) - at < 16:
            raise SnapshotError(f"{source}: truncated: section {s + 1} of {count} is missing")
        tag = bytes(view[at:at + 4]).decode("latin-1")
        crc, length = struct.unpack_from("<IQ", view, at + 4)
        if tag not in TAGS:
            raise SnapshotError(f"{source}: unknown section tag {tag!r} (corrupted?)")
        start = at + 16
        if start + _padded(length) > len(view):
            raise SnapshotError(f"{source}: truncated: section {tag} needs {_padded(length)} bytes")
        payload = view[start:start + length]
        if zlib.crc32(payload) != crc:
            raise SnapshotError(f"{source}: section {tag}: checksum mismatch (corrupted)")
        sections[tag] = payload
        at = start + _padded(length)
    if at != len(view):
        raise SnapshotError(f"{source}: {len(view) - at} bytes after the last section")
    return sections


def _bodies(payload: memoryview, source: str) -> dict:
    n, columns = struct.unpack_from("<QI", payload, 0)
    if 16 + 16 * columns > len(payload) or 8 * n * columns > len(payload):
        raise SnapshotError(f"{source}: section BODY: {n} bodies of {columns} columns don't fit "
                            f"its {len(payload)} bytes")
    names = [bytes(payload[16 + 16 * c:32 + 16 * c]).rstrip(b"\0").decode("ascii")
             for c in range(columns)]
    start = 16 + 16 * columns
    if len(payload) != start + 8 * n * columns:
        raise SnapshotError(f"{source}: section BODY: {n} bodies don't fit its {len(payload)} bytes")
    return {name: np.frombuffer(payload, dtype="<f8", count=n, offset=start + 8 * n * c)
            for c, name in enumerate(names)}


def parse_snapshot(data, source: str = "snapshot") -> Snapshot:
    """A snapshot from its bytes."""
    with _reading(source):
        return _parse_snapshot(data, source)


def _parse_snapshot(data, source: str) -> Snapshot:
    sections = _read_sections(data, source)
    for tag in ("WRLD", "BODY"):
        if tag not in sections:
            raise SnapshotError(f"{source}: the section {tag} is missing")
    world = sections["WRLD"]
    time, steps = struct.unpack_from("<dq", world, len(world) - 16)  # its last 16 bytes
    frame, scene = 0, None
    if "SCEN" in sections:
        (length,) = struct.unpack_from("<I", sections["SCEN"], 0)
        scene = bytes(sections["SCEN"][4:4 + length]).decode("utf-8", "replace")
        (frame,) = struct.unpack_from("<q", sections["SIMU"], 0)
    return Snapshot(sections, _bodies(sections["BODY"], source), frame, time, steps, scene)


def read_snapshot(path) -> Snapshot:
    """A snapshot file."""
    source = os.fspath(path)
    with _reading(source):
        with open(path, "rb") as f:
            size = f.seek(0, os.SEEK_END)
            if size > MAX_SNAPSHOT_BYTES:
                raise SnapshotError(f"{source}: {size} bytes, larger than the {MAX_SNAPSHOT_BYTES} "
                                    "bytes a snapshot may have (corrupted?)")
            f.seek(0)
            return _parse_snapshot(f.read(), source)


def _plausible(tag, frame, length) -> bool:
    return tag == b"SNAP" and 0 <= frame <= MAX_FRAMES and length <= MAX_SNAPSHOT_BYTES


def _crc_at(f, offset, length):
    """The CRC-32 of length bytes at offset, read a MiB at a time (None: the file ends first)."""
    f.seek(offset)
    crc, left = 0, length
    while left > 0:
        part = f.read(min(left, 1 << 20))
        if not part:
            return None
        crc, left = zlib.crc32(part, crc), left - len(part)
    return crc


class Archive:
    """An archive file: its index (or, for a run that was killed, the index
    rebuilt from the records' headers), and each snapshot read on its own."""

    def __init__(self, path):
        self.path = os.fspath(path)
        self._records = []  # (frame, offset, length, crc)
        self.complete = False
        with _reading(self.path):
            self._open()

    def _open(self):
        with open(self.path, "rb") as f:
            header = f.read(16)
            if header[:8] != ARCHIVE_MAGIC or len(header) < 16:
                raise SnapshotError(f"{self.path}: not a calder archive (no CALDARCH at its start)")
            (version,) = struct.unpack_from("<I", header, 8)
            if version != ARCHIVE_VERSION:
                raise SnapshotError(f"{self.path}: archive format version {version}; "
                                    f"this reader reads {ARCHIVE_VERSION}")
            size = f.seek(0, os.SEEK_END)
            self.complete = self._read_index(f, size)
            if not self.complete:
                self._scan(f, size)

    def _header(self, f, offset):
        f.seek(offset)
        raw = f.read(_RECORD.size)
        if len(raw) < _RECORD.size:
            return None
        tag, crc, frame, length = _RECORD.unpack(raw)
        return tag, crc, frame, length

    def _read_index(self, f, size) -> bool:
        if size < 16 + _RECORD.size + 16:
            return False
        f.seek(size - 16)
        (at,), end = struct.unpack("<Q", f.read(8)), f.read(8)
        if end != ARCHIVE_END or not 16 <= at <= size - 16 - _RECORD.size:
            return False
        tag, crc, _, length = self._header(f, at)
        if tag != b"INDX" or _padded(length) != size - 16 - at - _RECORD.size:
            return False
        if length > 8 + 16 * (at // _RECORD.size):  # more entries than records fit
            return False
        payload = f.read(length)
        if zlib.crc32(payload) != crc:
            return False
        (n,) = struct.unpack_from("<Q", payload, 0)
        if 8 + 16 * n > len(payload):
            return False
        entries = np.frombuffer(payload, dtype="<i8", count=2 * n, offset=8).reshape(n, 2)
        records = []
        for frame, offset in entries.tolist():
            header = self._header(f, offset)
            if (header is None or not _plausible(header[0], header[2], header[3])
                    or header[2] != frame or offset + _RECORD.size + header[3] > at):
                return False
            records.append((frame, offset, header[3], header[1]))
        self._records = records
        return True

    def _scan(self, f, size):
        at = 16
        while size - at >= _RECORD.size:
            tag, crc, frame, length = self._header(f, at)
            if not _plausible(tag, frame, length) or length > size - at - _RECORD.size:
                break
            self._records.append((frame, at, length, crc))
            at += _RECORD.size + _padded(length)
        if self._records:  # a last record cut while it was written
            frame, offset, length, crc = self._records[-1]
            if _crc_at(f, offset + _RECORD.size, length) != crc:
                self._records.pop()

    @property
    def frames(self) -> list:
        return [r[0] for r in self._records]

    def __len__(self) -> int:
        return len(self._records)

    def index_of(self, frame: int) -> int:
        """The position of the snapshot of this frame (SnapshotError if none)."""
        for i in range(len(self._records) - 1, -1, -1):
            if self._records[i][0] == frame:
                return i
        raise SnapshotError(f"{self.path}: no snapshot of frame {frame} (frames: {self.frames})")

    def snapshot_bytes(self, i: int) -> bytes:
        """The i-th snapshot's bytes, read alone and checked."""
        if not -len(self._records) <= i < len(self._records):
            raise SnapshotError(f"{self.path}: no snapshot {i} (the archive has {len(self)})")
        frame, offset, length, crc = self._records[i]
        with _reading(self.path), open(self.path, "rb") as f:
            f.seek(offset + _RECORD.size)
            data = f.read(length)
        if len(data) != length or zlib.crc32(data) != crc:
            raise SnapshotError(f"{self.path}: snapshot of frame {frame}: checksum mismatch (corrupted)")
        return data

    def snapshot(self, i: int) -> Snapshot:
        return parse_snapshot(self.snapshot_bytes(i), f"{self.path} (snapshot {i})")
