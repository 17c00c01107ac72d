/* Materials of docs/scene-format.md: parsing (with the three mutually exclusive `subsurface` parameterisations)
 * and resolution to per-scene-unit coefficients (docs/physics.md §2.2, 2.3; PBRT-v3 subsurface/kdsubsurface). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "scene/scene_internal.h"

/* Jimenez et al. 2019, Table 2, "production" preset (docs/physics.md §2.4): the defaults of an artist profile. */
static const double artist_near_default[3] = {0.22, 0.07, 0.07};
static const double artist_far_default[3] = {1.0, 0.3, 0.15};
static const double artist_w_default = 0.65;

static sss_result parse_artist(scene_ctx *c, const cJSON *item, sss_artist_params *a)
{
    jr *r = &c->r;
    static const char *const fields[] = {"s", "near", "far", "w"};
    sss_result res;
    if ((res = jr_expect_object(r, item)) != SSS_OK) return res;
    if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
    if ((res = jr_number(r, item, "s", 1, 0, &a->s)) != SSS_OK) return res;
    if ((res = jr_range(r, "s", a->s, 0, 1, INFINITY, 0)) != SSS_OK) return res;
    if ((res = jr_vec(r, item, "near", 0, artist_near_default, 3, a->near, NULL)) != SSS_OK) return res;
    if ((res = jr_range_vec(r, "near", a->near, 3, 0, 1, 1, 0)) != SSS_OK) return res;
    if ((res = jr_vec(r, item, "far", 0, artist_far_default, 3, a->far, NULL)) != SSS_OK) return res;
    if ((res = jr_range_vec(r, "far", a->far, 3, 0, 1, 1, 0)) != SSS_OK) return res;
    if ((res = jr_number(r, item, "w", 0, artist_w_default, &a->w)) != SSS_OK) return res;
    return jr_range(r, "w", a->w, 0, 0, 1, 0);
}

static sss_result parse_profile(scene_ctx *c, const cJSON *obj, sss_scene_material *m)
{
    jr *r = &c->r;
    const cJSON *item = jr_get(obj, "profile");
    m->profile = SSS_SCENE_PROFILE_PBD;
    if (!item) return SSS_OK;
    size_t mark = jr_enter_key(r, "profile");
    sss_result res = SSS_OK;
    if (cJSON_IsString(item)) {
        if (strcasecmp(item->valuestring, "pbd") == 0) m->profile = SSS_SCENE_PROFILE_PBD;
        else if (strcasecmp(item->valuestring, "dipole") == 0) m->profile = SSS_SCENE_PROFILE_DIPOLE;
        else res = jr_fail(r, SSS_ERROR_INVALID_ARGUMENT,
                           "unknown profile \"%s\" (expected \"pbd\", \"dipole\" or {\"artist\": {...}})",
                           item->valuestring);
    } else if (cJSON_IsObject(item)) {
        static const char *const fields[] = {"artist"};
        if ((res = jr_check_fields(r, item, fields, 1)) == SSS_OK && (res = jr_require(r, item, "artist")) == SSS_OK) {
            size_t mark2 = jr_enter_key(r, "artist");
            res = parse_artist(c, jr_get(item, "artist"), &m->artist);
            jr_leave(r, mark2);
            m->profile = SSS_SCENE_PROFILE_ARTIST;
        }
    } else {
        res = jr_fail(r, SSS_ERROR_PARSE, "expected \"pbd\", \"dipole\" or {\"artist\": {...}}");
    }
    jr_leave(r, mark);
    return res;
}

static sss_result unknown_medium(jr *r, const char *name)
{
    char list[256] = "";
    size_t at = 0;
    for (size_t i = 0; i < sss_measured_medium_count() && at < sizeof list; i++) {
        int w = snprintf(list + at, sizeof list - at, "%s%s", i ? ", " : "", sss_measured_medium_at(i)->name);
        if (w < 0) break;
        at += (size_t)w;
    }
    return jr_fail_key(r, "medium", SSS_ERROR_INVALID_ARGUMENT, "unknown medium \"%s\" (known: %s)", name, list);
}

