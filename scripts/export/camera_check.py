#!/usr/bin/env python3
"""What an exported camera sees in MuJoCo, beside what cortex's eye saw
(org/export.org, "The eyes in MuJoCo").

    $CORTEX_PYTHON scripts/export/camera_check.py SCENE.json OUT.json [IMAGES-DIR]

A Python script, outside cortex's Clojure code; cortex's test
(cortex.export-test/the-exported-eyes-see-what-cortex-s-eyes-see) writes
SCENE.json, runs this, and asserts on OUT.json.

SCENE.json: {"mjcf": path, "floor": {"height": h (its top, Z up)} or null,
"objects": [{"name", "type": "box" or "sphere", "pos": [x y z] (Z up),
"size": half-extents [x y z] or [radius], "colour": [r g b] (0 to 255, for
the pictures)}], "eyes": [{"name" (the MJCF camera), "width", "height",
"near", "far", "classes": [class per pixel, row 0 at the top, "" for
nothing]}]}.

Every object is added to the MJCF's world body as a geom of its own name,
and the floor as a box geom "floor" the size of cortex's (400 by 400 by 1,
its top at the floor's height). Each eye's camera is drawn at the size
the MJCF gives it (its resolution) with MuJoCo's segmentation rendering, multisampling off and the
near and far distances the eye's, the creature as built (qpos0, mj_forward);
each pixel's class is its geom's name if the geom is an object or the
floor, otherwise the name of its geom's body (a segment's id), "" where
nothing is seen.

OUT.json: {"gl": the MUJOCO_GL used, "eyes": {name: {"resolution": [w h]
(the MJCF camera's), "agreement": fraction of pixels whose classes agree
(null when the sizes differ), "classes": {class: [cortex's pixels,
MuJoCo's]}, "controls": {label: agreement of a wrong camera}}}}, or
{"skipped": why} when no GL context can be made.

The controls are cameras that are wrong on purpose, to show the
comparison can tell: the image upside down (the camera turned half a turn
about its view axis), mirrored left to right, the field of view 20% wider
(fovy times 1.2), the image's horizontal angle written as fovy, the camera turned 10 degrees to the side, and the other
eye's camera.

With IMAGES-DIR, each eye's two segmentations are written there side by
side, enlarged, as NAME.png (cortex's left, MuJoCo's right), each class in
its object's colour, the floor grey, the creature white, nothing sky blue.
"""

import json
import os
import struct
import subprocess
import sys
import zlib

PROBE = ("import mujoco\n"
         "m = mujoco.MjModel.from_xml_string('<mujoco/>')\n"
         "mujoco.Renderer(m, 8, 8).close()\n")


def choose_gl():
    """The MUJOCO_GL to use: the environment's if it is set and works,
    else the first of egl and osmesa with which a renderer can be made
    (each tried in a process of its own, since MuJoCo binds its GL when
    first imported); (None, why) when none can."""
    why = []
    for gl in [os.environ["MUJOCO_GL"]] if os.environ.get("MUJOCO_GL") else ["egl", "osmesa"]:
        p = subprocess.run([sys.executable, "-c", PROBE], env=dict(os.environ, MUJOCO_GL=gl),
                           capture_output=True, text=True, timeout=120)
        if p.returncode == 0:
            return gl, None
        last = (p.stderr.strip().splitlines() or ["exit code %d" % p.returncode])[-1]
        why.append(f"MUJOCO_GL={gl}: {last}")
    return None, "; ".join(why)


def model(scene):
    import mujoco
    spec = mujoco.MjSpec.from_file(scene["mjcf"])
    spec.visual.quality.offsamples = 0    # no multisampling: one geom per pixel
    world = spec.worldbody
    floor = scene.get("floor")
    if floor is not None:
        g = world.add_geom()
        g.name = "floor"
        g.type = mujoco.mjtGeom.mjGEOM_BOX
        g.size = [200.0, 200.0, 0.5]
        g.pos = [0.0, 0.0, floor["height"] - 0.5]
    for o in scene["objects"]:
        g = world.add_geom()
        g.name = o["name"]
        if o["type"] == "box":
            g.type = mujoco.mjtGeom.mjGEOM_BOX
            g.size = o["size"]
        else:
            g.type = mujoco.mjtGeom.mjGEOM_SPHERE
            g.size = [o["size"][0], 0.0, 0.0]
        g.pos = o["pos"]
        g.contype = 0
        g.conaffinity = 0
    return spec.compile()


def quat_mul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return [aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw]


