/* gl/common/tsm.c — light-view G-buffers (see tsm.h). */
#include <math.h>
#include <string.h>

#include "core/vecmath.h"
#include "gl/common/tsm.h"

static void grow(double lo[3], double hi[3], const double p[3])
{
    for (int k = 0; k < 3; k++) {
        if (p[k] < lo[k]) lo[k] = p[k];
        if (p[k] > hi[k]) hi[k] = p[k];
    }
}

/* World-space box of an object's corners, padded by what its animation can add (like scene_gpu.c). */
static void object_box(const sss_scene_object *so, double lo[3], double hi[3])
{
    double olo[3], ohi[3], diag = 0.0;
    for (int k = 0; k < 3; k++) {
        olo[k] = so->bounds_min[k];
        ohi[k] = so->bounds_max[k];
        diag += (ohi[k] - olo[k]) * (ohi[k] - olo[k]);
    }
    double pad = 0.0;
    if (so->animation.type == SSS_ANIMATION_TWIST || so->animation.type == SSS_ANIMATION_BEND) pad = sqrt(diag);
    if (so->animation.type == SSS_ANIMATION_WAVE) pad = fabs(so->animation.amplitude);
    for (int c = 0; c < 8; c++) {
        double p[3] = {(c & 1) ? ohi[0] + pad : olo[0] - pad, (c & 2) ? ohi[1] + pad : olo[1] - pad,
                       (c & 4) ? ohi[2] + pad : olo[2] - pad};
        double w[3];
        sss_transform_point(so->transform.matrix, p, w);
        grow(lo, hi, w);
    }
}

static void sphere_of(const double lo[3], const double hi[3], double c[3], double *radius)
{
    double r2 = 0.0;
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        r2 += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    *radius = sqrt(r2);
}

void tsm_bounds_compute(const gl_tech_ctx *c, tsm_bounds *out)
{
    memset(out, 0, sizeof *out);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < c->scene->object_count && i < (size_t)c->gs->object_count; i++) {
        if (!c->gs->objects[i].subsurface) continue;
        object_box(&c->scene->objects[i], lo, hi);
        out->any = 1;
    }
    if (out->any) sphere_of(lo, hi, out->centre, &out->radius);
    double slo[3], shi[3];
    for (int k = 0; k < 3; k++) {
        slo[k] = c->gs->bounds_min[k];
        shi[k] = c->gs->bounds_max[k];
    }
    sphere_of(slo, shi, out->scene_centre, &out->scene_radius);
    if (!(out->radius > 0.0) || !isfinite(out->radius)) out->any = 0;
}

/* ---- Matrices (column-major, right-handed, the camera looks down -z) ---------------------------- */

/* The light's view: y up, or x when the view axis is within 8 degrees of y. */
static void look_at(const double eye[3], const double target[3], float m[16])
{
    double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    double up[3] = {0.0, 1.0, 0.0};
    if (fabs(f[1]) > 0.99 * v3_len(f)) up[0] = 1.0, up[1] = 0.0;
    m4_look_at(eye, target, up, m);
}

int tsm_light_matrix(const gl_tech_ctx *c, const tsm_bounds *b, int light, float vp[16])
{
    if (!b->any || light < 0 || light >= c->gs->light_count) return 0;
    const gl_light_record *L = &c->gs->lights[light];
    int type = (int)(L->position[3] + 0.5f);
    float V[16], P[16];
    memset(P, 0, sizeof P);
    if (type == GL_LIGHT_DIRECTIONAL) {
        double d[3] = {L->direction[0], L->direction[1], L->direction[2]};
        double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(dl > 0.0)) return 0;
        /* The eye lies behind everything that can occlude: the scene's sphere projected on the axis. */
        double reach = b->radius;
        double sc[3] = {b->scene_centre[0] - b->centre[0], b->scene_centre[1] - b->centre[1],
                        b->scene_centre[2] - b->centre[2]};
        reach += sqrt(sc[0] * sc[0] + sc[1] * sc[1] + sc[2] * sc[2]) + b->scene_radius;
        double eye[3], target[3];
        for (int k = 0; k < 3; k++) {
            eye[k] = b->centre[k] - d[k] / dl * reach;
            target[k] = b->centre[k];
        }
        look_at(eye, target, V);
        double half = b->radius * 1.01, n = 0.0, f = reach + b->radius * 1.01;
        P[0] = (float)(1.0 / half);
        P[5] = (float)(1.0 / half);
        P[10] = (float)(-2.0 / (f - n));
        P[14] = (float)(-(f + n) / (f - n));
        P[15] = 1.0f;
    } else {
        double eye[3] = {L->position[0], L->position[1], L->position[2]};
        double to[3] = {b->centre[0] - eye[0], b->centre[1] - eye[1], b->centre[2] - eye[2]};
        double dist = sqrt(to[0] * to[0] + to[1] * to[1] + to[2] * to[2]);
        double half_angle, n, f;
        if (dist > 1.01 * b->radius) {
            half_angle = asin(b->radius / dist) * 1.02;
            n = fmax((dist - b->radius) * 0.05, dist * 1e-4);
            f = dist + b->radius * 1.01;
        } else {
            /* the light sits among the objects: one wide frustum aimed at the centre (misses behind) */
            half_angle = 75.0 * M_PI / 180.0;
            n = b->radius * 1e-4;
            f = dist + b->radius * 1.01;
            if (!(dist > 0.0)) {
                to[0] = 0.0; /* any direction */
                to[2] = -1.0;
            }
        }
        double target[3] = {eye[0] + to[0], eye[1] + to[1], eye[2] + to[2]};
        look_at(eye, target, V);
        double t = 1.0 / tan(half_angle);
        P[0] = (float)t;
        P[5] = (float)t;
        P[10] = (float)((f + n) / (n - f));
        P[11] = -1.0f;
        P[14] = (float)(2.0 * f * n / (n - f));
    }
    m4_mul(P, V, vp);
    for (int i = 0; i < 16; i++)
        if (!isfinite(vp[i])) return 0;
    return 1;
}

sss_result tsm_program(GLuint *prog, sss_error *err)
{
    return gl_program_vf("gbuffer.vert.glsl", "tsm.frag.glsl", "#define LIGHT_VIEW 1\n", prog, err);
}

void tsm_render(const gl_tech_ctx *c, GLuint prog, GLuint fbo, int size, int light, const float vp[16])
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, size, size);
    const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
    for (int i = 0; i < 3; i++) glClearBufferfv(GL_COLOR, i, zero);
    glClearBufferfv(GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glUseProgram(prog);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_light_vp"), 1, GL_FALSE, vp);
    glUniform1i(glGetUniformLocation(prog, "u_light"), light);
    GLint u_obj = glGetUniformLocation(prog, "u_object");
    for (int o = 0; o < c->gs->object_count; o++) {
        if (c->gs->objects[o].emitter) continue;
        glUniform1i(u_obj, o);
        glBindVertexArray(c->gs->objects[o].vao);
        glDrawElements(GL_TRIANGLES, (GLsizei)(3 * c->gs->objects[o].triangle_count), GL_UNSIGNED_INT, NULL);
    }
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
}
