/* kernel/cells.c — integrals of R_d(sqrt(x^2 + y^2)) over the cells of a square grid: the discretised
 * profile of the SVD (Jimenez et al. 2019, section 3) and guided (Appendix A) kernels.
 *
 * Each cell holds the integral of R_d over it, so every grid parity keeps each cell's true energy and
 * the cells sum to the integral over the square. A cell's centre value times its area is not that:
 * near r = 0 the PBD profile grows like 1/r (the dipole peaks on the scale z_r), so the cell centred on
 * the origin of an odd grid would take R_d(0) h^2 (200x its energy for Skin1 on a 25-cell grid).
 *
 *  - Rings, for the cell holding r = 0 and for cells where R_d varies within the cell (closer than 4
 *    cell widths to the origin, or wider than the profile's smooth length): R_d is radial, so the
 *    integral over a rectangle is int R_d(r) r arc(r) dr, arc(r) the angle of the circle of radius r
 *    inside it, in closed form. The radial integral runs over pieces between the radii where arc
 *    changes form, in Gauss-Legendre panels graded from the piece's start (from r = 0: from 1e-3 of
 *    the shortest length, the PBD table's first radius being 2.5e-3 mean free paths), no wider than
 *    R_d's local length, and split at the PBD table's radii (R_d r is a cubic in between, only C^1
 *    across them). The 1/r singularity becomes the bounded R_d(r) r; arc's square-root onsets are
 *    removed by substitution.
 *  - Tensor Gauss-Legendre elsewhere, 2 to 6 points per axis from the ratio of the cell width to the
 *    lengths on which R_d varies there (the distance to the origin, the decay length 1/sigma_tr,
 *    1/sigma_t near the origin, the Gaussians' widths).
 * Against the six Gaussians' closed form: 1e-7 of each cell; against brute-force quadrature for PBD
 * and the dipole: ~1e-6 of each cell near the origin and of the largest cell anywhere (the PBD knots
 * crossing tensor cells; tests/kernel/test_kernel_cells.c). Cost: ~50 profile evaluations per distinct
 * cell at grid 24, ~10 at grid 256 (the matrix's eightfold symmetry computes 1/8 of the cells). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernel/kernel_internal.h"

#define CELL_MAX_Q 6
#define CELL_RING_RATIO 0.25 /* rings for cells nearer than 4 cell widths (the PBD knots' spacing) */
#define CELL_PANEL_Q 6       /* Gauss-Legendre points per radial panel */
#define CELL_FIRST_PANEL 0.5 /* first panel of a piece: this fraction of the distance to a branch point */
#define CELL_MAX_KNOTS (3 * SSS_PBD_RADII)

typedef struct cell_ctx {
    const sss_profile *p;
    double feat;    /* kq_profile_length_scale: the finest structure near r = 0 */
    double decay;   /* kq_profile_decay_length */
    double r_zero;  /* R_d is exactly 0 beyond this radius in every channel */
    double knots[CELL_MAX_KNOTS]; /* PBD: the table's radii in scene units, all channels, ascending */
    int knot_count;
    double gl_x[CELL_MAX_Q + 1][CELL_MAX_Q], gl_w[CELL_MAX_Q + 1][CELL_MAX_Q]; /* on [0, 1] */
} cell_ctx;

static void rule01(int n, double *x, double *w)
{
    kq_gauss_legendre(n, x, w);
    for (int i = 0; i < n; i++) {
        x[i] = 0.5 * (x[i] + 1.0);
        w[i] *= 0.5;
    }
}

/* The length on which R_d varies smoothly around a point at distance d > 0 from the origin: the decay
 * length 1/sigma_tr, and 1/sigma_t within 12 mean free paths of the origin, where single scattering
 * still counts; for the six Gaussians each width sigma, or sigma^2 / d in its tail (ignored beyond
 * 8 sigma, below e^-32 of its peak). */
static double smooth_scale(const cell_ctx *c, double d)
{
    const sss_profile *p = c->p;
    double s = INFINITY;
    if (p->model == SSS_PROFILE_GAUSS6) {
        double mm = p->gauss6_mm_per_unit > 0.0 ? p->gauss6_mm_per_unit : 1.0;
        for (int i = 0; i < SSS_GAUSS6_TERMS; i++) {
            double sigma = sqrt(sss_gauss6_variance_mm2[i]) / mm;
            if (d < 8.0 * sigma) s = fmin(s, sigma * fmin(1.0, sigma / d));
        }
        return s;
    }
    s = fmin(s, c->decay);
    if (d < 12.0 * c->feat) s = fmin(s, c->feat);
    return s;
}

