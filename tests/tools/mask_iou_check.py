#!/usr/bin/env python3
"""Mask IoU against an independent reference: shapely's polygon areas.

Writes a labels-only study of random star-shaped outlines (non-convex, as rocks' masks are) in two domains, with
predictions that are jittered, shifted, shrunk or missing copies of them, runs `ipd export rocks --task segment
--format json --unpaired`, and checks every rock's performance value against the best shapely IoU among the
predictions of its class to 1e-9. Exits 1 on the first mismatch, naming the rock.

Usage: tests/tools/mask_iou_check.py IPD
"""
import json
import math
import os
import random
import subprocess
import sys
import tempfile

try:
    from shapely.geometry import Polygon
except ImportError:
    print("skipped: python3-shapely is not installed (apt install python3-shapely)")
    sys.exit(77)


def star(rng, cx, cy, r, n):
    # One point in each of n equal sectors: no gap between neighbours reaches half a turn, so the outline is a
    # simple (star-shaped) polygon with reflex corners where a radius dips.
    angles = [2 * math.pi * (k + rng.uniform(0, 0.8)) / n for k in range(n)]
    radii = [r * rng.uniform(0.45, 1.0) for _ in angles]
    return [(cx + rr * math.cos(a), cy + rr * math.sin(a)) for a, rr in zip(angles, radii)]


def line(cls, pts, conf=None):
    s = "%d %s" % (cls, " ".join("%.17g %.17g" % p for p in pts))
    return s + (" %.17g" % conf if conf is not None else "")


def main():
    ipd = sys.argv[1]
    rng = random.Random(7)
    root = tempfile.mkdtemp()
    with open(os.path.join(root, "study.yaml"), "w") as f:
        f.write("task: segment\nclasses: [rock, shadow]\nrock_class: rock\nimage_size: [1000, 1000]\n"
                "domains: [real, synth]\nmodels: {det: {trained_on: real}}\n")
    expected = {}  # (domain, stem, index) -> IoU
    for s in range(12):
        stem = "s%02d" % s
        centres = [(rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9)) for _ in range(8)]
        for dom in ("real", "synth"):
            gt, pred = [], []
            for k, (cx, cy) in enumerate(centres):
                g = star(rng, cx + (0.002 if dom == "synth" else 0), cy, rng.uniform(0.02, 0.05), rng.randint(5, 24))
                gt.append(g)
                for _ in range(rng.randint(0, 3)):
                    dx, dy, sc = rng.uniform(-0.01, 0.01), rng.uniform(-0.01, 0.01), rng.uniform(0.7, 1.2)
                    mx = sum(p[0] for p in g) / len(g)
                    my = sum(p[1] for p in g) / len(g)
                    # Scaled about a point inside and moved: still star-shaped, so a simple polygon for shapely.
                    q = [(mx + (p[0] - mx) * sc + dx, my + (p[1] - my) * sc + dy) for p in g]
                    pred.append((rng.choice([0, 0, 1]), q, rng.uniform(0.3, 1.0)))
            os.makedirs(os.path.join(root, dom, "labels"), exist_ok=True)
            os.makedirs(os.path.join(root, dom, "predictions", "det"), exist_ok=True)
            with open(os.path.join(root, dom, "labels", stem + ".txt"), "w") as f:
                f.write("".join(line(0, g) + "\n" for g in gt))
            with open(os.path.join(root, dom, "predictions", "det", stem + ".txt"), "w") as f:
                f.write("".join(line(c, q, conf) + "\n" for c, q, conf in pred))
            for i, g in enumerate(gt):
                pg = Polygon(g)
                best = 0.0
                for c, q, _ in pred:
                    if c != 0:
                        continue
                    pq = Polygon(q)
                    inter = pg.intersection(pq).area
                    best = max(best, inter / (pg.area + pq.area - inter) if inter > 0 else 0.0)
                expected[(dom, stem, i)] = best
    out = subprocess.run([ipd, "export", "rocks", root, "--format", "json", "--unpaired"], capture_output=True,
                         text=True)
    if out.returncode != 0:
        print("ipd export rocks failed:", out.stderr)
        return 1
    rows = json.loads(out.stdout)
    checked, worst = 0, 0.0
    for r in rows:
        for side, dom in (("a", r["a"]), ("b", r["b"])):
            i = r["index_" + side]
            if i is None:
                continue
            want = expected[(dom, r["scene"], i)]
            got = r["perf_" + side]
            if abs(got - want) > 1e-9:
                print("%s/%s rock %d: ipd %.15f, shapely %.15f" % (dom, r["scene"], i, got, want))
                return 1
            if r["task"] != "segment":
                print("row without task segment:", r)
                return 1
            worst = max(worst, abs(got - want))
            checked += 1
    if checked < 150:
        print("only %d rocks checked" % checked)
        return 1
    print("mask IoU of %d rocks matches shapely to 1e-9 (largest difference %.1e)" % (checked, worst))
    return 0


if __name__ == "__main__":
    sys.exit(main())
