#!/usr/bin/env python3
"""Compare two evaluation runs (`intrinsym-eval --tsv FILE`) per dataset, and list the shapes
that moved: the check behind "keep a change only if it raises the overall mean and lowers no
dataset's mean by more than half a point".

    python3 bench/compare_eval.py BEFORE.tsv AFTER.tsv [--min 0.02]
"""
import argparse
import csv
from collections import defaultdict


def load(path):
    with open(path) as f:
        return {r["shape"]: r for r in csv.DictReader(f, delimiter="\t")}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--min", type=float, default=0.02, help="list shapes that moved by at least this")
    args = ap.parse_args()
    a, b = load(args.before), load(args.after)
    shared = [s for s in a if s in b]
    sets = defaultdict(list)
    for s in shared:
        sets[a[s]["dataset"]].append(s)
    sets["all"] = shared
    print("| dataset | shapes | best before | best after | change | first before | first after | change |")
    print("|---|---|---|---|---|---|---|---|")
    verdict = True
    for name, shapes in sets.items():
        m = lambda d, k: 100 * sum(float(d[s][k]) for s in shapes) / len(shapes)
        db, df = m(b, "best05") - m(a, "best05"), m(b, "first05") - m(a, "first05")
        if name != "all" and db < -0.5:
            verdict = False
        if name == "all" and db <= 0:
            verdict = False
        print(f"| {name} | {len(shapes)} | {m(a, 'best05'):.1f}% | {m(b, 'best05'):.1f}% | {db:+.1f} | {m(a, 'first05'):.1f}% | {m(b, 'first05'):.1f}% | {df:+.1f} |")
    print()
    for s in shared:
        for k in ("best05", "first05"):
            d = float(b[s][k]) - float(a[s][k])
            if abs(d) >= args.min:
                print(f"{a[s]['dataset']:14s} {s:20s} {k:8s} {float(a[s][k]):.3f} -> {float(b[s][k]):.3f}")
    print()
    print("keep (best@0.05: overall up, no dataset down by more than 0.5 point):", "yes" if verdict else "no")


if __name__ == "__main__":
    main()
