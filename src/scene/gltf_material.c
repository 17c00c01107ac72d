/* glTF materials -> sss materials (sss/gltf.h lists the mapping; docs/gltf.md explains it).
 * Sources: KHR_materials_volume (thicknessFactor, attenuationDistance, attenuationColor: "the color
 * that white light turns into due to absorption when reaching the attenuation distance", so
 * c = exp(-sigma_t d); thicknessFactor: the path length rasterizers assume through the volume);
 * KHR_materials_volume_scatter (multiscatterColor, the multiple-scattering albedo, and
 * scatterAnisotropy, the Henyey-Greenstein g; rho_ss = 1 - s^2); KHR_materials_scatter (the draft of
 * KhronosGroup/glTF pull request 2579 that replaces volume_scatter and diffuse_transmission:
 * scatterStrengthFactor scales multiscatterColorFactor, rho_ss = (1 - s^2) / (1 - g s^2));
 * KHR_materials_ior (ior, default 1.5); KHR_materials_diffuse_transmission (diffuseTransmissionFactor
 * and diffuseTransmissionColorFactor: with a volume and no scattering extension, mapped to the nearest
 * subsurface medium, below). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scene/gltf_internal.h"
#include "sss/material.h"

/* Both scatter extensions write the multiple-scattering albedo rho of Kulla & Conty (2017, "Revisiting
 * Physically Based Shading at Imageworks", slide on the albedo inversion): rho = (1 - s)(1 - 0.139 s) /
 * (1 + 1.17 s), inverted as s = 4.09712 + 4.20863 rho - sqrt(9.59217 + 41.6808 rho + 17.7126 rho^2),
 * whose constants are those of the smaller root of 0.139 s^2 - (1.139 + 1.17 rho) s + (1 - rho) = 0,
 * rounded (1.139 / 0.278 = 4.097122..., ...). The root itself, written 2c / (b + sqrt(b^2 - 4ac)) to keep
 * its precision near rho = 1: s = 1 at rho = 0 and 0 at rho = 1 exactly. rho in [0, 1] (checked by the
 * caller: outside, s leaves [0, 1]). */
static double albedo_root(double rho)
{
    double a = 0.139, b = 1.139 + 1.17 * rho, cc = 1.0 - rho;
    return 2.0 * cc / (b + sqrt(b * b - 4.0 * a * cc));
}

/* The single-scattering albedo of rho: KHR_materials_volume_scatter's rho_ss = 1 - s^2 (its text has
 * no g); KHR_materials_scatter's rho_ss = (1 - s^2) / (1 - g s^2) (with g: s^2 is then one minus the
 * reduced albedo, (1 - alpha) / (1 - g alpha)). */
static double single_scatter_albedo(double rho, double g, int with_g)
{
    double s2 = albedo_root(rho) * albedo_root(rho);
    return with_g ? (1.0 - s2) / (1.0 - g * s2) : 1.0 - s2;
}

/* images[source] decoded into c->out->images[source] (once; PNG or JPEG by mimeType, from a bufferView
 * or a data: URI). */
