#!/usr/bin/env python3
"""Writes `bench speed`'s 1M-triangle displaced sphere (the same grid and bumps as
src/bench/procedural.rs) on its ground quad, lit by a 2 x 2 quad light instead of the point
light, as OBJ files and a TOML scene in DIR (default /tmp/sphere_area_light). Then:

  embray render DIR/scene.toml --spp 4096 --seed 99 -o DIR/ref.exr     # the reference
  embray bench convergence DIR/scene.toml --reference DIR/ref.exr --spps 16,64
"""
import math
import os
import sys

out_dir = sys.argv[1] if len(sys.argv) > 1 else "/tmp/sphere_area_light"
os.makedirs(out_dir, exist_ok=True)
rings = round(math.sqrt(1_000_000 / 4.0))
segments = 2 * rings
with open(os.path.join(out_dir, "sphere.obj"), "w") as f:
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2 * math.pi * j / segments
            bump = 1 + 0.05 * math.sin(7 * theta) * math.cos(9 * phi) \
                + 0.02 * math.cos(31 * theta) * math.sin(29 * phi)
            f.write("v %.7f %.7f %.7f\n" % (math.sin(theta) * math.cos(phi) * bump,
                                            math.cos(theta) * bump,
                                            math.sin(theta) * math.sin(phi) * bump))
    for i in range(rings):
        for j in range(segments):
            a = i * (segments + 1) + j + 1
            b, c, d = a + 1, a + segments + 1, a + segments + 2
            if i > 0:
                f.write("f %d %d %d\n" % (a, b, c))
            if i + 1 < rings:
                f.write("f %d %d %d\n" % (b, d, c))
with open(os.path.join(out_dir, "ground.obj"), "w") as f:
    f.write("v -10 -1.1 -10\nv 10 -1.1 -10\nv 10 -1.1 10\nv -10 -1.1 10\nf 1 3 2\nf 1 4 3\n")
with open(os.path.join(out_dir, "light.obj"), "w") as f:  # facing down
    f.write("v -1 3 -1\nv 1 3 -1\nv 1 3 1\nv -1 3 1\nf 1 2 3\nf 1 3 4\n")
with open(os.path.join(out_dir, "scene.toml"), "w") as f:
    f.write("""# bench speed's 1M-triangle displaced sphere on a ground quad, lit by a 2 x 2 quad light.
[camera]
lookfrom = [0.0, 1.2, 3.2]
lookat = [0.0, 0.1, 0.0]
up = [0.0, 1.0, 0.0]
vfov = 40.0
resolution = [128, 128]

[render]
spp = 16
max_depth = 3

[materials.grey]
albedo = [0.7, 0.7, 0.7]
[materials.light]
albedo = [0.0, 0.0, 0.0]
emission = [10.0, 10.0, 10.0]

[[objects]]
type = "mesh"
file = "sphere.obj"
material = "grey"
[[objects]]
type = "mesh"
file = "ground.obj"
material = "grey"
[[objects]]
type = "mesh"
file = "light.obj"
material = "light"
""")
print(out_dir)
