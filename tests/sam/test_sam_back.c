/* SAM with a lower-tessellation back-side mesh (Maisch & Ropinski 2017, section 4.4 and its appendix).
 *
 * Sphere (2562 vertices) with a given icosphere (162) and with its own simplification as back side:
 * every link indexes the back-side mesh and passes Eq. 13-14 against its positions and normals (on a
 * sphere the back side lies more than R below the tangent plane); the strongest link is among the
 * nearest back-side vertices; the tree equals the brute-force search; the map's copy of the back-side
 * mesh is the one given and its fan areas are Eq. 16 on it, summing to its surface area; K' gives K
 * at rest (Eq. 15); n links cover several times the back-side area they cover on the mesh itself.
 * Two parallel squares (the faces of a slab): Hottel's closed-form view factor from the fine front
 * face's reduced fans to the coarse back face's; the build's form factors from a fine receiver to every
 * coarse back-side vertex sum to an independent quadrature over the whole back face.
 * Deformation (section 3.4) on the back-side mesh: updates settle, links stay valid or stuck, never
 * worse. Files: version 2 round trip, version-1 file of an earlier build read and reproduced byte for
 * byte, corrupt back-side data rejected with the file named. Bad input: clear errors. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "sam_test_util.h"
#include "sss/sam.h"
#include "sss/scene.h"


static double longest_edge(const sss_mesh *m)
{
    double edge = 0.0;
    for (uint32_t t = 0; t < m->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            double e = sam_test_dist(m->positions + 3 * m->indices[3 * t + k], m->positions + 3 * m->indices[3 * t + (k + 1) % 3]);
            if (e > edge) edge = e;
        }
    return edge;
}

/* Mean over vertices of the back-side area its links cover (sum of the linked fans' F'). */
static double covered_area(const sss_sam *s, const float *src_area)
{
    double sum = 0.0;
    for (size_t i = 0; i < (size_t)s->vertex_count * s->n; i++)
        if (s->links[i] != SSS_SAM_NONE) sum += src_area[s->links[i]];
    return sum / s->vertex_count;
}

/* ---- Sphere ------------------------------------------------------------------------------------ */

