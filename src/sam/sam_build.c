/* sam/sam_build.c — building a Spatial Adjacency Map (seed 001, sections 3.2-3.3 and 4.2): for every
 * vertex v_o the n back-side vertices (Eq. 13-14) with the largest Monte Carlo form factors K_oi
 * (Eq. 11), with K' of Eq. 15.
 *
 * The search is exact best-first branch and bound over a bounding-volume tree of the vertices (the
 * paper uses an R-tree to skip vertices too far away to contribute, section 4.2). Every form factor
 * is bounded above by F'_i R(d_min): the Monte Carlo estimate averages R_d over pairs of points of the
 * two reduced fans, and every such pair is at least |v_i - v_o| - rad_o - rad_i apart (rad: the
 * largest distance from a vertex to its reduced fan), so with R the profile table's upper envelope
 * (sss_sam_profile_table_bound) no estimate exceeds the bound. A node bounds its vertices by its
 * largest fan area and the distance from v_o to its box less rad_o and its largest rad. Nodes are
 * visited by decreasing bound and the search stops when the best remaining bound cannot beat the
 * n-th best form factor found, so the result equals the brute-force search (checked in the tests) while
 * most of the mesh is never visited. Form factors are ranked by the sum of their three channels. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "sam/sam_internal.h"

#define LEAF_SIZE 12

typedef struct node {
    float lo[3], hi[3];   /* positions */
    float nlo[3], nhi[3]; /* normal components */
    float max_area, max_rad;
    uint32_t first, count; /* leaf: range of the ordered vertices; inner: count = 0, first = left child */
    uint32_t right;
} node;

typedef struct tree {
    node *nodes;
    uint32_t node_count, capacity;
    uint32_t *order; /* vertex ids in leaf order */
} tree;

typedef struct build_ctx {
    const sss_mesh *mesh;
    const sss_sam_profile_table *table;
    const float *area, *rad;
    const float *src; /* S source samples per vertex (3 floats each) */
    const double *shift;
    uint32_t samples, n;
    tree t;
} build_ctx;

/* ---- Tree --------------------------------------------------------------------------------------- */

static void node_bounds(const build_ctx *b, node *nd, const uint32_t *ids, uint32_t count)
{
    for (int k = 0; k < 3; k++) {
        nd->lo[k] = nd->nlo[k] = INFINITY;
        nd->hi[k] = nd->nhi[k] = -INFINITY;
    }
    nd->max_area = nd->max_rad = 0.0f;
    for (uint32_t i = 0; i < count; i++) {
        uint32_t v = ids[i];
        const float *p = b->mesh->positions + 3 * (size_t)v, *q = b->mesh->normals + 3 * (size_t)v;
        for (int k = 0; k < 3; k++) {
            if (p[k] < nd->lo[k]) nd->lo[k] = p[k];
            if (p[k] > nd->hi[k]) nd->hi[k] = p[k];
            if (q[k] < nd->nlo[k]) nd->nlo[k] = q[k];
            if (q[k] > nd->nhi[k]) nd->nhi[k] = q[k];
        }
        if (b->area[v] > nd->max_area) nd->max_area = b->area[v];
        if (b->rad[v] > nd->max_rad) nd->max_rad = b->rad[v];
    }
}

/* Quickselect (Lomuto, middle pivot) so that ids[count / 2] is the median along axis, smaller
 * coordinates before it and larger after. */
static void select_median(const float *pos, uint32_t *ids, uint32_t count, int axis)
{
    int64_t lo = 0, hi = (int64_t)count - 1, k = count / 2;
    while (lo < hi) {
        int64_t mid = lo + (hi - lo) / 2;
        uint32_t t = ids[mid];
        ids[mid] = ids[hi];
        ids[hi] = t;
        float pivot = pos[3 * (size_t)ids[hi] + axis];
        int64_t store = lo;
        for (int64_t i = lo; i < hi; i++)
            if (pos[3 * (size_t)ids[i] + axis] < pivot) {
                t = ids[i];
                ids[i] = ids[store];
                ids[store] = t;
                store++;
            }
        t = ids[store];
        ids[store] = ids[hi];
        ids[hi] = t;
        if (store == k) return;
        if (store < k) lo = store + 1;
        else hi = store - 1;
    }
}

