"""seqmassage.Massager: the same positions as the command line, iteration figures, threads,
array layouts, the remesh use."""
import gc
import threading

import numpy as np
import pytest

from conftest import SEQUENCE_CONFIG, read_obj, seqmassage, tube

ITERATIONS = SEQUENCE_CONFIG["massage"]["iterations"]


def frames(out):
    names = sorted(p.name for p in (out / "input").glob("*.obj"))
    assert len(names) == SEQUENCE_CONFIG["input"]["synthetic"]["frames"]
    return names


def test_positions_equal_the_command_lines(cli_sequence):
    out, report = cli_sequence
    names = frames(out)
    template, triangles = read_obj(out / "input" / names[0])
    massager = seqmassage.Massager(template, triangles, iterations=ITERATIONS)
    for name in names[1:]:
        vertices, _ = read_obj(out / "input" / name)
        result = massager.run(vertices)
        assert result.ok and result.failure is None
        expected, _ = read_obj(out / "frames" / name)
        assert np.array_equal(result.vertices, expected), name  # bit for bit
        assert not np.array_equal(vertices, expected)
    assert report["failures"] == []
    assert report["totals"]["optimized"] == len(names) - 1


def test_iterations_are_the_engines_figures(cli_sequence):
    out, _ = cli_sequence
    names = frames(out)
    template, triangles = read_obj(out / "input" / names[0])
    vertices, _ = read_obj(out / "input" / names[-1])
    massager = seqmassage.Massager(template, triangles, iterations=ITERATIONS, tolerance=0)
    seen = []
    result = massager.run(vertices, on_iteration=lambda stats, v: seen.append((stats, v.copy())))
    assert [it["iteration"] for it in result.iterations] == list(range(1, ITERATIONS + 1))
    assert [s for s, _ in seen] == result.iterations
    assert np.array_equal(seen[-1][1], result.vertices)
    keys = {"iteration", "mu", "energy", "max_dist_m_to_n", "rms_dist_m_to_n", "max_dist_n_to_m",
            "rms_dist_n_to_m", "max_move", "solver_iterations", "solver_residual",
            "exact_queries", "seconds_closest", "seconds_assemble", "seconds_solve"}
    for it in result.iterations:
        assert set(it) == keys
        assert 0 < it["mu"] < 1 and it["energy"] >= 0 and it["solver_iterations"] >= 1
    # The observer does not change the iterates.
    assert np.array_equal(massager.run(vertices).vertices, result.vertices)


def test_an_observer_that_raises_stops_the_run():
    vertices, triangles = tube()
    massager = seqmassage.Massager(vertices, triangles)

    def stop(stats, v):
        raise KeyError("stop here")

    with pytest.raises(KeyError, match="stop here"):
        massager.run(vertices * 1.1, on_iteration=stop)


def test_one_massager_from_several_threads(cli_sequence):
    out, _ = cli_sequence
    names = frames(out)
    template, triangles = read_obj(out / "input" / names[0])
    inputs = [read_obj(out / "input" / n)[0] for n in names[1:]]
    massager = seqmassage.Massager(template, triangles, iterations=ITERATIONS)
    serial = [massager.run(v).vertices for v in inputs]
    results = {}
    errors = []

    def work(worker):
        try:
            for round_ in range(2):
                for k, v in enumerate(inputs):
                    results[(worker, round_, k)] = massager.run(v).vertices
        except Exception as e:  # reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(w,)) for w in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    assert len(results) == 4 * 2 * len(inputs)
    for (worker, round_, k), v in results.items():
        assert np.array_equal(v, serial[k]), (worker, round_, k)


def test_array_layouts_and_dtypes_give_the_same_result():
    vertices, triangles = tube()
    frame = vertices * [1.0, 1.0, 1.2] + [0.01, 0.0, 0.0]
    reference = seqmassage.Massager(vertices, triangles).run(frame).vertices
    variants = [
        (vertices, triangles.astype(np.int32), frame),
        (np.asfortranarray(vertices), np.asfortranarray(triangles), np.asfortranarray(frame)),
        (vertices.tolist(), triangles.tolist(), frame.tolist()),
        (vertices, triangles.astype(np.uint16), np.ascontiguousarray(np.hstack([frame, frame])[:, :3])),
        (vertices, triangles, np.hstack([frame, frame])[:, 3:]),  # a strided view
    ]
    for templ, tris, start in variants:
        assert np.array_equal(seqmassage.Massager(templ, tris).run(start).vertices, reference)


def test_the_result_owns_its_positions():
    vertices, triangles = tube()
    massager = seqmassage.Massager(vertices, triangles)
    start = vertices * 1.05
    result = massager.run(start)
    positions = result.vertices
    assert positions.shape == vertices.shape and positions.dtype == np.float64
    assert positions.flags.c_contiguous
    assert positions is result.vertices  # one array, not a copy per access
    assert not np.shares_memory(positions, start)
    kept = positions.copy()
    # The array outlives the result and the Massager, and does not follow the input.
    del result, massager
    gc.collect()
    start[:] = 0.0
    assert np.array_equal(positions, kept)


def test_remesh_use_against_another_mesh():
    fine, fine_triangles = tube(segments=32, rings=16)
    coarse, coarse_triangles = tube(segments=12, rings=6)
    start = coarse * [1.02, 1.02, 1.0]  # off the fine tube's surface
    massager = seqmassage.Massager(coarse, coarse_triangles)
    result = massager.run(start, reference=(fine, fine_triangles))
    assert result.ok
    before = seqmassage.distances(start, coarse_triangles, fine, fine_triangles)
    after = seqmassage.distances(result.vertices, coarse_triangles, fine, fine_triangles)
    assert after["hausdorff"] < before["hausdorff"]
    # The frame as its own reference is the same as passing it with the template's triangles.
    frame = coarse * [1.0, 1.0, 1.1]
    assert np.array_equal(massager.run(frame).vertices,
                          massager.run(frame, reference=(frame, coarse_triangles)).vertices)


def test_options_and_counts():
    vertices, triangles = tube()
    massager = seqmassage.Massager(vertices, triangles, iterations=3, mu=0.5, solver="direct")
    assert massager.num_vertices == len(vertices)
    assert massager.num_triangles == len(triangles)
    options = massager.options
    assert options["iterations"] == 3 and options["mu"] == 0.5 and options["solver"] == "direct"
    assert seqmassage.Massager(vertices, triangles).options["mu"] == "auto"
    result = massager.run(vertices * 1.1)
    assert len(result.iterations) <= 3
    assert all(it["mu"] == 0.5 for it in result.iterations)


def test_pinned_vertices_keep_their_positions():
    vertices, triangles = tube()
    frame = vertices * [1.0, 1.0, 1.2]
    pinned = np.array([0, 5, 40])
    result = seqmassage.Massager(vertices, triangles, pinned=pinned).run(frame)
    assert np.array_equal(result.vertices[pinned], frame[pinned])
