#!/usr/bin/env python3
"""Where the live error estimate misses the truth by more than a factor 3, from the CSV that
`rope study --estimate-check` writes: the misses split by cause, and each method's share of
frames within the factor per group of scenes. The figures in docs/measurements.md come from it.

    python3 scripts/estimate-misses.py assets/estimate-check/estimate_check.csv
"""
import collections
import csv
import sys

RESOLVED, FACTOR, WINDOW, DIP = 1e-7, 3.0, 0.1, 0.2

path = sys.argv[1] if len(sys.argv) > 1 else "assets/estimate-check/estimate_check.csv"
cells = collections.defaultdict(list)
for r in csv.DictReader(open(path)):
    key = (r["method"], r["scene"], int(r["segments"]))
    cells[key].append((float(r["time"]), float(r["estimate"]), float(r["truth"])))

causes = collections.Counter()
elsewhere = collections.Counter()
share = {}
for key, frames in cells.items():
    judged = within = 0
    for t, e, truth in frames:
        if truth <= RESOLVED:
            continue
        judged += 1
        if 1 / FACTOR <= e / truth <= FACTOR:
            within += 1
            continue
        near = [f for f in frames if abs(f[0] - t) <= WINDOW]
        if t < WINDOW:
            causes["in the first 0.1 time units"] += 1
        elif truth < DIP * max(f[2] for f in near) or e < DIP * max(f[1] for f in near):
            causes["where the truth or the estimate dips towards zero"] += 1
        elif key[1].startswith("release") and t >= 1.3:
            causes["in a release from the whip on (t >= 1.3)"] += 1
        else:
            causes["elsewhere"] += 1
            elsewhere[key] += 1
    if judged:
        share[key] = 100.0 * within / judged

print(f"{sum(causes.values())} frames outside a factor {FACTOR}:")
for cause, n in causes.most_common():
    print(f"  {n:5d} {cause}")
for (method, scene, n), count in elsewhere.most_common():
    print(f"        elsewhere: {count} of {method} at N = {n} from the {scene}")
groups = {"from 0°": ["release at 0°"]}
groups["from 30°, 60° and the modes"] = [
    s for s in {k[1] for k in share} if s != "release at 0°" and s != "release at 90°"
]
for method in sorted({k[0] for k in share}):
    for name, scenes in groups.items():
        all_n = [v for k, v in share.items() if k[0] == method and k[1] in scenes]
        fine = [v for k, v in share.items() if k[0] == method and k[1] in scenes and k[2] >= 50]
        if all_n:
            print(
                f"{method} {name}: {min(all_n):.0f}–{max(all_n):.0f} % of frames within"
                f" (N ≥ 50: {min(fine):.0f}–{max(fine):.0f} %)"
            )