static uint32_t tree_build_rec(build_ctx *b, uint32_t first, uint32_t count)
{
    uint32_t id = b->t.node_count++;
    node *nd = &b->t.nodes[id];
    node_bounds(b, nd, b->t.order + first, count);
    nd->first = first;
    nd->count = count;
    nd->right = 0;
    if (count <= LEAF_SIZE) return id;
    int axis = 0;
    float ext = nd->hi[0] - nd->lo[0];
    for (int k = 1; k < 3; k++)
        if (nd->hi[k] - nd->lo[k] > ext) {
            ext = nd->hi[k] - nd->lo[k];
            axis = k;
        }
    select_median(b->mesh->positions, b->t.order + first, count, axis);
    uint32_t half = count / 2;
    uint32_t left = tree_build_rec(b, first, half);
    uint32_t right = tree_build_rec(b, first + half, count - half);
    nd = &b->t.nodes[id]; /* (the array does not move: capacity is reserved up front) */
    nd->count = 0;
    nd->first = left;
    nd->right = right;
    return id;
}

/* ---- Form factors ----------------------------------------------------------------------------- */

/* Eq. 11 by the 4D Kronecker points: receiver samples recv (of v_o), source samples of v_i. */
static void form_factor(const build_ctx *b, const float *recv, uint32_t vi, double out[3])
{
    const sss_sam_profile_table *t = b->table;
    const float *src = b->src + 3 * (size_t)b->samples * vi;
    double acc[3] = {0, 0, 0};
    double inv = 1.0 / t->r_max, scale = t->size - 1;
    for (uint32_t s = 0; s < b->samples; s++) {
        double dx = recv[3 * s] - src[3 * s], dy = recv[3 * s + 1] - src[3 * s + 1], dz = recv[3 * s + 2] - src[3 * s + 2];
        double r = sqrt(dx * dx + dy * dy + dz * dz);
        if (r >= t->r_max) continue;
        double x = sqrt(r * inv) * scale;
        int j = (int)x;
        if (j >= t->size - 1) j = t->size - 2;
        double f = x - j;
        const float *e = t->rgb + 3 * j;
        acc[0] += e[0] + f * (e[3] - e[0]);
        acc[1] += e[1] + f * (e[4] - e[1]);
        acc[2] += e[2] + f * (e[5] - e[2]);
    }
    double w = b->area[vi] / b->samples;
    for (int c = 0; c < 3; c++) out[c] = acc[c] * w;
}

/* ---- Search ---------------------------------------------------------------------------------- */

typedef struct cand {
    double ks; /* channel sum */
    double k[3];
    uint32_t v;
} cand;

typedef struct qitem {
    double bound;
    uint32_t node;
} qitem;

typedef struct search {
    cand *best; /* min-heap by ks, size <= n */
    uint32_t count;
    qitem *queue; /* max-heap by bound */
    size_t qcount, qcap;
    float *recv;
    uint64_t nodes, tested, ffs;
} search;

static void best_sift_down(cand *h, uint32_t n, uint32_t i)
{
    for (;;) {
        uint32_t l = 2 * i + 1, r = l + 1, m = i;
        if (l < n && h[l].ks < h[m].ks) m = l;
        if (r < n && h[r].ks < h[m].ks) m = r;
        if (m == i) return;
        cand t = h[i];
        h[i] = h[m];
        h[m] = t;
        i = m;
    }
}

