/* glTF 2.0 import (sss/gltf.h) on the assets of tests/data/gltf (written by make_assets.py):
 * material coefficients against the extension formulas evaluated here (the albedo inversion as the
 * extension texts print it, not the importer's exact root), node transforms against
 * the same object placed by hand in our scene format, cameras, lights, .glb = .gltf, bad inputs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "sss/gltf.h"
#include "sss/image.h"
#include "sss/scene.h"

#define DATA SSS_TEST_DATA "/gltf/"

static const double PI = 3.14159265358979323846;

static const sss_gltf_object *find_node(const sss_gltf_scene *s, int node)
{
    for (size_t i = 0; i < s->object_count; i++)
        if (s->objects[i].node == node) return &s->objects[i];
    return NULL;
}

/* The albedo inversion as the extension texts print it, with their rounded constants (not the
 * importer's exact root of the quadratic): s = 4.09712 + 4.20863 rho - sqrt(9.59217 + 41.6808 rho +
 * 17.7126 rho^2), then rho_ss = 1 - s^2 (KHR_materials_volume_scatter) or (1 - s^2) / (1 - g s^2)
 * (KHR_materials_scatter, KhronosGroup/glTF pull request 2579). The rounding moves rho_ss by < 1e-5. */
static double spec_albedo(double rho, double g, int with_g)
{
    double s = 4.09712 + 4.20863 * rho - sqrt(9.59217 + 41.6808 * rho + 17.7126 * rho * rho);
    return with_g ? (1 - s * s) / (1 - g * s * s) : 1 - s * s;
}

/* The imported medium against sigma_t and the multiple-scattering albedo rho, inverted here. */
static void check_medium(const sss_gltf_material *m, const double sigma_t[3], const double rho[3], double g,
                         int with_g, double eta)
{
    CHECK(m->subsurface);
    CHECK_NEAR(m->g, g, 0);
    CHECK_NEAR(m->eta, eta, 0);
    for (int k = 0; k < 3; k++) {
        double alpha = spec_albedo(rho[k], g, with_g);
        CHECK_NEAR(m->sigma_s[k] / sigma_t[k], alpha, 2e-5);
        CHECK_NEAR(m->sigma_a[k] / sigma_t[k], 1 - alpha, 2e-5);
        CHECK_REL(m->sigma_a[k] + m->sigma_s[k], sigma_t[k], 1e-6); /* 1e-6: float32 values in some JSON */
    }
}

/* KHR_materials_volume (c, d) + KHR_materials_volume_scatter (rho, g): sigma_t = -ln(c) / d. */
static void check_subsurface(const sss_gltf_material *m, const double color[3], double distance,
                             const double rho[3], double g, double eta)
{
    double sigma_t[3];
    for (int k = 0; k < 3; k++) sigma_t[k] = -log(color[k]) / distance; /* c = exp(-sigma_t d) */
    check_medium(m, sigma_t, rho, g, 0, eta);
}

static void test_materials(void)
{
    sss_gltf_scene s;
    sss_error err = {0};
    CHECK_MSG(sss_gltf_load(DATA "scatter.gltf", NULL, &s, &err) == SSS_OK, "%s", err.message);
    CHECK(s.object_count == 6);
    const sss_gltf_object *scatter = find_node(&s, 1), *diffuse = find_node(&s, 2), *glass = find_node(&s, 3),
                          *defaults = find_node(&s, 4);
    CHECK(scatter && diffuse && glass && defaults);
    if (!scatter || !diffuse || !glass || !defaults) return;
    /* materials[0]: volume (d = 0.25, c = [0.5, 0.25, 0.125]) + scatter (rho, g 0.3) + ior 1.4 */
    check_subsurface(&scatter->material, (double[]){0.5, 0.25, 0.125}, 0.25, (double[]){0.9, 0.6, 0.3}, 0.3, 1.4);
    /* materials[3]: no ior (1.5), no scatterAnisotropy (0) */
    check_subsurface(&defaults->material, (double[]){0.1, 0.2, 0.4}, 2, (double[]){0.95, 0.5, 0.05}, 0, 1.5);
    /* materials[1]: plain PBR -> diffuse baseColor; materials[2]: volume without scattering -> diffuse */
    CHECK(!diffuse->material.subsurface && !glass->material.subsurface);
    for (int k = 0; k < 3; k++) {
        CHECK_NEAR(diffuse->material.albedo[k], 0.2 * (k + 1), 1e-15);
        CHECK_NEAR(glass->material.albedo[k], 0.7, 1e-15);
    }
    sss_gltf_scene_free(&s);
}

/* Writes mesh as a PLY in dir and loads a scene that places it with our transform; returns the
 * world mesh of that object (sss_scene_object_world_mesh). */
