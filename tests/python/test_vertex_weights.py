"""massage.vertex_weights from Python: a numpy array (or a list) of one weight per vertex, or a
file as in a config; weight 1 everywhere is the default run, weight 0 keeps a vertex where the
input had it; checked as the config's, ValueError with the config's messages."""
import json

import numpy as np
import pytest

from conftest import read_obj, seqmassage, tube


def drifted_tube():
    """A tube and a frame of it stretched along z whose vertices also slide around it."""
    vertices, triangles = tube(segments=16, rings=8)
    angle = 0.15 * np.sin(3 * vertices[:, 2])
    c, s = np.cos(angle), np.sin(angle)
    frame = np.stack([c * vertices[:, 0] - s * vertices[:, 1],
                      s * vertices[:, 0] + c * vertices[:, 1], 1.2 * vertices[:, 2]], axis=1)
    return vertices, triangles, frame


def test_weight_one_everywhere_is_the_default_run():
    vertices, triangles, frame = drifted_tube()
    default = seqmassage.Massager(vertices, triangles).run(frame)
    ones = seqmassage.Massager(vertices, triangles,
                               vertex_weights=np.ones(len(vertices))).run(frame)
    assert default.ok and ones.ok
    assert np.array_equal(ones.vertices, default.vertices)  # bit for bit
    assert [it["energy"] for it in ones.iterations] == [it["energy"] for it in default.iterations]
    assert not np.array_equal(default.vertices, frame)


def test_weight_zero_in_a_region_keeps_it_at_the_input():
    vertices, triangles, frame = drifted_tube()
    weights = np.ones(len(vertices))
    region = vertices[:, 2] < 0.6  # the lower rings
    weights[region] = 0.0
    weights[(vertices[:, 2] > 1.2) & (vertices[:, 2] < 1.6)] = 0.5
    result = seqmassage.Massager(vertices, triangles, vertex_weights=weights).run(frame)
    assert result.ok
    assert np.array_equal(result.vertices[region], frame[region])  # exactly
    default = seqmassage.Massager(vertices, triangles).run(frame).vertices
    assert not np.array_equal(default[region], frame[region])  # the default moves them
    assert not np.array_equal(result.vertices[~region], frame[~region])


def test_lists_dtypes_and_files_give_the_same_run(tmp_path, monkeypatch):
    vertices, triangles, frame = drifted_tube()
    weights = np.where(vertices[:, 2] < 1.0, 0.0, 1.0)
    expected = seqmassage.Massager(vertices, triangles, vertex_weights=weights).run(frame).vertices
    (tmp_path / "weights.txt").write_text("\n".join(repr(float(w)) for w in weights) + "\n")
    monkeypatch.chdir(tmp_path)
    for given in (weights.tolist(), weights.astype(np.float32), weights.astype(np.int64),
                  weights.astype(bool), np.asfortranarray(np.stack([weights, weights]))[0],
                  "weights.txt", tmp_path / "weights.txt"):
        got = seqmassage.Massager(vertices, triangles, vertex_weights=given).run(frame).vertices
        assert np.array_equal(got, expected), type(given)


@pytest.mark.parametrize("weights, message", [
    (np.ones(5), r"^massage\.vertex_weights: expected 144 weights \(one per template vertex\), "
                 r"got 5$"),
    (np.r_[np.ones(16), 1.5, np.ones(127)],
     r"^massage\.vertex_weights\[16\]: expected a number in \[0, 1\], got 1\.5$"),
    (np.r_[-0.25, np.ones(143)], r"^massage\.vertex_weights\[0\]: expected a number in \[0, 1\], "
                                 r"got -0\.25$"),
    (np.r_[np.ones(3), np.nan, np.ones(140)],
     r"^massage\.vertex_weights\[3\]: expected a number in \[0, 1\], got nan$"),
    (np.ones((144, 1)), r"^massage\.vertex_weights: expected a 1-D array \(one number per "
                        r"vertex\), got shape \(144, 1\)$"),
    (np.array(["1"] * 144), r"^massage\.vertex_weights: expected an array of numbers, got dtype"),
    ({"a": 1}, r"^massage\.vertex_weights: expected an array of numbers, got a dict$"),
])
def test_bad_weights_raise_value_error_with_the_configs_style(weights, message):
    vertices, triangles, _ = drifted_tube()
    assert len(vertices) == 144
    with pytest.raises(ValueError, match=message) as raised:
        seqmassage.Massager(vertices, triangles, vertex_weights=weights)
    assert isinstance(raised.value, seqmassage.ConfigError)


def test_a_weights_file_is_checked_as_the_configs(tmp_path):
    vertices, triangles, _ = drifted_tube()
    short = tmp_path / "short.txt"
    short.write_text("1 1 1\n")
    with pytest.raises(ValueError, match=r"^massage\.vertex_weights: .*short\.txt has 3 weights, "
                                         r"but the template, template_vertices, has 144 vertices"):
        seqmassage.Massager(vertices, triangles, vertex_weights=str(short))
    bad = tmp_path / "bad.txt"
    bad.write_text("1\n" * 16 + "1.5\n" + "1\n" * 127)
    with pytest.raises(ValueError, match=r"bad\.txt:17: weight 1\.5 is not a number in \[0, 1\] "
                                         r"\(vertex 16, 0-based\)"):
        seqmassage.Massager(vertices, triangles, vertex_weights=bad)


def test_run_job_keeps_the_file_form(tmp_path, monkeypatch):
    """A job's massage.vertex_weights is a file, as in a config; its frames are the Massager's
    with the same weights as an array."""
    monkeypatch.chdir(tmp_path)
    synthetic = {"frames": 3, "segments": 16, "rings": 12, "drift": 0.6}
    base = {"job": "sequence", "input": {"synthetic": synthetic}, "massage": {"iterations": 5},
            "output": {"dir": "plain", "timings": False}, "threads": 1}
    seqmassage.run_job(base)
    first = sorted((tmp_path / "plain" / "input").glob("*.obj"))[0]
    template, triangles = read_obj(first)
    weights = np.where(template[:, 2] < np.median(template[:, 2]), 0.0, 1.0)
    (tmp_path / "weights.txt").write_text(" ".join(repr(float(w)) for w in weights))
    config = json.loads(json.dumps(base))
    config["massage"]["vertex_weights"] = "weights.txt"
    config["output"]["dir"] = "weighted"
    report = seqmassage.run_job(config)
    assert report["failures"] == []
    massager = seqmassage.Massager(template, triangles, iterations=5, vertex_weights=weights)
    names = sorted(p.name for p in (tmp_path / "weighted" / "frames").glob("*.obj"))
    assert len(names) == 3
    for name in names[1:]:
        frame, _ = read_obj(tmp_path / "weighted" / "input" / name)
        written, _ = read_obj(tmp_path / "weighted" / "frames" / name)
        assert np.array_equal(massager.run(frame).vertices, written), name
        low = weights == 0
        assert np.array_equal(written[low], frame[low])
    # An array is not a config value: the job's reader takes a path.
    config["massage"]["vertex_weights"] = weights
    with pytest.raises(ValueError, match=r"^massage\.vertex_weights: expected a path"):
        seqmassage.run_job(config)
