/* gl/registry.c — the techniques, selected by name, and the shared parameters' table. A new technique
 * is a folder src/gl/techniques/<name>/ defining a `const gl_technique gl_technique_<name>`
 * (technique.h) plus one line in the table below. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/core/gl_core.h"
#include "gl/technique.h"

extern const gl_technique gl_technique_maisch2020;
extern const gl_technique gl_technique_local;
extern const gl_technique gl_technique_sam;
extern const gl_technique gl_technique_mertens2003, gl_technique_dss, gl_technique_chen2012;
extern const gl_technique gl_technique_ssss, gl_technique_ssss_gauss6, gl_technique_ssss_svd, gl_technique_screen;
extern const gl_technique gl_technique_burley;

static const gl_technique *const techniques[] = {
    &gl_technique_maisch2020,
    &gl_technique_local,
    &gl_technique_sam,
    &gl_technique_mertens2003, &gl_technique_dss, &gl_technique_chen2012,
    &gl_technique_ssss, &gl_technique_ssss_gauss6, &gl_technique_ssss_svd, &gl_technique_screen,
    &gl_technique_burley,
};
#define TECHNIQUE_COUNT ((int)(sizeof techniques / sizeof techniques[0]))

int sss_gl_technique_count(void) { return TECHNIQUE_COUNT; }

const sss_gl_technique_info *sss_gl_technique_at(int index)
{
    if (index < 0 || index >= TECHNIQUE_COUNT) return NULL;
    return &techniques[index]->info;
}

const gl_technique *gl_technique_lookup(const char *name)
{
    if (!name) return NULL;
    for (int i = 0; i < TECHNIQUE_COUNT; i++)
        if (strcmp(techniques[i]->info.name, name) == 0) return techniques[i];
    return NULL;
}

const sss_gl_technique_info *sss_gl_technique_find(const char *name)
{
    const gl_technique *t = gl_technique_lookup(name);
    return t ? &t->info : NULL;
}

/* Shared parameters; indices are the GL_P_* enum. */
static const sss_gl_param_info shared_params[GL_P_SHARED_COUNT] = {
    [GL_P_SHADOW_2D_SIZE] = {"shadow_size", SSS_GL_PARAM_INT, 2048, 16, 16384,
                             "texels per side of the 2D shadow maps (spot and directional lights)"},
    [GL_P_SHADOW_CUBE_SIZE] = {"shadow_cube_size", SSS_GL_PARAM_INT, 1024, 16, 8192,
                               "texels per side of each face of the point lights' cube shadow maps"},
    [GL_P_SHADOW_VPL_SIZE] = {"shadow_vpl_size", SSS_GL_PARAM_INT, 256, 16, 4096,
                              "shadow map size of the virtual lights of area and environment lights"},
    [GL_P_SHADOW_BIAS] = {"shadow_bias", SSS_GL_PARAM_FLOAT, 1.5, 0, 64,
                          "shadow lookups offset along the normal and in depth, in shadow-map texels"},
    [GL_P_AREA_SAMPLES] = {"area_samples", SSS_GL_PARAM_INT, 16, 1, 1024,
                           "virtual point lights per area light (rounded to n x n cell centres)"},
    [GL_P_ENV_LIGHTS] = {"env_lights", SSS_GL_PARAM_INT, 32, 1, 1024,
                         "directional lights per environment map (median cut; rounded down to 2^k)"},
    [GL_P_LUT_SIZE] = {"lut_size", SSS_GL_PARAM_INT, 512, 16, 4096,
                       "texels per axis of the kernel LUT R'_d(r, A) (Maisch & Ropinski 2020, section 7.1: 512)"},
    [GL_P_LUT_AXES] = {"lut_sqrt_axes", SSS_GL_PARAM_BOOL, 1, 0, 1,
                       "1: LUT texels at squares of even steps (dense near r = 0, A = 0); 0: linear (Maisch & Ropinski 2020)"},
    [GL_P_LUT_CUTOFF] = {"lut_cutoff", SSS_GL_PARAM_FLOAT, 1e-7, 1e-30, 1,
                         "r_max solves Q(r_max) = alpha' sigma_t' e^(-sigma_t' r_max) = cutoff (Maisch & Ropinski 2020, 7.1)"},
    [GL_P_LUT_ENERGY] = {"lut_energy", SSS_GL_PARAM_FLOAT, 0.999, 0, 0.999999,
                         "if > 0: r_max is at least the radius holding this fraction of R_d's integral"},
    [GL_P_LUT_LEVELS] = {"lut_levels", SSS_GL_PARAM_INT, 3, 1, 4,
                         "LUT cascade: level l spans r_max / 16^l, for small areas of short kernels"},
    [GL_P_SPLAT_ENERGY] = {"splat_energy", SSS_GL_PARAM_FLOAT, 0.99, 0.5, 1,
                           "splats reach the radius holding this fraction of R_d's integral (<= r_max)"},
    [GL_P_SPLAT_TRIANGLES] = {"splat_triangles", SSS_GL_PARAM_INT, 4096, 4, 16777216,
                              "triangle budget of simplified splat meshes (objects without splat_mesh)"},
    [GL_P_INTERREFLECTION] = {"interreflection", SSS_GL_PARAM_BOOL, 1, 0, 1,
                              "1: light between surfaces, one bounce from virtual point lights on every surface "
                              "(docs/interreflection.md); 0: light from the lights only, as the papers (preset=paper)"},
    [GL_P_INTERREFLECTION_SOURCES] = {"interreflection_sources", SSS_GL_PARAM_INT, 512, 8, 16384,
                                      "virtual point lights of the interreflection stage, shared out equally over the "
                                      "objects (by area when that gives an object fewer than 8)"},
    [GL_P_INTERREFLECTION_ROWS] = {"interreflection_rows", SSS_GL_PARAM_INT, 68, 1, 16384,
                                   "the stage gathers at every (height / rows)-th pixel in x and y (at least every "
                                   "pixel) and upsamples geometry-aware: every 8th at 540 rows"},
    [GL_P_INTERREFLECTION_BOUNCES] = {"interreflection_bounces", SSS_GL_PARAM_INT, 2, 1, 8,
                                      "bounces between surfaces: the sources lit again by the virtual lights before"},
    [GL_P_PRESET] = {"preset", SSS_GL_PARAM_INT, SSS_GL_PRESET_MEASURED, 0, 2,
                     "sets every parameter: 0 (measured) the defaults, best on the eval scenes; 1 (paper) the "
                     "published configuration (`--param preset=paper`); 2 (hdrp) Unity HDRP's defaults, burley "
                     "only; parameters given with it override it"},
};

