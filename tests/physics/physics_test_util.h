/* tests/physics/physics_test_util.h — independent numerical tools for the physics tests: adaptive
 * Gauss-Kronrod (7/15) quadrature, a seeded RNG, and a chi-square goodness-of-fit statistic.
 * Nothing here calls the library: the tests compare the library against these. */
#ifndef SSS_PHYSICS_TEST_UTIL_H
#define SSS_PHYSICS_TEST_UTIL_H

#include <math.h>
#include <stdint.h>

typedef double (*tu_fn)(double x, void *ctx);

/* Gauss-Kronrod 15-point nodes/weights and the embedded 7-point Gauss weights (standard tables). */
static const double tu_xgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                                 0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                                 0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                                 0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
static const double tu_wgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                 0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                 0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                 0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
static const double tu_wg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

static inline double tu_gk15(tu_fn f, void *ctx, double a, double b, double *err)
{
    double c = 0.5 * (a + b), h = 0.5 * (b - a);
    double fc = f(c, ctx);
    double k = fc * tu_wgk[7], g = fc * tu_wg[3];
    for (int j = 0; j < 7; j++) {
        double dx = h * tu_xgk[j];
        double s = f(c - dx, ctx) + f(c + dx, ctx);
        k += tu_wgk[j] * s;
        if (j % 2 == 1) g += tu_wg[j / 2] * s;
    }
    *err = fabs((k - g) * h);
    return k * h;
}

static inline double tu_adapt(tu_fn f, void *ctx, double a, double b, double tol, int depth)
{
    double err, v = tu_gk15(f, ctx, a, b, &err);
    if (err <= tol || depth <= 0) return v;
    double m = 0.5 * (a + b);
    return tu_adapt(f, ctx, a, m, 0.5 * tol, depth - 1) + tu_adapt(f, ctx, m, b, 0.5 * tol, depth - 1);
}

/* Integral of f over [a, b] to absolute tolerance tol (adaptive bisection, depth <= 40). */
static inline double tu_integrate(tu_fn f, void *ctx, double a, double b, double tol)
{
    return tu_adapt(f, ctx, a, b, tol, 40);
}

/* Integral of f(r) over [r0, r1], 0 < r0 < r1, on a log scale (r = e^s, dr = r ds), split into
 * decades so that adaptive subdivision resolves each one. */
typedef struct tu_log_ctx {
    tu_fn f;
    void *ctx;
} tu_log_ctx;

static inline double tu_log_integrand(double s, void *c)
{
    tu_log_ctx *l = (tu_log_ctx *)c;
    double r = exp(s);
    return l->f(r, l->ctx) * r;
}

static inline double tu_integrate_log(tu_fn f, void *ctx, double r0, double r1, double tol)
{
    tu_log_ctx l = {f, ctx};
    double s0 = log(r0), s1 = log(r1), sum = 0.0;
    int pieces = (int)ceil((s1 - s0) / log(10.0));
    if (pieces < 1) pieces = 1;
    for (int i = 0; i < pieces; i++) {
        double a = s0 + (s1 - s0) * i / pieces, b = s0 + (s1 - s0) * (i + 1) / pieces;
        sum += tu_integrate(tu_log_integrand, &l, a, b, tol / pieces);
    }
    return sum;
}

/* splitmix64: a small, well-mixed, seeded generator. */
typedef struct tu_rng {
    uint64_t s;
} tu_rng;

static inline double tu_uniform(tu_rng *g)
{
    uint64_t z = (g->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0); /* [0, 1) */
}

/* Pearson chi-square of observed counts against expected probabilities (n samples in total). Bins
 * with expected count < 5 are merged into their neighbour. Returns the statistic, *dof the degrees of
 * freedom (merged bins - 1). */
static inline double tu_chi_square(const long *observed, const double *prob, int bins, long n, int *dof)
{
    double chi = 0.0, e_acc = 0.0, o_acc = 0.0;
    int used = 0;
    for (int i = 0; i < bins; i++) {
        e_acc += prob[i] * (double)n;
        o_acc += (double)observed[i];
        if (e_acc >= 5.0 || i == bins - 1) {
            if (e_acc > 0.0) chi += (o_acc - e_acc) * (o_acc - e_acc) / e_acc;
            used++;
            e_acc = o_acc = 0.0;
        }
    }
    *dof = used - 1;
    return chi;
}

/* Upper 0.1% critical value of chi-square with k degrees of freedom (Wilson-Hilferty approximation,
 * accurate to ~1% for k >= 5; z = 3.0902 is the standard normal 0.999 quantile). */
static inline double tu_chi2_critical_999(int k)
{
    double z = 3.090232306167813, a = 2.0 / (9.0 * k);
    double t = 1.0 - a + z * sqrt(a);
    return k * t * t * t;
}

#endif