static void check_sphere_map(const sss_mesh *m, const sss_sam *s, const sss_profile *p, int exact_sphere)
{
    sss_error err = {0};
    sss_mesh back;
    CHECK(sss_sam_back_mesh(s, &back) == 1);
    uint32_t n = s->n, B = back.vertex_count;
    /* the map's fan areas of the back-side mesh are Eq. 16 on it and partition its surface */
    float *area = malloc(sizeof(float) * B);
    sss_sam_fan_areas(&back, area);
    int same_area = 0;
    double sum = 0.0;
    for (uint32_t i = 0; i < B; i++) {
        same_area += fabs(area[i] - s->back_fan_area[i]) <= 1e-6 * area[i];
        sum += s->back_fan_area[i];
    }
    CHECK(same_area == (int)B);
    CHECK_REL(sum, sss_mesh_surface_area(&back), 1e-5);
    double edge = longest_edge(&back);
    int bad = 0, back_ok = 0, across = 0, nearest = 0, used = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *xo = m->positions + 3 * v, *no = m->normals + 3 * v;
        double dmin = INFINITY; /* nearest back-side vertex of the back-side mesh */
        for (uint32_t j = 0; j < B; j++)
            if (sss_sam_is_back(xo, no, back.positions + 3 * j, back.normals + 3 * j))
                dmin = fmin(dmin, sam_test_dist(xo, back.positions + 3 * j));
        for (uint32_t k = 0; k < n; k++) {
            uint32_t b = s->links[v * n + k];
            if (b == SSS_SAM_NONE) continue;
            used++;
            if (b >= B) {
                bad++;
                continue;
            }
            const float *xi = back.positions + 3 * b, *ni = back.normals + 3 * b;
            /* Eq. 13-14, written out: behind the tangent plane at x_o, normals facing apart */
            double depth = (xi[0] - xo[0]) * no[0] + (xi[1] - xo[1]) * no[1] + (xi[2] - xo[2]) * no[2];
            double facing = ni[0] * no[0] + ni[1] * no[1] + ni[2] * no[2];
            back_ok += depth < 0.0 && facing < 0.0;
            /* on the unit sphere a point whose normal faces away from n_o is more than R below the plane */
            if (exact_sphere) across += depth < -(1.0 - 1e-5);
        }
        uint32_t b0 = s->links[v * n];
        if (b0 != SSS_SAM_NONE && b0 < B && sam_test_dist(xo, back.positions + 3 * b0) <= dmin + 2.0 * edge) nearest++;
    }
    printf("  %u -> %u back-side vertices: %d links, %d in Eq. 13-14, strongest among the nearest %d/%u\n",
           m->vertex_count, B, used, back_ok, nearest, m->vertex_count);
    CHECK(bad == 0);
    CHECK(used == (int)(n * m->vertex_count)); /* a sphere has plenty of back side */
    CHECK(back_ok == used);
    if (exact_sphere) CHECK(across == used);
    CHECK(nearest == (int)m->vertex_count);
    /* K' F' R_d = K at rest (Eq. 15) with the back-side mesh's F' and positions */
    sss_sam_profile_table t;
    CHECK(sss_sam_profile_table_build(p, s->energy, 0, &t, &err) == SSS_OK);
    size_t slots = (size_t)n * m->vertex_count;
    float *approx = malloc(sizeof(float) * 3 * slots);
    sss_sam_approximate_back(s, m, &back, NULL, &t, approx);
    int same = 0;
    for (size_t i = 0; i < 3 * slots; i++) same += fabs(approx[i] - s->form_factor[i]) <= 1e-4 * s->form_factor[i] + 1e-30;
    CHECK(same == (int)(3 * slots));
    /* the functions for maps without a back-side mesh refuse this one (zeros, nothing moved) */
    sss_sam_approximate(s, m, NULL, &t, approx);
    int zero = 0;
    for (size_t i = 0; i < 3 * slots; i++) zero += approx[i] == 0.0f;
    CHECK(zero == (int)(3 * slots));
    sss_sam_profile_table_free(&t);
    free(approx);
    free(area);
}

static void test_sphere(void)
{
    sss_mesh m, ico;
    sss_error err = {0};
    CHECK(sss_mesh_sphere(1.0, 4, &m, &err) == SSS_OK);
    CHECK(sss_mesh_sphere(1.0, 2, &ico, &err) == SSS_OK);
    sss_profile p;
    sam_test_profile(10.0, &p); /* Marble: 1 / sigma_tr of red ~ 0.85 units, comparable to the radius */
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    d.n = 3;
    d.samples = 16;
    sss_sam own, given, given_bf, simp;
    sss_sam_stats st_own, st_given;
    CHECK(sss_sam_build(&m, &p, &d, &own, &st_own, &err) == SSS_OK);
    CHECK(own.back_vertex_count == 0);
    d.backside = &ico;
    CHECK(sss_sam_build(&m, &p, &d, &given, &st_given, &err) == SSS_OK);
    /* the map carries the mesh it was given */
    CHECK(given.back_vertex_count == ico.vertex_count && given.back_triangle_count == ico.triangle_count);
    CHECK(given.back_hash == sss_sam_mesh_hash(&ico));
    CHECK(memcmp(given.back_positions, ico.positions, 12 * (size_t)ico.vertex_count) == 0 &&
          memcmp(given.back_normals, ico.normals, 12 * (size_t)ico.vertex_count) == 0 &&
          memcmp(given.back_indices, ico.indices, 12 * (size_t)ico.triangle_count) == 0);
    printf("sphere, given icosphere:\n");
    check_sphere_map(&m, &given, &p, 1);
    /* the tree search equals testing every pair (fine receivers, coarse sources) */
    d.brute_force = 1;
    CHECK(sss_sam_build(&m, &p, &d, &given_bf, NULL, &err) == SSS_OK);
    size_t slots = (size_t)d.n * m.vertex_count;
    CHECK(memcmp(given.links, given_bf.links, 4 * slots) == 0 &&
          memcmp(given.form_factor, given_bf.form_factor, 12 * slots) == 0);
    d.brute_force = 0;
    /* its own simplification */
    d.backside = NULL;
    d.backside_triangles = 320;
    CHECK(sss_sam_build(&m, &p, &d, &simp, NULL, &err) == SSS_OK);
    CHECK(simp.back_vertex_count > 0 && simp.back_triangle_count <= 320);
    printf("sphere, simplified to %u triangles:\n", simp.back_triangle_count);
    check_sphere_map(&m, &simp, &p, 0);
    /* the point of section 4.4: n links cover far more of the back side on the coarse mesh (fans 16x
     * larger) and the search tests fewer candidates */
    double c_own = covered_area(&own, own.fan_area), c_given = covered_area(&given, given.back_fan_area);
    printf("covered back-side area per vertex: own mesh %.4g, icosphere %.4g; candidates tested %llu vs %llu\n",
           c_own, c_given, (unsigned long long)st_own.vertices_tested, (unsigned long long)st_given.vertices_tested);
    CHECK(c_given > 8.0 * c_own);
    CHECK(st_given.vertices_tested < st_own.vertices_tested);
    /* at or above the mesh's triangle count there is no separate back side: the plain map */
    sss_sam plain;
    d.backside_triangles = m.triangle_count;
    CHECK(sss_sam_build(&m, &p, &d, &plain, NULL, &err) == SSS_OK);
    CHECK(plain.back_vertex_count == 0 && memcmp(plain.links, own.links, 4 * slots) == 0);
    sss_sam_free(&plain);
    sss_sam_free(&own);
    sss_sam_free(&given);
    sss_sam_free(&given_bf);
    sss_sam_free(&simp);
    sss_mesh_free(&m);
    sss_mesh_free(&ico);
}

