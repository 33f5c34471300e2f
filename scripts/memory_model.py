#!/usr/bin/env python3
"""Measures the memory model of `limits.rs`: the peak resident memory of `embray render`
(read by /usr/bin/time) as one count grows and the others stay small, on each backend and
integrator; prints every run, the fitted bytes per unit, and embray's own estimate
(`embray info` prints it) beside the peak.

    python3 scripts/memory_model.py [--embray target/release/embray] [--quick]

Counts: pixels (resolution), triangles (a binary PLY grid), placements (`repeat` copies of
a box), texels (a PNG texture of noise, the least compressible), environment texels (an
EXR radiance map, which also gets a sampling table) and worker threads (`--threads`; the
estimate `embray info` prints is for one thread per core, so that series prints none).
"""

import argparse
import os
import re
import struct
import subprocess
import tempfile
import zlib

CAMERA = """[camera]
lookfrom = [0.0, 2.0, 6.0]
lookat = [0.0, 0.0, 0.0]
vfov = 40.0
resolution = [{res}, {res}]

[render]
spp = 1
max_depth = 3
{integrator}

[materials.white]
albedo = [0.7, 0.7, 0.7]
{material}

[[lights]]
type = "point"
position = [0.0, 4.0, 4.0]
intensity = [40.0, 40.0, 40.0]
"""


def ply_grid(path, triangles):
    """A binary PLY square of about `triangles` triangles."""
    side = max(1, int((triangles / 2) ** 0.5))
    verts = (side + 1) ** 2
    with open(path, "wb") as f:
        f.write(
            (
                "ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                "property float x\nproperty float y\nproperty float z\n"
                "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                % (verts, 2 * side * side)
            ).encode()
        )
        row = bytearray()
        for j in range(side + 1):
            row.clear()
            for i in range(side + 1):
                row += struct.pack("<3f", 2 * i / side - 1, 0.0, 2 * j / side - 1)
            f.write(row)
        for j in range(side):
            row.clear()
            for i in range(side):
                a = j * (side + 1) + i
                row += struct.pack("<B3i", 3, a, a + 1, a + side + 1)
                row += struct.pack("<B3i", 3, a + 1, a + side + 2, a + side + 1)
            f.write(row)
    return 2 * side * side


def png_noise(path, side):
    """An 8-bit RGB PNG of noise (the largest file for its texels)."""
    raw = bytearray()
    for _ in range(side):
        raw += b"\0" + os.urandom(3 * side)
    chunk = lambda kind, data: (
        struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    )
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", side, side, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(bytes(raw), 1)))
        f.write(chunk(b"IEND", b""))
    return side * side


def peak_kib(embray, scene, backend, workdir, extra=()):
    out = subprocess.run(
        ["/usr/bin/time", "-f", "PEAK %M", embray, "render", scene, "--spp", "1", "-q",
         "--backend", backend, "-o", "out.exr", *extra],
        cwd=workdir, capture_output=True, text=True,
    )
    if out.returncode != 0:
        raise SystemExit("render failed: %s" % out.stderr)
    return int(re.search(r"PEAK (\d+)", out.stderr).group(1))


