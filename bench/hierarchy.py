#!/usr/bin/env python3
"""Large meshes on the hierarchy (issue 17): time per stage, peak memory and accuracy, with
scipy's eigsh on the full mesh as the peer, all in one run.

    python3 bench/hierarchy.py BIN EVAL_BIN [--big] [--against OLD_BIN]

BIN is `intrinsym`, EVAL_BIN `intrinsym-eval` of the build to measure. Cases:
  * 5k: TOSCA's cat0 (under the hierarchy's threshold: the full pipeline);
  * 60k: the 5 KIDS poses of ../shared/data;
  * with --big, scan-like meshes made from KIDS pose 1 by midpoint subdivision (x4: 239k,
    x16: 955k vertices) plus Gaussian noise of 0.05% of the bounding-box diagonal (the
    original vertices keep their indices, so pose 1's ground truth still holds), and the
    generated posed quadruped at icosphere levels 7 and 8 (164k, 655k).
Each mesh: `BIN detect --json` under /usr/bin/time (wall time, peak memory) with the JSON's
stage timings; accuracy (best acc@0.05 of the reported symmetries) by EVAL_BIN, on the KIDS
poses also with `--set hierarchy_vertices=0` (the full-resolution pipeline, same run); and
scipy's `eigsh` (k = 100, shift-invert, cotangent Laplacian and lumped mass built here) on
the 60k and 239k meshes. Prints Markdown tables.

With --against OLD_BIN, each mesh is also detected by an older build, interleaved with BIN
(old, new, old, new: this machine's speed drifts by tens of percent), and the table gets the
ratio new / old of the faster of the two runs of each (detection time), and the ratio of
BIN's detection to eigsh.
"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import eigsh

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "shared", "data")


def read_off(path):
    with open(path) as f:
        toks = f.read().split()
    nv, nf = int(toks[1]), int(toks[2])
    v = np.array(toks[4:4 + 3 * nv], float).reshape(nv, 3)
    f = np.array(toks[4 + 3 * nv:4 + 3 * nv + 4 * nf], int).reshape(nf, 4)[:, 1:]
    return v, f


def area(v, f):
    """Surface area of the triangles `f` of positions `v`."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()


def edges(f):
    """Each undirected edge of the triangles `f` once, as sorted pairs."""
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    return np.unique(np.sort(e, axis=1), axis=0)


def edge_graph(v, f):
    """The edge graph, each edge once (a constructor that sums duplicates would double
    interior edges); one direction only, for `dijkstra(..., directed=False)`."""
    e = edges(f)
    w = np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1)
    return sp.coo_matrix((w, (e[:, 0], e[:, 1])), shape=(len(v), len(v))).tocsr()


def shapes_with_truth(data, datasets, out):
    """(dataset, NAME.off path, NAME.sym.txt path) of every shape with ground truth under
    DATA/DATASET, sorted, each dataset's folder made under OUT first (for the copy scripts)."""
    for ds in datasets:
        os.makedirs(os.path.join(out, ds), exist_ok=True)
        for path in sorted(glob.glob(os.path.join(data, ds, "*.off"))):
            truth = path[:-4] + ".sym.txt"
            if os.path.exists(truth):
                yield ds, path, truth


def write_off(path, v, f):
    with open(path, "w") as out:
        out.write(f"OFF\n{len(v)} {len(f)} 0\n")
        np.savetxt(out, v, fmt="%.7f")
        np.savetxt(out, np.hstack([np.full((len(f), 1), 3), f]), fmt="%d")


def subdivide(v, f):
    """Midpoint subdivision; vertex i < n stays vertex i."""
    e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    ue, inv = np.unique(e, axis=0, return_inverse=True)
    mid = len(v) + inv.reshape(-1)
    m = len(f)
    ab, bc, ca = mid[:m], mid[m:2 * m], mid[2 * m:]
    a, b, c = f[:, 0], f[:, 1], f[:, 2]
    nv = np.concatenate([v, 0.5 * (v[ue[:, 0]] + v[ue[:, 1]])])
    nf = np.concatenate([np.stack(t, 1) for t in ([a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca])])
    return nv, nf


def scipy_eigsh(path, k=100):
    """Seconds of eigsh for the k smallest pairs of the cotangent Laplacian (lumped mass)."""
    v, f = read_off(path)
    n = len(v)
    rows, cols, vals = [], [], []
    mass = np.zeros(n)
    for i in range(3):
        a, b, c = f[:, i], f[:, (i + 1) % 3], f[:, (i + 2) % 3]
        e1, e2 = v[b] - v[a], v[c] - v[a]
        cr = np.linalg.norm(np.cross(e1, e2), axis=1)
        cot = np.einsum("ij,ij->i", e1, e2) / np.maximum(cr, 1e-300)
        rows += [b, c]
        cols += [c, b]
        vals += [-0.5 * cot, -0.5 * cot]
        np.add.at(mass, a, cr / 6.0)
    W = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
    L = (sp.diags(-np.asarray(W.sum(axis=1)).ravel()) + W).tocsc()
    M = sp.diags(mass).tocsc()
    sigma = 1e-8 * mass.sum() ** -1
    t = time.perf_counter()
    eigsh(L, k=k, M=M, sigma=-sigma, which="LM", return_eigenvectors=True)
    return time.perf_counter() - t