static void best_offer(search *s, uint32_t n, const cand *c)
{
    if (s->count < n) {
        uint32_t i = s->count++;
        s->best[i] = *c;
        while (i > 0) {
            uint32_t p = (i - 1) / 2;
            if (s->best[p].ks <= s->best[i].ks) break;
            cand t = s->best[p];
            s->best[p] = s->best[i];
            s->best[i] = t;
            i = p;
        }
    } else if (c->ks > s->best[0].ks) {
        s->best[0] = *c;
        best_sift_down(s->best, n, 0);
    }
}

static double threshold(const search *s, uint32_t n) { return s->count < n ? 0.0 : s->best[0].ks; }

static int queue_push(search *s, double bound, uint32_t nd)
{
    if (s->qcount == s->qcap) {
        size_t cap = s->qcap ? 2 * s->qcap : 256;
        qitem *q = realloc(s->queue, cap * sizeof *q);
        if (!q) return 0;
        s->queue = q;
        s->qcap = cap;
    }
    size_t i = s->qcount++;
    s->queue[i].bound = bound;
    s->queue[i].node = nd;
    while (i > 0) {
        size_t p = (i - 1) / 2;
        if (s->queue[p].bound >= s->queue[i].bound) break;
        qitem t = s->queue[p];
        s->queue[p] = s->queue[i];
        s->queue[i] = t;
        i = p;
    }
    return 1;
}

static qitem queue_pop(search *s)
{
    qitem top = s->queue[0];
    s->queue[0] = s->queue[--s->qcount];
    size_t i = 0, n = s->qcount;
    for (;;) {
        size_t l = 2 * i + 1, r = l + 1, m = i;
        if (l < n && s->queue[l].bound > s->queue[m].bound) m = l;
        if (r < n && s->queue[r].bound > s->queue[m].bound) m = r;
        if (m == i) break;
        qitem t = s->queue[i];
        s->queue[i] = s->queue[m];
        s->queue[m] = t;
        i = m;
    }
    return top;
}

/* Upper bound of the form factors of a node's vertices for v_o, or -1 when none can be on the back
 * side (the box wholly in front of the tangent plane, or every normal facing n_o's way). */
static double node_bound(const build_ctx *b, const node *nd, const float *xo, const float *no, double rad_o)
{
    double plane = 0.0, facing = 0.0, d2 = 0.0;
    for (int k = 0; k < 3; k++) {
        plane += (no[k] > 0.0f ? nd->lo[k] : nd->hi[k]) * (double)no[k] - (double)xo[k] * no[k];
        facing += fmin((double)no[k] * nd->nlo[k], (double)no[k] * nd->nhi[k]);
        double e = xo[k] < nd->lo[k] ? nd->lo[k] - xo[k] : xo[k] > nd->hi[k] ? xo[k] - nd->hi[k] : 0.0;
        d2 += e * e;
    }
    if (plane >= 0.0 || facing >= 0.0) return -1.0;
    double d = sqrt(d2) - rad_o - nd->max_rad;
    return nd->max_area * sss_sam_profile_table_bound(b->table, d);
}

static void test_vertex(const build_ctx *b, search *s, uint32_t vo, uint32_t vi, double rad_o)
{
    const float *xo = b->mesh->positions + 3 * (size_t)vo, *no = b->mesh->normals + 3 * (size_t)vo;
    const float *xi = b->mesh->positions + 3 * (size_t)vi, *ni = b->mesh->normals + 3 * (size_t)vi;
    s->tested++;
    if (vi == vo || !(b->area[vi] > 0.0f) || !sss_sam_is_back(xo, no, xi, ni)) return;
    double thr = threshold(s, b->n);
    if (thr > 0.0) {
        double dx = xi[0] - xo[0], dy = xi[1] - xo[1], dz = xi[2] - xo[2];
        double d = sqrt(dx * dx + dy * dy + dz * dz) - rad_o - b->rad[vi];
        if (b->area[vi] * sss_sam_profile_table_bound(b->table, d) <= thr) return;
    }
    cand c;
    form_factor(b, s->recv, vi, c.k);
    s->ffs++;
    c.ks = c.k[0] + c.k[1] + c.k[2];
    c.v = vi;
    if (c.ks > 0.0) best_offer(s, b->n, &c);
}