const sss_gl_param_info *sss_gl_shared_params(int *count)
{
    if (count) *count = GL_P_SHARED_COUNT;
    return shared_params;
}

double sss_gl_paper_value(const char *technique, const char *param)
{
    const gl_technique *t = gl_technique_lookup(technique);
    if (!t || !param) return NAN;
    for (int i = 0; i < t->paper_count; i++)
        if (strcmp(t->paper[i].name, param) == 0) return t->paper[i].value;
    for (int i = 0; i < t->info.param_count; i++)
        if (strcmp(t->info.params[i].name, param) == 0) return t->info.params[i].default_value;
    for (int i = 0; i < GL_P_SHARED_COUNT; i++)
        if (strcmp(shared_params[i].name, param) == 0)
            return i == GL_P_PRESET ? SSS_GL_PRESET_PAPER : i == GL_P_INTERREFLECTION ? 0.0 : shared_params[i].default_value;
    return NAN;
}

sss_result sss_gl_param_parse(const char *name, const char *text, double *out, sss_error *err)
{
    if (!name || !text || !out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_param_parse: NULL argument");
    int is_preset = strcmp(name, shared_params[GL_P_PRESET].name) == 0;
    if (is_preset && strcmp(text, "paper") == 0) return *out = SSS_GL_PRESET_PAPER, SSS_OK;
    if (is_preset && strcmp(text, "measured") == 0) return *out = SSS_GL_PRESET_MEASURED, SSS_OK;
    if (is_preset && strcmp(text, "hdrp") == 0) return *out = SSS_GL_PRESET_HDRP, SSS_OK;
    char *end = NULL;
    double v = strtod(text, &end);
    if (end == text || *end != '\0' || !isfinite(v))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "parameter %s: '%s' is not a finite number%s", name, text,
                             is_preset ? " nor 'paper', 'measured' or 'hdrp'" : "");
    *out = v;
    return SSS_OK;
}
