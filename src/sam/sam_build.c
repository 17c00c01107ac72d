/* sam/sam_build.c — building a Spatial Adjacency Map (Maisch & Ropinski 2017, sections 3.2-3.3 and 4.2): for every
 * vertex v_o the n back-side vertices (Eq. 13-14) with the largest Monte Carlo form factors K_oi
 * (Eq. 11), with K' of Eq. 15. The sources are the mesh's own vertices or those of a lower-tessellation
 * back-side mesh (section 4.4 and the appendix: larger fans, so n links cover more of the back side).
 * The search itself is in sam_search.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "sam/sam_internal.h"

/* ---- Samples ------------------------------------------------------------------------------------ */

static void vertex_shift(uint64_t seed, uint32_t v, double shift[4])
{
    uint64_t st = seed ^ (0x632BE59BD9B4E019ull * ((uint64_t)v + 1));
    for (int k = 0; k < 4; k++) shift[k] = sam_unit(&st);
}

/* Fills S samples of v's reduced fan with the Kronecker coordinates (dim, dim + 1) and v's shift. */
static void fan_samples(const sss_mesh *mesh, const sam_incidence *inc, uint32_t v, uint32_t samples, uint64_t seed,
                        int dim, float *tris, double *cdf, float *out)
{
    size_t nt = sam_reduced_fan_inc(mesh, inc, v, tris, SIZE_MAX);
    sam_region reg;
    sam_region_init(&reg, tris, nt, cdf);
    double shift[4], u[4], p[3];
    vertex_shift(seed, v, shift);
    for (uint32_t s = 0; s < samples; s++) {
        if (nt == 0 || !(reg.area > 0.0)) {
            memcpy(out + 3 * (size_t)s, mesh->positions + 3 * (size_t)v, 3 * sizeof(float));
            continue;
        }
        sam_kronecker(s, shift, u);
        sam_region_sample(&reg, u[dim], u[dim + 1], p);
        for (int k = 0; k < 3; k++) out[3 * (size_t)s + k] = (float)p[k];
    }
}

/* ---- Build ---------------------------------------------------------------------------------------- */

uint64_t sss_sam_mesh_hash(const sss_mesh *mesh)
{
    uint64_t h = 0xcbf29ce484222325ull;
#define FNV_BYTE(b) (h = (h ^ (uint8_t)(b)) * 0x100000001b3ull)
    uint32_t counts[2] = {mesh->vertex_count, mesh->triangle_count};
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 4; k++) FNV_BYTE(counts[i] >> (8 * k));
    for (size_t i = 0; i < 3 * (size_t)mesh->vertex_count; i++) {
        uint32_t u;
        memcpy(&u, &mesh->positions[i], 4);
        for (int k = 0; k < 4; k++) FNV_BYTE(u >> (8 * k));
    }
    for (size_t i = 0; i < 3 * (size_t)mesh->triangle_count; i++)
        for (int k = 0; k < 4; k++) FNV_BYTE(mesh->indices[i] >> (8 * k));
#undef FNV_BYTE
    return h;
}

void sss_sam_free(sss_sam *sam)
{
    if (!sam) return;
    free(sam->fan_area);
    free(sam->links);
    free(sam->form_factor);
    free(sam->kprime);
    free(sam->back_positions);
    free(sam->back_normals);
    free(sam->back_uvs);
    free(sam->back_fan_area);
    free(sam->back_indices);
    memset(sam, 0, sizeof *sam);
}

static sss_result alloc_sam(sss_sam *out, sss_error *err)
{
    size_t nv = out->vertex_count, slots = nv * out->n;
    out->fan_area = malloc(sizeof(float) * (nv ? nv : 1));
    out->links = malloc(sizeof(uint32_t) * (slots ? slots : 1));
    out->form_factor = calloc(3 * slots + 1, sizeof(float));
    out->kprime = calloc(3 * slots + 1, sizeof(float));
    if (!out->fan_area || !out->links || !out->form_factor || !out->kprime)
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (%zu vertices x %u links)", nv, out->n);
    for (size_t i = 0; i < slots; i++) out->links[i] = SSS_SAM_NONE;
    return SSS_OK;
}

/* Per vertex of `mesh`: the radius of its reduced fan (rounded up: a bound) and, when `samples` is
 * given, S points of the fan (Kronecker dimensions 2, 3: the source side of Eq. 11). 0 on out of
 * memory. */
