"""Mirror modifiers the way other people use them, with Blender's own result.

Written by a helper session that read only what cortex's reader promises
(that it applies the Mirror modifier), not its code. Blender 3.4:

    blender -b --factory-startup --python scripts/blender/make_mirror_strangers.py -- OUTDIR [CASE ...]

Makes one .blend per case (all cases, or those named), saved compressed,
reopens it, and writes CASE.evaluated.json beside it (not CASE.json, which
would be read as dump.py's): each mesh object's modifiers
(with a Mirror's settings) and the mesh Blender evaluates: its vertices
in the object's own axes, rounded to 5 places and sorted, and its vertex
and polygon counts. test/fixtures/modifiers/strangers/ holds a choice of
them (see org/blender.org).
"""
import bpy, bmesh, sys, os, json, math
from mathutils import Matrix, Vector, Euler

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
OUT = os.path.abspath(argv[0] if argv else "/tmp/mirror-strangers/out")
ONLY = set(argv[1:])
os.makedirs(OUT, exist_ok=True)


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)


def link(ob):
    bpy.context.scene.collection.objects.link(ob)
    return ob


def mesh_object(name, verts, faces, edges=()):
    me = bpy.data.meshes.new(name + "Mesh")
    me.from_pydata([tuple(v) for v in verts], list(edges), [tuple(f) for f in faces])
    me.update()
    return link(bpy.data.objects.new(name, me))


def bm_object(name, bm):
    me = bpy.data.meshes.new(name + "Mesh")
    bm.to_mesh(me)
    bm.free()
    me.update()
    return link(bpy.data.objects.new(name, me))


def empty(name, loc=(0, 0, 0), rot=(0, 0, 0), scale=(1, 1, 1)):
    e = link(bpy.data.objects.new(name, None))
    e.empty_display_type = 'PLAIN_AXES'
    e.location, e.rotation_euler, e.scale = loc, rot, scale
    return e


def parent_keep(child, parent):
    """Like Ctrl+P > Object: keeps the child's world transform via parent inverse."""
    bpy.context.view_layer.update()
    child.parent = parent
    child.matrix_parent_inverse = parent.matrix_world.inverted()


def mirror(ob, name="Mirror", axes=(True, False, False), merge=True, thr=0.001,
           mob=None, clip=False, bisect=(False, False, False), flip=(False, False, False)):
    m = ob.modifiers.new(name, 'MIRROR')
    m.use_axis = axes
    m.use_mirror_merge = merge
    m.merge_threshold = thr
    m.use_clip = clip
    m.use_bisect_axis = bisect
    m.use_bisect_flip_axis = flip
    if mob is not None:
        m.mirror_object = mob
    return m


def half_torso(name, seam_x=None, keep_center_faces=False, full=False):
    """Half a torso: an elliptic tube for x >= 0, open at the x = 0 plane,
    capped on top with an n-gon, open at the bottom (waist)."""
    rings = [(-1.0, 0.45), (-0.5, 0.55), (0.0, 0.6), (0.5, 0.7), (0.9, 0.5), (1.1, 0.25)]
    segs = 8  # edges across the half; segs+1 vertices per ring
    verts, faces = [], []
    lo, hi = (-90, 90) if not full else (-180, 180)
    n = segs + 1 if not full else 2 * segs
    for ri, (z, r) in enumerate(rings):
        for k in range(n):
            th = math.radians(lo + (hi - lo) * k / (segs if not full else 2 * segs))
            x = r * math.cos(th)
            y = 0.7 * r * math.sin(th)
            if not full and k in (0, segs):
                x = 0.0 if seam_x is None else seam_x[ri % len(seam_x)]
            verts.append((x, y, z))
    for ri in range(len(rings) - 1):
        for k in range(n - 1 if not full else n):
            a = ri * n + k
            b = ri * n + (k + 1) % n
            faces.append((a, b, b + n, a + n))
    top = (len(rings) - 1) * n
    faces.append(tuple(range(top, top + n)))
    if keep_center_faces and not full:
        # the modeller forgot to delete the faces lying on the x = 0 plane:
        # a strip closing the back seam to the front seam at the waist.
        verts.append((0.0, 0.0, -1.0)); c = len(verts) - 1
        faces.append((0, c, segs))  # a triangle lying in x = 0
        verts.append((0.0, 0.0, -0.5)); c2 = len(verts) - 1
        faces.append((c, 0, n, c2))  # a quad in x = 0
        faces.append((c2, n + segs, segs, c))  # another in x = 0
    return mesh_object(name, verts, faces)