/* ---- Two parallel squares ------------------------------------------------------------------------ */

static void profile_kernel(const double xo[3], const double xi[3], void *user, double out[3])
{
    double dx = xi[0] - xo[0], dy = xi[1] - xo[1], dz = xi[2] - xo[2];
    sss_profile_eval_rgb(user, sqrt(dx * dx + dy * dy + dz * dz), out);
}

/* The faces of a slab [0, 1] x [0, c] x [0, 1]: y = 0 facing -y (vertices 0 .. (k+1)^2 - 1) and y = c
 * facing +y, each a k x k grid. */
static void slab_faces(int k, double c, sss_mesh *m)
{
    sss_error err = {0};
    uint32_t per = (uint32_t)((k + 1) * (k + 1));
    memset(m, 0, sizeof *m);
    m->vertex_count = 2 * per;
    m->triangle_count = (uint32_t)(4 * k * k);
    m->positions = malloc(sizeof(float) * 3 * m->vertex_count);
    m->normals = malloc(sizeof(float) * 3 * m->vertex_count);
    m->indices = malloc(sizeof(uint32_t) * 3 * m->triangle_count);
    uint32_t t = 0;
    for (int f = 0; f < 2; f++) {
        for (int i = 0; i <= k; i++)
            for (int j = 0; j <= k; j++) {
                uint32_t v = f * per + (uint32_t)(i * (k + 1) + j);
                float q[3] = {(float)i / k, f ? (float)c : 0.0f, (float)j / k}, nn[3] = {0, f ? 1.0f : -1.0f, 0};
                memcpy(m->positions + 3 * v, q, sizeof q);
                memcpy(m->normals + 3 * v, nn, sizeof nn);
            }
        for (int i = 0; i < k; i++)
            for (int j = 0; j < k; j++) {
                uint32_t a = f * per + (uint32_t)(i * (k + 1) + j), b = a + 1, cc = a + (uint32_t)(k + 1), dd = cc + 1;
                /* (a, b, cc) is counter-clockwise seen from +y */
                uint32_t tri[2][3] = {{a, b, cc}, {b, dd, cc}};
                for (int h = 0; h < 2; h++, t++)
                    for (int e = 0; e < 3; e++) m->indices[3 * t + e] = tri[h][f ? e : 2 - e];
            }
    }
    (void)err;
}

