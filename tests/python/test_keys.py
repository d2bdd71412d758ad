"""massage_keys() and measure_keys(): the options tables as data."""
import numpy as np

from conftest import seqmassage, tube


def test_massage_keys_are_the_massagers_options():
    keys = seqmassage.massage_keys()
    vertices, triangles = tube()
    options = seqmassage.Massager(vertices, triangles).options
    # An optional path with no default (vertex_weights: no file) is left out of the options.
    given = [k for k in keys if k["default"] is not None]
    assert [k["name"] for k in given] == list(options)
    for k in keys:
        if k["default"] is not None:
            assert k["default"] == options[k["name"]], k["name"]
        assert set(k) == {"name", "type", "default", "choices", "min", "max", "min_exclusive",
                          "max_exclusive", "range", "doc"}
        assert k["doc"]
    by_name = {k["name"]: k for k in keys}
    it = by_name["iterations"]
    assert (it["type"], it["default"], it["min"], it["max"]) == ("integer", 15, 1, None)
    mu = by_name["mu"]
    assert (mu["type"], mu["default"], mu["min"], mu["max"]) == ("number_or_auto", "auto", 0, 1)
    assert not mu["min_exclusive"] and mu["max_exclusive"]
    assert mu["range"] == '"auto" or a number in [0, 1)'
    assert by_name["solver"]["choices"] == ["iterative", "direct"]
    assert by_name["shape_target"]["type"] == "choice"
    assert by_name["lawson"]["type"] == "boolean" and by_name["lawson"]["default"] is True
    assert by_name["pinned"]["type"] == "integer_list" and by_name["pinned"]["default"] == []


def test_every_key_takes_its_default_back():
    vertices, triangles = tube()
    defaults = {k["name"]: k["default"] for k in seqmassage.massage_keys()
                if k["default"] is not None}
    assert seqmassage.Massager(vertices, triangles, **defaults).options == defaults
    measures = {k["name"]: k["default"] for k in seqmassage.measure_keys()}
    d = seqmassage.distances(vertices, triangles, vertices * 1.01, triangles, **measures)
    assert d == seqmassage.distances(vertices, triangles, vertices * 1.01, triangles)
    assert np.isfinite(d["hausdorff"])
