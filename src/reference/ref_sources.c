/* reference/ref_sources.c — the surface's light sources by where the camera sees them (ref_internal.h):
 * off the image, facing away, hidden behind nearer surface, seen at a grazing angle, or seen. A
 * diagnostic for the real-time techniques, which gather the seen part in screen space and need the
 * rest from elsewhere (Maisch & Ropinski 2020, section 5: splats "for the parts not visible on screen"). */
#include "reference/ref_internal.h"

ref_source_class ref_source_classify(const ref_ctx *ctx, const double p[3], const double ng[3], const double ns[3],
                                     double grazing)
{
    const ref_camera *cam = &ctx->cam;
    double d[3] = {p[0] - cam->origin[0], p[1] - cam->origin[1], p[2] - cam->origin[2]};
    double depth = v3_dot(d, cam->forward);
    if (!(depth > 0.0)) return REF_SOURCE_OFF;
    /* the image spans |right . d| <= depth tan_half[0] and |up . d| <= depth tan_half[1] (ref_camera_ray) */
    if (!(fabs(v3_dot(d, cam->right)) < depth * cam->tan_half[0]) ||
        !(fabs(v3_dot(d, cam->up)) < depth * cam->tan_half[1]))
        return REF_SOURCE_OFF;
    double dist = v3_len(d);
    double v[3] = {-d[0] / dist, -d[1] / dist, -d[2] / dist}; /* towards the camera */
    if (v3_dot(ng, v) < 0.0) return REF_SOURCE_BACK;
    /* Hidden when the camera's ray meets other surface before it; the relative margin keeps the
     * point's own triangle (met at dist, to float precision) out. */
    double dir[3] = {-v[0], -v[1], -v[2]};
    if (ref_occluded(ctx, cam->origin, dir, dist * (1.0 - 1e-4))) return REF_SOURCE_HIDDEN;
    return fabs(v3_dot(ns, v)) < grazing ? REF_SOURCE_GRAZING : REF_SOURCE_VISIBLE;
}

int ref_source_kept(const ref_ctx *ctx, const double p[3], const double ng[3], const double ns[3])
{
    unsigned keep = ctx->mask.keep;
    if (keep == 0 || (keep & REF_SOURCE_ALL) == REF_SOURCE_ALL) return 1;
    return (keep & ref_source_classify(ctx, p, ng, ns, ctx->mask.grazing)) != 0;
}

sss_result ref_source_mask_check(const ref_source_mask *mask, const sss_reference_desc *desc, sss_error *err)
{
    if (!desc || desc->bounces != 1)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "reference: a source mask needs bounces = 1 (the single-event integral)");
    if ((mask->keep & ~(unsigned)REF_SOURCE_ALL) || !(mask->grazing >= 0.0 && mask->grazing <= 1.0))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "reference: source mask: classes 0x%x (at most 0x1f), grazing %g (0..1)", mask->keep,
                             mask->grazing);
    return SSS_OK;
}