def tube(name, x0, segs=8, rings=((0, 0.18), (-0.6, 0.15), (-1.2, 0.12), (-1.5, 0.1)), cap=True):
    """A tapered leg along -Z centred at (x0, 0)."""
    verts, faces = [], []
    for z, r in rings:
        for k in range(segs):
            th = 2 * math.pi * k / segs
            verts.append((x0 + r * math.cos(th), r * math.sin(th), z))
    for ri in range(len(rings) - 1):
        for k in range(segs):
            a = ri * segs + k
            b = ri * segs + (k + 1) % segs
            faces.append((a, b, b + segs, a + segs))
    if cap:
        faces.append(tuple(reversed(range(segs))))
        last = (len(rings) - 1) * segs
        faces.append(tuple(range(last, last + segs)))
    return mesh_object(name, verts, faces)


def uvsphere_bm(segs=16, rings=8, radius=1.0):
    bm = bmesh.new()
    bmesh.ops.create_uvsphere(bm, u_segments=segs, v_segments=rings, radius=radius)
    return bm


def delete_where(bm, pred):
    bmesh.ops.delete(bm, geom=[v for v in bm.verts if pred(v.co)], context='VERTS')


def snap0(bm, eps=1e-6):
    for v in bm.verts:
        v.co = Vector([0.0 if abs(c) < eps else c for c in v.co])


# --------------------------------------------------------------------------
CASES = {}


def case(fn):
    CASES[fn.__name__] = fn
    return fn


@case
def torso_merge():
    ob = half_torso("Torso")
    mirror(ob)


@case
def torso_nomerge():
    ob = half_torso("Torso")
    mirror(ob, merge=False)


@case
def torso_bigmerge():
    ob = half_torso("Torso", seam_x=[0.01, 0.03, 0.08, 0.0, 0.01, 0.03])
    mirror(ob, thr=0.05)


@case
def torso_merge_zero_threshold():
    ob = half_torso("Torso")
    mirror(ob, thr=0.0)


@case
def torso_center_faces_kept():
    ob = half_torso("Torso", keep_center_faces=True)
    mirror(ob)


@case
def torso_full_forgot_delete():
    ob = half_torso("Torso", full=True)
    mirror(ob)


@case
def torso_crossing_plane_clip():
    # a few seam vertices slightly on the wrong side; Clipping on (edit-only)
    ob = half_torso("Torso", seam_x=[0.0, -0.0004, -0.02, 0.0, 0.0003, -0.1])
    mirror(ob, clip=True)


@case
def octant_xyz():
    bm = uvsphere_bm(16, 8, 1.0)
    snap0(bm)
    delete_where(bm, lambda c: c.x < 0 or c.y < 0 or c.z < 0)
    ob = bm_object("Blob", bm)
    mirror(ob, axes=(True, True, True))


@case
def stacked_x_then_y():
    bm = uvsphere_bm(16, 8, 1.0)
    snap0(bm)
    delete_where(bm, lambda c: c.x < 0 or c.y < 0)
    ob = bm_object("Quarter", bm)
    ob.scale = (1.0, 0.6, 1.3)  # unapplied scale
    mirror(ob, "MirrorX", axes=(True, False, False))
    mirror(ob, "MirrorY", axes=(False, True, False), merge=False)


@case
def mirror_y_only_and_z_only():
    bm = uvsphere_bm(12, 6, 0.5)
    snap0(bm)
    delete_where(bm, lambda c: c.y < 0)
    ob = bm_object("HalfY", bm)
    mirror(ob, axes=(False, True, False))
    bm = uvsphere_bm(12, 6, 0.5)
    snap0(bm)
    delete_where(bm, lambda c: c.z < 0)
    ob2 = bm_object("HalfZ", bm)
    ob2.location = (2, 0, 0)
    mirror(ob2, axes=(False, False, True))


