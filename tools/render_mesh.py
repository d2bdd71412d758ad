#!/usr/bin/env python3
"""Render meshes to a PNG with matplotlib only: coloured PLY files and textured OBJ files.

    render_mesh.py MESH [MESH ...] --out FILE.png [--titles T1 T2 ...] [--elev DEG] [--azim DEG]
                   [--subdivide N] [--colorbar MAX] [--size W H] [--dpi DPI] [--zoom Z]

Each MESH becomes one panel, all seen by the same camera (so before/after pairs compare):

  .ply  binary_little_endian or ascii PLY; faces take their face colour (red, green, blue), else
        the mean of their vertices' colours, else grey. seqmassage's colored/ output.
  .obj  v, vt and f statements (v, v/vt, v/vt/vn, v//vn corners; polygons fan-triangulated) with
        `mtllib` naming an MTL whose `map_Kd` image (PNG) textures the faces: every triangle is
        split into N x N smaller ones (--subdivide, default 4), each coloured by the texture at its
        centre (texture coordinates wrap around, as the viewers' default repeat does), so the
        checker squares come out crisp. Without a texture the faces are grey. seqmassage's
        checker/ output.

Faces are shaded by a headlight (Lambert) and drawn back to front (painter's algorithm of
mplot3d's Poly3DCollection). --colorbar MAX adds the blue-red scale of seqmassage's colored
output, from shear 0 (blue) to MAX and above (red).

Exit status: 0 on success, 1 on bad input or missing matplotlib, 2 on bad usage.
"""

import argparse
import math
import os
import struct
import sys


class InputError(Exception):
    """A problem with an input file; the message names the file."""


def load_matplotlib():
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import numpy  # noqa: F401  (a dependency of matplotlib)
    except ImportError:
        sys.stderr.write(
            "render_mesh.py: error: matplotlib is not available for %s\n"
            "  install it with: apt-get install python3-matplotlib\n"
            "  (then run the script with /usr/bin/python3 if another python3 is first on PATH)\n"
            % sys.executable)
        sys.exit(1)
    return plt


# ---------------------------------------------------------------------------------------------
# The blue-red scale of seqmassage's colored output (pipeline/outputs/shear_ply.hpp): blue, cyan, green,
# yellow, red at 0, 1/4, 1/2, 3/4, 1.

SCALE_STOPS = [(0.0, (0, 0, 255)), (0.25, (0, 255, 255)), (0.5, (0, 255, 0)),
               (0.75, (255, 255, 0)), (1.0, (255, 0, 0))]


def scale_color(t):
    """(r, g, b) bytes of t in [0, 1] on the blue-red scale, exactly as seqmassage computes it."""
    if t != t:  # NaN
        t = 1.0
    t = min(1.0, max(0.0, t))
    segment = min(3, int(math.floor(4.0 * t)))
    f = 4.0 * t - segment
    r, g, b = [(0, f, 1), (0, 1, 1 - f), (f, 1, 0), (1, 1 - f, 0)][segment]
    # C++ std::lround rounds halves away from zero; Python's round() to even: use floor(x + 0.5).
    return tuple(int(math.floor(255.0 * x + 0.5)) for x in (r, g, b))


def shear_color(shear, maximum):
    t = 1.0 if not math.isfinite(shear) else min(1.0, max(0.0, shear / maximum))
    return scale_color(t)


# ---------------------------------------------------------------------------------------------
# PLY

PLY_TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
             "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
             "float": "f", "float32": "f", "double": "d", "float64": "d"}


