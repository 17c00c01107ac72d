/* glTF export round trip: a scene exported by sss_export_gltf and imported by sss_gltf_load gives
 * back its world meshes, coefficients (sigma_a, sigma_s, g, eta per scene unit), camera basis and
 * punctual lights, with either scattering extension (KHR_materials_volume_scatter, KHR_materials_scatter);
 * area lights are counted as left out; the file is a valid .glb container; albedo
 * textures travel as embedded PNGs with their pixels. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "sss/export.h"
#include "sss/gltf.h"
#include "sss/image.h"
#include "sss/scene.h"

static const char scene_json[] =
    "{\"camera\": {\"position\": [0.5, 1, 5], \"look_at\": [0, 0.5, 0], \"fov\": 40, \"width\": 200, \"height\": 300},"
    " \"objects\": ["
    "  {\"procedural\": {\"shape\": \"sphere\", \"radius\": 0.5, \"subdivisions\": 2},"
    "   \"transform\": {\"translate\": [1, 2, 3], \"rotate\": [1, 1, 0, 70], \"scale\": [2, 1, 1]},"
    "   \"material\": {\"type\": \"subsurface\", \"medium\": \"skin1\", \"scale\": 10, \"eta\": 1.4}},"
    "  {\"procedural\": {\"shape\": \"box\", \"size\": [1, 1, 1]}, \"transform\": {\"scale\": [-1, 1, 1]},"
    "   \"animation\": {\"type\": \"twist\", \"amplitude\": 30, \"period\": 2},"
    "   \"material\": {\"type\": \"subsurface\", \"sigma_a\": [0.1, 0.2, 0.3], \"sigma_s\": [1, 2, 3], \"g\": 0.5}},"
    "  {\"procedural\": {\"shape\": \"torus\", \"major\": 1, \"minor\": 0.25, \"segments\": 16},"
    "   \"material\": {\"type\": \"subsurface\", \"reflectance\": [0.5, 0.6, 0.7], \"mfp\": 0.2, \"eta\": 1.0}},"
    "  {\"procedural\": {\"shape\": \"plane\", \"size\": 4},"
    "   \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.25, 0.5, 0.75]}}],"
    " \"lights\": ["
    "  {\"type\": \"point\", \"position\": [1, 2, 3], \"intensity\": [4, 5, 6]},"
    "  {\"type\": \"spot\", \"position\": [0, 3, 0], \"look_at\": [0.5, 0, 0], \"cone_angle\": 30, \"cone_delta\": 5,"
    "   \"intensity\": [1, 0, 2]},"
    "  {\"type\": \"spot\", \"position\": [0, 3, 1], \"look_at\": [0, 0, 1], \"cone_angle\": 20, \"cone_delta\": 0,"
    "   \"intensity\": [3, 3, 3]},"
    "  {\"type\": \"directional\", \"direction\": [0.3, -1, 0.2], \"radiance\": [2, 2, 2]},"
    "  {\"type\": \"area\", \"center\": [0, 4, 0], \"u\": [1, 0, 0], \"v\": [0, 0, 1], \"radiance\": [1, 1, 1]}]}";

static void check_vec(const double *a, const double *b, int n, double tol)
{
    for (int k = 0; k < n; k++) CHECK_NEAR(a[k], b[k], tol);
}

static void check_camera(const sss_camera *a, const sss_camera *b)
{
    sss_camera_basis x, y;
    CHECK(sss_camera_basis_init(a, &x, NULL) == SSS_OK && sss_camera_basis_init(b, &y, NULL) == SSS_OK);
    check_vec(x.origin, y.origin, 3, 1e-12);
    check_vec(x.right, y.right, 3, 1e-12);
    check_vec(x.up, y.up, 3, 1e-12);
    check_vec(x.forward, y.forward, 3, 1e-12);
    check_vec(x.tan_half, y.tan_half, 2, 1e-12);
    CHECK(x.width == y.width && x.height == y.height);
}

static void check_light(const sss_light *a, const sss_light *b)
{
    CHECK(a->type == b->type);
    if (a->type == SSS_LIGHT_DIRECTIONAL) {
        check_vec(a->direction, b->direction, 3, 1e-12);
        check_vec(a->radiance, b->radiance, 3, 1e-12);
        return;
    }
    check_vec(a->position, b->position, 3, 1e-12);
    check_vec(a->intensity, b->intensity, 3, 1e-12);
    if (a->type != SSS_LIGHT_SPOT) return;
    double da[3], db[3], la = 0, lb = 0;
    for (int k = 0; k < 3; k++) {
        da[k] = a->look_at[k] - a->position[k], db[k] = b->look_at[k] - b->position[k];
        la += da[k] * da[k], lb += db[k] * db[k];
    }
    for (int k = 0; k < 3; k++) CHECK_NEAR(da[k] / sqrt(la), db[k] / sqrt(lb), 1e-12);
    CHECK_NEAR(a->cone_angle, b->cone_angle, 1e-12);
    CHECK_NEAR(a->cone_delta, b->cone_delta, 1e-9); /* delta 0 becomes a delta of one ulp of the angle */
}

