#!/usr/bin/python3
"""Independent cross-check of `ipd`'s statistics with numpy (no network, no ipd code).

Writes a small labels-only study, runs `ipd table --format json`, `ipd export rocks` and `ipd metrics --json`,
and recomputes from the exported CSV and the label files:
  1. every cell's IPD and pair count (mean of `diff` over the cell's rows);
  2. every cell's scene-bootstrap interval, exactly, by replaying ipd's documented random stream
     (splitmix64 seeded with seed ^ FNV-1a("model|a|b"), index = ((x >> 32) * n) >> 32), and, within Monte
     Carlo error, with numpy's own generator;
  3. AP@0.5, AP@0.5:0.95, precision, recall and F1 with pycocotools' COCOeval logic re-written in numpy.
Usage: crosscheck_stats.py IPD_BINARY. Exit 0 when all agree, 1 otherwise, 77 when numpy is missing.
"""
import csv
import io
import json
import os
import subprocess
import sys
import tempfile

try:
    import numpy as np
except ImportError:
    print("numpy is not installed (apt-get install python3-numpy): skipped")
    sys.exit(77)

MASK = (1 << 64) - 1
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def write_study(root, rng):
    os.makedirs(root, exist_ok=True)
    with open(os.path.join(root, "study.yaml"), "w") as f:
        f.write("domains: [real, synth]\nimage_size: [800, 600]\nmodels: {det: {trained_on: real}, "
                "det2: {trained_on: synth}}\n")
    for s in range(15):
        n = int(rng.integers(6, 14))
        cx, cy = rng.uniform(0.1, 0.9, n), rng.uniform(0.1, 0.9, n)
        w = rng.uniform(0.02, 0.1, n)
        h = w * rng.uniform(0.7, 1.2, n)
        for dom in ("real", "synth"):
            jx = 0 if dom == "real" else rng.uniform(-0.002, 0.002, n)
            gx, gy = cx + jx, cy + (0 if dom == "real" else rng.uniform(-0.002, 0.002, n))
            os.makedirs(os.path.join(root, dom, "labels"), exist_ok=True)
            with open(os.path.join(root, dom, "labels", f"s{s:02d}.txt"), "w") as f:
                for k in range(n):
                    f.write(f"0 {gx[k]:.6f} {gy[k]:.6f} {w[k]:.6f} {h[k]:.6f}\n")
            for model in ("det", "det2"):
                d = os.path.join(root, dom, "predictions", model)
                os.makedirs(d, exist_ok=True)
                with open(os.path.join(d, f"s{s:02d}.txt"), "w") as f:
                    for k in range(n):
                        if rng.uniform() < 0.15:
                            continue  # a missed rock
                        shift = rng.uniform(0, 0.6) * w[k]
                        conf = round(rng.uniform(0.05, 0.95), 1)  # rounded: many ties in confidence
                        f.write(f"0 {gx[k] + shift:.6f} {gy[k]:.6f} {w[k]:.6f} {h[k]:.6f} {conf:.2f}\n")
                    for _ in range(int(rng.integers(0, 3))):  # false positives
                        f.write(f"0 {rng.uniform(0.1, 0.9):.6f} {rng.uniform(0.1, 0.9):.6f} 0.05 0.05 "
                                f"{round(rng.uniform(0.05, 0.95), 1):.2f}\n")


def run(ipd, *args):
    return subprocess.run([ipd, *args], check=True, capture_output=True, text=True).stdout


# ---- ipd's random stream, from its documentation in core/stats/statistics.h -----------------------
def fnv1a(s):
    h = 0xcbf29ce484222325
    for c in s.encode():
        h = ((h ^ c) * 0x100000001b3) & MASK
    return h