static int prepare_fans(const sss_mesh *mesh, const sam_incidence *inc, uint32_t max_deg, uint32_t S, uint64_t seed,
                        int threads, float *rad, float *samples)
{
    int failed = 0;
#pragma omp parallel num_threads(threads) reduction(| : failed)
    {
        float *tris = malloc(sizeof(float) * 18 * ((size_t)max_deg + 1));
        double *cdf = malloc(sizeof(double) * 2 * ((size_t)max_deg + 1));
        if (!tris || !cdf) failed = 1;
#pragma omp for schedule(static)
        for (int64_t v = 0; v < (int64_t)mesh->vertex_count; v++) {
            if (failed) continue;
            size_t nt = sam_reduced_fan_inc(mesh, inc, (uint32_t)v, tris, SIZE_MAX);
            const float *p = mesh->positions + 3 * v;
            double r2 = 0.0;
            for (size_t i = 0; i < 9 * nt; i += 3) {
                double dx = tris[i] - p[0], dy = tris[i + 1] - p[1], dz = tris[i + 2] - p[2];
                double q = dx * dx + dy * dy + dz * dz;
                if (q > r2) r2 = q;
            }
            rad[v] = (float)(sqrt(r2) * (1.0 + 1e-6));
            if (samples) fan_samples(mesh, inc, (uint32_t)v, S, seed, 2, tris, cdf, samples + 3 * (size_t)S * v);
        }
        free(tris);
        free(cdf);
    }
    return !failed;
}

static uint32_t max_degree(const sss_mesh *mesh, const sam_incidence *inc)
{
    uint32_t m = 0;
    for (uint32_t v = 0; v < mesh->vertex_count; v++)
        if (inc->offsets[v + 1] - inc->offsets[v] > m) m = inc->offsets[v + 1] - inc->offsets[v];
    return m;
}

