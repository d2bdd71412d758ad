"""End to end: a small generated run of seqmassage with every visual output, then the tools.

Runs the seqmassage binary named by $SEQMASSAGE_BIN (ctest sets it) on a synthetic sequence with
output.colored, output.checker and output.iterations, and checks what a user would look at:

  - plot_distortion.py on the run's CSVs writes PNG and SVG figures that are valid and not blank;
  - colored/ PLY files read back, their colours equal to the blue-red scale of the per-triangle
    CSV's shear for sampled triangles;
  - checker/ OBJ + MTL + PNG: the PNG decodes (zlib, CRC-32 of every chunk, the scanline
    filters undone) to the checkerboard's colours, the texture coordinates are the same before
    and after and in every frame;
  - render_mesh.py renders the PLY and the textured OBJ to non-blank PNGs;
  - the same bytes with 1 and 2 threads; a bad option fails with its JSON path.

Run with a python3 that has matplotlib:
    SEQMASSAGE_BIN=build/src/cli/seqmassage /usr/bin/python3 -m unittest tests/tools/test_visual_outputs.py
"""

import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET
import zlib

import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.normpath(os.path.join(HERE, "..", "..", "tools"))
sys.path.insert(0, TOOLS)
import render_mesh  # noqa: E402

BIN = os.environ.get("SEQMASSAGE_BIN", "")

FRAMES = 5
MAX = 0.05


def config(out_dir, threads=2, **output):
    out = {"dir": out_dir, "per_triangle_csv": True, "timings": False,
           "colored": {"max": MAX}, "checker": True,
           "iterations": {"shear_frames": [FRAMES - 1]}}
    out.update(output)
    return {"job": "sequence",
            "input": {"synthetic": {"frames": FRAMES, "segments": 12, "rings": 10, "drift": 0.8}},
            "output": out, "massage": {"iterations": 6}, "threads": threads}


def decode_png(path):
    """(width, height, channels, rows) of an 8-bit non-interlaced PNG, checking every CRC."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "%s: no PNG signature" % path
    at, idat, header = 8, b"", None
    while at < len(data):
        (length,) = struct.unpack(">I", data[at:at + 4])
        kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + length]
        (crc,) = struct.unpack(">I", data[at + 8 + length:at + 12 + length])
        assert zlib.crc32(kind + body) & 0xffffffff == crc, "%s: bad CRC in %s" % (path, kind)
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and interlace == 0
    channels = {0: 1, 2: 3, 6: 4}[colour]
    raw = zlib.decompress(idat)  # checks the Adler-32 too
    stride = width * channels
    assert len(raw) == height * (stride + 1)
    return width, height, channels, unfilter(raw, height, stride, channels)


def unfilter(raw, height, stride, bpp):
    """The rows of pixel bytes, each scanline's PNG filter (0 to 4) undone."""
    rows, prev = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        assert kind <= 4, "scanline %d: filter type %d" % (y, kind)
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:  # Paeth
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return rows