/* PBD and the dipole are not analytic at r = 0 (1/r; the dipole's branch points at r = +-i z_r): at
 * distance d, R_d varies on d too. The Gaussians are entire. */
static int singular_origin(const cell_ctx *c) { return c->p->model != SSS_PROFILE_GAUSS6; }

static double cell_scale(const cell_ctx *c, double d)
{
    double s = smooth_scale(c, d);
    return singular_origin(c) ? fmin(s, d) : s;
}

/* The largest cell width, in smooth lengths, that tensor Gauss-Legendre takes: the q-point rule's error
 * is h^2q f^(2q) (q!)^4 / ((2q + 1) ((2q)!)^3); for a Gaussian of width s, whose 2q-th derivative is
 * up to (2q - 1)!! / s^2q, that is below ~1e-7 of the cell for q = 2 up to h = 0.1 s, q = 3 up to
 * 0.45 s, q = 4 up to s; an exponential e^(-x / s) (PBD's and the dipole's decay) allows q = 5 up to
 * 2 s and q = 6 up to 3 s. */
static double tensor_max(const cell_ctx *c) { return c->p->model == SSS_PROFILE_GAUSS6 ? 1.0 : 3.0; }

/* Tensor Gauss-Legendre over the square [x0, x0 + h] x [y0, y0 + h] at distance d > 0 from the origin,
 * for h <= tensor_max smooth lengths and h <= d / 4, q points per axis as above; a singularity at
 * distance d converges like (h / 4 d)^(2q) (1e-7 for q = 3 at h = 0.12 d). */
static void cell_tensor(const cell_ctx *c, double x0, double y0, double h, double d, double out[3])
{
    double ts = h / smooth_scale(c, d), td = singular_origin(c) ? h / d : 0.0;
    int q = ts <= 0.1 ? 2 : ts <= 0.45 ? 3 : ts <= 1.0 ? 4 : ts <= 2.0 ? 5 : 6;
    int qd = td <= 0.04 ? 2 : td <= 0.12 ? 3 : 4;
    if (qd > q) q = qd;
    const double *gx = c->gl_x[q], *gw = c->gl_w[q];
    out[0] = out[1] = out[2] = 0.0;
    for (int i = 0; i < q; i++) {
        double x = x0 + gx[i] * h;
        for (int j = 0; j < q; j++) {
            double y = y0 + gx[j] * h, v[3], w = gw[i] * gw[j];
            sss_profile_eval_rgb(c->p, sqrt(x * x + y * y), v);
            for (int ch = 0; ch < 3; ch++) out[ch] += w * v[ch];
        }
    }
    for (int ch = 0; ch < 3; ch++) out[ch] *= h * h;
}

/* ---- Cells near the origin: rings ------------------------------------------------------------ */

/* A rectangle [a0, a1] x [b0, b1] in the closed first quadrant: R_d is radial, so its integral over
 * the rectangle is int R_d(r) r arc(r) dr with arc(r) the angle of the circle of radius r inside it,
 * in closed form: theta in [0, pi/2] with a0 <= r cos theta <= a1 and b0 <= r sin theta <= b1. */
typedef struct cell_part {
    double a0, a1, b0, b1;
} cell_part;

/* acos(p / r) and asin(p / r) for 0 <= p, r > 0, clamped, from sqrt((r - p)(r + p)) (no digits lost
 * where the circle grazes the line at distance p). */
static double acos_ratio(double p, double r) { return p >= r ? 0.0 : atan2(sqrt((r - p) * (r + p)), p); }
static double asin_ratio(double p, double r) { return p >= r ? 0.5 * KQ_PI : atan2(p, sqrt((r - p) * (r + p))); }

static double part_arc(const cell_part *q, double r)
{
    if (q->a0 >= r || q->b0 >= r) return 0.0;
    double lo = fmax(acos_ratio(q->a1, r), asin_ratio(q->b0, r));
    double hi = fmin(acos_ratio(q->a0, r), asin_ratio(q->b1, r));
    return hi > lo ? hi - lo : 0.0;
}

/* out += int R_d(r) r arc(r) dr over [lo, hi], on which arc is smooth but for a square-root onset at
 * lo > 0 (where the circle starts to cross a new edge): in u with r = lo + (hi - lo) u^2 the integrand
 * is smooth (from lo = 0, arc is constant and r = lo + (hi - lo) u). Panels in u: the first spans w0 in
 * r, the next ones double but never span more than the profile's local length in r, and none
 * straddles a knot of the PBD table (where R_d r, a cubic in between, is only C^1). */
