/* Measured media lookup (docs/physics.md §2.3) and material construction/validation with useful errors. */
#include <string.h>

#include "check.h"
#include "sss/material.h"

static int contains(const char *s, const char *sub) { return strstr(s, sub) != NULL; }

int main(void)
{
    /* The twelve media of Jensen et al. 2001, as docs/physics.md §2.3 lists them. */
    static const char *const names[] = {"Apple", "Chicken1", "Chicken2", "Cream", "Ketchup", "Marble",
                                        "Potato", "Skimmilk", "Skin1", "Skin2", "Spectralon", "Wholemilk"};
    CHECK(sss_measured_medium_count() == 12);
    CHECK(sss_measured_medium_at(12) == NULL);
    for (size_t i = 0; i < 12; i++) {
        const sss_measured_medium *m = sss_measured_medium_find(names[i]);
        CHECK_MSG(m != NULL, "%s", names[i]);
        if (m) CHECK(strcmp(m->name, names[i]) == 0);
    }
    /* Spot values straight from the docs/physics.md table. */
    const sss_measured_medium *skin = sss_measured_medium_find("Skin1");
    CHECK(skin && skin->sigma_s_prime[0] == 0.74 && skin->sigma_a[2] == 0.48);
    const sss_measured_medium *ket = sss_measured_medium_find("Ketchup");
    CHECK(ket && ket->sigma_s_prime[2] == 0.03 && ket->sigma_a[1] == 0.97);

    /* Case-insensitive lookup; near misses are unknown. */
    CHECK(sss_measured_medium_find("marble") == sss_measured_medium_find("Marble"));
    CHECK(sss_measured_medium_find("SKIN1") == skin);
    CHECK(sss_measured_medium_find("sKiMmIlK") != NULL);
    CHECK(sss_measured_medium_find("Marbl") == NULL);
    CHECK(sss_measured_medium_find("Marble ") == NULL);
    CHECK(sss_measured_medium_find("") == NULL);
    CHECK(sss_measured_medium_find(NULL) == NULL);

    /* Material from a medium: coefficients times scale (mm per unit), g = 0. */
    sss_material m;
    sss_error err = {0};
    CHECK(sss_material_from_medium("skin1", 10.0, 1.4, &m, &err) == SSS_OK);
    CHECK_NEAR(m.sigma_s[1], 8.8, 1e-12);
    CHECK_NEAR(m.sigma_a[2], 4.8, 1e-12);
    CHECK(m.g == 0.0 && m.eta == 1.4);
    CHECK(sss_material_validate(&m, &err) == SSS_OK);
    CHECK(sss_material_from_medium("Spectralon", 1.0, 1.33, &m, &err) == SSS_OK); /* sigma_a = 0 is fine */

    /* Unknown medium: the message names it and lists the known ones. */
    CHECK(sss_material_from_medium("Cheese", 1.0, 1.33, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(contains(err.message, "Cheese") && contains(err.message, "Marble") &&
                  contains(err.message, "Wholemilk") && contains(err.message, "Apple"),
              "%s", err.message);

    /* Bad scale / eta. */
    CHECK(sss_material_from_medium("Marble", 0.0, 1.33, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(contains(err.message, "scale"), "%s", err.message);
    CHECK(sss_material_from_medium("Marble", -2.0, 1.33, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_material_from_medium("Marble", NAN, 1.33, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_material_from_medium("Marble", INFINITY, 1.33, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_material_from_medium("Marble", 1.0, 0.9, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(contains(err.message, "eta"), "%s", err.message);
    CHECK(sss_material_from_medium("Marble", 1.0, 2.6, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_material_from_medium("Marble", 1.0, 1.0, &m, &err) == SSS_OK);  /* range ends included */
    CHECK(sss_material_from_medium("Marble", 1.0, SSS_ETA_MAX, &m, &err) == SSS_OK);

    /* Explicit coefficients. */
    double sa[3] = {0.1, 0.2, 0.3}, ss[3] = {1.0, 2.0, 3.0};
    CHECK(sss_material_from_coefficients(sa, ss, 2.0, 1.5, 0.3, &m, &err) == SSS_OK);
    CHECK_NEAR(m.sigma_a[1], 0.4, 1e-15);
    CHECK_NEAR(m.sigma_s[2], 6.0, 1e-15);
    CHECK(m.g == 0.3);
    double neg[3] = {0.1, -0.2, 0.3};
    CHECK(sss_material_from_coefficients(neg, ss, 1.0, 1.5, 0.0, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(contains(err.message, "negative") && contains(err.message, "G"), "%s", err.message);
    CHECK(sss_material_from_coefficients(sa, neg, 1.0, 1.5, 0.0, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(contains(err.message, "scattering"), "%s", err.message);
    double nan3[3] = {0.1, NAN, 0.3};
    CHECK(sss_material_from_coefficients(nan3, ss, 1.0, 1.5, 0.0, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(contains(err.message, "finite"), "%s", err.message);
    double zero[3] = {0.0, 0.0, 0.0};
    CHECK(sss_material_from_coefficients(zero, zero, 1.0, 1.5, 0.0, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_material_from_coefficients(sa, ss, 1.0, 1.5, 1.0, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(contains(err.message, "g = 1"), "%s", err.message);
    CHECK(sss_material_from_coefficients(sa, ss, 1.0, 1.5, -1.0, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_material_from_coefficients(sa, ss, 1.0, 1.5, 0.99, &m, &err) == SSS_OK);
    double huge[3] = {1e300, 1e300, 1e300};
    CHECK(sss_material_from_coefficients(huge, ss, 1e300, 1.5, 0.0, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_material_from_coefficients(NULL, ss, 1.0, 1.5, 0.0, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);

    /* validate on hand-made materials. */
    sss_material v = {{0.1, 0.1, 0.1}, {1, 1, 1}, 1.33, 0.0};
    CHECK(sss_material_validate(&v, &err) == SSS_OK);
    v.sigma_s[0] = INFINITY;
    CHECK(sss_material_validate(&v, &err) == SSS_ERROR_INVALID_ARGUMENT);
    v.sigma_s[0] = 1.0;
    v.eta = NAN;
    CHECK(sss_material_validate(&v, &err) == SSS_ERROR_INVALID_ARGUMENT);
    v.eta = 1.33;
    v.g = NAN;
    CHECK(sss_material_validate(&v, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_material_validate(NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    sss_material zeroed = {{0}, {0}, 0, 0};
    CHECK(sss_material_validate(&zeroed, NULL) == SSS_ERROR_INVALID_ARGUMENT); /* NULL err is allowed */
    return CHECK_DONE();
}
