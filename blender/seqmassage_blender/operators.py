"""The two operators: massage an object's shape keys, massage its Mesh Cache modifier's file."""
import os

import bpy
import numpy as np

from . import loader, massaging, properties, schema

MASSAGED = ".massaged"


def _positions(collection, n):
    co = np.empty(n * 3, dtype=np.float32)
    collection.foreach_get("co", co)
    return co.reshape(n, 3).astype(np.float64)


def triangles(mesh):
    """The mesh's faces as triangles (Blender's own triangulation of polygons), m x 3 int32."""
    mesh.calc_loop_triangles()
    tris = np.empty(len(mesh.loop_triangles) * 3, dtype=np.int32)
    mesh.loop_triangles.foreach_get("vertices", tris)
    return tris.reshape(-1, 3)


def group_weights(obj, name):
    """Per-vertex weights of vertex group `name`, in the mesh's vertex order (that of its shape
    keys and of a point cache): the group's weight where a vertex is in it, 0 where it is not."""
    group = obj.vertex_groups.get(name)
    if group is None:
        raise ValueError(f"{obj.name}: no vertex group named {name!r}")
    w = np.zeros(len(obj.data.vertices), dtype=np.float64)
    index = group.index
    for v in obj.data.vertices:
        for g in v.groups:
            if g.group == index:
                w[v.index] = g.weight
                break
    return w


class _Massage:
    """What both operators share: the module, the object's options, the Massager."""

    keep_original: bpy.props.BoolProperty(
        name="Keep Original",
        description="Write the corrected positions to new shape keys named <key>.massaged "
                    "instead of replacing each key's positions")
    vertex_group: bpy.props.StringProperty(
        name="Weights", description="Vertex group whose weights are massage.vertex_weights "
                                    "(1 massages fully, 0 keeps the vertex; vertices not in the "
                                    "group: 0). Not given: the panel's choice; empty: none")

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == "MESH" and context.mode == "OBJECT"

    # Each operator defines prepare(context) -> bool (sets self.batches, or reports why not) and
    # finish(context, cancelled) -> the operator's result. From a script (execute) every batch
    # runs at once; from the panel (invoke) the operator runs modal, one batch per timer tick,
    # with Blender's progress indicator, and Esc cancels after the batch in flight: what is done
    # is kept (shape keys) as one undo step.

    def execute(self, context):
        if not self.prepare(context):
            return {"CANCELLED"}
        while self.batches.step():
            pass
        return self.finish(context, cancelled=False)

    def invoke(self, context, event):
        if not self.prepare(context):
            return {"CANCELLED"}
        wm = context.window_manager
        wm.progress_begin(0, self.batches.total)
        self._timer = wm.event_timer_add(0.01, window=context.window)
        wm.modal_handler_add(self)
        self.report({"INFO"}, f"massaging {self.batches.total} frames (Esc cancels)")
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type == "ESC" and event.value == "PRESS":
            return self._end(context, cancelled=True)
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        more = self.batches.step()
        context.window_manager.progress_update(len(self.batches.results))
        return {"RUNNING_MODAL"} if more else self._end(context, cancelled=False)

    def _end(self, context, cancelled):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        return self.finish(context, cancelled)

    def setting(self, obj, name):
        """The operator's `name` when given (from a script, or the panel's button), else the
        object's panel option of that name."""
        if self.properties.is_property_set(name) or not hasattr(obj.seqmassage, name):
            return getattr(self, name)
        return getattr(obj.seqmassage, name)

    def massager(self, context, obj, template, tris):
        """(module, Massager), or None after reporting why."""
        m = properties.module(context)
        if m is None:
            self.report({"ERROR"}, loader.status())
            return None
        if not properties.has_schema():
            properties.register_options()
        kwargs = schema.massage_kwargs(m, obj.seqmassage)
        weights = None
        vertex_group = self.setting(obj, "vertex_group")
        if vertex_group:
            if not schema.accepts(m, "vertex_weights"):
                self.report({"ERROR"}, "vertex group weights need a seqmassage module with the "
                                       "vertex weights feature (massage.vertex_weights)")
                return None
            try:
                weights = group_weights(obj, vertex_group)
            except ValueError as e:
                self.report({"ERROR"}, str(e))
                return None
        try:
            return m, massaging.make_massager(m, template, tris, kwargs, weights)
        except (ValueError, RuntimeError) as e:
            self.report({"ERROR"}, f"{obj.name}: {e}")
            return None