@case
def leg_mirror_empty():
    e = empty("LegMirror", loc=(0.3, 0.2, 0.1), rot=(0, 0, math.radians(30)), scale=(1.0, 2.0, 0.5))
    ob = tube("Leg", 0.6)
    mirror(ob, mob=e)


@case
def leg_mirror_empty_rotscaled_obj():
    e = empty("LegMirror", loc=(0.3, 0.2, 0.1), rot=(0, 0, math.radians(30)), scale=(1.0, 2.0, 0.5))
    ob = tube("Leg", 0.6)
    ob.location = (0.5, -0.3, 1.0)
    ob.rotation_euler = (math.radians(10), math.radians(-20), math.radians(45))
    ob.scale = (1.2, 0.8, 1.5)
    mirror(ob, mob=e)


@case
def leg_mirror_empty_negscale_obj():
    e = empty("LegMirror", loc=(0.3, 0.2, 0.1), rot=(0, 0, math.radians(30)), scale=(1.0, 2.0, 0.5))
    ob = tube("Leg", 0.6)
    ob.location = (0.5, -0.3, 1.0)
    ob.rotation_euler = (0, 0, math.radians(-15))
    ob.scale = (-1.0, 0.8, 1.5)
    mirror(ob, mob=e)
    # and one with negative scale, no mirror object
    ob2 = tube("LegNeg", 0.6)
    ob2.location = (3, 0, 0)
    ob2.scale = (1.0, -1.0, 2.0)
    mirror(ob2)


@case
def leg_mirror_empty_merge_near_plane():
    # the leg's top touches the empty's plane: merge across the empty's YZ plane
    e = empty("Hips", loc=(0.5, 0.0, 0.0), rot=(0, 0, math.radians(30)))
    bpy.context.view_layer.update()
    ob = tube("Leg", 0.0, segs=8)
    # move the leg so that one ring vertex lies on the empty's plane
    # (the plane through (0.5,0,0) with normal (cos30, sin30, 0))
    n = Vector((math.cos(math.radians(30)), math.sin(math.radians(30)), 0))
    ob.location = Vector((0.5, 0, 0)) + n * 0.18  # vertex k=4 (at -x) ends near plane
    mirror(ob, mob=e, thr=0.01)


@case
def mirror_object_is_child():
    ob = tube("Leg", 0.6)
    ob.location = (0.2, 0.1, 1.0)
    ob.rotation_euler = (0, 0, math.radians(20))
    e = empty("ChildPlane", loc=(0.4, 0.3, 1.0), rot=(0, 0, math.radians(-10)))
    parent_keep(e, ob)
    mirror(ob, mob=e)


@case
def mirror_object_is_parent():
    p = empty("Pelvis", loc=(0.1, 0.2, 1.0), rot=(0, 0, math.radians(25)), scale=(1.5, 1.5, 1.5))
    ob = tube("Leg", 0.6)
    ob.location = (0.5, 0.3, 0.8)
    parent_keep(ob, p)
    mirror(ob, mob=p)


@case
def mirror_object_is_parent_raw():
    # parent set from Python without a parent inverse
    p = empty("Pelvis", loc=(0.1, 0.2, 1.0), rot=(0, 0, math.radians(25)), scale=(1.5, 1.0, 0.8))
    ob = tube("Leg", 0.6)
    ob.parent = p
    ob.location = (0.3, 0.0, -0.2)
    mirror(ob, mob=p)


@case
def parented_object_mirror():
    p = bm_object("Chest", uvsphere_bm(8, 4, 0.3))
    p.location = (1, 2, 3)
    p.rotation_euler = (math.radians(30), 0, math.radians(60))
    p.scale = (2, 1, 0.5)
    ob = half_torso("Arm")
    ob.location = (1.5, 2, 3)
    parent_keep(ob, p)
    mirror(ob)


@case
def parented_mirror_object_grandparent():
    # mirror object has its own parent chain
    g = empty("Root", loc=(0, 0, 1), rot=(0, 0, math.radians(40)), scale=(2, 2, 2))
    e = empty("Sym", loc=(0.5, 0, 0), rot=(math.radians(10), 0, 0))
    e.parent = g
    ob = tube("Leg", 1.0)
    mirror(ob, mob=e)


