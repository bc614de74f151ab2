"""Make cortex creatures with FLAT (single-sided, zero-thickness) parts.

Written by "outside designers" who followed only doc/designing-creatures.md.

Run it twice, once per Blender:

    blender -b --factory-startup --python scripts/blender/make_flat_strangers.py -- --blender 34
    /work/venvs/bpy52/bin/python scripts/blender/make_flat_strangers.py --blender 52

(from the repository's root; the files go to test/fixtures/flat-strangers,
or to $CORTEX_OUT).

The Blender 3.4 run makes fish, glider, leaf-walker, sloppy-fish,
line-blade and leaf-walker-on-plate; the Blender 5.2 run makes
flat-hexagon-paddle.  Each run merges its entries into
manifest.json beside them.

Units: metres and kilograms throughout (Blender's default unit scale 1),
Blender's axes (Z up).  The glider is a small model: about 0.30 m long,
modelled in metres at that real size.
"""

import json
import math
import os
import sys

import bpy
import bmesh
from mathutils import Euler, Matrix, Vector

HERE = os.path.dirname(os.path.abspath(__file__))
# cortex keeps them in test/fixtures/flat-strangers (CORTEX_OUT overrides)
OUT = os.environ.get("CORTEX_OUT",
                     os.path.join(HERE, "..", "..", "test", "fixtures", "flat-strangers"))
os.makedirs(OUT, exist_ok=True)

D = math.radians


# --------------------------------------------------------------------------
# small helpers


def fresh_scene(keep_camera_and_light=False):
    """An empty scene; optionally keep the factory camera and light (a
    designer who only deleted the default cube)."""
    bpy.ops.wm.read_factory_settings(use_empty=not keep_camera_and_light)
    if keep_camera_and_light:
        for ob in list(bpy.data.objects):
            if ob.type == "MESH":  # the default Cube
                bpy.data.objects.remove(ob, do_unlink=True)
    if bpy.context.object and bpy.context.object.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")


def active():
    return bpy.context.view_layer.objects.active


def name(ob, n):
    ob.name = n
    return ob


def apply_rot_scale(ob):
    """What Ctrl+A > Rotation & Scale does: bake rotation and scale into
    the mesh, keep the location on the object."""
    loc, rot, sca = ob.matrix_basis.decompose()
    m = rot.to_matrix().to_4x4() @ Matrix.Diagonal(sca.to_4d())
    ob.data.transform(m)
    ob.data.update()
    ob.rotation_euler = (0.0, 0.0, 0.0)
    ob.scale = (1.0, 1.0, 1.0)


def apply_all(ob):
    """Ctrl+A > All Transforms."""
    ob.data.transform(ob.matrix_basis)
    ob.data.update()
    ob.matrix_basis = Matrix.Identity(4)


def plane(n, size, location, rotation=(0, 0, 0), scale=(1, 1, 1)):
    """Blender's Plane primitive (Add > Mesh > Plane): 4 vertices, 1 quad,
    zero thickness.  No Solidify."""
    bpy.ops.mesh.primitive_plane_add(size=size, location=location, rotation=rotation)
    ob = name(active(), n)
    ob.scale = scale
    return ob


def box(n, dims, location):
    """A cube primitive scaled to dims, scale applied (a closed box)."""
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=location)
    ob = name(active(), n)
    ob.scale = dims
    apply_rot_scale(ob)
    return ob


def joints_root():
    ob = bpy.data.objects.new("joints", None)
    bpy.context.scene.collection.objects.link(ob)
    ob.empty_display_type = "PLAIN_AXES"
    return ob


def joint(root, n, location, spec, rotation=(0, 0, 0), rotation_mode="XYZ"):
    """One joint empty, parented to `joints`, with its `joint` property."""
    ob = bpy.data.objects.new(n, None)
    bpy.context.scene.collection.objects.link(ob)
    ob.empty_display_type = "ARROWS"
    ob.empty_display_size = 0.05
    ob.rotation_mode = rotation_mode
    ob.location = location
    ob.rotation_euler = rotation
    ob.parent = root
    ob["joint"] = spec
    return ob


def world_verts(ob):
    mw = ob.matrix_world
    return [mw @ v.co for v in ob.data.vertices]


