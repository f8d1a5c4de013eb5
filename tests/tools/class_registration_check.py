#!/usr/bin/env python3
"""Registration from one class or from every box: which recovers the camera better on POLAR-Sim views?

Pairs each POLAR view lit from sun 180 with the same camera's view lit from sun 30 (the camera did not move, so
the truth is the identity), moves the second view's boxes by a known affine, and registers the two with
`ipd register` twice: from rocks alone (`--class 0`) and from rocks and shadows (no --class; pairs then stay
within a class). Scores each answer by the mean pixel distance between where the truth and the answer put A's
rock centres, and prints, per choice, the share of views within 5 and 20 px and the median error.

Usage: tests/tools/class_registration_check.py IPD DATA_DIR [--terrains 01,02]   (DATA_DIR: .../polar-sim/labels)
"""
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

W, H = 1936, 1216


from yolo_txt import read_boxes as read


def truth(cx, cy):
    # 2 degrees of rotation about the picture's centre (in pixels), 4% scale, a shift of 40 and -25 px.
    x, y = cx * W - W / 2, cy * H - H / 2
    a, s = math.radians(2.0), 1.04
    u = s * (math.cos(a) * x - math.sin(a) * y) + W / 2 + 40
    v = s * (math.sin(a) * x + math.cos(a) * y) + H / 2 - 25
    return u / W, v / H


def main():
    ipd, data = sys.argv[1], sys.argv[2]
    terrains = None
    if "--terrains" in sys.argv:
        terrains = sys.argv[sys.argv.index("--terrains") + 1].split(",")
    tmp = tempfile.mkdtemp()
    jobs = []
    for a in sorted(glob.glob(os.path.join(data, "Terrain*", "*_180_*_1024.txt"))):
        if terrains and os.path.basename(os.path.dirname(a))[-2:] not in terrains:
            continue
        b = a.replace("_180_", "_30_")
        if not os.path.exists(b):
            continue
        boxes_a, boxes_b = read(a), read(b)
        if sum(1 for x in boxes_a if x[0] == 0) < 3 or sum(1 for x in boxes_b if x[0] == 0) < 3:
            continue
        moved = os.path.join(tmp, os.path.basename(b))
        with open(moved, "w") as f:
            for c, cx, cy, w, h in boxes_b:
                u, v = truth(cx, cy)
                if not (0.01 < u < 0.99 and 0.01 < v < 0.99):  # moved out of the picture: not seen
                    continue
                f.write(f"{c} {u:.6f} {v:.6f} {w * 1.04:.6f} {h * 1.04:.6f}\n")
        jobs.append((a, moved, [(cx, cy) for c, cx, cy, w, h in boxes_a if c == 0]))
    listing = os.path.join(tmp, "list.txt")
    with open(listing, "w") as f:
        for a, b, _ in jobs:
            f.write(f"{a}\t{b}\n")
    results = {}
    for name, extra in (("rocks only (--class 0)", ["--class", "0"]), ("rocks and shadows", [])):
        out = subprocess.run([ipd, "register", "--list", listing, "--json", "--image-size", f"{W},{H}"] + extra,
                             capture_output=True, text=True, check=True).stdout
        errors = []
        for line, (_, _, rocks) in zip(out.splitlines(), jobs):
            m = json.loads(line)["affine"]
            e = 0
            for cx, cy in rocks:
                tu, tv = truth(cx, cy)
                u = m[0][0] * cx + m[0][1] * cy + m[0][2]
                v = m[1][0] * cx + m[1][1] * cy + m[1][2]
                e += math.hypot((u - tu) * W, (v - tv) * H)
            errors.append(e / len(rocks))
        errors.sort()
        results[name] = errors
        n = len(errors)
        print(f"{name:<24} views {n}  within 5 px {sum(e < 5 for e in errors) / n:.3f}  within 20 px "
              f"{sum(e < 20 for e in errors) / n:.3f}  median {errors[n // 2]:.2f} px")


if __name__ == "__main__":
    main()
