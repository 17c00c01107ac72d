/* sam/sam_search.c — the search of Maisch & Ropinski 2017, section 4.2: for a receiving vertex v_o the n back-side
 * vertices (Eq. 13-14) with the largest Monte Carlo form factors K_oi (Eq. 11), among the vertices of
 * the source mesh: the mesh itself, or a lower-tessellation back-side mesh (section 4.4, appendix).
 *
 * The search is exact best-first branch and bound over a bounding-volume tree of the source vertices
 * (the paper uses an R-tree to skip vertices too far away to contribute, section 4.2). Every form factor
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

#include "sam/sam_internal.h"

#define LEAF_SIZE 12

/* ---- Tree --------------------------------------------------------------------------------------- */

static void node_bounds(const sam_build_ctx *b, sam_node *nd, const uint32_t *ids, uint32_t count)
{
    for (int k = 0; k < 3; k++) {
        nd->lo[k] = nd->nlo[k] = INFINITY;
        nd->hi[k] = nd->nhi[k] = -INFINITY;
    }
    nd->max_area = nd->max_rad = 0.0f;
    for (uint32_t i = 0; i < count; i++) {
        uint32_t v = ids[i];
        const float *p = b->src->positions + 3 * (size_t)v, *q = b->src->normals + 3 * (size_t)v;
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

uint32_t sam_tree_build(sam_build_ctx *b, uint32_t first, uint32_t count)
{
    uint32_t id = b->t.node_count++;
    sam_node *nd = &b->t.nodes[id];
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
    select_median(b->src->positions, b->t.order + first, count, axis);
    uint32_t half = count / 2;
    uint32_t left = sam_tree_build(b, first, half);
    uint32_t right = sam_tree_build(b, first + half, count - half);
    nd = &b->t.nodes[id]; /* (the array does not move: capacity is reserved up front) */
    nd->count = 0;
    nd->first = left;
    nd->right = right;
    return id;
}

/* ---- Form factors ----------------------------------------------------------------------------- */

/* Eq. 11 by the 4D Kronecker points: receiver samples recv (of v_o), source samples of v_i. */
static void form_factor(const sam_build_ctx *b, const float *recv, uint32_t vi, double out[3])
{
    const sss_sam_profile_table *t = b->table;
    const float *src = b->src_samples + 3 * (size_t)b->samples * vi;
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

static void best_sift_down(sam_cand *h, uint32_t n, uint32_t i)
{
    for (;;) {
        uint32_t l = 2 * i + 1, r = l + 1, m = i;
        if (l < n && h[l].ks < h[m].ks) m = l;
        if (r < n && h[r].ks < h[m].ks) m = r;
        if (m == i) return;
        sam_cand t = h[i];
        h[i] = h[m];
        h[m] = t;
        i = m;
    }
}

static void best_offer(sam_search *s, uint32_t n, const sam_cand *c)
{
    if (s->count < n) {
        uint32_t i = s->count++;
        s->best[i] = *c;
        while (i > 0) {
            uint32_t p = (i - 1) / 2;
            if (s->best[p].ks <= s->best[i].ks) break;
            sam_cand t = s->best[p];
            s->best[p] = s->best[i];
            s->best[i] = t;
            i = p;
        }
    } else if (c->ks > s->best[0].ks) {
        s->best[0] = *c;
        best_sift_down(s->best, n, 0);
    }
}

static double threshold(const sam_search *s, uint32_t n) { return s->count < n ? 0.0 : s->best[0].ks; }

static int queue_push(sam_search *s, double bound, uint32_t nd)
{
    if (s->qcount == s->qcap) {
        size_t cap = s->qcap ? 2 * s->qcap : 256;
        sam_qitem *q = realloc(s->queue, cap * sizeof *q);
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
        sam_qitem t = s->queue[p];
        s->queue[p] = s->queue[i];
        s->queue[i] = t;
        i = p;
    }
    return 1;
}

static sam_qitem queue_pop(sam_search *s)
{
    sam_qitem top = s->queue[0];
    s->queue[0] = s->queue[--s->qcount];
    size_t i = 0, n = s->qcount;
    for (;;) {
        size_t l = 2 * i + 1, r = l + 1, m = i;
        if (l < n && s->queue[l].bound > s->queue[m].bound) m = l;
        if (r < n && s->queue[r].bound > s->queue[m].bound) m = r;
        if (m == i) break;
        sam_qitem t = s->queue[i];
        s->queue[i] = s->queue[m];
        s->queue[m] = t;
        i = m;
    }
    return top;
}

/* Upper bound of the form factors of a node's vertices for v_o, or -1 when none can be on the back
 * side (the box wholly in front of the tangent plane, or every normal facing n_o's way). */
static double node_bound(const sam_build_ctx *b, const sam_node *nd, const float *xo, const float *no, double rad_o)
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

static void test_vertex(const sam_build_ctx *b, sam_search *s, uint32_t vo, uint32_t vi, double rad_o)
{
    const float *xo = b->recv->positions + 3 * (size_t)vo, *no = b->recv->normals + 3 * (size_t)vo;
    const float *xi = b->src->positions + 3 * (size_t)vi, *ni = b->src->normals + 3 * (size_t)vi;
    s->tested++;
    if ((b->same && vi == vo) || !(b->area[vi] > 0.0f) || !sss_sam_is_back(xo, no, xi, ni)) return;
    double thr = threshold(s, b->n);
    if (thr > 0.0) {
        double dx = xi[0] - xo[0], dy = xi[1] - xo[1], dz = xi[2] - xo[2];
        double d = sqrt(dx * dx + dy * dy + dz * dz) - rad_o - b->rad[vi];
        if (b->area[vi] * sss_sam_profile_table_bound(b->table, d) <= thr) return;
    }
    sam_cand c;
    form_factor(b, s->recv, vi, c.k);
    s->ffs++;
    c.ks = c.k[0] + c.k[1] + c.k[2];
    c.v = vi;
    if (c.ks > 0.0) best_offer(s, b->n, &c);
}

int sam_search_vertex(const sam_build_ctx *b, sam_search *s, uint32_t vo, int brute)
{
    const float *xo = b->recv->positions + 3 * (size_t)vo, *no = b->recv->normals + 3 * (size_t)vo;
    double rad_o = b->rad_recv[vo];
    s->count = 0;
    s->qcount = 0;
    if (brute) {
        for (uint32_t v = 0; v < b->src->vertex_count; v++) test_vertex(b, s, vo, v, rad_o);
        return 1;
    }
    if (b->t.node_count == 0) return 1;
    double rb = node_bound(b, &b->t.nodes[0], xo, no, rad_o);
    if (rb > 0.0 && !queue_push(s, rb, 0)) return 0;
    while (s->qcount > 0) {
        sam_qitem it = queue_pop(s);
        if (it.bound <= threshold(s, b->n)) break;
        s->nodes++;
        const sam_node *nd = &b->t.nodes[it.node];
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

int sam_cmp_cand_desc(const void *a, const void *b)
{
    const sam_cand *x = a, *y = b;
    if (x->ks != y->ks) return x->ks < y->ks ? 1 : -1;
    return x->v > y->v ? 1 : x->v < y->v ? -1 : 0;
}
