#!/usr/bin/env python3
"""Per-class IPD on POLAR-Sim's own labels (rocks and shadows), checked by an independent re-count.

Builds a study from ../shared/data/polar-sim: each view lit from sun 180 is `real`, the same camera's view lit from
sun 30 is `synth` (scene names without the sun), real/labels/classes.txt names rock and shadow. The detector's
boxes are made here from the ground truth, seeded: each box moved by up to 15% of its size, one in ten dropped, one
in twenty given the other class, plus a few false boxes, with a confidence. Then it checks with the built `ipd`:

  1. without a class, `ipd table` refuses (exit 1) and prints no number;
  2. --class rock, --class 0 and rock_class: 0 in study.yaml give the same rock-only IPD; --class shadow another;
  3. every cell's IPD equals a re-count from the label files (Python; the performance value of each exported
     pair's rocks as their best IoU among predictions of their class) to 1e-9.

Usage: tests/tools/polar_class_check.py IPD [DATA_DIR]   (exit 0: all hold; 77: no data, skipped)
"""
import csv
import glob
import io
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile


from yolo_txt import read_boxes as read


def iou(a, b):
    ax0, ay0, ax1, ay1 = a[0] - a[2] / 2, a[1] - a[3] / 2, a[0] + a[2] / 2, a[1] + a[3] / 2
    bx0, by0, bx1, by1 = b[0] - b[2] / 2, b[1] - b[3] / 2, b[0] + b[2] / 2, b[1] + b[3] / 2
    iw, ih = min(ax1, bx1) - max(ax0, bx0), min(ay1, by1) - max(ay0, by0)
    if iw <= 0 or ih <= 0:
        return 0.0
    inter = iw * ih
    return inter / (a[2] * a[3] + b[2] * b[3] - inter)


def predictions(gt, rng):
    out = []
    for c, cx, cy, w, h in gt:
        if rng.random() < 0.1:
            continue
        if rng.random() < 0.05:
            c = 1 - c
        cx += rng.uniform(-0.15, 0.15) * w
        cy += rng.uniform(-0.15, 0.15) * h
        w *= rng.uniform(0.85, 1.15)
        h *= rng.uniform(0.85, 1.15)
        out.append((c, min(max(cx, 0.0), 1.0), min(max(cy, 0.0), 1.0), w, h, rng.uniform(0.3, 0.99)))
    for _ in range(rng.randint(0, 2)):
        out.append((rng.randint(0, 1), rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9), 0.02, 0.02, rng.uniform(0.3, 0.6)))
    return out


def build(data, root):
    rng = random.Random(1)
    for a in sorted(glob.glob(os.path.join(data, "Terrain*", "*_180_*_1024.txt"))):
        b = a.replace("_180_", "_30_")
        if not os.path.exists(b):
            continue
        stem = os.path.basename(a).replace("_180_", "_")[:-4]
        for domain, src in (("real", a), ("synth", b)):
            gt = read(src)
            os.makedirs(os.path.join(root, domain, "labels"), exist_ok=True)
            os.makedirs(os.path.join(root, domain, "predictions", "det-real"), exist_ok=True)
            with open(os.path.join(root, domain, "labels", stem + ".txt"), "w") as f:
                f.writelines(f"{c} {cx:.6f} {cy:.6f} {w:.6f} {h:.6f}\n" for c, cx, cy, w, h in gt)
            with open(os.path.join(root, domain, "predictions", "det-real", stem + ".txt"), "w") as f:
                f.writelines(f"{c} {cx:.6f} {cy:.6f} {w:.6f} {h:.6f} {p:.4f}\n" for c, cx, cy, w, h, p in
                             predictions(gt, rng))
    with open(os.path.join(root, "real", "labels", "classes.txt"), "w") as f:
        f.write("rock\nshadow\n")


def ipd(args):
    return subprocess.run(args, capture_output=True, text=True)


def cell(exe, root, *extra):
    r = ipd([exe, "table", root, "--format", "json", "--bootstrap", "0", "--no-cache", *extra])
    if r.returncode != 0:
        sys.exit(f"ipd table {' '.join(extra)} failed: {r.stderr}")
    cells = [c for c in json.loads(r.stdout)["cells"] if c["model"] == "det-real"]
    return cells[0]["ipd"], cells[0]["pairs"]


def recount(exe, root, cls_word, cls_id):
    r = ipd([exe, "export", "rocks", root, "--class", cls_word, "--no-cache"])
    if r.returncode != 0:
        sys.exit(f"ipd export rocks failed: {r.stderr}")
    total, n = 0.0, 0
    cache = {}

    def perf(domain, stem, cx, cy, w, h):
        key = (domain, stem)
        if key not in cache:
            cache[key] = read_pred(os.path.join(root, domain, "predictions", "det-real", stem + ".txt"))
        return max([iou((cx, cy, w, h), p[1:5]) for p in cache[key] if p[0] == cls_id] + [0.0])

    for row in csv.DictReader(io.StringIO(r.stdout)):
        if not row["index_a"] or not row["index_b"]:
            continue
        pa = perf("real", row["scene"], *(float(row[k]) for k in ("cx_a", "cy_a", "w_a", "h_a")))
        pb = perf("synth", row["scene"], *(float(row[k]) for k in ("cx_b", "cy_b", "w_b", "h_b")))
        total += abs(pa - pb)
        n += 1
    return total / n, n


def read_pred(path):
    out = []
    if not os.path.exists(path):
        return out
    for line in open(path):
        p = line.split()
        out.append((int(p[0]), *map(float, p[1:6])))
    return out


def main():
    exe = sys.argv[1]
    data = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), "../../../shared/data/polar-sim/labels")
    if not os.path.isdir(data):
        print(f"skipped: no POLAR-Sim labels at {data}")
        sys.exit(77)
    root = tempfile.mkdtemp()
    try:
        build(data, root)
        blind = ipd([exe, "table", root, "--bootstrap", "0", "--no-cache"])
        assert blind.returncode != 0 and "choose one with --class rock" in blind.stderr and blind.stdout == "", blind
        rock, rock_pairs = cell(exe, root, "--class", "rock")
        assert cell(exe, root, "--class", "0") == (rock, rock_pairs)
        with open(os.path.join(root, "study.yaml"), "w") as f:
            f.write("rock_class: 0\n")
        assert cell(exe, root) == (rock, rock_pairs)
        os.remove(os.path.join(root, "study.yaml"))
        shadow, shadow_pairs = cell(exe, root, "--class", "shadow")
        blind_all, all_pairs = cell(exe, root, "--class", "all")
        for word, cls, value, pairs in (("rock", 0, rock, rock_pairs), ("shadow", 1, shadow, shadow_pairs)):
            again, n = recount(exe, root, word, cls)
            assert n == pairs and abs(again - value) < 1e-9, (word, value, again, pairs, n)
        print(f"rock IPD {rock:.4f} ({rock_pairs} pairs), shadow IPD {shadow:.4f} ({shadow_pairs} pairs), "
              f"class-blind {blind_all:.4f} ({all_pairs} pairs); re-counted to 1e-9")
    finally:
        shutil.rmtree(root)


if __name__ == "__main__":
    main()
