"""dump.py's JSON plus what Blender's Physics tab says: the rigid body of
each object, its rigid body constraint, and the scene's rigid body world.

Same command lines as dump.py.  The output is a superset of dump.py's
schema, so the reader's own oracle test can read it too:

    {..., "objects": [{..., "rigid_body": null | {...},
                            "rigid_body_constraint": null | {...}}, ...],
     "rigid_body_world": null | {...}, "gravity": [x, y, z], "use_gravity": bool}

Property names are Blender's Python (RNA) names: rigid_body.collision_shape,
.linear_damping, ...; rigid_body_constraint.object1, .use_limit_ang_z,
.limit_ang_z_lower, ...  Object pointers become object names.
"""

import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dump  # noqa: E402

RIGID_BODY_KEYS = [
    "type", "enabled", "kinematic", "mass", "collision_shape", "friction",
    "restitution", "use_margin", "collision_margin", "linear_damping",
    "angular_damping", "use_deactivation", "use_start_deactivated",
    "deactivate_linear_velocity", "deactivate_angular_velocity", "mesh_source",
]

CONSTRAINT_KEYS = (
    ["type", "enabled", "disable_collisions", "use_breaking", "breaking_threshold",
     "use_override_solver_iterations", "solver_iterations", "spring_type",
     "use_motor_lin", "use_motor_ang", "motor_lin_target_velocity",
     "motor_ang_target_velocity", "motor_lin_max_impulse", "motor_ang_max_impulse"]
    + ["use_limit_%s_%s" % (k, a) for k in ("lin", "ang") for a in "xyz"]
    + ["limit_%s_%s_%s" % (k, a, e) for k in ("lin", "ang") for a in "xyz"
       for e in ("lower", "upper")]
    + ["use_spring_%s" % a for a in ("x", "y", "z", "ang_x", "ang_y", "ang_z")]
    + ["spring_stiffness_%s" % a for a in ("x", "y", "z", "ang_x", "ang_y", "ang_z")]
    + ["spring_damping_%s" % a for a in ("x", "y", "z", "ang_x", "ang_y", "ang_z")]
)


def _value(v):
    if isinstance(v, bpy.types.ID):
        return v.name
    return dump.convert_value(v)


def _settings(struct, keys):
    """The values of `keys` that `struct` has, as JSON data."""
    if struct is None:
        return None
    out = {}
    for k in keys:
        if hasattr(struct, k):
            out[k] = _value(getattr(struct, k))
    return out


def constraint_info(rbc):
    info = _settings(rbc, CONSTRAINT_KEYS)
    if info is not None:
        info["object1"] = rbc.object1.name if rbc.object1 is not None else None
        info["object2"] = rbc.object2.name if rbc.object2 is not None else None
    return info


def world_info(scene):
    rbw = scene.rigidbody_world
    if rbw is None:
        return None
    info = _settings(rbw, ["enabled", "time_scale", "substeps_per_frame",
                           "steps_per_second", "solver_iterations", "use_split_impulse"])
    if rbw.effector_weights is not None:
        info["effector_gravity"] = _value(rbw.effector_weights.gravity)
    info["collection"] = rbw.collection.name if rbw.collection else None
    info["constraints"] = rbw.constraints.name if rbw.constraints else None
    return info


def dump_data():
    data = dump.dump_data()
    by_name = {o.name: o for o in bpy.data.objects}
    for o in data["objects"]:
        ob = by_name[o["name"]]
        o["rigid_body"] = _settings(ob.rigid_body, RIGID_BODY_KEYS)
        o["rigid_body_constraint"] = constraint_info(ob.rigid_body_constraint)
    scene = dump.current_scene()
    data["rigid_body_world"] = world_info(scene) if scene is not None else None
    data["gravity"] = dump._vec(scene.gravity) if scene is not None else None
    data["use_gravity"] = bool(scene.use_gravity) if scene is not None else None
    return data


def dumps():
    return dump._pretty(dump_data()) + "\n"


def dump_to(path):
    with open(path, "w", encoding="utf-8") as f:
        f.write(dumps())
    return path


def main(args=None):
    import argparse

    p = argparse.ArgumentParser(prog="dump_physics.py", description=__doc__.split("\n")[0])
    p.add_argument("-i", "--input", help=".blend file to open first")
    p.add_argument("-o", "--output", help="JSON file to write (default: stdout)")
    a = p.parse_args(dump.script_args() if args is None else args)
    if a.input:
        bpy.ops.wm.open_mainfile(filepath=os.path.abspath(a.input), load_ui=False)
    if a.output:
        dump_to(a.output)
    else:
        sys.stdout.write(dumps())
        sys.stdout.flush()


if __name__ == "__main__":
    main()