static int place_by_hand(const char *dir, const sss_mesh *local, const char *transform_json, sss_mesh *world)
{
    char ply[512], json[1024];
    snprintf(ply, sizeof ply, "%s/local.ply", dir);
    if (sss_mesh_write_ply(ply, local, NULL) != SSS_OK) return 0;
    int n = snprintf(json, sizeof json,
                     "{\"camera\": {\"position\": [0, 0, 10], \"look_at\": [0, 0, 0]}, \"objects\": [{\"mesh\": "
                     "\"local.ply\", \"transform\": %s, \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}}]}",
                     transform_json);
    sss_scene scene;
    sss_error err = {0};
    if (sss_scene_parse(json, (size_t)n, dir, "by-hand", NULL, &scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    sss_result res = sss_scene_object_world_mesh(&scene.objects[0], 0, world, &err);
    sss_scene_free(&scene);
    return res == SSS_OK;
}

static void check_same_mesh(const sss_mesh *a, const sss_mesh *b)
{
    CHECK(a->vertex_count == b->vertex_count && a->triangle_count == b->triangle_count);
    if (a->vertex_count != b->vertex_count || a->triangle_count != b->triangle_count) return;
    double dp = 0, dn = 0;
    for (size_t i = 0; i < 3 * (size_t)a->vertex_count; i++) {
        dp = fmax(dp, fabs((double)a->positions[i] - b->positions[i]));
        dn = fmax(dn, fabs((double)a->normals[i] - b->normals[i]));
    }
    CHECK_NEAR(dp, 0, 2e-6);
    CHECK_NEAR(dn, 0, 2e-6);
    CHECK(memcmp(a->indices, b->indices, 3 * sizeof *a->indices * a->triangle_count) == 0);
}

static void test_node_transforms(void)
{
    sss_gltf_scene s;
    sss_error err = {0};
    CHECK_MSG(sss_gltf_load(DATA "scatter.gltf", NULL, &s, &err) == SSS_OK, "%s", err.message);
    const sss_gltf_object *local = find_node(&s, 10), *child = find_node(&s, 1), *matrix = find_node(&s, 2),
                          *mirror = find_node(&s, 11);
    CHECK(local && child && matrix && mirror);
    if (!local || !child || !matrix || !mirror) return;
    char dir[] = "/tmp/sss_test_gltf_XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    sss_mesh world = {0};
    /* nodes[1] (T [0, 0.5, 0], R 60 degrees about (1, 1, 0), S [2, 1, 0.5]) under nodes[0] (T [1, 0, 0]) */
    CHECK(place_by_hand(dir, &local->mesh, "{\"translate\": [1, 0.5, 0], \"rotate\": [1, 1, 0, 60], \"scale\": [2, 1, 0.5]}",
                        &world));
    check_same_mesh(&child->mesh, &world);
    sss_mesh_free(&world);
    /* nodes[2]: `matrix` (column-major) = T [-2, 0, 0] R 30 degrees about y, S 1.5 */
    CHECK(place_by_hand(dir, &local->mesh, "{\"translate\": [-2, 0, 0], \"rotate\": [0, 1, 0, 30], \"scale\": 1.5}",
                        &world));
    check_same_mesh(&matrix->mesh, &world);
    sss_mesh_free(&world);
    /* nodes[11]: a mirror (S [-1, 1, 1]); both flip the winding so the cube stays outward-facing */
    CHECK(place_by_hand(dir, &local->mesh, "{\"translate\": [0, -3, 0], \"scale\": [-1, 1, 1]}", &world));
    check_same_mesh(&mirror->mesh, &world);
    sss_mesh_free(&world);
    for (size_t i = 0; i < s.object_count; i++) CHECK(sss_mesh_signed_volume(&s.objects[i].mesh) > 0);
    CHECK_NEAR(sss_mesh_signed_volume(&child->mesh), 2 * 1 * 0.5, 1e-5); /* det of the scale */
    char path[600];
    snprintf(path, sizeof path, "%s/local.ply", dir);
    remove(path);
    rmdir(dir);
    sss_gltf_scene_free(&s);
}

static void rotate_x(double degrees, const double v[3], double out[3])
{
    double c = cos(degrees * PI / 180), sn = sin(degrees * PI / 180);
    out[0] = v[0];
    out[1] = c * v[1] - sn * v[2];
    out[2] = sn * v[1] + c * v[2];
}

static void check_direction(const double from[3], const double to[3], const double expected[3])
{
    double d[3] = {to[0] - from[0], to[1] - from[1], to[2] - from[2]};
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; k++) CHECK_NEAR(d[k] / len, expected[k], 1e-12);
}

static void test_cameras(void)
{
    sss_gltf_scene s;
    sss_error err = {0};
    static const double zero[3] = {0, 0, 0}, minus_z[3] = {0, 0, -1}, plus_y[3] = {0, 1, 0};
    double fwd[3], up[3];
    /* nodes[5]: cameras[0] (yfov 0.6, aspect 1.5) at [0, 1, 8] turned -7 degrees about x */
    CHECK_MSG(sss_gltf_load(DATA "scatter.glb", NULL, &s, &err) == SSS_OK, "%s", err.message);
    CHECK(s.camera_from_asset);
    CHECK(s.camera.width == 810 && s.camera.height == 540);
    CHECK_NEAR(s.camera.fov, 0.6 * 180 / PI, 1e-12); /* landscape: yfov is the shorter axis */
    static const double camera0[3] = {0, 1, 8};
    for (int k = 0; k < 3; k++) CHECK_NEAR(s.camera.position[k], camera0[k], 1e-12);
    rotate_x(-7, minus_z, fwd);
    rotate_x(-7, plus_y, up);
    check_direction(s.camera.position, s.camera.look_at, fwd);
    check_direction(zero, s.camera.up, up);
    sss_gltf_scene_free(&s);

    /* --camera 1 (yfov 0.8, no aspect) at [8, 0, 0] turned 90 degrees about y: looks down -x; a
     * portrait image makes the width the shorter axis: fov = 2 atan(tan(yfov / 2) W / H). */
    sss_gltf_desc desc = {.use_camera = 1, .camera = 1, .width = 400, .height = 800};
    CHECK_MSG(sss_gltf_load(DATA "scatter.glb", &desc, &s, &err) == SSS_OK, "%s", err.message);
    CHECK(s.camera.width == 400 && s.camera.height == 800);
    CHECK_NEAR(s.camera.fov, 2 * atan(tan(0.4) * 0.5) * 180 / PI, 1e-12);
    check_direction(s.camera.position, s.camera.look_at, (double[]){-1, 0, 0});
    CHECK_NEAR(s.camera.position[0], 8, 1e-12);
    sss_gltf_scene_free(&s);

    desc.camera = 5;
    CHECK(sss_gltf_load(DATA "scatter.glb", &desc, &s, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "cameras[5]") != NULL, "%s", err.message);

    /* no camera: a framing camera sees every vertex */
    CHECK_MSG(sss_gltf_load(DATA "external.gltf", NULL, &s, &err) == SSS_OK, "%s", err.message);
    CHECK(!s.camera_from_asset);
    sss_camera_basis basis;
    CHECK(sss_camera_basis_init(&s.camera, &basis, NULL) == SSS_OK);
    const sss_mesh *m = &s.objects[0].mesh;
    for (uint32_t i = 0; i < m->vertex_count; i++) {
        double p[3] = {m->positions[3 * i], m->positions[3 * i + 1], m->positions[3 * i + 2]}, raster[2];
        CHECK(sss_camera_project(&basis, p, raster, NULL));
        CHECK(raster[0] > 0 && raster[0] < s.camera.width && raster[1] > 0 && raster[1] < s.camera.height);
    }
    sss_gltf_scene_free(&s);
}

static void test_lights(void)
{
    sss_gltf_desc desc = {.light_scale = 2.5};
    sss_gltf_scene s;
    sss_error err = {0};
    CHECK_MSG(sss_gltf_load(DATA "scatter.gltf", &desc, &s, &err) == SSS_OK, "%s", err.message);
    CHECK(s.light_count == 3);
    if (s.light_count != 3) return;
    const sss_light *point = &s.lights[0], *spot = &s.lights[1], *sun = &s.lights[2];
    static const double minus_z[3] = {0, 0, -1};
    static const double point_at[3] = {2, 3, 4}, point_color[3] = {1, 0.5, 0.25};
    double down45[3];
    rotate_x(-45, minus_z, down45);
    CHECK(point->type == SSS_LIGHT_POINT && spot->type == SSS_LIGHT_SPOT && sun->type == SSS_LIGHT_DIRECTIONAL);
    for (int k = 0; k < 3; k++) {
        CHECK_NEAR(point->position[k], point_at[k], 1e-12);
        CHECK_NEAR(point->intensity[k], 2.5 * 20 * point_color[k], 1e-12); /* candela as W/sr */
        CHECK_NEAR(spot->intensity[k], 2.5 * 30, 1e-12);
        CHECK_NEAR(sun->radiance[k], 2.5 * 3, 1e-12); /* lux as irradiance */
        CHECK_NEAR(sun->direction[k], down45[k], 1e-12);
    }
    check_direction(spot->position, spot->look_at, (double[]){0, -1, 0});
    CHECK_NEAR(spot->cone_angle, 0.5 * 180 / PI, 1e-12);
    CHECK_NEAR(spot->cone_delta, (0.5 - 0.2) * 180 / PI, 1e-12);
    sss_gltf_scene_free(&s);
}

/* The .glb holds the same JSON and bytes as the .gltf's data: URI: identical imports. */
static void test_glb_equals_gltf(void)
{
    sss_gltf_scene a, b;
    sss_error err = {0};
    CHECK_MSG(sss_gltf_load(DATA "scatter.gltf", NULL, &a, &err) == SSS_OK, "%s", err.message);
    CHECK_MSG(sss_gltf_load(DATA "scatter.glb", NULL, &b, &err) == SSS_OK, "%s", err.message);
    CHECK(a.object_count == b.object_count && a.object_count == 6);
    for (size_t i = 0; i < a.object_count && i < b.object_count; i++) {
        const sss_mesh *x = &a.objects[i].mesh, *y = &b.objects[i].mesh;
        CHECK(x->vertex_count == y->vertex_count && x->vertex_count == 24 && x->triangle_count == 12);
        CHECK(memcmp(x->positions, y->positions, 12 * (size_t)x->vertex_count) == 0);
        CHECK(x->uvs && y->uvs && memcmp(x->uvs, y->uvs, 8 * (size_t)x->vertex_count) == 0);
        CHECK(memcmp(a.objects[i].material.sigma_s, b.objects[i].material.sigma_s, sizeof(double[3])) == 0);
    }
    sss_gltf_scene_free(&a);
    sss_gltf_scene_free(&b);
}

/* An external buffer whose URI needs percent-decoding ("external%20data.bin"), no normals. */
static void test_external_buffer(void)
{
    sss_gltf_scene s;
    sss_error err = {0};
    CHECK_MSG(sss_gltf_load(DATA "external.gltf", NULL, &s, &err) == SSS_OK, "%s", err.message);
    CHECK(s.object_count == 1 && s.objects[0].mesh.triangle_count == 1);
    const sss_mesh *m = &s.objects[0].mesh;
    CHECK(m->positions[3] == 1.0f && m->positions[7] == 1.0f);
    CHECK_NEAR(m->normals[2], 1, 1e-6); /* computed: the triangle faces +z */
    CHECK(!s.objects[0].material.subsurface && s.objects[0].material.albedo[0] == 1.0);
    sss_gltf_scene_free(&s);
}

/* gltf_transform.glb, written by @gltf-transform (make_gltf_transform.cjs): interleaved vertex
 * buffer (byteStride), 32-bit indices, a volume with diffuse transmission and no scattering extension
 * (-> the nearest subsurface medium; it was imported as diffuse, silently), a scaled parent. */
static void test_gltf_transform_asset(void)
{
    sss_gltf_scene s;
    sss_error err = {0};
    CHECK_MSG(sss_gltf_load(DATA "gltf_transform.glb", NULL, &s, &err) == SSS_OK, "%s", err.message);
    CHECK(s.object_count == 1 && s.light_count == 1);
    if (s.object_count != 1 || s.light_count != 1) return;
    const sss_gltf_object *o = &s.objects[0];
    for (int k = 0; k < 3; k++) CHECK_NEAR(o->material.albedo[k], (0.3 + 0.2 * k), 1e-7); /* float32 in JSON */
    /* volume t = 1, d = 0.5, c = (0.6, 0.4, 0.2); diffuseTransmissionFactor 1 (colour white); ior 1.3:
     * rho = (1 - 1) baseColor + 1 x 1 x exp(-sigma_t t) = c^(t/d) = c^2 */
    static const double c[3] = {0.6, 0.4, 0.2}, rho[3] = {0.36, 0.16, 0.04};
    double sigma_t[3];
    for (int k = 0; k < 3; k++) sigma_t[k] = -log(c[k]) / 0.5;
    check_medium(&o->material, sigma_t, rho, 0, 0, 1.3);
    CHECK(o->material_index == 0 && o->material.note && strstr(o->material.note, "diffuse_transmission"));
    /* the box's corner i: x, y, z from bits 0, 1, 2 (make_gltf_transform.cjs) */
    sss_mesh local = {.vertex_count = 8, .triangle_count = o->mesh.triangle_count, .indices = o->mesh.indices};
    float corners[24], normals[24] = {0};
    for (int i = 0; i < 8; i++) {
        corners[3 * i] = i & 1 ? 0.5f : -0.5f;
        corners[3 * i + 1] = i & 2 ? 1.0f : -1.0f;
        corners[3 * i + 2] = i & 4 ? 0.5f : -0.5f;
    }
    local.positions = corners;
    local.normals = normals;
    CHECK(o->mesh.vertex_count == 8 && o->mesh.triangle_count == 12);
    sss_mesh tmp = {0};
    CHECK(sss_scene_mesh_copy(&local, &tmp, NULL) == SSS_OK && sss_mesh_compute_normals(&tmp, NULL) == SSS_OK);
    /* root S 2, child T [0, 1, 0] R 45 degrees about z: world = R (2 p) + [0, 2, 0] */
    char dir[] = "/tmp/sss_test_gltf_XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    sss_mesh world = {0};
    CHECK(place_by_hand(dir, &tmp, "{\"translate\": [0, 2, 0], \"rotate\": [0, 0, 1, 45], \"scale\": 2}", &world));
    check_same_mesh(&o->mesh, &world);
    CHECK_NEAR(sss_mesh_signed_volume(&o->mesh), 8 * 2, 1e-4);
    sss_mesh_free(&world);
    sss_mesh_free(&tmp);
    char path[600];
    snprintf(path, sizeof path, "%s/local.ply", dir);
    remove(path);
    rmdir(dir);
    CHECK_NEAR(s.camera.fov, 0.7 * 180 / PI, 1e-6);
    CHECK(s.camera.width == 720 && s.camera.height == 540); /* aspectRatio 4/3 at the default height */
    CHECK_NEAR(s.lights[0].intensity[1], 12 * 0.8, 1e-5);
    sss_gltf_scene_free(&s);
}

/* exported.glb, written by `sss export gltf exported_source.json`: the coefficients given there. */
static void test_exported_asset(void)
{
    sss_gltf_scene s;
    sss_error err = {0};
    CHECK_MSG(sss_gltf_load(DATA "exported.glb", NULL, &s, &err) == SSS_OK, "%s", err.message);
    CHECK(s.object_count == 2 && s.light_count == 1 && s.camera_from_asset);
    if (s.object_count != 2 || s.light_count != 1) return;
    static const double sigma_a[3] = {0.5, 1.0, 2.0}, sigma_s[3] = {20, 15, 10};
    const sss_gltf_material *m = &s.objects[0].material;
    CHECK(m->subsurface && !s.objects[1].material.subsurface);
    for (int k = 0; k < 3; k++) {
        CHECK_REL(m->sigma_a[k], sigma_a[k], 1e-9);
        CHECK_REL(m->sigma_s[k], sigma_s[k], 1e-9);
        CHECK_NEAR(s.objects[1].material.albedo[k], 0.5, 0);
        CHECK_NEAR(s.lights[0].intensity[k], 40, 1e-12);
    }
    CHECK_NEAR(m->g, 0.2, 1e-15);
    CHECK_NEAR(m->eta, 1.35, 1e-15);
    CHECK_NEAR(s.lights[0].cone_angle, 25, 1e-12);
    CHECK_NEAR(s.lights[0].cone_delta, 5, 1e-12);
    CHECK_NEAR(s.camera.fov, 35, 1e-12); /* landscape 4:3: yfov is the shorter axis' fov */
    CHECK(s.camera.width == 720 && s.camera.height == 540);
    sss_gltf_scene_free(&s);
}

/* textured.gltf: baseColorTexture (an external PNG) becomes the subsurface texture, with an absolute
 * path so that a scene written anywhere finds it; glTF's v (down the image) becomes 1 - v. */
static void test_texture(void)
{
    sss_gltf_scene s;
    sss_error err = {0};
    CHECK_MSG(sss_gltf_load(DATA "textured.gltf", NULL, &s, &err) == SSS_OK, "%s", err.message);
    CHECK(s.object_count == 1);
    if (s.object_count != 1) return;
    const char *tex = s.objects[0].material.texture;
    CHECK_MSG(tex && tex[0] == '/' && strstr(tex, "gltf/albedo.png"), "%s", tex ? tex : "(none)");
    const float *uv = s.objects[0].mesh.uvs;
    CHECK(uv != NULL);
    if (uv) { /* make_assets.py: corner 0 of a face has glTF uv (0, 1), corner 2 has (1, 0) */
        CHECK(uv[0] == 0.0f && uv[1] == 0.0f && uv[4] == 1.0f && uv[5] == 1.0f);
    }
    sss_gltf_scene_free(&s);
    sss_scene scene;
    CHECK_MSG(sss_scene_load(DATA "textured.gltf", NULL, &scene, &err) == SSS_OK, "%s", err.message);
    CHECK(scene.object_count == 1 && scene.objects[0].material.texture &&
          strstr(scene.objects[0].material.texture, "gltf/albedo.png"));
    sss_scene_free(&scene);
}

/* Two images hold the same pixels, bit for bit. */
static void check_same_image(const sss_image *a, const sss_image *b, const char *what)
{
    CHECK_MSG(a->pixels && b->pixels && a->width == b->width && a->height == b->height, "%s: %dx%d vs %dx%d", what,
              a->width, a->height, b->width, b->height);
    if (a->pixels && b->pixels && a->width == b->width && a->height == b->height)
        CHECK_MSG(memcmp(a->pixels, b->pixels, sizeof(float) * 3 * (size_t)a->width * (size_t)a->height) == 0,
                  "%s: pixels differ", what);
}

/* Embedded baseColorTexture images (a .glb's bufferView, a data: URI; PNG and JPEG) decode to the
 * pixels of the files they were made from (make_assets.py), reach the scene as its texture, and are
 * written beside an imported scene as PNG with the same pixels. */
static void test_embedded_textures(void)
{
    sss_error err = {0};
    sss_image png, jpeg;
    CHECK(sss_image_read(DATA "albedo.png", &png, &err) == SSS_OK);
    CHECK(sss_image_read(SSS_TEST_DATA "/images/two_colours.jpg", &jpeg, &err) == SSS_OK);
    const char *assets[] = {"textured_embedded.glb", "textured_datauri.gltf", "textured_jpeg.glb"};
    for (int a = 0; a < 3; a++) {
        char path[512];
        snprintf(path, sizeof path, DATA "%s", assets[a]);
        sss_gltf_scene g;
        CHECK_MSG(sss_gltf_load(path, NULL, &g, &err) == SSS_OK, "%s", err.message);
        if (g.object_count != 1) continue;
        const sss_gltf_material *m = &g.objects[0].material;
        CHECK_MSG(m->texture == NULL && m->image == 0 && g.image_count == 1, "%s: image %d", assets[a], m->image);
        if (m->image == 0 && g.image_count == 1) check_same_image(&g.images[0], a == 2 ? &jpeg : &png, assets[a]);
        sss_gltf_scene_free(&g);

        sss_scene scene;
        CHECK_MSG(sss_scene_load(path, NULL, &scene, &err) == SSS_OK, "%s", err.message);
        const sss_scene_material *sm = scene.object_count == 1 ? &scene.objects[0].material : NULL;
        CHECK(sm && sm->texture && strstr(sm->texture, "#images[0]") && sm->texture_image && scene.texture_count == 1);
        if (sm && sm->texture_image) check_same_image(sm->texture_image, a == 2 ? &jpeg : &png, assets[a]);
        sss_scene_free(&scene);
    }

    /* sss import: the embedded image becomes <stem>_img0.png beside the scene */
    sss_gltf_scene g;
    char dir[] = "/tmp/sss_test_gltf_XXXXXX", path[512], img[600], ply[600];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/imported.json", dir);
    snprintf(img, sizeof img, "%s/imported_img0.png", dir);
    snprintf(ply, sizeof ply, "%s/imported_obj0.ply", dir);
    CHECK(sss_gltf_load(DATA "textured_jpeg.glb", NULL, &g, &err) == SSS_OK);
    CHECK_MSG(sss_gltf_write_scene(&g, path, &err) == SSS_OK, "%s", err.message);
    sss_gltf_scene_free(&g);
    sss_scene scene;
    CHECK_MSG(sss_scene_load(path, NULL, &scene, &err) == SSS_OK, "%s", err.message);
    const sss_scene_material *sm = scene.object_count == 1 ? &scene.objects[0].material : NULL;
    CHECK(sm && sm->texture && strcmp(sm->texture, img) == 0);
    if (sm && sm->texture_image) check_same_image(sm->texture_image, &jpeg, "imported_img0.png");

    sss_scene_free(&scene);
    remove(img);
    remove(ply);
    remove(path);
    CHECK(rmdir(dir) == 0);
    sss_image_free(&png);
    sss_image_free(&jpeg);
}

static void check_bad(const char *file, sss_result code, const char *needle)
{
    char path[512];
    snprintf(path, sizeof path, DATA "bad/%s", file);
    sss_gltf_scene s;
    sss_error err = {0};
    sss_result res = sss_gltf_load(path, NULL, &s, &err);
    CHECK_MSG(res == code, "%s: %s", file, err.message);
    CHECK_MSG(strstr(err.message, file) && strstr(err.message, needle), "%s: %s", file, err.message);
    CHECK(s.objects == NULL && s.object_count == 0);
}

static void test_bad_inputs(void)
{
    check_bad("truncated.glb", SSS_ERROR_PARSE, "truncated .glb");
    check_bad("accessor_range.gltf", SSS_ERROR_PARSE, "accessors[0]: 4 elements");
    check_bad("missing_buffer.gltf", SSS_ERROR_IO, "buffers[0].uri");
    check_bad("required_ext.gltf", SSS_ERROR_UNSUPPORTED, "extensionsRequired[1]: \"KHR_texture_basisu\"");
    check_bad("index_range.gltf", SSS_ERROR_PARSE, "indices: accessors[1][2] = 3 is out of range");
    check_bad("image_mime.glb", SSS_ERROR_UNSUPPORTED, "images[0].mimeType: not image/png or image/jpeg");
    check_bad("image_corrupt.glb", SSS_ERROR_PARSE, "images[0].png: not a PNG file");

    /* a node that is its own child */
    static const char cycle[] = "{\"asset\": {\"version\": \"2.0\"}, \"scenes\": [{\"nodes\": [0]}], "
                                "\"nodes\": [{\"children\": [0]}]}";
    sss_gltf_scene s;
    sss_error err = {0};
    CHECK(sss_gltf_parse(cycle, strlen(cycle), NULL, "cycle.gltf", NULL, &s, &err) == SSS_ERROR_PARSE);
    CHECK_MSG(strstr(err.message, "cycle.gltf: nodes[0]: reached twice"), "%s", err.message);

    /* every prefix of a valid .glb fails cleanly (or, for none of them, succeeds) */
    FILE *f = fopen(DATA "scatter.glb", "rb");
    CHECK(f != NULL);
    if (!f) return;
    unsigned char buf[8192];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    int failures = 0;
    for (size_t len = 0; len < n; len++) {
        if (sss_gltf_parse(buf, len, NULL, "prefix.glb", NULL, &s, &err) == SSS_OK) sss_gltf_scene_free(&s);
        else failures++;
    }
    CHECK(failures == (int)n);
}

/* external.gltf's triangle (its buffer "external data.bin") with members added: node and root hold
 * text after the node's and the root's first member, material the materials array ("" for none), uri
 * the buffer's URI as JSON text. */
static sss_result parse_variant(const char *name, const char *node, const char *root, const char *material,
                                const char *uri, const sss_gltf_desc *desc, sss_gltf_scene *s, sss_error *err)
{
    char json[4096];
    snprintf(json, sizeof json,
             "{\"asset\": {\"version\": \"2.0\"}%s, \"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0%s}],"
             " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}%s}]}], %s%s"
             "%s \"buffers\": [{\"uri\": \"%s\", \"byteLength\": 36}], \"bufferViews\": [{\"buffer\": 0, \"byteLength\": 36}],"
             " \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\"}]}",
             root, node, material[0] ? ", \"material\": 0" : "", material[0] ? "\"materials\": " : "", material,
             material[0] ? "," : "", uri);
    return sss_gltf_parse(json, strlen(json), DATA, name, desc, s, err);
}

static const char external_uri[] = "external%20data.bin";

/* Refused with code and a message holding needle (the file and the JSON path), nothing left in s. */
static void check_variant_refused(const char *node, const char *root, const char *material, const char *uri,
                                  const sss_gltf_desc *desc, sss_result code, const char *needle)
{
    sss_gltf_scene s;
    sss_error err = {0};
    sss_result res = parse_variant("v.gltf", node, root, material, uri, desc, &s, &err);
    CHECK_MSG(res == code, "%s%s%s: %d %s", node, root, material, (int)res, err.message);
    CHECK_MSG(strstr(err.message, "v.gltf: ") && strstr(err.message, needle), "'%s' lacks '%s'", err.message, needle);
    CHECK(s.objects == NULL && s.object_count == 0);
    if (res == SSS_OK) sss_gltf_scene_free(&s);
}

static void check_variant_loads(const char *node, const char *root, const char *material)
{
    sss_gltf_scene s;
    sss_error err = {0};
    CHECK_MSG(parse_variant("v.gltf", node, root, material, external_uri, NULL, &s, &err) == SSS_OK, "%s%s%s: %s",
              node, root, material, err.message);
    sss_gltf_scene_free(&s);
}

/* A NUL in a JSON string (the escape, or a raw byte in a .glb's JSON chunk) is refused with the string's
 * path: cJSON's C strings would cut "external%20data.bin\u0000../../etc/passwd" to the buffer's file. */
static void test_nul_strings(void)
{
    check_variant_refused("", "", "", "external%20data.bin\\u0000../../etc/passwd", NULL, SSS_ERROR_PARSE,
                          "buffers[0].uri: a string holds a NUL character");
    check_variant_refused("", ", \"extras\": {\"a\\u0000\": 1}", "", external_uri, NULL, SSS_ERROR_PARSE,
                          "extras.a\\u0000: a string holds a NUL character");
    /* a .glb: 12-byte header, then the JSON chunk (padded to 4 bytes), with the raw byte or without */
    static const char json[] = "{\"asset\": {\"version\": \"2.0\", \"generator\": \"a#b\"}, \"scenes\": [{\"nodes\": []}]}";
    for (int raw = 0; raw < 2; raw++) {
        unsigned char glb[256] = {'g', 'l', 'T', 'F', 2};
        size_t n = strlen(json), padded = (n + 3) & ~(size_t)3, total = 20 + padded;
        memcpy(glb + 20, json, n);
        memset(glb + 20 + n, raw ? 0 : ' ', padded - n); /* zeros: padding written by some exporters */
        if (raw) *(char *)memchr(glb + 20, '#', n) = '\0';
        glb[8] = (unsigned char)total, glb[12] = (unsigned char)padded;
        memcpy(glb + 16, "JSON", 4);
        sss_gltf_scene s;
        sss_error err = {0};
        sss_result res = sss_gltf_parse(glb, total, NULL, "nul.glb", NULL, &s, &err);
        /* without the NUL, the asset parses and fails only for having nothing to render */
        const char *expected = raw ? "nul.glb: asset.generator: a string holds a NUL character" : "no mesh primitive";
        CHECK_MSG(res != SSS_OK && strstr(err.message, expected), "%s", err.message);
    }
}

/* Values outside the ranges of their schema are refused with their JSON path, not clamped or taken as
 * absent (multiscatterColor 1.5 used to become sigma_a = 0, -0.1 sigma_s = 0; aspectRatio 0 no ratio). */
static void test_out_of_range(void)
{
    static const char volume[] = "[{\"extensions\": {\"KHR_materials_volume\": {\"thicknessFactor\": %s, "
                                 "\"attenuationDistance\": 1, \"attenuationColor\": [0.5, 0.5, 0.5]}, "
                                 "\"KHR_materials_volume_scatter\": {\"%s\": %s}}}]";
#define MS "materials[0].extensions.KHR_materials_volume_scatter."
    struct { const char *thickness, *key, *value, *needle; } cases[] = {
        {"1", "multiscatterColor", "[1.5, 0.5, 0.5]", MS "multiscatterColor[0]: 1.5 is outside [0, 1]"},
        {"1", "multiscatterColor", "[0.5, -0.1, 0.5]", MS "multiscatterColor[1]: -0.1 is outside [0, 1]"},
        {"1", "multiscatterColorFactor", "[0.5, 0.5, 2]", MS "multiscatterColorFactor[2]: 2 is outside [0, 1]"},
        {"-1", "multiscatterColor", "[0.5, 0.5, 0.5]",
         "materials[0].extensions.KHR_materials_volume.thicknessFactor: -1 is negative"},
    };
#undef MS
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char material[512];
        snprintf(material, sizeof material, volume, cases[i].thickness, cases[i].key, cases[i].value);
        check_variant_refused("", "", material, external_uri, NULL, SSS_ERROR_INVALID_ARGUMENT, cases[i].needle);
    }
    char material[512];
    snprintf(material, sizeof material, volume, "1", "multiscatterColor", "[0, 1, 0.5]"); /* the ends are valid */
    check_variant_loads("", "", material);
    check_variant_refused("", "", "[{\"pbrMetallicRoughness\": {\"baseColorFactor\": [1, 1, 1, 1.5]}}]", external_uri,
                          NULL, SSS_ERROR_INVALID_ARGUMENT, "baseColorFactor[3]: 1.5 is outside [0, 1]");

    /* a camera's aspectRatio: absent is unknown; 0 or negative is refused */
    static const char camera[] = ", \"camera\": 0", cameras[] =
        ", \"cameras\": [{\"type\": \"perspective\", \"perspective\": {\"yfov\": 0.5, \"znear\": 0.1%s}}]";
    char root[256];
    snprintf(root, sizeof root, cameras, "");
    check_variant_loads(camera, root, "");
    const char *const aspects[] = {", \"aspectRatio\": 0", ", \"aspectRatio\": -1.5"};
    for (int i = 0; i < 2; i++) {
        snprintf(root, sizeof root, cameras, aspects[i]);
        check_variant_refused(camera, root, "", external_uri, NULL, SSS_ERROR_INVALID_ARGUMENT,
                              i ? "cameras[0].perspective.aspectRatio: -1.5 is outside" :
                                  "cameras[0].perspective.aspectRatio: 0 is outside");
    }
}