def thickness(ob):
    """Smallest spread of the world-space vertices about their centroid
    along any direction (via the covariance's smallest eigenvalue, found
    by brute force over directions).  0 for a flat mesh."""
    pts = world_verts(ob)
    c = sum(pts, Vector()) / len(pts)
    best = float("inf")
    steps = 90
    for i in range(steps + 1):
        th = math.pi * i / steps
        for j in range(2 * steps):
            ph = math.pi * j / steps
            n = Vector((math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)))
            ds = [(p - c).dot(n) for p in pts]
            best = min(best, max(ds) - min(ds))
    # refine with the normal of the best-fitting face, if any, for exact zeros
    for poly in ob.data.polygons:
        n = (ob.matrix_world.to_3x3().inverted().transposed() @ poly.normal).normalized()
        ds = [(p - c).dot(n) for p in pts]
        best = min(best, max(ds) - min(ds))
    return best


def is_closed(ob):
    bm = bmesh.new()
    bm.from_mesh(ob.data)
    closed = len(bm.faces) > 0 and all(len(e.link_faces) == 2 for e in bm.edges)
    bm.free()
    return closed


def collinear(ob):
    pts = world_verts(ob)
    a, b = pts[0], pts[-1]
    d = (b - a).normalized()
    return all(((p - a) - d * (p - a).dot(d)).length < 1e-6 for p in pts)


def bbox(ob):
    pts = world_verts(ob)
    lo = [min(p[i] for p in pts) for i in range(3)]
    hi = [max(p[i] for p in pts) for i in range(3)]
    return [round(x, 4) for x in lo], [round(x, 4) for x in hi]


def point_distance(ob, p):
    """Euclidean distance from world point p to the mesh of ob (0 inside a
    closed mesh); for an edges-only mesh, to its nearest edge."""
    mw = ob.matrix_world
    pts = [mw @ v.co for v in ob.data.vertices]
    if len(ob.data.polygons) == 0:
        best = float("inf")
        for e in ob.data.edges:
            a, b = pts[e.vertices[0]], pts[e.vertices[1]]
            d = b - a
            t = max(0.0, min(1.0, (p - a).dot(d) / d.length_squared))
            best = min(best, (a + d * t - p).length)
        return best
    tris = []
    for poly in ob.data.polygons:
        vs = [pts[i] for i in poly.vertices]
        for i in range(1, len(vs) - 1):
            tris.append((vs[0], vs[i], vs[i + 1]))
    from mathutils.bvhtree import BVHTree
    tree = BVHTree.FromPolygons(pts, [list(p_.vertices) for p_ in ob.data.polygons])
    loc, nrm, idx, dist = tree.find_nearest(p)
    if is_closed(ob):
        # inside test: count crossings of a ray in an odd direction
        direction = Vector((0.5773, 0.5774, 0.5775)).normalized()
        origin, hits = p.copy(), 0
        while True:
            h = tree.ray_cast(origin, direction)
            if h[0] is None:
                break
            hits += 1
            origin = h[0] + direction * 1e-7
        if hits % 2 == 1:
            return 0.0
    return dist


def r(v, k=4):
    return [round(x, k) for x in v]


def save(fname):
    path = os.path.join(OUT, fname)
    for old in (path, path + "1"):      # no stale file, no .blend1 backup
        if os.path.exists(old):
            os.remove(old)
    bpy.context.view_layer.update()
    # compressed, as many designers save (Blender 3.4: gzip; 5.2: zstd)
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
    return path


