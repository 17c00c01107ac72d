/* Classical dipole (Mertens et al. 2003): the closed-form total reflectance against an independent adaptive
 * quadrature of R_d over the plane; the exact sampler against R_d(r) 2 pi r / rho by a chi-square test;
 * the pdf integrates to 1. */
#include "check.h"
#include "physics/physics_test_util.h"
#include "sss/profile.h"

#define PI 3.14159265358979323846

typedef struct ctx {
    const sss_dipole *d;
    double length; /* substitution scale r = length t / (1 - t) */
    int pdf;       /* integrate the pdf instead of R_d 2 pi r */
} ctx;

static double radial(double r, const ctx *c)
{
    return c->pdf ? sss_dipole_pdf_radius(c->d, r) : sss_dipole_rd(c->d, r) * 2.0 * PI * r;
}

/* [0, inf) -> [0, 1): r = L t/(1-t), dr = L/(1-t)^2 dt. */
static double mapped(double t, void *p)
{
    const ctx *c = (const ctx *)p;
    double r = c->length * t / (1.0 - t);
    return radial(r, c) * c->length / ((1.0 - t) * (1.0 - t));
}

static double plane_integral(const ctx *c, double r0, double r1)
{
    /* Map the interval [r0, r1] (r1 may be inf) to t. */
    double t0 = r0 / (r0 + c->length), t1 = isinf(r1) ? 1.0 : r1 / (r1 + c->length);
    return tu_integrate(mapped, (void *)c, t0, t1, 1e-11);
}

int main(void)
{
    /* (sigma_a, sigma_s', eta): measured media channels in mm^-1 (docs/physics.md §2.3) and synthetic ones,
     * including no absorption (sigma_tr = 0) and strong absorption. */
    static const double cases[][3] = {
        {0.0021, 2.19, 1.33}, /* Marble R */
        {0.48, 1.01, 1.33},   /* Skin1 B */
        {0.97, 0.07, 1.33},   /* Ketchup G: absorption-dominated */
        {0.0, 11.6, 1.33},    /* Spectralon R: no absorption */
        {0.05, 1.0, 1.0},     /* index-matched */
        {0.3, 3.0, 2.0},
        {2.0, 20.0, 1.5},
    };
    int ncases = (int)(sizeof cases / sizeof cases[0]);
    for (int k = 0; k < ncases; k++) {
        sss_dipole d;
        sss_dipole_init(&d, cases[k][0], cases[k][1], cases[k][2]);
        ctx c = {&d, 1.0 / (cases[k][0] + cases[k][1]), 0};
        double rho = sss_dipole_total_reflectance(&d);
        double q = plane_integral(&c, 0.0, INFINITY);
        CHECK_REL(q, rho, 1e-4);
        CHECK(rho > 0.0 && rho <= 1.0);
        /* R_d is positive and decreasing in r. */
        double prev = INFINITY;
        for (double r = 0.0; r < 50.0 * c.length; r += 0.37 * c.length) {
            double v = sss_dipole_rd(&d, r);
            CHECK(v > 0.0 && v <= prev);
            prev = v;
        }
        c.pdf = 1;
        CHECK_REL(plane_integral(&c, 0.0, INFINITY), 1.0, 1e-4);
        c.pdf = 0;

        /* Sampler: 1e5 samples, bins with geometric edges L 10^(-2 + 4 j / 22) plus [0, first] and
         * [last, inf); expected probabilities by quadrature of R_d 2 pi r / rho. */
        enum { EDGES = 23, BINS = EDGES + 1 };
        double edge[EDGES], prob[BINS];
        long count[BINS] = {0};
        for (int j = 0; j < EDGES; j++) edge[j] = c.length * pow(10.0, -2.0 + 4.0 * j / (EDGES - 1));
        for (int j = 0; j < BINS; j++) {
            double lo = j == 0 ? 0.0 : edge[j - 1], hi = j == EDGES ? INFINITY : edge[j];
            prob[j] = plane_integral(&c, lo, hi) / q;
        }
        tu_rng rng = {12345u + (uint64_t)k};
        long n = 100000;
        int bad = 0;
        for (long i = 0; i < n; i++) {
            double r = sss_dipole_sample_radius(&d, tu_uniform(&rng), tu_uniform(&rng));
            if (!(r >= 0.0) || !isfinite(r)) {
                bad++;
                continue;
            }
            int j = 0;
            while (j < EDGES && r > edge[j]) j++;
            count[j]++;
        }
        CHECK(bad == 0);
        int dof;
        double chi = tu_chi_square(count, prob, BINS, n, &dof);
        CHECK_MSG(chi < tu_chi2_critical_999(dof), "case %d: chi2 %.2f, dof %d, critical %.2f", k, chi, dof,
                  tu_chi2_critical_999(dof));
    }

    /* Sampler edge cases: u_radius = 0 gives r = 0; monotone in u_radius; finite for u -> 1. */
    sss_dipole d;
    sss_dipole_init(&d, 0.01, 1.0, 1.3);
    CHECK(sss_dipole_sample_radius(&d, 0.1, 0.0) == 0.0);
    double prev = -1.0;
    for (double u = 0.0; u < 1.0; u += 0.01) {
        double r = sss_dipole_sample_radius(&d, 0.1, u);
        CHECK(r >= prev);
        prev = r;
    }
    CHECK(isfinite(sss_dipole_sample_radius(&d, 0.9, 1.0)));
    CHECK(isfinite(sss_dipole_sample_radius(&d, 0.9, 0.999999999999)));
    /* The real source's quantile: its radial CDF (Mertens et al. 2003, Eq. 6) at the sample equals u. */
    for (double u = 0.05; u < 1.0; u += 0.1) {
        double r = sss_dipole_sample_radius(&d, 0.0, u); /* u_source = 0 -> real source */
        double s = sqrt(r * r + d.z_r * d.z_r);
        double cdf = 1.0 - d.z_r / s * exp(-d.sigma_tr * (s - d.z_r));
        CHECK_NEAR(cdf, u, 1e-10);
    }

    /* A non-interacting medium gives a zero profile, never NaN. */
    sss_dipole_init(&d, 0.0, 0.0, 1.33);
    CHECK(sss_dipole_rd(&d, 0.5) == 0.0 && sss_dipole_total_reflectance(&d) == 0.0);
    CHECK(sss_dipole_pdf_radius(&d, 0.5) == 0.0);
    return CHECK_DONE();
}
