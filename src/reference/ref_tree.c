/* reference/ref_tree.c — a BVH over the surface samples of one object with aggregated T A and the
 * T A-weighted centroid per node, and the hierarchical sum of Jensen & Buhler 2002 (a node far
 * enough away, relative to its size and to the profile's local length, counts as one sample). */
#include <stdlib.h>

#include "reference/ref_internal.h"

static float point_coord(const void *pts, size_t i, const void *axis)
{
    return ((const ref_point *)pts)[i].p[*(const int *)axis];
}

static void swap_points(void *pts, size_t i, size_t j)
{
    ref_point *p = pts, t = p[i];
    p[i] = p[j];
    p[j] = t;
}

typedef struct build_item {
    uint32_t node, begin, end, depth;
} build_item;

sss_result ref_tree_build(ref_tree *tree, sss_error *err)
{
    free(tree->nodes);
    tree->nodes = NULL;
    tree->node_count = tree->leaf_count = 0;
    tree->depth = 0;
    size_t n = tree->point_count;
    if (n == 0) return SSS_OK;
    if (n > 0xffffffffu / 2)
        return sss_error_set(err, SSS_ERROR_LIMIT, "reference: too many surface samples (%zu)", n);
    /* Median splits of more than REF_LEAF_SIZE points give leaves of at least REF_LEAF_SIZE / 2. */
    size_t cap = 2 * (n / (REF_LEAF_SIZE / 2) + 2);
    ref_node *nodes = calloc(cap, sizeof *nodes);
    float *box = malloc(sizeof(float) * 6 * cap);
    build_item *stack = malloc(sizeof(build_item) * (2 * REF_TREE_MAX_DEPTH + 4));
    if (!nodes || !box || !stack) {
        free(nodes);
        free(box);
        free(stack);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (tree of %zu samples)", n);
    }
    size_t count = 1, top = 0;
    stack[top++] = (build_item){0, 0, (uint32_t)n, 1};
    uint32_t depth = 0;
    while (top > 0) {
        build_item it = stack[--top];
        if (it.depth > depth) depth = it.depth;
        float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (uint32_t i = it.begin; i < it.end; i++)
            for (int a = 0; a < 3; a++) {
                float v = tree->points[i].p[a];
                if (v < lo[a]) lo[a] = v;
                if (v > hi[a]) hi[a] = v;
            }
        memcpy(box + 6 * it.node, lo, sizeof lo);
        memcpy(box + 6 * it.node + 3, hi, sizeof hi);
        int axis = 0;
        for (int a = 1; a < 3; a++)
            if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
        uint32_t size = it.end - it.begin;
        ref_node *nd = &nodes[it.node];
        if (size <= REF_LEAF_SIZE || it.depth >= REF_TREE_MAX_DEPTH || !(hi[axis] > lo[axis]) ||
            count + 2 > cap) {
            nd->first = it.begin;
            nd->count = size;
            continue;
        }
        uint32_t mid = it.begin + size / 2;
        ref_select_kth(tree->points + it.begin, size, mid - it.begin, &axis, point_coord, swap_points);
        uint32_t child = (uint32_t)count;
        count += 2;
        nd->first = child;
        nd->count = 0;
        stack[top++] = (build_item){child + 1, mid, it.end, it.depth + 1};
        stack[top++] = (build_item){child, it.begin, mid, it.depth + 1};
    }
    free(stack);
    /* Aggregates bottom-up: children always have larger indices than their parent. */
    size_t leaves = 0;
    for (size_t k = count; k-- > 0;) {
        ref_node *nd = &nodes[k];
        double ta[3] = {0, 0, 0}, cw[3] = {0, 0, 0}, cu[3] = {0, 0, 0}, wsum = 0.0;
        size_t m = 0;
        if (nd->count > 0) {
            leaves++;
            for (uint32_t i = nd->first; i < nd->first + nd->count; i++) {
                const ref_point *p = &tree->points[i];
                double w = (double)p->ta[0] + p->ta[1] + p->ta[2];
                for (int c = 0; c < 3; c++) {
                    ta[c] += p->ta[c];
                    cw[c] += w * p->p[c];
                    cu[c] += p->p[c];
                }
                wsum += w;
                m++;
            }
        } else {
            float *lo = box + 6 * k, *hi = lo + 3;
            for (int j = 0; j < 2; j++) {
                const ref_node *ch = &nodes[nd->first + j];
                const float *clo = box + 6 * (nd->first + j), *chi = clo + 3;
                double w = (double)ch->ta[0] + ch->ta[1] + ch->ta[2];
                for (int c = 0; c < 3; c++) {
                    ta[c] += ch->ta[c];
                    cw[c] += w * ch->centroid[c];
                    cu[c] += ch->center[c];
                    lo[c] = j == 0 ? clo[c] : fminf(lo[c], clo[c]);
                    hi[c] = j == 0 ? chi[c] : fmaxf(hi[c], chi[c]);
                }
                wsum += w;
                m++;
            }
        }
        const float *lo = box + 6 * k, *hi = lo + 3;
        double diag2 = 0.0;
        for (int c = 0; c < 3; c++) {
            nd->center[c] = 0.5f * (lo[c] + hi[c]);
            diag2 += (double)(hi[c] - lo[c]) * (hi[c] - lo[c]);
            nd->ta[c] = (float)ta[c];
            nd->centroid[c] = (float)(wsum > 0.0 ? cw[c] / wsum : cu[c] / (double)m);
        }
        /* Half diagonal, padded by float rounding so that every point lies inside the sphere. */
        nd->radius = (float)(0.5 * sqrt(diag2)) * (1.0f + 1e-6f);
    }
    free(box);
    tree->nodes = nodes;
    tree->node_count = count;
    tree->leaf_count = leaves;
    tree->depth = depth;
    return SSS_OK;
}

