/* sss_scene_set_light: a light replaced from JSON is checked as the loader checks it (messages name
 * "<scene>: lights[i].<field>"), keeps its type and (environment) its file pointer, and on any error
 * leaves the scene's light as it was. */
#include <string.h>

#include "check.h"
#include "sss/scene.h"

static const char *const scene_json =
    "{\"camera\": {\"position\": [0, 1, 4], \"look_at\": [0, 0, 0], \"fov\": 40, \"width\": 16, \"height\": 16},"
    " \"objects\": [{\"procedural\": {\"shape\": \"plane\", \"size\": 2},"
    "                \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}}],"
    " \"lights\": [{\"type\": \"point\", \"position\": [0, 2, 0], \"intensity\": [1, 1, 1]},"
    "              {\"type\": \"environment\", \"file\": \"gl_sky.hdr\", \"rotate_y\": 10}]}";

static int set(sss_scene *s, size_t i, const char *json, sss_error *err)
{
    return sss_scene_set_light(s, i, json, strlen(json), err);
}

/* A failing update must leave lights[index] bit for bit as it was. */
static void check_refused(sss_scene *s, size_t i, const char *json, const char *expected)
{
    sss_light before = s->lights[i];
    sss_error err = {0};
    CHECK_MSG(set(s, i, json, &err) != SSS_OK, "%s accepted", json);
    CHECK_MSG(strstr(err.message, expected) != NULL, "'%s' lacks '%s'", err.message, expected);
    CHECK(memcmp(&before, &s->lights[i], sizeof before) == 0);
}

int main(void)
{
    sss_scene s;
    sss_error err = {0};
    sss_result r = sss_scene_parse(scene_json, strlen(scene_json), SSS_SOURCE_DIR "/scenes", "lit.json", NULL, &s, &err);
    CHECK_MSG(r == SSS_OK, "%s", err.message);
    if (r != SSS_OK) return CHECK_DONE();

    CHECK(set(&s, 0, "{\"type\": \"point\", \"position\": [1, 3, 2], \"intensity\": [2, 0.5, 0]}", &err) == SSS_OK);
    CHECK(s.lights[0].position[1] == 3.0 && s.lights[0].intensity[0] == 2.0 && s.lights[0].intensity[2] == 0.0);

    check_refused(&s, 0, "{\"type\": \"point\", \"position\": [1, 3, 2], \"intensity\": [-1, 0, 0]}",
                  "lit.json: lights[0].intensity");
    check_refused(&s, 0, "{\"type\": \"point\", \"position\": [1, 3, 2]}", "lights[0]");
    check_refused(&s, 0, "{\"type\": \"directional\", \"direction\": [0, -1, 0], \"radiance\": [1, 1, 1]}",
                  "lights[0].type: is directional, but the light is point");
    check_refused(&s, 0, "{\"type\": \"point\", ", "lights[0]: line 1, column 18: malformed JSON");
    /* the loader's JSON reader: a NUL would cut "point\u0000x" to "point"; text after the value */
    check_refused(&s, 0, "{\"type\": \"point\\u0000x\", \"position\": [1, 3, 2], \"intensity\": [1, 1, 1]}",
                  "lit.json: lights[0].type: a string holds a NUL character");
    check_refused(&s, 0, "{\"type\": \"point\", \"position\": [1, 3, 2], \"intensity\": [1, 1, 1]} {}",
                  "lights[0]: line 1, column 66: unexpected text after the JSON value");
    check_refused(&s, 0, "{\"type\": \"point\", \"position\": [1, 3, 2], \"intensity\": [1e39, 1, 1]}",
                  "lights[0].intensity[0]: 1e+39: out of range [0, 1e+30]");
    check_refused(&s, 1, "{\"type\": \"environment\", \"file\": \"gl_area.json\"}", "lights[1].file: differs");
    check_refused(&s, 1, "{\"type\": \"environment\", \"file\": \"missing.hdr\"}", "missing.hdr");
    err.message[0] = '\0';
    CHECK(set(&s, 2, "{}", &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "lights[2]: no such light"));

    /* An environment light may leave out its file, or give the same one; its file pointer stays. */
    const char *file = s.lights[1].file;
    CHECK(set(&s, 1, "{\"type\": \"environment\", \"rotate_y\": 30, \"scale\": [2, 2, 2]}", &err) == SSS_OK);
    CHECK(s.lights[1].file == file && s.lights[1].rotate_y == 30.0 && s.lights[1].scale[1] == 2.0);
    CHECK(set(&s, 1, "{\"type\": \"environment\", \"file\": \"gl_sky.hdr\"}", &err) == SSS_OK);
    CHECK(s.lights[1].file == file && s.lights[1].rotate_y == 0.0 && s.lights[1].scale[1] == 1.0);
    sss_scene_free(&s);
    return CHECK_DONE();
}