def estimate_bytes(embray, scene, backend, workdir):
    out = subprocess.run([embray, "info", scene], cwd=workdir, capture_output=True, text=True)
    m = re.search(r"([\d.]+) MiB on %s" % backend, out.stdout)
    return float(m.group(1)) * 1048576 if m else None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--embray", default="target/release/embray")
    ap.add_argument("--quick", action="store_true", help="smaller sizes, one backend")
    args = ap.parse_args()
    embray = os.path.abspath(args.embray)
    backends = ["embree"] if args.quick else ["embree", "obvhs"]
    integrators = {"path": "", "whitted": 'integrator = "whitted"'}
    scale = 0.25 if args.quick else 1.0
    work = tempfile.mkdtemp(prefix="embray-memory-")

    def scene(name, res=64, material="", objects="", integrator=""):
        text = CAMERA.format(res=res, integrator=integrator, material=material) + objects
        with open(os.path.join(work, name), "w") as f:
            f.write(text)
        return name

    floor = '\n[[objects]]\ntype = "quad"\nmaterial = "{m}"\ncorner = [-2.0, 0.0, -2.0]\n' \
        'u = [4.0, 0.0, 0.0]\nv = [0.0, 0.0, 4.0]\n'
    series = {
        "pixels": [
            (n * n, lambda n=n, i="": scene("p.toml", res=n, objects=floor.format(m="white"), integrator=i))
            for n in (int(1024 * scale ** 0.5), int(2048 * scale ** 0.5))
        ],
        "triangles": [],
        "placements": [],
        "texels": [],
        "environment texels": [],
        "EXR environment texels": [],
        "threads": [
            (n, lambda i="": scene("w.toml", res=512, objects=floor.format(m="white"), integrator=i))
            for n in (16, 256)
        ],
    }
    # (The threads' scene has 1024 tiles, so that each thread works and holds its buffers.)
    for t in (int(1e6 * scale), int(4e6 * scale)):
        count = ply_grid(os.path.join(work, "grid%d.ply" % t), t)
        obj = '\n[[objects]]\ntype = "mesh"\nmaterial = "white"\nfile = "grid%d.ply"\n' % t
        series["triangles"].append((count, lambda obj=obj, i="": scene("t.toml", objects=obj, integrator=i)))
    for k in (int(40 * scale ** (1 / 3)), int(80 * scale ** (1 / 3))):
        obj = ('\n[[objects]]\ntype = "box"\nmaterial = "white"\nmin = [0.0, 0.0, 0.0]\n'
               'max = [0.01, 0.01, 0.01]\nrepeat = { count = [%d, %d, %d], '
               'spacing = [0.02, 0.02, 0.02] }\n' % (k, k, k))
        series["placements"].append((k ** 3, lambda obj=obj, i="": scene("o.toml", objects=obj, integrator=i)))
    for side in (int(2048 * scale ** 0.5), int(4096 * scale ** 0.5)):
        texels = png_noise(os.path.join(work, "noise%d.png" % side), side)
        mat = '\n[materials.tex]\ntexture = { type = "image", file = "noise%d.png" }\n' % side
        series["texels"].append(
            (texels, lambda mat=mat, i="": scene("x.toml", material=mat, objects=floor.format(m="tex"), integrator=i)))
        env = '\n[[lights]]\ntype = "environment"\nfile = "noise%d.png"\n' % side
        series["environment texels"].append(
            (texels, lambda env=env, i="": scene("e.toml", objects=floor.format(m="white") + env, integrator=i)))

    # EXR radiance maps: renders of the floor scene (R, G, B, Z, N channels, as HDR tools
    # write more than RGB too).
    for side in (int(1024 * scale ** 0.5), int(2048 * scale ** 0.5)):
        subprocess.run([embray, "render", scene("m.toml", res=side, objects=floor.format(m="white")),
                        "--spp", "1", "-q", "-o", "map%d.exr" % side], cwd=work, check=True)
        env = '\n[[lights]]\ntype = "environment"\nfile = "map%d.exr"\n' % side
        series["EXR environment texels"].append(
            (side * side, lambda env=env, i="": scene("h.toml", objects=floor.format(m="white") + env, integrator=i)))

    print("quantity            count     backend integrator   peak MiB  estimate MiB  est/peak")
    only = os.environ.get("ONLY")
    for quantity, runs in series.items():
        if only and quantity != only:
            continue
        for backend in backends:
            for integ, line in integrators.items():
                points = []
                for count, make in runs:
                    name = make(i=line)
                    extra = ["--threads", str(count)] if quantity == "threads" else []
                    peak = peak_kib(embray, name, backend, work, extra) * 1024
                    est = None if extra else estimate_bytes(embray, name, backend, work)
                    ratio = "%.2f" % (est / peak) if est else "-"
                    print("%-18s %9d  %-7s %-10s %9.1f  %12s  %8s" % (
                        quantity, count, backend, integ, peak / 1048576,
                        "%.1f" % (est / 1048576) if est else "-", ratio), flush=True)
                    points.append((count, peak))
                (c0, p0), (c1, p1) = points
                print("%-18s slope: %.1f bytes per unit" % (quantity, (p1 - p0) / (c1 - c0)))
    subprocess.run(["rm", "-rf", work])


if __name__ == "__main__":
    main()
