#!/usr/bin/env python3
"""Writes a Mitsuba .vol (version 3, float32, one channel) of a torus's signed distance on an
N³ grid over [0, 1]³: ring radius 0.3 about z through the centre, tube radius 0.13.

  python3 scripts/torus_sdf_vol.py N OUT.vol
"""
import math
import struct
import sys


def main():
    n, out = int(sys.argv[1]), sys.argv[2]
    values = []
    for z in range(n):
        for y in range(n):
            for x in range(n):
                p = [x / (n - 1) - 0.5, y / (n - 1) - 0.5, z / (n - 1) - 0.5]
                ring = math.hypot(p[0], p[1]) - 0.3
                values.append(math.hypot(ring, p[2]) - 0.13)
    header = b"VOL" + bytes([3]) + struct.pack("<iiiii", 1, n, n, n, 1)
    header += struct.pack("<6f", 0, 0, 0, 1, 1, 1)
    with open(out, "wb") as f:
        f.write(header + struct.pack("<%df" % len(values), *values))


if __name__ == "__main__":
    main()
