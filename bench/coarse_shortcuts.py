#!/usr/bin/env python3
"""How far the hierarchy's coarse mesh cuts across the fine surface (issue 17; session 49).

    cargo build --release --example coarse_mesh
    ./target/release/examples/coarse_mesh FINE.off OUT          # writes OUT.off, OUT.kept.txt
    python3 bench/coarse_shortcuts.py FINE.off OUT [--center X,Y,Z --radius R]

For every coarse edge, the ratio of its chord to the fine mesh's geodesic between its two
ends (Dijkstra on the fine mesh's edge graph, each edge counted once). On a smooth surface the
ratio is near 1 (the edge graph's zigzag makes the fine distance a few percent long: the
median is about 0.94 on the KIDS poses); an edge that joins two sheets of a fold, or two
parts that nearly touch, has a far smaller one. Prints the ratio's percentiles over all
edges and, with --center and --radius (file coordinates), over the edges whose midpoint lies
in that ball, and the worst edges with their midpoints. Evaluation tooling only.
"""
import argparse
import os
import sys

import numpy as np
from scipy.sparse.csgraph import dijkstra

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hierarchy import edge_graph, edges, read_off  # noqa: E402


def describe(name, r):
    if len(r) == 0:
        print(f"{name}: no edges")
        return
    q = np.percentile(r, [0.1, 1, 5, 50])
    print(f"{name}: {len(r)} edges, ratio p0.1 {q[0]:.3f} p1 {q[1]:.3f} p5 {q[2]:.3f} median {q[3]:.3f}; "
          f"below 0.6: {100 * np.mean(r < 0.6):.2f}%, below 0.7: {100 * np.mean(r < 0.7):.2f}%")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("fine")
    ap.add_argument("coarse", help="OUT of examples/coarse_mesh (reads OUT.off and OUT.kept.txt)")
    ap.add_argument("--center", help="X,Y,Z in the file's coordinates")
    ap.add_argument("--radius", type=float)
    ap.add_argument("--worst", type=int, default=10)
    a = ap.parse_args()
    v, f = read_off(a.fine)
    _, fc = read_off(a.coarse + ".off")
    kept = np.loadtxt(a.coarse + ".kept.txt", dtype=int)
    ec = edges(fc)
    ends = kept[ec]
    chord = np.linalg.norm(v[ends[:, 0]] - v[ends[:, 1]], axis=1)
    # Geodesics from each coarse vertex, far enough for its longest edge (the zigzag and
    # folds make them longer than the chord; beyond the limit the ratio counts as 0).
    limit = 6.0 * chord.max()
    d = dijkstra(edge_graph(v, f), directed=False, indices=kept, limit=limit)
    geo = d[ec[:, 0], ends[:, 1]]
    r = np.where(np.isfinite(geo), chord / np.maximum(geo, 1e-300), 0.0)
    describe("all", r)
    mid = 0.5 * (v[ends[:, 0]] + v[ends[:, 1]])
    if a.center is not None:
        if a.radius is None:
            ap.error("--center needs --radius")
        c = np.array([float(x) for x in a.center.split(",")])
        describe(f"within {a.radius} of {a.center}", r[np.linalg.norm(mid - c, axis=1) < a.radius])
    for i in np.argsort(r)[:a.worst]:
        print(f"  ratio {r[i]:.3f}  chord {chord[i]:.3g}  geodesic {geo[i]:.3g}  midpoint {np.round(mid[i], 2).tolist()}")


if __name__ == "__main__":
    main()
