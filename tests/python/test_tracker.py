"""seqmassage.Tracker on a generated untracked sequence: a bumpy tube moving and turning, every
frame triangulated anew at random (and written non-indexed, as split along seams), the truth of
a template vertex being the surface point of its parameters."""
import numpy as np
import pytest

from conftest import seqmassage


def surface(u, v, time):
    """The tube at parameters (u along it, v around it) and frame `time`."""
    r = 1.0 + 0.2 * np.cos(2 * v) + 0.15 * np.sin(1.5 * u + v) + 0.1 * np.sin(0.9 * u)
    p = np.stack([u, r * np.cos(v), r * np.sin(v)], axis=-1)
    a = 0.04 * time
    turn = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    return p @ turn.T + 0.3 * time * np.array([0.8, 0.6, 0.0])


def triangulate(time, seed, cell=0.27):
    """A random triangulation of [0, 8] x [0, 2pi) (periodic in v): rows and columns at a random
    offset, interior vertices jittered, random diagonals."""
    rng = np.random.default_rng(seed)
    nu, nv = int(round(8 / cell)), int(round(2 * np.pi / cell))
    du, dv = 8 / nu, 2 * np.pi / nv
    rows = np.concatenate([[0.0], (np.arange(nu - 1) + rng.uniform(0.2, 0.8)) * du, [8.0]])
    cols = (np.arange(nv) + rng.uniform()) * dv
    u, v = np.meshgrid(rows, cols, indexing="ij")
    u[1:-1] += rng.uniform(-0.2, 0.2, u[1:-1].shape) * du
    v += rng.uniform(-0.2, 0.2, v.shape) * dv
    u, v = u.ravel(), v.ravel()
    triangles = []
    C = len(cols)
    for i in range(len(rows) - 1):
        for j in range(C):
            a, b, c, d = i * C + j, (i + 1) * C + j, (i + 1) * C + (j + 1) % C, i * C + (j + 1) % C
            triangles += [[a, b, c], [a, c, d]] if rng.uniform() < 0.5 else [[a, b, d], [b, c, d]]
    return u, v, surface(u, v, time), np.array(triangles, dtype=np.int64)


def test_tracker_follows_an_untracked_sequence():
    u, v, vertices, triangles = triangulate(0, 1)
    tracker = seqmassage.Tracker(vertices, triangles, refine_iterations=10)
    h = tracker.mean_edge
    frames = []
    for k in range(1, 7):
        _, _, fv, ft = triangulate(k, 100 + k, cell=0.25)
        frames.append((fv[ft.ravel()], np.arange(3 * len(ft)).reshape(-1, 3)))  # non-indexed
    results = tracker.track(frames)
    assert len(results) == 6
    for k, r in enumerate(results, start=1):
        assert r["vertices"].shape == vertices.shape
        error = np.linalg.norm(r["vertices"] - surface(u, v, k), axis=1).mean() / h
        assert error < 0.3, (k, error)
        assert r["status"] == "ok"
        assert r["fit"]["to_raw_mean"] < 0.06
        assert r["fit"]["from_raw_p99"] < 0.5
        # The tube moves about 1.1 edges per frame: tracking beats standing still.
        still = np.linalg.norm(surface(u, v, k - 1) - surface(u, v, k), axis=1).mean() / h
        assert error < 0.5 * still


def test_tracker_refuses_bad_options_and_frames():
    u, v, vertices, triangles = triangulate(0, 1)
    with pytest.raises(seqmassage.ConfigError, match=r"^track\.node_spacing: "):
        seqmassage.Tracker(vertices, triangles, node_spacing=-1)
    # Checked by the engine (the template's size), named with the config's path.
    n = len(vertices)
    with pytest.raises(seqmassage.ConfigError,
                       match=r"^massage\.pinned: vertex %d is out of range" % n):
        seqmassage.Tracker(vertices, triangles, refine_iterations=2, massage={"pinned": [n]})
    tracker = seqmassage.Tracker(vertices, triangles)
    with pytest.raises(seqmassage.InputError, match=r"frames\[0\]"):
        tracker.track([(vertices, triangles + 10 ** 6)])


def write_obj(path, vertices, triangles):
    lines = ["v %r %r %r" % tuple(p) for p in vertices.tolist()]
    lines += ["f %d %d %d" % tuple(t + 1) for t in triangles]
    path.write_text("\n".join(lines) + "\n")


def read_obj_positions(path):
    return np.array([[float(x) for x in line.split()[1:4]]
                     for line in path.read_text().splitlines() if line.startswith("v ")])


def test_track_job_writes_what_the_tracker_returns(tmp_path):
    """run_job({"job": "track"}) on a folder of OBJ frames writes, frame by frame, the positions
    seqmassage.Tracker returns for the same frames, and reports their status."""
    raw = tmp_path / "raw"
    raw.mkdir()
    frames = []
    for k in range(4):
        _, _, fv, ft = triangulate(k, 200 + k, cell=0.3)
        write_obj(raw / ("frame_%d.obj" % k), fv, ft)
        frames.append((fv, ft))
    report = seqmassage.run_job({"job": "track", "input": {"frames": str(raw)},
                                 "track": {"refine_iterations": 5},
                                 "output": {"dir": str(tmp_path / "out"), "html": False}})
    assert report["job"] == "track"
    assert report["summary"]["frames"] == 4 and report["summary"]["lost"] == 0
    tracker = seqmassage.Tracker(frames[0][0], frames[0][1], refine_iterations=5)
    for k, r in enumerate(tracker.track(frames)):
        written = read_obj_positions(tmp_path / "out" / "frames" / ("frame_%d.obj" % k))
        np.testing.assert_array_equal(written, r["vertices"])
        assert report["frames"][k]["status"] == r["status"]
