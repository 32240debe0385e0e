#!/usr/bin/env python3
"""How far an atlas's entries moved when they were measured again against other references:
for every (set, angle, N) that two atlas CSVs (as `examples/release_atlas` writes them) both
hold, the change of the worst tip error over the two references' own errors together. Below 1
at every entry, the two measurements agree within what their references can tell; the
largest such ratio, and where, is printed. The figures in docs/measurements.md on the atlases
remeasured against the tolerance check's references come from it.

    python3 scripts/atlas-shift.py <(git show 7b8ebdb~1:assets/release-atlas/atlas.csv) \\
        assets/release-atlas/atlas.csv
    python3 scripts/atlas-shift.py assets/release-atlas/graded-atlas.csv \\
        assets/release-atlas/graded-atlas-angles-read.csv
"""
import csv
import sys


def entries(path):
    """(set, angle, N) → (worst, reference's own error) of an atlas CSV."""
    with open(path, newline="") as f:
        return {
            (r["set"], float(r["angle_deg"]), int(r["segments"])): (
                float(r["worst"]),
                float(r["reference_own_error"]),
            )
            for r in csv.DictReader(f)
        }


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: atlas-shift.py BEFORE.csv AFTER.csv")
    before, after = entries(sys.argv[1]), entries(sys.argv[2])
    shared = sorted(before.keys() & after.keys())
    if not shared:
        sys.exit("the two atlases share no entry")
    ratios = []
    for key in shared:
        (worst0, own0), (worst1, own1) = before[key], after[key]
        ratios.append((abs(worst1 - worst0) / (own0 + own1), key))
    ratio, (kind, angle, n) = max(ratios)
    above = sum(1 for r, _ in ratios if r >= 1.0)
    print(f"{len(shared)} entries in both; {above} moved by their references' own errors or more")
    print(f"largest change over the own errors together: {ratio:.2f} ({kind} {angle:g}°, N = {n})")


if __name__ == "__main__":
    main()
