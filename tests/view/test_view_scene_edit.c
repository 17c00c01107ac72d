/* tests/view/test_view_scene_edit.c — the viewer's scene edits go through the scene loader: the edited
 * text loads, the camera and light come back exactly, a medium preset resolves to the same coefficients
 * as the material module computes for that medium and scale, the scale factor multiplies the
 * coefficients (or divides kdsubsurface's mean free path), untouched parts stay as in the file. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sss/material.h"
#include "view/view_internal.h"

static const char scene_text[] =
    "{\"camera\": {\"position\": [0, 0.5, 4], \"look_at\": [0, 0, 0], \"fov\": 40, \"width\": 32, \"height\": 24},\n"
    " \"objects\": [\n"
    "  {\"procedural\": {\"shape\": \"sphere\", \"radius\": 0.5, \"subdivisions\": 1},\n"
    "   \"material\": {\"type\": \"subsurface\", \"sigma_a\": [0.1, 0.2, 0.3], \"sigma_s\": [1, 2, 3],\n"
    "                \"scale\": 2, \"eta\": 1.4, \"g\": 0.3}},\n"
    "  {\"procedural\": {\"shape\": \"sphere\", \"radius\": 0.5, \"subdivisions\": 1},\n"
    "   \"transform\": {\"translate\": [1.5, 0, 0]},\n"
    "   \"material\": {\"type\": \"subsurface\", \"reflectance\": [0.8, 0.6, 0.4], \"mfp\": [0.5, 0.25, 0.125]}},\n"
    "  {\"procedural\": {\"shape\": \"sphere\", \"radius\": 0.5, \"subdivisions\": 1},\n"
    "   \"transform\": {\"translate\": [-1.5, 0, 0]},\n"
    "   \"material\": {\"type\": \"subsurface\", \"medium\": \"marble\"}},\n"
    "  {\"procedural\": {\"shape\": \"plane\", \"size\": 6}, \"transform\": {\"translate\": [0, -1, 0]},\n"
    "   \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.4, 0.5, 0.6]}}],\n"
    " \"lights\": [{\"type\": \"area\", \"center\": [-1, 1.8, 0.5], \"u\": [0.5, 0, 0], \"v\": [0, 0, 0.5],\n"
    "             \"radiance\": [6, 6, 6]},\n"
    "            {\"type\": \"point\", \"position\": [2, 2, 2], \"intensity\": [1, 1, 1]}]}\n";

static int load_edited(const view_edits *e, sss_scene *s)
{
    char *json = NULL;
    sss_error err = {0};
    if (view_scene_json(scene_text, strlen(scene_text), "edit.json", e, &json, &err) != SSS_OK) {
        fprintf(stderr, "edit: %s\n", err.message);
        return 0;
    }
    sss_result r = sss_scene_parse(json, strlen(json), ".", "edit.json", NULL, s, &err);
    free(json);
    if (r != SSS_OK) fprintf(stderr, "parse: %s\n", err.message);
    return r == SSS_OK;
}

static int medium_index(const char *name)
{
    for (size_t i = 0; i < sss_measured_medium_count(); i++)
        if (strcmp(sss_measured_medium_at(i)->name, name) == 0) return (int)i;
    return -1;
}

static void check_material(const sss_material *got, const sss_material *want)
{
    for (int k = 0; k < 3; k++) {
        CHECK_REL(got->sigma_a[k], want->sigma_a[k], 1e-12);
        CHECK_REL(got->sigma_s[k], want->sigma_s[k], 1e-12);
    }
    CHECK_NEAR(got->eta, want->eta, 1e-15);
    CHECK_NEAR(got->g, want->g, 1e-15);
}

static void test_identity(void)
{
    sss_scene a, b;
    view_edits e = {NULL, NULL, -1, 0.0};
    sss_error err = {0};
    CHECK(sss_scene_parse(scene_text, strlen(scene_text), ".", "x", NULL, &a, &err) == SSS_OK);
    CHECK(load_edited(&e, &b));
    for (size_t i = 0; i < a.object_count && i < b.object_count; i++) {
        check_material(&b.objects[i].material.optical, &a.objects[i].material.optical);
        for (int k = 0; k < 3; k++) CHECK_NEAR(b.objects[i].material.albedo[k], a.objects[i].material.albedo[k], 0.0);
    }
    for (int k = 0; k < 3; k++) CHECK_NEAR(b.camera.position[k], a.camera.position[k], 0.0);
    sss_scene_free(&a);
    sss_scene_free(&b);
}

static void test_camera_light(void)
{
    sss_camera cam;
    memset(&cam, 0, sizeof cam);
    double p[3] = {0.1234567890123, 0.7, 3.3}, l[3] = {0.01, -0.02, 0.03}, up[3] = {0, 1, 0};
    memcpy(cam.position, p, sizeof p);
    memcpy(cam.look_at, l, sizeof l);
    memcpy(cam.up, up, sizeof up);
    cam.fov = 33.3;
    cam.width = 17;
    cam.height = 19;
    sss_light light;
    memset(&light, 0, sizeof light);
    light.type = SSS_LIGHT_AREA;
    double c[3] = {-0.3, 2.0, 1.0 / 3.0}, u[3] = {0.4, 0, 0.3}, v[3] = {-0.3, 0, 0.4};
    memcpy(light.center, c, sizeof c);
    memcpy(light.u, u, sizeof u);
    memcpy(light.v, v, sizeof v);
    view_edits e = {&cam, &light, -1, 1.0};
    sss_scene s;
    CHECK(load_edited(&e, &s));
    for (int k = 0; k < 3; k++) {
        CHECK_NEAR(s.camera.position[k], p[k], 0.0); /* exact: cJSON prints round-trip digits */
        CHECK_NEAR(s.camera.look_at[k], l[k], 0.0);
        CHECK_NEAR(s.lights[0].center[k], c[k], 0.0);
        CHECK_NEAR(s.lights[0].u[k], u[k], 0.0);
        CHECK_NEAR(s.lights[0].v[k], v[k], 0.0);
    }
    CHECK_NEAR(s.camera.fov, 33.3, 0.0);
    CHECK(s.camera.width == 17 && s.camera.height == 19);
    CHECK(s.lights[0].type == SSS_LIGHT_AREA);
    CHECK_NEAR(s.lights[1].position[0], 2.0, 0.0); /* the second light is untouched */
    CHECK_NEAR(s.lights[0].radiance[0], 6.0, 0.0);
    sss_scene_free(&s);
}

