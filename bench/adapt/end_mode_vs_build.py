"""Medians per case of end_mode_vs_build.sh's output:
    python3 end_mode_vs_build.py [--equal-quality] OUT.txt
With --equal-quality (the script's mode of the same name) the 7th field is the PSNR: the table adds
it, "old" ran at 2N, and the summary is per N (time new / old and PSNR new − old)."""
import collections
import statistics
import sys

args = sys.argv[1:]
equal_quality = bool(args) and args[0] == "--equal-quality"
if equal_quality:
    args = args[1:]
ms, extra = collections.defaultdict(list), collections.defaultdict(list)
for line in open(args[0]):
    p = line.split()
    if len(p) == 7:
        key = (p[0], p[1], int(p[2]), p[4])
        ms[key].append(float(p[5]))
        extra[key].append(float(p[6]))
cases = sorted({k[:3] for k in ms})
if equal_quality:
    print("| mesh | kind | N | old at 2N: ms / dB | new at N: ms / dB | time new / old | dB new − old |")
    print("|---|---|---:|---|---|---:|---:|")
else:
    print("| mesh | kind | N | old ms | new ms | new / old |")
    print("|---|---|---:|---:|---:|---:|")
ratios, gains = collections.defaultdict(list), collections.defaultdict(list)
for c in cases:
    o, n = statistics.median(ms[c + ("old",)]), statistics.median(ms[c + ("new",)])
    group = c[2] if equal_quality else "all"
    ratios[group].append(n / o)
    if equal_quality:
        po, pn = statistics.median(extra[c + ("old",)]), statistics.median(extra[c + ("new",)])
        gains[group].append(pn - po)
        print(f"| {c[0]} | {c[1]} | {c[2]} | {o:.0f} / {po:.2f} | {n:.0f} / {pn:.2f} | {n / o:.2f} | {pn - po:+.2f} |")
    else:
        print(f"| {c[0]} | {c[1]} | {c[2]} | {o:.0f} | {n:.0f} | {n / o:.2f} |")
print()
for group, r in ratios.items():
    head = f"N = {group}: " if equal_quality else ""
    line = (f"{head}new / old: median {statistics.median(r):.2f}, range {min(r):.2f}-{max(r):.2f}, "
            f"{sum(x <= 1 for x in r)} of {len(r)} cases not slower")
    if equal_quality:
        g = gains[group]
        line += (f"; PSNR new - old: median {statistics.median(g):+.2f}, range {min(g):+.2f}..{max(g):+.2f} dB, "
                 f"{sum(x >= -0.1 for x in g)} of {len(g)} not worse by > 0.1 dB")
    print(line)
