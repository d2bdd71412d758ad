"""seqmassage.shear and seqmassage.distances."""
import math

import numpy as np

from conftest import seqmassage, tube


def test_shear_of_congruent_scaled_and_degenerate_triangles():
    vertices, triangles = tube()
    assert np.array_equal(seqmassage.shear(vertices, vertices, triangles),
                          np.zeros(len(triangles)))
    moved = vertices @ np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]]).T + 3.0  # rotated, moved
    assert np.allclose(seqmassage.shear(vertices, moved, triangles), 0, atol=1e-12)
    scaled = seqmassage.shear(vertices, 2 * vertices, triangles)
    assert np.allclose(scaled, 2 + 1 / 2 - 2)
    flat = vertices.copy()
    flat[:, 0] = 0  # every triangle seen edge-on collapses or distorts
    d = seqmassage.shear(vertices, flat, triangles)
    assert d.shape == (len(triangles),) and np.isinf(d).any()


def test_shear_equals_the_reports(cli_sequence):
    from conftest import read_obj
    out, report = cli_sequence
    names = sorted(p.name for p in (out / "input").glob("*.obj"))
    template, triangles = read_obj(out / "input" / names[0])
    frame, _ = read_obj(out / "frames" / names[-1])
    d = seqmassage.shear(template, frame, triangles)
    row = next(f for f in report["frames"] if f["file"] == names[-1])
    assert math.isclose(float(d.max()), row["shear_after"]["max"], rel_tol=0, abs_tol=0)


def test_distances_of_a_mesh_to_itself_and_to_a_moved_copy():
    vertices, triangles = tube()
    same = seqmassage.distances(vertices, triangles, vertices, triangles)
    assert same["hausdorff"] == 0
    assert same["to_reference"]["max"] == 0 and same["from_reference"]["max"] == 0
    moved = vertices + [0.0, 0.0, 0.0]
    moved[:, :2] *= 1.1  # radius 0.5 -> 0.55
    d = seqmassage.distances(moved, triangles, vertices, triangles)
    assert 0.04 < d["hausdorff"] <= 0.05 + 1e-12
    assert d["shear"] is not None  # B has A's triangles
    coarse, coarse_triangles = tube(segments=8, rings=4)
    d = seqmassage.distances(coarse, coarse_triangles, vertices, triangles, spacing=0.5,
                             adaptive=True)
    assert d["shear"] is None and d["hausdorff"] > 0
    assert d["to_reference"]["samples"] > 0
