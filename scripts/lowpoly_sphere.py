#!/usr/bin/env python3
"""Writes lowpoly.obj, lowpoly.ply and lowpoly.serialized (one low-polygon sphere without normals)
into the folder given, for tests/data/mitsuba/smooth_normals.xml:

    python3 scripts/lowpoly_sphere.py tests/data/mitsuba
"""
import math, struct, zlib, sys
out = sys.argv[1]
rings, segs = 5, 7
pos = [(0.0, 0.0, 1.0)]
for r in range(1, rings):
    th = math.pi * r / rings
    for s in range(segs):
        ph = 2 * math.pi * s / segs + 0.3 * r
        pos.append((math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)))
pos.append((0.0, 0.0, -1.0))
south = len(pos) - 1
def v(r, s):
    return 1 + (r - 1) * segs + (s % segs)
faces = []
for s in range(segs):
    faces.append((0, v(1, s), v(1, s + 1)))
for r in range(1, rings - 1):
    for s in range(segs):
        a, b, c, d = v(r, s), v(r + 1, s), v(r + 1, s + 1), v(r, s + 1)
        # Quads cut along alternating diagonals: a vertex sits in one or two triangles of
        # each quad, so area and angle weights differ.
        if (r + s) % 2 == 0:
            faces += [(a, b, c), (a, c, d)]
        else:
            faces += [(a, b, d), (b, c, d)]
for s in range(segs):
    faces.append((south, v(rings - 1, s + 1), v(rings - 1, s)))
with open(f"{out}/lowpoly.obj", "w") as f:
    f.write("# a low-polygon sphere without normals (smooth_normals.xml)\n")
    for p in pos:
        f.write("v %.6f %.6f %.6f\n" % p)
    for t in faces:
        f.write("f %d %d %d\n" % tuple(i + 1 for i in t))
with open(f"{out}/lowpoly.ply", "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n" % len(pos))
    f.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(faces))
    for p in pos:
        f.write("%.6f %.6f %.6f\n" % p)
    for t in faces:
        f.write("3 %d %d %d\n" % t)
body = struct.pack("<I", 0x1000) + b"lowpoly\0" + struct.pack("<QQ", len(pos), len(faces))
body += b"".join(struct.pack("<fff", *p) for p in pos)
body += b"".join(struct.pack("<III", *t) for t in faces)
data = b"\x1c\x04\x04\x00" + zlib.compress(body)
data += struct.pack("<Q", 0) + struct.pack("<I", 1)
open(f"{out}/lowpoly.serialized", "wb").write(data)
print(len(pos), "vertices", len(faces), "faces")