/* A material of materials[0] with a volume (t = thickness, d = 0.5, c = (0.5, 0.25, 0.125)), ior 1.4,
 * baseColor (0.8, 0.7, 0.6) and the extensions in `more` (JSON members); its import in *m. */
static sss_result load_material(const char *thickness, const char *more, sss_gltf_material *m, sss_error *err)
{
    char material[1024];
    snprintf(material, sizeof material,
             "[{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.8, 0.7, 0.6, 1]}, \"extensions\": {%s"
             "\"KHR_materials_volume\": {\"thicknessFactor\": %s, \"attenuationDistance\": 0.5, "
             "\"attenuationColor\": [0.5, 0.25, 0.125]}, \"KHR_materials_ior\": {\"ior\": 1.4}}}]",
             more, thickness);
    sss_gltf_scene s;
    sss_result res = parse_variant("m.gltf", "", "", material, external_uri, NULL, &s, err);
    if (res == SSS_OK) {
        *m = s.objects[0].material;
        m->texture = NULL;
        sss_gltf_scene_free(&s);
    }
    return res;
}

/* KHR_materials_scatter (the draft of KhronosGroup/glTF pull request 2579): rho_ms* = scatterStrength x
 * multiscatterColorFactor, rho_ss = (1 - s^2) / (1 - g s^2) with g (volume_scatter's has no g);
 * strength 0 (its default) is no scattering; without a volume it is a thin-walled surface (diffuse,
 * with a note); preferred over KHR_materials_volume_scatter. Before, the material became diffuse. */