static sss_result parse_subsurface(scene_ctx *c, const cJSON *obj, sss_scene_material *m)
{
    jr *r = &c->r;
    static const char *const fields[] = {"type", "medium", "sigma_a", "sigma_s", "reflectance", "mfp", "scale",
                                         "eta", "g", "profile", "texture", "specular"};
    sss_result res;
    if ((res = jr_check_fields(r, obj, fields, SCENE_COUNT(fields))) != SSS_OK) return res;

    int has_medium = jr_get(obj, "medium") != NULL;
    int has_coef = jr_get(obj, "sigma_a") || jr_get(obj, "sigma_s");
    int has_refl = jr_get(obj, "reflectance") || jr_get(obj, "mfp");
    if (has_medium + has_coef + has_refl == 0)
        return jr_fail(r, SSS_ERROR_PARSE, "a subsurface material needs one of: medium, sigma_a + sigma_s, "
                                           "reflectance + mfp");
    if (has_medium + has_coef + has_refl > 1)
        return jr_fail(r, SSS_ERROR_PARSE, "medium, sigma_a + sigma_s and reflectance + mfp are mutually "
                                           "exclusive (got %s%s%s)",
                       has_medium ? "medium " : "", has_coef ? "sigma_a/sigma_s " : "",
                       has_refl ? "reflectance/mfp" : "");

    double eta = 0, g = 0;
    if ((res = jr_number(r, obj, "eta", 0, 1.33, &eta)) != SSS_OK) return res;
    if ((res = jr_range(r, "eta", eta, SSS_ETA_MIN, 0, SSS_ETA_MAX, 0)) != SSS_OK) return res;
    m->optical.eta = eta;
    m->scale = 1;

    if (has_medium) {
        m->source = SSS_SUBSURFACE_MEDIUM;
        const char *name = NULL;
        if ((res = jr_string(r, obj, "medium", 1, &name)) != SSS_OK) return res;
        m->medium = sss_measured_medium_find(name);
        if (!m->medium) return unknown_medium(r, name);
        if (jr_get(obj, "g"))
            return jr_fail_key(r, "g", SSS_ERROR_INVALID_ARGUMENT,
                               "not allowed with medium (measured media are reduced coefficients, g = 0)");
    } else if (has_coef) {
        m->source = SSS_SUBSURFACE_COEFFICIENTS;
        if ((res = jr_vec(r, obj, "sigma_a", 1, NULL, 3, m->input_sigma_a, NULL)) != SSS_OK) return res;
        if ((res = jr_range_vec(r, "sigma_a", m->input_sigma_a, 3, 0, 0, INFINITY, 0)) != SSS_OK) return res;
        if ((res = jr_vec(r, obj, "sigma_s", 1, NULL, 3, m->input_sigma_s, NULL)) != SSS_OK) return res;
        if ((res = jr_range_vec(r, "sigma_s", m->input_sigma_s, 3, 0, 0, INFINITY, 0)) != SSS_OK) return res;
        for (int i = 0; i < 3; i++)
            if (!(m->input_sigma_a[i] + m->input_sigma_s[i] > 0))
                return jr_fail(r, SSS_ERROR_INVALID_ARGUMENT,
                               "sigma_a + sigma_s is 0 in channel %d (the medium must attenuate)", i);
    } else {
        m->source = SSS_SUBSURFACE_REFLECTANCE;
        if ((res = jr_vec(r, obj, "reflectance", 1, NULL, 3, m->reflectance, NULL)) != SSS_OK) return res;
        if ((res = jr_range_vec(r, "reflectance", m->reflectance, 3, 0, 1, 1, 1)) != SSS_OK) return res;
        if ((res = jr_number_or_vec(r, obj, "mfp", 1, 0, 3, m->mfp, NULL)) != SSS_OK) return res;
        if ((res = jr_range_vec(r, "mfp", m->mfp, 3, 0, 1, INFINITY, 0)) != SSS_OK) return res;
        if (jr_get(obj, "scale"))
            return jr_fail_key(r, "scale", SSS_ERROR_INVALID_ARGUMENT,
                               "not used with reflectance + mfp (mfp is in scene units)");
        /* docs/scene-format.md lists reflectance, mfp and eta for this form (PBRT's kdsubsurface without g). */
        if (jr_get(obj, "g"))
            return jr_fail_key(r, "g", SSS_ERROR_INVALID_ARGUMENT,
                               "not allowed with reflectance + mfp (docs/scene-format.md: only explicit coefficients take g)");
    }
    if (m->source != SSS_SUBSURFACE_REFLECTANCE) {
        if ((res = jr_number(r, obj, "scale", 0, 1, &m->scale)) != SSS_OK) return res;
        if ((res = jr_range(r, "scale", m->scale, 0, 1, INFINITY, 0)) != SSS_OK) return res;
    }
    if (m->source == SSS_SUBSURFACE_COEFFICIENTS) {
        if ((res = jr_number(r, obj, "g", 0, 0, &g)) != SSS_OK) return res;
        if ((res = jr_range(r, "g", g, -1, 1, 1, 1)) != SSS_OK) return res;
    }
    m->optical.g = g;

    if ((res = parse_profile(c, obj, m)) != SSS_OK) return res;
    if ((res = scene_file_field(c, obj, "texture", 0, &m->texture)) != SSS_OK) return res;
    const cJSON *spec = jr_get(obj, "specular");
    if (spec) {
        static const char *const spec_fields[] = {"roughness"};
        size_t mark = jr_enter_key(r, "specular");
        if ((res = jr_expect_object(r, spec)) == SSS_OK &&
            (res = jr_check_fields(r, spec, spec_fields, 1)) == SSS_OK &&
            (res = jr_number(r, spec, "roughness", 1, 0, &m->roughness)) == SSS_OK)
            res = jr_range(r, "roughness", m->roughness, 0, 0, 1, 0);
        jr_leave(r, mark);
        if (res != SSS_OK) return res;
        m->has_specular = 1;
    }
    return SSS_OK;
}

