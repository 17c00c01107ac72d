/* PBRT export: the written file carries the scene's camera, materials and lights as PBRT-v3 names
 * them; meshes are written in world space; the environment mapping agrees with the reference
 * renderer's lookup; area lights face u x v under PBRT's triangle-normal rule; failures leave
 * nothing behind. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "export/export_test.h"
#include "sss/export.h"
#include "sss/reference.h"

static const char scene_json[] =
    "{\"camera\": {\"position\": [0, 1, 5], \"look_at\": [0, 0.5, 0], \"fov\": 40, \"width\": 64, \"height\": 32},"
    " \"objects\": ["
    "  {\"procedural\": {\"shape\": \"sphere\", \"radius\": 0.5, \"subdivisions\": 2},"
    "   \"transform\": {\"translate\": [1, 2, 3], \"rotate\": [0, 1, 0, 90], \"scale\": [2, 1, 1]},"
    "   \"material\": {\"type\": \"subsurface\", \"medium\": \"skin1\", \"scale\": 10, \"eta\": 1.4}},"
    "  {\"procedural\": {\"shape\": \"box\", \"size\": [1, 1, 1]},"
    "   \"material\": {\"type\": \"subsurface\", \"sigma_a\": [0.1, 0.2, 0.3], \"sigma_s\": [1, 2, 3], \"g\": 0.5}},"
    "  {\"procedural\": {\"shape\": \"torus\", \"major\": 1, \"minor\": 0.25, \"segments\": 16},"
    "   \"material\": {\"type\": \"subsurface\", \"reflectance\": [0.5, 0.6, 0.7], \"mfp\": 0.2}},"
    "  {\"procedural\": {\"shape\": \"plane\", \"size\": 4},"
    "   \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.25, 0.5, 0.75]}}],"
    " \"lights\": ["
    "  {\"type\": \"point\", \"position\": [1, 2, 3], \"intensity\": [4, 5, 6]},"
    "  {\"type\": \"spot\", \"position\": [0, 3, 0], \"look_at\": [0, 0, 0], \"cone_angle\": 30, \"cone_delta\": 5,"
    "   \"intensity\": [1, 1, 1]},"
    "  {\"type\": \"directional\", \"direction\": [0, -1, 0], \"radiance\": [2, 2, 2]},"
    "  {\"type\": \"area\", \"center\": [0, 2, 0], \"u\": [0.5, 0, 0], \"v\": [0, 0, 0.25], \"radiance\": [3, 3, 3]}],"
    " \"render\": {\"exposure\": 1}}";

static int contains(const char *text, const char *needle) { return strstr(text, needle) != NULL; }

static void test_file_contents(const char *dir)
{
    sss_scene scene = {0};
    sss_error err = {0};
    CHECK(sss_scene_parse(scene_json, strlen(scene_json), dir, "export.json", NULL, &scene, &err) == SSS_OK);
    char out[512], ply[512];
    snprintf(out, sizeof out, "%s/scene.pbrt", dir);
    CHECK_MSG(sss_export_pbrt(&scene, NULL, out, &err) == SSS_OK, "%s", err.message);

    char *text = NULL;
    FILE *f = fopen(out, "rb");
    CHECK(f != NULL);
    if (!f) return;
    text = calloc(1, 1 << 16);
    size_t n = fread(text, 1, (1 << 16) - 1, f);
    fclose(f);
    CHECK(n > 0);

    /* Camera: PBRT's left-handed camera space needs the mirror before LookAt; fov passes unchanged
     * (PBRT's perspective fov is along the shorter axis, as the scene format's). */
    char *scale = strstr(text, "Scale -1 1 1"), *look = strstr(text, "LookAt 0 1 5  0 0.5 0  0 1 0");
    CHECK(scale && look && scale < look);
    CHECK(contains(text, "\"float fov\" [40]"));
    CHECK(contains(text, "\"integer xresolution\" [64] \"integer yresolution\" [32]"));
    CHECK(contains(text, "\"float scale\" [2]")); /* exposure 1 stop */
    /* The default depth matches sss reference's default (its bounce cap). */
    CHECK(SSS_EXPORT_PBRT_MAXDEPTH_DEFAULT == SSS_REFERENCE_MAX_BOUNCES);
    CHECK(contains(text, "Integrator \"path\" \"integer maxdepth\" [16]"));
    /* Materials, by their PBRT names and parameters. */
    CHECK(contains(text, "Material \"subsurface\" \"string name\" [\"Skin1\"] \"float scale\" [10] \"float eta\" [1.4]"));
    CHECK(contains(text, "\"rgb sigma_a\" [0.1 0.2 0.3] \"rgb sigma_s\" [1 2 3] \"float scale\" [1] \"float eta\" [1.33] \"float g\" [0.5]"));
    CHECK(contains(text, "Material \"kdsubsurface\" \"rgb Kd\" [0.5 0.6 0.7] \"rgb mfp\" [0.2 0.2 0.2] \"float eta\" [1.33]"));
    CHECK(contains(text, "Material \"matte\" \"rgb Kd\" [0.25 0.5 0.75]"));
    /* Lights. */
    CHECK(contains(text, "LightSource \"point\" \"point from\" [1 2 3] \"rgb I\" [4 5 6]"));
    CHECK(contains(text, "\"float coneangle\" [30] \"float conedelta\" [5]"));
    CHECK(contains(text, "LightSource \"distant\" \"point from\" [0 0 0] \"point to\" [0 -1 0] \"rgb L\" [2 2 2]"));
    CHECK(contains(text, "AreaLightSource \"diffuse\" \"rgb L\" [3 3 3] \"bool twosided\" [\"false\"]"));

    /* The area light's triangles: PBRT's normal (p0 - p2) x (p1 - p2) must point along
     * u x v = (0.5, 0, 0) x (0, 0, 0.25) = (0, -0.125, 0), i.e. straight down. */
    const char *pts = strstr(text, "\"point P\" [");
    double p[4][3];
    CHECK(pts && sscanf(pts + 11, "%lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf", &p[0][0], &p[0][1], &p[0][2],
                        &p[1][0], &p[1][1], &p[1][2], &p[2][0], &p[2][1], &p[2][2], &p[3][0], &p[3][1],
                        &p[3][2]) == 12);
    for (int t = 0; t < 2; t++) {
        const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
        const double *a = p[tri[t][0]], *b = p[tri[t][1]], *c = p[tri[t][2]];
        double e0[3] = {a[0] - c[0], a[1] - c[1], a[2] - c[2]}, e1[3] = {b[0] - c[0], b[1] - c[1], b[2] - c[2]};
        double ny = e0[2] * e1[0] - e0[0] * e1[2];
        double nx = e0[1] * e1[2] - e0[2] * e1[1], nz = e0[0] * e1[1] - e0[1] * e1[0];
        CHECK(ny < 0 && fabs(nx) < 1e-12 && fabs(nz) < 1e-12);
    }

    /* Meshes in world space: object 0's PLY equals its mesh under the scene transform. */
    snprintf(ply, sizeof ply, "%s/scene_obj0.ply", dir);
    CHECK(contains(text, "Shape \"plymesh\" \"string filename\" [\"scene_obj0.ply\"]"));
    sss_mesh written = {0};
    CHECK(sss_mesh_read(ply, &written, &err) == SSS_OK);
    const sss_scene_object *o = &scene.objects[0];
    CHECK(written.triangle_count == o->mesh.triangle_count && written.vertex_count == o->mesh.vertex_count);
    double worst = 0;
    for (uint32_t v = 0; v < written.vertex_count && v < o->mesh.vertex_count; v++) {
        double q[3] = {o->mesh.positions[3 * v], o->mesh.positions[3 * v + 1], o->mesh.positions[3 * v + 2]}, w[3];
        sss_transform_point(o->transform.matrix, q, w);
        for (int i = 0; i < 3; i++) worst = fmax(worst, fabs(w[i] - written.positions[3 * v + i]));
    }
    CHECK_MSG(worst < 1e-5, "max deviation %g", worst);
    sss_mesh_free(&written);
    for (int i = 0; i < 4; i++) {
        snprintf(ply, sizeof ply, "%s/scene_obj%d.ply", dir, i);
        CHECK(access(ply, F_OK) == 0);
        remove(ply);
    }
    remove(out);
    free(text);
    sss_scene_free(&scene);
}