static int search_vertex(const build_ctx *b, search *s, uint32_t vo, int brute)
{
    const float *xo = b->mesh->positions + 3 * (size_t)vo, *no = b->mesh->normals + 3 * (size_t)vo;
    double rad_o = b->rad[vo];
    s->count = 0;
    s->qcount = 0;
    if (brute) {
        for (uint32_t v = 0; v < b->mesh->vertex_count; v++) test_vertex(b, s, vo, v, rad_o);
        return 1;
    }
    if (b->t.node_count == 0) return 1;
    double rb = node_bound(b, &b->t.nodes[0], xo, no, rad_o);
    if (rb > 0.0 && !queue_push(s, rb, 0)) return 0;
    while (s->qcount > 0) {
        qitem it = queue_pop(s);
        if (it.bound <= threshold(s, b->n)) break;
        s->nodes++;
        const node *nd = &b->t.nodes[it.node];
        if (nd->count > 0) {
            for (uint32_t k = 0; k < nd->count; k++) test_vertex(b, s, vo, b->t.order[nd->first + k], rad_o);
            continue;
        }
        uint32_t kids[2] = {nd->first, nd->right};
        for (int c = 0; c < 2; c++) {
            double bd = node_bound(b, &b->t.nodes[kids[c]], xo, no, rad_o);
            if (bd > threshold(s, b->n) && !queue_push(s, bd, kids[c])) return 0;
        }
    }
    return 1;
}