sss_result scene_parse_material(scene_ctx *c, const cJSON *item, sss_scene_material *m)
{
    jr *r = &c->r;
    sss_result res;
    if ((res = jr_expect_object(r, item)) != SSS_OK) return res;
    const char *type = NULL;
    if ((res = jr_string(r, item, "type", 1, &type)) != SSS_OK) return res;
    if (strcmp(type, "subsurface") == 0) {
        m->type = SSS_SCENE_MATERIAL_SUBSURFACE;
        return parse_subsurface(c, item, m);
    }
    if (strcmp(type, "diffuse") == 0) {
        static const char *const fields[] = {"type", "reflectance"};
        m->type = SSS_SCENE_MATERIAL_DIFFUSE;
        if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
        if ((res = jr_vec(r, item, "reflectance", 1, NULL, 3, m->albedo, NULL)) != SSS_OK) return res;
        return jr_range_vec(r, "reflectance", m->albedo, 3, 0, 0, 1, 0);
    }
    return jr_fail_key(r, "type", SSS_ERROR_INVALID_ARGUMENT,
                       "unknown material type \"%s\" (expected \"subsurface\" or \"diffuse\")", type);
}

sss_result scene_resolve_material(scene_ctx *c, sss_scene_material *m, const sss_pbd_table *table)
{
    if (m->type != SSS_SCENE_MATERIAL_SUBSURFACE) return SSS_OK;
    sss_error *err = c->r.err;
    double eta = m->optical.eta, g = m->optical.g;
    sss_result res;
    switch (m->source) {
    case SSS_SUBSURFACE_MEDIUM:
        res = sss_material_from_medium(m->medium->name, m->scale, eta, &m->optical, err);
        break;
    case SSS_SUBSURFACE_COEFFICIENTS:
        res = sss_material_from_coefficients(m->input_sigma_a, m->input_sigma_s, m->scale, eta, g, &m->optical,
                                             err);
        break;
    default:
        res = sss_material_from_reflectance(table, m->reflectance, m->mfp, eta, &m->optical, err);
        m->optical.g = g; /* the table was built for this g: PBRT's kdsubsurface keeps its g */
        break;
    }
    if (res != SSS_OK) return jr_prefix(&c->r, NULL, res);
    if ((res = sss_material_validate(&m->optical, err)) != SSS_OK) return jr_prefix(&c->r, NULL, res);
    m->table = table;
    res = sss_profile_init(&m->rd, sss_scene_material_profile_model(m), &m->optical, table, err);
    if (res != SSS_OK) return jr_prefix(&c->r, NULL, res);
    /* The display albedo: the plane integral of the PBD profile (docs/physics.md §2.2, rho_eff), exactly the
     * requested reflectance for kdsubsurface. */
    for (int i = 0; i < 3; i++) {
        if (m->source == SSS_SUBSURFACE_REFLECTANCE) {
            m->albedo[i] = m->reflectance[i];
        } else {
            double st = m->optical.sigma_a[i] + m->optical.sigma_s[i];
            m->albedo[i] = sss_pbd_rho_eff(table, st > 0 ? m->optical.sigma_s[i] / st : 0);
        }
    }
    return SSS_OK;
}

sss_profile_model sss_scene_material_profile_model(const sss_scene_material *m)
{
    return m->profile == SSS_SCENE_PROFILE_DIPOLE ? SSS_PROFILE_DIPOLE : SSS_PROFILE_PBD;
}

void scene_material_free(sss_scene_material *m)
{
    free(m->texture);
    m->texture = NULL;
}
