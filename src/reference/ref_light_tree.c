/* reference/ref_light_tree.c — many point and spot lights: a hierarchy over their positions from which
 * each surface point draws a fixed number of them (ref_internal.h, "many point lights"). */
#include <stdlib.h>

#include "reference/ref_internal.h"

typedef struct light_key {
    double key;
    uint32_t light;
} light_key;

static int compare_keys(const void *a, const void *b)
{
    const light_key *x = a, *y = b;
    if (x->key != y->key) return x->key < y->key ? -1 : 1;
    return x->light < y->light ? -1 : (x->light > y->light);
}

static int is_point_light(const sss_light *s) { return s->type == SSS_LIGHT_POINT || s->type == SSS_LIGHT_SPOT; }

/* Fills node `at` over keys[0..n) (n >= 1); children go to *next and *next + 1. Median split along the
 * box's longest axis. */
static void build_node(const ref_ctx *ctx, ref_light_node *nodes, size_t at, light_key *keys, size_t n, size_t *next)
{
    ref_light_node *node = &nodes[at];
    node->power = 0.0;
    for (int c = 0; c < 3; c++) node->lo[c] = INFINITY, node->hi[c] = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        const sss_light *s = &ctx->lights[keys[i].light].src;
        for (int c = 0; c < 3; c++) {
            node->lo[c] = fminf(node->lo[c], (float)s->position[c]);
            node->hi[c] = fmaxf(node->hi[c], (float)s->position[c]);
        }
        node->power += s->intensity[0] + s->intensity[1] + s->intensity[2];
    }
    if (n == 1) {
        node->is_leaf = 1;
        node->child = keys[0].light;
        return;
    }
    int axis = 0;
    for (int c = 1; c < 3; c++)
        if (node->hi[c] - node->lo[c] > node->hi[axis] - node->lo[axis]) axis = c;
    for (size_t i = 0; i < n; i++) keys[i].key = ctx->lights[keys[i].light].src.position[axis];
    qsort(keys, n, sizeof *keys, compare_keys);
    node->is_leaf = 0;
    node->child = (uint32_t)*next;
    *next += 2;
    build_node(ctx, nodes, node->child, keys, n / 2, next);
    build_node(ctx, nodes, node->child + 1, keys + n / 2, n - n / 2, next);
}

sss_result ref_light_tree_build(ref_ctx *ctx, sss_error *err)
{
    size_t n = 0;
    for (size_t i = 0; i < ctx->light_count; i++) n += is_point_light(&ctx->lights[i].src);
    if (n <= REF_EXACT_POINT_LIGHTS) return SSS_OK;
    if (n > UINT32_MAX / 2)
        return sss_error_set(err, SSS_ERROR_LIMIT, "reference: %zu point and spot lights (at most %u)", n,
                             (unsigned)(UINT32_MAX / 2));
    light_key *keys = malloc(n * sizeof *keys);
    ref_light_node *nodes = malloc((2 * n - 1) * sizeof *nodes);
    if (!keys || !nodes) {
        free(keys);
        free(nodes);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "reference: out of memory (light tree of %zu lights)", n);
    }
    for (size_t i = 0, k = 0; i < ctx->light_count; i++)
        if (is_point_light(&ctx->lights[i].src)) keys[k++].light = (uint32_t)i;
    size_t next = 1;
    build_node(ctx, nodes, 0, keys, n, &next);
    free(keys);
    ctx->light_tree.nodes = nodes;
    ctx->light_tree.node_count = next;
    return SSS_OK;
}

void ref_light_tree_free(ref_light_tree *t)
{
    free(t->nodes);
    t->nodes = NULL;
    t->node_count = 0;
}

/* A node's importance at po: power over the squared distance to the box's centre, at least the squared
 * half-diagonal (so that a point inside or near the box does not give one child everything), and zero
 * where every corner lies on or below the plane through po (no light there can reach the surface). */
static double node_importance(const ref_light_node *node, const double po[3], const double ng[3])
{
    int above = 0;
    for (int corner = 0; corner < 8 && !above; corner++) {
        double d = 0.0;
        for (int c = 0; c < 3; c++) d += (((corner >> c) & 1 ? node->hi[c] : node->lo[c]) - po[c]) * ng[c];
        above = d > 0.0;
    }
    if (!above) return 0.0;
    double d2 = 0.0, r2 = 0.0;
    for (int c = 0; c < 3; c++) {
        double centre = 0.5 * ((double)node->lo[c] + node->hi[c]) - po[c];
        double half = 0.5 * ((double)node->hi[c] - node->lo[c]);
        d2 += centre * centre;
        r2 += half * half;
    }
    return node->power / fmax(fmax(d2, r2), 1e-300);
}

typedef struct descent {
    const ref_ctx *ctx;
    const double *po, *ng;
    double u;
    ref_light_visit add;
    void *user;
} descent;

/* The sample positions (j + u) / K, j = 0..K-1, that fall in [a, b). */
static int positions_in(double a, double b, double u)
{
    const int k = REF_TREE_LIGHT_SAMPLES;
    double first = ceil(a * k - u), end = ceil(b * k - u);
    first = fmax(first, 0.0), end = fmin(end, (double)k);
    return end > first ? (int)(end - first) : 0;
}

/* Node `at` owns [a, b) of the unit line, b - a being the probability of reaching it; its children
 * split it in proportion to their importance. A leaf drawn `draws` times adds its light with weight
 * draws / (K (b - a)): on average 1. */
static void descend(const descent *d, size_t at, double a, double b)
{
    int draws = positions_in(a, b, d->u);
    if (draws == 0) return;
    const ref_light_node *node = &d->ctx->light_tree.nodes[at];
    if (node->is_leaf) {
        d->add(d->user, &d->ctx->lights[node->child], draws / (REF_TREE_LIGHT_SAMPLES * (b - a)));
        return;
    }
    double wl = node_importance(&d->ctx->light_tree.nodes[node->child], d->po, d->ng);
    double wr = node_importance(&d->ctx->light_tree.nodes[node->child + 1], d->po, d->ng);
    if (!(wl + wr > 0.0)) return;
    double split = a + (b - a) * (wl / (wl + wr));
    if (wl > 0.0) descend(d, node->child, a, split);
    if (wr > 0.0) descend(d, node->child + 1, split, b);
}

void ref_light_tree_sample(const ref_ctx *ctx, const double po[3], const double ng[3], double u,
                           ref_light_visit add, void *user)
{
    if (!ctx->light_tree.nodes) return;
    descent d = {ctx, po, ng, u, add, user};
    descend(&d, 0, 0.0, 1.0);
}
