/* tests/view/test_view_script.c — the panel-independent parts of the viewer's panel: `--script` lines
 * parse into the actions they name and every wrong line is refused with a reason (the file and line in
 * the message); material edits that switch a material's form give the same optical coefficients back
 * through the scene loader; light edits land on the light's own field; the split view takes whole
 * columns from each side (its divider and labels: test_view_compose.c); the error map's colours rise
 * in luminance over its fixed range. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "sss/image.h"
#include "sss/scene.h"
#include "view/script.h"
#include "view/view_internal.h"

static int parse(const char *line, view_command *c)
{
    char why[512] = "";
    int r = view_script_parse_line(line, c, why, sizeof why);
    if (r < 0) fprintf(stderr, "  '%s': %s\n", line, why);
    return r;
}

static void test_good_lines(void)
{
    view_command c;
    CHECK(parse("", &c) == 0);
    CHECK(parse("   # a comment", &c) == 0);
    CHECK(parse("technique ssss", &c) == 1 && c.kind == VIEW_CMD_TECHNIQUE && strcmp(c.name, "ssss") == 0);
    CHECK(parse("param maisch2020.brightening 0", &c) == 1 && c.kind == VIEW_CMD_PARAM &&
          strcmp(c.name, "maisch2020.brightening") == 0 && c.values[0] == 0.0);
    CHECK(parse("  param   brightening\t1 ", &c) == 1 && strcmp(c.name, "brightening") == 0 && c.values[0] == 1.0);
    CHECK(parse("material 2 scale 2.5", &c) == 1 && c.kind == VIEW_CMD_MATERIAL && c.index == 2 &&
          strcmp(c.name, "scale") == 0 && c.value_count == 1 && c.values[0] == 2.5);
    CHECK(parse("material 0 sigma_a 0.1 0.2 0.3", &c) == 1 && c.value_count == 3 && c.values[2] == 0.3);
    CHECK(parse("material 0 mfp 0.5", &c) == 1 && c.value_count == 1);
    CHECK(parse("material 1 medium ketchup", &c) == 1 && strcmp(c.text, "Ketchup") == 0);
    CHECK(parse("light 0 position 1 2 3", &c) == 1 && c.kind == VIEW_CMD_LIGHT && c.values[1] == 2.0);
    CHECK(parse("light 1 intensity 4", &c) == 1 && c.value_count == 1);
    CHECK(parse("light 0 color 1 0.5 0", &c) == 1 && strcmp(c.name, "colour") == 0);
    CHECK(parse("buffer irradiance", &c) == 1 && c.kind == VIEW_CMD_BUFFER && c.index == 2);
    CHECK(parse("split reference", &c) == 1 && c.kind == VIEW_CMD_SPLIT && c.values[0] == 0.5);
    CHECK(parse("split ssss 0.25", &c) == 1 && strcmp(c.name, "ssss") == 0 && c.values[0] == 0.25);
    CHECK(parse("split off", &c) == 1);
    CHECK(parse("errormap on", &c) == 1 && c.kind == VIEW_CMD_ERRORMAP && c.index == 1);
    CHECK(parse("errormap on 0.1", &c) == 1 && c.index == 1 && c.value_count == 1 && c.values[0] == 0.1);
    CHECK(parse("panel off", &c) == 1 && c.kind == VIEW_CMD_PANEL && c.index == 0 && strcmp(c.name, "off") == 0);
    CHECK(parse("panel open Lights", &c) == 1 && strcmp(c.name, "open") == 0 &&
          strcmp(view_panel_sections[c.index], "Lights") == 0);
    CHECK(parse("panel scroll frame_time", &c) == 1 && strcmp(c.name, "scroll") == 0 &&
          strcmp(view_panel_sections[c.index], "Frame time") == 0);
    CHECK(parse("panel close VIEW", &c) == 1 && strcmp(view_panel_sections[c.index], "View") == 0);
    CHECK(parse("panel width 300", &c) == 1 && strcmp(c.name, "width") == 0 && c.values[0] == 300.0);
    CHECK(parse("reference draft", &c) == 1 && c.kind == VIEW_CMD_REFERENCE && c.index == 1);
    CHECK(parse("key shift+tab", &c) == 1 && c.kind == VIEW_CMD_KEY && strcmp(c.name, "shift+tab") == 0);
    CHECK(parse("frames 3", &c) == 1 && c.kind == VIEW_CMD_FRAMES && c.index == 3);
    CHECK(parse("screenshot out/a.png", &c) == 1 && c.kind == VIEW_CMD_SCREENSHOT && strcmp(c.text, "out/a.png") == 0);
}

static void test_bad_lines(void)
{
    static const char *const bad[] = {
        "teleport 3",          "technique",          "technique nosuch",         "technique ssss local",
        "param brightening",   "param nosuch 1",     "param ssss.brightening 1", "param nosuch.taps 1",
        "param taps x",        "param taps nan",     "param taps 1e999",         "material x scale 2",
        "material -1 scale 2", "material 0.5 eta 1", "material 0 colour 1",      "material 0 scale",
        "material 0 sigma_a 1", "material 0 sigma_a 1 2", "material 0 medium nosuch", "material 0 eta 1 2",
        "light 0 position 1",  "light 0 intensity 1 2 3", "light 0 spin 1",       "buffer nosuch",
        "split",               "split nosuch",       "split ssss 1",             "split reference 0",
        "errormap maybe",      "panel",              "reference final",          "frames 0",
        "errormap on 0",       "errormap on 1.5",    "errormap off 0.1",         "errormap on x",
        "panel open",          "panel open nosuch",  "panel fold Lights",        "panel on Lights",
        "panel width 10",      "panel width 5000",   "panel width 200.5",        "panel open Lights View",
        "frames 1.5",          "frames 100001",      "screenshot",               "screenshot a.exr",
        "key",                 "a b c d e f g h i",
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        view_command c;
        char why[512] = "";
        int r = view_script_parse_line(bad[i], &c, why, sizeof why);
        CHECK_MSG(r == -1 && why[0], "'%s' was accepted", bad[i]);
    }
}

static void test_file_errors(void)
{
    char path[] = "/tmp/sss_view_script_XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd < 0) return;
    const char text[] = "# test\r\nframes 1\n\nmaterial 0 shine 2\nscreenshot a.png\n";
    CHECK(write(fd, text, sizeof text - 1) == (ssize_t)(sizeof text - 1));
    close(fd);
    view_script s;
    sss_error err = {0};
    CHECK(view_script_load(path, &s, &err) != SSS_OK);
    char want[300];
    snprintf(want, sizeof want, "%s:4: material: unknown field 'shine'", path);
    CHECK_MSG(strstr(err.message, want) != NULL, "message: %s", err.message);
    CHECK(s.commands == NULL && s.count == 0);
    FILE *f = fopen(path, "wb");
    fputs("# only a comment\n", f);
    fclose(f);
    CHECK(view_script_load(path, &s, &err) != SSS_OK && strstr(err.message, "no actions"));
    f = fopen(path, "wb");
    fputs("frames 2\r\n  # c\nscreenshot x.png", f);
    fclose(f);
    CHECK(view_script_load(path, &s, &err) == SSS_OK && s.count == 2 && s.commands[0].line == 1 &&
          s.commands[1].line == 3 && s.commands[1].kind == VIEW_CMD_SCREENSHOT);
    view_script_free(&s);
    unlink(path);
    CHECK(view_script_load(path, &s, &err) != SSS_OK && strstr(err.message, path));
}

static const char scene_text[] =
    "{\"camera\": {\"position\": [0, 0.5, 4], \"look_at\": [0, 0, 0], \"fov\": 40, \"width\": 32, \"height\": 24},\n"
    " \"objects\": [\n"
    "  {\"procedural\": {\"shape\": \"sphere\", \"radius\": 0.5, \"subdivisions\": 1},\n"
    "   \"material\": {\"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": 10, \"eta\": 1.4}},\n"
    "  {\"procedural\": {\"shape\": \"plane\", \"size\": 6}, \"transform\": {\"translate\": [0, -1, 0]},\n"
    "   \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.4, 0.5, 0.6]}}],\n"
    " \"lights\": [{\"type\": \"area\", \"center\": [-1, 1.8, 0.5], \"u\": [0.5, 0, 0], \"v\": [0, 0, 0.5],\n"
    "             \"radiance\": [6, 6, 6]},\n"
    "            {\"type\": \"point\", \"position\": [2, 2, 2], \"intensity\": [1, 1, 1]}]}\n";

static int load(const char *json, sss_scene *s)
{
    sss_error err = {0};
    sss_result r = sss_scene_parse(json, strlen(json), ".", "edit.json", NULL, s, &err);
    if (r != SSS_OK) fprintf(stderr, "parse: %s\n", err.message);
    return r == SSS_OK;
}

/* Switching the form keeps the optics: coefficients exactly, reflectance + mfp through the PBD table's
 * inversion (rho_eff -> albedo), to the table's interpolation accuracy. */