def describe(fname, notes, segment_notes, joint_meant, extra=None):
    """Manifest entry built from the scene as saved."""
    segs = []
    for ob in sorted(bpy.data.objects, key=lambda o: o.name):
        if ob.type != "MESH":
            continue
        t = thickness(ob)
        closed = is_closed(ob)
        if len(ob.data.polygons) == 0 and collinear(ob):
            kind = "degenerate: all vertices on one line, edges only"
        elif t < 1e-6:
            kind = "flat (zero-thickness)"
        elif closed:
            kind = "closed"
        else:
            kind = "open, not flat"
        lo, hi = bbox(ob)
        segs.append({
            "name": ob.name,
            "kind": kind,
            "flat": t < 1e-6,
            "closed": closed,
            "thickness_m": round(t, 6),
            "vertices": len(ob.data.vertices),
            "faces": len(ob.data.polygons),
            "mass_kg": ob.get("mass"),
            "world_bbox_min": lo,
            "world_bbox_max": hi,
            "object_location": r(ob.location),
            "object_rotation_euler_deg": r([math.degrees(a) for a in ob.rotation_euler], 2),
            "object_scale": r(ob.scale),
            "transforms_applied": (ob.rotation_euler[:] == (0.0, 0.0, 0.0)
                                   and ob.scale[:] == (1.0, 1.0, 1.0)),
            "parent": ob.parent.name if ob.parent else None,
            "modifiers": [m.type for m in ob.modifiers],
            "note": segment_notes.get(ob.name, ""),
        })
    js = []
    root = bpy.data.objects.get("joints")
    for ob in sorted(root.children if root else [], key=lambda o: o.name):
        spec = ob.get("joint")
        jtype = spec.split(":type")[1].split()[0].strip(" :}")
        js.append({
            "name": ob.name,
            "type": jtype,
            "joint_property": spec,
            "meant_to_join": joint_meant[ob.name],
            "world_location": r(ob.matrix_world.translation),
            "rotation_euler_deg": r([math.degrees(a) for a in ob.rotation_euler], 2),
            "rotation_mode": ob.rotation_mode,
            "my_euclidean_distance_to_each_segment_m": {
                s_.name: round(point_distance(s_, ob.matrix_world.translation), 4)
                for s_ in sorted(bpy.data.objects, key=lambda o: o.name) if s_.type == "MESH"},
        })
    entry = {
        "file": fname,
        "blender_version": bpy.app.version_string,
        "blender_file_version": list(bpy.data.version),
        "units": "metres, kilograms, Blender axes (Z up)",
        "notes": notes,
        "segments": segs,
        "joints": js,
        "other_objects": sorted(o.name + " (" + o.type + ")" for o in bpy.data.objects
                                if o.type not in ("MESH",) and o.name != "joints"
                                and not (o.parent and o.parent.name == "joints")),
    }
    entry["file_compression"] = compression(os.path.join(OUT, fname))
    if extra:
        entry.update(extra)
    return entry


