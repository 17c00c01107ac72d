/* sam/sam_geom.c — the geometry of Maisch & Ropinski 2017: reduced fans and their areas (Eq. 16, Fig. 2), the
 * back-side criteria (Eq. 13-14), region integrals by a 4D Kronecker sequence (Eq. 11) and the radial
 * profile table with its upper envelope. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sam/sam_internal.h"

/* ---- Profile table ------------------------------------------------------------------------------ */

sss_result sss_sam_profile_table_build(const sss_profile *profile, double energy, int size,
                                       sss_sam_profile_table *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    if (!profile) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: no profile");
    if (energy == 0.0) energy = 0.9999;
    if (!(energy > 0.0 && energy < 1.0))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: profile energy %g outside (0, 1)", energy);
    if (size == 0) size = 4096;
    if (size < 16 || size > (1 << 20))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: profile table size %d outside 16..%d", size,
                             1 << 20);
    double rm = sss_profile_reach(profile, energy);
    if (!(rm > 0.0) || !isfinite(rm))
        return sss_error_set(err, SSS_ERROR_NUMERIC, "sam: the profile has no finite radius holding %g of its energy",
                             energy);
    out->rgb = malloc(sizeof(float) * 3 * (size_t)size);
    out->env_sum = malloc(sizeof(float) * (size_t)size);
    if (!out->rgb || !out->env_sum) {
        sss_sam_profile_table_free(out);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (profile table)");
    }
    out->size = size;
    out->r_max = rm;
    for (int j = 0; j < size; j++) {
        double t = (double)j / (size - 1), r = rm * t * t, v[3];
        sss_profile_eval_rgb(profile, r, v);
        for (int c = 0; c < 3; c++) {
            if (!isfinite(v[c]) || v[c] < 0.0) {
                sss_sam_profile_table_free(out);
                return sss_error_set(err, SSS_ERROR_NUMERIC, "sam: the profile is not finite at r = %g", r);
            }
            out->rgb[3 * j + c] = (float)v[c];
        }
    }
    /* Upper envelope of the channel sum; the value between nodes j and j+1 is a linear blend of
     * the two, so max over [r_j, inf) is the max over nodes >= j. */
    float m = 0.0f;
    for (int j = size - 1; j >= 0; j--) {
        float s = out->rgb[3 * j] + out->rgb[3 * j + 1] + out->rgb[3 * j + 2];
        if (s > m) m = s;
        out->env_sum[j] = m;
    }
    return SSS_OK;
}

void sss_sam_profile_table_free(sss_sam_profile_table *t)
{
    if (!t) return;
    free(t->rgb);
    free(t->env_sum);
    memset(t, 0, sizeof *t);
}

void sss_sam_profile_table_eval(const sss_sam_profile_table *t, double r, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    if (!(r >= 0.0) || r >= t->r_max) return;
    double x = sqrt(r / t->r_max) * (t->size - 1);
    int j = (int)x;
    if (j >= t->size - 1) j = t->size - 2;
    double f = x - j;
    for (int c = 0; c < 3; c++) out[c] = (1.0 - f) * t->rgb[3 * j + c] + f * t->rgb[3 * j + 3 + c];
}

double sss_sam_profile_table_bound(const sss_sam_profile_table *t, double r)
{
    if (r <= 0.0) return t->env_sum[0];
    if (r >= t->r_max) return 0.0;
    int j = (int)(sqrt(r / t->r_max) * (t->size - 1));
    if (j > t->size - 1) j = t->size - 1;
    return t->env_sum[j];
}

/* ---- Criteria and fans ---------------------------------------------------------------------------- */

int sss_sam_is_back(const float xo[3], const float no[3], const float xi[3], const float ni[3])
{
    double plane = (xi[0] - xo[0]) * no[0] + (xi[1] - xo[1]) * no[1] + (xi[2] - xo[2]) * no[2]; /* Eq. 13 */
    double facing = ni[0] * no[0] + ni[1] * no[1] + ni[2] * no[2];                               /* Eq. 14 */
    return plane < 0.0 && facing < 0.0;
}