static void test_scatter_extension(void)
{
    sss_gltf_material m;
    sss_error err = {0};
    const double sigma_t[3] = {-log(0.5) / 0.5, -log(0.25) / 0.5, -log(0.125) / 0.5};
    static const double rho[3] = {0.8 * 0.9, 0.8 * 0.6, 0.8 * 0.3};
    static const char scatter[] = "\"KHR_materials_scatter\": {\"%s\": 0.8, \"multiscatterColorFactor\": "
                                  "[0.9, 0.6, 0.3], \"scatterAnisotropy\": 0.5}, ";
    const char *const weights[] = {"scatterStrengthFactor", "scatterFactor"}; /* README, schema file */
    for (int i = 0; i < 2; i++) {
        char more[512];
        snprintf(more, sizeof more, scatter, weights[i]);
        CHECK_MSG(load_material("1", more, &m, &err) == SSS_OK, "%s", err.message);
        check_medium(&m, sigma_t, rho, 0.5, 1, 1.4);
        CHECK(m.note == NULL);
        /* the formula's g matters: without it rho_ss differs (here by more than 1e-3 in the red) */
        CHECK(fabs(spec_albedo(rho[0], 0.5, 1) - spec_albedo(rho[0], 0.5, 0)) > 1e-3);
    }
    /* with KHR_materials_volume_scatter beside it (g 0.2): KHR_materials_scatter's values count */
    CHECK_MSG(load_material("1", "\"KHR_materials_volume_scatter\": {\"multiscatterColor\": [0.5, 0.5, 0.5], "
                                 "\"scatterAnisotropy\": 0.2}, \"KHR_materials_scatter\": {\"scatterStrengthFactor\": "
                                 "0.8, \"multiscatterColorFactor\": [0.9, 0.6, 0.3], \"scatterAnisotropy\": 0.5}, ",
                            &m, &err) == SSS_OK, "%s", err.message);
    check_medium(&m, sigma_t, rho, 0.5, 1, 1.4);
    /* strength 0 or absent: a clear volume -> diffuse, nothing dropped */
    CHECK(load_material("1", "\"KHR_materials_scatter\": {\"multiscatterColorFactor\": [0.9, 0.6, 0.3]}, ", &m,
                        &err) == SSS_OK);
    CHECK(!m.subsurface && m.note == NULL);
    /* thin-walled (thicknessFactor 0): diffuse, with a note naming the extension */
    snprintf(err.message, sizeof err.message, "%s", "");
    char more[512];
    snprintf(more, sizeof more, scatter, "scatterStrengthFactor");
    CHECK(load_material("0", more, &m, &err) == SSS_OK);
    CHECK(!m.subsurface && m.note && strstr(m.note, "KHR_materials_scatter without an attenuating volume"));
    /* out of its schema's ranges: refused with the path */
    static const struct { const char *more, *needle; } bad[] = {
        {"\"KHR_materials_scatter\": {\"scatterStrengthFactor\": 1.5}, ",
         "KHR_materials_scatter.scatterStrengthFactor: 1.5 is outside [0, 1]"},
        {"\"KHR_materials_scatter\": {\"scatterStrengthFactor\": 1, \"multiscatterColorFactor\": [1, 2, 1]}, ",
         "KHR_materials_scatter.multiscatterColorFactor[1]: 2 is outside [0, 1]"},
        {"\"KHR_materials_scatter\": {\"scatterStrengthFactor\": 1, \"scatterAnisotropy\": 1}, ",
         "KHR_materials_scatter.scatterAnisotropy: 1 is outside (-1, 1)"},
        {"\"KHR_materials_diffuse_transmission\": {\"diffuseTransmissionFactor\": -0.5}, ",
         "KHR_materials_diffuse_transmission.diffuseTransmissionFactor: -0.5 is outside [0, 1]"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        CHECK(load_material("1", bad[i].more, &m, &err) == SSS_ERROR_INVALID_ARGUMENT);
        CHECK_MSG(strstr(err.message, "m.gltf: materials[0].extensions.") && strstr(err.message, bad[i].needle), "%s",
                  err.message);
    }
}

/* KHR_materials_volume_scatter's inversion has no g: rho_ss = 1 - s^2 (its text, every version of the
 * draft); the importer used (1 - s^2) / (1 - g s^2), which moved sigma_a by 30-40% at g = 0.3. */
static void test_volume_scatter_without_g(void)
{
    sss_gltf_material m;
    sss_error err = {0};
    const double sigma_t[3] = {-log(0.5) / 0.5, -log(0.25) / 0.5, -log(0.125) / 0.5};
    static const double rho[3] = {0.9, 0.6, 0.3};
    CHECK_MSG(load_material("1", "\"KHR_materials_volume_scatter\": {\"multiscatterColor\": [0.9, 0.6, 0.3], "
                                 "\"scatterAnisotropy\": 0.7}, ", &m, &err) == SSS_OK, "%s", err.message);
    check_medium(&m, sigma_t, rho, 0.7, 0, 1.4);
}

/* A volume with KHR_materials_diffuse_transmission and no scattering extension (what Blender users
 * export) becomes the nearest subsurface medium instead of a silent diffuse material: rho = (1 - f)
 * baseColor + f diffuseTransmissionColor exp(-sigma_t t), g 0, with a note. Here f = 0.25, colour
 * (1, 0.5, 0.25), t = 2, d = 0.5: exp(-sigma_t t) = c^(t/d) = c^4 = (0.0625, 0.00390625, 0.000244140625). */
static void test_diffuse_transmission_volume(void)
{
    sss_gltf_material m;
    sss_error err = {0};
    const double sigma_t[3] = {-log(0.5) / 0.5, -log(0.25) / 0.5, -log(0.125) / 0.5};
    static const double rho[3] = {0.75 * 0.8 + 0.25 * 1 * 0.0625, 0.75 * 0.7 + 0.25 * 0.5 * 0.00390625,
                                  0.75 * 0.6 + 0.25 * 0.25 * 0.000244140625}; /* 0.615625, 0.525488..., 0.450015... */
    CHECK_MSG(load_material("2", "\"KHR_materials_diffuse_transmission\": {\"diffuseTransmissionFactor\": 0.25, "
                                 "\"diffuseTransmissionColorFactor\": [1, 0.5, 0.25]}, ", &m, &err) == SSS_OK, "%s",
              err.message);
    check_medium(&m, sigma_t, rho, 0, 0, 1.4);
    CHECK(m.note && strstr(m.note, "mapped to the nearest subsurface material"));
    /* factor 0 (the default): no transmission, a clear volume -> diffuse, nothing dropped */
    CHECK(load_material("2", "\"KHR_materials_diffuse_transmission\": {}, ", &m, &err) == SSS_OK);
    CHECK(!m.subsurface && m.note == NULL);
    /* a thin surface that transmits diffusely: diffuse, with a note */
    CHECK(load_material("0", "\"KHR_materials_diffuse_transmission\": {\"diffuseTransmissionFactor\": 1}, ", &m,
                        &err) == SSS_OK);
    CHECK(!m.subsurface && m.note && strstr(m.note, "KHR_materials_diffuse_transmission without an attenuating volume"));
}

/* Triangle t of m as reference vertex indices (map: m's vertex -> the reference's), rotated to start at
 * the smallest: the same oriented triangle gives the same triple whatever its first corner. */
static void canonical_triangle(const sss_mesh *m, const uint32_t *map, size_t t, uint32_t out[3])
{
    uint32_t v[3] = {map[m->indices[3 * t]], map[m->indices[3 * t + 1]], map[m->indices[3 * t + 2]]};
    int first = v[0] <= v[1] && v[0] <= v[2] ? 0 : v[1] <= v[2] ? 1 : 2;
    for (int k = 0; k < 3; k++) out[k] = v[(first + k) % 3];
}

static int compare_triples(const void *a, const void *b)
{
    const uint32_t *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
    return 0;
}

/* m is ref decompressed: each vertex within pos_tol of one reference vertex, one to one (the writers
 * reorder vertices), normals within nrm_tol, and the same oriented triangles (as a set: they reorder
 * triangles too). */
static void check_same_topology(const sss_mesh *ref, const sss_mesh *m, double pos_tol, double nrm_tol,
                                const char *what)
{
    CHECK_MSG(m->vertex_count == ref->vertex_count && m->triangle_count == ref->triangle_count, "%s: %u/%u vs %u/%u",
              what, m->vertex_count, m->triangle_count, ref->vertex_count, ref->triangle_count);
    if (m->vertex_count != ref->vertex_count || m->triangle_count != ref->triangle_count) return;
    size_t n = m->vertex_count, t = m->triangle_count;
    uint32_t *map = malloc(n * sizeof *map), *a = malloc(3 * t * sizeof *a), *b = malloc(3 * t * sizeof *b);
    unsigned char *used = calloc(n, 1);
    double worst = 0, worst_n = 0;
    int one_to_one = 1;
    for (size_t i = 0; map && used && i < n; i++) {
        double best = INFINITY;
        for (size_t j = 0; j < n; j++) {
            double d = 0;
            for (int k = 0; k < 3; k++) d = fmax(d, fabs((double)m->positions[3 * i + k] - ref->positions[3 * j + k]));
            if (d < best) best = d, map[i] = (uint32_t)j;
        }
        worst = fmax(worst, best);
        one_to_one &= !used[map[i]]++;
        for (int k = 0; k < 3; k++)
            worst_n = fmax(worst_n, fabs((double)m->normals[3 * i + k] - ref->normals[3 * (size_t)map[i] + k]));
    }
    CHECK_MSG(worst <= pos_tol, "%s: a vertex %g from the nearest original (step %g)", what, worst, pos_tol);
    CHECK_MSG(worst_n <= nrm_tol, "%s: a normal %g from the original's", what, worst_n);
    CHECK_MSG(one_to_one, "%s: two vertices match one original", what);
    uint32_t *identity = malloc(n * sizeof *identity);
    for (size_t i = 0; identity && i < n; i++) identity[i] = (uint32_t)i;
    for (size_t i = 0; map && a && b && identity && i < t; i++) {
        canonical_triangle(m, map, i, a + 3 * i);
        canonical_triangle(ref, identity, i, b + 3 * i);
    }
    if (a && b) {
        qsort(a, t, 3 * sizeof *a, compare_triples);
        qsort(b, t, 3 * sizeof *b, compare_triples);
        CHECK_MSG(memcmp(a, b, 3 * t * sizeof *a) == 0, "%s: the triangles differ", what);
    }
    free(identity);
    free(used);
    free(map);
    free(a);
    free(b);
}

/* Compressed assets (tests/data/gltf/make_compressed.sh: assets/bunny.ply through @gltf-transform/cli
 * 4.5.1) import to the bunny itself: Draco (edgebreaker, sequential), EXT_meshopt_compression with
 * KHR_mesh_quantization, and KHR_mesh_quantization alone. Positions within the writers' quantization
 * step (14 bits over the largest extent: gltf-transform's default), normals within what 8 to 10 bits
 * keep, the same triangles; before, every one was refused ("KHR_draco_mesh_compression" is not
 * supported, ...). */
static void test_compressed_assets(void)
{
    sss_mesh ref;
    sss_error err = {0};
    CHECK_MSG(sss_mesh_read(SSS_SOURCE_DIR "/assets/bunny.ply", &ref, &err) == SSS_OK, "%s", err.message);
    float lo[3], hi[3];
    sss_mesh_bounds(&ref, lo, hi);
    double extent = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    double step = extent / ((1 << 14) - 1);
    const char *const assets[] = {"bunny_draco.glb", "bunny_draco_sequential.glb", "bunny_meshopt.glb",
                                  "bunny_quantized.glb"};
    for (int i = 0; i < 4; i++) {
        char path[512];
        snprintf(path, sizeof path, DATA "%s", assets[i]);
        sss_gltf_scene s;
        CHECK_MSG(sss_gltf_load(path, NULL, &s, &err) == SSS_OK, "%s", err.message);
        if (s.object_count != 1) continue;
        check_same_topology(&ref, &s.objects[0].mesh, step, 0.03, assets[i]);
        CHECK(s.objects[0].mesh.source_flags & SSS_MESH_FROM_FILE_NORMALS);
        sss_gltf_scene_free(&s);
    }
    sss_mesh_free(&ref);
}

/* What a renderer cannot carry in float is refused at import with its path: a node placing a vertex
 * beyond the world range (the loader's limit, which `sss import` used to write into scenes every other
 * command refused), a light beyond SSS_SCENE_MAX_LIGHT_VALUE, also through the import's light scale. */
static void test_float_range(void)
{
    check_variant_refused(", \"scale\": [1e30, 1e30, 1e30]", "", "", external_uri, NULL, SSS_ERROR_LIMIT,
                          "nodes[0] places meshes[0].primitives[0] vertex 1 at 1e+30, beyond 1e+18");
    check_variant_loads(", \"scale\": [1e18, 1e18, 1e18]", "", ""); /* the triangle reaches 1e18 exactly */
    static const char lights[] = ", \"extensions\": {\"KHR_lights_punctual\": {\"lights\": [{\"type\": \"point\", "
                                 "\"intensity\": %s, \"color\": [1, 0.5, 1]}]}}";
    static const char light_node[] = ", \"children\": [1]}, {\"extensions\": {\"KHR_lights_punctual\": {\"light\": 0}}";
    char root[256];
    snprintf(root, sizeof root, lights, "1e39");
    check_variant_refused(light_node, root, "", external_uri, NULL, SSS_ERROR_INVALID_ARGUMENT,
                          "extensions.KHR_lights_punctual.lights[0].intensity: 1e+39 x color[0] 1 x light scale 1 = "
                          "1e+39, beyond the 1e+30");
    snprintf(root, sizeof root, lights, "100");
    sss_gltf_desc desc = {.light_scale = 1e29};
    check_variant_refused(light_node, root, "", external_uri, &desc, SSS_ERROR_INVALID_ARGUMENT,
                          "lights[0].intensity: 100 x color[0] 1 x light scale 1e+29 = 1e+31, beyond");
    desc.light_scale = 1e27;
    sss_gltf_scene s;
    sss_error err = {0};
    CHECK_MSG(parse_variant("v.gltf", light_node, root, "", external_uri, &desc, &s, &err) == SSS_OK, "%s", err.message);
    CHECK(s.light_count == 1);
    if (s.light_count == 1) CHECK_REL(s.lights[0].intensity[1], 5e28, 1e-15);
    sss_gltf_scene_free(&s);
}

/* sss_scene_load of a .glb: the scene loader's materials and the imported meshes; a written import
 * loads to the same meshes. */
static void test_scene_load(void)
{
    sss_scene direct, written;
    sss_error err = {0};
    CHECK_MSG(sss_scene_load(DATA "scatter.glb", NULL, &direct, &err) == SSS_OK, "%s", err.message);
    CHECK(direct.object_count == 6 && direct.light_count == 3);
    const sss_scene_object *o = &direct.objects[0];
    CHECK(o->material.type == SSS_SCENE_MATERIAL_SUBSURFACE && o->mesh.triangle_count == 12);
    CHECK_REL(o->material.optical.sigma_a[0] + o->material.optical.sigma_s[0], -log(0.5) / 0.25, 1e-12);
    CHECK(o->bounds_max[1] > o->bounds_min[1]);
    CHECK_MSG(o->mesh_path && strstr(o->mesh_path, "gltf/scatter.glb#meshes[0].primitives[0]"), "%s", o->mesh_path);

    sss_gltf_scene g;
    char dir[] = "/tmp/sss_test_gltf_XXXXXX", path[512];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/imported.json", dir);
    CHECK(sss_gltf_load(DATA "scatter.glb", NULL, &g, &err) == SSS_OK);
    CHECK_MSG(sss_gltf_write_scene(&g, path, &err) == SSS_OK, "%s", err.message);
    sss_gltf_scene_free(&g);
    CHECK_MSG(sss_scene_load(path, NULL, &written, &err) == SSS_OK, "%s", err.message);
    CHECK(written.object_count == direct.object_count);
    for (size_t i = 0; i < written.object_count && i < direct.object_count; i++) {
        check_same_mesh(&written.objects[i].mesh, &direct.objects[i].mesh);
        CHECK(memcmp(&written.objects[i].material.optical, &direct.objects[i].material.optical,
                     sizeof(sss_material)) == 0);
        char ply[600];
        snprintf(ply, sizeof ply, "%s/imported_obj%zu.ply", dir, i);
        remove(ply);
    }
    CHECK(memcmp(&written.camera, &direct.camera, sizeof(sss_camera)) == 0);
    remove(path);
    rmdir(dir);
    sss_scene_free(&written);
    sss_scene_free(&direct);
}

int main(void)
{
    test_materials();
    test_node_transforms();
    test_cameras();
    test_lights();
    test_glb_equals_gltf();
    test_external_buffer();
    test_gltf_transform_asset();
    test_exported_asset();
    test_texture();
    test_embedded_textures();
    test_bad_inputs();
    test_nul_strings();
    test_out_of_range();
    test_float_range();
    test_compressed_assets();
    test_scatter_extension();
    test_volume_scatter_without_g();
    test_diffuse_transmission_volume();
    test_scene_load();
    return CHECK_DONE();
}
