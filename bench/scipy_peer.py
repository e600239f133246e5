"""The scipy peer of one spectral benchmark case (run by bench/spectral.py).

Reads the CSC arrays of L and the lumped mass written by `bench_spectral S K DIR`, solves
L x = lambda M x for the k smallest pairs with eigsh in shift-invert mode at the same shift
(L + sigma M, i.e. eigsh's sigma = -sigma), and prints one JSON line.
"""
import json
import resource
import sys
import time

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import eigsh

d, k, sigma = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
indptr = np.fromfile(f"{d}/indptr.bin", dtype="<u8").astype(np.int64)
indices = np.fromfile(f"{d}/indices.bin", dtype="<u8").astype(np.int64)
data = np.fromfile(f"{d}/data.bin", dtype="<f8")
mass = np.fromfile(f"{d}/mass.bin", dtype="<f8")
n = mass.size
L = sp.csc_matrix((data, indices, indptr), shape=(n, n))
M = sp.diags(mass).tocsc()
t = time.perf_counter()
evals = eigsh(L, k=k, M=M, sigma=-sigma, which="LM", return_eigenvectors=False)
seconds = time.perf_counter() - t
evals = np.sort(evals)
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
print(json.dumps({"seconds": seconds, "peak_mib": peak, "evals": evals.tolist()}))
