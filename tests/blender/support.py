"""Shared by the Blender tests: the add-on enabled from this checkout, a generated drifted tube,
OBJ frames for the command line, and checks that fail the Blender process.

Run inside Blender (tests/blender/run.sh): `blender -b --factory-startup --python-exit-code 1
--python tests/blender/test_x.py`. SEQMASSAGE_ROOT is the checkout, SEQMASSAGE_MODULE_DIR the
folder of the built module (build/python), SEQMASSAGE_CLI the command line next to it and
SEQMASSAGE_TEST_DIR the folder for the tests' files.
"""
import math
import os
import shutil
import subprocess
import sys
import tempfile

import bpy
import numpy as np

ROOT = os.environ.get("SEQMASSAGE_ROOT") or os.path.abspath(
    os.path.join(os.path.dirname(__file__), "..", ".."))
MODULE_DIR = os.environ.get("SEQMASSAGE_MODULE_DIR") or os.path.join(ROOT, "build", "python")
CLI = os.environ.get("SEQMASSAGE_CLI") or os.path.join(ROOT, "build", "src", "cli", "seqmassage")
TEST_DIR = os.environ.get("SEQMASSAGE_TEST_DIR") or os.path.join(ROOT, "build", "blender-test")
ADDON = "seqmassage_blender"


def log(*args):
    print(f"{os.path.basename(sys.argv[-1])}:", *args, flush=True)


def check(condition, what):
    if not condition:
        raise AssertionError(what)
    log("ok:", what)


def work_dir(name):
    path = os.path.join(TEST_DIR, name)
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


def enable_addon():
    """Enables the add-on the way a user's install does: a scripts folder whose addons/ holds the
    package (a link to this checkout's blender/seqmassage_blender)."""
    scripts = tempfile.mkdtemp(prefix="seqmassage-blender-scripts-")
    os.makedirs(os.path.join(scripts, "addons"))
    os.symlink(os.path.join(ROOT, "blender", ADDON), os.path.join(scripts, "addons", ADDON))
    bpy.context.preferences.filepaths.script_directory = scripts
    bpy.utils.refresh_script_paths()
    import addon_utils

    def fail(error):
        raise error

    addon_utils.enable(ADDON, default_set=True, handle_error=fail)
    check(ADDON in bpy.context.preferences.addons, f"add-on {ADDON} enabled")
    return sys.modules[ADDON]


def set_module_dir(path=MODULE_DIR):
    bpy.context.preferences.addons[ADDON].preferences.module_path = path


# --- The drifted tube ---------------------------------------------------------------------------

def tube_frames(frames=6, segments=16, rings=20, radius=0.5, length=4.0, bend_deg=90.0,
                drift=0.6, seed=1):
    """(frames x n x 3 float32 positions, m x 3 triangles): an open tube along z bending about x
    over time, its vertices sliding tangentially (around and along the surface) by a smooth
    time-varying field of `drift` edge lengths; frame 0 straight and undrifted."""
    rng = np.random.default_rng(seed)
    phase = rng.uniform(0, 2 * math.pi, size=4)
    a0 = np.linspace(0, 2 * math.pi, segments, endpoint=False)
    s0 = np.linspace(0, length, rings + 1)
    A, S = np.meshgrid(a0, s0)  # (rings + 1) x segments
    out = []
    for k in range(frames):
        t = k / (frames - 1)
        amp = drift * math.sin(math.pi * t / 2) if k else 0.0
        a = A + amp * (2 * math.pi / segments) * np.sin(2 * math.pi * S / length + phase[0]
                                                          + 3 * t) * np.sin(A + phase[1])
        s = S + amp * (length / rings) * np.cos(A + phase[2] + 2 * t) * np.sin(
            math.pi * S / length) * np.cos(math.pi * S / length + phase[3])
        x, y = radius * np.cos(a), radius * np.sin(a)
        theta = math.radians(bend_deg) * t
        if theta == 0:
            P = np.stack([x, y, s], axis=-1)
        else:
            R = length / theta
            phi = s / R
            # centre line (0, R(1 - cos phi), R sin phi); the section's y along its normal
            P = np.stack([x, R - (R - y) * np.cos(phi), (R - y) * np.sin(phi)], axis=-1)
        out.append(P.reshape(-1, 3))
    tris = []
    for r in range(rings):
        for j in range(segments):
            v00, v01 = r * segments + j, r * segments + (j + 1) % segments
            v10, v11 = v00 + segments, v01 + segments
            tris += [(v00, v01, v11), (v00, v11, v10)]
    return np.array(out, dtype=np.float32), np.array(tris, dtype=np.int32)


def tube_object(frames, tris, name="tube", shape_keys=True):
    """A mesh object with frame 0 as its mesh (and basis shape key) and, with `shape_keys`, the
    other frames as keys frame_1, frame_2, ..."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(frames[0].astype(np.float64).tolist(), [], tris.tolist())
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    if shape_keys:
        obj.shape_key_add(name="Basis", from_mix=False)
        for k in range(1, len(frames)):
            kb = obj.shape_key_add(name=f"frame_{k}", from_mix=False)
            kb.data.foreach_set("co", frames[k].ravel())
    return obj


def key_positions(obj, name):
    kb = obj.data.shape_keys.key_blocks[name]
    co = np.empty(len(kb.data) * 3, dtype=np.float32)
    kb.data.foreach_get("co", co)
    return co.reshape(-1, 3)


def evaluated_positions(obj, frame):
    """The object's vertex positions after its modifiers at scene frame `frame` (float32)."""
    bpy.context.scene.frame_set(frame)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    co = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
    mesh.vertices.foreach_get("co", co)
    evaluated.to_mesh_clear()
    return co.reshape(-1, 3)


# --- The command line ---------------------------------------------------------------------------

def write_obj(path, vertices, tris):
    """An OBJ whose coordinates read back as exactly the float32 values, as doubles: written by
    the shortest text of each float32 value widened to float64 (repr), so the command line reads
    the doubles the add-on gets from a shape key. (Nine significant digits identify a float32,
    but the command line parses them as a double, which is then another number: 0.461939752 for
    the float32 0.4619397521018982, 4.6e-9 off.)"""
    with open(path, "w") as f:
        for v in np.asarray(vertices, dtype=np.float32).astype(np.float64):
            f.write("v %s %s %s\n" % tuple(repr(float(c)) for c in v))
        for t in tris:
            f.write("f %d %d %d\n" % tuple(int(i) + 1 for i in t))


def read_obj_vertices(path):
    with open(path) as f:
        return np.array([[float(x) for x in line.split()[1:4]] for line in f
                         if line.startswith("v ")], dtype=np.float64)


def run_cli(config_path):
    check(os.access(CLI, os.X_OK), f"command line built at {CLI}")
    done = subprocess.run([CLI, config_path], capture_output=True, text=True)
    if done.returncode != 0:
        log(done.stdout, done.stderr)
    check(done.returncode == 0, f"seqmassage {os.path.basename(config_path)} exits 0")
    return done


def finish(main):
    """Runs `main`; any exception fails Blender (with --python-exit-code 1)."""
    try:
        main()
    except BaseException:
        import traceback

        traceback.print_exc()
        sys.stdout.flush()
        sys.exit(1)
    log("PASSED")