static double tri_area(const float *a, const float *b, const float *c)
{
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
    }
    double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2], z = e1[0] * e2[1] - e1[1] * e2[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

void sss_sam_fan_areas(const sss_mesh *mesh, float *areas)
{
    /* Eq. 16 summed per triangle: each triangle gives |cross| / 6 = area / 3 to each of its corners. */
    double *acc = calloc(mesh->vertex_count ? mesh->vertex_count : 1, sizeof *acc);
    if (!acc) {
        sss_mesh_vertex_areas(mesh, areas); /* the same quantity, in float */
        return;
    }
    for (uint32_t t = 0; t < mesh->triangle_count; t++) {
        const uint32_t *ix = mesh->indices + 3 * (size_t)t;
        double a = tri_area(mesh->positions + 3 * (size_t)ix[0], mesh->positions + 3 * (size_t)ix[1],
                            mesh->positions + 3 * (size_t)ix[2]) / 3.0;
        for (int k = 0; k < 3; k++) acc[ix[k]] += a;
    }
    for (uint32_t v = 0; v < mesh->vertex_count; v++) areas[v] = (float)acc[v];
    free(acc);
}

sss_result sam_incidence_build(const sss_mesh *mesh, sam_incidence *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    uint32_t nv = mesh->vertex_count;
    out->offsets = calloc((size_t)nv + 1, sizeof *out->offsets);
    out->tris = malloc((3 * (size_t)mesh->triangle_count + 1) * sizeof *out->tris);
    uint32_t *fill = malloc(((size_t)nv + 1) * sizeof *fill);
    if (!out->offsets || !out->tris || !fill) {
        free(fill);
        sam_incidence_free(out);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (incidence)");
    }
    for (size_t i = 0; i < 3 * (size_t)mesh->triangle_count; i++) {
        if (mesh->indices[i] >= nv) {
            free(fill);
            sam_incidence_free(out);
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: triangle %zu: index %u out of range", i / 3,
                                 mesh->indices[i]);
        }
        out->offsets[mesh->indices[i] + 1]++;
    }
    for (uint32_t v = 0; v < nv; v++) out->offsets[v + 1] += out->offsets[v];
    memcpy(fill, out->offsets, ((size_t)nv + 1) * sizeof *fill);
    for (uint32_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) out->tris[fill[mesh->indices[3 * (size_t)t + k]]++] = t;
    free(fill);
    return SSS_OK;
}

void sam_incidence_free(sam_incidence *inc)
{
    if (!inc) return;
    free(inc->offsets);
    free(inc->tris);
    memset(inc, 0, sizeof *inc);
}

/* The barycentric region of corner a of triangle (a, b, c): the quadrilateral a, mid(a, b),
 * centroid, mid(a, c), as two triangles of area A / 6 each (together a third, as Eq. 16 counts). */
static size_t corner_region(const float *a, const float *b, const float *c, float *out)
{
    float mab[3], mac[3], g[3];
    for (int k = 0; k < 3; k++) {
        mab[k] = 0.5f * (a[k] + b[k]);
        mac[k] = 0.5f * (a[k] + c[k]);
        g[k] = (a[k] + b[k] + c[k]) / 3.0f;
    }
    memcpy(out + 0, a, 3 * sizeof(float));
    memcpy(out + 3, mab, sizeof mab);
    memcpy(out + 6, g, sizeof g);
    memcpy(out + 9, a, 3 * sizeof(float));
    memcpy(out + 12, g, sizeof g);
    memcpy(out + 15, mac, sizeof mac);
    return 2;
}

size_t sam_reduced_fan_inc(const sss_mesh *mesh, const sam_incidence *inc, uint32_t v, float *tris, size_t capacity)
{
    size_t n = 0;
    for (uint32_t e = inc->offsets[v]; e < inc->offsets[v + 1]; e++) {
        const uint32_t *ix = mesh->indices + 3 * (size_t)inc->tris[e];
        int k = ix[0] == v ? 0 : ix[1] == v ? 1 : 2;
        const float *a = mesh->positions + 3 * (size_t)ix[k], *b = mesh->positions + 3 * (size_t)ix[(k + 1) % 3],
                    *c = mesh->positions + 3 * (size_t)ix[(k + 2) % 3];
        if (n + 2 <= capacity) corner_region(a, b, c, tris + 9 * n);
        n += 2;
    }
    return n;
}

size_t sss_sam_reduced_fan(const sss_mesh *mesh, uint32_t v, float *tris, size_t capacity)
{
    if (v >= mesh->vertex_count) return 0;
    size_t n = 0;
    for (uint32_t t = 0; t < mesh->triangle_count; t++) {
        const uint32_t *ix = mesh->indices + 3 * (size_t)t;
        for (int k = 0; k < 3; k++) {
            if (ix[k] != v) continue;
            if (n + 2 <= capacity)
                corner_region(mesh->positions + 3 * (size_t)ix[k], mesh->positions + 3 * (size_t)ix[(k + 1) % 3],
                              mesh->positions + 3 * (size_t)ix[(k + 2) % 3], tris + 9 * n);
            n += 2;
            break;
        }
    }
    return n;
}