sss_result sss_sam_build(const sss_mesh *mesh, const sss_profile *profile, const sss_sam_desc *desc_in, sss_sam *out,
                         sss_sam_stats *stats, sss_error *err)
{
    double t0 = sss_time_seconds();
    if (out) memset(out, 0, sizeof *out);
    if (stats) memset(stats, 0, sizeof *stats);
    if (!mesh || !profile || !out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: no mesh, profile or output");
    if (!mesh->normals || !mesh->positions || mesh->vertex_count == 0 || mesh->triangle_count == 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: the mesh is empty or has no normals");
    sss_sam_desc d;
    memset(&d, 0, sizeof d);
    if (desc_in) d = *desc_in;
    if (d.n == 0) d.n = 3;
    if (d.samples == 0) d.samples = 64;
    if (d.n > SSS_SAM_MAX_N) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: n = %u outside 1..%d", d.n, SSS_SAM_MAX_N);
    if (d.samples > SSS_SAM_MAX_SAMPLES)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: %u samples outside 1..%d", d.samples,
                             SSS_SAM_MAX_SAMPLES);
    for (size_t i = 0; i < 3 * (size_t)mesh->vertex_count; i++)
        if (!isfinite(mesh->positions[i]) || !isfinite(mesh->normals[i]))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: vertex %zu is not finite", i / 3);
    sss_mesh back;
    sss_result res = sam_back_prepare(mesh, &d, &back, err);
    if (res != SSS_OK) return res;
    /* the sources of Eq. 11: the back-side mesh's vertices when there is one, else the mesh's own */
    const sss_mesh *src_mesh = back.vertex_count ? &back : mesh;
    int same = src_mesh == mesh;
    uint64_t sample_vertices = same ? mesh->vertex_count : back.vertex_count;
    if (sample_vertices * d.samples * 12u > ((uint64_t)1 << 36)) {
        sss_mesh_free(&back);
        return sss_error_set(err, SSS_ERROR_LIMIT, "sam: %llu vertices x %u samples exceed the memory budget",
                             (unsigned long long)sample_vertices, d.samples);
    }

    sss_sam_profile_table table;
    res = sss_sam_profile_table_build(profile, d.energy, 0, &table, err);
    if (res != SSS_OK) {
        sss_mesh_free(&back);
        return res;
    }
    sam_incidence inc, inc_src;
    memset(&inc_src, 0, sizeof inc_src);
    res = sam_incidence_build(mesh, &inc, err);
    if (res == SSS_OK && !same) res = sam_incidence_build(src_mesh, &inc_src, err);
    if (res != SSS_OK) {
        sam_incidence_free(&inc);
        sss_sam_profile_table_free(&table);
        sss_mesh_free(&back);
        return res;
    }
    const sam_incidence *isrc = same ? &inc : &inc_src;
    out->vertex_count = mesh->vertex_count;
    out->triangle_count = mesh->triangle_count;
    out->n = d.n;
    out->samples = d.samples;
    out->seed = d.seed;
    out->model = profile->model;
    out->material = profile->material;
    out->energy = d.energy == 0.0 ? 0.9999 : d.energy;
    out->mesh_hash = sss_sam_mesh_hash(mesh);
    for (int i = 0; i < 16; i++) out->transform[i] = d.transform ? d.transform[i] : (i % 5 == 0 ? 1.0 : 0.0);
    res = alloc_sam(out, err);

    uint32_t nv = mesh->vertex_count, ns = src_mesh->vertex_count, S = d.samples;
    uint32_t deg_recv = max_degree(mesh, &inc), deg_src = max_degree(src_mesh, isrc);
    float *rad = malloc(sizeof(float) * ns);
    float *rad_recv = same ? rad : malloc(sizeof(float) * nv);
    float *src_area = same ? out->fan_area : malloc(sizeof(float) * ns);
    float *src = malloc(sizeof(float) * 3 * (size_t)S * ns);
    sam_build_ctx b;
    memset(&b, 0, sizeof b);
    b.t.nodes = malloc(sizeof(sam_node) * (2 * (size_t)ns + 1));
    b.t.order = malloc(sizeof(uint32_t) * ns);
    if (res == SSS_OK && (!rad || !rad_recv || !src_area || !src || !b.t.nodes || !b.t.order))
        res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (%u vertices)", nv);
    if (res == SSS_OK) {
        sss_sam_fan_areas(mesh, out->fan_area);
        if (!same) sss_sam_fan_areas(src_mesh, src_area); /* Eq. 16 on the back-side mesh */
        b.recv = mesh;
        b.src = src_mesh;
        b.same = same;
        b.table = &table;
        b.area = src_area;
        b.rad = rad;
        b.rad_recv = rad_recv;
        b.src_samples = src;
        b.samples = S;
        b.n = d.n;
        int threads = d.threads > 0 ? d.threads : omp_get_max_threads();
        /* per source vertex: fan radius and its samples; per receiver (a separate mesh): fan radius */
        int ok = prepare_fans(src_mesh, isrc, deg_src, S, d.seed, threads, rad, src);
        if (ok && !same) ok = prepare_fans(mesh, &inc, deg_recv, S, d.seed, threads, rad_recv, NULL);
        if (!ok) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (fan samples)");
        /* the tree holds only vertices that can be linked (non-zero fan area) */
        uint32_t m = 0;
        for (uint32_t v = 0; v < ns; v++)
            if (src_area[v] > 0.0f) b.t.order[m++] = v;
        if (res == SSS_OK && m > 0) sam_tree_build(&b, 0, m);

        uint64_t nodes = 0, tested = 0, ffs = 0;
        uint32_t linked = 0;
        int failed = 0;
#pragma omp parallel num_threads(threads) reduction(+ : nodes, tested, ffs, linked) reduction(| : failed)
        {
            sam_search s;
            memset(&s, 0, sizeof s);
            s.best = malloc(sizeof(sam_cand) * d.n);
            s.recv = malloc(sizeof(float) * 3 * S);
            float *tris = malloc(sizeof(float) * 18 * ((size_t)deg_recv + 1));
            double *cdf = malloc(sizeof(double) * 2 * ((size_t)deg_recv + 1));
            if (!s.best || !s.recv || !tris || !cdf) failed = 1;
#pragma omp for schedule(dynamic, 16)
            for (int64_t v = 0; v < (int64_t)nv; v++) {
                if (failed || res != SSS_OK) continue;
                /* receiver samples of v (Kronecker dimensions 0, 1) */
                fan_samples(mesh, &inc, (uint32_t)v, S, d.seed, 0, tris, cdf, s.recv);
                if (!sam_search_vertex(&b, &s, (uint32_t)v, d.brute_force)) {
                    failed = 1;
                    continue;
                }
                qsort(s.best, s.count, sizeof(sam_cand), sam_cmp_cand_desc);
                linked += s.count > 0;
                const float *xo = mesh->positions + 3 * v;
                for (uint32_t k = 0; k < s.count; k++) {
                    size_t slot = (size_t)v * d.n + k;
                    uint32_t vi = s.best[k].v;
                    out->links[slot] = vi;
                    const float *xi = src_mesh->positions + 3 * (size_t)vi;
                    double dx = xi[0] - xo[0], dy = xi[1] - xo[1], dz = xi[2] - xo[2], rd[3];
                    sss_sam_profile_table_eval(&table, sqrt(dx * dx + dy * dy + dz * dz), rd);
                    for (int c = 0; c < 3; c++) {
                        out->form_factor[3 * slot + c] = (float)s.best[k].k[c];
                        double den = src_area[vi] * rd[c]; /* Eq. 15 */
                        out->kprime[3 * slot + c] = den > 0.0 ? (float)(s.best[k].k[c] / den) : 0.0f;
                    }
                }
            }
            nodes += s.nodes;
            tested += s.tested;
            ffs += s.ffs;
            free(s.best);
            free(s.recv);
            free(s.queue);
            free(tris);
            free(cdf);
        }
        if (failed && res == SSS_OK) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (search)");
        if (res == SSS_OK && !same) res = sam_back_store(out, &back, src_area, err);
        if (stats) {
            stats->nodes_visited = nodes;
            stats->vertices_tested = tested;
            stats->form_factors = ffs;
            stats->linked_vertices = linked;
        }
    }
    free(rad);
    if (!same) {
        free(rad_recv);
        free(src_area);
    }
    free(src);
    free(b.t.nodes);
    free(b.t.order);
    sam_incidence_free(&inc);
    sam_incidence_free(&inc_src);
    sss_sam_profile_table_free(&table);
    sss_mesh_free(&back);
    if (res != SSS_OK) {
        sss_sam_free(out);
        return res;
    }
    if (stats) stats->seconds = sss_time_seconds() - t0;
    return SSS_OK;
}