/* The JSON chunk of the .glb at path (malloc'd, NUL-terminated), or NULL. */
static char *json_chunk(const char *path)
{
    FILE *f = fopen(path, "rb");
    unsigned char head[20];
    uint32_t length = 0;
    char *json = NULL;
    if (f && fread(head, 1, 20, f) == 20) {
        memcpy(&length, head + 12, 4);
        json = length < (1u << 26) ? calloc(length + 1, 1) : NULL;
        if (json && fread(json, 1, length, f) != length) json[0] = '\0';
    }
    if (f) fclose(f);
    return json;
}

/* Exported with either scattering extension, imported: the same coefficients (which = the extension). */
static void round_trip(sss_export_gltf_scatter which)
{
    sss_scene scene;
    sss_error err = {0};
    CHECK_MSG(sss_scene_parse(scene_json, strlen(scene_json), ".", "rt", NULL, &scene, &err) == SSS_OK, "%s",
              err.message);
    char dir[] = "/tmp/sss_test_export_gltf_XXXXXX", path[512];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/rt.glb", dir);
    const double time = 0.7; /* the animated box is exported posed */
    sss_export_gltf_desc desc = {.time = time, .scatter_extension = which};
    CHECK_MSG(sss_export_gltf(&scene, &desc, path, &err) == SSS_OK, "%s", err.message);
    CHECK(desc.skipped_lights == 1); /* the area light */
    /* the chosen extension and its companions only: KHR_materials_scatter excludes diffuse transmission
     * and needs transmission (KhronosGroup/glTF pull request 2579) */
    char *json = json_chunk(path);
    CHECK(json != NULL);
    if (json) {
        int scatter = which == SSS_EXPORT_GLTF_SCATTER;
        CHECK((strstr(json, "\"KHR_materials_scatter\"") != NULL) == scatter);
        CHECK((strstr(json, "KHR_materials_transmission") != NULL) == scatter);
        CHECK((strstr(json, "KHR_materials_volume_scatter") == NULL) == scatter);
        CHECK((strstr(json, "KHR_materials_diffuse_transmission") == NULL) == scatter);
        CHECK(!scatter || strstr(json, "\"scatterStrengthFactor\":1"));
    }
    free(json);

    sss_gltf_desc in = {.width = scene.camera.width, .height = scene.camera.height};
    sss_gltf_scene g;
    CHECK_MSG(sss_gltf_load(path, &in, &g, &err) == SSS_OK, "%s", err.message);
    CHECK(g.object_count == scene.object_count && g.light_count == 4);
    for (size_t i = 0; i < g.object_count && i < scene.object_count; i++) {
        sss_mesh world = {0};
        CHECK(sss_scene_object_world_mesh(&scene.objects[i], time, &world, NULL) == SSS_OK);
        const sss_mesh *m = &g.objects[i].mesh;
        CHECK(m->vertex_count == world.vertex_count && m->triangle_count == world.triangle_count);
        if (m->vertex_count == world.vertex_count && m->triangle_count == world.triangle_count) {
            CHECK(memcmp(m->positions, world.positions, 12 * (size_t)m->vertex_count) == 0);
            CHECK(memcmp(m->indices, world.indices, 12 * (size_t)m->triangle_count) == 0);
            double dn = 0;
            for (size_t k = 0; k < 3 * (size_t)m->vertex_count; k++) dn = fmax(dn, fabs(m->normals[k] - world.normals[k]));
            CHECK_NEAR(dn, 0, 1e-6);
            CHECK(!world.uvs == !m->uvs);
        }
        sss_mesh_free(&world);
        const sss_scene_material *a = &scene.objects[i].material;
        const sss_gltf_material *b = &g.objects[i].material;
        CHECK(b->subsurface == (a->type == SSS_SCENE_MATERIAL_SUBSURFACE));
        if (!b->subsurface) {
            check_vec(a->albedo, b->albedo, 3, 0);
            continue;
        }
        for (int k = 0; k < 3; k++) {
            CHECK_REL(b->sigma_a[k], a->optical.sigma_a[k], 1e-9);
            CHECK_REL(b->sigma_s[k], a->optical.sigma_s[k], 1e-9);
        }
        CHECK_NEAR(b->g, a->optical.g, 0);
        CHECK_NEAR(b->eta, a->optical.eta, 0);
    }
    check_camera(&scene.camera, &g.camera);
    for (size_t i = 0; i < 4 && i < g.light_count; i++) check_light(&scene.lights[i], &g.lights[i]);
    sss_gltf_scene_free(&g);

    /* the container: "glTF", version 2, the header's length = the file's, chunks JSON then BIN */
    FILE *f = fopen(path, "rb");
    unsigned char head[20];
    CHECK(f && fread(head, 1, 20, f) == 20);
    long size = f && fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
    if (f) fclose(f);
    uint32_t version, length;
    memcpy(&version, head + 4, 4);
    memcpy(&length, head + 8, 4);
    CHECK(memcmp(head, "glTF", 4) == 0 && version == 2 && (long)length == size && memcmp(head + 16, "JSON", 4) == 0);

    /* a failed export leaves nothing: a folder that does not exist */
    char bad[600];
    snprintf(bad, sizeof bad, "%s/missing/x.glb", dir);
    CHECK(sss_export_gltf(&scene, NULL, bad, &err) == SSS_ERROR_IO);
    remove(path);
    CHECK(rmdir(dir) == 0); /* empty: no temporary file left */
    sss_scene_free(&scene);
}