static void test_material_forms(void)
{
    sss_scene base, coeff, refl, eta;
    memset(&base, 0, sizeof base);
    memset(&coeff, 0, sizeof coeff);
    memset(&refl, 0, sizeof refl);
    memset(&eta, 0, sizeof eta);
    CHECK(load(scene_text, &base));
    const sss_scene_material *m = &base.objects[0].material;
    sss_error err = {0};
    char *json = NULL;
    double sa[3] = {m->optical.sigma_a[0], m->optical.sigma_a[1], m->optical.sigma_a[2]};
    CHECK(view_material_json(scene_text, strlen(scene_text), "edit.json", 0, "sigma_a", NULL, sa, 3, m, &json, &err) ==
          SSS_OK);
    CHECK(json && load(json, &coeff));
    free(json);
    for (int c = 0; c < 3; c++) {
        CHECK_REL(coeff.objects[0].material.optical.sigma_a[c], m->optical.sigma_a[c], 1e-12);
        CHECK_REL(coeff.objects[0].material.optical.sigma_s[c], m->optical.sigma_s[c], 1e-12);
    }
    CHECK(coeff.objects[0].material.source == SSS_SUBSURFACE_COEFFICIENTS);
    CHECK(view_material_json(scene_text, strlen(scene_text), "edit.json", 0, "reflectance", NULL, m->albedo, 3, m,
                             &json, &err) == SSS_OK);
    CHECK(json && load(json, &refl));
    free(json);
    for (int c = 0; c < 3; c++) {
        double st = m->optical.sigma_a[c] + m->optical.sigma_s[c];
        const sss_material *o = &refl.objects[0].material.optical;
        CHECK_REL(o->sigma_a[c] + o->sigma_s[c], st, 1e-9);
        CHECK_REL(o->sigma_s[c] / (o->sigma_a[c] + o->sigma_s[c]), m->optical.sigma_s[c] / st, 2e-3);
    }
    double e = 1.6;
    CHECK(view_material_json(scene_text, strlen(scene_text), "edit.json", 0, "eta", NULL, &e, 1, m, &json, &err) ==
          SSS_OK);
    CHECK(json && load(json, &eta));
    free(json);
    CHECK(eta.objects[0].material.optical.eta == 1.6 && eta.objects[0].material.medium == m->medium);
    CHECK(view_material_json(scene_text, strlen(scene_text), "edit.json", 1, "eta", NULL, &e, 1, NULL, &json, &err) !=
              SSS_OK &&
          strstr(err.message, "edit.json: objects[1].material: not a subsurface material"));
    CHECK(view_material_json(scene_text, strlen(scene_text), "edit.json", 5, "eta", NULL, &e, 1, NULL, &json, &err) !=
              SSS_OK &&
          strstr(err.message, "objects[5]"));
    sss_scene_free(&base);
    sss_scene_free(&coeff);
    sss_scene_free(&refl);
    sss_scene_free(&eta);
}

