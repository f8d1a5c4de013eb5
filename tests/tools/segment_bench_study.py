#!/usr/bin/env python3
"""Writes a labels-only study for timing the segment task against the detect task on the same instances.

Two domains (real, synth) of SCENES scenes; each picture has 30 ground-truth outlines of 24 points and 40
predicted outlines (30 jittered copies, 10 strays), so `ipd table S --task segment` and `--task detect` read the
same files and differ only in the IoU. Deterministic for a seed.

Usage: tests/tools/segment_bench_study.py OUT_DIR [--scenes 10000] [--seed 1]
Then:  time build/app/ipd table OUT_DIR --no-cache --bootstrap 0 --task detect
       time build/app/ipd table OUT_DIR --no-cache --bootstrap 0 --task segment
"""
import math
import os
import random
import sys


def outline(rng, cx, cy, r, n=24):
    pts = []
    for k in range(n):
        a = 2 * math.pi * k / n
        rr = r * rng.uniform(0.6, 1.0)
        pts.append((min(max(cx + rr * math.cos(a), 0.0), 1.0), min(max(cy + rr * math.sin(a), 0.0), 1.0)))
    return pts


def fmt(cls, pts, conf=None):
    s = "%d " % cls + " ".join("%.6f %.6f" % p for p in pts)
    return s + (" %.4f\n" % conf if conf is not None else "\n")


def main():
    out = sys.argv[1]
    scenes = int(sys.argv[sys.argv.index("--scenes") + 1]) if "--scenes" in sys.argv else 10000
    seed = int(sys.argv[sys.argv.index("--seed") + 1]) if "--seed" in sys.argv else 1
    rng = random.Random(seed)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "study.yaml"), "w") as f:
        f.write("image_size: [1936, 1216]\ndomains: [real, synth]\nmodels: {det: {trained_on: real}}\n")
    for dom in ("real", "synth"):
        os.makedirs(os.path.join(out, dom, "labels"), exist_ok=True)
        os.makedirs(os.path.join(out, dom, "predictions", "det"), exist_ok=True)
    for s in range(scenes):
        stem = "s%05d" % s
        centres = [(rng.uniform(0.05, 0.95), rng.uniform(0.05, 0.95), rng.uniform(0.01, 0.03)) for _ in range(30)]
        for dom in ("real", "synth"):
            gt = [outline(rng, cx, cy, r) for cx, cy, r in centres]
            pred = [(outline(rng, cx + rng.uniform(-0.005, 0.005), cy + rng.uniform(-0.005, 0.005), r),
                     rng.uniform(0.3, 1)) for cx, cy, r in centres]
            pred += [(outline(rng, rng.uniform(0.05, 0.95), rng.uniform(0.05, 0.95), 0.02), rng.uniform(0.3, 1))
                     for _ in range(10)]
            with open(os.path.join(out, dom, "labels", stem + ".txt"), "w") as f:
                f.write("".join(fmt(0, g) for g in gt))
            with open(os.path.join(out, dom, "predictions", "det", stem + ".txt"), "w") as f:
                f.write("".join(fmt(0, p, c) for p, c in pred))


if __name__ == "__main__":
    main()
