"""The operators as an artist runs them: from the UI (INVOKE_DEFAULT), modal, one batch per timer
tick with Blender's progress indicator, and Esc pressed during a long run.

Needs a window, so tests/blender/run.sh runs this file (test_modal_*.py) in a windowed Blender
on a virtual display (xvfb-run) with --enable-event-simulate, where Window.event_simulate queues
the Esc key as a user's key press would be queued. Checked:
- massage_shape_keys, cancelled after three batches: the keys massaged so far carry
  Massager.run's positions, the rest are untouched, and one undo restores every key;
- the same run not cancelled massages every key;
- massage_mesh_cache, cancelled: nothing is written, the modifier still reads the original file.
The script drives itself from bpy.app timers (the UI's event loop must run between steps) and
ends Blender; a failure exits with status 1 at once."""
import os
import sys
import traceback

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bpy  # noqa: E402
import numpy as np  # noqa: E402

from support import (check, enable_addon, key_positions, log, set_module_dir,  # noqa: E402
                     tube_frames, tube_object, work_dir)

FRAMES = 41       # keys frame_1 .. frame_40: far more batches than the three before Esc
ESC_AFTER = 3     # batches run before Esc is pressed


def ui_context():
    """A window and its largest area, for operators invoked from a timer."""
    window = bpy.context.window_manager.windows[0]
    area = max(window.screen.areas, key=lambda a: a.width * a.height)
    return dict(window=window, area=area,
                region=next(r for r in area.regions if r.type == "WINDOW"))


class Run:
    """One modal run of an operator: Batches.step is wrapped to count steps and, with
    `esc_after`, to press Esc in the window after that many steps."""

    def __init__(self, addon, esc_after):
        self.addon, self.esc_after, self.steps = addon, esc_after, 0
        self.progress = []
        batches = addon.massaging.Batches
        self.original_step = batches.step
        run = self

        def step(batches_self):
            more = run.original_step(batches_self)
            run.steps += 1
            run.done = len(batches_self.results)
            if run.esc_after and run.steps == run.esc_after:
                ui_context()["window"].event_simulate(type="ESC", value="PRESS")
            return more

        batches.step = step
        self.done = 0
        # The operator's end (timer removed, progress indicator ended, keys stored): the run is
        # over once it returns.
        base = addon.operators._Massage
        self.original_end = base._end
        self.ended = None

        def end(op_self, context, cancelled):
            result = run.original_end(op_self, context, cancelled)
            run.ended = (cancelled, result)
            return result

        base._end = end

    def restore(self):
        self.addon.massaging.Batches.step = self.original_step
        self.addon.operators._Massage._end = self.original_end


def wait_until(condition, then, timeout=120.0):
    """Calls `then()` once `condition()` holds, polling from a timer (the UI runs in between)."""
    state = {"t": 0.0}

    def poll():
        try:
            if condition():
                then()
                return None
            state["t"] += 0.05
            if state["t"] > timeout:
                raise AssertionError(f"the run did not end within {timeout} s")
            return 0.05
        except BaseException:
            fail()
    bpy.app.timers.register(poll, first_interval=0.05)


def fail():
    traceback.print_exc()
    sys.stdout.flush()
    os._exit(1)