static void test_light_fields(void)
{
    double p[3] = {0.25, 2.0, -0.5}, power[3] = {1, 2, 3};
    sss_error err = {0};
    char *json = NULL, *json2 = NULL;
    sss_scene s;
    memset(&s, 0, sizeof s);
    CHECK(view_light_json(scene_text, strlen(scene_text), "edit.json", 0, "position", p, &json, &err) == SSS_OK);
    CHECK(json && view_light_json(json, strlen(json), "edit.json", 1, "power", power, &json2, &err) == SSS_OK);
    CHECK(json2 && load(json2, &s));
    for (int c = 0; c < 3 && s.light_count == 2; c++) {
        CHECK(s.lights[0].center[c] == p[c]);
        CHECK(s.lights[0].radiance[c] == 6.0);
        CHECK(s.lights[1].intensity[c] == power[c]);
        CHECK(s.lights[1].position[c] == 2.0);
    }
    free(json);
    free(json2);
    sss_scene_free(&s);
    CHECK(view_light_json(scene_text, strlen(scene_text), "edit.json", 2, "position", p, &json, &err) != SSS_OK &&
          strstr(err.message, "lights[2]: no such light"));
}

static void test_split_and_error_map(void)
{
    sss_image a = {0}, b = {0}, out = {0}, map = {0}, colours = {0};
    sss_error err = {0};
    CHECK(sss_image_create(&a, 10, 4, &err) == SSS_OK && sss_image_create(&b, 10, 4, &err) == SSS_OK);
    for (size_t i = 0; i < 10 * 4 * 3; i++) a.pixels[i] = 1.0f, b.pixels[i] = 2.0f;
    CHECK(view_compose_split(&a, &b, 0.3, "a", "b", 0.0, &out, &err) == SSS_OK);
    for (int y = 0; y < 4; y++) /* away from the divider (columns 1..4 around the cut at 3) */
        for (int x = 0; x < 10; x++)
            if (x < 3 - VIEW_DIVIDER_WIDTH / 2 || x >= 3 + VIEW_DIVIDER_WIDTH / 2)
                CHECK(out.pixels[3 * (y * 10 + x) + 1] == (x < 3 ? 1.0f : 2.0f));
    sss_image c = {0};
    CHECK(sss_image_create(&c, 9, 4, &err) == SSS_OK);
    CHECK(view_compose_split(&a, &c, 0.5, "a", "c", 0.0, &out, &err) != SSS_OK);
    /* luminance of the colour scale rises from 0 to 1 (readable without colour vision) */
    double last = -1.0;
    for (int k = 0; k <= 20; k++) {
        float rgb[3];
        view_error_colour(k / 20.0, rgb);
        double y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
        CHECK_MSG(y > last, "luminance at %g: %g after %g", k / 20.0, y, last);
        last = y;
    }
    float nan_rgb[3];
    view_error_colour(NAN, nan_rgb);
    CHECK(nan_rgb[0] == 0.0f && nan_rgb[1] == 0.0f && nan_rgb[2] == 0.0f);
    CHECK(sss_image_create(&map, 40, 40, &err) == SSS_OK);
    map.pixels[3 * 5] = 0.027f; /* one pixel of mean 0.009, the rest 0 */
    CHECK(view_error_map(&map, 0.1, &colours, &err) == SSS_OK);
    float want[3];
    view_error_colour(0.09, want); /* the fixed range, not the data's largest value */
    CHECK_NEAR(colours.pixels[3 * 5 + 1], want[1], 1e-6);
    CHECK(view_error_map(&map, 0.0, &colours, &err) != SSS_OK && view_error_map(&map, NAN, &colours, &err) != SSS_OK);
    float lo[3], hi[3];
    view_error_colour(0.0, lo);
    view_error_colour(1.0, hi);
    const float *first = colours.pixels + 3 * (39 * 40), *last_px = colours.pixels + 3 * (39 * 40 + 39);
    CHECK(first[0] == lo[0] && first[1] == lo[1] && last_px[1] == hi[1]); /* the bar: low left, high right */
    const float *rule = colours.pixels + 3 * ((39 - VIEW_COLOUR_BAR_HEIGHT) * 40 + 20); /* no tick at 20 */
    CHECK(rule[0] == 0.0f && rule[1] == 0.0f && rule[2] == 0.0f);
    CHECK(colours.pixels[3 * 5 + 1] > colours.pixels[3 * 6 + 1]); /* the error brighter than no error */
    sss_image_free(&a);
    sss_image_free(&b);
    sss_image_free(&c);
    sss_image_free(&out);
    sss_image_free(&map);
    sss_image_free(&colours);
}

int main(void)
{
    test_good_lines();
    test_bad_lines();
    test_file_errors();
    test_material_forms();
    test_light_fields();
    test_split_and_error_map();
    return CHECK_DONE();
}