def compression(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if head.startswith(b"BLENDER"):
        return "none; header " + head[:17].decode("ascii", "replace")
    if head.startswith(b"\x28\xb5\x2f\xfd"):
        kind = "zstd (Blender's default 'Compress' on save)"
        try:
            import subprocess
            inner = subprocess.run(["zstd", "-dc", path], capture_output=True).stdout[:17]
            kind += "; inner header " + inner.decode("ascii", "replace")
        except Exception:
            pass
        return kind
    if head.startswith(b"\x1f\x8b"):
        return "gzip"
    return "unknown: " + head.hex()


# --------------------------------------------------------------------------
# 1 and 5: the fish (tidy and sloppy)

BODY_CENTRE = Vector((0.0, 0.0, 0.5))
BODY_HALF = Vector((0.5, 0.15, 0.2))   # 1 m long along X, 0.3 wide, 0.4 tall
FIN = 0.2                               # pectoral fins: 0.2 x 0.2 m planes
DROOP = D(12)                           # pectorals droop 12 degrees
SWEEP = D(8)                            # and are swept back 8 degrees
TAIL_LEN, TAIL_H = 0.30, 0.24           # tail fin: 0.30 long, 0.24 tall


def fin_seam(side):
    """Where a pectoral fin meets the body, by eye: on the body's side at
    x=0.15, 5 cm below its middle, 3 mm inside the (smooth) ellipsoid."""
    x, dz = 0.15, -0.05
    y = BODY_HALF.y * math.sqrt(1 - (x / BODY_HALF.x) ** 2 - (dz / BODY_HALF.z) ** 2) - 0.003
    return Vector((x, side * y, BODY_CENTRE.z + dz))


def fin_rotation(side):
    # side +1: left fin (+Y).  Droop: tip down; sweep: tip towards -X.
    return Euler((-side * DROOP, 0.0, side * SWEEP), "XYZ")


def make_fish(sloppy):
    fresh_scene(keep_camera_and_light=True)

    bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8, radius=1.0,
                                         location=BODY_CENTRE)
    body = name(active(), "body")
    body.scale = BODY_HALF
    apply_rot_scale(body)          # both fish: the body itself is tidy
    body["mass"] = 2.0

    fins = {}
    for side, n in ((1, "fin-left"), (-1, "fin-right")):
        rot = fin_rotation(side)
        R = rot.to_matrix()
        seam = fin_seam(side)
        # root edge of the fin is its local -Y (left) / +Y (right) edge;
        # its midpoint goes on the seam.
        root_local = Vector((0.0, -side * FIN / 2, 0.0))
        centre = seam - R @ root_local
        if sloppy:
            # default-size plane (2 m), scaled down and rotated in object mode
            ob = plane(n, 2.0, centre, rotation=rot, scale=(FIN / 2, FIN / 2, FIN / 2))
        else:
            ob = plane(n, FIN, centre, rotation=rot)
            apply_rot_scale(ob)
        ob["mass"] = 0.05
        fins[n] = (ob, seam, rot)

    # tail fin: a vertical plane in the XZ plane behind the body,
    # overlapping the body's tip by 2 cm.
    tail_centre = Vector((-BODY_HALF.x - TAIL_LEN / 2 + 0.02, 0.0, BODY_CENTRE.z))
    tail_rot = Euler((D(90), 0.0, 0.0), "XYZ")
    if sloppy:
        tail = plane("tail-fin", 2.0, tail_centre, rotation=tail_rot,
                     scale=(TAIL_LEN / 2, TAIL_H / 2, 1.0))
    else:
        tail = plane("tail-fin", 2.0, tail_centre, rotation=tail_rot,
                     scale=(TAIL_LEN / 2, TAIL_H / 2, 1.0))
        apply_rot_scale(tail)
    tail["mass"] = 0.1
    tail_seam = Vector((-BODY_HALF.x + 0.01, 0.0, BODY_CENTRE.z))

    if sloppy:
        # Ctrl+P > Object (keep transform): the left fin follows the body.
        bpy.context.view_layer.update()
        left = fins["fin-left"][0]
        mw = left.matrix_world.copy()
        left.parent = body
        left.matrix_parent_inverse = body.matrix_world.inverted()
        bpy.context.view_layer.update()
        for a, b in zip(left.matrix_world, mw):
            assert (Vector(a) - Vector(b)).length < 1e-6

    root = joints_root()
    meant = {}
    pect = "{:type :hinge :limit [-0.6 0.6] :axis [1 0 0]}"
    for n, jn in (("fin-left", "shoulder-left"), ("fin-right", "shoulder-right")):
        ob, seam, rot = fins[n]
        side = 1 if n == "fin-left" else -1
        loc = seam.copy()
        if sloppy:
            # a hurried designer: 4 mm out from the body, 3 mm above the fin
            loc = loc + Vector((0.0, side * 0.004, 0.003))
        # empty turned like the fin, so its X runs along the fin's root
        joint(root, jn, loc, pect, rotation=rot)
        meant[jn] = ["body", n]
    tloc = tail_seam.copy()
    if sloppy:
        tloc = tloc + Vector((-0.002, 0.004, 0.0))   # 4 mm off the tail's plane
    joint(root, "tail-joint", tloc,
          "{:type :hinge :limit [(- (/ Math/PI 4)) (/ Math/PI 4)] :axis [0 0 1]}")
    meant["tail-joint"] = ["body", "tail-fin"]

    fname = "sloppy-fish.blend" if sloppy else "fish.blend"
    save(fname)

    notes = ["Body: UV sphere (16 segments, 8 rings) scaled to 1.0 x 0.3 x 0.4 m, "
             "scale applied, centre at z=0.5 (lowest point z=0.3).",
             "Pectoral fins: Plane primitive 0.2 x 0.2 m, drooped 12 deg and swept back 8 deg; "
             "the midpoint of each root edge sits 3 mm inside the body's ellipsoid "
             "(the faceted mesh lies a little inside the ellipsoid, so by the mesh there is a 1.5 mm gap "
             "between the root's midpoint and the body, and the root edge, swept 8 deg, runs into "
             "the body at its front end and leaves a ~2-3 cm gap at its back end).",
             "Tail fin: Plane primitive 0.30 x 0.24 m, vertical (XZ plane), overlapping "
             "the body's tail tip by 2 cm.",
             "Default Camera and Light left in the file (only the default Cube deleted).",
             "Hinge limits are symmetric, so which segment comes first should not matter."]
    if sloppy:
        notes += ["SLOPPY: fins made from the default 2 m Plane and scaled/rotated in object mode, "
                  "NOT applied (fin-left/right: scale 0.1, rotation (-/+12, 0, +/-8) deg; "
                  "tail-fin: rotation (90,0,0) deg, scale (0.15, 0.12, 1.0)).",
                  "SLOPPY: fin-left is parented to body (Ctrl+P keep transform: parent inverse = "
                  "inverse of body's matrix, i.e. a translation of -0.5 in z). Same world geometry as fish.blend.",
                  "SLOPPY: joint empties off the seam: shoulders 4 mm outwards (in y) and 3 mm above "
                  "the fin's plane (z); tail-joint 2 mm towards the tail and 4 mm off the tail's plane (y)."]
    return describe(fname, notes, {}, meant)


