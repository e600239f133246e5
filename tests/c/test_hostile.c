/* Hostile input battery: every case must return the documented status and a message, never
 * crash, hang or leak (run under ASan/UBSan and valgrind by ctest). Usage: test_hostile MESH.off */
#include "intrinsym.h"
#include "common.h"

static int cases = 0;

static void expect(const char *name, sym_status got, sym_status want, int want_message) {
    char buf[512];
    size_t len = 0;
    CHECK(got == want, "%s: status %d (%s), expected %d", name, (int)got, sym_status_str(got), (int)want);
    CHECK(sym_last_error(buf, sizeof buf, &len) == SYM_STATUS_OK, "%s: last_error", name);
    if (want_message) CHECK(len > 0 && strlen(buf) > 0, "%s: no message", name);
    printf("%-46s -> %-28s %s\n", name, sym_status_str(got), buf);
    cases++;
}

static int cancel_after = 0;
static int cancelling(float fraction, void *user_data) {
    int *n = (int *)user_data;
    (void)fraction;
    return ++*n < cancel_after;
}

/* Returns 0 (stop) only at the final call, fraction 1 (issue 16, item 11). */
static int stop_at_the_end(float fraction, void *user_data) {
    (void)user_data;
    return fraction < 1.0f;
}

/* Makes a failing call, then continues: the outer call's last error must not keep its message
 * (issue 16, item 12). */
static int fail_inside(float fraction, void *user_data) {
    (void)fraction;
    (void)sym_params_set_samples((sym_params *)user_data, 1);
    return 1;
}

/* Starts a detection from inside the callback (issue 16, item 10): it must return, not
 * deadlock, with a clear error; the outer detection goes on. */
