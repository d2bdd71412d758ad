"""run_job's progress callback and its cancel, Massager.run_many against a loop of run, and the
point caches' reader and writer (headers checked against the formats written out by hand)."""
import os
import signal
import struct

import numpy as np
import pytest

from conftest import SEQUENCE_CONFIG, seqmassage, tube


def drifted(vertices, k):
    """Frame k of a tube whose vertices slide around it and bend: a different start each frame."""
    v = vertices.copy()
    angle = 0.05 * k * v[:, 2]
    x, y = v[:, 0].copy(), v[:, 1].copy()
    v[:, 0] = np.cos(angle) * x - np.sin(angle) * y + 0.02 * k * v[:, 2] ** 2
    v[:, 1] = np.sin(angle) * x + np.cos(angle) * y
    return v


def test_progress_is_called_per_frame_in_order(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    config = dict(SEQUENCE_CONFIG, output=dict(SEQUENCE_CONFIG["output"], dir="out"))
    calls = []
    report = seqmassage.run_job(config, progress=lambda f, s, fig: calls.append((f, s, fig)))
    frames = SEQUENCE_CONFIG["input"]["synthetic"]["frames"]
    # The template frame is one of them; every frame reported once, in order, 1..N done.
    assert [c[0] for c in calls] == list(range(frames))
    assert [c[2]["done"] for c in calls] == list(range(1, frames + 1))
    assert all(c[2]["total"] == frames for c in calls)
    assert all(isinstance(c[1], str) and c[1] == c[2]["status"] for c in calls)
    assert not report["interrupted"]


def test_progress_returning_false_cancels_and_returns_the_report(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    synthetic = dict(SEQUENCE_CONFIG["input"]["synthetic"], frames=12)
    config = dict(SEQUENCE_CONFIG, input={"synthetic": synthetic}, threads=1,
                  output=dict(SEQUENCE_CONFIG["output"], dir="out"))
    calls = []

    def progress(frame, status, figures):
        calls.append(frame)
        return False  # stop after the first

    report = seqmassage.run_job(config, progress=progress)
    assert report["interrupted"]
    assert 1 <= len(calls) < 12


def test_an_exception_in_progress_cancels_and_is_raised(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    config = dict(SEQUENCE_CONFIG, output=dict(SEQUENCE_CONFIG["output"], dir="out"))

    def progress(frame, status, figures):
        raise LookupError("stop here")

    with pytest.raises(LookupError, match="stop here"):
        seqmassage.run_job(config, progress=progress)


def test_run_many_equals_a_loop_of_run_bit_for_bit():
    template, triangles = tube(segments=16, rings=8)
    massager = seqmassage.Massager(template, triangles, iterations=5)
    frames = [drifted(template, k) for k in range(1, 7)]
    batch = massager.run_many(frames)
    assert len(batch) == len(frames)
    for frame, result in zip(frames, batch):
        single = massager.run(frame)
        assert result.ok and single.ok
        assert np.array_equal(result.vertices, single.vertices)
        assert [it["energy"] for it in result.iterations] == \
            [it["energy"] for it in single.iterations]
    # An F x n x 3 array is a batch too.
    stacked = massager.run_many(np.stack(frames))
    assert all(np.array_equal(a.vertices, b.vertices) for a, b in zip(stacked, batch))


def test_run_many_names_a_frame_of_the_wrong_size():
    template, triangles = tube()
    massager = seqmassage.Massager(template, triangles, iterations=2)
    with pytest.raises(seqmassage.InputError, match=r"frames\[1\]"):
        massager.run_many([template, template[:-1]])


@pytest.mark.parametrize("suffix", ["pc2", "mdd"])
def test_point_cache_round_trip_in_float32(tmp_path, suffix):
    template, _ = tube()
    frames = np.stack([drifted(template, k) for k in range(3)])
    path = tmp_path / f"cache.{suffix}"
    seqmassage.write_point_cache(path, frames, start=2.0, sample_rate=0.5,
                                 times=[0.0, 0.5, 1.0] if suffix == "mdd" else None)
    cache = seqmassage.read_point_cache(path)
    assert cache.format == suffix and len(cache) == 3
    assert cache.frames.dtype == np.float32 and cache.frames.shape == frames.shape
    assert np.array_equal(cache.frames, frames.astype(np.float32))
    raw = path.read_bytes()
    n = template.shape[0]
    if suffix == "pc2":  # char[12], int32 version, points, float start, rate, int32 samples
        assert raw[:12] == b"POINTCACHE2\0"
        assert struct.unpack("<iiffi", raw[12:32]) == (1, n, 2.0, 0.5, 3)
        first = np.frombuffer(raw[32:32 + 12 * n], dtype="<f4").reshape(n, 3)
        assert (cache.start, cache.sample_rate) == (2.0, 0.5)
    else:  # big-endian: int32 frames, points, float32 times[frames]
        assert struct.unpack(">ii", raw[:8]) == (3, n)
        assert struct.unpack(">3f", raw[8:20]) == (0.0, 0.5, 1.0)
        first = np.frombuffer(raw[20:20 + 12 * n], dtype=">f4").reshape(n, 3)
        assert cache.times == [0.0, 0.5, 1.0]
    assert np.array_equal(first, frames[0].astype(np.float32))


def test_point_cache_errors_name_the_file(tmp_path):
    template, _ = tube()
    path = tmp_path / "cut.pc2"
    seqmassage.write_point_cache(path, [template, template])
    path.write_bytes(path.read_bytes()[:-5])
    with pytest.raises(seqmassage.InputError, match="cut.pc2"):
        seqmassage.read_point_cache(path)
    with pytest.raises(seqmassage.ConfigError, match=r"\.pc2 or \.mdd"):
        seqmassage.read_point_cache(tmp_path / "cache.bin")
    bad = template.copy()
    bad[3, 1] = np.nan
    target = tmp_path / "nan.mdd"
    with pytest.raises(seqmassage.InputError, match="vertex 3"):
        seqmassage.write_point_cache(target, [template, bad])
    assert not target.exists()  # atomic: nothing written


def test_ctrl_c_stops_run_between_iterations():
    template, triangles = tube(segments=16, rings=8)
    massager = seqmassage.Massager(template, triangles, iterations=10, tolerance=0)
    calls = []

    def interrupt(stats, vertices):  # SIGINT as Ctrl-C sends it, during the first iteration
        calls.append(stats["iteration"])
        os.kill(os.getpid(), signal.SIGINT)

    # Python's own SIGINT handler, whatever this process inherited: a shell starts background
    # jobs with SIGINT ignored, and an ignored signal never reaches the check.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            massager.run(drifted(template, 3), on_iteration=interrupt)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert len(calls) == 1  # stopped after the iteration in which it came, not at the end
    # The Massager is usable afterwards, with the same result as before.
    assert massager.run(drifted(template, 3)).ok
