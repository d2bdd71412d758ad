"""Tests for tools/render_mesh.py on tiny meshes written here: PLY (ASCII and binary, face or
vertex colours), OBJ + MTL + PNG (texture sampled per sub-triangle), the colour bar, errors.

Run with a python3 that has matplotlib:  /usr/bin/python3 -m unittest tests/tools/test_render_mesh.py
"""

import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.normpath(os.path.join(HERE, "..", "..", "tools"))
SCRIPT = os.path.join(TOOLS, "render_mesh.py")
sys.path.insert(0, TOOLS)
import render_mesh  # noqa: E402

# A unit square in the plane z = 0, two triangles.
SQUARE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
SQUARE_F = [(0, 1, 2), (0, 2, 3)]


def write_ascii_ply(path, face_colors):
    with open(path, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n")
        for v in SQUARE_V:
            f.write("%g %g %g\n" % v)
        for tri, c in zip(SQUARE_F, face_colors):
            f.write("3 %d %d %d %d %d %d\n" % (tri + c))


def write_binary_ply(path, vertex_colors):
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty double x\n"
              "property double y\nproperty double z\nproperty uchar red\nproperty uchar green\n"
              "property uchar blue\nelement face 2\nproperty list uchar int vertex_indices\n"
              "end_header\n").encode()
    body = b"".join(struct.pack("<dddBBB", *v, *c) for v, c in zip(SQUARE_V, vertex_colors))
    body += b"".join(struct.pack("<Biii", 3, *tri) for tri in SQUARE_F)
    with open(path, "wb") as f:
        f.write(header + body)


def colours_of(path):
    img = mpimg.imread(path)[:, :, :3]
    return {tuple(p) for p in (img.reshape(-1, 3) * 255).round().astype(int).tolist()}


class RenderMeshTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="render_mesh_")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def run_script(self, *args):
        return subprocess.run([sys.executable, SCRIPT] + list(args), stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, universal_newlines=True, timeout=300)

    def test_read_ply_both_formats(self):
        a = os.path.join(self.tmp, "a.ply")
        write_ascii_ply(a, [(255, 0, 0), (0, 0, 255)])
        mesh = render_mesh.read_ply(a)
        self.assertEqual(mesh["F"], [[0, 1, 2], [0, 2, 3]])
        self.assertEqual(mesh["face_colors"], [(255, 0, 0), (0, 0, 255)])
        self.assertIsNone(mesh["vertex_colors"])
        b = os.path.join(self.tmp, "b.ply")
        write_binary_ply(b, [(10, 20, 30)] * 4)
        mesh = render_mesh.read_ply(b)
        self.assertEqual(mesh["V"][2], (1.0, 1.0, 0.0))
        self.assertEqual(mesh["vertex_colors"][0], (10, 20, 30))
        self.assertIsNone(mesh["face_colors"])

    def test_face_colours_reach_the_image(self):
        ply = os.path.join(self.tmp, "a.ply")
        write_ascii_ply(ply, [(255, 0, 0), (0, 0, 255)])
        out = os.path.join(self.tmp, "a.png")
        r = self.run_script(ply, "--out", out, "--elev", "90", "--azim", "-90",
                            "--colorbar", "0.1", "--titles", "square")
        self.assertEqual(r.returncode, 0, r.stderr)
        colours = colours_of(out)
        # the headlight looks straight at the square: full brightness, exact colours
        self.assertIn((255, 0, 0), colours)
        self.assertIn((0, 0, 255), colours)
        self.assertGreater(len(colours), 20)  # the colour bar and its labels

    def test_textured_obj_shows_the_checker(self):
        texture = np.zeros((2, 2, 3))
        texture[0, 0] = texture[1, 1] = (1.0, 1.0, 0.0)  # yellow and black squares
        matplotlib.image.imsave(os.path.join(self.tmp, "t.png"), texture)
        with open(os.path.join(self.tmp, "t.mtl"), "w") as f:
            f.write("newmtl m\nmap_Kd t.png\n")
        obj = os.path.join(self.tmp, "t.obj")
        with open(obj, "w") as f:
            f.write("mtllib t.mtl\n")
            f.write("".join("v %g %g %g\n" % v for v in SQUARE_V))
            f.write("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n")
        mesh = render_mesh.read_obj(obj)
        self.assertTrue(mesh["texture"].endswith("t.png"))
        tris, colors = render_mesh.triangles_and_colors(mesh, obj, 4)
        self.assertEqual(len(tris), 2 * 16)
        self.assertEqual({tuple(c) for c in np.round(colors, 3).tolist()},
                         {(1.0, 1.0, 0.0), (0.0, 0.0, 0.0)})
        out = os.path.join(self.tmp, "t_render.png")
        r = self.run_script(obj, "--out", out, "--elev", "90", "--azim", "-90")
        self.assertEqual(r.returncode, 0, r.stderr)
        colours = colours_of(out)
        self.assertIn((255, 255, 0), colours)
        self.assertIn((0, 0, 0), colours)

    def test_errors(self):
        bad = os.path.join(self.tmp, "bad.ply")
        with open(bad, "w") as f:
            f.write("ply\nformat binary_big_endian 1.0\nend_header\n")
        r = self.run_script(bad, "--out", os.path.join(self.tmp, "x.png"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("binary_big_endian", r.stderr)
        obj = os.path.join(self.tmp, "m.obj")
        with open(obj, "w") as f:
            f.write("mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        r = self.run_script(obj, "--out", os.path.join(self.tmp, "x.png"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("missing.mtl: file not found", r.stderr)
        r = self.run_script(obj, obj, "--out", "x.png", "--titles", "one")
        self.assertEqual(r.returncode, 2)
        self.assertIn("one title per mesh", r.stderr)


if __name__ == "__main__":
    unittest.main()