# --------------------------------------------------------------------------
# 2: the glider (0.30 m long, modelled in metres at its real size)

def make_glider():
    fresh_scene()
    FL, FW, FH = 0.30, 0.04, 0.03
    FZ = 0.10
    fus = box("fuselage", (FL, FW, FH), (0.0, 0.0, FZ))
    fus["mass"] = 0.05

    SPAN, CHORD = 0.12, 0.06     # each wing
    DIH = D(6)                   # dihedral
    root_y = FW / 2 - 0.004      # wing roots 4 mm inside the fuselage side
    root_z = FZ + 0.008          # a high-ish wing
    WX = 0.02                    # wings a little forward of the middle
    meant = {}
    root = joints_root()
    for side, n, jn in ((1, "wing-left", "wing-root-left"), (-1, "wing-right", "wing-root-right")):
        th = side * DIH          # left (+Y) tip up: +angle about X; right: -angle
        rot = Euler((th, 0.0, 0.0), "XYZ")
        R = rot.to_matrix()
        root_mid = Vector((WX, side * root_y, root_z))
        centre = root_mid - R @ Vector((0.0, -side * SPAN / 2, 0.0))
        ob = plane(n, 1.0, centre, rotation=rot, scale=(CHORD, SPAN, 1.0))
        apply_rot_scale(ob)
        ob["mass"] = 0.01
        # joint: on the wing's plane where it passes the fuselage's side
        along = (FW / 2 - root_y) / math.cos(DIH)
        jloc = root_mid + R @ Vector((0.0, side * along, 0.0))
        joint(root, jn, jloc, "{:type :hinge :limit [-0.2 0.6] :axis [1 0 0]}",
              rotation=rot)
        meant[jn] = ["fuselage", n]
    save("glider.blend")
    notes = ["Scale: the whole glider is about 0.30 m long and 0.27 m in span, modelled in "
             "metres at that size (NOT centimetres-as-metres). Fuselage 0.30 x 0.04 x 0.03 m, "
             "so it is thinner than 5 cm (the guide's small-body case).",
             "Wings: Plane primitive scaled to 0.06 (chord, X) x 0.12 (span, Y), rotated 6 deg "
             "dihedral about X (tips up), all applied. Each wing root runs 4 mm into the fuselage.",
             "Joint empties sit on each wing's plane where it leaves the fuselage's side, turned "
             "with the dihedral so their X runs along the wing root (chord direction).",
             "Limits [-0.2 0.6]: intended as 'fold up 0.6, down 0.2'. By the guide's rule "
             "(first segment = the one towards -X-Y-Z in the empty's frame) I reasoned fold-up "
             "is positive for both wings, but this is a guess."]
    return describe("glider.blend", notes, {}, meant)


# --------------------------------------------------------------------------
# 3: the leaf-walker (and the extra: on a flat ground plate)

