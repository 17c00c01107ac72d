/* gl/params.c — a technique's parameter values and the shared ones, by name: defaults, presets, checks.
 * No GL: sss_gl_tables_build resolves parameters here as the runtime does. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gl/runtime.h"

static int find_param(const sss_gl_param_info *params, int count, const char *name)
{
    for (int i = 0; i < count; i++)
        if (strcmp(params[i].name, name) == 0) return i;
    return -1;
}

static sss_result check_value(const sss_gl_param_info *p, double v, sss_error *err)
{
    if (!isfinite(v) || v < p->min_value || v > p->max_value)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "parameter %s = %g is outside [%g, %g] (%s)", p->name,
                             v, p->min_value, p->max_value, p->doc);
    if (p->type != SSS_GL_PARAM_FLOAT && v != floor(v))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "parameter %s must be %s, got %g", p->name,
                             p->type == SSS_GL_PARAM_BOOL ? "0 or 1" : "an integer", v);
    return SSS_OK;
}

/* Edit distance (insertions, deletions, substitutions) of two names, capped at 63 characters each. */
static int edit_distance(const char *a, const char *b)
{
    int n = (int)strnlen(a, 63), m = (int)strnlen(b, 63);
    int row[64];
    for (int j = 0; j <= m; j++) row[j] = j;
    for (int i = 1; i <= n; i++) {
        int diagonal = row[0];
        row[0] = i;
        for (int j = 1; j <= m; j++) {
            int up = row[j];
            int best = diagonal + (a[i - 1] != b[j - 1]);
            if (up + 1 < best) best = up + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            row[j] = best;
            diagonal = up;
        }
    }
    return row[m];
}

/* The known name closest to `name` in the technique's and the shared table. */
static const char *closest_param(const gl_technique *tech, const char *name)
{
    const char *best = NULL;
    int best_d = 1 << 30, n = 0;
    const sss_gl_param_info *shared = sss_gl_shared_params(&n);
    for (int t = 0; t < 2; t++) {
        const sss_gl_param_info *p = t ? shared : tech->info.params;
        int count = t ? n : tech->info.param_count;
        for (int i = 0; i < count; i++) {
            int d = edit_distance(name, p[i].name);
            if (d < best_d) best_d = d, best = p[i].name;
        }
    }
    return best;
}

/* An unknown name: the closest known one; the full lists are in `sss techniques` (too long for one
 * message). */
static sss_result unknown_param(const gl_technique *tech, const char *name, sss_error *err)
{
    const char *near = closest_param(tech, name);
    return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                         "technique %s has no parameter '%s'%s%s%s (`sss techniques` lists its %d parameters and "
                         "the shared ones)",
                         tech->info.name, name, near ? "; did you mean '" : "", near ? near : "", near ? "'?" : "",
                         tech->info.param_count);
}

/* preset: every parameter back to its default, then (paper) the technique's published values; hdrp is
 * the paper's values of a technique whose paper is HDRP's (tech->paper_is_hdrp: burley). */
static sss_result apply_preset(const gl_technique *tech, double *params, double *shared, double preset, sss_error *err)
{
    if (preset == SSS_GL_PRESET_HDRP && !tech->paper_is_hdrp)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "technique %s has no preset hdrp (Unity HDRP's defaults are burley's; use paper or "
                             "measured)",
                             tech->info.name);
    gl_params_defaults(&tech->info, params);
    int n = 0;
    const sss_gl_param_info *sp = sss_gl_shared_params(&n);
    for (int i = 0; i < n; i++) shared[i] = sp[i].default_value;
    shared[GL_P_PRESET] = preset;
    /* the papers and HDRP model light from the lights only */
    if (preset != SSS_GL_PRESET_MEASURED) shared[GL_P_INTERREFLECTION] = 0;
    sss_result res = SSS_OK;
    for (int i = 0; preset != SSS_GL_PRESET_MEASURED && i < tech->paper_count && res == SSS_OK; i++)
        res = gl_params_set_value(tech, params, shared, tech->paper[i].name, tech->paper[i].value, NULL, err);
    return res;
}

