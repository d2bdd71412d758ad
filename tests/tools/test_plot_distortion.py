"""Tests for tools/plot_distortion.py: run it as a subprocess on a small fake run directory.

Run with a python3 that has matplotlib:  /usr/bin/python3 -m unittest tests/tools/test_plot_distortion.py
"""

import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.normpath(os.path.join(HERE, "..", "..", "tools", "plot_distortion.py"))

HEADER = ("frame,file,vertices,triangles,shear_max_before,shear_mean_before,shear_p95_before,"
          "shear_max_after,shear_mean_after,shear_p95_after,dist_out_to_in_max,dist_out_to_in_rms,"
          "dist_in_to_out_max,dist_in_to_out_rms,iterations,seconds")


def summary_rows():
    rows = [HEADER + ",status"]
    rows.append("0,frame_0000.obj,100,196,0,0,0,0,0,0,0,0,0,0,0,0.01,template")
    maxima = [0.5, 2.0, 7.5, 3.0, 1.2]
    for i, m in enumerate(maxima, start=1):
        rows.append("%d,frame_%04d.obj,100,196,%g,%g,%g,%g,%g,%g,0.001,0.0005,0.002,0.0006,8,0.2,"
                    "optimized" % (i, i, m, m / 20, m / 4, m / 3, m / 25, m / 8))
    # a failed frame: empty after-values, inf before-max
    rows.append("6,frame_0006.obj,100,196,inf,nan,,,,,,,,,0,0.1,failed")
    return rows


def distortion_rows(scale):
    rows = ["triangle,shear_before,shear_after"]
    for t in range(196):
        b = scale * ((t * 37) % 101) / 100.0
        rows.append("%d,%r,%r" % (t, b, b * 0.4 + 0.001 * (t % 7)))
    rows.append("196,0,0")
    return rows


def iteration_rows():
    rows = ["frame,iteration,shear_max,shear_mean,max_dist_m_to_n,rms_dist_m_to_n,"
            "max_dist_n_to_m,rms_dist_n_to_m,energy"]
    for frame in (2, 3):
        for it in range(10):
            d = 1.0 / (it + 1)
            rows.append("%d,%d,%g,%g,%g,%g,%g,%g,%g"
                        % (frame, it, frame * 3 * d + 1, 0.2 + 0.01 * it, 0.01 * d, 0.004 * d,
                           0.012 * d, 0.005 * d, 10 * d * d))
    return rows


