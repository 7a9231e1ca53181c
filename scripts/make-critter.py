#!/usr/bin/env python3
"""Writes models/critter.obj: a box-modelled four-legged animal cage, all quads, made for
this project the way a modeller makes a subdivision cage in Blender or Maya: a box body
with a few divisions, faces extruded into legs, a neck, a head with a snout and ears, and
a tail. Catmull-Clark turns it into a smooth, organic body; the triangle schemes see its
quads fanned.

    python3 scripts/make-critter.py

Deterministic: the same file every run (no randomness). Extrusions scale the moved face
about its centre and bend it by an offset, so legs taper and the tail curls.
"""
import os

verts = []
faces = []  # lists of vertex ids, counter-clockwise seen from outside


def add(p):
    verts.append(list(p))
    return len(verts) - 1


def grid_box(x0, x1, y0, y1, z0, z1, nx, ny, nz):
    """A box with nx x ny x nz divisions, its faces quads, returns the face ids per side."""
    ids = {}

    def vid(i, j, k):
        key = (i, j, k)
        if key not in ids:
            ids[key] = add((x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny, z0 + (z1 - z0) * k / nz))
        return ids[key]

    sides = {}

    def quad(name, a, b, c, d):
        faces.append([a, b, c, d])
        sides.setdefault(name, []).append(len(faces) - 1)

    for j in range(ny):
        for k in range(nz):
            quad("-x", vid(0, j, k), vid(0, j, k + 1), vid(0, j + 1, k + 1), vid(0, j + 1, k))
            quad("+x", vid(nx, j, k), vid(nx, j + 1, k), vid(nx, j + 1, k + 1), vid(nx, j, k + 1))
    for i in range(nx):
        for k in range(nz):
            quad("-y", vid(i, 0, k), vid(i + 1, 0, k), vid(i + 1, 0, k + 1), vid(i, 0, k + 1))
            quad("+y", vid(i, ny, k), vid(i, ny, k + 1), vid(i + 1, ny, k + 1), vid(i + 1, ny, k))
    for i in range(nx):
        for j in range(ny):
            quad("-z", vid(i, j, 0), vid(i, j + 1, 0), vid(i + 1, j + 1, 0), vid(i + 1, j, 0))
            quad("+z", vid(i, j, nz), vid(i + 1, j, nz), vid(i + 1, j + 1, nz), vid(i, j + 1, nz))
    return sides


def centre(f):
    n = len(faces[f])
    return [sum(verts[v][a] for v in faces[f]) / n for a in range(3)]


def extrude(region, offset, scale=1.0):
    """Moves the faces `region` (a list of face ids, or one id) by `offset`, scaled by
    `scale` about the region's centre, bridging the gap along the region's border with
    side quads; the faces keep their ids, so the result can be extruded again."""
    region = [region] if isinstance(region, int) else region
    vs = sorted({v for f in region for v in faces[f]})
    c = [sum(verts[v][a] for v in vs) / len(vs) for a in range(3)]
    new = {v: add([c[a] + (verts[v][a] - c[a]) * scale + offset[a] for a in range(3)]) for v in vs}
    edges = [(f[i], f[(i + 1) % len(f)]) for f in (faces[g] for g in region) for i in range(len(f))]
    inner = set(edges)
    for a, b in edges:
        if (b, a) not in inner:  # a border edge of the region
            faces.append([a, b, new[b], new[a]])
    for f in region:
        faces[f] = [new[v] for v in faces[f]]
    return region


def chain(region, steps):
    for offset, scale in steps:
        region = extrude(region, offset, scale)
    return region


# body: x from tail (-) to head (+), y across, z up
sides = grid_box(-1.2, 1.2, -0.5, 0.5, 0.0, 0.8, 3, 2, 2)
bottom = sides["-z"]  # 3 x 2 faces, ordered i-major
front, back = sides["+x"], sides["-x"]


def bottom_face(i, j):
    return bottom[i * 2 + j]


# legs: the four corner faces of the belly, down in tapering steps with a knee bend
for i, j in [(0, 0), (0, 1), (2, 0), (2, 1)]:
    forward = 0.08 if i == 2 else -0.08
    chain(bottom_face(i, j), [((0, 0, -0.35), 0.8), ((forward, 0, -0.45), 0.85), ((0, 0, -0.35), 0.9),
                              ((forward * 1.5, 0, -0.08), 1.1)])

# neck and head: the two upper front faces together, up and forward, then the head
head = [f for f in front if centre(f)[2] > 0.4]
chain(head, [((0.3, 0, 0.35), 0.85), ((0.3, 0, 0.4), 0.9)])
first_head_side = len(faces)
chain(head, [((0.25, 0, 0.1), 1.3)])
head_sides = list(range(first_head_side, len(faces)))
chain(head, [((0.35, 0, -0.05), 1.0), ((0.3, 0, -0.12), 0.65), ((0.12, 0, -0.02), 0.8)])

# ears: the two highest faces of the head's widest ring
for f in sorted(head_sides, key=lambda f: -centre(f)[2])[:2]:
    side = 1 if centre(f)[1] > 0 else -1
    chain(f, [((-0.05, side * 0.1, 0.22), 0.6), ((-0.05, side * 0.06, 0.18), 0.35)])

# tail: the upper back faces, out and curling up
tail = [f for f in back if centre(f)[2] > 0.4]
chain(tail, [((-0.35, 0, 0.05), 0.6), ((-0.3, 0, 0.15), 0.7), ((-0.2, 0, 0.3), 0.7), ((0.0, 0, 0.3), 0.6)])

here = os.path.dirname(os.path.abspath(__file__))
path = os.path.join(here, "..", "models", "critter.obj")
with open(path, "w") as out:
    out.write("# critter: a box-modelled four-legged animal cage, all quads, made for subdiv\n")
    out.write("# by scripts/make-critter.py (no third-party data); view it with Catmull-Clark\n")
    for x, y, z in verts:
        # modelled z up; written y up like the other bundled models (a rotation: the
        # faces keep their orientation)
        out.write("v %.4f %.4f %.4f\n" % (x, z, -y))
    for f in faces:
        out.write("f " + " ".join(str(v + 1) for v in f) + "\n")
print(f"{path}: {len(verts)} vertices, {len(faces)} quads")
