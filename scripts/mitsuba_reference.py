#!/usr/bin/env python3
"""A reference for Mitsuba's pass rule, made with Mitsuba 3 itself: the mean image and the
per-sample variance of each pixel, from P independent passes of S samples each.

  /tmp/peers/venv/bin/python scripts/mitsuba_reference.py SCENE.xml --spp S --passes P \
      --out OUT [--variant scalar_rgb] [-D name=value ...]

Writes OUT_ref_rgb.exr (the mean of the passes) and OUT_ref_rgb_var.exr (the variance of one
sample: the passes' variance times S), as the suite's references are laid out.
(Mitsuba comes from ../shared/peers/setup_peers.sh.)
"""
import argparse

import numpy as np
import mitsuba as mi


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("xml")
    ap.add_argument("--spp", type=int, required=True)
    ap.add_argument("--passes", type=int, required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--variant", default="scalar_rgb")
    ap.add_argument("-D", action="append", default=[])
    a = ap.parse_args()
    if a.passes < 2:
        ap.error("--passes must be at least 2 (the variance is measured between passes)")
    mi.set_variant(a.variant)
    params = dict(kv.split("=", 1) for kv in a.D)
    scene = mi.load_file(a.xml, **params)
    total = total_sq = None
    for seed in range(a.passes):
        img = np.array(scene.integrator().render(scene, seed=seed, spp=a.spp))[..., :3]
        img = img.astype(np.float64)
        total = img if total is None else total + img
        total_sq = img * img if total_sq is None else total_sq + img * img
    mean = total / a.passes
    between = (total_sq / a.passes - mean * mean) * a.passes / (a.passes - 1)
    variance = np.maximum(between, 0.0) * a.spp
    for suffix, data in (("_ref_rgb.exr", mean), ("_ref_rgb_var.exr", variance)):
        mi.Bitmap(data.astype(np.float32), mi.Bitmap.PixelFormat.RGB).write(a.out + suffix)
    print(f"wrote {a.out}_ref_rgb.exr and {a.out}_ref_rgb_var.exr: {a.passes} x {a.spp} spp")


if __name__ == "__main__":
    main()
