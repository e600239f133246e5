#!/usr/bin/env python3
"""Is the ground truth the most isometric map? (issue 14: what an intrinsic detector can reach)

    python3 bench/isometry_ceiling.py BIN [--datasets tosca,faust] [--only NAME,...]
                                          [--sources 40] [--tsv OUT]

BIN is the `intrinsym` CLI of the build to measure. For every shape of ../shared/data's
datasets it runs `BIN detect --json` (default parameters, seed 0) and compares three maps on
the vertices the ground truth covers:

  * `first`: the first reported symmetry (what MeshLab colours by default);
  * `truth`: the ground truth `x -> sym_x` of shared/data;
  * `smoothed truth`: the ground truth made smooth (its functional map in the first 100
    Laplace-Beltrami eigenfunctions, then each vertex to the nearest row of `Phi C`), so that
    the annotation's vertex-level jitter does not count against it.

For each, the **distortion** `mean |d(s, x) - d(T s, T x)| / sqrt(area)` over `--sources`
random covered vertices `s` and every covered vertex `x`, with heat-method geodesic distances
(potpourri3d's `MeshHeatMethodDistanceSolver`, robust intrinsic Laplacian: not the edge graph
the pipeline and the scorer use, so no Dijkstra bias is shared with the pipeline). And the
first map's acc@0.05 against the truth (Dijkstra on the edge graph, each edge once, over every
third covered vertex: the protocol's scorer, subsampled).

An intrinsic detector looks for the map that preserves geodesic distances best. Where the
first map already preserves them better than the (smoothed) truth, a better isometry search
cannot move it towards the truth: what separates the two is what the annotation encodes
beyond isometry (the null pose's extrinsic mirror carried through a pose that stretched the
body). Needs numpy, scipy and potpourri3d (`pip install potpourri3d`); test tooling only.
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import dijkstra
from scipy.sparse.linalg import eigsh

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hierarchy import edge_graph  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "shared", "data")


def load_off(path):
    with open(path) as f:
        assert f.readline().strip() == "OFF"
        head = f.readline().split()
        while not head:
            head = f.readline().split()
        nv, nf = int(head[0]), int(head[1])
        data = np.array(f.read().split(), dtype=float)
    return data[: 3 * nv].reshape(nv, 3), data[3 * nv : 3 * nv + 4 * nf].reshape(nf, 4)[:, 1:].astype(int)


def surface_area(v, f):
    return 0.5 * np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1).sum()


def smoothed(v, f, xs, gx, pp3d, k=100):
    """The truth's functional map in k eigenfunctions, turned back into a point map."""
    lap = pp3d.cotan_laplacian(v, f).tocsc()
    mass = pp3d.vertex_areas(v, f)
    _, phi = eigsh(lap, k=k, M=sp.diags(mass).tocsc(), sigma=-1e-8)
    mx = mass[xs] * mass.sum() / mass[xs].sum()
    c = (phi[xs] * mx[:, None]).T @ phi[gx]
    target = phi @ c
    sq = (phi**2).sum(1)
    out = np.empty(len(v), dtype=int)
    for a in range(0, len(v), 1000):
        out[a : a + 1000] = (sq[None, :] - 2 * target[a : a + 1000] @ phi.T).argmin(1)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("bin")
    ap.add_argument("--datasets", default="tosca,faust")
    ap.add_argument("--only", default="")
    ap.add_argument("--sources", type=int, default=40)
    ap.add_argument("--tsv")
    a = ap.parse_args()
    try:
        import potpourri3d as pp3d
    except ImportError:
        sys.exit("needs potpourri3d: pip install potpourri3d")
    only = set(filter(None, a.only.split(",")))
    rows = []
    out = open(a.tsv, "w") if a.tsv else None
    header = "dataset\tshape\tacc05_first\tdistortion_first\tdistortion_truth\tdistortion_smoothed_truth\tacc05_smoothed_truth"
    print(header)
    if out:
        print(header, file=out)
    with tempfile.TemporaryDirectory() as tmp:
        for ds in a.datasets.split(","):
            for path in sorted(glob.glob(os.path.join(DATA, ds, "*.off"))):
                name = os.path.basename(path)[:-4]
                truth = path[:-4] + ".sym.txt"
                if not os.path.exists(truth) or (only and name not in only):
                    continue
                js = os.path.join(tmp, name + ".json")
                subprocess.run([a.bin, "detect", path, "--json", js], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                syms = json.load(open(js))["symmetries"]
                if not syms:
                    continue
                first = np.array(syms[0]["map"])
                v, f = load_off(path)
                s = np.loadtxt(truth, dtype=int)
                xs, gx = s[:, 0], s[:, 1]
                root = np.sqrt(surface_area(v, f))
                # Unmapped vertices (-1) are sent to themselves: the identity's distortion.
                img = np.where(first[xs] >= 0, first[xs], xs)
                smooth = smoothed(v, f, xs, gx, pp3d)
                solver = pp3d.MeshHeatMethodDistanceSolver(v, f, use_robust=True)
                src = np.random.default_rng(0).choice(len(xs), min(a.sources, len(xs)), replace=False)
                heat = lambda sources: np.array([solver.compute_distance(int(q)) for q in sources]) / root
                d0 = heat(xs[src])

                def distortion(image):
                    return np.abs(d0[:, xs] - heat(image[src])[:, image]).mean()

                sub = np.arange(0, len(xs), 3)
                dg = dijkstra(edge_graph(v, f), directed=False, indices=gx[sub]) / root
                acc = lambda image: float((dg[np.arange(len(sub)), image[sub]] <= 0.05).mean())
                row = (ds, name, acc(img), distortion(img), distortion(gx), distortion(smooth[xs]), acc(smooth[xs]))
                rows.append(row)
                line = "%s\t%s\t%.4f\t%.5f\t%.5f\t%.5f\t%.4f" % row
                print(line, flush=True)
                if out:
                    print(line, file=out, flush=True)
    print()
    print("| dataset | shapes | first map more isometric than the truth | ... than the smoothed truth | of the shapes with first acc@0.05 < 0.9: more isometric than the smoothed truth | mean distortion: first / truth / smoothed truth | smoothed truth's acc@0.05 |")
    print("|---|---|---|---|---|---|---|")
    for ds in a.datasets.split(","):
        r = [x for x in rows if x[0] == ds]
        if not r:
            continue
        low = [x for x in r if x[2] < 0.9]
        print(
            "| %s | %d | %d | %d | %d of %d | %.4f / %.4f / %.4f | %.1f%% |"
            % (
                ds,
                len(r),
                sum(x[3] < x[4] for x in r),
                sum(x[3] < x[5] for x in r),
                sum(x[3] < x[5] for x in low),
                len(low),
                np.mean([x[3] for x in r]),
                np.mean([x[4] for x in r]),
                np.mean([x[5] for x in r]),
                100 * np.mean([x[6] for x in r]),
            )
        )


if __name__ == "__main__":
    main()
