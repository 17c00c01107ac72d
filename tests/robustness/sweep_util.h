/* tests/robustness/sweep_util.h — the sweep shared by the numerical robustness tests: every measured
 * medium x eta in {1.0, 1.2, 1.33, 1.5, 2.0} x scale in {1e-3, 1, 1e3} millimetres per scene unit
 * (coefficients from 1e-3 to 1e3 times the table's), each as a PBD and a dipole profile. */
#ifndef SSS_TEST_SWEEP_UTIL_H
#define SSS_TEST_SWEEP_UTIL_H

#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "sss/material.h"
#include "sss/profile.h"

static const double sweep_etas[] = {1.0, 1.2, 1.33, 1.5, 2.0};
static const double sweep_scales[] = {1e-3, 1.0, 1e3};
#define SWEEP_NETA (sizeof sweep_etas / sizeof sweep_etas[0])
#define SWEEP_NSCALE (sizeof sweep_scales / sizeof sweep_scales[0])

/* Called once per profile; what names it ("Marble eta 1.33 scale 1000 pbd"). */
typedef void (*sweep_fn)(const sss_profile *p, const char *what);

/* Runs fn over the whole sweep; returns the number of profiles visited. */
static int sweep_profiles(sweep_fn fn)
{
    sss_pbd_table *tables = malloc(SWEEP_NETA * sizeof *tables);
    CHECK(tables != NULL);
    if (!tables) return 0;
    for (size_t e = 0; e < SWEEP_NETA; e++) CHECK(sss_pbd_table_build(sweep_etas[e], 0.0, &tables[e], NULL) == SSS_OK);
    int n = 0;
    for (size_t i = 0; i < sss_measured_medium_count(); i++) {
        const char *name = sss_measured_medium_at(i)->name;
        for (size_t e = 0; e < SWEEP_NETA; e++)
            for (size_t s = 0; s < SWEEP_NSCALE; s++) {
                sss_material m;
                sss_error err = {0};
                sss_result r = sss_material_from_medium(name, sweep_scales[s], sweep_etas[e], &m, &err);
                CHECK_MSG(r == SSS_OK, "%s eta %g scale %g: %s", name, sweep_etas[e], sweep_scales[s], err.message);
                if (r != SSS_OK) continue;
                sss_profile pbd, dip;
                char what[160];
                CHECK(sss_profile_init(&pbd, SSS_PROFILE_PBD, &m, &tables[e], NULL) == SSS_OK);
                CHECK(sss_profile_init(&dip, SSS_PROFILE_DIPOLE, &m, NULL, NULL) == SSS_OK);
                snprintf(what, sizeof what, "%s eta %g scale %g pbd", name, sweep_etas[e], sweep_scales[s]);
                fn(&pbd, what);
                snprintf(what, sizeof what, "%s eta %g scale %g dipole", name, sweep_etas[e], sweep_scales[s]);
                fn(&dip, what);
                n += 2;
            }
    }
    free(tables);
    return n;
}

#endif
