#!/usr/bin/env python3
"""Accuracy over several seeds: the evaluation of `intrinsym-eval` repeated with
`--set seed=S` (the seed picks the first farthest-point sample; the rest of the pipeline is
deterministic), per dataset, with the mean and the spread over the seeds.

Why: one seed is one draw of the sample set, and the result of a shape can flip with it
(TOSCA horse7's first symmetry 0.72 at seed 0, 0.003 at seed 1). Session 20 measured the
release at seeds 0, 1 and 2: first acc@0.05 over all 85.2, 83.1 and 83.2%. The pipeline's
constants were chosen on seed 0 only, so its figure is the luckiest of the three: a change
measured at one seed moves within that noise. Compare changes on the mean over seeds.

    python3 bench/seeds.py run EVAL_BIN OUTDIR [--seeds 0,1,2] [--set KEY=VALUE]... [--data DIR]
    python3 bench/seeds.py summary OUTDIR
    python3 bench/seeds.py compare BEFORE_DIR AFTER_DIR [--min 0.2]

With restarts (two by default) the detection from seed S may also search from seeds S+1 and
S+2, so neighbouring seeds share draws: check a change on seeds that are apart too
(`--seeds 10,20`; session 23's four restarts gained at seeds 0–3 and lost at 10 and 20), or
on one search each (`--set restarts=0`).

`run` writes OUTDIR/seedS.tsv and OUTDIR/seedS.sym.tsv (the eval's tables) and prints the
summary; `compare` applies the keep rule (overall mean up, no dataset's mean down by more than
half a point) to the means over the seeds both runs have, for best and for first.
"""
import argparse
import csv
import glob
import os
import re
import statistics
import subprocess
import sys
from collections import defaultdict


def load(path):
    with open(path) as f:
        return {r["shape"]: r for r in csv.DictReader(f, delimiter="\t")}


def runs(outdir):
    """{seed: table} of the seeds evaluated in `outdir`."""
    found = {}
    for p in glob.glob(os.path.join(outdir, "seed*.tsv")):
        m = re.fullmatch(r"seed(\d+)\.tsv", os.path.basename(p))
        if m:
            found[int(m.group(1))] = load(p)
    return dict(sorted(found.items()))


def means(table):
    """{dataset or 'all': (best, first)} in percent."""
    sets = defaultdict(list)
    for r in table.values():
        sets[r["dataset"]].append(r)
        sets["all"].append(r)
    return {d: (100 * statistics.mean(float(r["best05"]) for r in rs), 100 * statistics.mean(float(r["first05"]) for r in rs)) for d, rs in sets.items()}


def datasets(tables):
    names = sorted({d for t in tables for d in means(t) if d != "all"})
    return names + ["all"]


def summary(outdir):
    tables = runs(outdir)
    if not tables:
        sys.exit(f"no seed*.tsv in {outdir}")
    per = {s: means(t) for s, t in tables.items()}
    seeds = list(per)
    print(f"seeds {', '.join(map(str, seeds))}: best / first acc@0.05 (%)")
    print("| dataset | " + " | ".join(f"seed {s}" for s in seeds) + " | mean | min–max |")
    print("|---|" + "---|" * (len(seeds) + 2))
    for d in datasets(tables.values()):
        cells = [per[s][d] for s in seeds if d in per[s]]
        b = [c[0] for c in cells]
        f = [c[1] for c in cells]
        row = " | ".join(f"{c[0]:.1f} / {c[1]:.1f}" for c in cells)
        print(f"| {d} | {row} | **{statistics.mean(b):.1f} / {statistics.mean(f):.1f}** | {min(b):.1f}–{max(b):.1f} / {min(f):.1f}–{max(f):.1f} |")


def compare(before, after, min_move):
    a, b = runs(before), runs(after)
    seeds = [s for s in a if s in b]
    if not seeds:
        sys.exit("no seed in common")
    names = datasets([a[s] for s in seeds] + [b[s] for s in seeds])
    print(f"mean over seeds {', '.join(map(str, seeds))}, acc@0.05 (%)")
    print("| dataset | best before | best after | change | seeds up | first before | first after | change | seeds up |")
    print("|---|---|---|---|---|---|---|---|---|")
    keep = {0: True, 1: True}
    for d in names:
        ma = [means(a[s])[d] for s in seeds]
        mb = [means(b[s])[d] for s in seeds]
        cells = []
        for k in (0, 1):
            x, y = statistics.mean(m[k] for m in ma), statistics.mean(m[k] for m in mb)
            up = sum(mb[i][k] > ma[i][k] + 1e-9 for i in range(len(seeds)))
            cells.append(f"{x:.1f} | {y:.1f} | {y - x:+.1f} | {up} of {len(seeds)}")
            if (d == "all" and y - x <= 0) or (d != "all" and y - x < -0.5):
                keep[k] = False
        print(f"| {d} | {cells[0]} | {cells[1]} |")
    print()
    # Shapes whose mean over the seeds moved.
    for shape in sorted(a[seeds[0]]):
        for key in ("best05", "first05"):
            try:
                x = statistics.mean(float(a[s][shape][key]) for s in seeds)
                y = statistics.mean(float(b[s][shape][key]) for s in seeds)
            except KeyError:
                continue
            if abs(y - x) >= min_move:
                print(f"{a[seeds[0]][shape]['dataset']:14s} {shape:20s} {key:8s} {x:.3f} -> {y:.3f} (mean over seeds)")
    print()
    print("keep by best (overall mean up, no dataset down by more than 0.5 point):", "yes" if keep[0] else "no")
    print("keep by first:", "yes" if keep[1] else "no")


def run(args):
    os.makedirs(args.outdir, exist_ok=True)
    for s in [int(x) for x in args.seeds.split(",")]:
        cmd = [args.eval_bin, "--data", args.data, "--tsv", os.path.join(args.outdir, f"seed{s}.tsv"), "--symmetries", os.path.join(args.outdir, f"seed{s}.sym.tsv"), "--set", f"seed={s}"]
        for kv in args.set:
            cmd += ["--set", kv]
        print("+", " ".join(cmd), file=sys.stderr, flush=True)
        with open(os.path.join(args.outdir, f"seed{s}.log"), "w") as log:
            subprocess.run(cmd, check=True, stdout=log, stderr=subprocess.STDOUT)
    summary(args.outdir)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("eval_bin")
    r.add_argument("outdir")
    r.add_argument("--seeds", default="0,1,2")
    r.add_argument("--set", action="append", default=[], help="KEY=VALUE passed to intrinsym-eval")
    r.add_argument("--data", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "data"))
    s = sub.add_parser("summary")
    s.add_argument("outdir")
    c = sub.add_parser("compare")
    c.add_argument("before")
    c.add_argument("after")
    c.add_argument("--min", type=float, default=0.2, help="list shapes whose mean moved by at least this")
    args = ap.parse_args()
    if args.cmd == "run":
        run(args)
    elif args.cmd == "summary":
        summary(args.outdir)
    else:
        compare(args.before, args.after, args.min)


if __name__ == "__main__":
    main()
