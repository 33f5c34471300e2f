#!/usr/bin/env python3
"""What denoising buys: time to a given error, denoised against not.

Renders SCENE at a rising spp with `--denoise`, and measures each noisy and denoised EXR
against a high-spp reference with `embray compare` (its per-pixel relMSE, mean of
(x − r)² / (r² + 0.01), as denoising work reports: the energy-weighted relative MSE would
be swamped by the light's pixels, whose edges any denoiser softens). The time of a noisy
image is its render time; a denoised one adds the denoiser's time. Prints a table per spp
and, for each error the noisy renders reach, the time the denoised ones need to reach it
(log-log interpolation between the spp measured).

    bash scripts/oidn-runtime.sh; cargo build --release --features denoise
    python3 scripts/denoise_time_to_error.py scenes/cornell.toml --reference-spp 8192

Timings are medians of --repeats runs; run nothing else meanwhile.
"""

import argparse
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile

SUMMARY = re.compile(r"render ([0-9.]+) s")
DENOISED = re.compile(r"denoised in ([0-9.]+) s")
REL_MSE = re.compile(r"per-pixel relMSE ([0-9.e+-]+)")


def run(cmd):
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{done.stderr}")
    return done.stdout + done.stderr


def rel_mse(embray, image, reference):
    return float(REL_MSE.search(run([embray, "compare", image, reference])).group(1))


def time_to(error, points):
    """The time at which the (time, error) curve first reaches `error` (log-log), as text:
    '≤ t' when its first point is already below."""
    if points and points[0][1] <= error:
        return f"≤ {points[0][0]:.3f}", points[0][0]
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if e0 >= error >= e1 and e0 > e1:
            f = math.log(e0 / error) / math.log(e0 / e1)
            t = math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
            return f"{t:.3f}", t
    return None, None


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene")
    p.add_argument("--embray", default="target/release/embray")
    p.add_argument("--resolution", help="WxH (default: the scene's)")
    p.add_argument("--camera", help="for multi-camera CENG795 files")
    p.add_argument("--reference-spp", type=int, default=8192)
    p.add_argument("--spp", default="1,2,4,8,16,32,64,128,256")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--keep", help="a folder for the images (default: a temporary one)")
    args = p.parse_args()

    folder = args.keep or tempfile.mkdtemp(prefix="embray-denoise-")
    os.makedirs(folder, exist_ok=True)
    common = [args.embray, "render", args.scene]
    if args.resolution:
        common += ["--resolution", args.resolution]
    if args.camera:
        common += ["--camera", args.camera]
    reference = os.path.join(folder, "reference.exr")
    if not os.path.exists(reference):
        print(f"reference: {args.reference_spp} spp …", file=sys.stderr)
        run(common + ["--spp", str(args.reference_spp), "-o", reference, "-q"])

    rows = []
    for spp in [int(s) for s in args.spp.split(",")]:
        noisy = os.path.join(folder, f"spp{spp}.exr")
        renders, denoises = [], []
        for _ in range(args.repeats):
            said = run(common + ["--spp", str(spp), "--denoise", "-o", noisy])
            renders.append(float(SUMMARY.search(said).group(1)))
            denoises.append(float(DENOISED.search(said).group(1)))
        render, denoise = statistics.median(renders), statistics.median(denoises)
        denoised = noisy.replace(".exr", ".denoised.exr")
        rows.append((spp, render, rel_mse(args.embray, noisy, reference),
                     render + denoise, rel_mse(args.embray, denoised, reference), denoise))

    print(f"{args.scene}: per-pixel relMSE against {args.reference_spp} spp "
          f"(medians of {args.repeats} runs)")
    print("| spp | noisy: time (s) | noisy: relMSE | denoised: time (s) | denoised: relMSE |")
    print("|---|---|---|---|---|")
    for spp, t_noisy, e_noisy, t_den, e_den, _ in rows:
        print(f"| {spp} | {t_noisy:.3f} | {e_noisy:.3e} | {t_den:.3f} | {e_den:.3e} |")
    print(f"denoiser time: median {statistics.median(r[5] for r in rows):.3f} s")
    denoised_curve = [(r[3], r[4]) for r in rows]
    print("\n| error (per-pixel relMSE) | noisy reaches it in (s) | denoised in (s) | speed-up |")
    print("|---|---|---|---|")
    for spp, t_noisy, e_noisy, *_ in rows:
        text, t_den = time_to(e_noisy, denoised_curve)
        if t_den is None:
            print(f"| {e_noisy:.3e} ({spp} spp noisy) | {t_noisy:.3f} | not reached | – |")
        else:
            bound = "≥ " if text.startswith("≤") else ""
            print(f"| {e_noisy:.3e} ({spp} spp noisy) | {t_noisy:.3f} | {text} | "
                  f"{bound}{t_noisy / t_den:.1f}× |")


if __name__ == "__main__":
    main()
