/* Scene materials resolved to coefficients: measured media x scale (docs/physics.md §2.3), explicit
 * coefficients, kdsubsurface inversion (reflectance + mfp), profiles, the shared PBD table cache. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "sss/scene.h"

#define SCENES SSS_TEST_DATA "/scenes"

/* Parses a one-or-more-object scene whose objects are given as JSON (no meshes loaded). */
static sss_result load(const char *objects, sss_scene *s, sss_error *err)
{
    char json[4096];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 0, 5], \"look_at\": [0, 0, 0]}, \"objects\": [%s]}", objects);
    sss_scene_load_desc desc = {SSS_SCENE_SKIP_MESHES};
    sss_result res = sss_scene_parse(json, strlen(json), SCENES, "material.json", &desc, s, err);
    CHECK_MSG(res == SSS_OK, "%s", err->message);
    return res;
}

#define SPHERE "\"procedural\": {\"shape\": \"sphere\", \"radius\": 1}"

static void test_medium(void)
{
    sss_scene s;
    sss_error err = {0};
    if (load("{" SPHERE ", \"material\": {\"type\": \"subsurface\", \"medium\": \"mArBlE\", \"scale\": 100}}", &s,
             &err) != SSS_OK)
        return;
    const sss_scene_material *m = &s.objects[0].material;
    /* Marble (Jensen et al. 2001, docs/physics.md §2.3): sigma_s' 2.19, 2.62, 3.00; sigma_a 0.0021, 0.0041,
     * 0.0071 mm^-1; 100 mm per scene unit. */
    const double ss[3] = {2.19, 2.62, 3.00}, sa[3] = {0.0021, 0.0041, 0.0071};
    for (int i = 0; i < 3; i++) {
        CHECK_REL(m->optical.sigma_s[i], 100 * ss[i], 1e-12);
        CHECK_REL(m->optical.sigma_a[i], 100 * sa[i], 1e-12);
    }
    CHECK(m->source == SSS_SUBSURFACE_MEDIUM && strcmp(m->medium->name, "Marble") == 0);
    CHECK(m->optical.g == 0 && m->optical.eta == 1.33);
    /* rho_eff of Marble at eta 1.33 under PBRT-v3's table (docs/physics.md §1): 0.901, 0.868, 0.834. */
    CHECK_NEAR(m->albedo[0], 0.901, 2e-3);
    CHECK_NEAR(m->albedo[1], 0.868, 2e-3);
    CHECK_NEAR(m->albedo[2], 0.834, 2e-3);
    CHECK(m->table && m->table->eta == 1.33 && m->table->g == 0);
    sss_scene_free(&s);
}

static void test_coefficients(void)
{
    sss_scene s;
    sss_error err = {0};
    if (load("{" SPHERE ", \"material\": {\"type\": \"subsurface\", \"sigma_a\": [0.1, 0.2, 0.3],"
             " \"sigma_s\": [1, 2, 0], \"scale\": 10, \"eta\": 1.5, \"g\": 0.4, \"profile\": \"dipole\"}}",
             &s, &err) != SSS_OK)
        return;
    const sss_scene_material *m = &s.objects[0].material;
    CHECK(m->source == SSS_SUBSURFACE_COEFFICIENTS);
    CHECK_REL(m->optical.sigma_a[1], 2.0, 1e-12);
    CHECK_REL(m->optical.sigma_s[0], 10.0, 1e-12);
    CHECK(m->optical.sigma_s[2] == 0);
    CHECK(m->input_sigma_a[2] == 0.3 && m->scale == 10);
    CHECK(m->optical.eta == 1.5 && m->optical.g == 0.4);
    CHECK(m->table->eta == 1.5 && m->table->g == 0.4);
    CHECK(m->profile == SSS_SCENE_PROFILE_DIPOLE && sss_scene_material_profile_model(m) == SSS_PROFILE_DIPOLE);
    /* A purely absorbing channel reflects nothing. */
    CHECK_NEAR(m->albedo[2], 0, 1e-9);
    sss_scene_free(&s);
}

/* kdsubsurface: the coefficients' rho_eff under the (eta, g) table reproduces the reflectance, and
 * 1 / sigma_t the mean free path (PBRT-v3 SubsurfaceFromDiffuse). */