class Test:
    def __init__(self):
        self.work = work_dir("modal_cancel")
        self.addon = enable_addon()
        set_module_dir()
        self.m = self.addon.properties.module()
        check(self.m is not None, "module found")
        check(bpy.app.background is False, "Blender runs with a window (not -b)")
        self.frames, self.tris = tube_frames(frames=FRAMES, segments=48, rings=60)
        self.obj = tube_object(self.frames, self.tris, "tube_modal")
        bpy.ops.ed.undo_push(message="tube created")

    def start(self, esc_after, operator):
        self.run = Run(self.addon, esc_after)
        self.finished = False
        with bpy.context.temp_override(**ui_context()):
            got = operator("INVOKE_DEFAULT")
        check(got == {"RUNNING_MODAL"}, f"{operator.idname()} runs modal from the UI ({got})")

    def batches_over(self):
        """True once the modal run has ended (after its finish, one tick later, so that Blender
        has taken the operator's undo step)."""
        if self.run.ended is None:
            return False
        self.ticks = getattr(self, "ticks", 0) + 1
        if self.ticks < 2:
            return False
        self.ticks = 0
        return True

    # 1. shape keys, Esc after three batches
    def shape_keys_cancel(self):
        self.start(ESC_AFTER, bpy.ops.seqmassage.massage_shape_keys)
        wait_until(self.batches_over, self.after_shape_keys_cancel)

    def after_shape_keys_cancel(self):
        run = self.run
        run.restore()
        check(run.ended == (True, {"FINISHED"}), f"Esc ends the run as cancelled, keeping what "
                                                  f"is done ({run.ended})")
        total = FRAMES - 1
        batch = self.addon.massaging.batch_size()
        check(run.steps == ESC_AFTER, f"Esc stops the run after the batch in flight "
                                      f"({run.steps} steps of {-(-total // batch)})")
        done = run.done
        check(0 < done < total, f"{done} of {total} keys massaged before Esc")
        massager = self.m.Massager(self.frames[0].astype(np.float64), self.tris)
        massaged = [k for k in range(1, done + 1) if np.array_equal(
            key_positions(self.obj, f"frame_{k}"),
            np.asarray(massager.run(self.frames[k].astype(np.float64)).vertices,
                       dtype=np.float32))]
        check(massaged == list(range(1, done + 1)),
              f"keys frame_1..frame_{done}: Massager.run's positions")
        untouched = [k for k in range(done + 1, FRAMES)
                     if np.array_equal(key_positions(self.obj, f"frame_{k}"), self.frames[k])]
        check(untouched == list(range(done + 1, FRAMES)),
              f"keys frame_{done + 1}..frame_{FRAMES - 1}: untouched after Esc")
        with bpy.context.temp_override(**ui_context()):
            bpy.ops.ed.undo()
        # Undo reloads the scene's data: the object is found again by name.
        self.obj = bpy.data.objects["tube_modal"]
        bpy.context.view_layer.objects.active = self.obj
        restored = [k for k in range(1, FRAMES)
                    if np.array_equal(key_positions(self.obj, f"frame_{k}"), self.frames[k])]
        check(len(restored) == FRAMES - 1,
              "one undo restores every key: the cancelled run is one undo step")
        self.shape_keys_whole()

    # 2. the same run, not cancelled
    def shape_keys_whole(self):
        self.start(0, bpy.ops.seqmassage.massage_shape_keys)
        wait_until(self.batches_over, self.after_shape_keys_whole)

    def after_shape_keys_whole(self):
        self.run.restore()
        check(self.run.ended == (False, {"FINISHED"}), f"uncancelled run finishes ({self.run.ended})")
        changed = [k for k in range(1, FRAMES)
                   if not np.array_equal(key_positions(self.obj, f"frame_{k}"), self.frames[k])]
        check(len(changed) == FRAMES - 1, f"uncancelled: all {FRAMES - 1} keys massaged")
        self.mesh_cache_cancel()

    # 3. mesh cache, Esc: nothing written
    def mesh_cache_cancel(self):
        path = os.path.join(self.work, "tube.pc2")
        self.m.write_point_cache(path, [f.astype(np.float64) for f in self.frames])
        obj = tube_object(self.frames, self.tris, "tube_cache", shape_keys=False)
        md = obj.modifiers.new("cache", "MESH_CACHE")
        md.cache_format, md.filepath = "PC2", path
        self.cache_path, self.cache_obj = path, obj
        self.start(ESC_AFTER, bpy.ops.seqmassage.massage_mesh_cache)
        wait_until(self.batches_over, self.after_mesh_cache_cancel)

    def after_mesh_cache_cancel(self):
        self.run.restore()
        check(self.run.ended == (True, {"CANCELLED"}), f"Esc cancels the cache run ({self.run.ended})")
        check(self.run.steps == ESC_AFTER, "Esc stops the cache run after the batch in flight")
        stem, ext = os.path.splitext(self.cache_path)
        check(not os.path.exists(stem + ".massaged" + ext), "cancelled cache: nothing written")
        check(self.cache_obj.modifiers["cache"].filepath == self.cache_path,
              "cancelled cache: the modifier still reads the original file")
        log("PASSED")
        sys.stdout.flush()
        os._exit(0)


def begin():
    try:
        Test().shape_keys_cancel()
    except BaseException:
        fail()
    return None


bpy.app.timers.register(begin, first_interval=0.5)
