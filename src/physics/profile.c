/* physics/profile.c — one radial profile R_d(r) (PBD table, dipole or six-Gaussian fit) behind a
 * common interface for the kernel builders: evaluation, plane integral, and the radius holding a
 * given fraction of that integral. */
#include "sss/profile.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const model_name[3] = {"pbd", "dipole", "gauss6"};

sss_result sss_profile_init(sss_profile *p, sss_profile_model model, const sss_material *m,
                            const sss_pbd_table *table, sss_error *err)
{
    if (!p) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "profile is NULL");
    if (model != SSS_PROFILE_PBD && model != SSS_PROFILE_DIPOLE && model != SSS_PROFILE_GAUSS6)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "unknown profile model %d", (int)model);
    sss_profile q;
    memset(&q, 0, sizeof q);
    q.model = model;
    q.gauss6_mm_per_unit = 1.0;
    if (model == SSS_PROFILE_GAUSS6) {
        /* The skin fit has fixed coefficients: the material is carried along but not required. */
        if (m) q.material = *m;
        *p = q;
        return SSS_OK;
    }
    if (!m)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s profile: material is NULL",
                             model_name[model]);
    sss_result r = sss_material_validate(m, err);
    if (r != SSS_OK) {
        sss_error_prefix(err, model == SSS_PROFILE_PBD ? "pbd profile" : "dipole profile");
        return r;
    }
    q.material = *m;
    if (model == SSS_PROFILE_PBD) {
        if (!table)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "pbd profile: no PBD table given");
        if (fabs(table->eta - m->eta) > 1e-12 || fabs(table->g - m->g) > 1e-12)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "pbd profile: the table was built for eta %g, g %g but the material "
                                 "has eta %g, g %g (build the table for the material)",
                                 table->eta, table->g, m->eta, m->g);
        q.table = table;
    } else {
        /* The dipole takes reduced scattering sigma_s' = sigma_s (1 - g) (Mertens et al. 2003, Table 1). */
        for (int c = 0; c < 3; c++)
            sss_dipole_init(&q.dipole[c], m->sigma_a[c], m->sigma_s[c] * (1.0 - m->g), m->eta);
    }
    *p = q;
    return SSS_OK;
}

/* Variance of six-Gaussian term k in scene units^2 (the fit is in mm^2). */
static double gauss6_variance(const sss_profile *p, int k)
{
    double s = p->gauss6_mm_per_unit > 0.0 && isfinite(p->gauss6_mm_per_unit) ? p->gauss6_mm_per_unit : 1.0;
    return sss_gauss6_variance_mm2[k] / (s * s);
}

double sss_profile_eval(const sss_profile *p, int channel, double r)
{
    if (!p || channel < 0 || channel > 2 || !isfinite(r)) return 0.0;
    double v = 0.0;
    switch (p->model) {
    case SSS_PROFILE_PBD:
        v = sss_pbd_sr(p->table, p->material.sigma_a[channel], p->material.sigma_s[channel], r);
        break;
    case SSS_PROFILE_DIPOLE:
        v = sss_dipole_rd(&p->dipole[channel], r);
        break;
    case SSS_PROFILE_GAUSS6:
        /* d'Eon 2007: sum of normalised 2D Gaussians (docs/physics.md §2.4). */
        for (int k = 0; k < SSS_GAUSS6_TERMS; k++)
            v += sss_gauss6_weight[channel][k] * sss_gaussian_2d(gauss6_variance(p, k), r);
        break;
    }
    return v > 0.0 && isfinite(v) ? v : 0.0;
}

void sss_profile_eval_rgb(const sss_profile *p, double r, double out[3])
{
    for (int c = 0; c < 3; c++) out[c] = sss_profile_eval(p, c, r);
}

double sss_profile_total(const sss_profile *p, int channel)
{
    if (!p || channel < 0 || channel > 2) return 0.0;
    double v = 0.0;
    switch (p->model) {
    case SSS_PROFILE_PBD: {
        /* int S_r 2 pi r dr = int (interpolated 2 pi r_opt S) dr_opt = interpolated rho_eff. */
        double sa = p->material.sigma_a[channel], ss = p->material.sigma_s[channel];
        v = sa + ss > 0.0 ? sss_pbd_rho_eff(p->table, ss / (sa + ss)) : 0.0;
        break;
    }
    case SSS_PROFILE_DIPOLE:
        v = sss_dipole_total_reflectance(&p->dipole[channel]);
        break;
    case SSS_PROFILE_GAUSS6:
        for (int k = 0; k < SSS_GAUSS6_TERMS; k++) v += sss_gauss6_weight[channel][k];
        break;
    }
    return v > 0.0 && isfinite(v) ? v : 0.0;
}