@case
def mirror_hidden_viewport():
    ob = half_torso("Torso")
    m = mirror(ob)
    m.show_viewport = False


@case
def mirror_render_only_off():
    ob = half_torso("Torso")
    m = mirror(ob)
    m.show_render = False  # viewport still shows it


@case
def mirror_no_axis():
    ob = half_torso("Torso")
    mirror(ob, axes=(False, False, False))


@case
def mirror_then_subsurf():
    ob = half_torso("Torso")
    mirror(ob)
    s = ob.modifiers.new("Subdivision", 'SUBSURF'); s.levels = 1


@case
def subsurf_then_mirror():
    ob = half_torso("Torso")
    s = ob.modifiers.new("Subdivision", 'SUBSURF'); s.levels = 1
    mirror(ob)


@case
def mirror_then_hidden_subsurf():
    ob = half_torso("Torso")
    mirror(ob)
    s = ob.modifiers.new("Subdivision", 'SUBSURF'); s.levels = 2
    s.show_viewport = False


@case
def mirror_then_triangulate():
    ob = half_torso("Torso")
    mirror(ob)
    ob.modifiers.new("Triangulate", 'TRIANGULATE')


@case
def mirror_bisect():
    bm = uvsphere_bm(16, 8, 1.0)
    ob = bm_object("Head", bm)  # full sphere, bisect keeps +x half and mirrors
    mirror(ob, bisect=(True, False, False))


@case
def mirror_bisect_flip():
    ob = half_torso("Torso", seam_x=[0.0, -0.1, -0.2, 0.0, -0.1, 0.0])
    mirror(ob, bisect=(True, False, False), flip=(True, False, False))


@case
def mirror_uv_materials():
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0)
    bmesh.ops.subdivide_edges(bm, edges=bm.edges[:], cuts=1, use_grid_fill=True)
    delete_where(bm, lambda c: c.x < -1e-6)
    snap0(bm)
    # remove faces lying on x = 0
    bmesh.ops.delete(bm, geom=[f for f in bm.faces if all(abs(v.co.x) < 1e-6 for v in f.verts)],
                     context='FACES_ONLY')
    ob = bm_object("Box", bm)
    me = ob.data
    me.uv_layers.new(name="UVMap")
    for i, l in enumerate(me.uv_layers[0].data):
        l.uv = ((i % 7) / 7.0, (i % 5) / 5.0)
    for nm in ("Skin", "Cloth"):
        me.materials.append(bpy.data.materials.new(nm))
    for p in me.polygons:
        p.material_index = 1 if p.center.z > 0 else 0
    m = mirror(ob)
    m.use_mirror_u = True
    m.mirror_offset_u = 0.25


@case
def head_uvsphere_half():
    bm = uvsphere_bm(24, 12, 1.0)
    bmesh.ops.subdivide_edges(bm, edges=bm.edges[:], cuts=1, use_grid_fill=True)
    delete_where(bm, lambda c: c.x < 0)  # no snapping: vertices near +-1e-17 stay as they are
    ob = bm_object("Head", bm)
    ob.scale = (0.9, 1.0, 1.15)
    mirror(ob)


@case
def mirror_vertex_groups():
    ob = half_torso("Torso")
    for nm in ("Arm.L", "Leg_L", "Spine"):
        g = ob.vertex_groups.new(name=nm)
        g.add([i for i in range(len(ob.data.vertices)) if i % 3 == len(ob.vertex_groups) % 3], 0.7, 'REPLACE')
    m = mirror(ob)
    m.use_mirror_vertex_groups = True


@case
def mirror_object_self():
    ob = half_torso("Torso")
    ob.location = (1, 1, 0)
    ob.rotation_euler = (0, 0, math.radians(30))
    mirror(ob)
    try:
        ob.modifiers["Mirror"].mirror_object = ob
    except Exception as ex:
        print("self mirror object refused:", ex)


@case
def mirror_object_mesh():
    # mirror across another mesh object (the torso), not an empty
    t = half_torso("Torso")
    t.location = (0, 0, 1.5)
    t.rotation_euler = (0, math.radians(15), 0)
    arm = tube("Arm", 0.9)
    arm.location = (0.2, 0, 2.0)
    arm.rotation_euler = (0, math.radians(80), 0)
    mirror(arm, mob=t)


