/* The GPU deformation (common.glsl anim_deform, used by the G-buffer and shadow vertex stages and the
 * splat compute pass) against the scene module's CPU definition (sss_animation_deform_point and
 * _normal, sss/scene.h) for twist, bend and wave at several times, on points inside and outside the
 * bounding box: positions within float rounding of the box size (2e-5 of it), normals within 1e-5 rad. */
#include <stdlib.h>
#include <string.h>

#include "gl_probe_util.h"

#define N_POINTS 200

static const char *const probe_src =
    "#version 450 core\n"
    "#include \"common.glsl\"\n"
    "layout(local_size_x = 64) in;\n"
    "layout(std430, binding = 4) buffer Io { vec4 io[]; };\n"
    "uniform uint u_count;\n"
    "uniform float u_time;\n"
    "void main()\n"
    "{\n"
    "    uint i = gl_GlobalInvocationID.x;\n"
    "    if (i >= u_count) return;\n"
    "    vec3 n = io[2u * i + 1u].xyz;\n"
    "    vec3 p = anim_deform(objects[0], io[2u * i].xyz, n, u_time);\n"
    "    io[2u * i] = vec4(p, 1.0);\n"
    "    io[2u * i + 1u] = vec4(n, 0.0);\n"
    "}\n";

static double frand(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (*s >> 8) / 16777216.0;
}

int main(void)
{
    gt_probe probe;
    if (!gt_probe_create(&probe, "animation_probe.comp.glsl", probe_src, sizeof(float) * 8 * N_POINTS)) {
        CHECK(0);
        return CHECK_DONE();
    }
    const float lo[3] = {-0.3f, 0.1f, -0.2f}, hi[3] = {0.5f, 1.7f, 0.25f};
    const sss_animation_type types[3] = {SSS_ANIMATION_TWIST, SSS_ANIMATION_BEND, SSS_ANIMATION_WAVE};
    const double amplitude[3] = {70.0, 35.0, 0.08}, times[3] = {0.0, 0.7, 2.9};
    float pts[N_POINTS][3], nrm[N_POINTS][3];
    unsigned seed = 12345;
    for (int i = 0; i < N_POINTS; i++) {
        double len = 0.0;
        for (int k = 0; k < 3; k++) {
            /* inside the box and up to 20% beyond it on every side */
            pts[i][k] = (float)(lo[k] + (hi[k] - lo[k]) * (1.4 * frand(&seed) - 0.2));
            nrm[i][k] = (float)(2.0 * frand(&seed) - 1.0);
            len += (double)nrm[i][k] * nrm[i][k];
        }
        len = sqrt(len);
        for (int k = 0; k < 3; k++) nrm[i][k] = (float)(nrm[i][k] / (len > 0.0 ? len : 1.0));
    }
    double extent = 0.0;
    for (int k = 0; k < 3; k++) extent = fmax(extent, hi[k] - lo[k]);
    for (int a = 0; a < 3; a++)
        for (int ti = 0; ti < 3; ti++) {
            sss_animation anim = {types[a], amplitude[a], 4.0};
            gl_object_record rec;
            memset(&rec, 0, sizeof rec);
            for (int k = 0; k < 4; k++) rec.model[5 * k] = rec.normal_matrix[5 * k] = 1.0f;
            for (int k = 0; k < 3; k++) {
                rec.bounds_min[k] = lo[k];
                rec.bounds_max[k] = hi[k];
            }
            rec.bounds_min[3] = (float)anim.type;
            rec.bounds_max[3] = (float)anim.amplitude;
            rec.anim[0] = (float)anim.period;
            glNamedBufferSubData(probe.objs, 0, sizeof rec, &rec);
            float data[N_POINTS][8];
            for (int i = 0; i < N_POINTS; i++) {
                for (int k = 0; k < 3; k++) {
                    data[i][k] = pts[i][k];
                    data[i][4 + k] = nrm[i][k];
                }
                data[i][3] = data[i][7] = 0.0f;
            }
            glUseProgram(probe.prog);
            glUniform1f(glGetUniformLocation(probe.prog, "u_time"), (float)times[ti]);
            gt_probe_run(&probe, data, sizeof data, N_POINTS);
            double worst_p = 0.0, worst_n = 0.0;
            for (int i = 0; i < N_POINTS; i++) {
                float p[3], n[3];
                sss_animation_deform_point(&anim, lo, hi, times[ti], pts[i], p);
                sss_animation_deform_normal(&anim, lo, hi, times[ti], pts[i], nrm[i], n);
                double dp = 0.0, dot = 0.0, c[3];
                const float *m = &data[i][4];
                for (int k = 0; k < 3; k++) {
                    dp = fmax(dp, fabs(p[k] - data[i][k]));
                    dot += (double)n[k] * m[k];
                }
                c[0] = (double)n[1] * m[2] - (double)n[2] * m[1];
                c[1] = (double)n[2] * m[0] - (double)n[0] * m[2];
                c[2] = (double)n[0] * m[1] - (double)n[1] * m[0];
                /* the angle from |n x m| (acos of a float dot product near 1 resolves only ~5e-4) */
                double ang = atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), dot);
                worst_p = fmax(worst_p, dp);
                worst_n = fmax(worst_n, ang);
            }
            printf("%s t = %.1f: largest position error %.3g (box %.3g), normal angle %.3g rad\n",
                   sss_animation_type_name(anim.type), times[ti], worst_p, extent, worst_n);
            CHECK(worst_p < 2e-5 * extent);
            CHECK(worst_n < 1e-5);
        }
    gt_probe_destroy(&probe, "animation probe");
    return CHECK_DONE();
}