static void test_squares(void)
{
    const double c = 0.5;
    sss_mesh fine, coarse;
    slab_faces(8, c, &fine);
    slab_faces(2, c, &coarse);
    uint32_t fper = 81, cper = 9;
    /* Closed form: the reduced fans of the fine front face and of the coarse back face each partition
     * their square, so the view kernel summed over all fan pairs is Hottel's factor. */
    float A[9 * 64], Bt[9 * 64];
    double total = 0.0, area_a = 0.0;
    sss_error err = {0};
    float *fa = malloc(sizeof(float) * fine.vertex_count);
    sss_sam_fan_areas(&fine, fa);
    for (uint32_t o = 0; o < fper; o++) {
        size_t na = sss_sam_reduced_fan(&fine, o, A, 64);
        area_a += fa[o];
        for (uint32_t i = cper; i < 2 * cper; i++) {
            size_t nb = sss_sam_reduced_fan(&coarse, i, Bt, 64);
            double out[3];
            CHECK(sss_sam_region_integral(A, na, Bt, nb, 1u << 12, o * 31u + i, sam_test_view_kernel, (void *)&c, out, &err) ==
                  SSS_OK);
            total += fa[o] * out[0];
        }
    }
    double exact = sam_test_plates(1.0, 1.0, c);
    printf("squares 1 x 1 at %g: view factor over fine x coarse fans %.5f, closed form %.5f\n", c, total / area_a,
           exact);
    CHECK_REL(area_a, 1.0, 1e-5);
    CHECK_REL(total / area_a, exact, 0.01);

    /* The build: each fine front-face vertex links to every coarse back-face vertex (n = 9, the coarse
     * front face fails Eq. 13: it lies in the tangent plane), and sum_k K_ok is R_d integrated over the
     * whole back face (Eq. 8-11), here against an independent quadrature over the square itself. */
    sss_profile p;
    sam_test_profile(10.0, &p);
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    d.n = 9;
    d.samples = 4096;
    d.backside = &coarse;
    sss_sam s;
    CHECK(sss_sam_build(&fine, &p, &d, &s, NULL, &err) == SSS_OK);
    float square_b[18] = {0, (float)c, 0, 1, (float)c, 0, 1, (float)c, 1, 0, (float)c, 0, 1, (float)c, 1, 0, (float)c, 1};
    int all_back = 0, checked = 0, good = 0;
    double worst = 0.0;
    for (uint32_t o = 0; o < fper; o++) {
        double sum[3] = {0, 0, 0};
        int back = 1;
        for (uint32_t k = 0; k < 9; k++) {
            uint32_t b = s.links[o * 9 + k];
            back &= b >= cper && b < 2 * cper;
            for (int ch = 0; ch < 3; ch++) sum[ch] += s.form_factor[3 * (o * 9 + k) + ch];
        }
        all_back += back;
        if (o % 4) continue; /* the quadrature on every fourth receiver */
        size_t na = sss_sam_reduced_fan(&fine, o, A, 64);
        double ref[3];
        CHECK(sss_sam_region_integral(A, na, square_b, 2, 1u << 16, 99 + o, profile_kernel, &p, ref, &err) == SSS_OK);
        int ok = 1;
        for (int ch = 0; ch < 3; ch++) {
            double rel = fabs(sum[ch] - ref[ch]) / ref[ch];
            worst = fmax(worst, rel);
            ok &= rel < 0.02;
        }
        good += ok;
        checked++;
    }
    printf("slab: %d/%u receivers linked to the 9 back-face vertices; sum of K within 2%% of the quadrature "
           "for %d/%d (worst %.3g)\n",
           all_back, fper, good, checked, worst);
    CHECK(all_back == (int)fper);
    CHECK(good == checked);
    sss_sam_free(&s);
    free(fa);
    sss_mesh_free(&fine);
    sss_mesh_free(&coarse);
}

/* ---- Deformation --------------------------------------------------------------------------------- */

