/* The pinhole camera of docs/scene-format.md: basis, primary rays, projection, GL matrices. fov is along the
 * shorter image axis, as PBRT-v3's perspective camera (screen window [-aspect, aspect] x [-1, 1] for
 * wide images, [-1, 1] x [-1/aspect, 1/aspect] for tall ones, scaled by tan(fov / 2)). */
#include <math.h>
#include <string.h>

#include "core/vecmath.h"
#include "sss/scene.h"

static const double SCENE_PI = 3.14159265358979323846;

/* v3_unit with hypot: no overflow for components near DBL_MAX (camera positions are checked, not limited). */
static int normalize3(double v[3])
{
    double n = hypot(hypot(v[0], v[1]), v[2]); /* no overflow for components near DBL_MAX */
    if (!(n > 0) || !isfinite(n)) return 0;
    for (int i = 0; i < 3; i++) v[i] /= n;
    return 1;
}

static int finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

sss_result sss_camera_basis_init(const sss_camera *cam, sss_camera_basis *b, sss_error *err)
{
    if (!finite3(cam->position) || !finite3(cam->look_at) || !finite3(cam->up))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera: position, look_at and up must be finite");
    if (!(cam->fov >= SSS_SCENE_FOV_MIN && cam->fov < 180))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera: fov %g is out of range [%g, 180)", cam->fov,
                             SSS_SCENE_FOV_MIN);
    if (cam->width < 1 || cam->width > SSS_SCENE_MAX_IMAGE_SIZE || cam->height < 1 ||
        cam->height > SSS_SCENE_MAX_IMAGE_SIZE)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera: image size %d x %d is out of range 1..%d",
                             cam->width, cam->height, SSS_SCENE_MAX_IMAGE_SIZE);
    double f[3] = {cam->look_at[0] - cam->position[0], cam->look_at[1] - cam->position[1],
                   cam->look_at[2] - cam->position[2]};
    double up[3] = {cam->up[0], cam->up[1], cam->up[2]};
    if (!normalize3(f)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera: look_at equals position");
    if (!normalize3(up)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera: up is a zero vector");
    double right[3];
    v3_cross(f, up, right);
    if (!(hypot(hypot(right[0], right[1]), right[2]) > 1e-6) || !normalize3(right))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "camera: up is parallel to the view direction");
    memset(b, 0, sizeof *b);
    memcpy(b->origin, cam->position, sizeof b->origin);
    memcpy(b->forward, f, sizeof b->forward);
    memcpy(b->right, right, sizeof b->right);
    v3_cross(right, f, b->up);
    normalize3(b->up);
    double t = tan(cam->fov * SCENE_PI / 360.0);
    double aspect = (double)cam->width / cam->height;
    if (aspect >= 1) {
        b->tan_half[0] = t * aspect;
        b->tan_half[1] = t;
    } else {
        b->tan_half[0] = t;
        b->tan_half[1] = t / aspect;
    }
    b->width = cam->width;
    b->height = cam->height;
    return SSS_OK;
}

void sss_camera_ray(const sss_camera_basis *b, double px, double py, double origin[3], double direction[3])
{
    /* NDC in [-1, 1]: x to the right, y up (raster y runs down). */
    double sx = (2.0 * px / b->width - 1.0) * b->tan_half[0];
    double sy = (1.0 - 2.0 * py / b->height) * b->tan_half[1];
    double d[3];
    for (int i = 0; i < 3; i++) {
        d[i] = b->forward[i] + sx * b->right[i] + sy * b->up[i];
        origin[i] = b->origin[i];
    }
    normalize3(d);
    memcpy(direction, d, sizeof d);
}

int sss_camera_project(const sss_camera_basis *b, const double p[3], double raster[2], double *depth)
{
    double q[3] = {p[0] - b->origin[0], p[1] - b->origin[1], p[2] - b->origin[2]};
    double z = v3_dot(q, b->forward);
    if (depth) *depth = z;
    if (!(z > 0)) return 0;
    double sx = v3_dot(q, b->right) / z / b->tan_half[0], sy = v3_dot(q, b->up) / z / b->tan_half[1];
    raster[0] = (sx + 1.0) * 0.5 * b->width;
    raster[1] = (1.0 - sy) * 0.5 * b->height;
    return 1;
}

void sss_camera_view_matrix(const sss_camera_basis *b, double m[16])
{
    /* Rows: right, up, -forward; translation moves the camera to the origin. */
    const double *rows[3] = {b->right, b->up, b->forward};
    for (int r = 0; r < 3; r++) {
        double s = r == 2 ? -1.0 : 1.0;
        for (int c = 0; c < 3; c++) m[4 * r + c] = s * rows[r][c];
        m[4 * r + 3] = -s * v3_dot(rows[r], b->origin);
    }
    m[12] = m[13] = m[14] = 0;
    m[15] = 1;
}

void sss_camera_projection_matrix(const sss_camera_basis *b, double n, double f, double m[16])
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = 1.0 / b->tan_half[0];
    m[5] = 1.0 / b->tan_half[1];
    m[10] = -(f + n) / (f - n);
    m[11] = -2.0 * f * n / (f - n);
    m[14] = -1.0;
}
