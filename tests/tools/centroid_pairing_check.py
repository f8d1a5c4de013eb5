#!/usr/bin/env python3
"""Which centre pairs segmented rocks better: the box centre or the mask centroid?

Writes PAIRS real/synth label pairs of irregular rock outlines (YOLO-seg): the synthetic picture holds the same
rocks under a small camera change (turn, scale, shift), each outline traced again with its own vertex noise (as
two renderers and two labellings differ), 5% of the rocks dropped on each side and those leaving the picture
gone. Each pair is registered twice with `ipd register --json`: from the outlines as written (registration takes
the box centres) and from boxes moved onto the outlines' area centroids. Prints the pair precision, recall and F1
of each against the known correspondence, for a few noise levels. Deterministic for a seed.

Usage: tests/tools/centroid_pairing_check.py build/app/ipd [--pairs 60] [--seed 1]
"""
import json
import math
import os
import random
import subprocess
import sys
import tempfile


def outline(rng, r, n=16):
    # A lumpy, lopsided rock: radius varies with the angle, so the box centre and the centroid differ.
    lump = [rng.uniform(0.55, 1.0) for _ in range(n)]
    return [(r * lump[k] * math.cos(2 * math.pi * k / n), r * lump[k] * math.sin(2 * math.pi * k / n)) for k in range(n)]


def area_centroid(pts):
    a = cx = cy = 0.0
    for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1]):
        c = x0 * y1 - x1 * y0
        a += c
        cx += (x0 + x1) * c
        cy += (y0 + y1) * c
    return cx / (3 * a), cy / (3 * a)


def line(pts):
    return "0 " + " ".join("%.6f %.6f" % p for p in pts) + "\n"


def box_line_at_centroid(pts):
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    cx, cy = area_centroid(pts)
    return "0 %.6f %.6f %.6f %.6f\n" % (cx, cy, max(xs) - min(xs), max(ys) - min(ys))


def make_pair(rng, noise, count):
    rocks = []
    for _ in range(rng.randint(count // 2, count)):
        r = rng.uniform(0.01, 0.035)
        rocks.append((rng.uniform(0.05, 0.95), rng.uniform(0.05, 0.95), outline(rng, r)))
    ang, s = math.radians(rng.uniform(-3, 3)), rng.uniform(0.97, 1.03)
    tx, ty = rng.uniform(-0.03, 0.03), rng.uniform(-0.03, 0.03)
    real, synth, truth = [], [], []
    for k, (cx, cy, shape) in enumerate(rocks):
        a_pts = [(cx + x, cy + y) for x, y in shape]
        # The synthetic rock: the same shape moved by the camera change, each vertex traced again.
        b_pts = []
        for x, y in shape:
            jx, jy = x * (1 + rng.gauss(0, noise)), y * (1 + rng.gauss(0, noise))
            px, py = cx + jx, cy + jy
            b_pts.append((s * (math.cos(ang) * px - math.sin(ang) * py) + tx,
                          s * (math.sin(ang) * px + math.cos(ang) * py) + ty))
        inside = all(0 <= x <= 1 and 0 <= y <= 1 for x, y in a_pts + b_pts)
        if not inside:
            continue
        keep_a, keep_b = rng.random() > 0.05, rng.random() > 0.05
        if keep_a:
            real.append(a_pts)
        if keep_b:
            synth.append(b_pts)
        if keep_a and keep_b:
            truth.append((len(real) - 1, len(synth) - 1))
    return real, synth, truth


def score(found, truth):
    found, truth = set(map(tuple, found)), set(truth)
    tp = len(found & truth)
    p = tp / len(found) if found else 0.0
    r = tp / len(truth) if truth else 0.0
    return tp, len(found), len(truth), p, r, (2 * p * r / (p + r) if p + r else 0.0)


def register(ipd, a, b):
    out = subprocess.run([ipd, "register", a, b, "--json", "--image-size", "1936,1216"], capture_output=True,
                         text=True, check=True).stdout
    return json.loads(out)["pairs"]


def main():
    ipd = sys.argv[1]
    n = int(sys.argv[sys.argv.index("--pairs") + 1]) if "--pairs" in sys.argv else 60
    seed = int(sys.argv[sys.argv.index("--seed") + 1]) if "--seed" in sys.argv else 1
    print("rocks   noise  centre     TP / found / true   precision  recall  F1")
    with tempfile.TemporaryDirectory() as d:
        for count in (45, 180):
            for noise in (0.05, 0.15, 0.30):
                rng = random.Random(seed)
                totals = {"box centre": [0, 0, 0], "mask centroid": [0, 0, 0]}
                for k in range(n):
                    real, synth, truth = make_pair(rng, noise, count)
                    for name, writer in (("box centre", line), ("mask centroid", box_line_at_centroid)):
                        a, b = os.path.join(d, "a.txt"), os.path.join(d, "b.txt")
                        with open(a, "w") as f:
                            f.writelines(writer(p) for p in real)
                        with open(b, "w") as f:
                            f.writelines(writer(p) for p in synth)
                        tp, found, true, _, _, _ = score(register(ipd, a, b), truth)
                        t = totals[name]
                        t[0] += tp
                        t[1] += found
                        t[2] += true
                for name, (tp, found, true) in totals.items():
                    p, r = tp / max(found, 1), tp / max(true, 1)
                    f1 = 2 * p * r / max(p + r, 1e-12)
                    print("%3d-%-3d %.2f   %-13s %5d / %5d / %5d   %.4f     %.4f  %.4f" %
                          (count // 2, count, noise, name, tp, found, true, p, r, f1))


if __name__ == "__main__":
    main()
