#!/usr/bin/env python3
"""A reference's own error, read off the CSV that gives it (`references.csv` of
`rope study --tolerance-check`, or the `release-ANGLE.csv` files of
`examples/reference_convergence` with a folder): for each scene, the largest own error over
every row, over the instants on a 1/1000 grid, and over the frames a run logs (60 a time
unit), each with the time where it is largest, or "not given" where the file does not give
every instant of that grid (a file at 1000 a unit gives only every third frame); and how far
a cubic through every other row (rows i − 3, i − 1, i + 1, i + 3) misses row i, at worst: what
interpolating at twice the file's spacing would cost (at the file's own spacing about a
sixteenth of it, where the tip is smooth on that scale). The figures in docs/measurements.md on the
graded references come from it.

    python3 scripts/reference-errors.py assets/reference-convergence/graded-references/*.csv
"""
import collections
import csv
import sys

# The instants a time unit of each column; an instant is on a grid when t × rate is a whole
# number to within this (the CSVs give t to 16 digits).
GRIDS, ON_GRID = (("every row", None), ("every 1/1000", 1000), ("frames (60 a unit)", 60)), 1e-6

if len(sys.argv) < 2:
    sys.exit(__doc__)
worst = collections.defaultdict(lambda: {name: (0.0, 0.0) for name, _ in GRIDS})
found = collections.defaultdict(collections.Counter)
tips = collections.defaultdict(list)
for path in sys.argv[1:]:
    for r in csv.DictReader(open(path, encoding="utf-8")):
        scene, t, own = r["scene"], float(r["t"]), float(r["own_error"])
        tips[scene].append((t, float(r["tip_x"]), float(r["tip_y"])))
        for name, rate in GRIDS:
            if rate is None or abs(t * rate - round(t * rate)) < ON_GRID:
                found[scene][name] += 1
                if own > worst[scene][name][0]:
                    worst[scene][name] = (own, t)


def cubic_miss(samples):
    """The largest miss of row i by the cubic through rows i − 3, i − 1, i + 1, i + 3."""
    samples = sorted(samples)
    worst = (0.0, 0.0)
    for i in range(3, len(samples) - 3):
        (t, x, y), a, b, c, d = samples[i], samples[i - 3], samples[i - 1], samples[i + 1], samples[i + 3]
        mid = [(-a[k] + 9 * b[k] + 9 * c[k] - d[k]) / 16 for k in (1, 2)]
        worst = max(worst, (((mid[0] - x) ** 2 + (mid[1] - y) ** 2) ** 0.5, t))
    return worst


head = " | ".join(f"own error at {name} (at t)" for name, _ in GRIDS)
print(f"| scene | rows | {head} | cubic through every other row misses by (at t) |")
print("|---|---|" + "---|" * (len(GRIDS) + 1))
for scene, by_grid in worst.items():
    last = max(t for t, _, _ in tips[scene])

    def cell(name, rate):
        whole = rate is None or found[scene][name] >= round(last * rate) + 1
        own, t = by_grid[name]
        return f"{own:.1e} ({t:.4f})" if whole else "not given"

    cells = " | ".join(cell(name, rate) for name, rate in GRIDS)
    miss, at = cubic_miss(tips[scene])
    print(f"| {scene} | {len(tips[scene])} | {cells} | {miss:.1e} ({at:.4f}) |")
