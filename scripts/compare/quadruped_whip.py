#!/usr/bin/env python3
"""A cortex creature's drop in MuJoCo: each body's peak speed (the whipping tail).

A Python script, outside cortex's Clojure code (see scripts/compare/README.md
for the venv; it needs only `mujoco` and numpy, and without them it says so
and exits 0).

    /work/venvs/compare/bin/python scripts/compare/quadruped_whip.py EXPORT.xml OUT.json
    ... --frictions 0.25,0.5,1.0   # one drop per friction (the default)
    ... --dt 0.001 --seconds 3     # MuJoCo's step and how long each drop runs
    ... --cortex-csv FILE          # a cortex drop's speeds to draw (repeatable)
    ... --plot OUT.png             # draw the speeds against time (needs Pillow)

The picture org/images/quadruped-whip.png (run from the repository root):

    /work/venvs/compare/bin/python scripts/compare/quadruped_whip.py out/compare/quadruped.xml /tmp/whip.json --frictions 0.5 --cortex-csv out/compare/whip-jbullet.csv --cortex-csv out/compare/whip-native.csv --plot org/images/quadruped-whip.png

Why: cortex's physics-trust drop test says no body may move faster than
sqrt(2 g H) + 1 m/s, H the drop of the creature's highest point to the floor.
A whipping chain's tip beats that bound honestly (the energy of the heavy
bodies flows into the light tip), and MuJoCo's does too.  This script gives
the reference figure the test compares the four-legged creature (torso,
legs, neck, head and a three-segment tail) with.

What it runs: the creature of EXPORT.xml, cortex's MJCF export
(`lein run -- FILE.blend --mjcf EXPORT.xml`, org/export.org), loaded with
MjSpec: a floor plane added at z = 0, the creature lifted by its free
joint until its lowest point (of its geoms' corners, ends or vertices) is
1 m above the floor, as the drop test places it; its actuators off (the
drop sends the muscles nothing); friction on every geom and the floor
(torsional and rolling as exported); implicitfast, time step --dt, the
export's other settings (pyramidal cones, Newton solver, MuJoCo's default
contact softness); joined bodies' contacts excluded (as exported), all
other pairs on.  Every body starts at rest and falls onto the floor, for
each friction.  A body's speed is the finite difference of its centre of
mass (xipos) over one step; its peak and the time at the end of that step
are recorded.  Printed: per friction the fastest body, its peak speed,
when, and the test's bound sqrt(2 g H) + 1 with H = 1 + the creature's
height (highest geom point - lowest; the test drops the creature with its
lowest point 1 m above the floor; g = 9.81).

Before the export this script wrote its own model from cortex.whip-json's
JSON (each cone one ball joint limited to its larger swing, no twist
limit); the export's model gives the reference within 0.02%.

OUT.json: {"source", "command", "export", "frictions": {"0.25": {"fastest",
"body", "time", "speeds": {body: peak m/s}}, ...}}, numbers rounded to 3
decimals and keys sorted: reruns write the same bytes.  --cortex-csv and
--plot do not change it (the speed series are drawn, never written there).

--cortex-csv FILE (repeatable): a cortex drop's speeds, as cortex writes them
(out/compare/whip-jbullet.csv, whip-native.csv): line 1 a comment
`# engine: cortex (jBullet), friction 0.5, step 1/60 s` (the legend's label
is the text after `# engine: ` up to the first comma), line 2 the header
`time,<segment>,...`, then one row per step: the time at the end of the step
(s) and each segment's centre-of-mass speed (m/s).

--plot OUT.png: a 900x520 line chart (Pillow's ImageDraw, drawn at twice the
size and scaled down), speed against time from 0 to 1.5 s, for the FIRST
friction of --frictions: MuJoCo's fastest body (every MuJoCo step) and its
root body (thinner, lighter), the same two bodies of every --cortex-csv in a
colour of its own, and a dashed line at the bound sqrt(2 g H) + 1.

Friction: MuJoCo takes the larger of a contact pair's two frictions,
Bullet (cortex) their product.  Here the floor's friction is set equal to
the bodies', so every MuJoCo pair has exactly the friction named (the
larger of two equal values); in Bullet the same pair would have the
product of the floor's and the body's coefficients.
"""

import argparse
import json
import math
import os
import shlex
import sys

