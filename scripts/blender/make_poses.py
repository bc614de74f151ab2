"""Make test/fixtures/poses/: files whose saved bone poses Blender would not
show, and a file with two scenes.

    blender -b --factory-startup --python-exit-code 1 --python scripts/blender/make_poses.py -- test/fixtures/poses

Writes, in the folder given:

- stale-pose.blend: armature `rig-a` (turned, scaled) with a chain of bones
  `root` > `mid` (connected) > `tip` (not connected), `side` (child of root,
  rolled) and `free` (child of mid, not connected); each pose bone in another
  rotation mode (XYZ, QUATERNION, AXIS_ANGLE, ZXY, YZX) with location (where
  the bone is not connected) and scale.  Armature `rig-b` hangs from rig-a's
  `tip` (a chained armature); its bones `b-root` (YXZ) > `b-end` (XZY, ZYX
  on `b-side`) are posed too.  A cube hangs from every bone (`cube-<bone>`).
  The pose was evaluated once, then every channel was changed again and the
  file saved without evaluating it: the pose matrices in the file are stale,
  as in a file written by a script that never evaluated its scene.
  Armature `rig-c` (evaluated, not changed after) has bone `held` with a
  Copy Rotation constraint and bone `driven` with a driver on its rotation:
  cortex uses their saved pose and says so.
- scenes.blend: scene `Menu` (saved as the current one: a camera and an
  empty), scene `Game` (three meshes) and scene `Empty` (nothing).

The JSON beside each file is dump.py's account of the re-opened file (what
Blender shows after evaluating it).
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dump  # noqa: E402


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.context.preferences.filepaths.save_version = 0


def cube(name, size=0.3, collection=None):
    me = bpy.data.meshes.new(name)
    import bmesh
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=size)
    bm.to_mesh(me)
    bm.free()
    o = bpy.data.objects.new(name, me)
    (collection or bpy.context.scene.collection).objects.link(o)
    return o


def armature(name, bones, location=(0, 0, 0), rotation=(0, 0, 0), scale=(1, 1, 1)):
    """bones: [(name, parent, head, tail, roll, connected)]"""
    arm = bpy.data.armatures.new(name)
    ob = bpy.data.objects.new(name, arm)
    bpy.context.scene.collection.objects.link(ob)
    ob.location = location
    ob.rotation_euler = rotation
    ob.scale = scale
    bpy.context.view_layer.objects.active = ob
    bpy.ops.object.mode_set(mode='EDIT')
    made = {}
    for bname, parent, head, tail, roll, connected in bones:
        eb = arm.edit_bones.new(bname)
        eb.head = head
        eb.tail = tail
        eb.roll = roll
        if parent:
            eb.parent = made[parent]
            eb.use_connect = connected
        made[bname] = eb
    bpy.ops.object.mode_set(mode='OBJECT')
    return ob


def hang(ob_name, rig, bone, offset=(0.2, 0.1, 0.0)):
    c = cube(ob_name)
    c.parent = rig
    c.parent_type = 'BONE'
    c.parent_bone = bone
    c.location = offset
    c.rotation_euler = (0.1, 0.2, 0.3)
    return c


def pose(rig, settings):
    for bname, mode, rot, loc, scale in settings:
        pb = rig.pose.bones[bname]
        pb.rotation_mode = mode
        if mode == 'QUATERNION':
            pb.rotation_quaternion = rot
        elif mode == 'AXIS_ANGLE':
            pb.rotation_axis_angle = rot
        else:
            pb.rotation_euler = rot
        pb.location = loc
        pb.scale = scale


def save(folder, name):
    path = os.path.join(folder, name + ".blend")
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(path), compress=False)
    return path


def stale_pose(folder):
    reset()
    a = armature("rig-a", [("root", None, (0, 0, 0), (0, 0, 1), 0.0, False),
                           ("mid", "root", (0, 0, 1), (0, 0.5, 1.8), 0.3, True),
                           ("tip", "mid", (0.2, 0.6, 2.0), (0.2, 1.2, 2.4), -0.5, False),
                           ("side", "root", (0.3, 0, 0.5), (1.0, 0, 0.6), 0.8, False),
                           ("free", "mid", (0, 0.7, 2.2), (0.1, 0.8, 2.9), 0.0, False)],
                 location=(1, -1, 0.5), rotation=(0.1, 0.0, 0.6), scale=(1.2, 1.2, 1.2))
    b = armature("rig-b", [("b-root", None, (0, 0, 0), (0, 0.8, 0), 0.2, False),
                           ("b-end", "b-root", (0, 0.8, 0), (0, 0.8, 0.7), 0.0, True),
                           ("b-side", "b-root", (0.2, 0.4, 0), (0.8, 0.4, 0.1), 0.4, False)])
    b.parent = a
    b.parent_type = 'BONE'
    b.parent_bone = "tip"
    b.location = (0.1, 0.2, -0.1)
    for rig, bones in ((a, ["root", "mid", "tip", "side", "free"]), (b, ["b-root", "b-end", "b-side"])):
        for bone in bones:
            hang("cube-" + bone, rig, bone)
    first = [("root", 'XYZ', (0.1, 0.2, 0.3), (0, 0, 0.1), (1, 1, 1)),
             ("mid", 'QUATERNION', (0.9, 0.1, 0.2, 0.0), (0, 0, 0), (1, 1, 1)),
             ("tip", 'AXIS_ANGLE', (0.5, 1, 0, 0), (0, 0.1, 0), (1, 1, 1)),
             ("side", 'ZXY', (0.0, 0.3, 0.2), (0, 0, 0), (1, 1, 1)),
             ("free", 'YZX', (0.2, 0.0, 0.1), (0, 0, 0), (1, 1, 1))]
    pose(a, first)
    pose(b, [("b-root", 'YXZ', (0.1, 0.1, 0.1), (0, 0, 0), (1, 1, 1)),
             ("b-end", 'XZY', (0.2, 0.1, 0.0), (0, 0, 0), (1, 1, 1)),
             ("b-side", 'ZYX', (0.0, 0.2, 0.3), (0, 0, 0), (1, 1, 1))])
    c = armature("rig-c", [("held", None, (0, 0, 0), (0, 0, 1), 0.0, False),
                           ("driven", None, (1, 0, 0), (1, 0, 1), 0.0, False)],
                 location=(-3, 0, 0))
    hang("cube-held", c, "held")
    hang("cube-driven", c, "driven")
    pc = c.pose.bones["held"]
    con = pc.constraints.new('COPY_ROTATION')
    con.target = a
    pc.rotation_mode = 'XYZ'
    pc.rotation_euler = (0.4, 0, 0)
    pd = c.pose.bones["driven"]
    pd.rotation_mode = 'XYZ'
    fc = pd.driver_add("rotation_euler", 0)
    fc.driver.type = 'SCRIPTED'
    fc.driver.expression = "0.7"
    bpy.context.view_layer.update()
    # now the pose the file will hold as channels, never evaluated
    pose(a, [("root", 'XYZ', (0.4, -0.3, 0.9), (0.1, 0.2, 0.3), (1.1, 0.9, 1.0)),
             ("mid", 'QUATERNION', (0.7, 0.3, -0.4, 0.5), (0.5, 0.5, 0.5), (1.0, 1.3, 1.0)),
             ("tip", 'AXIS_ANGLE', (1.1, 0.3, 1.0, -0.2), (0.2, -0.1, 0.3), (0.8, 1.0, 1.2)),
             ("side", 'ZXY', (0.5, -0.6, 0.7), (0.0, 0.3, 0.0), (1.0, 1.0, 2.0)),
             ("free", 'YZX', (-0.3, 0.8, 0.2), (0.1, 0.0, -0.2), (1.0, 1.0, 1.0))])
    pose(b, [("b-root", 'YXZ', (0.6, -0.2, 0.4), (0.1, 0.1, 0.1), (1.0, 1.2, 1.0)),
             ("b-end", 'XZY', (0.3, 0.9, -0.4), (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)),
             ("b-side", 'ZYX', (-0.5, 0.4, 0.6), (0.2, 0.0, 0.1), (0.9, 0.9, 0.9))])
    # Saving evaluates the scene first; writing the scene as a library
    # does not, so the pose matrices stay those of the first pose.
    path = os.path.abspath(os.path.join(folder, "stale-pose.blend"))
    bpy.data.libraries.write(path, {bpy.context.scene}, compress=False)
    return path


def scenes(folder):
    reset()
    menu = bpy.context.scene
    menu.name = "Menu"
    cam = bpy.data.objects.new("menu-camera", bpy.data.cameras.new("menu-camera"))
    menu.collection.objects.link(cam)
    title = bpy.data.objects.new("menu-title", None)
    menu.collection.objects.link(title)
    game = bpy.data.scenes.new("Game")
    for i, name in enumerate(["floor", "player", "crate"]):
        cube(name, 1.0, game.collection).location = (i * 2.0, 0, 0)
    bpy.data.scenes.new("Empty")
    if bpy.context.window is not None:
        bpy.context.window.scene = menu
    return save(folder, "scenes")


def main():
    args = dump.script_args()
    folder = args[0] if args else "test/fixtures/poses"
    os.makedirs(folder, exist_ok=True)
    paths = [stale_pose(folder), scenes(folder)]
    for p in paths:
        bpy.ops.wm.open_mainfile(filepath=os.path.abspath(p), load_ui=False)
        dump.dump(os.path.abspath(p)[:-len(".blend")] + ".json")
    print("made", paths)


if __name__ == "__main__":
    main()