static void test_update(void)
{
    sss_error err = {0};
    sss_mesh m;
    char path[1024];
    snprintf(path, sizeof path, "%s/assets/bunny.ply", SSS_SOURCE_DIR);
    CHECK(sss_mesh_read(path, &m, &err) == SSS_OK);
    sss_profile p;
    sam_test_profile(2.5, &p);
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    d.n = 3;
    d.samples = 16;
    d.backside_triangles = 800;
    sss_sam s;
    CHECK(sss_sam_build(&m, &p, &d, &s, NULL, &err) == SSS_OK);
    sss_mesh back;
    CHECK(sss_sam_back_mesh(&s, &back));
    sss_sam_profile_table t;
    CHECK(sss_sam_profile_table_build(&p, s.energy, 0, &t, &err) == SSS_OK);
    sss_mesh_adjacency adj;
    CHECK(sss_mesh_adjacency_build(&back, &adj, &err) == SSS_OK);
    uint32_t V = m.vertex_count, B = back.vertex_count, n = s.n;
    size_t slots = (size_t)V * n;
    float *area = malloc(sizeof(float) * B), *approx = malloc(sizeof(float) * 3 * slots);
    uint32_t *before = malloc(4 * slots);
    float lo[3], hi[3];
    sss_mesh_bounds(&m, lo, hi);
    /* both meshes deform by the same map with the render mesh's box (sss/scene.h) */
    sss_animation anim = {SSS_ANIMATION_TWIST, 70.0, 4.0};
    sss_mesh dm, db;
    CHECK(sss_animation_deform_mesh(&anim, lo, hi, 1.0, &m, &dm, &err) == SSS_OK);
    CHECK(sss_animation_deform_mesh(&anim, lo, hi, 1.0, &back, &db, &err) == SSS_OK);
    /* the plain update refuses a map with a back-side mesh; a mismatched back-side mesh is refused */
    memcpy(before, s.links, 4 * slots);
    CHECK(sss_sam_update(&s, &dm, &adj, &t, NULL) == 0);
    CHECK(sss_sam_update_back(&s, &dm, &dm, &adj, &t, area) == 0);
    CHECK(memcmp(before, s.links, 4 * slots) == 0);
    uint64_t moved = sss_sam_update_back(&s, &dm, &db, &adj, &t, area);
    int in_range = 0, not_worse = 0, unique = 0;
    for (size_t i = 0; i < slots; i++) {
        uint32_t b = s.links[i], o = (uint32_t)(i / n);
        in_range += b == SSS_SAM_NONE || b < B;
        if (b == SSS_SAM_NONE || b >= B) continue;
        not_worse += sam_test_score(&dm, &db, area, &t, o, b) >= sam_test_score(&dm, &db, area, &t, o, before[i]) - 1e-12;
        int dup = 0;
        for (uint32_t q = 0; q < n; q++) dup |= q != i % n && s.links[(size_t)o * n + q] == b;
        unique += !dup;
    }
    int used = 0;
    for (size_t i = 0; i < slots; i++) used += s.links[i] != SSS_SAM_NONE && s.links[i] < B;
    CHECK(in_range == (int)slots);
    CHECK(not_worse == used);
    CHECK(unique == used);
    /* the deformed fan areas are Eq. 16 on the deformed back-side mesh */
    float *fa = malloc(sizeof(float) * B);
    sss_sam_fan_areas(&db, fa);
    CHECK(memcmp(fa, area, 4 * (size_t)B) == 0);
    free(fa);
    /* repeated steps on one pose settle, and then every valid link beats its free one-ring */
    int steps = 0;
    while (steps < 100 && sss_sam_update_back(&s, &dm, &db, &adj, &t, area) > 0) steps++;
    int local_max = 0, valid = 0;
    for (size_t i = 0; i < slots; i++) {
        uint32_t b = s.links[i], o = (uint32_t)(i / n);
        if (b == SSS_SAM_NONE) continue;
        double sb = sam_test_score(&dm, &db, area, &t, o, b);
        if (sb < 0.0) continue;
        valid++;
        int best = 1;
        for (uint32_t e = adj.offsets[b]; e < adj.offsets[b + 1]; e++) {
            uint32_t j = adj.neighbors[e];
            int taken = 0;
            for (uint32_t q = 0; q < n; q++) taken |= s.links[(size_t)o * n + q] == j;
            if (!taken && sam_test_score(&dm, &db, area, &t, o, j) > sb) best = 0;
        }
        local_max += best;
    }
    printf("bunny, back side %u vertices, twist t = 1: %llu links moved, settled after %d more steps, %d/%d valid "
           "links are local maxima\n",
           B, (unsigned long long)moved, steps, local_max, valid);
    CHECK(moved > 0);
    CHECK(steps < 100);
    CHECK(local_max == valid);
    /* Eq. 15 on the deformed meshes: finite, non-negative, 0 for links that fail Eq. 13-14 */
    sss_sam_approximate_back(&s, &dm, &db, area, &t, approx);
    int ok = 0;
    for (size_t i = 0; i < slots; i++) {
        uint32_t b = s.links[i], o = (uint32_t)(i / n);
        int fails = b != SSS_SAM_NONE && sam_test_score(&dm, &db, area, &t, o, b) < 0.0;
        int g = 1;
        for (int c = 0; c < 3; c++)
            g &= isfinite(approx[3 * i + c]) && approx[3 * i + c] >= 0.0f && (!fails || approx[3 * i + c] == 0.0f);
        ok += g;
    }
    CHECK(ok == (int)slots);
    sss_mesh_free(&dm);
    sss_mesh_free(&db);
    free(area);
    free(approx);
    free(before);
    sss_mesh_adjacency_free(&adj);
    sss_sam_profile_table_free(&t);
    sss_sam_free(&s);
    sss_mesh_free(&m);
}