def read_ply(path):
    """{'V': [(x, y, z)], 'F': [[i, j, k]], 'vertex_colors': [...] or None,
    'face_colors': [...] or None} of a PLY file."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise InputError("%s: cannot open: %s" % (path, e.strerror or e))
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise InputError("%s: not a PLY file (no 'ply' ... 'end_header')" % path)
    header = data[:end].decode("ascii", "replace").splitlines()
    body_start = data.index(b"\n", end) + 1
    fmt, elements = None, []
    for n, line in enumerate(header, start=1):
        words = line.split()
        if not words or words[0] in ("ply", "comment", "obj_info"):
            continue
        if words[0] == "format":
            fmt = words[1] if len(words) > 1 else None
        elif words[0] == "element" and len(words) == 3:
            elements.append({"name": words[1], "count": int(words[2]), "props": []})
        elif words[0] == "property" and elements:
            if words[1] == "list" and len(words) == 5:
                elements[-1]["props"].append((words[4], "list", words[2], words[3]))
            elif len(words) == 3 and words[1] in PLY_TYPES:
                elements[-1]["props"].append((words[2], words[1], None, None))
            else:
                raise InputError("%s: header line %d: unsupported property: %s" % (path, n, line))
        else:
            raise InputError("%s: header line %d: unexpected: %s" % (path, n, line))
    if fmt not in ("ascii", "binary_little_endian"):
        raise InputError("%s: format '%s' is not read (ascii or binary_little_endian)" % (path, fmt))

    values = {}
    if fmt == "ascii":
        tokens = data[body_start:].split()
        at = [0]

        def take(kind):
            if at[0] >= len(tokens):
                raise InputError("%s: the data ends early" % path)
            word = tokens[at[0]]
            at[0] += 1
            return float(word) if PLY_TYPES[kind] in "fd" else int(word)
    else:
        offset = [body_start]

        def take(kind):
            code = "<" + PLY_TYPES[kind]
            size = struct.calcsize(code)
            if offset[0] + size > len(data):
                raise InputError("%s: the data ends early" % path)
            (x,) = struct.unpack_from(code, data, offset[0])
            offset[0] += size
            return x
    for element in elements:
        rows = []
        for _ in range(element["count"]):
            row = {}
            for name, kind, count_kind, item_kind in element["props"]:
                if kind == "list":
                    row[name] = [take(item_kind) for _ in range(take(count_kind))]
                else:
                    row[name] = take(kind)
            rows.append(row)
        values[element["name"]] = rows
    vertices, faces = values.get("vertex", []), values.get("face", [])
    if not vertices or not faces:
        raise InputError("%s: no vertices or no faces" % path)
    index_name = "vertex_indices" if "vertex_indices" in faces[0] else "vertex_index"
    if index_name not in faces[0]:
        raise InputError("%s: faces without vertex_indices" % path)
    V = [(v["x"], v["y"], v["z"]) for v in vertices]
    F = []
    face_of_triangle = []
    for k, face in enumerate(faces):
        idx = face[index_name]
        for j in range(1, len(idx) - 1):
            F.append([idx[0], idx[j], idx[j + 1]])
            face_of_triangle.append(k)
    rgb = ("red", "green", "blue")
    vertex_colors = [tuple(v[c] for c in rgb) for v in vertices] if "red" in vertices[0] else None
    face_colors = None
    if "red" in faces[0]:
        face_colors = [tuple(faces[k][c] for c in rgb) for k in face_of_triangle]
    return {"V": V, "F": F, "vertex_colors": vertex_colors, "face_colors": face_colors}


# ---------------------------------------------------------------------------------------------
# OBJ + MTL + PNG

def read_obj(path):
    """{'V', 'F', 'UV' (or None), 'FT' (per triangle uv indices or None), 'texture' (path or
    None)} of an OBJ file."""
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise InputError("%s: cannot open: %s" % (path, e.strerror or e))
    V, UV, F, FT, mtllibs = [], [], [], [], []
    for n, line in enumerate(lines, start=1):
        words = line.split("#", 1)[0].split()
        if not words:
            continue
        try:
            if words[0] == "v":
                V.append(tuple(float(x) for x in words[1:4]))
            elif words[0] == "vt":
                UV.append((float(words[1]), float(words[2]) if len(words) > 2 else 0.0))
            elif words[0] == "f":
                corners = []
                for word in words[1:]:
                    parts = word.split("/")
                    v = int(parts[0])
                    t = int(parts[1]) if len(parts) > 1 and parts[1] else None
                    v = v - 1 if v > 0 else len(V) + v
                    if t is not None:
                        t = t - 1 if t > 0 else len(UV) + t
                    corners.append((v, t))
                for j in range(1, len(corners) - 1):
                    tri = [corners[0], corners[j], corners[j + 1]]
                    F.append([c[0] for c in tri])
                    FT.append([c[1] for c in tri])
            elif words[0] == "mtllib":
                mtllibs.append(line.split(None, 1)[1].strip())
        except (ValueError, IndexError):
            raise InputError("%s:%d: malformed statement: %s" % (path, n, line.strip()))
    if not V or not F:
        raise InputError("%s: no vertices or no faces" % path)
    for tri in F:
        for v in tri:
            if not 0 <= v < len(V):
                raise InputError("%s: a face refers to vertex %d of %d" % (path, v + 1, len(V)))
    has_uv = UV and all(t is not None and 0 <= t < len(UV) for tri in FT for t in tri)
    texture = None
    for lib in mtllibs:
        mtl = os.path.join(os.path.dirname(path), lib)
        if not os.path.isfile(mtl):
            raise InputError("%s: mtllib %s: file not found" % (path, mtl))
        with open(mtl, encoding="utf-8", errors="replace") as f:
            for line in f:
                words = line.split()
                if words and words[0] == "map_Kd" and len(words) > 1:
                    texture = os.path.join(os.path.dirname(mtl), words[-1])
                    break
        if texture:
            break
    if texture and not os.path.isfile(texture):
        raise InputError("%s: texture %s: file not found" % (path, texture))
    return {"V": V, "F": F, "UV": UV if has_uv else None, "FT": FT if has_uv else None,
            "texture": texture}


# ---------------------------------------------------------------------------------------------
# Rendering

def triangles_and_colors(mesh, path, subdivide):
    """(T x 3 x 3 corner positions, T x 3 colours in [0, 1]) of a mesh read by read_ply/read_obj."""
    import numpy as np
    V = np.asarray(mesh["V"], dtype=float)
    F = np.asarray(mesh["F"], dtype=int)
    tris = V[F]
    if mesh.get("face_colors"):
        return tris, np.asarray(mesh["face_colors"], dtype=float) / 255.0
    if mesh.get("vertex_colors"):
        vc = np.asarray(mesh["vertex_colors"], dtype=float) / 255.0
        return tris, vc[F].mean(axis=1)
    if mesh.get("texture") and mesh.get("UV") is not None:
        import matplotlib.image as mpimg
        try:
            image = mpimg.imread(mesh["texture"])
        except Exception as e:  # noqa: BLE001  (matplotlib/Pillow raise various errors)
            raise InputError("%s: cannot read the texture: %s" % (mesh["texture"], e))
        if image.dtype != np.float32 and image.dtype != np.float64:
            image = image.astype(float) / 255.0
        if image.ndim == 2:
            image = np.stack([image] * 3, axis=-1)
        image = image[:, :, :3]
        UV = np.asarray(mesh["UV"], dtype=float)[np.asarray(mesh["FT"], dtype=int)]
        s = max(1, subdivide)
        # barycentric corners of the s*s sub-triangles, and their centres
        bary, centres = [], []
        for i in range(s):
            for j in range(s - i):
                a = np.array([[i, j], [i + 1, j], [i, j + 1]], dtype=float) / s
                bary.append(a)
                centres.append(a.mean(axis=0))
                if j < s - i - 1:
                    b = np.array([[i + 1, j], [i + 1, j + 1], [i, j + 1]], dtype=float) / s
                    bary.append(b)
                    centres.append(b.mean(axis=0))
        bary, centres = np.asarray(bary), np.asarray(centres)

        def weights(b):  # (.., 2) barycentric (b1, b2) -> (.., 3) weights of corners 0, 1, 2
            return np.stack([1 - b[..., 0] - b[..., 1], b[..., 0], b[..., 1]], axis=-1)
        W = weights(bary)                     # k x 3 x 3
        sub = np.einsum("kcw,twd->tkcd", W, tris).reshape(-1, 3, 3)
        uv = np.einsum("kw,twd->tkd", weights(centres), UV).reshape(-1, 2)
        h, w = image.shape[:2]
        u, v = uv[:, 0] % 1.0, uv[:, 1] % 1.0
        x = np.minimum((u * w).astype(int), w - 1)
        y = np.minimum(((1.0 - v) * h).astype(int), h - 1)  # OBJ's v points up the image
        return sub, image[y, x]
    return tris, np.full((len(F), 3), 0.75)


def shade(tris, colors, view):
    import numpy as np
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    length = np.linalg.norm(n, axis=1)
    length[length == 0] = 1.0
    lambert = np.abs(n @ view) / length
    return np.clip(colors * (0.35 + 0.65 * lambert)[:, None], 0.0, 1.0)


def view_direction(elev, azim):
    import numpy as np
    e, a = math.radians(elev), math.radians(azim)
    return np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])


def render(plt, paths, out, titles, elev, azim, subdivide, colorbar, size, dpi, zoom):
    import numpy as np
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    meshes = []
    for path in paths:
        ext = os.path.splitext(path)[1].lower()
        if ext == ".ply":
            mesh = read_ply(path)
        elif ext == ".obj":
            mesh = read_obj(path)
        else:
            raise InputError("%s: unknown extension (give .ply or .obj)" % path)
        meshes.append(triangles_and_colors(mesh, path, subdivide))
    points = np.concatenate([t.reshape(-1, 3) for t, _ in meshes])
    low, high = points.min(axis=0), points.max(axis=0)
    centre, radius = (low + high) / 2, max(1e-12, float((high - low).max()) / 2 / zoom)
    view = view_direction(elev, azim)

    fig = plt.figure(figsize=size)
    n = len(meshes)
    bar = 0.9 / size[0] if colorbar else 0.0  # 0.9 inch for the scale and its labels
    width = (1.0 - bar) / n
    for k, (tris, colors) in enumerate(meshes):
        ax = fig.add_axes([k * width, 0.0, width, 0.92 if titles else 1.0], projection="3d")
        shaded = shade(tris, colors, view)
        # edges in the face colour close the hairline gaps antialiasing leaves between faces
        collection = Poly3DCollection(tris, facecolors=shaded, edgecolors=shaded,
                                      linewidths=0.25)
        ax.add_collection3d(collection)
        for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
            setter(c - radius, c + radius)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=elev, azim=azim)
        ax.set_axis_off()
        if titles:
            fig.text(k * width + width / 2, 0.95, titles[k], ha="center", va="center",
                     fontsize=11)
    if colorbar:
        import matplotlib as mpl
        from matplotlib.colors import ListedColormap
        ramp = ListedColormap([[c / 255.0 for c in scale_color(i / 255.0)] for i in range(256)])
        cax = fig.add_axes([1.0 - bar, 0.12, 0.15 / size[0], 0.72])
        cb = fig.colorbar(mpl.cm.ScalarMappable(norm=mpl.colors.Normalize(0, colorbar),
                                                cmap=ramp), cax=cax)
        cb.set_label("shear (eq. 8)")
        ticks = list(cb.get_ticks())
        cb.set_ticks(ticks)
        cb.set_ticklabels(["%g" % t if t < colorbar else "≥ %g" % t for t in ticks])
    fig.savefig(out, dpi=dpi)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Render coloured PLY and textured OBJ meshes side by side to a PNG.")
    parser.add_argument("meshes", metavar="MESH", nargs="+", help=".ply or .obj files")
    parser.add_argument("--out", required=True, metavar="FILE", help="the PNG to write")
    parser.add_argument("--titles", nargs="+", metavar="TITLE", help="one title per mesh")
    parser.add_argument("--elev", type=float, default=20.0, help="camera elevation (degrees)")
    parser.add_argument("--azim", type=float, default=-60.0, help="camera azimuth (degrees)")
    parser.add_argument("--subdivide", type=int, default=4,
                        help="textured meshes: split each triangle into N x N (default 4)")
    parser.add_argument("--colorbar", type=float, metavar="MAX",
                        help="add the blue-red shear scale from 0 to MAX")
    parser.add_argument("--size", type=float, nargs=2, default=None, metavar=("W", "H"),
                        help="figure size in inches (default 4 x 4 per panel)")
    parser.add_argument("--dpi", type=int, default=100)
    parser.add_argument("--zoom", type=float, default=1.0, help="> 1 magnifies (default 1)")
    args = parser.parse_args(argv)
    if args.titles and len(args.titles) != len(args.meshes):
        parser.error("--titles needs one title per mesh (%d meshes, %d titles)"
                     % (len(args.meshes), len(args.titles)))
    if args.colorbar is not None and not args.colorbar > 0:
        parser.error("--colorbar MAX must be > 0")
    if args.zoom <= 0 or args.subdivide < 1:
        parser.error("--zoom must be > 0 and --subdivide >= 1")
    size = args.size or (4.0 * len(args.meshes) + (0.9 if args.colorbar else 0.0), 4.0)
    plt = load_matplotlib()
    try:
        out_dir = os.path.dirname(os.path.abspath(args.out))
        if not os.path.isdir(out_dir):
            raise InputError("%s: output folder not found" % out_dir)
        render(plt, args.meshes, args.out, args.titles, args.elev, args.azim, args.subdivide,
               args.colorbar, size, args.dpi, args.zoom)
    except InputError as e:
        sys.stderr.write("render_mesh.py: error: %s\n" % e)
        return 1
    print("wrote %s" % args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
