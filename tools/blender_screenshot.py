"""Run by tools/blender_screenshot.sh inside Blender with a display (Xvfb): a drifted tube with
shape keys and a Mesh Cache modifier, the add-on's panel open in a Properties editor (Object
tab) in place of the 3D viewport, then that editor saved as PNG (the argument after --) and
Blender quit."""
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "blender"))
import support  # noqa: E402

OUT = sys.argv[sys.argv.index("--") + 1]


def scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    support.enable_addon()
    support.set_module_dir()
    frames, tris = support.tube_frames(frames=24)
    obj = support.tube_object(frames, tris, "take1")
    work = support.work_dir("screenshot")
    path = os.path.join(work, "take1.pc2")
    sys.modules[support.ADDON].pointcache.write(path, "PC2", frames)
    md = obj.modifiers.new("MeshCache", "MESH_CACHE")
    md.cache_format = "PC2"
    md.filepath = path
    obj.vertex_groups.new(name="lips")
    obj.seqmassage.vertex_group = "lips"
    obj.seqmassage.iterations = 15


def maximize():
    """The 3D viewport, the largest area, becomes a Properties editor on the Object tab (an area's
    type set directly: screen operators run from a timer can crash Blender)."""
    window = bpy.context.window_manager.windows[0]
    area = max(window.screen.areas, key=lambda a: a.width * a.height)
    area.type = "PROPERTIES"
    bpy.app.timers.register(show_object_tab, first_interval=1.0)


def show_object_tab():
    area = largest()
    area.spaces.active.context = "OBJECT"
    area.tag_redraw()
    bpy.app.timers.register(shoot, first_interval=2.0)


def largest():
    window = bpy.context.window_manager.windows[0]
    return max(window.screen.areas, key=lambda a: a.width * a.height)


def shoot():
    window = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=window, area=largest()):
        bpy.ops.screen.screenshot_area(filepath=OUT)
    print("blender_screenshot: wrote", OUT, flush=True)
    bpy.ops.wm.quit_blender()


def start():
    try:
        scene()
        maximize()
    except Exception:
        import traceback

        traceback.print_exc()
        bpy.ops.wm.quit_blender()


# Before the window opens: no splash screen over the panel.
bpy.context.preferences.view.show_splash = False
bpy.app.timers.register(start, first_interval=1.0)
