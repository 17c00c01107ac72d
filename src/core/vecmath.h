/* core/vecmath.h — the small vector and matrix arithmetic the modules share (internal, not public API).
 *
 * Vectors are double[3]. Matrices are 4x4 in one of two layouts, named in each function:
 *  - row-major double[16] (m[4 * row + col]): the scene's transforms and cameras (sss/scene.h);
 *  - column-major float[16] (m[4 * col + row]): what OpenGL's uniforms take; right-handed, the camera
 *    looks down -z, clip depth in [-1, 1] unless said otherwise.
 * Everything is inline: the header is included by modules that link nothing else of each other. */
#ifndef SSS_CORE_VECMATH_H
#define SSS_CORE_VECMATH_H

#include <math.h>
#include <string.h>

static inline double v3_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* o = a x b (o may alias a or b). */
static inline void v3_cross(const double a[3], const double b[3], double o[3])
{
    double t[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(o, t, sizeof t);
}

static inline double v3_len(const double a[3]) { return sqrt(v3_dot(a, a)); }

/* Normalises in place; returns the old length (a zero vector stays zero). */
static inline double v3_normalize(double a[3])
{
    double l = v3_len(a);
    if (l > 0.0) a[0] /= l, a[1] /= l, a[2] /= l;
    return l;
}

/* Normalises in place when the length is positive and finite: 1; else 0 and a unchanged. */
static inline int v3_unit(double a[3])
{
    double l = v3_len(a);
    if (!(l > 0.0) || !isfinite(l)) return 0;
    a[0] /= l, a[1] /= l, a[2] /= l;
    return 1;
}

/* out = a b, row-major doubles (out may alias a or b). */
static inline void m4_mul_rows(const double a[16], const double b[16], double out[16])
{
    double r[16];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += a[4 * i + k] * b[4 * k + j];
            r[4 * i + j] = s;
        }
    memcpy(out, r, sizeof r);
}

/* A row-major double matrix as a column-major float one. */
static inline void m4_from_rows(const double m[16], float out[16])
{
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) out[4 * c + r] = (float)m[4 * r + c];
}

/* out = a b, column-major floats (out may alias a or b). */
static inline void m4_mul(const float a[16], const float b[16], float out[16])
{
    float t[16];
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++) s += a[4 * k + r] * b[4 * c + k];
            t[4 * c + r] = s;
        }
    memcpy(out, t, sizeof t);
}

/* The inverse of a column-major float matrix (cofactors in double); 0 when it is singular. */
static inline int m4_inverse(const float m[16], float out[16])
{
    double inv[16], a[16];
    for (int i = 0; i < 16; i++) a[i] = m[i];
    inv[0] = a[5] * a[10] * a[15] - a[5] * a[11] * a[14] - a[9] * a[6] * a[15] + a[9] * a[7] * a[14] +
             a[13] * a[6] * a[11] - a[13] * a[7] * a[10];
    inv[4] = -a[4] * a[10] * a[15] + a[4] * a[11] * a[14] + a[8] * a[6] * a[15] - a[8] * a[7] * a[14] -
             a[12] * a[6] * a[11] + a[12] * a[7] * a[10];
    inv[8] = a[4] * a[9] * a[15] - a[4] * a[11] * a[13] - a[8] * a[5] * a[15] + a[8] * a[7] * a[13] +
             a[12] * a[5] * a[11] - a[12] * a[7] * a[9];
    inv[12] = -a[4] * a[9] * a[14] + a[4] * a[10] * a[13] + a[8] * a[5] * a[14] - a[8] * a[6] * a[13] -
              a[12] * a[5] * a[10] + a[12] * a[6] * a[9];
    inv[1] = -a[1] * a[10] * a[15] + a[1] * a[11] * a[14] + a[9] * a[2] * a[15] - a[9] * a[3] * a[14] -
             a[13] * a[2] * a[11] + a[13] * a[3] * a[10];
    inv[5] = a[0] * a[10] * a[15] - a[0] * a[11] * a[14] - a[8] * a[2] * a[15] + a[8] * a[3] * a[14] +
             a[12] * a[2] * a[11] - a[12] * a[3] * a[10];
    inv[9] = -a[0] * a[9] * a[15] + a[0] * a[11] * a[13] + a[8] * a[1] * a[15] - a[8] * a[3] * a[13] -
             a[12] * a[1] * a[11] + a[12] * a[3] * a[9];
    inv[13] = a[0] * a[9] * a[14] - a[0] * a[10] * a[13] - a[8] * a[1] * a[14] + a[8] * a[2] * a[13] +
              a[12] * a[1] * a[10] - a[12] * a[2] * a[9];
    inv[2] = a[1] * a[6] * a[15] - a[1] * a[7] * a[14] - a[5] * a[2] * a[15] + a[5] * a[3] * a[14] +
             a[13] * a[2] * a[7] - a[13] * a[3] * a[6];
    inv[6] = -a[0] * a[6] * a[15] + a[0] * a[7] * a[14] + a[4] * a[2] * a[15] - a[4] * a[3] * a[14] -
             a[12] * a[2] * a[7] + a[12] * a[3] * a[6];
    inv[10] = a[0] * a[5] * a[15] - a[0] * a[7] * a[13] - a[4] * a[1] * a[15] + a[4] * a[3] * a[13] +
              a[12] * a[1] * a[7] - a[12] * a[3] * a[5];
    inv[14] = -a[0] * a[5] * a[14] + a[0] * a[6] * a[13] + a[4] * a[1] * a[14] - a[4] * a[2] * a[13] -
              a[12] * a[1] * a[6] + a[12] * a[2] * a[5];
    inv[3] = -a[1] * a[6] * a[11] + a[1] * a[7] * a[10] + a[5] * a[2] * a[11] - a[5] * a[3] * a[10] -
             a[9] * a[2] * a[7] + a[9] * a[3] * a[6];
    inv[7] = a[0] * a[6] * a[11] - a[0] * a[7] * a[10] - a[4] * a[2] * a[11] + a[4] * a[3] * a[10] +
             a[8] * a[2] * a[7] - a[8] * a[3] * a[6];
    inv[11] = -a[0] * a[5] * a[11] + a[0] * a[7] * a[9] + a[4] * a[1] * a[11] - a[4] * a[3] * a[9] -
              a[8] * a[1] * a[7] + a[8] * a[3] * a[5];
    inv[15] = a[0] * a[5] * a[10] - a[0] * a[6] * a[9] - a[4] * a[1] * a[10] + a[4] * a[2] * a[9] +
              a[8] * a[1] * a[6] - a[8] * a[2] * a[5];
    double det = a[0] * inv[0] + a[1] * inv[4] + a[2] * inv[8] + a[3] * inv[12];
    if (det == 0.0 || !isfinite(det)) return 0;
    for (int i = 0; i < 16; i++) out[i] = (float)(inv[i] / det);
    return 1;
}

