/* The shared animation definition (formulas in sss/scene.h; the GL renderer's GLSL mirrors them). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/vecmath.h"
#include "sss/scene.h"

static const double PI = 3.14159265358979323846;

/* The deformed point and the Jacobian's columns a = dp'/dx, b = dp'/dy, c = dp'/dz at p. */
static void deform(const sss_animation *an, const float lo[3], const float hi[3], double t, const float pf[3],
                   double out[3], double a[3], double b[3], double c[3])
{
    double p[3] = {pf[0], pf[1], pf[2]};
    memcpy(out, p, sizeof p);
    a[0] = 1, a[1] = 0, a[2] = 0;
    b[0] = 0, b[1] = 1, b[2] = 0;
    c[0] = 0, c[1] = 0, c[2] = 1;
    if (!an || an->type == SSS_ANIMATION_NONE || !(an->period > 0)) return;
    double H = (double)hi[1] - lo[1], W = (double)hi[0] - lo[0];
    double h = H > 0 ? (p[1] - lo[1]) / H : 0;
    double s = sin(2 * PI * t / an->period);
    double A = an->amplitude, rad = A * PI / 180.0;

    switch (an->type) {
    case SSS_ANIMATION_TWIST: {
        double cx = 0.5 * ((double)lo[0] + hi[0]), cz = 0.5 * ((double)lo[2] + hi[2]);
        double th = rad * h * s, ct = cos(th), st = sin(th);
        double qx = p[0] - cx, qz = p[2] - cz;
        double th_y = H > 0 ? rad * s / H : 0;
        out[0] = cx + qx * ct + qz * st;
        out[2] = cz - qx * st + qz * ct;
        a[0] = ct, a[1] = 0, a[2] = -st;
        c[0] = st, c[1] = 0, c[2] = ct;
        b[0] = th_y * (-qx * st + qz * ct);
        b[1] = 1;
        b[2] = th_y * (-qx * ct - qz * st);
        break;
    }
    case SSS_ANIMATION_BEND: {
        double cx = 0.5 * ((double)lo[0] + hi[0]);
        double phi = rad * h * h * s, cp = cos(phi), sp = sin(phi);
        double qx = p[0] - cx, qy = p[1] - lo[1];
        double phi_y = H > 0 ? 2 * rad * s * h / H : 0;
        out[0] = cx + qx * cp - qy * sp;
        out[1] = lo[1] + qx * sp + qy * cp;
        a[0] = cp, a[1] = sp, a[2] = 0;
        b[0] = -sp + phi_y * (-qx * sp - qy * cp);
        b[1] = cp + phi_y * (qx * cp - qy * sp);
        b[2] = 0;
        break;
    }
    case SSS_ANIMATION_WAVE: {
        double k = W > 0 ? 2 * PI / W : 0;
        double arg = k * (p[0] - lo[0]) + 2 * PI * t / an->period;
        out[1] = p[1] + A * sin(arg);
        a[1] = A * k * cos(arg);
        break;
    }
    default: break;
    }
}

void sss_animation_deform_point(const sss_animation *anim, const float bounds_min[3], const float bounds_max[3],
                                double t, const float p[3], float out[3])
{
    double q[3], a[3], b[3], c[3];
    deform(anim, bounds_min, bounds_max, t, p, q, a, b, c);
    for (int i = 0; i < 3; i++) out[i] = (float)q[i];
}

void sss_animation_deform_normal(const sss_animation *anim, const float bounds_min[3], const float bounds_max[3],
                                 double t, const float p[3], const float n[3], float out[3])
{
    double q[3], a[3], b[3], c[3], bc[3], ca[3], ab[3];
    deform(anim, bounds_min, bounds_max, t, p, q, a, b, c);
    /* cof(J) n = det(J) J^-T n, sign-corrected: the normal of the deformed surface. */
    v3_cross(b, c, bc);
    v3_cross(c, a, ca);
    v3_cross(a, b, ab);
    double det = a[0] * bc[0] + a[1] * bc[1] + a[2] * bc[2];
    double sg = det < 0 ? -1.0 : 1.0, m[3];
    for (int i = 0; i < 3; i++) m[i] = sg * (bc[i] * n[0] + ca[i] * n[1] + ab[i] * n[2]);
    double len = hypot(hypot(m[0], m[1]), m[2]);
    for (int i = 0; i < 3; i++) out[i] = len > 0 && isfinite(len) ? (float)(m[i] / len) : n[i];
}

sss_result sss_animation_validate(const sss_animation *anim, sss_error *err)
{
    if (anim->type == SSS_ANIMATION_NONE) return SSS_OK;
    if (anim->type != SSS_ANIMATION_TWIST && anim->type != SSS_ANIMATION_BEND && anim->type != SSS_ANIMATION_WAVE)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "animation: unknown type %d", (int)anim->type);
    if (!isfinite(anim->amplitude))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "animation: amplitude must be finite");
    if (!(anim->period > 0) || !isfinite(anim->period))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "animation: period %g must be > 0", anim->period);
    return SSS_OK;
}