static void test_presets(void)
{
    int skin = medium_index("Skin1");
    CHECK(skin >= 0);
    view_edits e = {NULL, NULL, skin, 2.0};
    sss_scene s;
    CHECK(load_edited(&e, &s));
    /* every subsurface material becomes Skin1; the file's scale (mm per unit) is kept, times 2 */
    double scales[3] = {2.0 * 2.0, 1.0 * 2.0, 1.0 * 2.0}, etas[3] = {1.4, 1.33, 1.33};
    for (int i = 0; i < 3; i++) {
        sss_material want;
        CHECK(sss_material_from_medium("Skin1", scales[i], etas[i], &want, NULL) == SSS_OK);
        CHECK(s.objects[i].material.source == SSS_SUBSURFACE_MEDIUM);
        CHECK(s.objects[i].material.medium && strcmp(s.objects[i].material.medium->name, "Skin1") == 0);
        check_material(&s.objects[i].material.optical, &want);
    }
    CHECK(s.objects[3].material.type == SSS_SCENE_MATERIAL_DIFFUSE);
    CHECK_NEAR(s.objects[3].material.albedo[2], 0.6, 0.0);
    sss_scene_free(&s);
}

static void test_scale_only(void)
{
    view_edits e = {NULL, NULL, -1, 0.5};
    sss_scene s;
    CHECK(load_edited(&e, &s));
    /* coefficients: scale 2 x 0.5 = 1 */
    double sa[3] = {0.1, 0.2, 0.3}, ss[3] = {1, 2, 3};
    sss_material want;
    CHECK(sss_material_from_coefficients(sa, ss, 1.0, 1.4, 0.3, &want, NULL) == SSS_OK);
    check_material(&s.objects[0].material.optical, &want);
    /* kdsubsurface: half the coefficients is twice the mean free path */
    CHECK_NEAR(s.objects[1].material.mfp[0], 1.0, 0.0);
    CHECK_NEAR(s.objects[1].material.mfp[1], 0.5, 0.0);
    CHECK_NEAR(s.objects[1].material.mfp[2], 0.25, 0.0);
    /* a measured medium: scale 1 x 0.5 */
    CHECK(sss_material_from_medium("Marble", 0.5, 1.33, &want, NULL) == SSS_OK);
    check_material(&s.objects[2].material.optical, &want);
    sss_scene_free(&s);
}

static void test_errors(void)
{
    static const char no_lights[] =
        "{\"camera\": {\"position\": [0, 0, 4], \"look_at\": [0, 0, 0]},"
        " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1},"
        " \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}}]}";
    sss_light light;
    memset(&light, 0, sizeof light);
    view_edits e = {NULL, &light, -1, 1.0};
    char *json = NULL;
    sss_error err = {0};
    CHECK(view_scene_json(no_lights, strlen(no_lights), "nolights.json", &e, &json, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(json == NULL);
    CHECK(strstr(err.message, "nolights.json") && strstr(err.message, "lights[0]"));
    view_edits none = {NULL, NULL, -1, 1.0};
    CHECK(view_scene_json("[1, 2", 5, "broken.json", &none, &json, &err) == SSS_ERROR_PARSE);
    CHECK(strstr(err.message, "broken.json") != NULL);
    view_edits bad = {NULL, NULL, 100000, 1.0};
    CHECK(view_scene_json(scene_text, strlen(scene_text), "x.json", &bad, &json, &err) != SSS_OK);
}

int main(void)
{
    test_identity();
    test_camera_light();
    test_presets();
    test_scale_only();
    test_errors();
    return CHECK_DONE();
}
