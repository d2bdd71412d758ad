"""seqmassage for Blender: Mesh Massage (Winkler, Hormann, Gotsman) on shape keys and point
caches, through the seqmassage Python module. See docs/blender.md."""

bl_info = {
    "name": "seqmassage",
    "author": "seqmassage contributors",
    "version": (0, 5, 0),  # the zip takes project(VERSION) of CMakeLists.txt
    "blender": (3, 4, 0),
    "location": "Properties > Object > Mesh Massage",
    "description": "Correct texture swimming in shape keys and PC2/MDD point caches "
                   "(Mesh Massage)",
    "category": "Animation",
}

if "bpy" in locals():  # F8 / script reload: reload the submodules too
    import importlib

    for _name in ("loader", "schema", "massaging", "properties", "operators",
                  "panel"):
        if _name in locals():
            importlib.reload(locals()[_name])

import bpy  # noqa: E402

from . import loader, massaging, operators, panel, properties, schema  # noqa: E402,F401


def register():
    properties.register()
    operators.register()
    panel.register()


def unregister():
    panel.unregister()
    operators.unregister()
    properties.unregister()