/* ---- Files ------------------------------------------------------------------------------------------ */

static unsigned char *slurp(const char *path, long *size)
{
    *size = sam_test_file_size(path);
    FILE *f = fopen(path, "rb");
    unsigned char *b = *size > 0 ? malloc((size_t)*size) : NULL;
    if (f && b && fread(b, 1, (size_t)*size, f) != (size_t)*size) {
        free(b);
        b = NULL;
    }
    if (f) fclose(f);
    return b;
}

/* Writes bytes with a u32 replaced at `at` and the trailing FNV-1a 64 checksum recomputed (so that the
 * reader's own checks, not the checksum, must catch the change). */
static void write_patched(const char *path, const unsigned char *data, long size, long at, uint32_t value)
{
    unsigned char *b = malloc((size_t)size);
    memcpy(b, data, (size_t)size);
    for (int k = 0; k < 4; k++) b[at + k] = (unsigned char)(value >> (8 * k));
    uint64_t h = 0xcbf29ce484222325ull;
    for (long i = 0; i < size - 8; i++) h = (h ^ b[i]) * 0x100000001b3ull;
    for (int k = 0; k < 8; k++) b[size - 8 + k] = (unsigned char)(h >> (8 * k));
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(b, 1, (size_t)size, f);
        fclose(f);
    }
    free(b);
}

static uint32_t u32_at(const unsigned char *b, long at)
{
    return (uint32_t)b[at] | (uint32_t)b[at + 1] << 8 | (uint32_t)b[at + 2] << 16 | (uint32_t)b[at + 3] << 24;
}

