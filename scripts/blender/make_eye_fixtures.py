"""Cameras with known lenses, sensors and fits: test/fixtures/eyes/cameras.blend.

    blender -b --factory-startup --python-exit-code 1 --python scripts/blender/make_eye_fixtures.py -- [OUTDIR]

OUTDIR defaults to test/fixtures/eyes.  Writes cameras.blend, dump.py's
cameras.json beside it, and expected.json: for every camera under the
empty "eyes", what Blender itself says of it, read back from the saved
file: its settings, `angle`, `angle_x`, `angle_y` (radians) and the
projection matrix `calc_matrix_camera` gives for the eye's image size
(the `eye` property's :resolution, 64 x 48 when it has none), from which
the fields of view across and up the image follow (2 atan(1 / m[0][0]),
2 atan(1 / m[1][1]) for a perspective camera).  A box `body` gives the
cameras a segment to sit on.
"""

import json
import math
import os
import re
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import dump  # noqa: E402
from make_fixtures import box_mesh, empty_file, new_object, save, update  # noqa: E402

# name, type, lens, sensor w, h, fit, clip start, end, ortho scale, shift x, y, resolution
CAMERAS = [
    ("horizontal", "PERSP", 35.0, 36.0, 24.0, "HORIZONTAL", 0.1, 100.0, 7.0, 0.0, 0.0, [64, 48]),
    ("vertical", "PERSP", 50.0, 36.0, 24.0, "VERTICAL", 0.1, 100.0, 7.0, 0.0, 0.0, [64, 48]),
    ("auto-landscape", "PERSP", 28.0, 32.0, 18.0, "AUTO", 0.05, 20.0, 7.0, 0.0, 0.0, [80, 40]),
    ("auto-portrait", "PERSP", 28.0, 32.0, 18.0, "AUTO", 0.05, 20.0, 7.0, 0.0, 0.0, [40, 80]),
    ("horizontal-portrait", "PERSP", 20.0, 36.0, 24.0, "HORIZONTAL", 0.2, 30.0, 7.0, 0.0, 0.0, [48, 96]),
    ("vertical-portrait", "PERSP", 70.0, 24.0, 36.0, "VERTICAL", 0.2, 30.0, 7.0, 0.0, 0.0, [30, 60]),
    ("square", "PERSP", 18.0, 36.0, 24.0, "AUTO", 0.01, 1000.0, 7.0, 0.0, 0.0, [32, 32]),
    ("shifted", "PERSP", 50.0, 36.0, 24.0, "AUTO", 0.1, 100.0, 7.0, 0.1, -0.05, [64, 64]),
    ("ortho", "ORTHO", 50.0, 36.0, 24.0, "AUTO", 0.1, 100.0, 3.0, 0.0, 0.0, [64, 32]),
    ("ortho-portrait", "ORTHO", 50.0, 36.0, 24.0, "AUTO", 0.1, 100.0, 2.5, 0.0, 0.0, [24, 48]),
    ("default", "PERSP", 50.0, 36.0, 24.0, "AUTO", 0.1, 100.0, 7.0, 0.0, 0.0, None),
]


def build():
    empty_file()
    new_object("body", box_mesh("body", 2.0, 2.0, 0.5)).__setitem__("mass", 1.0)
    root = new_object("eyes", None)
    for i, (name, kind, lens, sw, sh, fit, near, far, ortho, sx, sy, res) in enumerate(CAMERAS):
        cam = bpy.data.cameras.new(name)
        cam.type = kind
        cam.lens = lens
        cam.sensor_width = sw
        cam.sensor_height = sh
        cam.sensor_fit = fit
        cam.clip_start = near
        cam.clip_end = far
        cam.ortho_scale = ortho
        cam.shift_x = sx
        cam.shift_y = sy
        # on the box's top, spread along X, looking up
        obj = new_object(name, cam, parent=root, location=(-1.8 + 0.36 * i, 0.0, 0.55))
        if res is not None:
            obj["eye"] = "{:resolution [%d %d]}" % tuple(res)
    update()


def expected():
    depsgraph = bpy.context.evaluated_depsgraph_get()
    out = {}
    for obj in sorted(bpy.data.objects["eyes"].children, key=lambda o: o.name):
        cam = obj.data
        m = re.search(r"\[(\d+) (\d+)\]", obj.get("eye", ""))
        w, h = (int(m.group(1)), int(m.group(2))) if m else (64, 48)
        p = obj.calc_matrix_camera(depsgraph, x=w, y=h, scale_x=1.0, scale_y=1.0)
        rows = [[p[i][j] for j in range(4)] for i in range(4)]
        e = {"type": cam.type, "lens": cam.lens, "sensor_width": cam.sensor_width,
             "sensor_height": cam.sensor_height, "sensor_fit": cam.sensor_fit,
             "clip_start": cam.clip_start, "clip_end": cam.clip_end,
             "ortho_scale": cam.ortho_scale, "shift_x": cam.shift_x, "shift_y": cam.shift_y,
             "angle": cam.angle, "angle_x": cam.angle_x, "angle_y": cam.angle_y,
             "resolution": [w, h], "projection": rows}
        if cam.type == "PERSP":
            e["fov_x"] = 2.0 * math.atan(1.0 / rows[0][0])
            e["fov_y"] = 2.0 * math.atan(1.0 / rows[1][1])
        else:
            e["width"] = 2.0 / rows[0][0]
            e["height"] = 2.0 / rows[1][1]
        out[obj.name] = e
    return out


def main():
    args = dump.script_args()
    out = os.path.abspath(args[0]) if args else os.path.normpath(
        os.path.join(HERE, "..", "..", "test", "fixtures", "eyes"))
    os.makedirs(out, exist_ok=True)
    print("Blender", bpy.app.version_string, "->", out)
    build()
    path = os.path.join(out, "cameras.blend")
    save(path)   # re-opens the saved file: expected() reads what was saved
    with open(os.path.join(out, "expected.json"), "w") as f:
        json.dump({"blender_version": bpy.app.version_string, "cameras": expected()},
                  f, indent=1, sort_keys=True)
        f.write("\n")
    print("wrote", os.path.join(out, "expected.json"))


if __name__ == "__main__":
    main()
