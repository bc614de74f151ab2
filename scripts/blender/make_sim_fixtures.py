"""Make test/fixtures/physics-sim/: one small Physics-tab scene per rule of
Blender's rigid body simulation that cortex follows, each to be simulated by
Blender itself (simulate_physics.py) and by cortex, and compared.

    blender -b --factory-startup --python-exit-code 1 --python scripts/blender/make_sim_fixtures.py -- test/fixtures/physics-sim

Writes, in the folder given, NAME.blend and NAME.json (dump_physics.py of
the re-opened file) for each NAME below; then run simulate_physics.py with
--times on each (make_sim_fixtures.sh does both).  Blender axes, Z up; every
scene has a passive box `ground` whose top is at z = 0.

ragdoll       ten boxes shaped like a figure lying just above the ground
              (torso, head, upper and lower arms and legs), joined by
              Blender's own Object > Rigid Body > Connect (GENERIC, pivot at
              the centre between the two), translation locked, each angle
              limited to [-0.4, 0.4]; collisions between joined bodies off.
addon-ragdoll a ragdoll as the Rigid Body Bones add-on writes it (see
              addon_ragdoll): ten bone-shaped boxes, GENERIC constraints at
              the bones' heads with angular limits (some locked, the head's
              locked away from the start pose), a zero-thickness ground
              plane, and the add-on sample's world: 60 fps, 1 substep a
              frame, 1 solver iteration.
rig-chain     what a rigging add-on makes of an arm: five bone-shaped bodies
              (long thin boxes along each bone's Y, turned as the bones are,
              zig-zag), each joined to its parent at the bone's head by a
              GENERIC constraint turned as the bone, translation locked,
              angles limited ([-0.3, 0.3] X, [-0.1, 0.1] Y, [-0.5, 0.5] Z),
              Disable Collisions on; the first hangs from a passive `anchor`.
kick          a rigging add-on's ragdoll-like arm whose limits were built from
              another pose than the one the bones start in: `bone-1` hangs
              from a passive `anchor`, `bone-2` to `bone-5` are a ring (a
              parallelogram, tilted) hanging from it, each bone a long thin
              box joined to its parent at its head by a GENERIC constraint
              turned as the bone, translation locked, angles limited, most of
              them so that the start pose lies 0.1 to 0.35 radians outside
              (0 is not in [0.2, 0.5] ...); `ring` closes the ring (bone-5's
              tail to bone-1's, limits around the start).  Disable
              Collisions on every constraint, and every body in a collision
              collection of its own: nothing collides.
collisions    boxes in collision collections: `a` (collection 1) lands on the
              ground (collections 1 and 2); `b` (collection 3 only) falls
              through it; `c` (collection 2) lands on `d` (collection 2,
              resting on the ground); `e` (collections 1 and 3) lands on `a`.
breaking      under a passive `beam`: `light` (mass 1) and `heavy` (mass 5)
              hang from POINT constraints that break at impulse 0.1 (Blender's
              10 substeps: 1/240 s; the heavy one's weight is 0.2 a substep,
              the light one's 0.04); `shelf` (mass 1), beside the beam, is held
              by a FIXED constraint breaking at 0.5 until `ball` (mass 4)
              lands on it.
outside       `inside` falls; `outside` has rigid body settings but was taken
              out of the RigidBodyWorld collection (Blender never moves it);
              `pair-a`/`pair-b` are joined by a FIXED constraint taken out of
              the RigidBodyConstraints collection, so they fall apart;
              `helper` is an ACTIVE body whose mesh has no vertices, joined to
              `carrier` by a FIXED constraint (a zero-size body);
              `lift` is Animated; `plate` is an ACTIVE MESH body that is not
              Dynamic, and `pebble` falls on it.
sheets        planes (four vertices, one face, no thickness) falling as
              Convex Hulls with Blender's margin: `flat` dropped flat,
              `tilted` and `steep` turned, `box-shaped` with the Box shape
              (a box no thickness thick), `on-block` onto an ACTIVE `block`;
              beside them `hull-cube`, a cube with the Convex Hull shape.
deactivation  `sleeper` starts deactivated in mid-air (deactivation on) and
              stays there until `hammer` falls on it; `rester` (deactivation
              on, thresholds 0.4 and 0.5) and `restless` (Blender's default,
              never sleeps) land on the ground.
substeps      a chain of four POINT-jointed bars from a passive `post`,
              starting level, in a world of 5 substeps a frame (2 of 1/120 s
              each cortex step), 4 solver iterations, time scale 0.5 and
              gravity (0, 0, -6).
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dump  # noqa: E402
import dump_physics  # noqa: E402
import make_fixtures as mf  # noqa: E402


def activate(*objs):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    for o in objs:
        o.select_set(True)
    bpy.context.view_layer.objects.active = objs[-1]


def box(name, half, location, rotation=(0, 0, 0), kind="ACTIVE", mass=1.0, shape="BOX",
        friction=0.5):
    o = mf.new_object(name, mf.box_mesh(name, *half), location=location, rotation=rotation)
    activate(o)
    bpy.ops.rigidbody.object_add(type=kind)
    o.rigid_body.collision_shape = shape
    o.rigid_body.mass = mass
    o.rigid_body.friction = friction
    return o


def constraint(name, kind, a, b, location, rotation=(0, 0, 0)):
    e = mf.new_object(name, None, location=location, rotation=rotation)
    activate(e)
    bpy.ops.rigidbody.constraint_add(type=kind)
    c = e.rigid_body_constraint
    c.object1 = a
    c.object2 = b
    return c


def lock_translation(c):
    for ax in "xyz":
        setattr(c, "use_limit_lin_" + ax, True)
        setattr(c, "limit_lin_%s_lower" % ax, 0.0)
        setattr(c, "limit_lin_%s_upper" % ax, 0.0)


def limit_angles(c, limits):
    for ax, (lo, hi) in zip("xyz", limits):
        setattr(c, "use_limit_ang_" + ax, True)
        setattr(c, "limit_ang_%s_lower" % ax, lo)
        setattr(c, "limit_ang_%s_upper" % ax, hi)


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.context.preferences.filepaths.save_version = 0
    bpy.ops.rigidbody.world_add()
    sc = bpy.context.scene
    sc.frame_start = 1
    sc.frame_end = 60
    sc.rigidbody_world.point_cache.frame_end = 60


def ground(half=(6, 6, 0.5), groups=None):
    g = box("ground", half, (0, 0, -half[2]), kind="PASSIVE")
    if groups:
        for i in range(20):
            g.rigid_body.collision_collections[i] = i in groups
    return g


def ragdoll():
    ground()
    z = 0.25
    parts = {  # name: (half extents, location)
        "torso": ((0.25, 0.15, 0.4), (0, 0, 1.0)),
        "head": ((0.12, 0.12, 0.12), (0, 0, 1.56)),
        "upper-arm-l": ((0.25, 0.07, 0.07), (0.55, 0, 1.3)),
        "lower-arm-l": ((0.22, 0.06, 0.06), (1.05, 0, 1.3)),
        "upper-arm-r": ((0.25, 0.07, 0.07), (-0.55, 0, 1.3)),
        "lower-arm-r": ((0.22, 0.06, 0.06), (-1.05, 0, 1.3)),
        "thigh-l": ((0.09, 0.09, 0.25), (0.14, 0, 0.33)),
        "shin-l": ((0.08, 0.08, 0.24), (0.14, 0, -0.19)),
        "thigh-r": ((0.09, 0.09, 0.25), (-0.14, 0, 0.33)),
        "shin-r": ((0.08, 0.08, 0.24), (-0.14, 0, -0.19)),
    }
    obs = {}
    for name, (half, (x, y, zz)) in parts.items():
        # the figure lies on its back, a little above the ground, tilted
        obs[name] = box(name, half, (x, zz - 0.45, z + 0.3 + 0.2 * x), rotation=(math.pi / 2, 0, 0))
    pairs = [("torso", "head"), ("torso", "upper-arm-l"), ("upper-arm-l", "lower-arm-l"),
             ("torso", "upper-arm-r"), ("upper-arm-r", "lower-arm-r"), ("torso", "thigh-l"),
             ("thigh-l", "shin-l"), ("torso", "thigh-r"), ("thigh-r", "shin-r")]
    for a, b in pairs:
        activate(obs[a], obs[b])
        before = set(bpy.data.objects.keys())
        bpy.ops.rigidbody.connect(con_type='GENERIC', pivot_type='CENTER',
                                  connection_pattern='SELECTED_TO_ACTIVE')
        made = [bpy.data.objects[n] for n in set(bpy.data.objects.keys()) - before]
        e = made[0]
        e.name = "joint-" + b
        c = e.rigid_body_constraint
        lock_translation(c)
        limit_angles(c, [(-0.4, 0.4)] * 3)
        c.disable_collisions = True


def rig_chain():
    ground()
    anchor = box("anchor", (0.2, 0.2, 0.2), (0, 0, 3.0), kind="PASSIVE")
    # bones: head, direction (unit), length; zig-zag in the XZ plane, tilted in Y
    heads = [(0.0, 0.0, 2.8)]
    dirs = [(0.6, 0.2, -0.77), (0.7, -0.1, 0.7), (0.8, 0.3, -0.52), (0.6, -0.2, 0.77), (0.9, 0.1, -0.42)]
    parent = anchor
    prev = None
    for i, d in enumerate(dirs):
        n = math.sqrt(sum(c * c for c in d))
        d = tuple(c / n for c in d)
        length = 0.6
        head = heads[-1]
        tail = tuple(h + length * c for h, c in zip(head, d))
        heads.append(tail)
        centre = tuple((h + t) / 2 for h, t in zip(head, tail))
        # the bone's frame: Y along the bone, as Blender's bones
        from mathutils import Vector
        rot = Vector((0, 1, 0)).rotation_difference(Vector(d)).to_euler()
        seg = box("bone-%d" % (i + 1), (0.06, length / 2 - 0.02, 0.05), centre, rotation=rot, mass=1.0)
        c = constraint("joint-%d" % (i + 1), "GENERIC", parent, seg, head, rotation=rot)
        lock_translation(c)
        limit_angles(c, [(-0.3, 0.3), (-0.1, 0.1), (-0.5, 0.5)])
        c.disable_collisions = True
        parent = seg


def kick():
    from mathutils import Vector
    ground()
    anchor = box("anchor", (0.2, 0.2, 0.2), (0, 0, 4.7), kind="PASSIVE")
    # each body in a collision collection of its own: nothing collides
    anchor.rigid_body.collision_collections[0] = False
    anchor.rigid_body.collision_collections[19] = True
    d = Vector((0.8, 0.2, -0.56)).normalized()
    e = Vector((-0.3, 0.5, -0.8)).normalized()
    # bone: direction, angular limits (X, Y, Z) of the joint at its head
    bones = [((0.2, 0.1, -0.97), [(0.2, 0.5), (-0.1, 0.1), (-0.5, 0.5)]),
             (tuple(d), [(-0.6, -0.3), (-0.1, 0.1), (0.15, 0.5)]),
             (tuple(e), [(-0.3, 0.3), (0.1, 0.3), (-0.5, 0.5)]),
             (tuple(-d), [(0.35, 0.7), (-0.1, 0.1), (-0.6, -0.25)]),
             (tuple(-e), [(-0.3, 0.3), (-0.1, 0.1), (0.3, 0.6)])]
    length = 0.6
    head = Vector((0.0, 0.0, 4.5))
    parent = anchor
    segs = []
    for i, (direction, limits) in enumerate(bones):
        v = Vector(direction).normalized()
        tail = head + length * v
        rot = Vector((0, 1, 0)).rotation_difference(v).to_euler()
        seg = box("bone-%d" % (i + 1), (0.06, length / 2 - 0.02, 0.05), (head + tail) / 2,
                  rotation=rot, mass=1.0)
        seg.rigid_body.collision_collections[0] = False
        seg.rigid_body.collision_collections[i + 1] = True
        c = constraint("joint-%d" % (i + 1), "GENERIC", parent, seg, tuple(head), rotation=rot)
        lock_translation(c)
        limit_angles(c, limits)
        c.disable_collisions = True
        segs.append((seg, tail, rot))
        # bone-2 hangs from bone-1's tail; bone-3 to 5 follow each other
        parent = seg
        head = tail
    b1, t1, _ = segs[0]
    b5, t5, r5 = segs[4]
    assert (t5 - t1).length < 1e-5
    c = constraint("ring", "GENERIC", b1, b5, tuple(t1), rotation=r5)
    lock_translation(c)
    limit_angles(c, [(-0.4, 0.4), (-0.2, 0.2), (-0.6, 0.6)])
    c.disable_collisions = True


# The Rigid Body Bones add-on's ragdoll (see addon_ragdoll's docstring):
# bone name: (parent, head, tail, hitbox width and depth, mass, angular
# limits X, Y, Z as the file holds them, after the add-on's flip; None
# for the root bone, which the add-on joins to its [Root] body with the
# constraint its user left unlimited).
ADDON_BONES = [
    ("torso", None, (0.0, 0.0, 1.0), (0.0, 0.0, 1.6), (0.5, 0.3), 4.0, None),
    ("head", "torso", (0.0, 0.0, 1.6), (0.0, 0.0, 1.95), (0.25, 0.25), 2.0,
     [(-0.175, -0.175), (-0.436, 0.436), (-0.349, 0.349)]),
    ("upper-arm-l", "torso", (0.28, 0.0, 1.55), (0.55, 0.0, 1.15), (0.12, 0.12), 1.0,
     [(-1.047, 1.222), (-1.571, 1.571), (-0.175, 1.571)]),
    ("forearm-l", "upper-arm-l", (0.55, 0.0, 1.15), (0.7, -0.05, 0.75), (0.1, 0.1), 1.0,
     [(0.0, 0.0), (-1.571, 1.571), (0.0, 2.269)]),
    ("upper-arm-r", "torso", (-0.28, 0.0, 1.55), (-0.55, 0.0, 1.15), (0.12, 0.12), 1.0,
     [(-1.047, 1.222), (-1.571, 1.571), (-0.175, 1.571)]),
    ("forearm-r", "upper-arm-r", (-0.55, 0.0, 1.15), (-0.7, -0.05, 0.75), (0.1, 0.1), 1.0,
     [(0.0, 0.0), (-1.571, 1.571), (0.0, 2.269)]),
    ("thigh-l", "torso", (0.13, 0.0, 1.0), (0.15, -0.02, 0.55), (0.16, 0.16), 2.0,
     [(-1.222, 1.571), (-0.785, 0.785), (-0.524, 0.436)]),
    ("shin-l", "thigh-l", (0.15, -0.02, 0.55), (0.16, 0.0, 0.1), (0.13, 0.13), 1.5,
     [(-1.745, 0.262), (-0.175, 0.175), (0.0, 0.0)]),
    ("thigh-r", "torso", (-0.13, 0.0, 1.0), (-0.15, -0.02, 0.55), (0.16, 0.16), 2.0,
     [(-1.222, 1.571), (-0.785, 0.785), (-0.524, 0.436)]),
    ("shin-r", "thigh-r", (-0.15, -0.02, 0.55), (-0.16, 0.0, 0.1), (0.13, 0.13), 1.5,
     [(-1.745, 0.262), (-0.175, 0.175), (0.0, 0.0)]),
]


# the start pose: turned (Euler XYZ) and lifted
ADDON_POSE = ((1.2, 0.1, 0.3), (0.0, 0.0, 0.6))


def addon_ragdoll():
    """A ragdoll as the Rigid Body Bones add-on (Pauan/blender-rigid-body-bones,
    1.6) writes it into a file, made here with Blender's own operators and
    settings (the add-on is not run).  What its source says it writes, and
    is mirrored: per bone an ACTIVE body `NAME [Active]`, a box hitbox
    along the bone (the bone's Y, centred on the bone: Offset Origin 0.5),
    parented to a joint empty `NAME [Head]` at the bone's head, turned as
    the bone; on that empty a GENERIC constraint (GENERIC_SPRING only when
    a spring is on: none is here) from the parent bone's body (object1) to
    the bone's (object2), Disable Collisions on, translation limited to
    [0, 0] on X, Y and Z (its defaults), breaking off with its default
    threshold 10, no solver-iteration override; the angular limits are
    stored flipped (lower = -upper of the add-on's panel), and are given
    here as the file holds them.  The root bone's constraint joins a
    PASSIVE, Animated body `Armature [Root]` whose mesh has no vertices and
    which is in no collision collection.  What it leaves as its user left
    it, and is copied from its own Ragdoll.blend sample (20 bodies, 17
    constraints): every angle limited, some angles locked (lower = upper),
    one locked away from the start pose (the head's X at -0.175, as the
    sample's neck), the root constraint unlimited (the ragdoll falls
    free), a ground that is a plane (a mesh without thickness, BOX shape),
    and the Rigid Body World at 60 fps, 1 substep per frame and 1 solver
    iteration.  Not confirmed: the add-on's exact hitbox sizes and masses
    (its defaults are 0.2 of the bone's length wide and mass 1; the
    sample's user changed them, as here), and the bone roll (here the
    shortest turn from Y to the bone).  The figure lies leaning back, its
    lowest point 0.2 above the ground, and lands at about 0.35 s; the pose
    was chosen so that Blender itself is well conditioned (lifted 1 mm
    more, Blender's own bodies move 0.11% of the figure's size at 1 s and
    0.25% at 4 s; the sample's stand-up fall from 2 units moves 2.1% and
    5.2%), so that the comparison judges the engine, not chaos."""
    from mathutils import Euler, Vector
    sc = bpy.context.scene
    sc.render.fps = 60
    sc.frame_end = 300
    w = sc.rigidbody_world
    w.substeps_per_frame = 1
    w.solver_iterations = 1
    w.point_cache.frame_end = 300
    me = mf.mesh_from("ground", [(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)],
                      [(0, 1, 2, 3)])
    g = mf.new_object("ground", me)
    activate(g)
    bpy.ops.rigidbody.object_add(type='PASSIVE')
    g.rigid_body.collision_shape = 'BOX'
    root = mf.new_object("Armature [Root]", bpy.data.meshes.new("Armature [Root]"))
    activate(root)
    bpy.ops.rigidbody.object_add(type='PASSIVE')
    root.rigid_body.kinematic = True
    root.rigid_body.collision_collections[0] = False
    root.rigid_body.collision_shape = 'BOX'
    # the pose: lifted 2 units and leaning forward and sideways
    lean = Euler(ADDON_POSE[0]).to_matrix()
    lift = Vector(ADDON_POSE[1])

    def place(p):
        return lean @ Vector(p) + lift
    bodies = {}
    heads = {}
    for name, parent, head, tail, (wd, dp), mass, limits in ADDON_BONES:
        h, t = place(head), place(tail)
        d = t - h
        rot = Vector((0, 1, 0)).rotation_difference(d.normalized())
        body = box(name + " [Active]", (wd / 2, d.length / 2, dp / 2), tuple((h + t) / 2),
                   rotation=rot.to_euler(), mass=mass)
        bodies[name] = body
        e = mf.new_object(name + " [Head]", None, location=tuple(h))
        e.rotation_mode = 'QUATERNION'
        e.rotation_quaternion = rot
        heads[name] = e
        mf.update()
        # the add-on parents each joint empty to its parent bone's, and
        # each body to its joint empty, where they are
        for child, to in ((e, heads.get(parent)), (body, e)):
            if to is not None:
                world = child.matrix_world.copy()
                child.parent = to
                child.matrix_world = world
                mf.update()
        activate(e)
        bpy.ops.rigidbody.constraint_add(type='GENERIC')
        c = e.rigid_body_constraint
        c.object1 = bodies[parent] if parent else root
        c.object2 = body
        c.disable_collisions = True
        c.use_breaking = False
        c.breaking_threshold = 10.0
        c.use_override_solver_iterations = False
        if limits is None:
            for ax in "xyz":
                setattr(c, "use_limit_lin_" + ax, False)
        else:
            lock_translation(c)
            limit_angles(c, limits)


def collisions():
    ground(groups={0, 1})

    def grouped(name, loc, groups):
        o = box(name, (0.3, 0.3, 0.3), loc)
        for i in range(20):
            o.rigid_body.collision_collections[i] = i in groups
        return o
    grouped("a", (-2, 0, 1.0), {0})
    grouped("b", (0, 0, 1.0), {2})
    grouped("d", (2, 0, 0.3), {1})
    grouped("c", (2, 0, 1.5), {1})
    grouped("e", (-2, 0, 2.2), {0, 2})


def breaking():
    ground()
    beam = box("beam", (3, 0.2, 0.2), (0, 0, 4.0), kind="PASSIVE")
    light = box("light", (0.2, 0.2, 0.2), (-2, 0, 3.2), mass=1.0)
    heavy = box("heavy", (0.2, 0.2, 0.2), (-1, 0, 3.2), mass=5.0)
    for o in (light, heavy):
        c = constraint("hang-" + o.name, "POINT", beam, o, (o.location.x, 0, 3.8))
        c.use_breaking = True
        c.breaking_threshold = 0.1
    shelf = box("shelf", (0.5, 0.3, 0.05), (1.5, 0.7, 3.0), mass=1.0)
    c = constraint("hold-shelf", "FIXED", beam, shelf, (1.5, 0.2, 3.5))
    c.use_breaking = True
    c.breaking_threshold = 0.5
    box("ball", (0.15, 0.15, 0.15), (1.5, 0.7, 4.2), mass=4.0, shape="SPHERE")


def outside():
    ground()
    box("inside", (0.3, 0.3, 0.3), (-3, 0, 1.5))
    out = box("outside", (0.3, 0.3, 0.3), (-2, 0, 1.5))
    bpy.data.collections["RigidBodyWorld"].objects.unlink(out)
    a = box("pair-a", (0.3, 0.3, 0.3), (0, 0, 2.0), kind="PASSIVE")
    b = box("pair-b", (0.3, 0.3, 0.3), (0.62, 0, 2.0))
    constraint("pair-joint", "FIXED", a, b, (0.31, 0, 2.0))
    bpy.data.collections["RigidBodyConstraints"].objects.unlink(bpy.data.objects["pair-joint"])
    carrier = box("carrier", (0.3, 0.3, 0.3), (2, 0, 1.5))
    me = bpy.data.meshes.new("helper")
    helper = mf.new_object("helper", me, location=(2, 0, 2.2))
    activate(helper)
    bpy.ops.rigidbody.object_add(type='ACTIVE')
    helper.rigid_body.mass = 0.5
    helper.rigid_body.collision_shape = 'BOX'
    constraint("helper-joint", "FIXED", carrier, helper, (2, 0, 1.9))
    lift = box("lift", (0.3, 0.3, 0.3), (3.5, 0, 1.0), kind="ACTIVE")
    lift.rigid_body.kinematic = True
    plate = box("plate", (0.8, 0.8, 0.05), (-4.5, 0, 1.0), shape="MESH")
    plate.rigid_body.enabled = False
    box("pebble", (0.15, 0.15, 0.15), (-4.5, 0, 2.0), shape="SPHERE")


def deactivation():
    ground()
    s = box("sleeper", (0.3, 0.3, 0.3), (0, 0, 1.5))
    s.rigid_body.use_deactivation = True
    s.rigid_body.use_start_deactivated = True
    box("hammer", (0.2, 0.2, 0.2), (0.1, 0, 3.0), mass=2.0)
    r = box("rester", (0.3, 0.3, 0.3), (-2, 0, 0.8), rotation=(0.3, 0.2, 0))
    r.rigid_body.use_deactivation = True
    r.rigid_body.deactivate_linear_velocity = 0.4
    r.rigid_body.deactivate_angular_velocity = 0.5
    box("restless", (0.3, 0.3, 0.3), (2, 0, 0.8), rotation=(0.3, 0.2, 0))
    # an unsupported sleeper: starts deactivated and nothing wakes it
    f = box("floater", (0.2, 0.2, 0.2), (-4, 0, 2.0))
    f.rigid_body.use_deactivation = True
    f.rigid_body.use_start_deactivated = True


def substeps():
    ground()
    sc = bpy.context.scene
    w = sc.rigidbody_world
    w.substeps_per_frame = 5
    w.solver_iterations = 4
    w.time_scale = 0.5
    sc.gravity = (0, 0, -6.0)
    post = box("post", (0.1, 0.1, 0.1), (0, 0, 3.0), kind="PASSIVE")
    prev = post
    for i in range(4):
        bar = box("bar-%d" % (i + 1), (0.25, 0.05, 0.05), (0.35 + 0.6 * i, 0, 3.0), mass=1.0)
        constraint("link-%d" % (i + 1), "POINT", prev, bar, (0.05 + 0.6 * i, 0, 3.0))
        prev = bar


def plane(name, half, location, rotation=(0, 0, 0), shape="CONVEX_HULL", mass=1.0):
    """A Plane's mesh (four vertices, one face, no thickness) as an ACTIVE
    rigid body of collision `shape`, Blender's default margin (0.04)."""
    hx, hy = half
    me = bpy.data.meshes.new(name)
    me.from_pydata([(-hx, -hy, 0), (hx, -hy, 0), (hx, hy, 0), (-hx, hy, 0)], [], [(0, 1, 2, 3)])
    me.update()
    o = mf.new_object(name, me, location=location, rotation=rotation)
    activate(o)
    bpy.ops.rigidbody.object_add(type="ACTIVE")
    o.rigid_body.collision_shape = shape
    o.rigid_body.mass = mass
    return o


def sheets():
    ground()
    plane("flat", (0.3, 0.3), (-2, 0, 0.5))
    plane("tilted", (0.3, 0.2), (0, 0, 0.6), rotation=(0.5, 0, 0))
    plane("steep", (0.25, 0.25), (2, 0, 0.8), rotation=(1.2, 0.3, 0))
    plane("box-shaped", (0.25, 0.15), (0, 2, 0.7), rotation=(0.3, 0.2, 0), shape="BOX")
    box("block", (0.3, 0.3, 0.2), (0, -2, 0.2))
    plane("on-block", (0.2, 0.2), (0, -2, 0.8), rotation=(0.2, 0, 0))
    box("hull-cube", (0.2, 0.2, 0.2), (-2, 2, 0.6), rotation=(0.3, 0, 0), shape="CONVEX_HULL")


CASES = [("ragdoll", ragdoll), ("addon-ragdoll", addon_ragdoll), ("rig-chain", rig_chain), ("kick", kick), ("collisions", collisions),
         ("breaking", breaking), ("outside", outside), ("deactivation", deactivation),
         ("substeps", substeps), ("sheets", sheets)]


def main(cases=None, default_folder="test/fixtures/physics-sim"):
    """Write each of `cases` ([name, make] pairs; CASES by default), or
    those the arguments after the folder name, into the folder (the
    first argument, or `default_folder`) as NAME.blend and NAME.json."""
    cases = CASES if cases is None else cases
    args = dump.script_args()
    folder = os.path.abspath(args[0] if args else default_folder)
    only = set(args[1:])
    os.makedirs(folder, exist_ok=True)
    for name, make in cases:
        if only and name not in only:
            continue
        reset()
        make()
        mf.update()
        path = os.path.join(folder, name + ".blend")
        bpy.ops.wm.save_as_mainfile(filepath=path, check_existing=False, compress=False)
        bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)
        dump_physics.dump_to(os.path.splitext(path)[0] + ".json")
        print("wrote", path)


if __name__ == "__main__":
    main()