class SEQMASSAGE_OT_massage_shape_keys(_Massage, bpy.types.Operator):
    """Correct the texture swimming of the shape keys: every key's triangles take the basis
    key's shapes while the key keeps its surface"""

    bl_idname = "seqmassage.massage_shape_keys"
    bl_label = "Massage Shape Keys"
    bl_options = {"REGISTER", "UNDO"}

    def prepare(self, context):
        obj = context.active_object
        mesh = obj.data
        keys = mesh.shape_keys
        if keys is None or len(keys.key_blocks) < 2:
            self.report({"ERROR"}, f"{obj.name}: needs a basis shape key and at least one other")
            return False
        basis = keys.reference_key
        frames = [kb for kb in keys.key_blocks
                  if kb != basis and not kb.name.endswith(MASSAGED)]
        if not frames:
            self.report({"ERROR"}, f"{obj.name}: no shape keys besides the basis "
                                   f"(keys named *{MASSAGED} are results, not frames)")
            return False
        n = len(mesh.vertices)
        tris = triangles(mesh)
        template = _positions(basis.data, n)
        got = self.massager(context, obj, template, tris)
        if got is None:
            return False
        m, massager = got
        self.keys = [kb.name for kb in frames]
        self.batches = massaging.Batches(m, massager, template, tris,
                                         [_positions(kb.data, n) for kb in frames])
        return True

    def finish(self, context, cancelled):
        obj = context.active_object
        results = self.batches.results
        keep = self.setting(obj, "keep_original")
        blocks = obj.data.shape_keys.key_blocks
        for name, r in zip(self.keys, results):
            self.store(obj, blocks[name], r, keep)
            self.report({"INFO"} if r.ok else {"WARNING"}, massaging.describe(name, r))
        what = f"{obj.name}: {len(results)} of {len(self.keys)} shape keys"
        if cancelled:
            self.report({"WARNING"}, f"{what}: cancelled; the keys massaged so far are kept")
            if not results:
                return {"CANCELLED"}
        self.report({"INFO"}, summary(what, results))
        return {"FINISHED"}

    def store(self, obj, kb, r, keep_original):
        if not r.ok and keep_original:
            return
        target = kb
        if keep_original:
            name = kb.name + MASSAGED
            target = obj.data.shape_keys.key_blocks.get(name)
            if target is None:
                target = obj.shape_key_add(name=name, from_mix=False)
                target.relative_key = kb.relative_key
                target.slider_min, target.slider_max = kb.slider_min, kb.slider_max
        if r.ok:
            target.data.foreach_set("co", r.vertices.astype(np.float32).ravel())
        obj.data.update()


def summary(what, results):
    ok = [r for r in results if r.ok]
    failed = len(results) - len(ok)
    if not ok:
        return f"{what}: every frame failed"
    before = np.mean([r.shear_before for r in ok])
    after = np.mean([r.shear_after for r in ok])
    text = f"{what} massaged: mean shear {before:.4g} -> {after:.4g}"
    return text + (f"; {failed} failed, left as they were" if failed else "")


def mesh_cache_modifier(obj):
    active = obj.modifiers.active
    if active is not None and active.type == "MESH_CACHE":
        return active
    return next((md for md in obj.modifiers if md.type == "MESH_CACHE"), None)


def massaged_path(path):
    stem, ext = os.path.splitext(path)
    return stem + MASSAGED + ext


class SEQMASSAGE_OT_massage_mesh_cache(_Massage, bpy.types.Operator):
    """Correct the texture swimming of the Mesh Cache modifier's PC2 or MDD file against the
    object's mesh: writes <name>.massaged.pc2 (or .mdd) beside it and points the modifier at it"""

    bl_idname = "seqmassage.massage_mesh_cache"
    bl_label = "Massage Mesh Cache"
    bl_options = {"REGISTER", "UNDO"}

    def prepare(self, context):
        obj = context.active_object
        md = mesh_cache_modifier(obj)
        if md is None:
            self.report({"ERROR"}, f"{obj.name}: no Mesh Cache modifier")
            return False
        m = properties.module(context)
        if m is None:
            self.report({"ERROR"}, loader.status())
            return False
        path = bpy.path.abspath(md.filepath)
        try:
            # The module's reader: the header checked against the file's size, every position
            # finite; the format as the modifier reads the file.
            cache = m.read_point_cache(path, format=md.cache_format.lower())
        except (ValueError, OSError) as e:
            self.report({"ERROR"}, str(e))
            return False
        n = len(obj.data.vertices)
        frames, points = cache.frames.shape[0], cache.frames.shape[1]
        if points != n:
            self.report({"ERROR"}, f"{path}: {points} points, but the mesh of "
                                   f"{obj.name} has {n} vertices")
            return False
        if md.deform_mode != "OVERWRITE":
            self.report({"WARNING"}, f"{md.name}: deform mode {md.deform_mode}; the cache's "
                                     f"positions are massaged as absolute positions")
        tris = triangles(obj.data)
        template = _positions(obj.data.vertices, n)
        got = self.massager(context, obj, template, tris)
        if got is None:
            return False
        self.module, massager = got
        self.cache, self.path, self.modifier = cache, path, md.name
        self.batches = massaging.Batches(self.module, massager, template, tris, cache.frames)
        return True

    def finish(self, context, cancelled):
        results = self.batches.results
        name = os.path.basename(self.path)
        if cancelled:
            # A cache is one file: nothing is written unless every frame was massaged.
            self.report({"WARNING"}, f"{name}: cancelled after {len(results)} of "
                                     f"{self.batches.total} frames; nothing written")
            return {"CANCELLED"}
        cache = self.cache
        out = massaged_path(self.path)
        try:
            self.module.write_point_cache(out, [r.vertices for r in results], format=cache.format,
                                          start=cache.start, sample_rate=cache.sample_rate,
                                          times=cache.times or None)
        except (ValueError, OSError) as e:
            self.report({"ERROR"}, f"{out}: {e}")
            return {"CANCELLED"}
        md = context.active_object.modifiers[self.modifier]
        relative = md.filepath.startswith("//")
        md.filepath = bpy.path.relpath(out) if relative else out
        failed = [k for k, r in enumerate(results) if not r.ok]
        for k in failed[:10]:
            self.report({"WARNING"}, massaging.describe(f"frame {k}", results[k]))
        self.report({"INFO"}, summary(f"{name}: {len(results)} frames", results) +
                    f"; written to {out}")
        return {"FINISHED"}


classes = (SEQMASSAGE_OT_massage_shape_keys, SEQMASSAGE_OT_massage_mesh_cache)


def register():
    for c in classes:
        bpy.utils.register_class(c)


def unregister():
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