static sss_result embedded_image(gltf_ctx *c, const cJSON *image, long source)
{
    char p[48];
    snprintf(p, sizeof p, "images[%ld]", source);
    size_t count = gltf_count(c, GLTF_IMAGES);
    if (!c->out->images) {
        if (!(c->out->images = calloc(count, sizeof *c->out->images)))
            return gltf_fail(c, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", p);
        c->out->image_count = count;
    }
    if (c->out->images[source].pixels) return SSS_OK;
    const cJSON *uri = gltf_get(image, "uri"), *mime = gltf_get(image, "mimeType");
    long view = -1;
    sss_result res = gltf_int(c, image, p, "bufferView", 0, -1, 0, 1L << 30, &view);
    if (res != SSS_OK) return res;
    const char *type = cJSON_IsString(mime) ? mime->valuestring : cJSON_IsString(uri) ? uri->valuestring : "";
    const char *ext = strstr(type, "image/png") ? "png" : strstr(type, "image/jpeg") ? "jpg" : NULL;
    if (!ext) return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s.mimeType: not image/png or image/jpeg", p);
    unsigned char *owned = NULL;
    const unsigned char *bytes = NULL;
    size_t size = 0;
    char use[64];
    snprintf(use, sizeof use, "%s.%s", p, view >= 0 ? "bufferView" : "uri");
    if (view >= 0)
        res = gltf_buffer_view(c, view, use, &bytes, &size);
    else if ((res = gltf_data_uri(c, uri->valuestring, use, &owned, &size)) == SSS_OK)
        bytes = owned;
    char name[96];
    snprintf(name, sizeof name, "%s.%s", p, ext); /* the decoder takes the format from the name */
    sss_error inner = {0};
    if (res == SSS_OK && (res = sss_image_decode(bytes, size, name, &c->out->images[source], &inner)) != SSS_OK)
        gltf_fail(c, res, "%s", inner.message);
    if (res == SSS_OK && sss_image_count_nonfinite(&c->out->images[source])) /* no 8-bit image has any */
        res = gltf_fail(c, SSS_ERROR_NUMERIC, "%s: holds NaN or Inf", p);
    free(owned);
    return res;
}

/* The baseColorTexture's image: an external file's resolved path in *file, or an embedded image
 * decoded into c->out->images[*image]. */
static sss_result base_color_texture(gltf_ctx *c, const cJSON *pbr, const char *path, char **file, int *image)
{
    const cJSON *info = gltf_get(pbr, "baseColorTexture");
    long tex = 0, source = 0, texcoord = 0;
    sss_result res;
    *file = NULL;
    *image = -1;
    if (!info) return SSS_OK;
    char p[192];
    snprintf(p, sizeof p, "%s.pbrMetallicRoughness.baseColorTexture", path);
    if ((res = gltf_int(c, info, p, "index", 1, 0, 0, 1L << 30, &tex)) != SSS_OK ||
        (res = gltf_int(c, info, p, "texCoord", 0, 0, 0, 1L << 30, &texcoord)) != SSS_OK)
        return res;
    if (texcoord != 0) return SSS_OK; /* only TEXCOORD_0 is imported */
    const cJSON *t = gltf_item(c, GLTF_TEXTURES, tex);
    if (!t) return gltf_fail(c, SSS_ERROR_PARSE, "%s.index: texture %ld does not exist", p, tex);
    snprintf(p, sizeof p, "textures[%ld]", tex);
    if ((res = gltf_int(c, t, p, "source", 0, -1, 0, 1L << 30, &source)) != SSS_OK) return res;
    if (source < 0) return SSS_OK;
    const cJSON *img = gltf_item(c, GLTF_IMAGES, source);
    if (!img) return gltf_fail(c, SSS_ERROR_PARSE, "%s.source: image %ld does not exist", p, source);
    const cJSON *uri = gltf_get(img, "uri");
    if (!cJSON_IsString(uri) || strncmp(uri->valuestring, "data:", 5) == 0) {
        if ((res = embedded_image(c, img, source)) == SSS_OK) *image = (int)source;
        return res;
    }
    char *resolved = gltf_resolve_uri(c->base_dir, uri->valuestring);
    struct stat st;
    if (!resolved || stat(resolved, &st) != 0 || !S_ISREG(st.st_mode)) {
        free(resolved);
        return gltf_fail(c, SSS_ERROR_IO, "images[%ld].uri: \"%s\" is not a readable file", source,
                         uri->valuestring);
    }
    /* absolute, so that a scene written anywhere (or loaded from memory) finds it */
    *file = realpath(resolved, NULL);
    free(resolved);
    if (!*file) return gltf_fail(c, SSS_ERROR_OUT_OF_MEMORY, "images[%ld].uri: out of memory", source);
    return SSS_OK;
}

/* The note of a material whose scattering extension has no medium to act on. */
#define THIN_NOTE                                                                                                    \
    " without an attenuating volume (KHR_materials_volume with thicknessFactor > 0 and a finite "                    \
    "attenuationDistance): imported as diffuse"

/* The extension that gives a material its scattering, in the order one is preferred to another:
 * KHR_materials_scatter replaces the two others (and excludes diffuse transmission). */
enum { SCATTER_KHR, SCATTER_VOLUME, SCATTER_DIFFUSE_TRANSMISSION, SCATTER_KINDS };
static const char *const scatter_names[SCATTER_KINDS] = {
    "KHR_materials_scatter", "KHR_materials_volume_scatter", "KHR_materials_diffuse_transmission"};

/* A scattering extension's values (validated against its schema): weight (scatterStrengthFactor,
 * diffuseTransmissionFactor; 1 for volume_scatter), colour (multiscatterColor, diffuseTransmissionColor)
 * and g (scatterAnisotropy; 0 for diffuse transmission). */
typedef struct scatter_ext {
    int kind;
    double weight, color[3], g;
    char path[160]; /* "materials[i].extensions.<name>" */
} scatter_ext;

/* v[0..n) in [0, 1] (the schemas' colours and factors): refused outside, never clamped (clamping turned
 * multiscatterColor 1.5 into sigma_a = 0 and -0.1 into sigma_s = 0). */
static sss_result check_unit(gltf_ctx *c, const char *path, const char *key, const double *v, int n)
{
    for (int k = 0; k < n; k++) {
        if (v[k] >= 0 && v[k] <= 1) continue;
        if (n == 1) return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.%s: %g is outside [0, 1]", path, key, v[k]);
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.%s[%d]: %g is outside [0, 1]", path, key, k, v[k]);
    }
    return SSS_OK;
}

/* e's members by its kind; keys[0] the weight ("" when the extension has none), keys[1] the colour,
 * keys[2] g, alias a second name of the weight or colour (drafts renamed them). */
static sss_result read_scatter_ext(gltf_ctx *c, const cJSON *obj, scatter_ext *e)
{
    static const double white[3] = {1, 1, 1}, black[3] = {0, 0, 0};
    static const struct {
        const char *weight, *weight_alias, *color, *color_alias, *g;
        double weight_def;
        const double *color_def;
    } keys[] = {
        /* the draft's README names the weight scatterStrengthFactor, its schema file scatterFactor */
        [SCATTER_KHR] = {"scatterStrengthFactor", "scatterFactor", "multiscatterColorFactor", NULL,
                         "scatterAnisotropy", 0, white},
        /* an earlier draft (and some sample assets) name the colour multiscatterColorFactor */
        [SCATTER_VOLUME] = {NULL, NULL, "multiscatterColor", "multiscatterColorFactor", "scatterAnisotropy", 1,
                            black},
        [SCATTER_DIFFUSE_TRANSMISSION] = {"diffuseTransmissionFactor", NULL, "diffuseTransmissionColorFactor", NULL,
                                          NULL, 0, white},
    };
    const char *weight = keys[e->kind].weight, *color = keys[e->kind].color;
    if (weight && !gltf_get(obj, weight) && keys[e->kind].weight_alias && gltf_get(obj, keys[e->kind].weight_alias))
        weight = keys[e->kind].weight_alias;
    if (!gltf_get(obj, color) && keys[e->kind].color_alias && gltf_get(obj, keys[e->kind].color_alias))
        color = keys[e->kind].color_alias;
    e->weight = keys[e->kind].weight_def;
    e->g = 0;
    sss_result res;
    if ((res = gltf_object(c, obj, e->path)) != SSS_OK ||
        (weight && (res = gltf_number(c, obj, e->path, weight, e->weight, &e->weight)) != SSS_OK) ||
        (res = gltf_vec(c, obj, e->path, color, 3, keys[e->kind].color_def, e->color)) != SSS_OK ||
        (keys[e->kind].g && (res = gltf_number(c, obj, e->path, keys[e->kind].g, 0.0, &e->g)) != SSS_OK) ||
        (weight && (res = check_unit(c, e->path, weight, &e->weight, 1)) != SSS_OK) ||
        (res = check_unit(c, e->path, color, e->color, 3)) != SSS_OK)
        return res;
    if (!(e->g > -1 && e->g < 1))
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.scatterAnisotropy: %g is outside (-1, 1)", e->path, e->g);
    return SSS_OK;
}

/* sigma_t = -ln(c) / d per channel of KHR_materials_volume (vp: its JSON path), within what sss renders. */
static sss_result volume_extinction(gltf_ctx *c, const cJSON *volume, const char *vp, double d, double sigma_t[3])
{
    static const double white[3] = {1, 1, 1};
    double color[3];
    sss_result res = gltf_vec(c, volume, vp, "attenuationColor", 3, white, color);
    for (int k = 0; res == SSS_OK && k < 3; k++) {
        sigma_t[k] = -log(color[k]) / d; /* c = exp(-sigma_t d) */
        if (!(color[k] > 0 && color[k] <= 1) || !(sigma_t[k] >= SSS_SIGMA_T_MIN && sigma_t[k] <= SSS_SIGMA_T_MAX))
            res = gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT,
                            "%s.attenuationColor[%d]: %g with attenuationDistance %g gives the extinction %g per "
                            "unit, outside the [%g, %g] sss renders",
                            vp, k, color[k], d, sigma_t[k], SSS_SIGMA_T_MIN, SSS_SIGMA_T_MAX);
    }
    return res;
}

