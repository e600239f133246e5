/* Minimal use of intrinsym from C: detect the symmetries of an OFF mesh and print them.
 * Build against the installed package: see examples/c/CMakeLists.txt or
 *   cc detect.c $(pkg-config --cflags --libs intrinsym) -o detect */
#include <stdio.h>
#include <stdlib.h>
#include <intrinsym.h>

int main(int argc, char **argv) {
    FILE *f;
    char magic[8];
    size_t nv, nt, ne, i;
    double *v;
    uint32_t *t;
    sym_result *result = NULL;
    sym_status status;
    if (argc != 2 || !(f = fopen(argv[1], "r")) || fscanf(f, "%7s %zu %zu %zu", magic, &nv, &nt, &ne) != 4) {
        fprintf(stderr, "usage: detect MESH.off\n");
        return 2;
    }
    v = malloc(3 * nv * sizeof *v);
    t = malloc(3 * nt * sizeof *t);
    for (i = 0; i < 3 * nv; i++) if (fscanf(f, "%lf", &v[i]) != 1) return 2;
    for (i = 0; i < nt; i++) if (fscanf(f, "%*u %u %u %u", &t[3 * i], &t[3 * i + 1], &t[3 * i + 2]) != 3) return 2;
    fclose(f);

    status = sym_detect(v, nv, t, nt, NULL /* default parameters */, NULL, NULL, &result);
    if (status != SYM_STATUS_OK) {
        char message[256];
        sym_last_error(message, sizeof message, NULL);
        fprintf(stderr, "sym_detect: %s: %s\n", sym_status_str(status), message);
        return 1;
    }
    printf("intrinsym %s: %zu symmetries\n", sym_version(), sym_count(result));
    for (i = 0; i < sym_count(result); i++) {
        sym_symmetry s = { sizeof(sym_symmetry) };
        sym_get_map(result, i, &s);
        printf("#%zu %s order %u region %zu complexity %.3f; vertex 0 -> %lld\n", i,
               s.kind == SYM_KIND_GLOBAL ? "global" : "partial", s.order, s.region_size, s.complexity,
               (long long)s.map[0]);
    }
    sym_free(result);
    free(v);
    free(t);
    return 0;
}