void ref_tree_free(ref_tree *tree)
{
    if (!tree) return;
    free(tree->points);
    free(tree->nodes);
    memset(tree, 0, sizeof *tree);
}

static inline float dist3(const float a[3], const float b[3])
{
    float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrtf(dx * dx + dy * dy + dz * dz);
}

void ref_tree_sum(const ref_tree *tree, const ref_profile *prof, const float xo[3], const float abs_tol[3],
                  double out[3], uint64_t *visits)
{
    ref_tree_sum_angle(tree, prof, xo, abs_tol, REF_TREE_ANGLE, out, visits);
}

void ref_tree_sum_angle(const ref_tree *tree, const ref_profile *prof, const float xo[3], const float abs_tol[3],
                        float angle, double out[3], uint64_t *visits)
{
    double acc[3] = {0, 0, 0};
    uint64_t v = 0;
    if (tree->node_count > 0) {
        uint32_t stack[2 * REF_TREE_MAX_DEPTH + 4];
        size_t top = 0;
        stack[top++] = 0;
        const float r0 = prof->r0, r_cut = prof->r_cut;
        while (top > 0) {
            const ref_node *nd = &tree->nodes[stack[--top]];
            v++;
            if (!(nd->ta[0] + nd->ta[1] + nd->ta[2] > 0.0f)) continue; /* unlit: contributes nothing */
            float d = dist3(xo, nd->center);
            float dmin = d - nd->radius;
            if (dmin >= r_cut) continue; /* beyond the profile's support */
            float s[3];
            if (d + nd->radius <= r0) {
                /* Wholly inside R0, where S_far is the constant S_r(R0). */
                ref_profile_lookup(prof, r0, s, NULL);
                for (int c = 0; c < 3; c++) acc[c] += (double)nd->ta[c] * s[c];
                continue;
            }
            if (nd->count > 0) {
                for (uint32_t i = nd->first; i < nd->first + nd->count; i++) {
                    const ref_point *p = &tree->points[i];
                    ref_profile_lookup(prof, dist3(xo, p->p), s, NULL);
                    for (int c = 0; c < 3; c++) acc[c] += (double)p->ta[c] * s[c];
                }
                v += nd->count;
                continue;
            }
            float size = 2.0f * nd->radius;
            if (dmin > 0.0f && size <= angle * dmin) {
                float len;
                ref_profile_lookup(prof, dmin, s, &len);
                /* Relative: the monopole error (size / l)^2 / 40 is small against the node itself;
                 * or absolute: that error is negligible against the object's lit level. */
                int ok = size <= REF_TREE_PROFILE * len;
                if (!ok && abs_tol) {
                    float k = size * size / (40.0f * len * len);
                    ok = nd->ta[0] * s[0] * k <= abs_tol[0] && nd->ta[1] * s[1] * k <= abs_tol[1] &&
                         nd->ta[2] * s[2] * k <= abs_tol[2];
                }
                if (ok) {
                    /* Seen from x_o the node is one sample at its T A-weighted centroid. */
                    ref_profile_lookup(prof, dist3(xo, nd->centroid), s, NULL);
                    for (int c = 0; c < 3; c++) acc[c] += (double)nd->ta[c] * s[c];
                    continue;
                }
            }
            stack[top++] = nd->first + 1;
            stack[top++] = nd->first;
        }
    }
    out[0] = acc[0], out[1] = acc[1], out[2] = acc[2];
    if (visits) *visits += v;
}

void ref_brute_sum(const ref_tree *tree, const ref_profile *prof, const float xo[3], double out[3],
                   uint64_t *visits)
{
    double acc[3] = {0, 0, 0};
    for (size_t i = 0; i < tree->point_count; i++) {
        const ref_point *p = &tree->points[i];
        float s[3];
        ref_profile_lookup(prof, dist3(xo, p->p), s, NULL);
        for (int c = 0; c < 3; c++) acc[c] += (double)p->ta[c] * s[c];
    }
    out[0] = acc[0], out[1] = acc[1], out[2] = acc[2];
    if (visits) *visits += tree->point_count;
}