static int cmp_cand_desc(const void *a, const void *b)
{
    const cand *x = a, *y = b;
    if (x->ks != y->ks) return x->ks < y->ks ? 1 : -1;
    return x->v > y->v ? 1 : x->v < y->v ? -1 : 0;
}

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
    if ((uint64_t)mesh->vertex_count * d.samples * 12u > ((uint64_t)1 << 36))
        return sss_error_set(err, SSS_ERROR_LIMIT, "sam: %u vertices x %u samples exceed the memory budget",
                             mesh->vertex_count, d.samples);

    sss_sam_profile_table table;
    sss_result res = sss_sam_profile_table_build(profile, d.energy, 0, &table, err);
    if (res != SSS_OK) return res;
    sam_incidence inc;
    res = sam_incidence_build(mesh, &inc, err);
    if (res != SSS_OK) {
        sss_sam_profile_table_free(&table);
        return res;
    }
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

    uint32_t nv = mesh->vertex_count, S = d.samples, max_deg = 0;
    for (uint32_t v = 0; v < nv; v++)
        if (inc.offsets[v + 1] - inc.offsets[v] > max_deg) max_deg = inc.offsets[v + 1] - inc.offsets[v];
    float *rad = malloc(sizeof(float) * nv);
    float *src = malloc(sizeof(float) * 3 * (size_t)S * nv);
    build_ctx b;
    memset(&b, 0, sizeof b);
    b.t.nodes = malloc(sizeof(node) * (2 * (size_t)nv + 1));
    b.t.order = malloc(sizeof(uint32_t) * nv);
    if (res == SSS_OK && (!rad || !src || !b.t.nodes || !b.t.order))
        res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (%u vertices)", nv);
    if (res == SSS_OK) {
        sss_sam_fan_areas(mesh, out->fan_area);
        b.mesh = mesh;
        b.table = &table;
        b.area = out->fan_area;
        b.rad = rad;
        b.src = src;
        b.samples = S;
        b.n = d.n;
        int failed = 0;
        int threads = d.threads > 0 ? d.threads : omp_get_max_threads();
        /* per vertex: fan radius and its source samples (Kronecker dimensions 2, 3) */
#pragma omp parallel num_threads(threads) reduction(| : failed)
        {
            float *tris = malloc(sizeof(float) * 18 * ((size_t)max_deg + 1));
            double *cdf = malloc(sizeof(double) * 2 * ((size_t)max_deg + 1));
            if (!tris || !cdf) failed = 1;
#pragma omp for schedule(static)
            for (int64_t v = 0; v < (int64_t)nv; v++) {
                if (failed) continue;
                size_t nt = sam_reduced_fan_inc(mesh, &inc, (uint32_t)v, tris, SIZE_MAX);
                const float *p = mesh->positions + 3 * v;
                double r2 = 0.0;
                for (size_t i = 0; i < 9 * nt; i += 3) {
                    double dx = tris[i] - p[0], dy = tris[i + 1] - p[1], dz = tris[i + 2] - p[2];
                    double q = dx * dx + dy * dy + dz * dz;
                    if (q > r2) r2 = q;
                }
                rad[v] = (float)(sqrt(r2) * (1.0 + 1e-6)); /* rounded up: a bound */
                fan_samples(mesh, &inc, (uint32_t)v, S, d.seed, 2, tris, cdf, src + 3 * (size_t)S * v);
            }
            free(tris);
            free(cdf);
        }
        if (failed) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (fan samples)");
        /* the tree holds only vertices that can be linked (non-zero fan area) */
        uint32_t m = 0;
        for (uint32_t v = 0; v < nv; v++)
            if (out->fan_area[v] > 0.0f) b.t.order[m++] = v;
        if (res == SSS_OK && m > 0) tree_build_rec(&b, 0, m);

        uint64_t nodes = 0, tested = 0, ffs = 0;
        uint32_t linked = 0;
        failed = 0;
#pragma omp parallel num_threads(threads) reduction(+ : nodes, tested, ffs, linked) reduction(| : failed)
        {
            search s;
            memset(&s, 0, sizeof s);
            s.best = malloc(sizeof(cand) * d.n);
            s.recv = malloc(sizeof(float) * 3 * S);
            float *tris = malloc(sizeof(float) * 18 * ((size_t)max_deg + 1));
            double *cdf = malloc(sizeof(double) * 2 * ((size_t)max_deg + 1));
            if (!s.best || !s.recv || !tris || !cdf) failed = 1;
#pragma omp for schedule(dynamic, 16)
            for (int64_t v = 0; v < (int64_t)nv; v++) {
                if (failed || res != SSS_OK) continue;
                /* receiver samples of v (Kronecker dimensions 0, 1) */
                fan_samples(mesh, &inc, (uint32_t)v, S, d.seed, 0, tris, cdf, s.recv);
                if (!search_vertex(&b, &s, (uint32_t)v, d.brute_force)) {
                    failed = 1;
                    continue;
                }
                qsort(s.best, s.count, sizeof(cand), cmp_cand_desc);
                linked += s.count > 0;
                const float *xo = mesh->positions + 3 * v;
                for (uint32_t k = 0; k < s.count; k++) {
                    size_t slot = (size_t)v * d.n + k;
                    uint32_t vi = s.best[k].v;
                    out->links[slot] = vi;
                    const float *xi = mesh->positions + 3 * (size_t)vi;
                    double dx = xi[0] - xo[0], dy = xi[1] - xo[1], dz = xi[2] - xo[2], rd[3];
                    sss_sam_profile_table_eval(&table, sqrt(dx * dx + dy * dy + dz * dz), rd);
                    for (int c = 0; c < 3; c++) {
                        out->form_factor[3 * slot + c] = (float)s.best[k].k[c];
                        double den = out->fan_area[vi] * rd[c]; /* Eq. 15 */
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
        if (stats) {
            stats->nodes_visited = nodes;
            stats->vertices_tested = tested;
            stats->form_factors = ffs;
            stats->linked_vertices = linked;
        }
    }
    free(rad);
    free(src);
    free(b.t.nodes);
    free(b.t.order);
    sam_incidence_free(&inc);
    sss_sam_profile_table_free(&table);
    if (res != SSS_OK) {
        sss_sam_free(out);
        return res;
    }
    if (stats) stats->seconds = sss_time_seconds() - t0;
    return SSS_OK;
}
