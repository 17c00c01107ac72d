/* Object transforms of docs/scene-format.md: M = T R S (scale, then rotate about an axis, then translate). */
#include <math.h>
#include <string.h>

#include "sss/scene.h"

static const double SCENE_PI = 3.14159265358979323846;

void sss_transform_identity(sss_transform *t)
{
    memset(t, 0, sizeof *t);
    t->rotate[1] = 1;
    t->scale[0] = t->scale[1] = t->scale[2] = 1;
    for (int i = 0; i < 4; i++) t->matrix[5 * i] = 1;
    for (int i = 0; i < 3; i++) t->normal_matrix[4 * i] = 1;
}

sss_result sss_transform_update(sss_transform *t, sss_error *err)
{
    for (int i = 0; i < 3; i++)
        if (!isfinite(t->translate[i]) || !isfinite(t->scale[i]) || t->scale[i] == 0 || !isfinite(t->rotate[i]))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "transform: translate, scale (non-zero) and rotate must be finite");
    for (int i = 0; i < 3; i++)
        if (!(fabs(t->scale[i]) >= SSS_SCENE_SCALE_MIN && fabs(t->scale[i]) <= SSS_SCENE_SCALE_MAX))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "transform: scale %.3g is out of range: |scale| in [%g, %g]",
                                 t->scale[i], SSS_SCENE_SCALE_MIN, SSS_SCENE_SCALE_MAX);
    if (!isfinite(t->rotate[3]))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "transform: rotation angle must be finite");
    double ax = t->rotate[0], ay = t->rotate[1], az = t->rotate[2];
    double n = hypot(hypot(ax, ay), az); /* hypot: no overflow for axes near DBL_MAX */
    if (!(n > 0) || !isfinite(n))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "transform: rotation axis must be non-zero");
    ax /= n;
    ay /= n;
    az /= n;
    /* Rodrigues: R = cos I + sin [a]x + (1 - cos) a a^T, right-handed about the axis. */
    /* fmod first: exact in degrees, and 1e308 degrees would overflow to inf radians. */
    double th = fmod(t->rotate[3], 360.0) * SCENE_PI / 180.0, c = cos(th), s = sin(th), k = 1 - c;
    double R[3][3] = {{c + k * ax * ax, k * ax * ay - s * az, k * ax * az + s * ay},
                      {k * ay * ax + s * az, c + k * ay * ay, k * ay * az - s * ax},
                      {k * az * ax - s * ay, k * az * ay + s * ax, c + k * az * az}};
    for (int r = 0; r < 3; r++) {
        for (int col = 0; col < 3; col++) {
            t->matrix[4 * r + col] = R[r][col] * t->scale[col];        /* R S */
            t->normal_matrix[3 * r + col] = R[r][col] / t->scale[col]; /* (R S)^-T = R S^-1 */
        }
        t->matrix[4 * r + 3] = t->translate[r];
    }
    t->matrix[12] = t->matrix[13] = t->matrix[14] = 0;
    t->matrix[15] = 1;
    return SSS_OK;
}

void sss_transform_point(const double m[16], const double p[3], double out[3])
{
    double q[3];
    for (int r = 0; r < 3; r++) q[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
    memcpy(out, q, sizeof q);
}

void sss_transform_normal(const double nm[9], const double n[3], double out[3])
{
    double q[3];
    for (int r = 0; r < 3; r++) q[r] = nm[3 * r] * n[0] + nm[3 * r + 1] * n[1] + nm[3 * r + 2] * n[2];
    double len = hypot(hypot(q[0], q[1]), q[2]);
    if (len > 0 && isfinite(len))
        for (int i = 0; i < 3; i++) q[i] /= len;
    else
        q[0] = q[1] = q[2] = 0;
    memcpy(out, q, sizeof q);
}