typedef struct {
    int calls;
    sym_status inner;
    size_t message_length;
} reentry;
static int detect_inside(float fraction, void *user_data) {
    static const double v[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const uint32_t t[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    reentry *e = (reentry *)user_data;
    sym_result *inner = NULL;
    (void)fraction;
    if (e->calls++ == 0) {
        e->inner = sym_detect(v, 4, t, 4, NULL, NULL, NULL, &inner);
        (void)sym_last_error(NULL, 0, &e->message_length);
        sym_free(inner);
    }
    return 1;
}

static sym_status detect(const double *v, size_t nv, const uint32_t *t, size_t nt, const sym_params *p) {
    sym_result *r = NULL;
    sym_status s = sym_detect(v, nv, t, nt, p, NULL, NULL, &r);
    if (s == SYM_STATUS_OK) {
        CHECK(r != NULL, "OK without result");
        sym_free(r);
    } else {
        CHECK(r == NULL, "out written on failure");
    }
    return s;
}

int main(int argc, char **argv) {
    test_mesh m;
    const double tet_v[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint32_t tet_t[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    double bad_v[12];
    uint32_t bad_t[12];
    sym_params *p = sym_params_new();
    sym_result *r = NULL, *good = NULL;
    sym_symmetry s;
    char small[8];
    size_t len;
    int n = 0;
    CHECK(argc == 2 && read_off(argv[1], &m), "cannot read mesh");
    CHECK(p != NULL, "params");

    /* NULL pointers. */
    expect("NULL vertices", sym_detect(NULL, 4, tet_t, 4, NULL, NULL, NULL, &r), SYM_STATUS_NULL_PARAMETER, 1);
    expect("NULL triangles", sym_detect(tet_v, 4, NULL, 4, NULL, NULL, NULL, &r), SYM_STATUS_NULL_PARAMETER, 1);
    expect("NULL out", sym_detect(tet_v, 4, tet_t, 4, NULL, NULL, NULL, NULL), SYM_STATUS_NULL_PARAMETER, 1);
    expect("NULL everything", sym_detect(NULL, 0, NULL, 0, NULL, NULL, NULL, NULL), SYM_STATUS_NULL_PARAMETER, 1);
    expect("get_map NULL result", sym_get_map(NULL, 0, &s), SYM_STATUS_NULL_PARAMETER, 1);
    expect("setter NULL params", sym_params_set_samples(NULL, 32), SYM_STATUS_NULL_PARAMETER, 1);
    expect("last_error NULL buf with len", sym_last_error(NULL, 8, &len), SYM_STATUS_NULL_PARAMETER, 1);
    CHECK(sym_count(NULL) == 0 && sym_vertex_count(NULL) == 0 && sym_vertex_symmetry(NULL) == NULL, "NULL queries");
    cases++;
    sym_free(NULL);
    sym_params_free(NULL);
    cases++;

    /* Sizes. */
    expect("zero vertices", detect(tet_v, 0, tet_t, 4, NULL), SYM_STATUS_INVALID_MESH, 1);
    expect("zero triangles", detect(tet_v, 4, tet_t, 0, NULL), SYM_STATUS_INVALID_MESH, 1);
    expect("absurd vertex count", detect(tet_v, SIZE_MAX / 2, tet_t, 4, NULL), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("absurd triangle count", detect(tet_v, 4, tet_t, SIZE_MAX / 3, NULL), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("vertex count too small for indices", detect(tet_v, 3, tet_t, 4, NULL), SYM_STATUS_INVALID_MESH, 1);

    /* Coordinates. */
    memcpy(bad_v, tet_v, sizeof bad_v);
    bad_v[4] = NAN;
    expect("NaN coordinate", detect(bad_v, 4, tet_t, 4, NULL), SYM_STATUS_INVALID_MESH, 1);
    bad_v[4] = INFINITY;
    expect("+inf coordinate", detect(bad_v, 4, tet_t, 4, NULL), SYM_STATUS_INVALID_MESH, 1);
    bad_v[4] = -INFINITY;
    expect("-inf coordinate", detect(bad_v, 4, tet_t, 4, NULL), SYM_STATUS_INVALID_MESH, 1);

    /* Indices. */
    memcpy(bad_t, tet_t, sizeof bad_t);
    bad_t[5] = 4;
    expect("index out of range", detect(tet_v, 4, bad_t, 4, NULL), SYM_STATUS_INVALID_MESH, 1);
    bad_t[5] = UINT32_MAX;
    expect("index UINT32_MAX", detect(tet_v, 4, bad_t, 4, NULL), SYM_STATUS_INVALID_MESH, 1);
    memcpy(bad_t, tet_t, sizeof bad_t);
    bad_t[4] = bad_t[3];
    expect("repeated index in a triangle", detect(tet_v, 4, bad_t, 4, NULL), SYM_STATUS_INVALID_MESH, 1);
    {
        /* Non-manifold edges are accepted by default (issue 16, item 2) and refused on request. */
        const uint32_t twice[15] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 0, 2, 1};
        const double fan_v[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0};
        const uint32_t fan_t[9] = {0, 1, 2, 0, 1, 3, 0, 1, 4};
        sym_params *strict = sym_params_new();
        CHECK(sym_params_set_allow_non_manifold(strict, 0) == SYM_STATUS_OK, "strict");
        /* A repeated triangle is dropped (0.7), so it makes no non-manifold edge, even for the strict. */
        expect("duplicate triangle, dropped, strict", detect(tet_v, 4, twice, 5, strict), SYM_STATUS_OK, 0);
        expect("edge shared by 3 triangles, refused", detect(fan_v, 5, fan_t, 3, strict), SYM_STATUS_INVALID_MESH, 1);
        expect("duplicate triangle, dropped", detect(tet_v, 4, twice, 5, NULL), SYM_STATUS_OK, 0);
        expect("edge shared by 3 triangles, accepted", detect(fan_v, 5, fan_t, 3, NULL), SYM_STATUS_OK, 0);
        sym_params_free(strict);
    }
    {
        /* A triangle soup (every triangle its own vertices, as from STL) is welded (item 3):
         * the report says how many, and every input vertex gets an image. */
        double soup_v[36];
        uint32_t soup_t[12];
        sym_mesh_report info;
        sym_result *welded = NULL;
        int i, d;
        for (i = 0; i < 12; i++) {
            for (d = 0; d < 3; d++) soup_v[3 * i + d] = tet_v[3 * tet_t[i] + d];
            soup_t[i] = (uint32_t)i;
        }
        CHECK(sym_detect(soup_v, 12, soup_t, 4, NULL, NULL, NULL, &welded) == SYM_STATUS_OK, "soup detect");
        memset(&info, 0, sizeof info);
        info.struct_size = sizeof info;
        CHECK(sym_get_mesh_report(welded, &info) == SYM_STATUS_OK, "mesh report");
        CHECK(info.input_vertices == 12 && info.welded_vertices == 8 && info.isolated_vertices == 0 && info.components == 1, "welded %zu of %zu", info.welded_vertices, info.input_vertices);
        if (sym_count(welded) > 0) {
            sym_symmetry w;
            memset(&w, 0, sizeof w);
            w.struct_size = sizeof w;
            CHECK(sym_get_map(welded, 0, &w) == SYM_STATUS_OK, "soup map");
            for (i = 0; i < 12; i++) CHECK(w.map[i] >= 0 && w.map[i] < 12, "soup vertex %d has no image", i);
        }
        info.struct_size = 8;
        expect("mesh report struct_size too small", sym_get_mesh_report(welded, &info), SYM_STATUS_INVALID_ARGUMENT, 1);
        expect("mesh report NULL out", sym_get_mesh_report(welded, NULL), SYM_STATUS_NULL_PARAMETER, 1);
        sym_free(welded);
    }

    /* Degenerate and tiny meshes. */
    {
        const double line_v[12] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0};
        expect("all triangles degenerate", detect(line_v, 4, tet_t, 4, NULL), SYM_STATUS_INVALID_MESH, 1);
        expect("all vertices coincide", detect((const double[12]){1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1}, 4, tet_t, 4, NULL), SYM_STATUS_INVALID_MESH, 1);
    }
    /* k (default 100) larger than the vertex count is clamped to it: tiny meshes still run. */
    expect("3-vertex mesh, k clamped to 3", detect(tet_v, 3, tet_t, 1, NULL), SYM_STATUS_OK, 0);
    expect("tetrahedron, k clamped to 4", detect(tet_v, 4, tet_t, 4, NULL), SYM_STATUS_OK, 0);
    {
        sym_params *small_k = sym_params_new();
        sym_status st;
        CHECK(sym_params_set_eigenpairs(small_k, 4) == SYM_STATUS_OK, "k=4");
        CHECK(sym_params_set_samples(small_k, 8) == SYM_STATUS_OK, "samples");
        st = detect(tet_v, 4, tet_t, 4, small_k);
        CHECK(st == SYM_STATUS_OK, "a tetrahedron with k = 4 runs (%s)", sym_status_str(st));
        cases++;
        sym_params_free(small_k);
    }

    /* Disconnected: two tetrahedra. */
    {
        double two_v[24];
        uint32_t two_t[24];
        int i;
        sym_params *reject = sym_params_new();
        for (i = 0; i < 12; i++) { two_v[i] = tet_v[i]; two_v[12 + i] = tet_v[i] + 5.0; two_t[i] = tet_t[i]; two_t[12 + i] = tet_t[i] + 4; }
        CHECK(sym_params_set_reject_disconnected(reject, 1) == SYM_STATUS_OK, "reject");
        expect("disconnected, rejected", detect(two_v, 8, two_t, 8, reject), SYM_STATUS_INVALID_MESH, 1);
        sym_params_free(reject);
    }

    /* Parameter values. */
    expect("eigenpairs 0", sym_params_set_eigenpairs(p, 0), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("eigenpairs 10^6", sym_params_set_eigenpairs(p, 1000000), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("samples 1", sym_params_set_samples(p, 1), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("eps NaN", sym_params_set_voting_eps(p, NAN), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("eps negative", sym_params_set_voting_eps(p, -0.1), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("wks quantile 2", sym_params_set_wks_quantile(p, 2.0), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("accept inf", sym_params_set_accept(p, INFINITY), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("groups 1000", sym_params_set_groups(p, 1000), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("proxy 10", sym_params_set_proxy_vertices(p, 10), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("restarts 9", sym_params_set_restarts(p, 9), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("restarts 0", sym_params_set_restarts(p, 0), SYM_STATUS_OK, 0);
    expect("restarts NULL params", sym_params_set_restarts(NULL, 1), SYM_STATUS_NULL_PARAMETER, 1);
    expect("min score ratio NaN", sym_params_set_min_score_ratio(p, NAN), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("min score ratio 1.5", sym_params_set_min_score_ratio(p, 1.5), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("min score ratio -0.1", sym_params_set_min_score_ratio(p, -0.1), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("min score ratio 0", sym_params_set_min_score_ratio(p, 0.0), SYM_STATUS_OK, 0);
    expect("min score ratio NULL params", sym_params_set_min_score_ratio(NULL, 0.2), SYM_STATUS_NULL_PARAMETER, 1);
    expect("global preference NaN", sym_params_set_global_preference(p, NAN), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("global preference inf", sym_params_set_global_preference(p, INFINITY), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("global preference 0.5", sym_params_set_global_preference(p, 0.5), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("global preference 1", sym_params_set_global_preference(p, 1.0), SYM_STATUS_OK, 0);
    expect("global preference NULL params", sym_params_set_global_preference(NULL, 3.0), SYM_STATUS_NULL_PARAMETER, 1);
    expect("curvature weight NaN", sym_params_set_curvature_weight(p, NAN), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("curvature weight inf", sym_params_set_curvature_weight(p, INFINITY), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("curvature weight -0.01", sym_params_set_curvature_weight(p, -0.01), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("curvature weight NULL params", sym_params_set_curvature_weight(NULL, 0.0), SYM_STATUS_NULL_PARAMETER, 1);
    expect("curvature weight 0.03", sym_params_set_curvature_weight(p, 0.03), SYM_STATUS_OK, 0);
    expect("proxy off", sym_params_set_proxy_vertices(p, 0), SYM_STATUS_OK, 0);
    expect("proxy 6000", sym_params_set_proxy_vertices(p, 6000), SYM_STATUS_OK, 0);
    expect("valid setter", sym_params_set_groups(p, 0), SYM_STATUS_OK, 0);
    {
        sym_params *freed = sym_params_new();
        sym_params_free(freed);
        expect("setter on freed params", sym_params_set_samples(freed, 32), SYM_STATUS_INVALID_ARGUMENT, 1);
        sym_params_free(freed); /* double free: no-op */
        cases++;
    }

    /* Cancel from the callback. */
    cancel_after = 3;
    n = 0;
    r = NULL;
    expect("cancel from progress callback", sym_detect(m.v, m.nv, m.t, m.nt, p, cancelling, &n, &r), SYM_STATUS_CANCELLED, 1);
    CHECK(r == NULL && n == 3, "cancel: out untouched, callback called %d times", n);

    /* The final progress call (fraction 1) can cancel too, and the message names the stage. */
    r = NULL;
    expect("cancel at the final progress call", sym_detect(tet_v, 4, tet_t, 4, NULL, stop_at_the_end, NULL, &r), SYM_STATUS_CANCELLED, 1);
    CHECK(r == NULL, "cancelled at the end: out untouched");
    {
        char message[256];
        CHECK(sym_last_error(message, sizeof message, NULL) == SYM_STATUS_OK && strstr(message, "report") != NULL && strstr(message, "eigensolver") == NULL,
              "the cancel message names the stage: %s", message);
        cases++;
    }
    /* A failing call made inside the callback leaves no message after the outer success. */
    {
        sym_params *scratch = sym_params_new();
        CHECK(sym_detect(tet_v, 4, tet_t, 4, NULL, fail_inside, scratch, &r) == SYM_STATUS_OK, "detect with a failing call inside");
        CHECK(sym_last_error(NULL, 0, &len) == SYM_STATUS_OK && len == 0, "last error after a success is empty (%zu bytes)", len);
        sym_free(r);
        sym_params_free(scratch);
        cases++;
    }
    /* A detection started inside the callback returns an error instead of deadlocking. */
    {
        reentry e = {0, SYM_STATUS_OK, 0};
        CHECK(sym_detect(m.v, m.nv, m.t, m.nt, p, detect_inside, &e, &r) == SYM_STATUS_OK, "the outer detection goes on");
        CHECK(e.inner == SYM_STATUS_INVALID_ARGUMENT && e.message_length > 0, "re-entrant detect: status %d, message %zu bytes", (int)e.inner, e.message_length);
        sym_free(r);
        cases++;
    }

    /* A good result, then misuse of it. */
    CHECK(sym_detect(m.v, m.nv, m.t, m.nt, p, NULL, NULL, &good) == SYM_STATUS_OK, "good detect");
    memset(&s, 0, sizeof s);
    s.struct_size = sizeof s;
    expect("get_map index out of range", sym_get_map(good, sym_count(good), &s), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("get_map index SIZE_MAX", sym_get_map(good, SIZE_MAX, &s), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("get_map NULL out", sym_get_map(good, 0, NULL), SYM_STATUS_NULL_PARAMETER, 1);
    s.struct_size = 8;
    expect("get_map struct_size too small", sym_get_map(good, 0, &s), SYM_STATUS_INVALID_ARGUMENT, 1);
    s.struct_size = sizeof s;
    expect("get_map valid", sym_get_map(good, 0, &s), SYM_STATUS_OK, 0);
    {
        sym_result *bogus = (sym_result *)(void *)&s;
        expect("get_map on a pointer not from sym_detect", sym_get_map(bogus, 0, &s), SYM_STATUS_INVALID_ARGUMENT, 1);
        CHECK(sym_count(bogus) == 0, "count of bogus handle");
        sym_free(bogus); /* not ours: ignored */
        cases++;
    }
    /* Handles of one type passed as the other (issue 16, item 8): refused, nothing freed. */
    expect("get_map on a params handle", sym_get_map((const sym_result *)(const void *)p, 0, &s), SYM_STATUS_INVALID_ARGUMENT, 1);
    expect("setter on a result handle", sym_params_set_samples((sym_params *)(void *)good, 32), SYM_STATUS_INVALID_ARGUMENT, 1);
    sym_free((sym_result *)(void *)p);
    sym_params_free((sym_params *)(void *)good);
    expect("params still live after sym_free(params)", sym_params_set_samples(p, 64), SYM_STATUS_OK, 0);
    CHECK(sym_count(good) > 0 && sym_get_map(good, 0, &s) == SYM_STATUS_OK, "result still live after sym_params_free(result)");
    cases++;
    sym_free(good);
    expect("get_map after free", sym_get_map(good, 0, &s), SYM_STATUS_INVALID_ARGUMENT, 1);
    sym_free(good); /* double free: no-op */
    cases++;
    /* A freed handle stays dead when new results are made (issue 16, item 9). */
    {
        sym_result *fresh[4] = {NULL, NULL, NULL, NULL};
        int i;
        for (i = 0; i < 4; i++) {
            CHECK(sym_detect(tet_v, 4, tet_t, 4, NULL, NULL, NULL, &fresh[i]) == SYM_STATUS_OK, "fresh result");
            CHECK(fresh[i] != good, "a new handle equals a freed one");
        }
        expect("stale handle after new results", sym_get_map(good, 0, &s), SYM_STATUS_INVALID_ARGUMENT, 1);
        CHECK(sym_count(good) == 0, "a stale handle has no symmetries");
        for (i = 0; i < 4; i++) sym_free(fresh[i]);
    }

    /* Last error: truncation and length query. */
    (void)sym_params_set_samples(p, 1);
    CHECK(sym_last_error(small, sizeof small, &len) == SYM_STATUS_OK && strlen(small) == sizeof small - 1 && len > sizeof small, "truncation");
    CHECK(sym_last_error(NULL, 0, &len) == SYM_STATUS_OK && len > 0, "length query");
    cases++;
    {
        int st;
        for (st = 0; st <= 7; st++) CHECK(sym_status_str((sym_status)st) != NULL && strlen(sym_status_str((sym_status)st)) > 0, "status_str");
        /* Values outside the enum (issue 16, item 7). */
        CHECK(strcmp(sym_status_str(-1), "unknown status") == 0 && strcmp(sym_status_str(1000000), "unknown status") == 0, "status_str out of range");
        cases++;
    }

    sym_params_free(p);
    free_mesh(&m);
    printf("test_hostile: %d cases, all as documented\n", cases);
    CHECK(cases >= 40, "only %d cases", cases);
    return 0;
}