def classes(m, d, renderer, eye, camera=None):
    """Each pixel's class, as a numpy array of strings, as camera
    `camera` (default the eye's own) sees the scene."""
    import mujoco
    import numpy as np
    extent = m.stat.extent
    m.vis.map.znear = eye["near"] / extent
    m.vis.map.zfar = eye["far"] / extent
    renderer.update_scene(d, camera=camera or eye["name"])
    seg = renderer.render()
    names = np.array([""] + [class_of(m, g) for g in range(m.ngeom)], dtype=object)
    objid = seg[:, :, 0].astype(int)
    objtype = seg[:, :, 1]
    geom = np.where((objtype == int(mujoco.mjtObj.mjOBJ_GEOM)) & (objid >= 0), objid + 1, 0)
    return names[geom]


def class_of(m, g):
    name = m.geom(g).name
    body = m.geom_bodyid[g]
    return name if body == 0 else m.body(body).name


def agreement(a, b):
    return float((a == b).mean())


def write_png(path, rgb):
    """An RGB uint8 array (rows, columns, 3) as a PNG file (zlib alone)."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))

    def chunk(tag, data):
        return (struct.pack(">I", len(data)) + tag + data
                + struct.pack(">I", zlib.crc32(tag + data) & 0xffffffff))
    with open(path, "wb") as fh:
        fh.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                 + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def picture(path, cortex, mujoco_, colours, scale=6):
    """cortex's and MuJoCo's classes side by side, a colour per class."""
    import numpy as np
    def colour(c):
        return colours.get(c, (140, 178, 230) if c == "" else (128, 128, 128) if c == "floor"
                           else (255, 255, 255))
    h, w = cortex.shape
    out = np.full((h, 2 * w + 2, 3), 255, dtype=np.uint8)
    for x0, img in [(0, cortex), (w + 2, mujoco_)]:
        for y in range(h):
            for x in range(w):
                out[y, x0 + x] = colour(img[y, x])
    write_png(path, out.repeat(scale, axis=0).repeat(scale, axis=1))


def main():
    scene = json.load(open(sys.argv[1]))
    images = sys.argv[3] if len(sys.argv) > 3 else None
    gl, why = choose_gl()
    if gl is None:
        result = {"skipped": f"no GL context for MuJoCo's renderer ({why})"}
    else:
        os.environ["MUJOCO_GL"] = gl
        import mujoco
        import numpy as np
        m = model(scene)
        d = mujoco.MjData(m)
        mujoco.mj_forward(m, d)
        result = {"gl": gl, "eyes": {}}
        eyes = scene["eyes"]
        colours = {o["name"]: tuple(o["colour"]) for o in scene["objects"] if o.get("colour")}
        for eye in eyes:
            cam = m.camera(eye["name"]).id
            w, h = (int(v) for v in m.cam_resolution[cam])
            out = result["eyes"][eye["name"]] = {"resolution": [w, h], "agreement": None}
            if (w, h) != (eye["width"], eye["height"]):
                continue
            mine = np.array(eye["classes"], dtype=object).reshape(h, w)
            r = mujoco.Renderer(m, h, w)
            r.enable_segmentation_rendering()
            seen = classes(m, d, r, eye)
            controls = {"upside down": agreement(mine, seen[::-1, ::-1]),
                        "mirrored left to right": agreement(mine, seen[:, ::-1])}
            fovy = float(m.cam_fovy[cam])
            across = np.degrees(2 * np.arctan(np.tan(np.radians(fovy) / 2) * w / h))
            for label, wrong in [("field of view 20% wider", fovy * 1.2),
                                 ("the horizontal angle as fovy", across)]:
                m.cam_fovy[cam] = wrong
                controls[label] = agreement(mine, classes(m, d, r, eye))
            m.cam_fovy[cam] = fovy
            quat = m.cam_quat[cam].copy()
            # 10 degrees about the camera's own Y (its up): a turn to the side
            a = np.radians(10.0) / 2
            m.cam_quat[cam] = quat_mul(quat, [np.cos(a), 0.0, np.sin(a), 0.0])
            mujoco.mj_forward(m, d)
            controls["turned 10 degrees to the side"] = agreement(mine, classes(m, d, r, eye))
            m.cam_quat[cam] = quat
            mujoco.mj_forward(m, d)
            for other in eyes:
                o = m.camera(other["name"]).id
                if o != cam and tuple(m.cam_resolution[o]) == (w, h):
                    controls["the other eye's camera (" + other["name"] + ")"] = \
                        agreement(mine, classes(m, d, r, eye, other["name"]))
            r.close()
            names = sorted(set(mine.ravel()) | set(seen.ravel()))
            out.update({"agreement": agreement(mine, seen),
                        "classes": {c: [int((mine == c).sum()), int((seen == c).sum())] for c in names},
                        "controls": controls})
            if images:
                os.makedirs(images, exist_ok=True)
                picture(os.path.join(images, eye["name"] + ".png"), mine, seen, colours)
    with open(sys.argv[2], "w") as fh:
        json.dump(result, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