def detect(binary, path):
    with tempfile.NamedTemporaryFile(suffix=".json") as j:
        t = subprocess.run(["/usr/bin/time", "-v", binary, "detect", path, "--json", j.name], capture_output=True, text=True, check=True)
        peak = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", t.stderr).group(1)) / 1024.0
        wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)", t.stderr).group(1)
        parts = [float(x) for x in wall.split(":")]
        seconds = sum(p * 60 ** i for i, p in enumerate(reversed(parts)))
        with open(j.name) as f:
            report = json.load(f)
    return report, seconds, peak


def accuracy(eval_bin, folder, extra=()):
    """{shape: best acc@0.05} from EVAL_BIN on every shape of `folder`."""
    with tempfile.NamedTemporaryFile(suffix=".tsv") as tsv:
        subprocess.run([eval_bin, "--data", folder, "--tsv", tsv.name, *extra], capture_output=True, check=True)
        with open(tsv.name) as f:
            lines = [l.rstrip("\n").split("\t") for l in f]
    head = lines[0]
    return {r[head.index("shape")]: float(r[head.index("best05")]) for r in lines[1:]}


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    binary, eval_bin, big = sys.argv[1], sys.argv[2], "--big" in sys.argv[3:]
    old = sys.argv[sys.argv.index("--against") + 1] if "--against" in sys.argv else None
    tmp = tempfile.mkdtemp(prefix="intrinsym-hierarchy-")
    try:
        kids = sorted(glob.glob(os.path.join(DATA, "kids_hires", "*.off")))
        cases = [("TOSCA cat0", os.path.join(DATA, "tosca", "cat0.off"), None)]
        cases += [(f"KIDS {os.path.basename(k)[:-4]}", k, "kids") for k in kids]
        scan = os.path.join(tmp, "scan")
        if big:
            os.makedirs(scan)
            v, f = read_off(kids[0])
            rng = np.random.default_rng(0)
            for times in (1, 2):
                v, f = subdivide(v, f)
                diag = np.linalg.norm(v.max(0) - v.min(0))
                name = os.path.join(scan, f"kids1_x{4 ** times}.off")
                write_off(name, v + rng.normal(0.0, 5e-4 * diag, v.shape), f)
                shutil.copy(kids[0][:-4] + ".sym.txt", name[:-4] + ".sym.txt")
                cases.append((f"scan-like KIDS 1 x{4 ** times}", name, "scan"))
            for level in (7, 8):
                name = os.path.join(tmp, f"quadruped{level}.off")
                subprocess.run([binary, "generate", "quadruped", name, "--size", str(level)], capture_output=True, check=True)
                cases.append((f"generated quadruped level {level}", name, None))
        acc = accuracy(eval_bin, os.path.join(DATA, "kids_hires"))
        acc_full = accuracy(eval_bin, os.path.join(DATA, "kids_hires"), ("--set", "hierarchy_vertices=0"))
        if big:
            acc.update(accuracy(eval_bin, scan))
        extra = " new/old detection | detection/eigsh |" if old else ""
        print("| mesh | vertices | wall s | detection s | coarse mesh s | lift s | spectral s | maps s | peak MiB | acc@0.05 | full resolution acc@0.05 | scipy eigsh s (k=100) |" + extra)
        print("|---|---|---|---|---|---|---|---|---|---|---|---|" + ("---|---|" if old else ""))
        for label, path, kind in cases:
            if old:
                runs = [(detect(b, path), b) for _ in range(2) for b in (old, binary)]
                fastest = lambda b: min((r for r, bb in runs if bb == b), key=lambda r: r[0]["timings"]["total"])
                (report, wall, peak), previous = fastest(binary), fastest(old)[0]
            else:
                report, wall, peak = detect(binary, path)
            t = report["timings"]
            shape = os.path.basename(path)[:-4]
            a = f"{100 * acc[shape]:.1f}%" if shape in acc else "–"
            full = f"{100 * acc_full[shape]:.1f}%" if shape in acc_full else "–"
            eig_s = scipy_eigsh(path) if report["vertices"] <= 250000 and kind is not None else None
            eig = f"{eig_s:.2f}" if eig_s else "–"
            row = f"| {label} | {report['vertices']} | {wall:.2f} | {t['total']:.2f} | {t.get('hierarchy', 0):.2f} | {t.get('lift', 0):.2f} | {t['spectral']:.2f} | {t['maps']:.2f} | {peak:.0f} | {a} | {full} | {eig} |"
            if old:
                ratio = f"{t['total'] / eig_s:.2f}" if eig_s else "–"
                row += f" {t['total'] / previous['timings']['total']:.2f} | {ratio} |"
            print(row, flush=True)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