static void part_piece(const cell_ctx *c, const cell_part *q, double lo, double hi, double w0, double out[3])
{
    const int sq = lo > 0.0;
    const double span = hi - lo;
    const double *gx = c->gl_x[CELL_PANEL_Q], *gw = c->gl_w[CELL_PANEL_Q];
    /* the first knot past lo */
    int lo_k = 0, hi_k = c->knot_count;
    while (lo_k < hi_k) {
        int mid = (lo_k + hi_k) / 2;
        if (c->knots[mid] <= lo) lo_k = mid + 1;
        else hi_k = mid;
    }
    int k = lo_k;
    double u = 0.0, du = sq ? sqrt(w0 / span) : w0 / span;
    while (u < 1.0) {
        if (u > 0.0) {
            double r = lo + span * (sq ? u * u : u), drdu = span * (sq ? 2.0 * u : 1.0);
            du = fmin(2.0 * du, cell_scale(c, r) / drdu);
        }
        double end = fmin(u + du, 1.0);
        while (k < c->knot_count && c->knots[k] <= lo + span * (sq ? u * u : u) * (1.0 + 1e-12)) k++;
        if (k < c->knot_count && c->knots[k] < hi) {
            double uk = sq ? sqrt((c->knots[k] - lo) / span) : (c->knots[k] - lo) / span;
            if (uk < end) end = uk;
        }
        if (1.0 - end < 1e-9 * du) end = 1.0;
        if (!(end > u)) { /* a knot at u after rounding: step past it */
            k++;
            continue;
        }
        double len = end - u;
        for (int i = 0; i < CELL_PANEL_Q; i++) {
            double t = u + gx[i] * len, r = lo + span * (sq ? t * t : t);
            double f = gw[i] * len * span * (sq ? 2.0 * t : 1.0) * r * part_arc(q, r), v[3];
            if (f == 0.0) continue;
            sss_profile_eval_rgb(c->p, r, v);
            for (int ch = 0; ch < 3; ch++) out[ch] += f * v[ch];
        }
        u = end;
    }
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Where R_d becomes exactly 0 in every channel: PBD past the table's last radius (PBRT's
 * CatmullRomWeights fails there), the dipole and the Gaussians where their exponentials underflow
 * (e^-746 = 0 in double); INFINITY without absorption. Cells beyond cost nothing. */
static double zero_radius(const sss_profile *p)
{
    double r = 0.0;
    for (int ch = 0; ch < 3; ch++) {
        if (p->model == SSS_PROFILE_PBD) {
            double st = p->material.sigma_a[ch] + p->material.sigma_s[ch];
            if (st > 0.0 && p->table) r = fmax(r, p->table->radius[SSS_PBD_RADII - 1] / st * (1.0 + 1e-9));
        } else if (p->model == SSS_PROFILE_DIPOLE) {
            double str = p->dipole[ch].sigma_tr;
            r = fmax(r, str > 0.0 ? 760.0 / str : INFINITY);
        }
    }
    if (p->model == SSS_PROFILE_GAUSS6) {
        double mm = p->gauss6_mm_per_unit > 0.0 && isfinite(p->gauss6_mm_per_unit) ? p->gauss6_mm_per_unit : 1.0;
        for (int i = 0; i < SSS_GAUSS6_TERMS; i++) r = fmax(r, sqrt(1520.0 * sss_gauss6_variance_mm2[i]) / mm);
    }
    return isfinite(r) ? r : INFINITY;
}

/* The integral over one first-quadrant part: pieces between the radii where arc(r) changes form
 * (the edges' distances and the corners'). */
static void part_integral(const cell_ctx *c, const cell_part *q, double out[3])
{
    double cut[10], d_min = sqrt(q->a0 * q->a0 + q->b0 * q->b0);
    double d_max = fmin(sqrt(q->a1 * q->a1 + q->b1 * q->b1), c->r_zero);
    int m = 0;
    double cand[8] = {q->a0, q->a1, q->b0, q->b1, sqrt(q->a0 * q->a0 + q->b1 * q->b1),
                      sqrt(q->a1 * q->a1 + q->b0 * q->b0), d_min, d_max};
    cut[m++] = d_min;
    for (int i = 0; i < 8; i++)
        if (cand[i] > d_min && cand[i] < d_max) cut[m++] = cand[i];
    cut[m++] = d_max;
    qsort(cut, (size_t)m, sizeof cut[0], cmp_double);
    out[0] = out[1] = out[2] = 0.0;
    if (!(d_max > d_min)) return;
    for (int i = 0; i + 1 < m; i++) {
        double lo = cut[i], hi = cut[i + 1];
        if (!(hi > lo * (1.0 + 1e-12))) continue;
        /* From r = 0 (the part touches the origin): R_d's structure down to 1e-3 of its shortest
         * length (the PBD table's first radius is 2.5e-3 mean free paths); elsewhere the local one. */
        double w0 = 1e-3 * c->feat;
        if (lo > 0.0) {
            /* arc has square-root branch points at the edges' distances; the nearest below lo limits
             * the first panel (after r = lo + w u^2 it sits at u = i sqrt((lo - p) / w)) */
            double edge[4] = {q->a0, q->a1, q->b0, q->b1}, gap = INFINITY;
            for (int e = 0; e < 4; e++)
                if (edge[e] < lo * (1.0 - 1e-12)) gap = fmin(gap, lo - edge[e]);
            w0 = CELL_FIRST_PANEL * fmin(cell_scale(c, lo), gap);
        }
        part_piece(c, q, lo, hi, fmin(w0, hi - lo), out);
    }
}

