#!/usr/bin/env python3
"""Is a map imprecise because the polish is stuck, or because isometry is not the ground truth?
(docs/accuracy.md, session 15.)

    python3 bench/precision_probe.py SHAPE.off MAP.json [INDEX]

SHAPE.off with its SHAPE.sym.txt (../shared/data), MAP.json from `intrinsym detect --json`
(symmetry INDEX, default 0). On 128 farthest-point samples a_i among the ground-truth
vertices, with Dijkstra geodesics on the edge graph over sqrt(area) (each edge once):
  * profile matching from the true images b_i = T(a_i): every third ground-truth vertex to the
    vertex whose distances to the images of its 16 nearest samples best match its own
    distances to them (brute force; the polish's step 2 without its descent);
  * the same from the map's images of the samples, and the map itself on those vertices;
  * the mean over sample pairs of |g(a_i, a_j) - g(b_i, b_j)| for the true and the map's b_i.
"""
import json
import os
import sys

import numpy as np
from scipy.sparse.csgraph import dijkstra

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hierarchy import edge_graph, read_off  # noqa: E402


def main():
    off, js = sys.argv[1], sys.argv[2]
    which = int(sys.argv[3]) if len(sys.argv) > 3 else 0
    v, t = read_off(off)
    n = len(v)
    gt = np.loadtxt(off[:-4] + ".sym.txt", int)
    truth = np.full(n, -1)
    truth[gt[:, 0]] = gt[:, 1]
    area = 0.5 * np.linalg.norm(np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]), axis=1).sum()
    v = v / np.sqrt(area)
    graph = edge_graph(v, t)
    geo = lambda idx: dijkstra(graph, directed=False, indices=idx)
    have = np.where(truth >= 0)[0]
    samples = [have[0]]
    d = geo(samples[0])
    for _ in range(127):
        d2 = np.where(truth >= 0, d, -1)
        s = int(np.argmax(d2))
        samples.append(s)
        d = np.minimum(d, geo(s))
    samples = np.array(samples)
    images = np.unique(truth[have])
    to_truth = geo(images)
    row = {x: i for i, x in enumerate(images)}
    ours = np.array(json.load(open(js))["symmetries"][which]["map"])
    ga = geo(samples)
    probe = have[::3]

    def matched(b):
        gb = geo(b)
        err = []
        for x in probe:
            g = ga[:, x].copy()
            g[samples == x] = np.inf
            near = np.argsort(g)[:16]
            w = int(np.argmin(np.abs(gb[near, :] - g[near, None]).mean(0)))
            err.append(to_truth[row[truth[x]], w])
        return np.array(err)

    def report(label, err):
        print(f"{label}: acc@0.05 {np.mean(err <= 0.05):.3f} acc@0.10 {np.mean(err <= 0.10):.3f}")

    report("profile matching from the true sample images", matched(truth[samples]))
    mapped = ours[samples]
    if (mapped < 0).any():
        print("the map leaves samples unmapped: a partial map, no comparison")
        return
    report("profile matching from the map's sample images", matched(mapped))
    report("the map", np.array([to_truth[row[truth[x]], ours[x]] if ours[x] >= 0 else np.inf for x in probe]))
    near = np.array([to_truth[row[truth[s]], b] for s, b in zip(samples, mapped)])
    print(f"the map's sample images within 0.05 of the truth: {np.mean(near <= 0.05):.3f}")
    gas = ga[:, samples]
    for label, b in (("truth", truth[samples]), ("map", mapped)):
        print(f"sample-pair distortion, {label}: {np.abs(gas - geo(b)[:, b]).mean():.4f}")


if __name__ == "__main__":
    main()
