/* physics/catmull_rom.c — Catmull-Rom spline weights, integration, inversion and 2D sampling.
 *
 * Same semantics as PBRT-v3 core/interpolation.cpp (pbrt book 3rd ed., section 8.4.4 / appendix):
 * derivatives at the nodes by non-uniform finite differences, one-sided at the ends, Hermite cubic per
 * interval. Differences from PBRT: double precision, Newton-bisection with double tolerances and an
 * iteration cap (PBRT's loops are unbounded). */
#include "physics/catmull_rom.h"

#include <math.h>

/* PBRT FindInterval: the largest i in [0, size-2] with pred(i) true (binary search over a monotone
 * predicate), clamped. Implemented per caller with a predicate on a value array. */
static int find_interval_values(int size, const double *v, double x)
{
    int first = 0, len = size;
    while (len > 0) {
        int half = len >> 1, middle = first + half;
        if (v[middle] <= x) {
            first = middle + 1;
            len -= half + 1;
        } else {
            len = half;
        }
    }
    int i = first - 1;
    return i < 0 ? 0 : (i > size - 2 ? size - 2 : i);
}

int cr_weights(int size, const double *nodes, double x, int *offset, double w[4])
{
    if (!(x >= nodes[0] && x <= nodes[size - 1])) return 0;
    int idx = find_interval_values(size, nodes, x);
    *offset = idx - 1;
    double x0 = nodes[idx], x1 = nodes[idx + 1];
    double t = (x - x0) / (x1 - x0), t2 = t * t, t3 = t2 * t;
    /* Hermite basis for the values at x0, x1 ... */
    w[1] = 2 * t3 - 3 * t2 + 1;
    w[2] = -2 * t3 + 3 * t2;
    /* ... plus the derivative bases, the derivatives being finite differences of neighbours. */
    if (idx > 0) {
        double w0 = (t3 - 2 * t2 + t) * (x1 - x0) / (x1 - nodes[idx - 1]);
        w[0] = -w0;
        w[2] += w0;
    } else {
        double w0 = t3 - 2 * t2 + t;
        w[0] = 0;
        w[1] -= w0;
        w[2] += w0;
    }
    if (idx + 2 < size) {
        double w3 = (t3 - t2) * (x1 - x0) / (nodes[idx + 2] - x0);
        w[1] -= w3;
        w[3] = w3;
    } else {
        double w3 = t3 - t2;
        w[1] -= w3;
        w[2] += w3;
        w[3] = 0;
    }
    return 1;
}

double cr_eval(int size, const double *nodes, const double *values, double x)
{
    int off;
    double w[4];
    if (!cr_weights(size, nodes, x, &off, w)) return 0.0;
    double v = 0.0;
    for (int i = 0; i < 4; i++)
        if (w[i] != 0.0) v += w[i] * values[off + i];
    return v;
}

/* End derivatives of interval i (scaled by its width), PBRT's finite differences. */
static void interval_derivatives(int n, const double *x, const double *f, int i, double *d0, double *d1)
{
    double width = x[i + 1] - x[i];
    *d0 = i > 0 ? width * (f[i + 1] - f[i - 1]) / (x[i + 1] - x[i - 1]) : f[i + 1] - f[i];
    *d1 = i + 2 < n ? width * (f[i + 2] - f[i]) / (x[i + 2] - x[i]) : f[i + 1] - f[i];
}

double cr_integrate(int n, const double *x, const double *values, double *cdf)
{
    double sum = 0.0;
    cdf[0] = 0.0;
    for (int i = 0; i < n - 1; i++) {
        double d0, d1;
        interval_derivatives(n, x, values, i, &d0, &d1);
        /* Exact integral of the Hermite cubic over the interval. */
        sum += ((d0 - d1) * (1.0 / 12.0) + (values[i] + values[i + 1]) * 0.5) * (x[i + 1] - x[i]);
        cdf[i + 1] = sum;
    }
    return sum;
}