/* PBRT's infinite light looks its map up at (phi / 2 pi, theta / pi) of the light-space direction,
 * phi = atan2(y, x) in [0, 2 pi), theta from +z. Through the exported light-to-world matrix this
 * must agree with the reference renderer's equirectangular lookup for every direction. */
static void test_environment_mapping(void)
{
    double worst = 0;
    for (int r = 0; r < 4; r++) {
        double rot = -90.0 + 70.0 * r, m[16];
        export_pbrt_env_light_to_world(rot, m);
        for (int k = 0; k < 200; k++) {
            double z = 1.0 - 2.0 * (k + 0.5) / 200.0, a = 2.39996 * k, s = sqrt(1 - z * z);
            double d[3] = {s * cos(a), z, s * sin(a)}, L[3];
            for (int i = 0; i < 3; i++) L[i] = m[i] * d[0] + m[4 + i] * d[1] + m[8 + i] * d[2]; /* W = M^T */
            double phi = atan2(L[1], L[0]);
            if (phi < 0) phi += 2 * M_PI;
            double u_pbrt = phi / (2 * M_PI), v_pbrt = acos(fmax(-1, fmin(1, L[2]))) / M_PI, u, v;
            sss_reference_env_uv(d, rot, &u, &v);
            double du = fabs(u - u_pbrt);
            du = fmin(du, 1 - du);
            worst = fmax(worst, fmax(du, fabs(v - v_pbrt)));
        }
    }
    CHECK_MSG(worst < 1e-9, "worst (u, v) disagreement %g", worst);
}

static void test_failure_leaves_nothing(const char *dir)
{
    sss_scene scene = {0};
    sss_error err = {0};
    CHECK(sss_scene_parse(scene_json, strlen(scene_json), dir, "export.json", NULL, &scene, &err) == SSS_OK);
    CHECK(sss_export_pbrt(&scene, NULL, "/nonexistent-dir/x.pbrt", &err) != SSS_OK);
    CHECK_MSG(strstr(err.message, "/nonexistent-dir/") != NULL, "%s", err.message);
    sss_export_pbrt_desc bad = {.time = NAN};
    char out[512];
    snprintf(out, sizeof out, "%s/t.pbrt", dir);
    CHECK(sss_export_pbrt(&scene, &bad, out, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(access(out, F_OK) != 0);
    sss_scene_free(&scene);
}

int main(void)
{
    char dir[] = "/tmp/sss-export-XXXXXX";
    if (!mkdtemp(dir)) return 1;
    test_file_contents(dir);
    test_environment_mapping();
    test_failure_leaves_nothing(dir);
    rmdir(dir);
    return CHECK_DONE();
}