/* The multiple-scattering albedo each extension gives, per channel. KHR_materials_scatter: its colour
 * scaled by scatterStrength ("rho_ms* = scatterStrength x rho_ms"). Diffuse transmission with a volume
 * and no scattering extension (light crosses the surface diffusely, then the volume only absorbs): the
 * fraction of the light reaching the base layer that the asset sends back out, taken as the medium's
 * multiple-scattering albedo (Kulla & Conty's "perceived colour" of a dense medium), with the path
 * length rasterizers assume (KHR_materials_volume's thicknessFactor t):
 *     rho = (1 - f) baseColor + f diffuseTransmissionColor exp(-sigma_t t),
 * reflected diffusely by the share 1 - f, transmitted by f through t units of the volume. */
static void multiscatter_albedo(const scatter_ext *e, const double base[3], const double sigma_t[3],
                                double thickness, double rho[3])
{
    for (int k = 0; k < 3; k++) {
        if (e->kind == SCATTER_DIFFUSE_TRANSMISSION)
            rho[k] = (1 - e->weight) * base[k] + e->weight * e->color[k] * exp(-sigma_t[k] * thickness);
        else
            rho[k] = e->weight * e->color[k];
    }
}

/* sigma_a, sigma_s, g, eta of a material with an attenuating volume and the scattering extension e. */
static sss_result subsurface(gltf_ctx *c, const cJSON *ext, const char *path, const scatter_ext *e,
                             const double base[3], double thickness, double d, sss_gltf_material *m)
{
    const cJSON *volume = gltf_get(ext, "KHR_materials_volume"), *ior = gltf_get(ext, "KHR_materials_ior");
    char vp[192], ip[192];
    snprintf(vp, sizeof vp, "%s.extensions.KHR_materials_volume", path);
    snprintf(ip, sizeof ip, "%s.extensions.KHR_materials_ior", path);
    double sigma_t[3], rho[3];
    sss_result res;
    if ((res = volume_extinction(c, volume, vp, d, sigma_t)) != SSS_OK ||
        (res = gltf_number(c, ior, ip, "ior", 1.5, &m->eta)) != SSS_OK)
        return res;
    if (!(m->eta >= SSS_ETA_MIN && m->eta <= SSS_ETA_MAX))
        return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s.ior: %g is outside the [%g, %g] sss accepts", ip, m->eta,
                         SSS_ETA_MIN, SSS_ETA_MAX);
    multiscatter_albedo(e, base, sigma_t, thickness, rho);
    m->g = e->g;
    for (int k = 0; k < 3; k++) {
        double alpha = single_scatter_albedo(rho[k], m->g, e->kind == SCATTER_KHR);
        m->sigma_s[k] = alpha * sigma_t[k];
        m->sigma_a[k] = sigma_t[k] - m->sigma_s[k];
    }
    m->subsurface = 1;
    if (e->kind == SCATTER_DIFFUSE_TRANSMISSION)
        m->note = "KHR_materials_volume + KHR_materials_diffuse_transmission without a scattering extension: "
                  "mapped to the nearest subsurface material (docs/gltf.md)";
    return SSS_OK;
}