def make_leaf_walker(with_plate=False):
    fresh_scene()
    TZ = 0.6
    torso = box("torso", (0.8, 0.4, 0.2), (0.0, 0.0, TZ))
    torso["mass"] = 3.0
    LEG = 0.4
    LW = 0.08
    bottom = TZ - 0.1            # torso's underside, z = 0.5
    foot_z = bottom - LEG        # z = 0.1
    root = joints_root()
    meant = {}
    for fx, fb in ((0.3, "front"), (-0.3, "back")):
        for sy, lr in ((0.15, "l"), (-0.15, "r")):
            leg = box(f"leg-{fb}-{lr}", (LW, LW, LEG), (fx, sy, bottom - LEG / 2))
            leg["mass"] = 0.3
            foot = plane(f"foot-{fb}-{lr}", 0.2, (fx, sy, foot_z))   # horizontal leaf
            foot["mass"] = 0.05
            hip = joint(root, f"hip-{fb}-{lr}", (fx, sy, bottom),
                        "{:type :hinge :limit [-0.6 0.6] :axis [0 1 0]}")
            meant[hip.name] = ["torso", leg.name]
            # ankle: a cone whose X axis points up the leg (empty turned -90 deg
            # about Y), rotation mode XZY as the guide asks for cones
            ank = joint(root, f"ankle-{fb}-{lr}", (fx, sy, foot_z),
                        "{:type :cone :limit-xz 0.4 :limit-xy 0.4 :twist 0.1}",
                        rotation=(0.0, D(-90), 0.0), rotation_mode="XZY")
            meant[ank.name] = [leg.name, foot.name]
    seg_notes = {}
    fname = "leaf-walker.blend"
    notes = ["Torso: box 0.8 x 0.4 x 0.2 m at z=0.6. Legs: boxes 0.08 x 0.08 x 0.4 m hanging "
             "from the torso's underside (touching it, z 0.1..0.5). Feet: Plane primitive "
             "0.2 x 0.2 m, horizontal, at z=0.1, exactly at the bottom face of each leg.",
             "Hips: hinge about Y, empty on the torso's underside at the top of each leg. Ankles: "
             "cone, empty at the centre of the leg's bottom face, which is in the foot's plane; "
             "empty rotated (0,-90,0) deg in XZY mode so its X points up the leg."]
    extra = None
    if with_plate:
        fname = "leaf-walker-on-plate.blend"
        plate = plane("ground-plate", 3.0, (0.0, 0.0, foot_z - 0.03))
        plate["mass"] = 0.0
        seg_notes["ground-plate"] = "flat ground plate, mass 0 (never moves), 3 cm below the feet"
        notes.append("EXTRA (not in the brief's list): the leaf-walker standing 3 cm above a "
                     "3 x 3 m flat ground plate (Plane primitive) with mass 0. No joint to it.")
    save(fname)
    return describe(fname, notes, seg_notes, meant, extra)


# --------------------------------------------------------------------------
# 6: the line blade (a real mistake)

def make_line_blade():
    fresh_scene()
    hub = box("hub", (0.4, 0.4, 0.4), (0.0, 0.0, 0.3))
    hub["mass"] = 1.0
    me = bpy.data.meshes.new("blade-mesh")
    xs = [0.19, 0.39, 0.59, 0.79]
    me.from_pydata([(x, 0.0, 0.0) for x in xs], [(0, 1), (1, 2), (2, 3)], [])
    me.update()
    blade = bpy.data.objects.new("blade", me)
    bpy.context.scene.collection.objects.link(blade)
    blade.location = (0.0, 0.0, 0.3)
    blade["mass"] = 0.2
    root = joints_root()
    joint(root, "blade-joint", (0.2, 0.0, 0.3), "{:type :hinge :limit [-1 1] :axis [0 0 1]}")
    save("line-blade.blend")
    notes = ["A deliberate mistake: 'blade' is a mesh of 4 collinear vertices on the X axis "
             "(x 0.19..0.79 at y=0, z=0.3) with 3 edges and no faces. It starts 1 cm inside "
             "the hub box (0.4 m cube at z=0.3). The library should refuse it with a clear "
             "message, or skip it."]
    return describe("line-blade.blend", notes, {"blade": "degenerate on purpose"},
                    {"blade-joint": ["hub", "blade"]})


# --------------------------------------------------------------------------
# 4: the flat hexagon paddle (Blender 5.2)

