#!/usr/bin/env python3
"""Draws soaks' samples (the CSVs of `scripts/web-check.py --soak`) as one SVG chart.

    scripts/soak-chart.py OUT.svg COLUMN LABEL=CSV[:COLUMN] [LABEL=CSV[:COLUMN] …]

COLUMN is a column of the CSVs (browser_mb, wasm_mb, rope_mb, …), drawn against minutes; a
series may name a column of its own after its CSV (`total=native-growth.csv:viewer_mb`), so
that several columns of one soak share a chart. A soak whose page stopped answering ends
with a cross at its last sample (a CSV without page_alive, such as a native viewer's, has no
page to stop). Plain SVG, no
plotting library: it reads on GitHub and in any browser.
"""

import csv
import pathlib
import sys

COLOURS = ["#c0392b", "#2471a3", "#1e8449", "#7d3c98", "#b9770e", "#566573"]
WIDTH, HEIGHT, LEFT, RIGHT, TOP, BOTTOM = 820, 420, 70, 230, 30, 50


def samples(path: pathlib.Path, column: str):
    """(minutes, value, alive) of each sample with the column, and whether the CSV has a page."""
    rows = []
    with path.open() as f:
        reader = csv.DictReader(f)
        for row in reader:
            if row.get(column) not in (None, ""):
                alive = row.get("page_alive", "1") == "1"
                rows.append((float(row["seconds"]) / 60, float(row[column]), alive))
        return rows, "page_alive" in (reader.fieldnames or [])


def main() -> int:
    if len(sys.argv) < 4:
        print(__doc__)
        return 2
    out, column, soaks, pages, own_columns = pathlib.Path(sys.argv[1]), sys.argv[2], [], False, False
    for arg in sys.argv[3:]:
        label, _, path = arg.partition("=")
        path, _, own = path.partition(":")
        rows, page = samples(pathlib.Path(path), own or column)
        soaks.append((label, rows))
        pages, own_columns = pages or page, own_columns or bool(own)
    # The value of a page that stopped answering is not its own: drawn as a cross at the last
    # live sample instead.
    live = [[s for s in rows if s[2]] for _, rows in soaks]
    x_max = max(s[0] for rows in live for s in rows)
    top = max(s[1] for rows in live for s in rows)
    tick = next(t for t in (50, 100, 200, 250, 500, 1000, 2000, 5000) if top / t <= 8)
    y_max = tick * (int(top // tick) + 1)
    plot_w, plot_h = WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM

    def x(m):
        return LEFT + plot_w * m / x_max

    def y(v):
        return TOP + plot_h * (1 - v / y_max)

    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
           f'font-family="sans-serif" font-size="12"><rect width="100%" height="100%" fill="white"/>']
    for i in range(int(y_max // tick) + 1):
        v = tick * i
        svg.append(f'<line x1="{LEFT}" x2="{LEFT + plot_w}" y1="{y(v):.1f}" y2="{y(v):.1f}" stroke="#ddd"/>')
        svg.append(f'<text x="{LEFT - 6}" y="{y(v) + 4:.1f}" text-anchor="end">{v:.0f}</text>')
    step = 10 if x_max > 30 else 5
    for m in range(0, int(x_max) + 1, step):
        svg.append(f'<text x="{x(m):.1f}" y="{TOP + plot_h + 18}" text-anchor="middle">{m}</text>')
    svg.append(f'<text x="{LEFT + plot_w / 2}" y="{HEIGHT - 10}" text-anchor="middle">minutes</text>')
    svg.append(f'<text x="14" y="{TOP + plot_h / 2}" transform="rotate(-90 14 {TOP + plot_h / 2})" '
               f'text-anchor="middle">{"" if own_columns else column + " "}(MB)</text>')
    svg.append(f'<rect x="{LEFT}" y="{TOP}" width="{plot_w}" height="{plot_h}" fill="none" stroke="#888"/>')
    for k, ((label, rows), alive) in enumerate(zip(soaks, live)):
        colour = COLOURS[k % len(COLOURS)]
        points = " ".join(f"{x(m):.1f},{y(v):.1f}" for m, v, _ in alive)
        svg.append(f'<polyline points="{points}" fill="none" stroke="{colour}" stroke-width="1.8"/>')
        if len(alive) < len(rows):  # the page stopped answering after its last live sample
            m, v, _ = alive[-1]
            svg.append(f'<text x="{x(m):.1f}" y="{y(v) + 5:.1f}" text-anchor="middle" fill="{colour}" '
                       f'font-size="16" font-weight="bold">✕</text>')
        svg.append(f'<line x1="{WIDTH - RIGHT + 12}" x2="{WIDTH - RIGHT + 32}" y1="{TOP + 10 + 22 * k}" '
                   f'y2="{TOP + 10 + 22 * k}" stroke="{colour}" stroke-width="3"/>')
        svg.append(f'<text x="{WIDTH - RIGHT + 38}" y="{TOP + 14 + 22 * k}">{label}</text>')
    if pages:
        svg.append(f'<text x="{WIDTH - RIGHT + 12}" y="{TOP + 14 + 22 * len(soaks)}">✕ page stopped</text>')
    svg.append("</svg>")
    out.write_text("\n".join(svg) + "\n")
    print(f"soak-chart: wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
