"""seqmassage.run_job: the command line's job, from a dict or a file, returning report.json."""
import json

import numpy as np

from conftest import SEQUENCE_CONFIG, read_obj, seqmassage


def test_run_job_from_a_dict_writes_and_returns_the_report(tmp_path, monkeypatch, cli_sequence):
    monkeypatch.chdir(tmp_path)
    config = dict(SEQUENCE_CONFIG, output=dict(SEQUENCE_CONFIG["output"], dir="out"))
    report = seqmassage.run_job(config)
    out = tmp_path / "out"
    assert report == json.loads((out / "report.json").read_text())
    cli_out, cli_report = cli_sequence
    for name in (p.name for p in (cli_out / "frames").glob("*.obj")):
        assert (out / "frames" / name).read_bytes() == (cli_out / "frames" / name).read_bytes()
    assert report["frames"] == cli_report["frames"]
    assert report["totals"] == cli_report["totals"]


def test_run_job_from_a_file_resolves_paths_against_its_folder(tmp_path, cli_sequence):
    cli_out, _ = cli_sequence
    names = sorted(p.name for p in (cli_out / "input").glob("*.obj"))
    folder = tmp_path / "job"
    (folder / "mesh").mkdir(parents=True)
    (folder / "mesh" / "before.obj").write_bytes((cli_out / "input" / names[-1]).read_bytes())
    (folder / "mesh" / "template.obj").write_bytes((cli_out / "input" / names[0]).read_bytes())
    config = {"job": "crossparam",
              "input": {"mesh": "mesh/before.obj"},
              "template": {"mesh": "mesh/template.obj"},
              "massage": {"iterations": 4},
              "output": {"dir": "out", "timings": False}}
    (folder / "job.json").write_text(json.dumps(config))
    report = seqmassage.run_job(folder / "job.json")
    assert report == json.loads((folder / "out" / "report.json").read_text())
    assert report["massage"]["ok"]
    # The same optimizer from Python: the crossparam job's output positions.
    template, triangles = read_obj(folder / "mesh" / "template.obj")
    start, _ = read_obj(folder / "mesh" / "before.obj")
    written = next((folder / "out").glob("*.obj"))
    massager = seqmassage.Massager(template, triangles, iterations=4)
    result = massager.run(start)
    assert np.array_equal(result.vertices, read_obj(written)[0])