double cr_invert(int n, const double *x, const double *values, double u)
{
    if (!(u > values[0])) return x[0];
    if (!(u < values[n - 1])) return x[n - 1];
    int i = find_interval_values(n, values, u);
    double f0 = values[i], f1 = values[i + 1], width = x[i + 1] - x[i];
    double d0, d1;
    interval_derivatives(n, x, values, i, &d0, &d1);
    /* Newton-bisection on the Hermite cubic F(t) = u, t in [0, 1]. */
    double a = 0.0, b = 1.0, t = 0.5;
    double tol = 1e-13 * (fabs(f0) + fabs(f1) + fabs(d0) + fabs(d1)); /* scale of the cubic */
    for (int it = 0; it < 200; it++) {
        if (!(t > a && t < b)) t = 0.5 * (a + b);
        double t2 = t * t, t3 = t2 * t;
        double Fh = (2 * t3 - 3 * t2 + 1) * f0 + (-2 * t3 + 3 * t2) * f1 + (t3 - 2 * t2 + t) * d0 +
                    (t3 - t2) * d1;
        double fh = (6 * t2 - 6 * t) * f0 + (-6 * t2 + 6 * t) * f1 + (3 * t2 - 4 * t + 1) * d0 +
                    (3 * t2 - 2 * t) * d1;
        if (fabs(Fh - u) <= tol || b - a < 1e-14) break;
        if (Fh - u < 0)
            a = t;
        else
            b = t;
        t -= (Fh - u) / fh;
    }
    return x[i] + t * width;
}

double cr_sample_2d(int size1, int size2, const double *nodes1, const double *nodes2,
                    const double *values, const double *cdf, double alpha, double u, double *fval,
                    double *pdf)
{
    int off;
    double w[4];
    if (fval) *fval = 0.0;
    if (pdf) *pdf = 0.0;
    if (!cr_weights(size1, nodes1, alpha, &off, w)) return 0.0;
/* Interpolate column idx of a table across the four rows. */
#define INTERP(array, idx) \
    (((w[0] != 0.0) ? (array)[(off + 0) * size2 + (idx)] * w[0] : 0.0) + \
     ((w[1] != 0.0) ? (array)[(off + 1) * size2 + (idx)] * w[1] : 0.0) + \
     ((w[2] != 0.0) ? (array)[(off + 2) * size2 + (idx)] * w[2] : 0.0) + \
     ((w[3] != 0.0) ? (array)[(off + 3) * size2 + (idx)] * w[3] : 0.0))

    double maximum = INTERP(cdf, size2 - 1);
    if (!(maximum > 0.0)) return 0.0;
    u *= maximum;
    /* Binary search of the interpolated CDF (PBRT FindInterval with an interpolating predicate). */
    int first = 0, len = size2;
    while (len > 0) {
        int half = len >> 1, middle = first + half;
        if (INTERP(cdf, middle) <= u) {
            first = middle + 1;
            len -= half + 1;
        } else {
            len = half;
        }
    }
    int idx = first - 1;
    idx = idx < 0 ? 0 : (idx > size2 - 2 ? size2 - 2 : idx);

    double f0 = INTERP(values, idx), f1 = INTERP(values, idx + 1);
    double x0 = nodes2[idx], x1 = nodes2[idx + 1], width = x1 - x0;
    u = (u - INTERP(cdf, idx)) / width;
    double d0 = idx > 0 ? width * (f1 - INTERP(values, idx - 1)) / (x1 - nodes2[idx - 1]) : f1 - f0;
    double d1 = idx + 2 < size2 ? width * (INTERP(values, idx + 2) - f0) / (nodes2[idx + 2] - x0)
                                : f1 - f0;
#undef INTERP

    /* Initial guess: invert the integral of the linear interpolant; then Newton-bisection on the
     * integral of the Hermite cubic, Fhat(t) = u (PBRT SampleCatmullRom2D). */
    double t;
    if (f0 != f1)
        t = (f0 - sqrt(fmax(0.0, f0 * f0 + 2 * u * (f1 - f0)))) / (f0 - f1);
    else
        t = f0 != 0.0 ? u / f0 : 0.5;
    double a = 0.0, b = 1.0, Fh = 0.0, fh = 0.0;
    double tol = 1e-13 * (fabs(f0) + fabs(f1) + fabs(d0) + fabs(d1)); /* scale of the cubic */
    for (int it = 0; it < 200; it++) {
        if (!(t >= a && t <= b)) t = 0.5 * (a + b);
        Fh = t * (f0 + t * (.5 * d0 + t * ((1.0 / 3.0) * (-2 * d0 - d1) + f1 - f0 +
                                          t * (.25 * (d0 + d1) + .5 * (f0 - f1)))));
        fh = f0 + t * (d0 + t * (-2 * d0 - d1 + 3 * (f1 - f0) + t * (d0 + d1 + 2 * (f0 - f1))));
        if (fabs(Fh - u) <= tol || b - a < 1e-14) break;
        if (Fh - u < 0)
            a = t;
        else
            b = t;
        t -= (Fh - u) / fh;
    }
    if (fval) *fval = fh;
    if (pdf) *pdf = fh / maximum;
    return x0 + width * t;
}