static void test_files(void)
{
    sss_error err = {0};
    sss_mesh m, ico, other;
    CHECK(sss_mesh_sphere(1.0, 3, &m, &err) == SSS_OK);
    CHECK(sss_mesh_sphere(1.0, 1, &ico, &err) == SSS_OK);
    CHECK(sss_mesh_sphere(1.0, 2, &other, &err) == SSS_OK);
    sss_profile p;
    sam_test_profile(10.0, &p);
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    d.n = 5;
    d.samples = 8;
    d.backside = &ico;
    sss_sam s, r;
    CHECK(sss_sam_build(&m, &p, &d, &s, NULL, &err) == SSS_OK);
    char dir[] = "/tmp/sss_sam_backXXXXXX", path[256], bad[256];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/coarse.sam", dir);
    snprintf(bad, sizeof bad, "%s/bad.sam", dir);
    CHECK(sss_sam_write(path, &s, &err) == SSS_OK);
    long size;
    unsigned char *bytes = slurp(path, &size);
    CHECK(bytes != NULL);
    if (!bytes) return;
    /* version 2, and the size the layout of docs/sam_format.md gives */
    uint64_t V = s.vertex_count, slots = V * s.n, B = ico.vertex_count, T = ico.triangle_count;
    CHECK(u32_at(bytes, 8) == 2);
    CHECK((uint64_t)size == 320 + 4 * V + 28 * slots + 4 * (7 * B + 3 * T) + 8);
    CHECK(u32_at(bytes, 256) == B && u32_at(bytes, 260) == T);
    /* round trip */
    CHECK(sss_sam_read(path, &r, &err) == SSS_OK);
    CHECK(r.vertex_count == s.vertex_count && r.n == s.n && r.mesh_hash == s.mesh_hash &&
          r.back_vertex_count == s.back_vertex_count && r.back_triangle_count == s.back_triangle_count &&
          r.back_hash == s.back_hash && r.back_uvs == NULL);
    CHECK(memcmp(r.links, s.links, 4 * slots) == 0 && memcmp(r.form_factor, s.form_factor, 12 * slots) == 0 &&
          memcmp(r.kprime, s.kprime, 12 * slots) == 0 && memcmp(r.fan_area, s.fan_area, 4 * V) == 0);
    CHECK(memcmp(r.back_positions, s.back_positions, 12 * B) == 0 &&
          memcmp(r.back_normals, s.back_normals, 12 * B) == 0 &&
          memcmp(r.back_fan_area, s.back_fan_area, 4 * B) == 0 && memcmp(r.back_indices, s.back_indices, 12 * T) == 0);
    CHECK(sss_sam_check(&r, &m, &p.material, SSS_PROFILE_PBD, NULL, path, &err) == SSS_OK);
    /* written again: the same bytes */
    CHECK(sss_sam_write(bad, &r, &err) == SSS_OK);
    long size2;
    unsigned char *again = slurp(bad, &size2);
    CHECK(again && size2 == size && memcmp(again, bytes, (size_t)size) == 0);
    free(again);
    sss_sam_free(&r);
    /* another render mesh: rejected, naming the file */
    CHECK(sss_sam_read(path, &r, &err) == SSS_OK);
    CHECK(sss_sam_check(&r, &other, NULL, SSS_PROFILE_PBD, NULL, path, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "different mesh") != NULL && strstr(err.message, "coarse.sam") != NULL);
    sss_sam_free(&r);
    /* corrupt back-side data behind a valid checksum: a triangle index, a link past the back-side
     * mesh, a moved back-side vertex (its hash), an unknown flag, a newer version */
    long back_at = 320 + 4 * (long)V + 28 * (long)slots, idx_at = back_at + 4 * 7 * (long)B;
    struct {
        long at;
        uint32_t value;
        const char *words;
    } cases[5] = {{idx_at + 4, (uint32_t)B, "triangle"},
                  {320 + 4 * (long)V, (uint32_t)B, "out of range"},
                  {back_at, 0x3f800001u, "hash"},
                  {272, 2u, "back-side"},
                  {8, 3u, "version 3"}};
    for (int i = 0; i < 5; i++) {
        write_patched(bad, bytes, size, cases[i].at, cases[i].value);
        CHECK(sss_sam_read(bad, &r, &err) != SSS_OK);
        CHECK(r.links == NULL && r.back_positions == NULL);
        printf("patched: %s\n", err.message);
        CHECK(strstr(err.message, cases[i].words) != NULL && strstr(err.message, "bad.sam") != NULL);
    }
    /* truncated inside the back-side data; a flipped bit there */
    FILE *f = fopen(bad, "wb");
    if (f) {
        fwrite(bytes, 1, (size_t)(size - 20), f);
        fclose(f);
    }
    CHECK(sss_sam_read(bad, &r, &err) == SSS_ERROR_PARSE && strstr(err.message, "truncated") != NULL);
    bytes[idx_at - 3] ^= 0x10;
    f = fopen(bad, "wb");
    if (f) {
        fwrite(bytes, 1, (size_t)size, f);
        fclose(f);
    }
    CHECK(sss_sam_read(bad, &r, &err) == SSS_ERROR_PARSE && strstr(err.message, "checksum") != NULL);
    free(bytes);

    /* a version-1 file written by an earlier build (tests/data/sam/sphere_v1.sam: `sss sam build
     * sphere_v1.json -n 4 --samples 16` before version 2 existed) is read, fits its sphere, and the
     * same map built now is written byte for byte as that file */
    char v1[1024];
    snprintf(v1, sizeof v1, "%s/sam/sphere_v1.sam", SSS_TEST_DATA);
    CHECK(sss_sam_read(v1, &r, &err) == SSS_OK);
    CHECK(r.back_vertex_count == 0 && r.n == 4 && r.samples == 16);
    CHECK(sss_sam_check(&r, &other, NULL, r.model, NULL, v1, &err) == SSS_OK);
    sss_sam now;
    sss_material mat = r.material;
    sss_profile p1;
    CHECK(sss_profile_init(&p1, SSS_PROFILE_PBD, &mat, &sam_test_table, &err) == SSS_OK);
    memset(&d, 0, sizeof d);
    d.n = 4;
    d.samples = 16;
    CHECK(sss_sam_build(&other, &p1, &d, &now, NULL, &err) == SSS_OK);
    CHECK(sss_sam_write(bad, &now, &err) == SSS_OK);
    long s1, s2;
    unsigned char *a1 = slurp(v1, &s1), *a2 = slurp(bad, &s2);
    CHECK(a1 && a2 && s1 == s2 && memcmp(a1, a2, (size_t)s1) == 0 && u32_at(a2, 8) == 1);
    free(a1);
    free(a2);
    sss_sam_free(&now);
    sss_sam_free(&r);
    unlink(path);
    unlink(bad);
    rmdir(dir);
    sss_sam_free(&s);
    sss_mesh_free(&m);
    sss_mesh_free(&ico);
    sss_mesh_free(&other);
}