/* ---- Sampling ------------------------------------------------------------------------------------ */

void sam_kronecker(uint32_t s, const double shift[4], double u[4])
{
    /* phi = 1.1673039782614187 (x^5 = x + 1); alpha_k = phi^-k */
    static const double alpha[4] = {0.8566748838545029, 0.7338918566271260, 0.6287067210378086,
                                    0.5385972572236100};
    for (int k = 0; k < 4; k++) {
        double x = shift[k] + alpha[k] * (double)s;
        u[k] = x - floor(x);
    }
}

uint64_t sam_splitmix(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double sam_unit(uint64_t *state) { return (double)(sam_splitmix(state) >> 11) * (1.0 / 9007199254740992.0); }

void sam_region_init(sam_region *r, const float *tris, size_t count, double *cdf)
{
    r->tris = tris;
    r->count = count;
    r->cdf = cdf;
    double acc = 0.0;
    for (size_t i = 0; i < count; i++) {
        acc += tri_area(tris + 9 * i, tris + 9 * i + 3, tris + 9 * i + 6);
        cdf[i] = acc;
    }
    r->area = acc;
}

void sam_region_sample(const sam_region *r, double u0, double u1, double out[3])
{
    double x = u0 * r->area;
    size_t lo = 0, hi = r->count - 1;
    while (lo < hi) { /* first triangle whose running area exceeds x */
        size_t mid = (lo + hi) / 2;
        if (r->cdf[mid] > x) hi = mid;
        else lo = mid + 1;
    }
    double prev = lo ? r->cdf[lo - 1] : 0.0, w = r->cdf[lo] - prev;
    double t = w > 0.0 ? (x - prev) / w : 0.5;
    if (t < 0.0) t = 0.0;
    if (t > 1.0) t = 1.0;
    /* uniform in the triangle: b0 = 1 - sqrt(t), b1 = u1 sqrt(t) */
    double st = sqrt(t), b0 = 1.0 - st, b1 = u1 * st, b2 = 1.0 - b0 - b1;
    const float *p = r->tris + 9 * lo;
    for (int k = 0; k < 3; k++) out[k] = b0 * p[k] + b1 * p[3 + k] + b2 * p[6 + k];
}

sss_result sss_sam_region_integral(const float *tris_a, size_t count_a, const float *tris_b, size_t count_b,
                                   uint32_t samples, uint64_t seed, sss_sam_kernel_fn kernel, void *user,
                                   double out[3], sss_error *err)
{
    out[0] = out[1] = out[2] = 0.0;
    if (!tris_a || !tris_b || !kernel || count_a == 0 || count_b == 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: region integral needs two non-empty regions");
    if (samples < 1 || samples > (1u << 24))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: %u samples outside 1..%u", samples, 1u << 24);
    double *cdf = malloc(sizeof(double) * (count_a + count_b));
    if (!cdf) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "sam: out of memory (region integral)");
    sam_region ra, rb;
    sam_region_init(&ra, tris_a, count_a, cdf);
    sam_region_init(&rb, tris_b, count_b, cdf + count_a);
    if (!(ra.area > 0.0) || !(rb.area > 0.0)) {
        free(cdf);
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sam: a region of the integral has zero area");
    }
    uint64_t st = seed;
    double shift[4];
    for (int k = 0; k < 4; k++) shift[k] = sam_unit(&st);
    double acc[3] = {0, 0, 0};
    for (uint32_t s = 0; s < samples; s++) {
        double u[4], xo[3], xi[3], k3[3];
        sam_kronecker(s, shift, u);
        sam_region_sample(&ra, u[0], u[1], xo);
        sam_region_sample(&rb, u[2], u[3], xi);
        kernel(xo, xi, user, k3);
        for (int c = 0; c < 3; c++) acc[c] += k3[c];
    }
    /* (1/|A|) int_A int_B k = |B| E[k] for x_o, x_i uniform on A and B */
    for (int c = 0; c < 3; c++) out[c] = rb.area * acc[c] / samples;
    free(cdf);
    return SSS_OK;
}
