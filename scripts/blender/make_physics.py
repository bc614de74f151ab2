"""Build physics.blend: a creature made only with Blender's Physics tab.

Runs inside Blender 3.4 and the bpy 4.5 / 5.0 PyPI modules:

    blender -b --factory-startup --python-exit-code 1 --python make_physics.py -- OUTDIR
    /work/venvs/bpy50/bin/python make_physics.py OUTDIR

Writes OUTDIR/physics.blend and OUTDIR/physics.json (dump_physics.py of the
saved file, re-opened).  No custom property drives the physics: every body
is a Rigid Body and every joint a Rigid Body Constraint, set as a designer
sets them in the Physics tab.  One pair of custom-property segments
(seg-1, seg-2, joined through the "joints" empty) shares the file, to show
that both ways of making a creature can live together.

Scene (Blender axes, Z up), one station per constraint type, 4 units apart
along X.  At each station a passive box "<kind>-a" (half size 0.5) at
height 3 anchors an active body "<kind>-b" whose near face is 0.1 away on
its +X side; the constraint empty "<kind>-joint" sits in the gap:

    fixed    B box, mass 2              the pair must stay rigid
    point    B sphere                   swings about the pivot
    hinge    B triangle mesh (MESH)     axis along -Y, limits [-0.5, 0.7]
    slider   B box                      axis tilted 45 degrees down, [-0.3, 0.8]
    piston   B cylinder                 as slider, turning about the axis too
    generic  B convex hull              linear locked, angular x, y locked,
                                        z in [-0.3, 0.3]; breaks at 50
    spring   B capsule (GENERIC_SPRING) hangs on a spring along Z, k = 50
    motor    B cone, hinged about Z by "motor-hinge", spun by a MOTOR
             whose X axis points up: 2 rad/s, max impulse 10

plus "ground", a passive MESH plane, "ball", an active sphere dropped on
it, and "lift", a passive box animated (kinematic).
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dump  # noqa: E402
import dump_physics  # noqa: E402
import make_fixtures as mf  # noqa: E402


def uv_sphere_mesh(name, radius=0.5, rings=6, segments=8):
    verts = [(0.0, 0.0, -radius)]
    for i in range(1, rings):
        t = math.pi * i / rings - math.pi / 2
        for j in range(segments):
            a = 2 * math.pi * j / segments
            verts.append((radius * math.cos(t) * math.cos(a),
                          radius * math.cos(t) * math.sin(a), radius * math.sin(t)))
    verts.append((0.0, 0.0, radius))
    top = len(verts) - 1
    faces = [(0, 1 + (j + 1) % segments, 1 + j) for j in range(segments)]
    for i in range(rings - 2):
        for j in range(segments):
            a = 1 + i * segments + j
            b = 1 + i * segments + (j + 1) % segments
            faces.append((a, b, b + segments, a + segments))
    last = 1 + (rings - 2) * segments
    faces += [(last + j, last + (j + 1) % segments, top) for j in range(segments)]
    return mf.mesh_from(name, verts, faces)


def cone_mesh(name, radius=0.5, depth=1.0, sides=8):
    h = depth / 2.0
    verts = [(radius * math.cos(2 * math.pi * i / sides),
              radius * math.sin(2 * math.pi * i / sides), -h) for i in range(sides)]
    verts.append((0.0, 0.0, h))
    faces = [(i, (i + 1) % sides, sides) for i in range(sides)]
    faces.append(tuple(reversed(range(sides))))
    return mf.mesh_from(name, verts, faces)


def octahedron_mesh(name, rx=0.5, ry=0.4, rz=0.45):
    verts = [(rx, 0, 0), (-rx, 0, 0), (0, ry, 0), (0, -ry, 0), (0, 0, rz), (0, 0, -rz)]
    faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4),
             (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    return mf.mesh_from(name, verts, faces)


def activate(obj):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)


def rigid_body(obj, kind="ACTIVE", shape="BOX", mass=1.0, friction=0.5,
               restitution=0.0, linear_damping=0.04, angular_damping=0.1):
    activate(obj)
    bpy.ops.rigidbody.object_add(type=kind)
    rb = obj.rigid_body
    rb.collision_shape = shape
    rb.mass = mass
    rb.friction = friction
    rb.restitution = restitution
    rb.linear_damping = linear_damping
    rb.angular_damping = angular_damping
    return rb


def constraint(name, kind, a, b, location, rotation=(0, 0, 0)):
    empty = mf.new_object(name, None, location=location, rotation=rotation)
    empty.empty_display_size = 0.3
    activate(empty)
    bpy.ops.rigidbody.constraint_add(type=kind)
    rbc = empty.rigid_body_constraint
    rbc.object1 = a
    rbc.object2 = b
    return rbc


def station(kind, x, b_mesh, b_shape, b_mass=1.0, **b_args):
    """A passive anchor box and an active body beside it; returns (a, b, pivot)."""
    a = mf.new_object(kind + "-a", mf.box_mesh(kind + "-a", 0.5, 0.5, 0.5),
                      location=(x, 0.0, 3.0))
    rigid_body(a, "PASSIVE", "BOX")
    b = mf.new_object(kind + "-b", b_mesh, location=(x + 1.1, 0.0, 3.0))
    rigid_body(b, "ACTIVE", b_shape, mass=b_mass, **b_args)
    return a, b, (x + 0.55, 0.0, 3.0)


def build():
    mf.empty_file()
    sc = mf.scene()
    sc.frame_end = 250
    x = iter(range(0, 100, 4))

    ground = mf.new_object("ground", mf.mesh_from(
        "ground", [(-12, -6, 0), (40, -6, 0), (40, 6, 0), (-12, 6, 0)], [(0, 1, 2, 3)]))
    rigid_body(ground, "PASSIVE", "MESH", friction=0.8)

    ball = mf.new_object("ball", uv_sphere_mesh("ball", 0.4), location=(-4.0, 3.0, 2.0))
    rigid_body(ball, "ACTIVE", "SPHERE", mass=0.5, restitution=0.3)

    lift = mf.new_object("lift", mf.box_mesh("lift", 0.4, 0.4, 0.1), location=(-4.0, -3.0, 1.0))
    rigid_body(lift, "PASSIVE", "BOX")
    lift.rigid_body.kinematic = True

    # FIXED: a cantilever that must not sag
    a, b, p = station("fixed", next(x), mf.box_mesh("fixed-b", 0.5, 0.5, 0.5), "BOX", 2.0,
                      friction=0.7, restitution=0.1, linear_damping=0.2, angular_damping=0.3)
    constraint("fixed-joint", "FIXED", a, b, p)

    # POINT
    a, b, p = station("point", next(x), uv_sphere_mesh("point-b", 0.5), "SPHERE", 1.5)
    rbc = constraint("point-joint", "POINT", a, b, p)
    rbc.disable_collisions = True

    # HINGE about -Y (the empty's Z), B falls to the upper limit
    a, b, p = station("hinge", next(x), mf.box_mesh("hinge-b", 0.5, 0.5, 0.5), "MESH", 1.0)
    rbc = constraint("hinge-joint", "HINGE", a, b, p, rotation=(math.pi / 2, 0, 0))
    rbc.use_limit_ang_z = True
    rbc.limit_ang_z_lower = -0.5
    rbc.limit_ang_z_upper = 0.7
    rbc.use_override_solver_iterations = True
    rbc.solver_iterations = 30

    # SLIDER along the empty's X, tilted 45 degrees down
    a, b, p = station("slider", next(x), mf.box_mesh("slider-b", 0.5, 0.5, 0.5), "BOX", 1.0)
    rbc = constraint("slider-joint", "SLIDER", a, b, p, rotation=(0, math.pi / 4, 0))
    rbc.use_limit_lin_x = True
    rbc.limit_lin_x_lower = -0.3
    rbc.limit_lin_x_upper = 0.8
    rbc.disable_collisions = False

    # PISTON: slides and turns about the same axis
    a, b, p = station("piston", next(x), mf.cylinder_mesh("piston-b", 8, 0.4, 1.0),
                      "CYLINDER", 1.0)
    rbc = constraint("piston-joint", "PISTON", a, b, p, rotation=(0, math.pi / 4, 0))
    rbc.use_limit_lin_x = True
    rbc.limit_lin_x_lower = -0.2
    rbc.limit_lin_x_upper = 0.6
    rbc.use_limit_ang_x = True
    rbc.limit_ang_x_lower = -1.0
    rbc.limit_ang_x_upper = 1.0

    # GENERIC: a limited hinge made of six limits, breakable
    a, b, p = station("generic", next(x), octahedron_mesh("generic-b"), "CONVEX_HULL", 1.0)
    rbc = constraint("generic-joint", "GENERIC", a, b, p, rotation=(math.pi / 2, 0, 0))
    for axis in "xyz":
        setattr(rbc, "use_limit_lin_" + axis, True)
        setattr(rbc, "limit_lin_%s_lower" % axis, 0.0)
        setattr(rbc, "limit_lin_%s_upper" % axis, 0.0)
    for axis, (lo, hi) in zip("xyz", [(0.0, 0.0), (0.0, 0.0), (-0.3, 0.3)]):
        setattr(rbc, "use_limit_ang_" + axis, True)
        setattr(rbc, "limit_ang_%s_lower" % axis, lo)
        setattr(rbc, "limit_ang_%s_upper" % axis, hi)
    rbc.use_breaking = True
    rbc.breaking_threshold = 50.0

    # GENERIC_SPRING: hangs on a vertical spring, free only along Z
    a, b, p = station("spring", next(x), mf.cylinder_mesh("spring-b", 8, 0.3, 1.2),
                      "CAPSULE", 1.0)
    rbc = constraint("spring-joint", "GENERIC_SPRING", a, b, p)
    for axis, (lo, hi) in zip("xyz", [(0.0, 0.0), (0.0, 0.0), (-1.0, 1.0)]):
        setattr(rbc, "use_limit_lin_" + axis, True)
        setattr(rbc, "limit_lin_%s_lower" % axis, lo)
        setattr(rbc, "limit_lin_%s_upper" % axis, hi)
    for axis in "xyz":
        setattr(rbc, "use_limit_ang_" + axis, True)
        setattr(rbc, "limit_ang_%s_lower" % axis, 0.0)
        setattr(rbc, "limit_ang_%s_upper" % axis, 0.0)
    rbc.use_spring_z = True
    rbc.spring_stiffness_z = 50.0
    rbc.spring_damping_z = 2.0
    rbc.use_spring_ang_x = True
    rbc.spring_stiffness_ang_x = 5.0
    rbc.spring_damping_ang_x = 0.5

    # MOTOR on a vertical hinge: the motor turns about its own X, set upright
    a, b, p = station("motor", next(x), cone_mesh("motor-b", 0.5, 1.0), "CONE", 1.0)
    rbc = constraint("motor-hinge", "HINGE", a, b, p)
    rbc = constraint("motor-joint", "MOTOR", a, b, p, rotation=(0, -math.pi / 2, 0))
    rbc.use_motor_ang = True
    rbc.motor_ang_target_velocity = 2.0
    rbc.motor_ang_max_impulse = 10.0
    rbc.use_motor_lin = False
    rbc.motor_lin_target_velocity = 0.5
    rbc.motor_lin_max_impulse = 1.0

    # the other way: custom-property segments and a "joints" empty
    s1 = mf.new_object("seg-1", mf.box_mesh("seg-1", 0.5, 0.3, 0.3), location=(-8.0, 0.0, 1.0))
    s2 = mf.new_object("seg-2", mf.box_mesh("seg-2", 0.5, 0.3, 0.3), location=(-6.98, 0.0, 1.0))
    s1["mass"] = 1.0
    s2["mass"] = 1.0
    joints = mf.new_object("joints", None, location=(0.0, 0.0, 0.0))
    mf.new_object("seg-joint", None, parent=joints, location=(-7.49, 0.0, 1.0))["joint"] = \
        "{:type :point}"

    sc.rigidbody_world.solver_iterations = 12
    sc.rigidbody_world.time_scale = 1.0
    mf.update()


def main():
    args = dump.script_args()
    if len(args) != 1:
        sys.exit("usage: make_physics.py OUTDIR")
    out = os.path.abspath(args[0])
    os.makedirs(out, exist_ok=True)
    print("Blender", bpy.app.version_string, "->", out)
    build()
    path = os.path.join(out, "physics.blend")
    mf.update()
    bpy.ops.wm.save_as_mainfile(filepath=path, check_existing=False)
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)
    dump_physics.dump_to(os.path.splitext(path)[0] + ".json")
    print("wrote", path)


if __name__ == "__main__":
    main()