static void test_round_trip(void)
{
    round_trip(SSS_EXPORT_GLTF_VOLUME_SCATTER);
    round_trip(SSS_EXPORT_GLTF_SCATTER);
    sss_scene scene = {0};
    sss_export_gltf_desc bad = {.scatter_extension = (sss_export_gltf_scatter)7};
    sss_error err = {0};
    CHECK(sss_export_gltf(&scene, &bad, "/tmp/unused.glb", &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(access("/tmp/unused.glb", F_OK) != 0);
}

/* A textured object (the JPEG of the image tests, decoded once by the scene loader) exports as an
 * embedded PNG baseColorTexture that imports to the same pixels, bit for bit. */
static void test_texture(void)
{
    static const char textured[] =
        "{\"camera\": {\"position\": [0, 0, 3], \"look_at\": [0, 0, 0], \"width\": 32, \"height\": 32},"
        " \"objects\": [{\"procedural\": {\"shape\": \"box\", \"size\": [1, 1, 1]},"
        "   \"material\": {\"type\": \"subsurface\", \"medium\": \"marble\", \"texture\": \"two_colours.jpg\"}}]}";
    sss_error err = {0};
    sss_scene scene;
    sss_image jpeg;
    CHECK(sss_image_read(SSS_TEST_DATA "/images/two_colours.jpg", &jpeg, &err) == SSS_OK);
    CHECK_MSG(sss_scene_parse(textured, strlen(textured), SSS_TEST_DATA "/images", "textured.json", NULL, &scene,
                              &err) == SSS_OK, "%s", err.message);
    char dir[] = "/tmp/sss_test_export_XXXXXX", path[600];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/textured.glb", dir);
    CHECK_MSG(sss_export_gltf(&scene, NULL, path, &err) == SSS_OK, "%s", err.message);
    sss_gltf_scene g;
    CHECK_MSG(sss_gltf_load(path, NULL, &g, &err) == SSS_OK, "%s", err.message);
    CHECK(g.object_count == 1 && g.objects[0].material.image == 0 && g.image_count == 1);
    if (g.image_count == 1 && g.images[0].pixels && g.images[0].width == jpeg.width && g.images[0].height == jpeg.height)
        CHECK(memcmp(g.images[0].pixels, jpeg.pixels, sizeof(float) * 3 * (size_t)jpeg.width * (size_t)jpeg.height) == 0);
    else
        CHECK_MSG(0, "exported image missing or resized");
    sss_gltf_scene_free(&g);
    sss_scene_free(&scene);
    sss_image_free(&jpeg);
    remove(path);
    CHECK(rmdir(dir) == 0);
}

int main(void)
{
    test_round_trip();
    test_texture();
    return CHECK_DONE();
}