/* A cell by rings: its parts in the four quadrants, mirrored into the first (identical parts once). */
static void cell_rings(const cell_ctx *c, double x0, double x1, double y0, double y1, double out[3])
{
    double xa[2][2] = {{fmax(x0, 0.0), x1}, {fmax(-x1, 0.0), -x0}}, ya[2][2] = {{fmax(y0, 0.0), y1}, {fmax(-y1, 0.0), -y0}};
    cell_part parts[4];
    double part_v[4][3];
    int np = 0;
    out[0] = out[1] = out[2] = 0.0;
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            if (!(xa[a][1] > xa[a][0]) || !(ya[b][1] > ya[b][0])) continue;
            cell_part q = {xa[a][0], xa[a][1], ya[b][0], ya[b][1]};
            int k = 0;
            while (k < np && memcmp(&parts[k], &q, sizeof q) != 0) k++;
            if (k == np) {
                parts[np] = q;
                part_integral(c, &q, part_v[np]);
                np++;
            }
            for (int ch = 0; ch < 3; ch++) out[ch] += part_v[k][ch];
        }
}

void kq_cell_integrals(const sss_profile *p, int grid, double extent, double *out)
{
    cell_ctx c;
    c.p = p;
    c.feat = kq_profile_length_scale(p);
    c.decay = kq_profile_decay_length(p);
    c.r_zero = zero_radius(p);
    for (int q = 1; q <= CELL_MAX_Q; q++) rule01(q, c.gl_x[q], c.gl_w[q]);
    c.knot_count = 0;
    if (p->model == SSS_PROFILE_PBD && p->table) {
        for (int ch = 0; ch < 3; ch++) {
            double st = p->material.sigma_a[ch] + p->material.sigma_s[ch];
            if (!(st > 0.0) || !isfinite(st)) continue;
            for (int i = 1; i < SSS_PBD_RADII; i++) c.knots[c.knot_count++] = p->table->radius[i] / st;
        }
        qsort(c.knots, (size_t)c.knot_count, sizeof c.knots[0], cmp_double);
    }
    size_t n = (size_t)grid, nn = n * n;
    double h = 2.0 * extent / grid;
    /* The matrix has the square's symmetry (x -> -x, y -> -y, x <-> y): compute the cells of the
     * octant x >= y >= 0 (index >= grid / 2; for odd grids that is the centre row) and mirror them.
     * Edges (2 i - grid) extent / grid are exactly symmetric: 0 or -+h/2 at the centre. */
    for (size_t i = n / 2; i < n; i++)
        for (size_t j = n / 2; j <= i; j++) {
            double x0 = (2.0 * (double)i - grid) * extent / grid, x1 = (2.0 * (double)i + 2.0 - grid) * extent / grid;
            double y0 = (2.0 * (double)j - grid) * extent / grid, y1 = (2.0 * (double)j + 2.0 - grid) * extent / grid;
            double v[3];
            double dx = fmax(x0, 0.0), dy = fmax(y0, 0.0), d = sqrt(dx * dx + dy * dy);
            /* Rings where R_d varies on a length shorter than the cell (the cell holds r = 0, or single
             * scattering's 1/sigma_t, or a coarse grid), tensor Gauss-Legendre elsewhere. */
            if (d >= c.r_zero) v[0] = v[1] = v[2] = 0.0;
            else if (d == 0.0 || (singular_origin(&c) && h > CELL_RING_RATIO * d) ||
                     h > tensor_max(&c) * smooth_scale(&c, d))
                cell_rings(&c, x0, x1, y0, y1, v);
            else cell_tensor(&c, x0, y0, h, d, v);
            size_t is[2] = {i, n - 1 - i}, js[2] = {j, n - 1 - j};
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++)
                    for (int ch = 0; ch < 3; ch++) {
                        double *m = out + (size_t)ch * nn;
                        m[is[a] * n + js[b]] = m[js[b] * n + is[a]] = v[ch];
                    }
        }
}
