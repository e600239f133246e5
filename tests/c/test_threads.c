/* Four threads call sym_detect at once on different meshes (the quadruped and a scaled copy,
 * two seeds) and must get exactly what sequential calls get. Usage: test_threads MESH.off */
#include <pthread.h>
#include "intrinsym.h"
#include "common.h"

typedef struct {
    const test_mesh *mesh;
    uint64_t seed;
    int64_t *map; /* strongest map, copied out */
    size_t count;
    sym_status status;
} job;

static void *run(void *arg) {
    job *j = (job *)arg;
    sym_params *p = sym_params_new();
    sym_result *r = NULL;
    sym_symmetry s;
    sym_params_set_seed(p, j->seed);
    j->status = sym_detect(j->mesh->v, j->mesh->nv, j->mesh->t, j->mesh->nt, p, NULL, NULL, &r);
    if (j->status == SYM_STATUS_OK) {
        j->count = sym_count(r);
        memset(&s, 0, sizeof s);
        s.struct_size = sizeof s;
        if (j->count > 0 && sym_get_map(r, 0, &s) == SYM_STATUS_OK) {
            j->map = (int64_t *)malloc(s.num_vertices * sizeof(int64_t));
            memcpy(j->map, s.map, s.num_vertices * sizeof(int64_t));
        }
    }
    sym_free(r);
    sym_params_free(p);
    return NULL;
}

int main(int argc, char **argv) {
    test_mesh m, big;
    job par[4], seq[4];
    pthread_t th[4];
    size_t i;
    int k;
    CHECK(argc == 2 && read_off(argv[1], &m) && read_off(argv[1], &big), "cannot read mesh");
    for (i = 0; i < 3 * big.nv; i++) big.v[i] *= 3.0;
    for (k = 0; k < 4; k++) {
        job j = { k % 2 ? &big : &m, (uint64_t)(k / 2), NULL, 0, SYM_STATUS_PANIC };
        par[k] = j;
        seq[k] = j;
    }
    for (k = 0; k < 4; k++) CHECK(pthread_create(&th[k], NULL, run, &par[k]) == 0, "thread");
    for (k = 0; k < 4; k++) pthread_join(th[k], NULL);
    for (k = 0; k < 4; k++) run(&seq[k]);
    for (k = 0; k < 4; k++) {
        CHECK(par[k].status == SYM_STATUS_OK && seq[k].status == SYM_STATUS_OK, "job %d status", k);
        CHECK(par[k].count == seq[k].count, "job %d: %zu vs %zu symmetries", k, par[k].count, seq[k].count);
        CHECK(par[k].map && seq[k].map && memcmp(par[k].map, seq[k].map, m.nv * sizeof(int64_t)) == 0, "job %d: maps differ", k);
        free(par[k].map);
        free(seq[k].map);
    }
    free_mesh(&m);
    free_mesh(&big);
    printf("test_threads: 4 concurrent calls equal to sequential ones\n");
    return 0;
}