/* Column-major view matrix of a camera at eye looking at target; `up` is the preferred up, replaced by
 * y (or x when the view axis is near y) when it lies within 2.6 degrees of the view axis. */
static inline void m4_look_at(const double eye[3], const double target[3], const double up_in[3], float m[16])
{
    double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]}, up[3] = {up_in[0], up_in[1], up_in[2]};
    double lf = v3_len(f), lu = v3_len(up), un[3];
    for (int k = 0; k < 3; k++) f[k] = lf > 0.0 ? f[k] * (1.0 / lf) : (k == 1);
    for (int k = 0; k < 3; k++) un[k] = lu > 0.0 ? up[k] * (1.0 / lu) : (k == 1);
    if (fabs(v3_dot(f, un)) > 0.999) {
        int y = fabs(f[1]) < 0.9;
        up[0] = y ? 0.0 : 1.0, up[1] = y ? 1.0 : 0.0, up[2] = 0.0;
    }
    double s[3], u[3];
    v3_cross(f, up, s);
    double ls = v3_len(s);
    for (int k = 0; k < 3; k++) s[k] = ls > 0.0 ? s[k] * (1.0 / ls) : (k == 1);
    v3_cross(s, f, u);
    float r[16] = {(float)s[0], (float)u[0], (float)-f[0], 0, (float)s[1], (float)u[1], (float)-f[1], 0,
                   (float)s[2], (float)u[2], (float)-f[2], 0, (float)-v3_dot(s, eye), (float)-v3_dot(u, eye),
                   (float)v3_dot(f, eye), 1};
    memcpy(m, r, sizeof r);
}

/* Column-major perspective projection: vertical field of view fovy (radians), near n, far f. */
static inline void m4_perspective(double fovy, double n, double f, float m[16])
{
    double t = 1.0 / tan(fovy / 2.0);
    memset(m, 0, 16 * sizeof(float));
    m[0] = (float)t;
    m[5] = (float)t;
    m[10] = (float)((f + n) / (n - f));
    m[11] = -1.0f;
    m[14] = (float)(2.0 * f * n / (n - f));
}

/* Column-major orthographic projection of the box [-half, half]^2 x [-f, -n]. */
static inline void m4_ortho(double half, double n, double f, float m[16])
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = (float)(1.0 / half);
    m[5] = (float)(1.0 / half);
    m[10] = (float)(-2.0 / (f - n));
    m[14] = (float)(-(f + n) / (f - n));
    m[15] = 1.0f;
}

#endif