try:
    import mujoco
    import numpy as np
except ImportError:  # main() says so
    mujoco = np = None

G = 9.81


def geom_points(m, d, g):
    """World points bounding geom g (its corners, ends or vertices)."""
    pos, rot, size = d.geom_xpos[g], d.geom_xmat[g].reshape(3, 3), m.geom_size[g]
    t = m.geom_type[g]
    if t == mujoco.mjtGeom.mjGEOM_BOX:
        local = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1)
                          for sz in (-1, 1)]) * size
    elif t == mujoco.mjtGeom.mjGEOM_MESH:
        a = m.geom_dataid[g]
        local = m.mesh_vert[m.mesh_vertadr[a]:m.mesh_vertadr[a] + m.mesh_vertnum[a]]
    elif t == mujoco.mjtGeom.mjGEOM_SPHERE:
        return pos + np.vstack([np.eye(3), -np.eye(3)]) * size[0]
    elif t in (mujoco.mjtGeom.mjGEOM_CAPSULE, mujoco.mjtGeom.mjGEOM_CYLINDER):
        # a rim or end cap: its lowest and highest points along world z
        r, h = size[0], size[1]
        ends = np.array([[0, 0, -h], [0, 0, h]]) @ rot.T + pos
        ax = rot[:, 2]
        reach = r if t == mujoco.mjtGeom.mjGEOM_CAPSULE else r * math.sqrt(max(0.0, 1 - ax[2] ** 2))
        return np.vstack([ends + [0, 0, reach], ends - [0, 0, reach]])
    else:
        raise ValueError(f"geom {m.geom(g).name}: type {t} not bounded here")
    return local @ rot.T + pos


def build(path, friction, dt):
    """The creature of the MJCF export `path` (cortex.export/mjcf) on a floor,
    its lowest point 1 m above it, every geom and the floor on `friction`,
    MuJoCo's step `dt`, its muscles off.  Returns (model, data, limit):
    limit = sqrt(2 g H) + 1, H = 1 + the creature's height."""
    spec = mujoco.MjSpec.from_file(path)
    spec.worldbody.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 1])
    m = spec.compile()
    m.opt.timestep = dt
    m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
    m.geom_friction[:, 0] = friction
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    zs = np.concatenate([geom_points(m, d, g)[:, 2] for g in range(m.ngeom)
                         if m.geom_bodyid[g] != 0])
    root = next(j for j in range(m.njnt) if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE)
    d.qpos[m.jnt_qposadr[root] + 2] += 1.0 - zs.min()
    mujoco.mj_forward(m, d)
    return m, d, math.sqrt(2 * G * (1 + zs.max() - zs.min())) + 1


def drop(m, d, seconds, series=None):
    """Peak finite-difference speed of every body's centre of mass, and when.
    With a dict `series`, also fills it: "time" -> [s], body -> [m/s] per
    step, "root" -> the name of the body hung on the world."""
    dt = m.opt.timestep
    prev = d.xipos.copy()
    peak, when = np.zeros(m.nbody), np.zeros(m.nbody)
    rows, times = [], []
    for _ in range(int(round(seconds / dt))):
        mujoco.mj_step(m, d)
        v = np.linalg.norm(d.xipos - prev, axis=1) / dt
        prev[:] = d.xipos
        faster = v > peak
        peak[faster], when[faster] = v[faster], d.time
        if series is not None:
            rows.append(v.copy())
            times.append(d.time)
    if series is not None:
        rows = np.array(rows).reshape(-1, m.nbody)
        series["time"] = times
        for b in range(1, m.nbody):
            series[m.body(b).name] = rows[:, b].tolist()
        series["root"] = next(m.body(b).name for b in range(1, m.nbody)
                              if m.body_parentid[b] == 0)
    return {m.body(b).name: (float(peak[b]), float(when[b])) for b in range(1, m.nbody)}


def read_cortex_csv(path):
    """(label, {"time": [...], segment: [...]}) of a cortex drop's CSV."""
    with open(path) as fh:
        lines = [ln.strip() for ln in fh if ln.strip()]
    first = lines[0]
    assert first.startswith("# engine: "), f"{path}: line 1 is not '# engine: ...'"
    label = first[len("# engine: "):].split(",")[0].strip()
    head = lines[1].split(",")
    cols = {h: [] for h in head}
    for ln in lines[2:]:
        for h, x in zip(head, ln.split(",")):
            cols[h].append(float(x))
    return label, cols