/* The scattering extension of ext that applies (SCATTER_KINDS: none), read and validated into e. */
static sss_result scatter_extension(gltf_ctx *c, const cJSON *ext, const char *path, scatter_ext *e)
{
    for (e->kind = 0; e->kind < SCATTER_KINDS; e->kind++) {
        const cJSON *obj = gltf_get(ext, scatter_names[e->kind]);
        if (!obj) continue;
        snprintf(e->path, sizeof e->path, "%s.extensions.%s", path, scatter_names[e->kind]);
        return read_scatter_ext(c, obj, e);
    }
    return SSS_OK;
}

sss_result gltf_material(gltf_ctx *c, long index, sss_gltf_material *m)
{
    static const double white[4] = {1, 1, 1, 1};
    memset(m, 0, sizeof *m);
    m->image = -1;
    char path[64];
    snprintf(path, sizeof path, "materials[%ld]", index);
    for (int k = 0; k < 3; k++) m->albedo[k] = 1.0; /* the default material: white, diffuse */
    if (index < 0) return SSS_OK;
    const cJSON *mat = gltf_item(c, GLTF_MATERIALS, index);
    if (!mat) return gltf_fail(c, SSS_ERROR_PARSE, "%s: does not exist", path);
    const cJSON *pbr = gltf_get(mat, "pbrMetallicRoughness"), *ext = gltf_get(mat, "extensions");
    sss_result res;
    double base[4];
    char pp[192];
    snprintf(pp, sizeof pp, "%s.pbrMetallicRoughness", path);
    if ((res = gltf_object(c, mat, path)) != SSS_OK || (res = gltf_object(c, pbr, pp)) != SSS_OK ||
        (res = gltf_vec(c, pbr, pp, "baseColorFactor", 4, white, base)) != SSS_OK ||
        (res = check_unit(c, pp, "baseColorFactor", base, 4)) != SSS_OK) /* alpha is not used, but as invalid */
        return res;
    for (int k = 0; k < 3; k++) m->albedo[k] = base[k];
    const cJSON *volume = gltf_get(ext, "KHR_materials_volume");
    double thickness = 0, distance = INFINITY;
    snprintf(pp, sizeof pp, "%s.extensions.KHR_materials_volume", path);
    if ((res = gltf_number(c, volume, pp, "thicknessFactor", 0.0, &thickness)) != SSS_OK ||
        (res = gltf_number(c, volume, pp, "attenuationDistance", INFINITY, &distance)) != SSS_OK)
        return res;
    /* The schema's ranges (thicknessFactor >= 0, attenuationDistance > 0), also where the values end
     * up unused: a negative thickness is not a thin wall. */
    if (!(thickness >= 0))
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.thicknessFactor: %g is negative", pp, thickness);
    if (!(distance > 0))
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.attenuationDistance: %g is not > 0", pp, distance);
    scatter_ext e = {0};
    if ((res = scatter_extension(c, ext, path, &e)) != SSS_OK) return res;
    /* No scattering extension, or one switched off (weight 0): a plain or clear (absorbing only)
     * material, which no sss renderer draws as such: diffuse. */
    if (e.kind == SCATTER_KINDS || !(e.weight > 0)) return SSS_OK;
    /* thicknessFactor 0 means a thin wall: "all volumetric effects are disabled"; an infinite
     * attenuationDistance a volume without extinction. Neither has a medium: diffuse, said in the note. */
    static const char *const thin[SCATTER_KINDS] = {
        "KHR_materials_scatter" THIN_NOTE, "KHR_materials_volume_scatter" THIN_NOTE,
        "KHR_materials_diffuse_transmission" THIN_NOTE};
    if (!volume || !(thickness > 0) || isinf(distance)) {
        m->note = thin[e.kind];
        return SSS_OK;
    }
    if ((res = subsurface(c, ext, path, &e, base, thickness, distance, m)) != SSS_OK) return res;
    return pbr ? base_color_texture(c, pbr, path, &m->texture, &m->image) : SSS_OK;
}

void gltf_material_free(sss_gltf_material *m)
{
    free(m->texture);
    m->texture = NULL;
    m->image = -1;
}