static void test_reflectance(void)
{
    sss_scene s;
    sss_error err = {0};
    if (load("{" SPHERE ", \"material\": {\"type\": \"subsurface\", \"reflectance\": [0.8, 0.5, 0.2],"
             " \"mfp\": [1, 2, 0.5], \"eta\": 1.4}},"
             "{" SPHERE ", \"material\": {\"type\": \"subsurface\", \"reflectance\": [0.3, 0.6, 0.9],"
             " \"mfp\": 0.25}}",
             &s, &err) != SSS_OK)
        return;
    const double refl[2][3] = {{0.8, 0.5, 0.2}, {0.3, 0.6, 0.9}}, mfp[2][3] = {{1, 2, 0.5}, {0.25, 0.25, 0.25}};
    for (int o = 0; o < 2; o++) {
        const sss_scene_material *m = &s.objects[o].material;
        CHECK(m->source == SSS_SUBSURFACE_REFLECTANCE && m->table);
        for (int i = 0; i < 3; i++) {
            double st = m->optical.sigma_a[i] + m->optical.sigma_s[i];
            CHECK_REL(1 / st, mfp[o][i], 1e-12);
            CHECK_NEAR(sss_pbd_rho_eff(m->table, m->optical.sigma_s[i] / st), refl[o][i], 1e-3);
            CHECK(m->albedo[i] == refl[o][i]);
        }
    }
    CHECK(s.objects[0].material.optical.eta == 1.4 && s.objects[0].material.table->eta == 1.4);
    CHECK(s.objects[1].material.optical.g == 0 && s.objects[1].material.table->g == 0);
    sss_scene_free(&s);
    /* docs/scene-format.md lists only reflectance, mfp and eta for this form: g is an error naming the field. */
    const char *with_g = "{\"camera\": {\"position\": [0, 0, 5], \"look_at\": [0, 0, 0]}, \"objects\": [{" SPHERE
                         ", \"material\": {\"type\": \"subsurface\", \"reflectance\": [0.3, 0.6, 0.9],"
                         " \"mfp\": 0.25, \"g\": 0.3}}]}";
    sss_scene_load_desc desc = {SSS_SCENE_SKIP_MESHES};
    CHECK(sss_scene_parse(with_g, strlen(with_g), SCENES, "material.json", &desc, &s, &err) ==
          SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "objects[0].material.g") != NULL, "%s", err.message);
}

static void test_table_cache(void)
{
    sss_scene s;
    sss_error err = {0};
    if (load("{" SPHERE ", \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin1\"}},"
             "{" SPHERE ", \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.2, 0.2, 0.2]}},"
             "{" SPHERE ", \"material\": {\"type\": \"subsurface\", \"medium\": \"Apple\", \"eta\": 1.33}},"
             "{" SPHERE ", \"material\": {\"type\": \"subsurface\", \"medium\": \"Apple\", \"eta\": 1.5}},"
             "{" SPHERE ", \"material\": {\"type\": \"subsurface\", \"reflectance\": [0.5, 0.5, 0.5], \"mfp\": 1}}",
             &s, &err) != SSS_OK)
        return;
    /* (1.33, 0) shared by objects 0, 2, 4; (1.5, 0) for object 3; none for the diffuse one. */
    CHECK(s.table_count == 2);
    CHECK(s.objects[0].material.table == s.objects[2].material.table);
    CHECK(s.objects[0].material.table == s.objects[4].material.table);
    CHECK(s.objects[3].material.table != s.objects[0].material.table);
    CHECK(s.objects[1].material.table == NULL);
    CHECK(sss_scene_find_table(&s, 1.5, 0) == s.objects[3].material.table);
    CHECK(sss_scene_find_table(&s, 1.4, 0) == NULL);
    sss_scene_free(&s);
}

static void test_extras(void)
{
    sss_scene s;
    sss_error err = {0};
    if (load("{" SPHERE ", \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin2\", \"texture\": "
             "\"assets/albedo.png\", \"specular\": {\"roughness\": 0.3}, \"profile\": {\"artist\": {\"s\": 0.5}}}},"
             "{" SPHERE ", \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin2\", \"profile\": {\"artist\":"
             " {\"s\": 2, \"near\": [0.1, 0.2, 0.3], \"far\": [0.4, 0.5, 0.6], \"w\": 0.25}}}}",
             &s, &err) != SSS_OK)
        return;
    const sss_scene_material *m = &s.objects[0].material;
    CHECK(m->texture && strcmp(m->texture, SCENES "/assets/albedo.png") == 0);
    CHECK(m->has_specular && m->roughness == 0.3);
    CHECK(m->profile == SSS_SCENE_PROFILE_ARTIST && sss_scene_material_profile_model(m) == SSS_PROFILE_PBD);
    /* Defaults of the artist profile: Jimenez et al. 2019's production preset (docs/physics.md §2.4). */
    CHECK(m->artist.s == 0.5 && m->artist.w == 0.65);
    CHECK(m->artist.near[0] == 0.22 && m->artist.near[1] == 0.07 && m->artist.near[2] == 0.07);
    CHECK(m->artist.far[0] == 1.0 && m->artist.far[1] == 0.3 && m->artist.far[2] == 0.15);
    m = &s.objects[1].material;
    CHECK(m->artist.s == 2 && m->artist.w == 0.25 && m->artist.near[2] == 0.3 && m->artist.far[0] == 0.4);
    CHECK(!m->has_specular && m->texture == NULL);
    CHECK(strcmp(sss_scene_profile_name(m->profile), "artist") == 0);
    sss_scene_free(&s);

    /* eta beyond the physics module's accepted range: refused, naming the field. */
    char json[512];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 0, 5], \"look_at\": [0, 0, 0]}, \"objects\": [{" SPHERE
             ", \"material\": {\"type\": \"subsurface\", \"medium\": \"Apple\", \"eta\": %.17g}}]}",
             SSS_ETA_MAX + 0.01);
    sss_result res = sss_scene_parse(json, strlen(json), SCENES, "eta.json", NULL, &s, &err);
    CHECK_MSG(res != SSS_OK && strstr(err.message, "eta.json: objects[0].material.eta: "), "%s", err.message);
    CHECK(s.tables == NULL && s.objects == NULL);
}

int main(void)
{
    test_medium();
    test_coefficients();
    test_reflectance();
    test_table_cache();
    test_extras();
    return CHECK_DONE();
}