@case
def linked_duplicate():
    a = half_torso("TorsoA")
    b = link(bpy.data.objects.new("TorsoB", a.data))
    b.location = (3, 0, 0)
    mirror(b)  # only B mirrors the shared mesh


@case
def loose_edges_mirror():
    # an edge chain (e.g. a guide / skin-modifier skeleton) with no faces,
    # plus a face, mirrored
    verts = [(0, 0, 0), (0.3, 0, 0.2), (0.6, 0.1, 0.3), (0.9, 0.1, 0.2), (0.4, 0.5, 0.0), (0.5, 0.6, 0.0), (0.4, 0.6, 0.1)]
    edges = [(0, 1), (1, 2), (2, 3)]
    ob = mesh_object("Guide", verts, [(4, 5, 6)], edges)
    mirror(ob)


@case
def two_mirrors_same_axis():
    # two X mirrors stacked (e.g. duplicated by accident), second one merges
    ob = half_torso("Torso")
    ob.location = (0, 0, 0)
    mirror(ob, "Mirror")
    mirror(ob, "Mirror.001")


@case
def mirror_plus_armature():
    # Mirror then an Armature modifier with no armature object (a do-nothing
    # modifier Blender still lists)
    ob = half_torso("Torso")
    mirror(ob)
    ob.modifiers.new("Armature", 'ARMATURE')



@case
def mirror_empty_on_seam_merge():
    # the torso's own x=0 seam lies on the empty's YZ plane (empty matches the
    # object's frame but is scaled non-uniformly): seam vertices merge
    ob = half_torso("Torso")
    ob.location = (1.0, 0.5, 0.0)
    ob.rotation_euler = (0, 0, math.radians(30))
    e = empty("Sym", loc=(1.0, 0.5, 0.0), rot=(0, 0, math.radians(30)), scale=(1.0, 2.0, 0.5))
    mirror(ob, mob=e)


@case
def mirror_empty_near_seam_bigmerge():
    # empty's plane 0.01 off the seam (in world X along the object's rotated x), threshold 0.05
    ob = half_torso("Torso")
    ob.rotation_euler = (0, 0, math.radians(30))
    c, s_ = math.cos(math.radians(30)), math.sin(math.radians(30))
    e = empty("Sym", loc=(0.01 * c, 0.01 * s_, 0.0), rot=(0, 0, math.radians(30)))
    mirror(ob, mob=e, thr=0.05)
    ob2 = half_torso("Torso2")
    ob2.location = (3, 0, 0)
    ob2.rotation_euler = (0, 0, math.radians(30))
    e2 = empty("Sym2", loc=(3 + 0.03 * c, 0.03 * s_, 0.0), rot=(0, 0, math.radians(30)))
    mirror(ob2, mob=e2, thr=0.05)


@case
def mirror_object_negative_scale():
    e = empty("FlippedEmpty", loc=(0.2, 0.0, 0.3), rot=(0, 0, math.radians(15)), scale=(-1.0, 1.0, 1.0))
    ob = tube("Leg", 0.6)
    mirror(ob, mob=e)
    e2 = empty("FlippedEmptyY", loc=(0.0, 0.4, 0.0), scale=(1.0, -2.0, 1.0))
    ob2 = tube("Leg2", 0.6)
    ob2.location = (2, 0, 0)
    mirror(ob2, axes=(True, True, False), mob=e2)


@case
def mirror_object_constrained_delta():
    # mirror object placed by a constraint and a delta transform
    target = empty("Target", loc=(0.4, -0.2, 0.5), rot=(0, 0, math.radians(45)))
    e = empty("Sym", loc=(0, 0, 0))
    e.delta_rotation_euler = (0, 0, math.radians(10))
    c = e.constraints.new('COPY_LOCATION'); c.target = target
    ob = tube("Leg", 0.6)
    ob.delta_location = (0.1, 0.0, 0.2)
    ob.delta_scale = (1.0, 1.5, 1.0)
    mirror(ob, mob=e)


