"""seqmassage.shear and seqmassage.distances."""
import csv

import numpy as np
import pytest

from conftest import read_obj, seqmassage, tube


def test_shear_of_congruent_scaled_and_degenerate_triangles():
    vertices, triangles = tube()
    assert np.array_equal(seqmassage.shear(vertices, vertices, triangles),
                          np.zeros(len(triangles)))
    moved = vertices @ np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]]).T + 3.0  # rotated, moved
    assert np.allclose(seqmassage.shear(vertices, moved, triangles), 0, atol=1e-12)
    scaled = seqmassage.shear(vertices, 2 * vertices, triangles)
    assert np.allclose(scaled, 2 + 1 / 2 - 2)
    collapsed = vertices.copy()
    collapsed[triangles[0]] = collapsed[triangles[0][0]]  # triangle 0 is a point
    d = seqmassage.shear(vertices, collapsed, triangles)
    assert d.shape == (len(triangles),) and np.isinf(d[0])


def test_shear_equals_the_summarys(cli_sequence):
    out, _ = cli_sequence
    names = sorted(p.name for p in (out / "input").glob("*.obj"))
    template, triangles = read_obj(out / "input" / names[0])
    with open(out / "summary.csv", newline="") as f:
        rows = {row["file"]: row for row in csv.DictReader(f)}
    for name in names[1:]:
        for folder, when in (("input", "before"), ("frames", "after")):
            d = seqmassage.shear(template, read_obj(out / folder / name)[0], triangles)
            assert float(d.max()) == float(rows[name][f"shear_max_{when}"]), (name, when)
            assert float(d.mean()) == pytest.approx(float(rows[name][f"shear_mean_{when}"]),
                                                    rel=1e-12)


def test_distances_of_a_mesh_to_itself_and_to_a_moved_copy():
    vertices, triangles = tube()
    same = seqmassage.distances(vertices, triangles, vertices, triangles)
    assert same["hausdorff"] == 0
    assert same["dist_mesh_to_ref"]["max"] == 0 and same["dist_ref_to_mesh"]["max"] == 0
    moved = vertices + [0.0, 0.0, 0.0]
    moved[:, :2] *= 1.1  # radius 0.5 -> 0.55
    d = seqmassage.distances(moved, triangles, vertices, triangles)
    assert 0.04 < d["hausdorff"] <= 0.05 + 1e-12
    assert d["shear"] is not None  # B has A's triangles
    coarse, coarse_triangles = tube(segments=8, rings=4)
    d = seqmassage.distances(coarse, coarse_triangles, vertices, triangles, spacing=0.5,
                             adaptive=True)
    assert d["shear"] is None and d["hausdorff"] > 0
    degenerate = vertices.copy()
    degenerate[triangles[0]] = degenerate[triangles[0][0]]  # one triangle collapsed to a point
    d = seqmassage.distances(degenerate, triangles, vertices, triangles)
    assert d["shear"]["max"] == float("inf") and d["shear"]["degenerate"] >= 1
    assert d["dist_mesh_to_ref"]["samples"] > 0
