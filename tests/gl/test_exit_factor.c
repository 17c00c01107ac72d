/* The exit factor of every GL technique (common.glsl exit_factor: F_t(cos_o) / (pi c), c of Sw)
 * against the CPU's Fresnel code for normals on both sides of the view direction. The ground truth
 * (ref_render.c) uses |n . v|: an interpolated shading normal may face away from the camera on a
 * visible triangle (creases, silhouettes, the rim of the glasses on the head scenes), and F_t there
 * is that of the same angle, not of grazing (which made isolated black pixels on lit skin). */
#include <stdlib.h>
#include <string.h>

#include "gl_probe_util.h"
#include "sss/material.h"

#define N_PAIRS 64
#define PI 3.14159265358979323846

static const char *const probe_src =
    "#version 450 core\n"
    "#include \"common.glsl\"\n"
    "layout(local_size_x = 64) in;\n"
    "layout(std430, binding = 4) buffer Io { vec4 io[]; };\n"
    "uniform uint u_count;\n"
    "void main()\n"
    "{\n"
    "    uint i = gl_GlobalInvocationID.x;\n"
    "    if (i >= u_count) return;\n"
    "    Material m;\n"
    "    m.params = vec4(io[2u * i].w, io[2u * i + 1u].w, 0.0, -1.0);\n"
    "    float f = exit_factor(m, io[2u * i].xyz, io[2u * i + 1u].xyz);\n"
    "    io[2u * i] = vec4(f);\n"
    "}\n";

int main(void)
{
    gt_probe probe;
    if (!gt_probe_create(&probe, "exit_factor_probe.comp.glsl", probe_src, sizeof(float) * 8 * N_PAIRS)) {
        CHECK(0);
        return CHECK_DONE();
    }
    /* The view direction v = +z; normals at angles from 0 to 180 degrees to it (past 90: facing away),
     * for two indices of refraction. */
    float data[N_PAIRS][8];
    double expect[N_PAIRS];
    for (int i = 0; i < N_PAIRS; i++) {
        double eta = i % 2 ? 1.33 : 1.5;
        double theta = PI * (i / 2 + 0.5) / (N_PAIRS / 2), c = sss_bssrdf_normalization(eta);
        double cos_o = cos(theta);
        float n[3] = {(float)sin(theta), 0.0f, (float)cos_o}, v[3] = {0.0f, 0.0f, 1.0f};
        for (int k = 0; k < 3; k++) {
            data[i][k] = n[k];
            data[i][4 + k] = v[k];
        }
        data[i][3] = (float)eta;
        data[i][7] = (float)c;
        expect[i] = (1.0 - sss_fresnel_dielectric(fabs(cos_o), 1.0, eta)) / (PI * c);
    }
    gt_probe_run(&probe, data, sizeof data, N_PAIRS);
    double worst_front = 0.0, worst_away = 0.0;
    for (int i = 0; i < N_PAIRS; i++) {
        double rel = fabs(data[i][0] - expect[i]) / expect[i];
        if (i / 2 < N_PAIRS / 4) worst_front = fmax(worst_front, rel);
        else worst_away = fmax(worst_away, rel);
    }
    printf("exit factor vs CPU Fresnel: facing the camera %.3g, facing away %.3g (relative)\n", worst_front,
           worst_away);
    CHECK(worst_front < 1e-4);
    CHECK(worst_away < 1e-4);
    gt_probe_destroy(&probe, "exit factor probe");
    return CHECK_DONE();
}
