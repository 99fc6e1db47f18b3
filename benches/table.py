#!/usr/bin/env python3
"""Prints the last `cargo bench` results as Markdown tables: one per benchmark group, one row per
parameter (size, light count, …), one column per path, in Mpix/s (median), plus the ratios the
project tracks. Reads target/criterion/*/*/*/new/{benchmark,estimates}.json; run it after
`cargo bench`."""

import glob
import json
import os
import sys

root = sys.argv[1] if len(sys.argv) > 1 else "target/criterion"
results = {}  # group -> param -> path -> (Mpix/s, ms)
for bench in glob.glob(os.path.join(root, "**", "new", "benchmark.json"), recursive=True):
    meta = json.load(open(bench))
    est = json.load(open(os.path.join(os.path.dirname(bench), "estimates.json")))
    seconds = est["median"]["point_estimate"] / 1e9
    pixels = (meta.get("throughput") or {}).get("Elements")
    if not pixels:
        continue
    group = results.setdefault(meta["group_id"], {})
    group.setdefault(meta["value_str"], {})[meta["function_id"]] = (pixels / seconds / 1e6, seconds * 1e3)

order = ["scalar", "simd4", "simd8", "fixed"]


def num(param):
    head = param.split("x")[0].split("-")[0]
    return (0, int(head)) if head.isdigit() else (1, param)


for group in sorted(results):
    params = results[group]
    paths = [p for p in order if any(p in v for v in params.values())]
    paths += sorted({p for v in params.values() for p in v} - set(paths))
    print(f"\n{group} (Mpix/s, median; ms per frame in parentheses)\n")
    print("| | " + " | ".join(paths) + " |")
    print("|---" * (len(paths) + 1) + "|")
    for param in sorted(params, key=num):
        cells = []
        for p in paths:
            v = params[param].get(p)
            cells.append(f"{v[0]:.1f} ({v[1]:.3f})" if v else "")
        print(f"| {param} | " + " | ".join(cells) + " |")


def rate(group, path, param):
    return results.get(group, {}).get(param, {}).get(path, (None,))[0]


print("\nRatios")
k8, k1 = rate("kernel/covered", "simd8", "1-light"), rate("kernel/covered", "scalar", "1-light")
if k8 and k1:
    print(f"- kernel on covered packets, simd8 / scalar: {k8 / k1:.2f}x")
f8 = rate("frame/exponent-series/spans", "simd8", "1024x747")
f1 = rate("frame/exponent-series/naive", "scalar", "1024x747")
if f8 and f1:
    print(f"- exponent series 1024x747, simd8 + spans / scalar naive: {f8 / f1:.2f}x ({f8:.0f} Mpix/s)")