class SplitMix:
    def __init__(self, seed, key):
        self.state = seed ^ fnv1a(key)
        self.state = self.next()

    def next(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & MASK
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        return z ^ (z >> 31)

    def indices(self, n):
        return np.array([((self.next() >> 32) * n) >> 32 for _ in range(n)])


def percentile_ci(values, level):
    values = np.asarray(values)
    return np.percentile(values, 50 * (1 - level)), np.percentile(values, 100 - 50 * (1 - level)), values.std(ddof=1)


def bootstrap(sums, counts, resamples, level, draw):
    vals = []
    for _ in range(resamples):
        idx = draw(len(sums))
        c = counts[idx].sum()
        if c > 0:
            vals.append(sums[idx].sum() / c)
    return percentile_ci(vals, level)


# ---- pycocotools' COCOeval (evaluateImg + accumulate + summarize) for one class, area all -------------------
def iou(a, b):
    ax0, ay0, ax1, ay1 = a[0] - a[2] / 2, a[1] - a[3] / 2, a[0] + a[2] / 2, a[1] + a[3] / 2
    bx0, by0, bx1, by1 = b[0] - b[2] / 2, b[1] - b[3] / 2, b[0] + b[2] / 2, b[1] + b[3] / 2
    iw, ih = max(0.0, min(ax1, bx1) - max(ax0, bx0)), max(0.0, min(ay1, by1) - max(ay0, by0))
    inter = iw * ih
    union = a[2] * a[3] + b[2] * b[3] - inter
    return inter / union if union > 0 else 0.0


def coco_ap(images, t, max_dets=100):
    scores, matched, npig = [], [], 0
    for gt, dt in images:
        npig += len(gt)
        order = np.argsort([-d[4] for d in dt], kind="mergesort")[:max_dets]
        gtm = [False] * len(gt)
        for di in order:
            best, m = min(t, 1 - 1e-10), -1
            for gi, g in enumerate(gt):
                if gtm[gi]:
                    continue
                v = iou(dt[di], g)
                if v < best:
                    continue
                best, m = v, gi
            if m >= 0:
                gtm[m] = True
            scores.append(dt[di][4])
            matched.append(m >= 0)
    if npig == 0:
        return float("nan")
    inds = np.argsort(-np.array(scores), kind="mergesort")
    tps = np.array(matched, dtype=bool)[inds]
    tp, fp = np.cumsum(tps).astype(float), np.cumsum(~tps).astype(float)
    rc, pr = tp / npig, (tp / (fp + tp + np.spacing(1))).tolist()
    for i in range(len(pr) - 1, 0, -1):
        pr[i - 1] = max(pr[i - 1], pr[i])
    rec_thrs = np.linspace(0.0, 1.00, int(np.round((1.00 - 0.0) / 0.01)) + 1, endpoint=True)
    q = np.zeros(len(rec_thrs))
    for ri, pi in enumerate(np.searchsorted(rc, rec_thrs, side="left")):
        if pi < len(pr):
            q[ri] = pr[pi]
    return q.mean()


def read_boxes(path, pred):
    out = []
    if os.path.exists(path):
        for line in open(path):
            v = line.split()
            if v:
                out.append([float(x) for x in v[1:6 if pred else 5]])
    return out


def main():
    ipd = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        root = os.path.join(tmp, "study")
        write_study(root, np.random.default_rng(11))
        seed, resamples, level = 3, 2000, 0.9
        table = json.loads(run(ipd, "table", root, "--format", "json", "--seed", str(seed), "--bootstrap",
                               str(resamples), "--ci", str(level), "--no-cache"))
        rows = list(csv.DictReader(io.StringIO(run(ipd, "export", "rocks", root, "--seed", str(seed), "--no-cache"))))
        metrics = json.loads(run(ipd, "metrics", root, "--json", "--conf", "0.5", "--no-cache"))

        for cell in table["cells"]:
            key = f"{cell['model']}|{cell['a']}|{cell['b']}"
            mine = [r for r in rows if (r["model"], r["a"], r["b"]) == (cell["model"], cell["a"], cell["b"])]
            diffs = np.array([float(r["diff"]) for r in mine])
            check(len(mine) == cell["pairs"] and abs(diffs.mean() - cell["ipd"]) < 1e-9,
                  f"{key}: mean diff of {len(mine)} exported rows {diffs.mean():.10f} = IPD {cell['ipd']:.10f}")
            scenes = sorted({r["scene"] for r in mine})
            if len(scenes) != cell["scenes"]:
                check(False, f"{key}: every scene has pairs (needed to replay the stream)")
                continue
            sums = np.array([sum(float(r["diff"]) for r in mine if r["scene"] == s) for s in scenes])
            counts = np.array([sum(1 for r in mine if r["scene"] == s) for s in scenes])
            stream = SplitMix(seed, key)
            lo, hi, se = bootstrap(sums, counts, resamples, level, stream.indices)
            check(abs(lo - cell["ci_low"]) < 1e-9 and abs(hi - cell["ci_high"]) < 1e-9 and abs(se - cell["se"]) < 1e-9,
                  f"{key}: replayed {level:g} interval [{lo:.6f}, {hi:.6f}] se {se:.6f} = ipd's "
                  f"[{cell['ci_low']:.6f}, {cell['ci_high']:.6f}] se {cell['se']:.6f}")
            rng = np.random.default_rng(5)
            lo2, hi2, se2 = bootstrap(sums, counts, 4000, level, lambda n: rng.integers(0, n, n))
            tol = 0.2 * se2
            check(abs(lo2 - cell["ci_low"]) < tol and abs(hi2 - cell["ci_high"]) < tol and abs(se2 - cell["se"]) < tol,
                  f"{key}: numpy's own bootstrap [{lo2:.4f}, {hi2:.4f}] se {se2:.4f} within {tol:.4f} of ipd's")

        for m in metrics["metrics"]:
            images = []
            for s in sorted(os.listdir(os.path.join(root, m["domain"], "labels"))):
                gt = read_boxes(os.path.join(root, m["domain"], "labels", s), False)
                dt = read_boxes(os.path.join(root, m["domain"], "predictions", m["model"], s), True)
                images.append((gt, dt))
            ap50 = coco_ap(images, 0.5)
            ap = np.mean([coco_ap(images, t) for t in np.linspace(0.5, 0.95, int(np.round((0.95 - 0.5) / 0.05)) + 1)])
            kept = [(gt, [d for d in dt if d[4] >= 0.5]) for gt, dt in images]
            tp = 0
            for gt, dt in kept:
                order = np.argsort([-d[4] for d in dt], kind="mergesort")
                used = [False] * len(gt)
                for di in order:
                    best, g = 0.5, -1
                    for gi in range(len(gt)):
                        if not used[gi] and iou(dt[di], gt[gi]) >= best:
                            best, g = iou(dt[di], gt[gi]), gi
                    if g >= 0:
                        used[g] = True
                        tp += 1
            ndet, ngt = sum(len(d) for _, d in kept), sum(len(g) for g, _ in kept)
            p, r = tp / ndet, tp / ngt
            name = f"{m['model']} on {m['domain']}"
            check(abs(ap50 - m["ap50"]) < 1e-12, f"{name}: AP50 {ap50:.6f} = ipd's {m['ap50']:.6f}")
            check(abs(ap - m["ap50_95"]) < 1e-12, f"{name}: AP50:95 {ap:.6f} = ipd's {m['ap50_95']:.6f}")
            check(ndet == m["detections"] and ngt == m["gt"] and abs(p - m["precision"]) < 1e-12 and
                  abs(r - m["recall"]) < 1e-12 and abs(2 * p * r / (p + r) - m["f1"]) < 1e-12,
                  f"{name}: P {p:.4f} R {r:.4f} F1 {2 * p * r / (p + r):.4f} at conf 0.5 = ipd's")
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