def make_paddle():
    fresh_scene()
    HZ = 0.2
    bpy.ops.mesh.primitive_cylinder_add(vertices=12, radius=0.03, depth=0.6,
                                        end_fill_type="NGON", location=(0.0, 0.0, HZ),
                                        rotation=(0.0, D(90), 0.0))
    handle = name(active(), "handle")
    apply_rot_scale(handle)        # the handle is tidy: along X, x -0.3..0.3
    handle["mass"] = 0.5

    # the blade: Add > Mesh > Circle, 6 vertices, Fill Type N-Gon: one hexagon face
    bpy.ops.mesh.primitive_circle_add(vertices=6, radius=0.15, fill_type="NGON",
                                      location=(0.0, 0.0, 0.0))
    pad = name(active(), "paddle")
    # sloppy: turned upright and skewed, stretched non-uniformly, NOT applied
    pad.rotation_euler = (D(90), D(0), D(4))
    pad.scale = (1.6, 0.9, 2.0)
    bpy.context.view_layer.update()
    # slide it along X until its nearest point is 2 cm inside the handle's end
    xmin = min(p.x for p in world_verts(pad))
    pad.location = (0.28 - xmin, 0.0, HZ)
    bpy.context.view_layer.update()
    pad["mass"] = 0.2

    # the joint: on the paddle's own plane, on its local X axis, 1 cm in
    # from its tip -- which lies inside the handle's end.
    mw = pad.matrix_world
    local_xmin = min(v.co.x for v in pad.data.vertices)
    jloc = mw @ Vector((local_xmin + 0.01 / pad.scale.x, 0.0, 0.0))
    # check by hand that it is inside the handle (radius 0.03, x <= 0.3)
    assert jloc.x <= 0.3 and math.hypot(jloc.y, jloc.z - HZ) < 0.03, jloc
    root = joints_root()
    joint(root, "wrist", jloc,
          "{:type :hinge :limit [(- (/ Math/PI 2)) (/ Math/PI 2)] :axis [1 0 0]}")
    save("flat-hexagon-paddle.blend")
    notes = ["Handle: Cylinder primitive, 12 sides, NGON caps, radius 0.03 m, 0.6 m long, "
             "rotated to lie along X and applied; centre at z=0.2.",
             "Paddle: Circle primitive, 6 vertices, fill N-Gon (one hexagon face, radius 0.15). "
             "Object rotation (90, 0, 4) deg and scale (1.6, 0.9, 2.0) left UNAPPLIED "
             "(the 2.0 in local Z does nothing to a flat mesh). The blade stands vertical, "
             "skewed 4 deg off the handle's axis; its tip pokes 2 cm into the handle's end.",
             "Saved by the Blender 5.2 Python module. The README says cortex reads files "
             "saved by Blender 2.48 to 5.0, so this may be outside what it supports.",
             "wrist: hinge about X (the handle's axis; empty not rotated), on the paddle's plane "
             "1 cm in from its tip, inside the handle."]
    return describe("flat-hexagon-paddle.blend", notes, {}, {"wrist": ["handle", "paddle"]})


# --------------------------------------------------------------------------

def merge_manifest(entries):
    path = os.path.join(OUT, "manifest.json")
    order = ["fish.blend", "glider.blend", "leaf-walker.blend", "flat-hexagon-paddle.blend",
             "sloppy-fish.blend", "line-blade.blend", "leaf-walker-on-plate.blend"]
    old = {}
    if os.path.exists(path):
        with open(path) as f:
            for e in json.load(f)["files"]:
                old[e["file"]] = e
    for e in entries:
        old[e["file"]] = e
    files = sorted(old.values(), key=lambda e: order.index(e["file"]) if e["file"] in order else 99)
    with open(path, "w") as f:
        json.dump({"made_by": "make_flat_strangers.py",
                   "guide_followed": "/work/main/doc/designing-creatures.md",
                   "files": files}, f, indent=2)
        f.write("\n")


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    which = argv[argv.index("--blender") + 1] if "--blender" in argv else "34"
    if which == "52":
        entries = [make_paddle()]
    else:
        entries = [make_fish(False), make_glider(), make_leaf_walker(), make_fish(True),
                   make_line_blade(), make_leaf_walker(with_plate=True)]
    merge_manifest(entries)
    for e in entries:
        print("saved", e["file"], "with Blender", e["blender_version"])


main()
