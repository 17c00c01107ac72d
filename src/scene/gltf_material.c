/* glTF materials -> sss materials (sss/gltf.h lists the mapping; docs/gltf.md explains it).
 * Sources: KHR_materials_volume (thicknessFactor, attenuationDistance, attenuationColor: "the color
 * that white light turns into due to absorption when reaching the attenuation distance", so
 * c = exp(-sigma_t d)); KHR_materials_volume_scatter (multiscatterColor, the multiple-scattering
 * albedo, and scatterAnisotropy, the Henyey-Greenstein g; its albedo inversion); KHR_materials_ior
 * (ior, default 1.5); KHR_materials_diffuse_transmission (only marks the surface as letting light
 * in diffusely; its factors are not used). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scene/gltf_internal.h"
#include "sss/material.h"

/* KHR_materials_volume_scatter: rho_ms = (1 - s)(1 - 0.139 s) / (1 + 1.17 s) with
 * s^2 = (1 - alpha) / (1 - g alpha). rho (1 + 1.17 s) = (1 - s)(1 - 0.139 s) is the quadratic
 * 0.139 s^2 - (1.139 + 1.17 rho) s + (1 - rho) = 0, whose smaller root is the one in [0, 1]
 * (rho = 0 gives s = 1, rho = 1 gives s = 0); written as 2c / (b + sqrt(b^2 - 4ac)) to keep its
 * precision near rho = 1. Then alpha = (1 - s^2) / (1 - g s^2). rho in [0, 1] (checked by the caller:
 * outside, s leaves [0, 1] and alpha [0, 1]). */
static double single_scatter_albedo(double rho, double g)
{
    double a = 0.139, b = 1.139 + 1.17 * rho, cc = 1.0 - rho;
    double s = 2.0 * cc / (b + sqrt(b * b - 4.0 * a * cc));
    double s2 = s * s;
    return (1.0 - s2) / (1.0 - g * s2);
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

/* sigma_a, sigma_s, g, eta of a material with KHR_materials_volume (+ _scatter, _ior). */
static sss_result subsurface(gltf_ctx *c, const cJSON *ext, const char *path, sss_gltf_material *m)
{
    static const double white[3] = {1, 1, 1}, black[3] = {0, 0, 0};
    const cJSON *volume = gltf_get(ext, "KHR_materials_volume"), *scatter = gltf_get(ext, "KHR_materials_volume_scatter");
    const cJSON *ior = gltf_get(ext, "KHR_materials_ior");
    char vp[192], sp[192], ip[192];
    snprintf(vp, sizeof vp, "%s.extensions.KHR_materials_volume", path);
    snprintf(sp, sizeof sp, "%s.extensions.KHR_materials_volume_scatter", path);
    snprintf(ip, sizeof ip, "%s.extensions.KHR_materials_ior", path);
    double d = 0, color[3], rho[3];
    sss_result res;
    if ((res = gltf_number(c, volume, vp, "attenuationDistance", INFINITY, &d)) != SSS_OK ||
        (res = gltf_vec(c, volume, vp, "attenuationColor", 3, white, color)) != SSS_OK ||
        (res = gltf_vec(c, scatter, sp, "multiscatterColor", 3, black, rho)) != SSS_OK ||
        /* an older draft (and some sample assets) name it multiscatterColorFactor */
        (res = gltf_vec(c, scatter, sp, "multiscatterColorFactor", 3, NULL, rho)) != SSS_OK ||
        (res = gltf_number(c, scatter, sp, "scatterAnisotropy", 0.0, &m->g)) != SSS_OK ||
        (res = gltf_number(c, ior, ip, "ior", 1.5, &m->eta)) != SSS_OK)
        return res;
    /* the albedo of the extension's schema is a colour in [0, 1]: refused outside, not clamped (which
     * turned 1.5 into sigma_a = 0 and -0.1 into sigma_s = 0) */
    const char *rho_key = gltf_get(scatter, "multiscatterColorFactor") ? "multiscatterColorFactor"
                                                                        : "multiscatterColor";
    for (int k = 0; k < 3; k++)
        if (!(rho[k] >= 0 && rho[k] <= 1))
            return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.%s[%d]: %g is outside [0, 1]", sp, rho_key, k, rho[k]);
    if (!(m->g > -1 && m->g < 1))
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.scatterAnisotropy: %g is outside (-1, 1)", sp, m->g);
    if (!(m->eta >= SSS_ETA_MIN && m->eta <= SSS_ETA_MAX))
        return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s.ior: %g is outside the [%g, %g] sss accepts", ip, m->eta,
                         SSS_ETA_MIN, SSS_ETA_MAX);
    for (int k = 0; k < 3; k++) {
        double sigma_t = -log(color[k]) / d; /* c = exp(-sigma_t d) */
        if (!(color[k] > 0 && color[k] <= 1) || !(sigma_t >= SSS_SIGMA_T_MIN && sigma_t <= SSS_SIGMA_T_MAX))
            return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT,
                             "%s.attenuationColor[%d]: %g with attenuationDistance %g gives the extinction %g per "
                             "unit, outside the [%g, %g] sss renders",
                             vp, k, color[k], d, sigma_t, SSS_SIGMA_T_MIN, SSS_SIGMA_T_MAX);
        double alpha = single_scatter_albedo(rho[k], m->g);
        m->sigma_s[k] = alpha * sigma_t;
        m->sigma_a[k] = sigma_t - m->sigma_s[k];
    }
    m->subsurface = 1;
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
        (res = gltf_vec(c, pbr, pp, "baseColorFactor", 4, white, base)) != SSS_OK)
        return res;
    for (int k = 0; k < 4; k++) { /* alpha (k = 3) is not used, but as invalid */
        if (!(base[k] >= 0 && base[k] <= 1))
            return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.baseColorFactor[%d]: %g is outside [0, 1]", pp, k, base[k]);
        if (k < 3) m->albedo[k] = base[k];
    }
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
    /* thicknessFactor 0 means a thin wall: "all volumetric effects are disabled". */
    if (!volume || !(thickness > 0) || isinf(distance) || !gltf_get(ext, "KHR_materials_volume_scatter"))
        return SSS_OK;
    if ((res = subsurface(c, ext, path, m)) != SSS_OK) return res;
    return pbr ? base_color_texture(c, pbr, path, &m->texture, &m->image) : SSS_OK;
}

void gltf_material_free(sss_gltf_material *m)
{
    free(m->texture);
    m->texture = NULL;
    m->image = -1;
}
