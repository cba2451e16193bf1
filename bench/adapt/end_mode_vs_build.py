"""Medians per case of end_mode_vs_build.sh's output: python3 end_mode_vs_build.py OUT.txt"""
import collections
import statistics
import sys

runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    p = line.split()
    if len(p) == 7:
        runs[(p[0], p[1], int(p[2]), p[4])].append(float(p[5]))
cases = sorted({k[:3] for k in runs})
print("| mesh | kind | N | old ms | new ms | new / old |")
print("|---|---|---:|---:|---:|---:|")
ratios = []
for c in cases:
    o, n = statistics.median(runs[c + ("old",)]), statistics.median(runs[c + ("new",)])
    ratios.append(n / o)
    print(f"| {c[0]} | {c[1]} | {c[2]} | {o:.0f} | {n:.0f} | {n / o:.2f} |")
print(f"\nnew / old: median {statistics.median(ratios):.2f}, range {min(ratios):.2f}-{max(ratios):.2f}, "
      f"{sum(r <= 1 for r in ratios)} of {len(ratios)} cases not slower")
