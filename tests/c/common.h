/* Helpers shared by the C tests: a small OFF reader and mirror ground truth. */
#ifndef INTRINSYM_TEST_COMMON_H
#define INTRINSYM_TEST_COMMON_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>

typedef struct {
    double *v;
    uint32_t *t;
    size_t nv, nt;
} test_mesh;

static inline int read_off(const char *path, test_mesh *m) {
    FILE *f = fopen(path, "r");
    char header[16];
    size_t i, ne;
    if (!f) return 0;
    if (fscanf(f, "%15s %zu %zu %zu", header, &m->nv, &m->nt, &ne) != 4) { fclose(f); return 0; }
    m->v = (double *)malloc(3 * m->nv * sizeof(double));
    m->t = (uint32_t *)malloc(3 * m->nt * sizeof(uint32_t));
    for (i = 0; i < m->nv; i++)
        if (fscanf(f, "%lf %lf %lf", &m->v[3 * i], &m->v[3 * i + 1], &m->v[3 * i + 2]) != 3) { fclose(f); return 0; }
    for (i = 0; i < m->nt; i++) {
        unsigned k, a, b, c;
        if (fscanf(f, "%u %u %u %u", &k, &a, &b, &c) != 4 || k != 3) { fclose(f); return 0; }
        m->t[3 * i] = a; m->t[3 * i + 1] = b; m->t[3 * i + 2] = c;
    }
    fclose(f);
    return 1;
}

static inline void free_mesh(test_mesh *m) { free(m->v); free(m->t); }

/* Index of the vertex nearest to the mirror image (x -> -x) of vertex i. */
static inline size_t mirror_of(const test_mesh *m, size_t i) {
    size_t j, best = 0;
    double bd = INFINITY;
    for (j = 0; j < m->nv; j++) {
        double dx = m->v[3 * j] + m->v[3 * i], dy = m->v[3 * j + 1] - m->v[3 * i + 1], dz = m->v[3 * j + 2] - m->v[3 * i + 2];
        double d = dx * dx + dy * dy + dz * dz;
        if (d < bd) { bd = d; best = j; }
    }
    return best;
}

#define CHECK(cond, ...) do { if (!(cond)) { fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__); fprintf(stderr, __VA_ARGS__); fprintf(stderr, "\n"); exit(1); } } while (0)

#endif
