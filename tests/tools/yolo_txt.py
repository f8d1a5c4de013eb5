"""Reading YOLO txt label files for the checking tools: `class cx cy w h` lines, others skipped (POLAR-Sim has a
line with a file name pasted into it)."""


def read_boxes(path):
    out = []
    for line in open(path):
        p = line.split()
        if len(p) != 5:
            continue
        try:
            out.append((int(p[0]), *map(float, p[1:])))
        except ValueError:
            continue
    return out
