/* gl/tech_mertens2003_table.c — importance-sampling tables of mertens2003 (see tech_mertens2003.h). */
#include <math.h>
#include <string.h>

#include "gl/techniques/mertens2003/tech_mertens2003.h"

/* The exact sampler of Mertens et al. 2003, section 4 as a quantile function: for PBD the table's own inverse CDF
 * (sss_pbd_sample_radius, PBRT Sample_Sr); for the dipole (and the Gaussian fit) the inverse of the
 * closed-form CDF, the same distribution sss_dipole_sample_radius draws from with two uniforms. */
static double quantile(const sss_profile *p, int c, double u)
{
    if (u <= 0.0) return 0.0;
    if (p->model == SSS_PROFILE_PBD) {
        double r = sss_pbd_sample_radius(p->table, p->material.sigma_a[c], p->material.sigma_s[c], u);
        return r > 0.0 ? r : 0.0;
    }
    return sss_profile_radius_for_fraction(p, c, u);
}

sss_result mertens_table_build(const sss_profile *profile, float *out, sss_error *err)
{
    memset(out, 0, sizeof(float) * MERTENS_TABLE_FLOATS);
    int max_scan = 0;
    for (int c = 0; c < 3; c++) {
        float *rq = out + MERTENS_RADII_AT + c * (MERTENS_T + 1);
        float *guide = out + MERTENS_GUIDE_AT + c * MERTENS_G;
        if (!(sss_profile_total(profile, c) > 0.0)) continue; /* r_T = 0: no importance samples */
        rq[0] = 0.0f;
        for (int k = 1; k <= MERTENS_T; k++) {
            double r = quantile(profile, c, MERTENS_U_MAX * k / MERTENS_T);
            if (!isfinite(r) || r < 0.0)
                return sss_error_set(err, SSS_ERROR_NUMERIC, "mertens2003: sampler returned r = %g (channel %d)", r, c);
            /* strictly increasing, so every segment has a finite density */
            double floor_r = (double)rq[k - 1] * (1.0 + 1e-6) + 1e-30;
            rq[k] = (float)(r > floor_r ? r : floor_r);
            if (!(rq[k] > rq[k - 1])) rq[k] = nextafterf(rq[k - 1], INFINITY);
        }
        double rt = rq[MERTENS_T];
        out[c] = (float)rt;
        /* guide cell g starts at r_T (g / G)^2: the last segment whose start lies at or below it */
        int s = 0;
        for (int g = 0; g < MERTENS_G; g++) {
            double x = (double)g / MERTENS_G;
            float r0 = (float)(rt * x * x);
            while (s < MERTENS_T - 1 && rq[s + 1] <= r0) s++;
            guide[g] = (float)s;
        }
        for (int g = 0; g < MERTENS_G; g++) {
            int next = g + 1 < MERTENS_G ? (int)guide[g + 1] : MERTENS_T - 1;
            if (next - (int)guide[g] > max_scan) max_scan = next - (int)guide[g];
        }
    }
    out[3] = (float)max_scan;
    return SSS_OK;
}

double mertens_table_sample(const float *table, int channel, double u)
{
    const float *rq = table + MERTENS_RADII_AT + channel * (MERTENS_T + 1);
    double x = u * MERTENS_T;
    int k = (int)floor(x);
    if (k < 0) k = 0;
    if (k > MERTENS_T - 1) k = MERTENS_T - 1;
    double t = x - k;
    return rq[k] + t * (rq[k + 1] - rq[k]);
}

double mertens_table_pdf(const float *table, int channel, double r)
{
    const float *rq = table + MERTENS_RADII_AT + channel * (MERTENS_T + 1);
    const float *guide = table + MERTENS_GUIDE_AT + channel * MERTENS_G;
    double rt = table[channel];
    if (!(rt > 0.0) || r < 0.0 || r >= rt) return 0.0;
    int g = (int)(sqrt(r / rt) * MERTENS_G);
    if (g > MERTENS_G - 1) g = MERTENS_G - 1;
    int s = (int)guide[g];
    while (s > 0 && r < rq[s]) s--; /* rounding of the guide cell */
    while (s < MERTENS_T - 1 && r >= rq[s + 1]) s++;
    return 1.0 / (MERTENS_T * ((double)rq[s + 1] - rq[s]));
}
