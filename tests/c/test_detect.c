/* Real results through the C ABI: on a mirror-symmetric quadruped the strongest symmetry sends
 * vertices to their mirror images; maps are in range; confidences in [0, 1]; the progress
 * callback is called with increasing fractions. Then two copies of the mesh side by side (two
 * components): the strongest symmetry swaps them (component 0 <-> 1), each vertex going to
 * its copy or to its copy's mirror image. Usage: test_detect MESH.off */
#include "intrinsym.h"
#include "common.h"

static int calls = 0;
static float last = -1.0f;
static int on_progress(float fraction, void *user_data) {
    (void)user_data;
    CHECK(fraction >= 0.0f && fraction <= 1.0f, "fraction %f", (double)fraction);
    CHECK(fraction + 1e-6f >= last, "progress went back: %f after %f", (double)fraction, (double)last);
    last = fraction;
    calls++;
    return 1;
}

int main(int argc, char **argv) {
    test_mesh m;
    sym_params *p;
    sym_result *r = NULL;
    sym_symmetry s;
    size_t i, exact = 0, count;
    const double *q;
    CHECK(argc == 2 && read_off(argv[1], &m), "cannot read mesh");
    CHECK(sym_abi_version() == SYM_ABI_VERSION, "ABI mismatch");
    CHECK(strlen(sym_version()) >= 5, "version string");
    p = sym_params_new();
    CHECK(p != NULL, "params");
    CHECK(sym_params_set_seed(p, 0) == SYM_STATUS_OK, "seed");
    CHECK(sym_detect(m.v, m.nv, m.t, m.nt, p, on_progress, NULL, &r) == SYM_STATUS_OK, "detect");
    CHECK(r != NULL && calls > 3, "result and progress (%d calls)", calls);
    count = sym_count(r);
    CHECK(count >= 1, "no symmetry");
    CHECK(sym_vertex_count(r) == m.nv, "vertex count");
    memset(&s, 0, sizeof s);
    s.struct_size = sizeof s;
    CHECK(sym_get_map(r, 0, &s) == SYM_STATUS_OK, "get_map");
    CHECK(s.num_vertices == m.nv && s.kind == SYM_KIND_GLOBAL && s.order == 2, "kind %d order %u", (int)s.kind, s.order);
    CHECK(s.fmap_size > 0 && s.fmap != NULL && s.support_pairs != NULL && s.num_support_pairs > 0, "fmap / pairs");
    for (i = 0; i < m.nv; i++) {
        CHECK(s.map[i] >= -1 && s.map[i] < (int64_t)m.nv, "map[%zu] = %lld", i, (long long)s.map[i]);
        CHECK(s.confidence[i] >= 0.0 && s.confidence[i] <= 1.0, "confidence[%zu]", i);
        if (s.map[i] >= 0 && (size_t)s.map[i] == mirror_of(&m, i)) exact++;
    }
    printf("strongest symmetry: %zu of %zu vertices map exactly to their mirror image; complexity %.3f\n", exact, m.nv, s.complexity);
    CHECK(exact >= m.nv * 95 / 100, "only %zu exact mirror images", exact);
    /* The judge: a mirror reverses orientation and fixes only a band along its plane. */
    CHECK(s.reversal > 0.9 && s.fixed < 0.2 && s.score > 0.5 && s.score <= 1.0, "judge: reversal %.3f fixed %.3f score %.3f", s.reversal, s.fixed, s.score);
    for (i = 1; i < count; i++) {
        sym_symmetry t;
        memset(&t, 0, sizeof t);
        t.struct_size = sizeof t;
        CHECK(sym_get_map(r, i, &t) == SYM_STATUS_OK, "get_map %zu", i);
        CHECK(t.score <= s.score, "symmetry %zu scores %.3f above the first (%.3f)", i, t.score, s.score);
    }
    q = sym_vertex_symmetry(r);
    CHECK(q != NULL, "vertex symmetry");
    for (i = 0; i < m.nv; i++) CHECK(q[i] >= s.confidence[i] - 1e-12 && q[i] <= 1.0, "summary");
    {
        sym_mesh_report info;
        memset(&info, 0, sizeof info);
        info.struct_size = sizeof info;
        CHECK(sym_get_mesh_report(r, &info) == SYM_STATUS_OK && info.kept_components == 1, "one component");
        CHECK(s.source_component == 0 && s.target_component == 0, "components %u -> %u", s.source_component, s.target_component);
    }
    sym_free(r);
    r = NULL;
    {
        /* Ten faces repeated reversed (a double-sided export): dropped and counted (0.7). */
        uint32_t *t2 = (uint32_t *)malloc(3 * (m.nt + 10) * sizeof(uint32_t));
        sym_mesh_report info;
        CHECK(t2 != NULL, "memory");
        memcpy(t2, m.t, 3 * m.nt * sizeof(uint32_t));
        for (i = 0; i < 10; i++) {
            t2[3 * (m.nt + i)] = m.t[3 * i + 2];
            t2[3 * (m.nt + i) + 1] = m.t[3 * i + 1];
            t2[3 * (m.nt + i) + 2] = m.t[3 * i];
        }
        CHECK(sym_detect(m.v, m.nv, t2, m.nt + 10, p, NULL, NULL, &r) == SYM_STATUS_OK, "detect with repeated faces");
        memset(&info, 0, sizeof info);
        info.struct_size = sizeof info;
        CHECK(sym_get_mesh_report(r, &info) == SYM_STATUS_OK && info.duplicate_triangles == 10 && info.non_manifold_edges == 0,
              "repeated faces: %zu dropped, %zu non-manifold edges", info.duplicate_triangles, info.non_manifold_edges);
        free(t2);
        sym_free(r);
        r = NULL;
    }
    {
        /* Two copies, the second 3 units further along x. */
        size_t n = m.nv, good = 0;
        double *v2 = (double *)malloc(6 * n * sizeof(double));
        uint32_t *t2 = (uint32_t *)malloc(6 * m.nt * sizeof(uint32_t));
        sym_mesh_report info;
        CHECK(v2 != NULL && t2 != NULL, "memory");
        memcpy(v2, m.v, 3 * n * sizeof(double));
        for (i = 0; i < 3 * n; i++) v2[3 * n + i] = m.v[i] + (i % 3 == 0 ? 3.0 : 0.0);
        memcpy(t2, m.t, 3 * m.nt * sizeof(uint32_t));
        for (i = 0; i < 3 * m.nt; i++) t2[3 * m.nt + i] = m.t[i] + (uint32_t)n;
        CHECK(sym_detect(v2, 2 * n, t2, 2 * m.nt, p, NULL, NULL, &r) == SYM_STATUS_OK, "detect two components");
        memset(&info, 0, sizeof info);
        info.struct_size = sizeof info;
        CHECK(sym_get_mesh_report(r, &info) == SYM_STATUS_OK && info.components == 2 && info.kept_components == 2, "two components kept (%zu)", info.kept_components);
        memset(&s, 0, sizeof s);
        s.struct_size = sizeof s;
        CHECK(sym_get_map(r, 0, &s) == SYM_STATUS_OK, "get_map");
        CHECK(s.source_component == 0 && s.target_component == 1 && s.order == 2 && s.kind == SYM_KIND_GLOBAL, "swap: components %u -> %u, order %u", s.source_component, s.target_component, s.order);
        for (i = 0; i < n; i++) {
            size_t img = (size_t)s.map[i], mir = mirror_of(&m, i);
            if (s.map[i] >= 0 && (img == n + i || img == n + mir) && (size_t)s.map[n + i] < n) good++;
        }
        printf("two copies: %zu of %zu vertices map exactly to their copy or its mirror image\n", good, n);
        CHECK(good >= n * 9 / 10, "only %zu exact", good);
        free(v2);
        free(t2);
        sym_free(r);
    }
    {
        /* Partial symmetries between repeated parts (added in 0.5): after every global one. */
        size_t partial = 0;
        CHECK(sym_params_set_parts(NULL, 1) == SYM_STATUS_NULL_PARAMETER, "parts: NULL params");
        CHECK(sym_params_set_parts(p, 1) == SYM_STATUS_OK, "parts");
        CHECK(sym_detect(m.v, m.nv, m.t, m.nt, p, NULL, NULL, &r) == SYM_STATUS_OK, "detect with parts");
        for (i = 0; i < sym_count(r); i++) {
            sym_symmetry t;
            memset(&t, 0, sizeof t);
            t.struct_size = sizeof t;
            CHECK(sym_get_map(r, i, &t) == SYM_STATUS_OK, "get_map %zu", i);
            if (t.kind == SYM_KIND_PARTIAL) partial++;
            else CHECK(partial == 0, "global symmetry %zu after a partial one", i);
        }
        memset(&s, 0, sizeof s);
        s.struct_size = sizeof s;
        CHECK(sym_get_map(r, 0, &s) == SYM_STATUS_OK && s.kind == SYM_KIND_GLOBAL, "first symmetry global with parts");
        printf("with parts: %zu symmetries, %zu partial\n", sym_count(r), partial);
        sym_free(r);
    }
    sym_params_free(p);
    free_mesh(&m);
    printf("test_detect: ok\n");
    return 0;
}