def distinct_colours(path):
    img = mpimg.imread(path)
    pixels = img.reshape(-1, img.shape[2])
    return len({tuple(p) for p in pixels[:: max(1, len(pixels) // 20000)].tolist()})


def read_obj_uv(path):
    """(vertices, texture coordinates, per-corner (v, vt)) of an OBJ."""
    v, vt, corners, mtllib = [], [], [], None
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "v":
                v.append(tuple(words[1:4]))
            elif words[0] == "vt":
                vt.append(tuple(words[1:3]))
            elif words[0] == "f":
                corners.append(tuple(tuple(int(x) for x in w.split("/")) for w in words[1:]))
            elif words[0] == "mtllib":
                mtllib = words[1]
    return v, vt, corners, mtllib


@unittest.skipUnless(BIN and os.path.isfile(BIN), "SEQMASSAGE_BIN is not set to the seqmassage binary")
class VisualOutputsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="visual_outputs_")
        cls.run_dir = os.path.join(cls.tmp, "run")
        cls.result = cls.run_job(config(cls.run_dir))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    @classmethod
    def run_job(cls, cfg, name="config.json"):
        path = os.path.join(cls.tmp, name)
        with open(path, "w") as f:
            json.dump(cfg, f)
        return subprocess.run([BIN, path], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              universal_newlines=True, timeout=600)

    def test_run_succeeded(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)

    def test_plots_of_the_run(self):
        out = os.path.join(self.tmp, "plots")
        r = subprocess.run([sys.executable, os.path.join(TOOLS, "plot_distortion.py"),
                            self.run_dir, "--out", out, "--frame", str(FRAMES - 1)],
                           stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, universal_newlines=True, timeout=300)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("convergence: frame %d" % (FRAMES - 1), r.stdout)
        for stem in ("shear_per_frame", "shear_histogram_frame_0004", "convergence"):
            png = os.path.join(out, stem + ".png")
            with open(png, "rb") as f:
                head = f.read(24)
            self.assertEqual(head[:8], b"\x89PNG\r\n\x1a\n", png)
            width, height = struct.unpack(">II", head[16:24])
            self.assertGreater(width, 200)
            self.assertGreater(height, 200)
            self.assertGreater(distinct_colours(png), 10, "%s looks blank" % png)
            root = ET.parse(os.path.join(out, stem + ".svg")).getroot()
            self.assertTrue(root.tag.endswith("svg"))

    def test_colored_ply_matches_the_csv(self):
        for frame in range(FRAMES):
            name = "frame_%04d" % frame
            with open(os.path.join(self.run_dir, "distortion", name + ".csv")) as f:
                rows = [line.strip().split(",") for line in f][1:]
            for column, side in ((1, "before"), (2, "after")):
                ply = render_mesh.read_ply(
                    os.path.join(self.run_dir, "colored", side, name + ".ply"))
                self.assertEqual(len(ply["F"]), len(rows))
                self.assertEqual(len(ply["V"]), 3 * len(rows))  # split per face
                for t in range(0, len(rows), 11):
                    expected = render_mesh.shear_color(float(rows[t][column]), MAX)
                    self.assertEqual(tuple(ply["face_colors"][t]), expected, (name, side, t))
                    for k in range(3):
                        self.assertEqual(tuple(ply["vertex_colors"][3 * t + k]), expected)
        # frame 0 is the template: shear 0, all blue
        ply = render_mesh.read_ply(os.path.join(self.run_dir, "colored/after/frame_0000.ply"))
        self.assertEqual(set(ply["face_colors"]), {(0, 0, 255)})

    def test_scale_stops(self):
        self.assertEqual(render_mesh.scale_color(0.0), (0, 0, 255))
        self.assertEqual(render_mesh.scale_color(0.5), (0, 255, 0))
        self.assertEqual(render_mesh.scale_color(1.0), (255, 0, 0))
        self.assertEqual(render_mesh.shear_color(float("inf"), MAX), (255, 0, 0))

    def test_checker_obj_mtl_png(self):
        reference = None
        for side in ("before", "after"):
            folder = os.path.join(self.run_dir, "checker", side)
            width, height, channels, rows = decode_png(os.path.join(folder, "checker.png"))
            self.assertEqual((width, height, channels), (256, 256, 3))
            self.assertEqual(rows[0][:3], bytes([235, 235, 235]))  # light at the top left
            self.assertEqual(rows[0][32 * 3:32 * 3 + 3], bytes([45, 50, 70]))  # dark beside it
            self.assertEqual(rows[32][:3], bytes([45, 50, 70]))
            self.assertEqual(rows[255][255 * 3:], bytes([235, 235, 235]))
            with open(os.path.join(folder, "checker.mtl")) as f:
                self.assertIn("map_Kd checker.png", f.read())
            for frame in range(FRAMES):
                v, vt, corners, mtllib = read_obj_uv(os.path.join(folder, "frame_%04d.obj" % frame))
                self.assertEqual(mtllib, "checker.mtl")
                self.assertTrue(vt)
                self.assertTrue(all(len(c) == 2 for face in corners for c in face))
                if reference is None:
                    reference = (vt, [[c[1] for c in face] for face in corners])
                self.assertEqual(vt, reference[0], (side, frame))
                self.assertEqual([[c[1] for c in face] for face in corners], reference[1])

    def test_iterations_csv(self):
        with open(os.path.join(self.run_dir, "iterations.csv")) as f:
            header = f.readline().strip().split(",")
            rows = [dict(zip(header, line.rstrip("\n").split(","))) for line in f]
        last = [r for r in rows if r["frame"] == str(FRAMES - 1)]
        self.assertEqual(len(last), 7)  # iterations 0..6
        self.assertTrue(all(r["shear_max"] for r in last))
        other = [r for r in rows if r["frame"] == "2"]
        self.assertEqual([bool(r["shear_max"]) for r in other],
                         [True] + [False] * (len(other) - 2) + [True])

    def test_render_mesh(self):
        png = os.path.join(self.tmp, "colored.png")
        r = subprocess.run([sys.executable, os.path.join(TOOLS, "render_mesh.py"),
                            os.path.join(self.run_dir, "colored/before/frame_0004.ply"),
                            os.path.join(self.run_dir, "colored/after/frame_0004.ply"),
                            "--out", png, "--titles", "before", "after", "--colorbar", str(MAX)],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           universal_newlines=True, timeout=300)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGreater(distinct_colours(png), 20)
        png = os.path.join(self.tmp, "checker.png")
        r = subprocess.run([sys.executable, os.path.join(TOOLS, "render_mesh.py"),
                            os.path.join(self.run_dir, "checker/after/frame_0004.obj"),
                            "--out", png, "--subdivide", "2"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           universal_newlines=True, timeout=300)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGreater(distinct_colours(png), 10)
        r = subprocess.run([sys.executable, os.path.join(TOOLS, "render_mesh.py"),
                            os.path.join(self.tmp, "missing.ply"), "--out", png],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           universal_newlines=True, timeout=300)
        self.assertEqual(r.returncode, 1)
        self.assertIn("missing.ply: cannot open", r.stderr)

    def test_same_bytes_with_one_and_two_threads(self):
        one = os.path.join(self.tmp, "one")
        r = self.run_job(config(one, threads=1), "one.json")
        self.assertEqual(r.returncode, 0, r.stderr)
        for sub in ("colored/before", "colored/after", "checker/before", "checker/after"):
            for name in sorted(os.listdir(os.path.join(one, sub))):
                with open(os.path.join(one, sub, name), "rb") as a, \
                        open(os.path.join(self.run_dir, sub, name), "rb") as b:
                    self.assertEqual(a.read(), b.read(), os.path.join(sub, name))
        for name in ("iterations.csv", "summary.csv"):
            with open(os.path.join(one, name), "rb") as a, \
                    open(os.path.join(self.run_dir, name), "rb") as b:
                self.assertEqual(a.read(), b.read(), name)

    def test_bad_option_names_its_json_path(self):
        r = self.run_job(config(os.path.join(self.tmp, "bad"), colored={"max": -1}), "bad.json")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("output.colored.max: expected a number in (0, 1e+06], got -1", r.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.tmp, "bad")))


if __name__ == "__main__":
    unittest.main()