@case
def mirror_shapekey():
    ob = half_torso("Torso")
    ob.shape_key_add(name="Basis")
    k = ob.shape_key_add(name="Breathe")
    for i, v in enumerate(k.data):
        v.co = v.co * 1.1
    k.value = 0.0  # basis shown
    mirror(ob)
    ob2 = half_torso("TorsoKeyed")
    ob2.location = (3, 0, 0)
    ob2.shape_key_add(name="Basis")
    k2 = ob2.shape_key_add(name="Breathe")
    for v in k2.data:
        v.co = v.co * 1.1
    k2.value = 1.0  # shape key applied in the viewport
    mirror(ob2)


@case
def saved_in_edit_mode():
    ob = half_torso("Torso")
    mirror(ob)
    bpy.context.view_layer.objects.active = ob
    ob.select_set(True)
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    bpy.ops.transform.translate(value=(0.0, 0.0, 0.25))  # an unflushed edit


@case
def mirror_object_constraint_only():
    target = empty("Target", loc=(0.4, -0.2, 0.5), rot=(0, 0, math.radians(45)))
    e = empty("Sym", loc=(0, 0, 0))
    c = e.constraints.new('COPY_TRANSFORMS'); c.target = target
    ob = tube("Leg", 0.6)
    mirror(ob, mob=e)


@case
def mirror_object_delta_only():
    e = empty("Sym", loc=(0.2, 0, 0))
    e.delta_location = (0.1, 0.1, 0.0)
    e.delta_rotation_euler = (0, 0, math.radians(20))
    ob = tube("Leg", 0.6)
    ob.delta_location = (0.1, 0.0, 0.2)
    ob.delta_scale = (1.0, 1.5, 1.0)
    mirror(ob, mob=e)


@case
def mirrored_object_constrained():
    # the mirrored object itself is turned by a constraint (Child Of, as riggers use)
    e = empty("Sym", loc=(0.3, 0, 0), rot=(0, 0, math.radians(20)))
    rig = empty("Rig", loc=(0, 0.5, 0), rot=(0, 0, math.radians(-35)))
    ob = tube("Leg", 0.6)
    c = ob.constraints.new('CHILD_OF'); c.target = rig
    c.set_inverse_pending = False
    mirror(ob, mob=e)

# --------------------------------------------------------------------------
def r5(x):
    v = round(x, 5)
    return 0.0 if v == 0 else v


def mod_info(m):
    d = {"name": m.name, "type": m.type, "show_viewport": m.show_viewport,
         "show_render": m.show_render}
    if m.type == 'MIRROR':
        d.update(use_axis=list(m.use_axis), use_bisect_axis=list(m.use_bisect_axis),
                 use_bisect_flip_axis=list(m.use_bisect_flip_axis),
                 use_mirror_merge=m.use_mirror_merge, merge_threshold=m.merge_threshold,
                 mirror_object=m.mirror_object.name if m.mirror_object else None,
                 use_clip=m.use_clip)
    return d


def dump(path):
    dg = bpy.context.evaluated_depsgraph_get()
    out = {"file": os.path.basename(path), "blender": bpy.app.version_string, "objects": []}
    for ob in bpy.data.objects:
        if ob.type != 'MESH':
            continue
        ev = ob.evaluated_get(dg)
        me = ev.to_mesh()
        verts = sorted([[r5(c) for c in v.co] for v in me.vertices])
        out["objects"].append({
            "name": ob.name,
            "parent": ob.parent.name if ob.parent else None,
            "matrix_world": [list(r) for r in ob.matrix_world],
            "modifiers": [mod_info(m) for m in ob.modifiers],
            "base_vertex_count": len(ob.data.vertices),
            "base_polygon_count": len(ob.data.polygons),
            "vertex_count": len(me.vertices),
            "polygon_count": len(me.polygons),
            "vertices": verts,
        })
        ev.to_mesh_clear()
    with open(path[:-6] + ".evaluated.json", "w") as f:
        json.dump(out, f, indent=1)


for name, fn in CASES.items():
    if ONLY and name not in ONLY:
        continue
    reset()
    fn()
    bpy.context.view_layer.update()
    path = os.path.join(OUT, name + ".blend")
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
    bpy.ops.wm.open_mainfile(filepath=path)
    dump(path)
    print("WROTE", path)
