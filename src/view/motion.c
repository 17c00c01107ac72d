/* view/motion.c — the viewer's camera (orbit, pan, zoom around look_at) and the light moved around the
 * object (a rotation about the vertical axis through the camera's look_at). Plain vector algebra on the
 * scene structs; the renderer reads the camera every frame. */
#include <math.h>
#include <string.h>

#include "core/vecmath.h"
#include "view/view_internal.h"

static void sub3(const double a[3], const double b[3], double o[3])
{
    for (int k = 0; k < 3; k++) o[k] = a[k] - b[k];
}
/* Rodrigues: v rotated by angle (radians) about the unit axis k (right-handed). */
static void rotate_about(const double v[3], const double k[3], double angle, double out[3])
{
    double c = cos(angle), s = sin(angle), kxv[3];
    v3_cross(k, v, kxv);
    double kv = v3_dot(k, v);
    double t[3];
    for (int i = 0; i < 3; i++) t[i] = v[i] * c + kxv[i] * s + k[i] * kv * (1.0 - c);
    memcpy(out, t, sizeof t);
}

static void camera_up(const sss_camera *cam, double up[3])
{
    memcpy(up, cam->up, sizeof cam->up);
    if (!v3_unit(up)) up[0] = 0.0, up[1] = 1.0, up[2] = 0.0;
}

void view_orbit(sss_camera *cam, double azimuth_deg, double elevation_deg)
{
    double up[3], off[3];
    camera_up(cam, up);
    sub3(cam->position, cam->look_at, off);
    double dist = v3_len(off);
    if (!(dist > 0.0) || !isfinite(dist)) return;
    rotate_about(off, up, azimuth_deg * M_PI / 180.0, off);
    /* Elevation: the polar angle between the offset and up, clamped away from the poles so the view
     * direction never becomes parallel to up (the camera basis would be undefined). */
    double polar = acos(fmax(-1.0, fmin(1.0, v3_dot(off, up) / dist)));
    double target = polar - elevation_deg * M_PI / 180.0;
    double lo = M_PI / 180.0, hi = M_PI - lo;
    target = fmin(hi, fmax(lo, target));
    double axis[3];
    v3_cross(up, off, axis); /* horizontal, perpendicular to the offset */
    if (v3_unit(axis)) rotate_about(off, axis, target - polar, off);
    for (int k = 0; k < 3; k++) cam->position[k] = cam->look_at[k] + off[k];
}

void view_pan(sss_camera *cam, double dx, double dy, int width, int height)
{
    double fwd[3], up[3], right[3], u[3];
    sub3(cam->look_at, cam->position, fwd);
    double dist = v3_len(fwd);
    if (!v3_unit(fwd) || width < 1 || height < 1) return;
    camera_up(cam, up);
    v3_cross(fwd, up, right);
    if (!v3_unit(right)) return;
    v3_cross(right, fwd, u);
    /* World size of one pixel at look_at's depth: the shorter axis spans 2 tan(fov / 2) (sss/scene.h). */
    int shorter = width < height ? width : height;
    double px = dist * 2.0 * tan(cam->fov * M_PI / 360.0) / shorter;
    for (int k = 0; k < 3; k++) {
        double d = (-right[k] * dx + u[k] * dy) * px;
        cam->position[k] += d;
        cam->look_at[k] += d;
    }
}

void view_zoom(sss_camera *cam, double factor)
{
    if (!(factor > 0.0) || !isfinite(factor)) return;
    double off[3];
    sub3(cam->position, cam->look_at, off);
    double dist = v3_len(off), next = dist * factor;
    if (!(dist > 0.0) || !isfinite(next) || next < 1e-9) return;
    for (int k = 0; k < 3; k++) cam->position[k] = cam->look_at[k] + off[k] * (next / dist);
}

static void rotate_point_y(double p[3], const double pivot[3], double angle)
{
    static const double y[3] = {0.0, 1.0, 0.0};
    double q[3];
    sub3(p, pivot, q);
    rotate_about(q, y, angle, q);
    for (int k = 0; k < 3; k++) p[k] = pivot[k] + q[k];
}

static void rotate_vector_y(double v[3], double angle)
{
    static const double y[3] = {0.0, 1.0, 0.0};
    rotate_about(v, y, angle, v);
}

void view_rotate_light_y(sss_light *light, const double pivot[3], double degrees)
{
    double a = degrees * M_PI / 180.0;
    switch (light->type) {
    case SSS_LIGHT_POINT: rotate_point_y(light->position, pivot, a); break;
    case SSS_LIGHT_SPOT:
        rotate_point_y(light->position, pivot, a);
        rotate_point_y(light->look_at, pivot, a);
        break;
    case SSS_LIGHT_DIRECTIONAL: rotate_vector_y(light->direction, a); break;
    case SSS_LIGHT_AREA:
        rotate_point_y(light->center, pivot, a);
        rotate_vector_y(light->u, a);
        rotate_vector_y(light->v, a);
        break;
    case SSS_LIGHT_ENVIRONMENT:
        /* rotate_y is a right-handed rotation of the map about +y (sss/reference.h) */
        light->rotate_y = fmod(light->rotate_y + degrees, 360.0);
        break;
    }
}
