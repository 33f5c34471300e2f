#!/usr/bin/env python3
"""Mitsuba 3's own values of its `principled` and `principledthin` BSDFs, for the unit test
that checks embray's evaluation against them (src/shading/bsdf/tests_principled_values.rs).

  /tmp/peers/venv/bin/python scripts/mitsuba_principled_values.py [--variant VARIANT] \
      > tests/data/mitsuba/principled_values.txt

For each parameter set (a `config` line: its plugin and parameters) it writes direction
pairs in Mitsuba's local frame (wi towards the viewer, wo towards the light, as Mitsuba names
them) with Mitsuba's eval (f·|cos θo|, RGB) and pdf: random pairs over the sphere, and pairs
near the mirror and refracted directions where the specular lobes are. Constant parameters
only. (Mitsuba comes from ../shared/peers/setup_peers.sh.)

The default variant is llvm_ad_rgb: where the diffuse lobe is off (spec_trans 1 or metallic
1) but the sheen is on, scalar_rgb leaves the sheen out (its masked block is nested in the
diffuse one's, which a scalar skips) and the vectorised variants add it, as the masks say;
embray follows the masks, and `sheen_without_diffuse` is that case.
"""
import argparse

import mitsuba as mi
import numpy as np

CONFIGS = [
    ("default", "principled", {}),
    ("everything_opaque", "principled", {
        "base_color": [0.2, 0.8, 0.1], "roughness": 0.3, "anisotropic": 0.6, "metallic": 0.7,
        "spec_tint": 0.4, "specular": 0.7, "sheen": 0.8, "sheen_tint": 0.5, "clearcoat": 0.9,
        "clearcoat_gloss": 0.3, "flatness": 0.4,
    }),
    ("glass_like", "principled", {
        "base_color": [0.9, 0.6, 0.3], "roughness": 0.35, "metallic": 0.1, "spec_trans": 0.8,
        "eta": 1.4, "spec_tint": 0.3, "sheen": 0.4, "clearcoat": 0.5, "clearcoat_gloss": 0.8,
        "main_specular_sampling_rate": 2.0, "clearcoat_sampling_rate": 0.5,
        "diffuse_reflectance_sampling_rate": 1.5,
    }),
    ("thin", "principledthin", {
        "base_color": [0.7, 0.1, 0.1], "roughness": 0.4, "anisotropic": 0.5, "spec_trans": 0.6,
        "diff_trans": 1.4, "eta": 1.33, "sheen": 0.5, "sheen_tint": 0.3, "spec_tint": 0.2,
        "flatness": 0.5, "specular_reflectance_sampling_rate": 0.7,
        "diffuse_transmittance_sampling_rate": 1.3,
    }),
    ("sheen_without_diffuse", "principled", {
        "base_color": [0.4, 0.7, 0.2], "roughness": 0.9, "spec_trans": 1.0, "sheen": 1.0,
        "sheen_tint": 0.6,
    }),
    ("thin_diffuse", "principledthin", {
        "base_color": [0.3, 0.5, 0.9], "roughness": 0.8, "diff_trans": 0.6, "sheen": 0.2,
    }),
]

PAIRS_RANDOM = 40
PAIRS_NEAR_PEAKS = 16


def unit(v):
    return v / np.linalg.norm(v)


def bsdf_of(kind, params):
    d = {"type": kind}
    for key, value in params.items():
        d[key] = {"type": "rgb", "value": value} if isinstance(value, list) else value
    return mi.load_dict(d)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--variant", default="llvm_ad_rgb")
    mi.set_variant(ap.parse_args().variant)
    rng = np.random.default_rng(7)
    ctx = mi.BSDFContext()
    for name, kind, params in CONFIGS:
        words = " ".join(
            f"{k}={','.join(map(repr, v)) if isinstance(v, list) else repr(v)}"
            for k, v in params.items()
        )
        print(f"config {name} {kind} {words}".rstrip())
        bsdf = bsdf_of(kind, params)
        transmits = kind == "principledthin" or "spec_trans" in params
        pairs = []
        for _ in range(PAIRS_RANDOM):
            wi = unit(rng.normal(size=3))
            if not transmits and wi[2] < 0:
                wi[2] = -wi[2]
            pairs.append((wi, unit(rng.normal(size=3))))
        for i in range(PAIRS_NEAR_PEAKS):
            wi = unit(rng.normal(size=3))
            if not transmits or i % 2 == 0:
                wi[2] = abs(wi[2])
            mirror = np.array([-wi[0], -wi[1], wi[2]])
            wo = unit(mirror + 0.15 * rng.normal(size=3))
            if transmits and i % 4 < 2:
                wo = unit(-wi + 0.15 * rng.normal(size=3))
            pairs.append((wi, wo))
        for wi, wo in pairs:
            si = mi.SurfaceInteraction3f()
            si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
            si.wi = mi.Vector3f(*map(float, wi))
            value = np.array(bsdf.eval(ctx, si, mi.Vector3f(*map(float, wo)))).ravel()
            pdf = np.array(bsdf.pdf(ctx, si, mi.Vector3f(*map(float, wo)))).ravel()
            numbers = [*wi, *wo, *value, *pdf]
            print(" ".join(f"{float(x):.9g}" for x in numbers))


if __name__ == "__main__":
    main()