/* ---- Bad input ----------------------------------------------------------------------------------- */

static void test_errors(void)
{
    sss_error err = {0};
    sss_mesh m, ico;
    CHECK(sss_mesh_sphere(1.0, 2, &m, &err) == SSS_OK);
    CHECK(sss_mesh_sphere(1.0, 1, &ico, &err) == SSS_OK);
    sss_profile p;
    sam_test_profile(10.0, &p);
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    d.samples = 4;
    d.backside = &ico;
    d.backside_triangles = 40;
    sss_sam s;
    CHECK(sss_sam_build(&m, &p, &d, &s, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT && s.links == NULL);
    CHECK(strstr(err.message, "exclude") != NULL);
    d.backside_triangles = 0;
    ico.indices[5] = ico.vertex_count;
    CHECK(sss_sam_build(&m, &p, &d, &s, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    printf("%s\n", err.message);
    CHECK(strstr(err.message, "back-side") != NULL && strstr(err.message, "out of range") != NULL);
    ico.indices[5] = 0;
    ico.positions[7] = NAN;
    CHECK(sss_sam_build(&m, &p, &d, &s, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "back-side") != NULL && strstr(err.message, "not finite") != NULL);
    ico.positions[7] = 0.0f;
    sss_mesh empty;
    memset(&empty, 0, sizeof empty);
    d.backside = &empty;
    CHECK(sss_sam_build(&m, &p, &d, &s, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    /* a back-side mesh without normals gets area-weighted ones */
    float *keep = ico.normals;
    ico.normals = NULL;
    d.backside = &ico;
    CHECK(sss_sam_build(&m, &p, &d, &s, NULL, &err) == SSS_OK);
    int unit = 0;
    for (uint32_t v = 0; v < s.back_vertex_count; v++) {
        const float *q = s.back_normals + 3 * v;
        unit += fabs(sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - 1.0) < 1e-5;
    }
    CHECK(unit == (int)ico.vertex_count);
    ico.normals = keep;
    sss_sam_free(&s);
    sss_mesh_free(&m);
    sss_mesh_free(&ico);
}

int main(void)
{
    sss_error err = {0};
    if (sss_pbd_table_build(1.33, 0.0, &sam_test_table, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    test_sphere();
    test_squares();
    test_update();
    test_files();
    test_errors();
    return CHECK_DONE();
}
