"""Draws bench/scaling's CSV as an SVG: ms per step against the number of
boxes, log-log, one line per thread count, with the speed-up printed.

Plain SVG text, so that it needs nothing beyond Debian's python3.

Usage: plot_scaling.py SCALING_CSV OUT_SVG
"""

import csv
import math
import sys

WIDTH, HEIGHT = 640, 420
LEFT, RIGHT, TOP, BOTTOM = 70, 20, 30, 50
COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"]


def read(path):
    series = {}
    for row in csv.DictReader(open(path, encoding="utf-8")):
        try:
            point = (int(row["n"]), float(row["mean_ms"]))
        except ValueError:
            continue  # a failed point
        series.setdefault(int(row["threads"]), []).append(point)
    return series


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    series = read(argv[1])
    points = [p for line in series.values() for p in line]
    if not points:
        print("plot_scaling: no points", file=sys.stderr)
        return 1
    x_lo, x_hi = math.log10(min(p[0] for p in points)), math.log10(max(p[0] for p in points))
    y_lo = math.floor(math.log10(min(p[1] for p in points)))
    y_hi = math.ceil(math.log10(max(p[1] for p in points)))
    x_hi = max(x_hi, x_lo + 1e-9)

    def x(n):
        return LEFT + (math.log10(n) - x_lo) / (x_hi - x_lo) * (WIDTH - LEFT - RIGHT)

    def y(ms):
        return HEIGHT - BOTTOM - (math.log10(ms) - y_lo) / (y_hi - y_lo) * (HEIGHT - TOP - BOTTOM)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
           'font-family="sans-serif" font-size="12">',
           '<rect width="100%" height="100%" fill="white"/>',
           f'<text x="{WIDTH / 2}" y="18" text-anchor="middle">rbsim pile, no sleeping: ms per step</text>']
    for decade in range(y_lo, y_hi + 1):
        yy = y(10 ** decade)
        out.append(f'<line x1="{LEFT}" y1="{yy:.1f}" x2="{WIDTH - RIGHT}" y2="{yy:.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{LEFT - 6}" y="{yy + 4:.1f}" text-anchor="end">{10 ** decade:g}</text>')
    for n in sorted({p[0] for p in points}):
        xx = x(n)
        out.append(f'<line x1="{xx:.1f}" y1="{TOP}" x2="{xx:.1f}" y2="{HEIGHT - BOTTOM}" stroke="#eee"/>')
        out.append(f'<text x="{xx:.1f}" y="{HEIGHT - BOTTOM + 16}" text-anchor="middle">{n}</text>')
    out.append(f'<text x="{WIDTH / 2}" y="{HEIGHT - 12}" text-anchor="middle">boxes</text>')
    for k, (threads, line) in enumerate(sorted(series.items())):
        colour = COLOURS[k % len(COLOURS)]
        line.sort()
        path = " ".join(f"{x(n):.1f},{y(ms):.1f}" for n, ms in line)
        out.append(f'<polyline points="{path}" fill="none" stroke="{colour}" stroke-width="2"/>')
        for n, ms in line:
            out.append(f'<circle cx="{x(n):.1f}" cy="{y(ms):.1f}" r="3" fill="{colour}"/>')
        out.append(f'<text x="{LEFT + 10}" y="{TOP + 16 * (k + 1)}" fill="{colour}">'
                   f'{threads} thread{"s" if threads > 1 else ""}</text>')
    if 1 in series and 2 in series:
        one, two = dict(series[1]), dict(series[2])
        ups = [f"{n}: {one[n] / two[n]:.2f}x" for n in sorted(one) if n in two]
        out.append(f'<text x="{LEFT + 10}" y="{TOP + 16 * (len(series) + 1)}">speed-up '
                   f'{", ".join(ups)}</text>')
    out.append("</svg>")
    open(argv[2], "w", encoding="utf-8").write("\n".join(out) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
