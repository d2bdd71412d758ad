"""PC2 and MDD point caches, as Blender's Mesh Cache modifier reads them (numpy only, no bpy).

PC2: little-endian; "POINTCACHE2\\0", int32 version (1), int32 points, float32 start frame,
float32 sample rate, int32 samples, then samples x points x 3 float32.
MDD: big-endian; int32 frames, int32 points, float32 times[frames], then frames x points x 3
float32.
Headers are checked against the file size before anything is read; the positions are memory
mapped, not loaded, and a cache is written frame by frame to a temporary file beside the target,
then renamed over it, so a reader never sees half a file.
"""
import os
import tempfile

import numpy as np

PC2_MAGIC = b"POINTCACHE2\0"
PC2_HEADER = np.dtype([("magic", "S12"), ("version", "<i4"), ("points", "<i4"),
                       ("start", "<f4"), ("rate", "<f4"), ("samples", "<i4")])


class CacheError(ValueError):
    """A cache that cannot be read: the message names the file and what is wrong."""


class PointCache:
    """An open cache: `frames` (a read-only frames x points x 3 float32 array, memory mapped),
    `format` ("PC2" or "MDD") and its timing (`start`, `rate` for PC2; `times` for MDD)."""

    def __init__(self, path, fmt, frames, start=0.0, rate=1.0, times=None):
        self.path, self.format, self.frames = path, fmt, frames
        self.start, self.rate = start, rate
        self.times = times if times is not None else np.arange(len(frames), dtype=np.float32)

    @property
    def num_frames(self):
        return self.frames.shape[0]

    @property
    def num_points(self):
        return self.frames.shape[1]


def format_of(path):
    ext = os.path.splitext(path)[1].lower()
    if ext in (".pc2", ".mdd"):
        return ext[1:].upper()
    raise CacheError(f"{path}: not a point cache (the name must end in .pc2 or .mdd)")


def read(path, fmt=None):
    fmt = fmt or format_of(path)
    try:
        size = os.path.getsize(path)
    except OSError as e:
        raise CacheError(f"{path}: cannot open the cache: {e.strerror}") from e
    return _read_pc2(path, size) if fmt == "PC2" else _read_mdd(path, size)


def _read_pc2(path, size):
    if size < PC2_HEADER.itemsize:
        raise CacheError(f"{path}: {size} bytes, shorter than a PC2 header (32 bytes)")
    head = np.fromfile(path, dtype=PC2_HEADER, count=1)[0]
    if head["magic"] + b"\0" * (12 - len(head["magic"])) != PC2_MAGIC:
        raise CacheError(f"{path}: not a PC2 file (no POINTCACHE2 header)")
    points, samples = int(head["points"]), int(head["samples"])
    if points < 1 or samples < 1:
        raise CacheError(f"{path}: the header gives {points} points and {samples} samples")
    expected = PC2_HEADER.itemsize + samples * points * 12
    if size != expected:
        raise CacheError(f"{path}: {size} bytes, but the header's {samples} samples of {points} "
                         f"points take {expected}")
    frames = np.memmap(path, dtype="<f4", mode="r", offset=PC2_HEADER.itemsize,
                       shape=(samples, points, 3))
    return PointCache(path, "PC2", frames, float(head["start"]), float(head["rate"]))


def _read_mdd(path, size):
    if size < 8:
        raise CacheError(f"{path}: {size} bytes, shorter than an MDD header (8 bytes)")
    frames_tot, points = (int(x) for x in np.fromfile(path, dtype=">i4", count=2))
    if points < 1 or frames_tot < 1:
        raise CacheError(f"{path}: the header gives {frames_tot} frames and {points} points")
    expected = 8 + frames_tot * 4 + frames_tot * points * 12
    if size != expected:
        raise CacheError(f"{path}: {size} bytes, but the header's {frames_tot} frames of "
                         f"{points} points take {expected}")
    times = np.fromfile(path, dtype=">f4", count=frames_tot, offset=8).astype(np.float32)
    frames = np.memmap(path, dtype=">f4", mode="r", offset=8 + 4 * frames_tot,
                       shape=(frames_tot, points, 3))
    return PointCache(path, "MDD", frames, times=times)


def write(path, fmt, frames, start=0.0, rate=1.0, times=None):
    """Writes `frames` (an iterable of points x 3 arrays, `len()` known) as a PC2 or MDD file at
    `path`, atomically."""
    count = len(frames)
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp",
                               dir=folder)
    try:
        with os.fdopen(fd, "wb") as f:
            points = None
            for k, frame in enumerate(frames):
                frame = np.asarray(frame)
                if points is None:
                    points = frame.shape[0]
                    _write_header(f, fmt, count, points, start, rate, times)
                if frame.shape != (points, 3) or not np.isfinite(frame).all():
                    raise CacheError(f"{path}: frame {k} is not {points} x 3 finite positions")
                f.write(frame.astype("<f4" if fmt == "PC2" else ">f4").tobytes())
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def _write_header(f, fmt, count, points, start, rate, times):
    if fmt == "PC2":
        head = np.zeros(1, dtype=PC2_HEADER)
        head[0] = (PC2_MAGIC, 1, points, start, rate, count)
        f.write(head.tobytes())
    elif fmt == "MDD":
        f.write(np.array([count, points], dtype=">i4").tobytes())
        t = np.arange(count, dtype=np.float32) if times is None else np.asarray(times)
        if t.shape != (count,):
            raise CacheError(f"MDD: {t.shape[0]} frame times for {count} frames")
        f.write(t.astype(">f4").tobytes())
    else:
        raise CacheError(f"unknown point cache format {fmt!r} (PC2 or MDD)")