/* Fraction of the plane integral inside radius r, in closed form for the dipole (Mertens et al. 2003, Eq. 6:
 * int_0^r z (1 + s_tr s) e^(-s_tr s)/s^3 r dr = e^(-s_tr z) - z e^(-s_tr s(r))/s(r)) and for the
 * Gaussians (int_0^r G 2 pi r dr = 1 - e^(-r^2/2v)). */
static double closed_form_cdf(const sss_profile *p, int channel, double r)
{
    if (p->model == SSS_PROFILE_DIPOLE) {
        const sss_dipole *d = &p->dipole[channel];
        double zs[2] = {d->z_r, d->z_v}, num = 0.0, den = 0.0;
        for (int k = 0; k < 2; k++) {
            double s = sqrt(r * r + zs[k] * zs[k]);
            double e0 = exp(-d->sigma_tr * zs[k]);
            num += e0 - zs[k] * exp(-d->sigma_tr * s) / s;
            den += e0;
        }
        return den > 0.0 ? num / den : 1.0;
    }
    double num = 0.0, den = 0.0;
    for (int k = 0; k < SSS_GAUSS6_TERMS; k++) {
        double w = sss_gauss6_weight[channel][k], v = gauss6_variance(p, k);
        num -= w * expm1(-r * r / (2.0 * v));
        den += w;
    }
    return den > 0.0 ? num / den : 1.0;
}

double sss_profile_radius_for_fraction(const sss_profile *p, int channel, double fraction)
{
    if (!p || channel < 0 || channel > 2 || !(fraction > 0.0)) return 0.0;
    if (sss_profile_total(p, channel) <= 0.0) return 0.0;
    if (p->model == SSS_PROFILE_PBD) {
        /* The table's own inverse CDF, as PBRT bounds its probe rays (rMax = Sample_Sr(ch, 0.999)). */
        double sa = p->material.sigma_a[channel], ss = p->material.sigma_s[channel];
        if (fraction >= 1.0) return p->table->radius[SSS_PBD_RADII - 1] / (sa + ss);
        double r = sss_pbd_sample_radius(p->table, sa, ss, fraction);
        return r > 0.0 ? r : 0.0;
    }
    /* Infinite support: "everything" means all but 1e-12 of it. */
    if (fraction > 1.0 - 1e-12) fraction = 1.0 - 1e-12;
    double lo = 0.0, hi = 1e-6;
    for (int i = 0; i < 200 && closed_form_cdf(p, channel, hi) < fraction; i++) {
        lo = hi;
        hi *= 2.0;
    }
    for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; i++) {
        double mid = 0.5 * (lo + hi);
        if (closed_form_cdf(p, channel, mid) < fraction)
            lo = mid;
        else
            hi = mid;
    }
    return hi;
}

double sss_profile_reach(const sss_profile *p, double fraction)
{
    double reach = 0.0;
    for (int c = 0; c < 3; c++) {
        double x = sss_profile_radius_for_fraction(p, c, fraction);
        if (isfinite(x) && x > reach) reach = x;
    }
    return reach;
}

sss_result sss_medium_profile_init(sss_medium_profile *out, const char *medium, double scale, double eta,
                                   sss_profile_model model, sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_medium_profile_init: out is NULL");
    memset(out, 0, sizeof *out);
    if (model != SSS_PROFILE_PBD && model != SSS_PROFILE_DIPOLE)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: model %d is neither PBD nor the dipole",
                             medium ? medium : "medium", (int)model);
    sss_result res = sss_material_from_medium(medium, scale, eta, &out->material, err);
    if (res == SSS_OK && model == SSS_PROFILE_PBD) {
        out->table = malloc(sizeof *out->table);
        res = out->table ? sss_pbd_table_build(out->material.eta, out->material.g, out->table, err)
                         : sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory for the PBD table", medium);
    }
    if (res == SSS_OK) res = sss_profile_init(&out->profile, model, &out->material, out->table, err);
    if (res != SSS_OK) sss_medium_profile_free(out);
    return res;
}

void sss_medium_profile_free(sss_medium_profile *p)
{
    if (!p) return;
    free(p->table);
    memset(p, 0, sizeof *p);
}
