#!/usr/bin/env python3
"""A study of one scene with N rocks a side (labels only), for timing ipd-studio on dense scenes.

Usage: tests/tools/dense_scene.py DIR N
real and synth share the same N random boxes (seed 1, sides 0.2-0.6% of the picture at 20,000 rocks,
0.4-1.4% below); det finds 80% of them, shifted by 0.1% of the width, at confidence 0.8 on both sides.
"""
import os
import random
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    root, n = sys.argv[1], int(sys.argv[2])
    random.seed(1)
    side, spread = (0.002, 0.004) if n > 5000 else (0.004, 0.01)
    rocks = [(random.random() * 0.98 + 0.01, random.random() * 0.98 + 0.01, side + random.random() * spread)
             for _ in range(n)]
    for domain in ("real", "synth"):
        os.makedirs(os.path.join(root, domain, "labels"), exist_ok=True)
        os.makedirs(os.path.join(root, domain, "predictions", "det"), exist_ok=True)
        with open(os.path.join(root, domain, "labels", "s1.txt"), "w") as f:
            for x, y, s in rocks:
                f.write(f"0 {x:.6f} {y:.6f} {s:.6f} {s:.6f}\n")
        with open(os.path.join(root, domain, "predictions", "det", "s1.txt"), "w") as f:
            for x, y, s in rocks[: n * 8 // 10]:
                f.write(f"0 {x + 0.001:.6f} {y:.6f} {s:.6f} {s:.6f} 0.8\n")


if __name__ == "__main__":
    main()