def nice_step(top, ticks=6):
    """A round tick step (1, 2 or 5 times a power of ten) giving about `ticks` ticks."""
    raw = top / ticks
    p = 10 ** math.floor(math.log10(raw))
    return next(k * p for k in (1, 2, 5, 10) if k * p >= raw)


def plot(path, title, lines, limit, x_max=1.5, size=(900, 520), scale=2):
    """Line chart of `lines` [(label, colour, width, times, speeds)] and the
    dashed bound `limit`, drawn with Pillow at `scale` times the size."""
    from PIL import Image, ImageDraw, ImageFont
    W, H = size[0] * scale, size[1] * scale
    S = lambda v: int(round(v * scale))
    try:
        font = ImageFont.load_default(size=14 * scale)
        small = ImageFont.load_default(size=13 * scale)
        big = ImageFont.load_default(size=15 * scale)
    except TypeError:  # Pillow < 10.1: one fixed bitmap font
        font = small = big = ImageFont.load_default()
    img = Image.new("RGB", (W, H), "white")
    dr = ImageDraw.Draw(img)
    left, right, top, bottom = S(62), W - S(20), S(44), H - S(52)
    shown = [v for _, _, _, ts, vs in lines for t, v in zip(ts, vs) if t <= x_max]
    y_hi = max(shown + [limit])
    ystep = nice_step(y_hi)
    y_max = ystep * (math.floor(y_hi / ystep) + 1)
    px = lambda t: left + (right - left) * t / x_max
    py = lambda v: bottom - (bottom - top) * v / y_max
    grey, axis = (225, 225, 225), (60, 60, 60)
    # grid, ticks and tick labels
    y = 0.0
    while y <= y_max + 1e-9:
        yy = py(y)
        dr.line([(left, yy), (right, yy)], fill=grey, width=S(1))
        dr.line([(left - S(5), yy), (left, yy)], fill=axis, width=S(1))
        dr.text((left - S(8), yy), f"{y:g}", fill=axis, font=font, anchor="rm")
        y += ystep
    for i in range(int(round(x_max / 0.25)) + 1):
        t = i * 0.25
        xx = px(t)
        dr.line([(xx, top), (xx, bottom)], fill=grey, width=S(1))
        dr.line([(xx, bottom), (xx, bottom + S(5))], fill=axis, width=S(1))
        dr.text((xx, bottom + S(8)), f"{t:g}", fill=axis, font=font, anchor="mt")
    dr.rectangle([left, top, right, bottom], outline=axis, width=S(1))
    dr.text(((left + right) / 2, H - S(8)), "time (s)", fill=axis, font=font, anchor="mb")
    ylab = Image.new("RGBA", (S(160), S(20)), (255, 255, 255, 0))
    ImageDraw.Draw(ylab).text((S(80), S(10)), "speed (m/s)", fill=axis, font=font, anchor="mm")
    ylab = ylab.rotate(90, expand=True)
    img.paste(ylab, (S(4), int((top + bottom) / 2 - ylab.height / 2)), ylab)
    dr.text((W / 2, S(14)), title, fill=(0, 0, 0), font=big, anchor="mt")
    # the bound, dashed
    yl, x0, dash = py(limit), left, S(9)
    while x0 < right:
        dr.line([(x0, yl), (min(x0 + dash, right), yl)], fill=(90, 90, 90), width=S(1.5))
        x0 += 2 * dash
    dr.text((left + S(8), yl - S(4)), "clean fall + 1 m/s (the speed rule)",
            fill=(70, 70, 70), font=small, anchor="lb")
    # the lines, thin ones first
    for label, colour, width, ts, vs in sorted(lines, key=lambda l: l[2]):
        pts = [(px(t), py(v)) for t, v in zip([0.0] + list(ts), [0.0] + list(vs)) if t <= x_max]
        dr.line(pts, fill=colour, width=S(width), joint="curve")
    # legend at the right: just under the bound if no line passes there, else at the top
    row, sw = S(20), S(26)
    wide = max(dr.textlength(l[0], font=small) for l in lines)
    lx1 = right - S(10)
    lx0 = lx1 - (S(10) + sw + S(8) + wide + S(10))
    box_h = S(8) + row * len(lines)
    ly0 = yl + S(10)
    under = [py(v) for _, _, _, ts, vs in lines for t, v in zip(ts, vs)
             if t <= x_max and lx0 - S(10) <= px(t) <= lx1 + S(10)]
    if ly0 + box_h + S(10) > min(under + [bottom]):
        ly0 = top + S(10)
    dr.rectangle([lx0, ly0, lx1, ly0 + box_h], fill="white",
                 outline=(170, 170, 170), width=S(1))
    for i, (label, colour, width, _, _) in enumerate(lines):
        yy = ly0 + S(4) + row * i + row / 2
        dr.line([(lx0 + S(10), yy), (lx0 + S(10) + sw, yy)], fill=colour, width=S(max(width, 2)))
        dr.text((lx0 + S(10) + sw + S(8), yy), label, fill=(30, 30, 30), font=small, anchor="lm")
    img.resize(size, Image.LANCZOS).save(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("export")
    ap.add_argument("out")
    ap.add_argument("--frictions", default="0.25,0.5,1.0")
    ap.add_argument("--dt", type=float, default=0.001)
    ap.add_argument("--seconds", type=float, default=3.0)
    ap.add_argument("--cortex-csv", action="append", default=[], metavar="FILE",
                    help="a cortex drop's speeds (time, one column per segment); repeatable")
    ap.add_argument("--plot", metavar="OUT.png",
                    help="draw speed against time for the first friction")
    a = ap.parse_args()
    if mujoco is None:
        print("quadruped_whip.py needs the mujoco package and numpy (see scripts/compare/README.md); skipped")
        return 0
    result = {}
    limit = None
    print(f"{'friction':>8}  {'fastest body':<18} {'peak m/s':>8} {'time s':>7}  {'limit m/s':>9}")
    series = None
    for f in [float(x) for x in a.frictions.split(",")]:
        first = a.plot and series is None
        if first:
            series = {}
        m, d, limit = build(a.export, f, a.dt)
        res = drop(m, d, a.seconds, series if first else None)
        if first:
            series["friction"] = f
        body = max(sorted(res), key=lambda n: res[n][0])
        speed, t = res[body]
        print(f"{f:>8g}  {body:<18} {speed:>8.3f} {t:>7.3f}  {limit:>9.3f}")
        result[repr(f)] = {"fastest": round(speed, 3), "body": body, "time": round(t, 3),
                           "speeds": {n: round(v[0], 3) for n, v in res.items()}}
    doc = {"source": f"MuJoCo {mujoco.__version__}, implicitfast, dt {a.dt:g} s, {a.seconds:g} s,"
                     " cortex's MJCF export lifted 1 m, muscles off,"
                     " friction on every geom and the floor, joined bodies' contacts off",
           "command": shlex.join([sys.executable] + sys.argv),
           "export": os.path.basename(a.export),
           "frictions": result}
    with open(a.out, "w") as fh:
        json.dump(doc, fh, indent=1, sort_keys=True)
        fh.write("\n")
    if a.plot:
        f = series["friction"]
        fast = result[repr(f)]["body"]
        root = series["root"]
        palette = [((31, 84, 180), (150, 175, 225)),   # MuJoCo: blue
                   ((214, 96, 20), (240, 180, 140)),   # first CSV: orange
                   ((30, 140, 60), (150, 205, 160)),   # second CSV: green
                   ((150, 40, 160), (210, 160, 215)),
                   ((120, 90, 40), (200, 180, 140))]
        lines = [(f"MuJoCo {fast}", palette[0][0], 2.5, series["time"], series[fast]),
                 (f"MuJoCo {root}", palette[0][1], 1.5, series["time"], series[root])]
        for i, path in enumerate(a.cortex_csv):
            label, cols = read_cortex_csv(path)
            dark, light = palette[(i + 1) % len(palette)]
            for name, colour, width in ((fast, dark, 2.5), (root, light, 1.5)):
                if name not in cols:
                    print(f"{path}: no column {name}; not drawn")
                    continue
                lines.append((f"{label} {name}", colour, width, cols["time"], cols[name]))
        title = (f"four-legged creature dropped 1 m, friction {f:g}:"
                 f" the tail tip whips past a clean fall")
        plot(a.plot, title, lines, limit)
        print(f"wrote {a.plot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
