"""massage_keys() and measure_keys(): the options tables as data."""
import json
import re
from pathlib import Path

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
    # The documented reference (docs/configuration.md, the `massage` table) is the contract:
    # every key is there with the same default.
    documented = documented_massage_defaults()
    assert sorted(documented) == sorted(k["name"] for k in keys)
    for k in keys:
        if k["default"] is not None:
            assert documented[k["name"]] == k["default"], k["name"]
    by_name = {k["name"]: k for k in keys}
    mu = by_name["mu"]
    assert mu["type"] == "number_or_auto" and not mu["min_exclusive"] and mu["max_exclusive"]
    assert by_name["solver"]["type"] == "choice"
    assert by_name["lawson"]["type"] == "boolean"
    assert by_name["pinned"]["type"] == "integer_list"


def documented_massage_defaults():
    """Key -> default (sequence jobs) of the `massage` table in docs/configuration.md."""
    doc = Path(__file__).resolve().parents[2] / "docs" / "configuration.md"
    defaults = {}
    for line in doc.read_text(encoding="utf-8").splitlines():
        m = re.match(r"\| `massage\.(\w+)` \| [^|]+ \| ([^|]*?) *\|", line)
        if m:
            cell = m.group(2)
            defaults[m.group(1)] = json.loads(cell.strip("`")) if cell.startswith("`") else None
    return defaults


def test_every_key_takes_its_default_back():
    vertices, triangles = tube()
    defaults = {k["name"]: k["default"] for k in seqmassage.massage_keys()
                if k["default"] is not None}
    assert seqmassage.Massager(vertices, triangles, **defaults).options == defaults
    measures = {k["name"]: k["default"] for k in seqmassage.measure_keys()}
    d = seqmassage.distances(vertices, triangles, vertices * 1.01, triangles, **measures)
    assert d == seqmassage.distances(vertices, triangles, vertices * 1.01, triangles)
    assert np.isfinite(d["hausdorff"])