def write(path, lines):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def png_size(path):
    with open(path, "rb") as f:
        data = f.read(33)
    if data[:8] != b"\x89PNG\r\n\x1a\n" or data[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", data[16:24])


class PlotDistortionTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="plot_distortion_")
        self.run_dir = os.path.join(self.tmp, "run")
        write(os.path.join(self.run_dir, "summary.csv"), summary_rows())
        write(os.path.join(self.run_dir, "distortion", "frame_0002.csv"), distortion_rows(2.0))
        write(os.path.join(self.run_dir, "distortion", "frame_0003.csv"), distortion_rows(7.5))
        write(os.path.join(self.run_dir, "iterations.csv"), iteration_rows())

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def run_script(self, *args):
        return subprocess.run([sys.executable, SCRIPT] + list(args), stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, universal_newlines=True, timeout=300)

    def assert_figure(self, path):
        self.assertTrue(os.path.isfile(path), path)
        if path.endswith(".png"):
            size = png_size(path)
            self.assertIsNotNone(size, "%s: not a PNG" % path)
            self.assertGreater(size[0], 200)
            self.assertGreater(size[1], 200)
            img = mpimg.imread(path)
            self.assertEqual(img.shape[:2], (size[1], size[0]))
            pixels = img.reshape(-1, img.shape[2])
            colours = {tuple(p) for p in pixels[:: max(1, len(pixels) // 20000)].tolist()}
            self.assertGreater(len(colours), 10, "%s looks blank" % path)
        else:
            root = ET.parse(path).getroot()
            self.assertTrue(root.tag.endswith("svg"), "%s: root is %s" % (path, root.tag))

    def expect_outputs(self, out_dir, stems, result):
        for stem in stems:
            for ext in ("png", "svg"):
                p = os.path.join(out_dir, "%s.%s" % (stem, ext))
                self.assert_figure(p)
                self.assertIn(p, result.stdout)

    def test_default_run_writes_all_figures(self):
        r = self.run_script(self.run_dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        out = os.path.join(self.run_dir, "plots")
        # default histogram frame: largest max shear before among frames with a distortion CSV
        # (frame 3, 7.5; frame 6 has inf but no CSV)
        self.expect_outputs(out, ["shear_per_frame", "shear_histogram_frame_0003", "convergence"], r)
        self.assertFalse(os.path.exists(os.path.join(out, "shear_histogram_frame_0002.png")))

    def test_log_frame_and_out(self):
        out = os.path.join(self.tmp, "figs")
        r = self.run_script(self.run_dir, "--out", out, "--frame", "2", "--log")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.expect_outputs(out, ["shear_per_frame", "shear_histogram_frame_0002", "convergence"], r)
        r = self.run_script(self.run_dir, "--out", out, "--frame", "frame_0003.obj")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.expect_outputs(out, ["shear_histogram_frame_0003"], r)

    def test_optional_inputs_absent(self):
        os.remove(os.path.join(self.run_dir, "iterations.csv"))
        shutil.rmtree(os.path.join(self.run_dir, "distortion"))
        r = self.run_script(self.run_dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.expect_outputs(os.path.join(self.run_dir, "plots"), ["shear_per_frame"], r)
        self.assertIn("iterations.csv not found", r.stdout)
        self.assertIn("histogram skipped", r.stdout)

    def test_iterations_with_some_metrics(self):
        write(os.path.join(self.run_dir, "iterations.csv"),
              ["frame,iteration,shear_max,energy,extra"] +
              ["4,%d,%g,%g,x" % (i, 5.0 / (i + 1), 1.0 / (i + 1)) for i in range(6)])
        r = self.run_script(self.run_dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.expect_outputs(os.path.join(self.run_dir, "plots"), ["convergence"], r)

    def expect_error(self, args, *fragments):
        r = self.run_script(*args)
        self.assertNotEqual(r.returncode, 0, r.stdout)
        for f in fragments:
            self.assertIn(f, r.stderr)
        return r

    def test_missing_run_dir(self):
        missing = os.path.join(self.tmp, "nope")
        self.expect_error([missing], missing, "run directory not found")

    def test_missing_summary(self):
        os.remove(os.path.join(self.run_dir, "summary.csv"))
        self.expect_error([self.run_dir], "summary.csv", "not found")

    def test_empty_summary(self):
        write(os.path.join(self.run_dir, "summary.csv"), [])
        self.expect_error([self.run_dir], "summary.csv", "empty file")
        write(os.path.join(self.run_dir, "summary.csv"), [HEADER])
        self.expect_error([self.run_dir], "summary.csv", "no frame rows")

    def test_missing_column(self):
        lines = summary_rows()
        lines[0] = lines[0].replace("shear_mean_after", "shear_avg_after")
        write(os.path.join(self.run_dir, "summary.csv"), lines)
        self.expect_error([self.run_dir], "summary.csv", "missing required column",
                          "shear_mean_after")

    def test_non_numeric_cell(self):
        lines = summary_rows()
        lines[3] = lines[3].replace(",2,", ",two,", 1)
        self.assertIn("two", lines[3])
        write(os.path.join(self.run_dir, "summary.csv"), lines)
        self.expect_error([self.run_dir], "summary.csv", "line 4", "not a number", "'two'")

    def test_bad_distortion_csv(self):
        lines = distortion_rows(7.5)
        lines[5] = "4,abc,0.1"
        write(os.path.join(self.run_dir, "distortion", "frame_0003.csv"), lines)
        self.expect_error([self.run_dir], "frame_0003.csv", "shear_before", "not a number")

    def test_bad_iterations_csv(self):
        write(os.path.join(self.run_dir, "iterations.csv"), ["frame,shear_max", "1,2"])
        self.expect_error([self.run_dir], "iterations.csv", "missing required column", "iteration")

    def test_unknown_frame(self):
        self.expect_error([self.run_dir, "--frame", "42"], "no frame '42'")
        self.expect_error([self.run_dir, "--frame", "4"], "frame_0004.csv",
                          "no per-triangle CSV")

    def test_missing_matplotlib_message(self):
        code = ("import runpy, sys; sys.modules['matplotlib'] = None; "
                "sys.argv = [sys.argv[1], sys.argv[2]]; "
                "runpy.run_path(sys.argv[0], run_name='__main__')")
        r = subprocess.run([sys.executable, "-c", code, SCRIPT, self.run_dir],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           universal_newlines=True, timeout=120)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("apt-get install python3-matplotlib", r.stderr)


if __name__ == "__main__":
    unittest.main()