sss_result gl_params_set_value(const gl_technique *tech, double *params, double *shared, const char *name, double value,
                               int *scene_level, sss_error *err)
{
    if (!name) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "parameter name is NULL");
    int i = find_param(tech->info.params, tech->info.param_count, name);
    if (i >= 0) {
        sss_result res = check_value(&tech->info.params[i], value, err);
        if (res != SSS_OK) return res;
        params[i] = value;
        if (scene_level) *scene_level = 0;
        return SSS_OK;
    }
    int n = 0;
    const sss_gl_param_info *sp = sss_gl_shared_params(&n);
    i = find_param(sp, n, name);
    if (i < 0) return unknown_param(tech, name, err);
    sss_result res = check_value(&sp[i], value, err);
    if (res != SSS_OK) return res;
    /* read per frame: no new GPU scene */
    if (scene_level)
        *scene_level = i != GL_P_SHADOW_BIAS && i != GL_P_INTERREFLECTION && i != GL_P_INTERREFLECTION_ROWS &&
                       i != GL_P_INTERREFLECTION_BOUNCES;
    if (i == GL_P_PRESET) return apply_preset(tech, params, shared, value, err);
    shared[i] = value;
    return SSS_OK;
}

double gl_params_get(const gl_technique *tech, const double *params, const double *shared, const char *name)
{
    if (!tech || !name) return NAN;
    int i = find_param(tech->info.params, tech->info.param_count, name);
    if (i >= 0) return params[i];
    int n = 0;
    const sss_gl_param_info *sp = sss_gl_shared_params(&n);
    i = find_param(sp, n, name);
    return i >= 0 ? shared[i] : NAN;
}

sss_result gl_params_technique(const sss_scene *scene, const sss_gl_renderer_desc *desc, const gl_technique **out,
                               sss_error *err)
{
    const char *name = desc->technique ? desc->technique : scene->render.technique;
    if (!name || !name[0]) name = SSS_SCENE_DEFAULT_TECHNIQUE;
    *out = gl_technique_lookup(name);
    if (*out) return SSS_OK;
    char list[256] = "";
    size_t at = 0;
    for (int i = 0; i < sss_gl_technique_count() && at < sizeof list; i++)
        at += (size_t)snprintf(list + at, sizeof list - at, "%s%s", i ? ", " : "", sss_gl_technique_at(i)->name);
    if (desc->technique)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "unknown technique '%s' (known: %s)", name, list);
    return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: render.technique: unknown technique '%s' (known: %s)",
                         scene->name ? scene->name : "scene", name, list);
}

sss_result gl_params_from_desc(const gl_technique *tech, const sss_gl_renderer_desc *desc, double *params,
                               double *shared, sss_error *err)
{
    if (tech->info.param_count > GL_MAX_PARAMS)
        return sss_error_set(err, SSS_ERROR_LIMIT, "technique %s declares too many parameters", tech->info.name);
    gl_params_defaults(&tech->info, params);
    int n = 0;
    const sss_gl_param_info *sp = sss_gl_shared_params(&n);
    for (int i = 0; i < n; i++) shared[i] = sp[i].default_value;
    /* the preset first, so that the parameters given with it override it */
    sss_result res = SSS_OK;
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < desc->param_count && res == SSS_OK; i++) {
            int is_preset = desc->params[i].name && strcmp(desc->params[i].name, sp[GL_P_PRESET].name) == 0;
            if (is_preset == (pass == 0))
                res = gl_params_set_value(tech, params, shared, desc->params[i].name, desc->params[i].value, NULL, err);
        }
    return res;
}

void gl_params_defaults(const sss_gl_technique_info *info, double *values)
{
    for (int i = 0; i < info->param_count && i < GL_MAX_PARAMS; i++) values[i] = info->params[i].default_value;
}

void gl_params_set(const sss_gl_technique_info *info, double *values, const char *name, double value)
{
    for (int i = 0; i < info->param_count && i < GL_MAX_PARAMS; i++)
        if (strcmp(info->params[i].name, name) == 0) values[i] = value;
}
