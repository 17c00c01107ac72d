/* Scene loader: the scene format's example verbatim, defaults, and a table of bad scenes whose errors must
 * name the file and the JSON path. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sss/scene.h"

#define SCENES SSS_TEST_DATA "/scenes"

static int vec3_is(const double *v, double x, double y, double z)
{
    return v[0] == x && v[1] == y && v[2] == z;
}

/* Parses json (relative paths from SCENES) into *s; 1 on success, else reports the error and 0. */
static int parse_ok(const char *json, const char *name, sss_scene *s)
{
    sss_error err = {0};
    sss_result res = sss_scene_parse(json, strlen(json), SCENES, name, NULL, s, &err);
    CHECK_MSG(res == SSS_OK, "%s: %s", name, err.message);
    return res == SSS_OK;
}

/* the scene format's example scene, copied verbatim into tests/data/scenes/example.json; its mesh
 * assets/dragon.ply is a fixture octahedron there. */
static void test_example(void)
{
    sss_scene s;
    sss_error err = {0};
    sss_result res = sss_scene_load(SCENES "/example.json", NULL, &s, &err);
    CHECK_MSG(res == SSS_OK, "%s", err.message);
    if (res != SSS_OK) return;
    CHECK(strstr(s.name, "example.json") != NULL);
    CHECK(vec3_is(s.camera.position, 0.0, 0.12, 0.35));
    CHECK(vec3_is(s.camera.look_at, 0.0, 0.12, 0.0));
    CHECK(vec3_is(s.camera.up, 0.0, 1.0, 0.0));
    CHECK(s.camera.fov == 30.0 && s.camera.width == 512 && s.camera.height == 512);
    CHECK(s.object_count == 2);
    const sss_scene_object *o = &s.objects[0];
    CHECK(o->procedural.shape == SSS_SHAPE_MESH && o->mesh_path && strstr(o->mesh_path, "assets/dragon.ply"));
    CHECK(o->mesh.vertex_count == 6 && o->mesh.triangle_count == 8);
    CHECK(o->bounds_min[0] == -1.0f && o->bounds_max[1] == 1.0f);
    CHECK(vec3_is(o->transform.translate, 0, 0, 0) && vec3_is(o->transform.scale, 1, 1, 1));
    CHECK(o->transform.rotate[1] == 1 && o->transform.rotate[3] == 30);
    CHECK(o->material.type == SSS_SCENE_MATERIAL_SUBSURFACE && o->material.source == SSS_SUBSURFACE_MEDIUM);
    CHECK(o->material.medium && strcmp(o->material.medium->name, "Ketchup") == 0);
    CHECK(o->material.scale == 100.0 && o->material.optical.eta == 1.33 && o->material.optical.g == 0);
    /* Ketchup (docs/physics.md §2.3): sigma_s' 0.18, 0.07, 0.03; sigma_a 0.061, 0.97, 1.45 mm^-1, times 100. */
    CHECK_REL(o->material.optical.sigma_s[0], 18.0, 1e-12);
    CHECK_REL(o->material.optical.sigma_a[2], 145.0, 1e-12);
    CHECK(o->material.profile == SSS_SCENE_PROFILE_PBD && o->material.table != NULL);
    CHECK(o->animation.type == SSS_ANIMATION_NONE && o->splat_mesh_path == NULL && o->splat_triangles == 0);
    const sss_scene_object *p = &s.objects[1];
    CHECK(p->procedural.shape == SSS_SHAPE_PLANE && p->procedural.size == 2.0 && p->mesh_path == NULL);
    CHECK(p->mesh.triangle_count == 2);
    CHECK(p->material.type == SSS_SCENE_MATERIAL_DIFFUSE && vec3_is(p->material.albedo, 0.5, 0.5, 0.5));
    CHECK(s.light_count == 1 && s.lights[0].type == SSS_LIGHT_POINT);
    CHECK(vec3_is(s.lights[0].position, 0.0, 0.2, -0.4) && vec3_is(s.lights[0].intensity, 0.5, 0.5, 0.5));
    CHECK(strcmp(s.render.technique, "maisch2020") == 0 && s.render.exposure == 0.0);
    CHECK(s.table_count == 1);
    sss_scene_free(&s);
    sss_scene_free(&s); /* free on a freed (zeroed) scene is safe */
}

static void test_defaults(void)
{
    const char *json = "{\"camera\": {\"position\": [0, 0, 3], \"look_at\": [0, 0, 0]},\n"
                       " \"objects\": [{\"mesh\": \"assets/dragon.ply\",\n"
                       "   \"material\": {\"type\": \"subsurface\", \"medium\": \"marble\"}}]}";
    sss_scene s;
    if (!parse_ok(json, "defaults.json", &s)) return;
    CHECK(s.camera.fov == 35 && s.camera.width == 512 && s.camera.height == 512);
    CHECK(vec3_is(s.camera.up, 0, 1, 0));
    const sss_scene_object *o = &s.objects[0];
    CHECK(vec3_is(o->transform.scale, 1, 1, 1) && vec3_is(o->transform.translate, 0, 0, 0));
    for (int i = 0; i < 16; i++) CHECK(o->transform.matrix[i] == (i % 5 == 0 ? 1.0 : 0.0));
    CHECK(o->material.scale == 1 && o->material.optical.eta == 1.33 && o->material.optical.g == 0);
    CHECK(strcmp(o->material.medium->name, "Marble") == 0);
    CHECK(o->material.profile == SSS_SCENE_PROFILE_PBD && o->material.texture == NULL && !o->material.has_specular);
    CHECK(s.light_count == 0 && s.lights == NULL);
    CHECK(s.render.exposure == 0 && strcmp(s.render.technique, SSS_SCENE_DEFAULT_TECHNIQUE) == 0);
    CHECK(strcmp(SSS_SCENE_DEFAULT_TECHNIQUE, "maisch2020") == 0);
    sss_scene_free(&s);

    /* Area lights are one-sided and environment maps unscaled unless asked. */
    const char *lights = "{\"camera\": {\"position\": [0, 0, 3], \"look_at\": [0, 0, 0]},"
                         " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1},"
                         "   \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}}],"
                         " \"lights\": [{\"type\": \"area\", \"center\": [0, 2, 0], \"u\": [1, 0, 0],"
                         "   \"v\": [0, 0, 1], \"radiance\": [1, 1, 1]},"
                         "  {\"type\": \"environment\", \"file\": \"assets/sky.hdr\"},"
                         "  {\"type\": \"directional\", \"direction\": [0, -2, 0], \"radiance\": [3, 3, 3]},"
                         "  {\"type\": \"spot\", \"position\": [0, 3, 0], \"look_at\": [0, 0, 0],"
                         "   \"cone_angle\": 30, \"cone_delta\": 5, \"intensity\": [2, 2, 2]}]}";
    if (!parse_ok(lights, "lights.json", &s)) return;
    CHECK(s.light_count == 4);
    CHECK(s.lights[0].type == SSS_LIGHT_AREA && s.lights[0].two_sided == 0);
    CHECK(s.lights[1].type == SSS_LIGHT_ENVIRONMENT && vec3_is(s.lights[1].scale, 1, 1, 1) &&
          s.lights[1].rotate_y == 0 && strstr(s.lights[1].file, "scenes/assets/sky.hdr"));
    CHECK(s.lights[2].type == SSS_LIGHT_DIRECTIONAL && vec3_is(s.lights[2].direction, 0, -1, 0));
    CHECK(s.lights[3].type == SSS_LIGHT_SPOT && s.lights[3].cone_angle == 30 && s.lights[3].cone_delta == 5);
    CHECK(s.objects[0].procedural.subdivisions == 4);
    sss_scene_free(&s);

    /* A texture on a shape with UVs (the plane) loads. */
    const char *tex = "{\"camera\": {\"position\": [0, 3, 3], \"look_at\": [0, 0, 0]},"
                      " \"objects\": [{\"procedural\": {\"shape\": \"plane\", \"size\": 2},"
                      "   \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin1\", \"texture\": \"assets/albedo.png\"}}]}";
    if (parse_ok(tex, "tex.json", &s)) CHECK(s.objects[0].mesh.uvs != NULL && strstr(s.objects[0].material.texture, "albedo.png"));
    sss_scene_free(&s);

    /* One decoded image per texture file, in the order of first use, shared by the objects naming it. */
#define TEX_PLANE(t) "{\"procedural\": {\"shape\": \"plane\", \"size\": 2}, \"material\": {\"type\": " \
                     "\"subsurface\", \"medium\": \"Skin1\"" t "}}"
    const char *shared = "{\"camera\": {\"position\": [0, 3, 3], \"look_at\": [0, 0, 0]}, \"objects\": ["
        TEX_PLANE(", \"texture\": \"assets/albedo.png\"") "," TEX_PLANE(", \"texture\": \"assets/sky.hdr\"") ","
        TEX_PLANE(", \"texture\": \"assets/albedo.png\"") "," TEX_PLANE("") "]}";
#undef TEX_PLANE
    if (parse_ok(shared, "shared.json", &s)) {
        CHECK(s.texture_count == 2 && strstr(s.textures[0].path, "albedo.png") && strstr(s.textures[1].path, "sky.hdr"));
        CHECK(s.objects[0].material.texture_image == &s.textures[0].image);
        CHECK(s.objects[1].material.texture_image == &s.textures[1].image);
        CHECK(s.objects[2].material.texture_image == &s.textures[0].image);
        CHECK(s.objects[3].material.texture_image == NULL);
    }
    sss_scene_free(&s);
}

/* Finite values at the edge of the double range are either refused or give a unit basis, unit light
 * directions and finite matrices (found by probing every number of a scene with +-1e308, 1e-300,
 * 1e-320, 5e-324: sqrt(x^2 + ...) overflowed, 1e308 degrees overflowed to inf radians). */
static void test_extreme_values(void)
{
    const char *json =
        "{\"camera\": {\"position\": [0, 0, 1e300], \"look_at\": [0, 0, -1e300], \"up\": [0, 1e308, 1e308]},"
        " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1},"
        "   \"transform\": {\"rotate\": [1e308, 0, 1e308, 1e308], \"scale\": [1e-18, 1e18, -1]},"
        "   \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}}],"
        " \"lights\": [{\"type\": \"directional\", \"direction\": [1e308, -1e308, 0], \"radiance\": [1, 1, 1]},"
        "  {\"type\": \"environment\", \"file\": \"assets/sky.hdr\", \"rotate_y\": -1e308}]}";
    sss_scene s;
    if (!parse_ok(json, "extreme.json", &s)) return;
    const double h = sqrt(0.5);
    CHECK(fabs(s.lights[0].direction[0] - h) < 1e-12 && fabs(s.lights[0].direction[1] + h) < 1e-12);
    /* fmod keeps the rotation (-1e308 is a multiple of 360 up to rounding: any value in (-360, 360)). */
    CHECK(isfinite(s.lights[1].rotate_y) && fabs(s.lights[1].rotate_y) < 360);
    int finite = 1;
    for (int i = 0; i < 16; i++) finite &= isfinite(s.objects[0].transform.matrix[i]);
    for (int i = 0; i < 9; i++) finite &= isfinite(s.objects[0].transform.normal_matrix[i]);
    CHECK(finite);
    const sss_camera_basis *b = &s.basis;
    CHECK(fabs(b->forward[2] + 1) < 1e-12 && fabs(hypot(hypot(b->up[0], b->up[1]), b->up[2]) - 1) < 1e-12);
    sss_scene_free(&s);
}

/* ---- Bad scenes ------------------------------------------------------------------------------ */

#define CAM "\"camera\": {\"position\": [0, 0, 5], \"look_at\": [0, 0, 0]}"
#define DIFFUSE "\"material\": {\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5]}"
#define SPHERE "\"procedural\": {\"shape\": \"sphere\", \"radius\": 1}"
#define OBJ "{" SPHERE ", " DIFFUSE "}"
#define SCENE_OBJS(objs) "{" CAM ", \"objects\": [" objs "]}"
/* An object with a subsurface material whose fields are `m`. */
#define SSS_OBJ(m) SCENE_OBJS("{" SPHERE ", \"material\": {\"type\": \"subsurface\", " m "}}")
#define WITH_LIGHT(l) "{" CAM ", \"objects\": [" OBJ "], \"lights\": [" l "]}"
#define WITH_CAMERA(c) "{\"camera\": {" c "}, \"objects\": [" OBJ "]}"

typedef struct bad_case {
    const char *json;
    const char *expect; /* must occur in the message (after "bad.json: ") */
} bad_case;

static const bad_case bad_cases[] = {
    /* unknown fields at several depths */
    {"{" CAM ", \"objects\": [" OBJ "], \"camra\": 1}", "bad.json: camra: unknown field"},
    {WITH_CAMERA("\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], \"fovy\": 30"), "camera.fovy: unknown field"},
    {SCENE_OBJS(OBJ ", {" SPHERE ", \"material\": {\"type\": \"subsurface\", \"sigmaa\": [1, 1, 1]}}"),
     "bad.json: objects[1].material.sigmaa: unknown field"},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"transform\": {\"scael\": 2}}"), "objects[0].transform.scael: unknown field"},
    {SCENE_OBJS("{\"procedural\": {\"shape\": \"sphere\", \"radus\": 1}, " DIFFUSE "}"),
     "objects[0].procedural.radus: unknown field"},
    {WITH_LIGHT("{\"type\": \"point\", \"position\": [0, 1, 0], \"intensity\": [1, 1, 1], \"colour\": 1}"),
     "lights[0].colour: unknown field"},
    {"{" CAM ", \"objects\": [" OBJ "], \"render\": {\"exposur\": 1}}", "render.exposur: unknown field"},
    {SSS_OBJ("\"medium\": \"Skin1\", \"profile\": {\"artist\": {\"s\": 1, \"x\": 2}}"),
     "objects[0].material.profile.artist.x: unknown field"},
    {SSS_OBJ("\"medium\": \"Skin1\", \"eta\": 1.4, \"eta\": 1.5"), "objects[0].material.eta: duplicate field"},
    {SCENE_OBJS("{" SPHERE ", \"material\": {\"type\": \"diffuse\", \"reflectance\": [0.5, 0.5, 0.5], \"eta\": 1.3}}"),
     "objects[0].material.eta: unknown field"},
    /* wrong types */
    {WITH_CAMERA("\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], \"fov\": \"wide\""), "camera.fov: expected a number"},
    {WITH_CAMERA("\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], \"width\": 512.5"), "camera.width: expected an integer"},
    {WITH_CAMERA("\"position\": [0, 0], \"look_at\": [0, 0, 0]"), "camera.position: expected an array of 3 numbers"},
    {WITH_CAMERA("\"position\": [0, \"a\", 5], \"look_at\": [0, 0, 0]"), "camera.position[1]: expected a number"},
    {"{\"camera\": [0, 0, 5], \"objects\": [" OBJ "]}", "camera: expected an object"},
    {"{" CAM ", \"objects\": {}}", "objects: expected an array"},
    {"{" CAM ", \"objects\": [" OBJ "], \"render\": {\"technique\": 123}}", "render.technique: expected a string"},
    {WITH_LIGHT("{\"type\": \"area\", \"center\": [0, 1, 0], \"u\": [1, 0, 0], \"v\": [0, 0, 1], "
                "\"radiance\": [1, 1, 1], \"two_sided\": \"yes\"}"),
     "lights[0].two_sided: expected true or false"},
    {WITH_CAMERA("\"position\": [0, 0, 1e999], \"look_at\": [0, 0, 0]"), "camera.position[2]: must be finite"},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"transform\": {\"scale\": \"big\"}}"),
     "objects[0].transform.scale: expected a number or an array of 3 numbers"},
    /* missing required fields */
    {"{\"objects\": [" OBJ "]}", "bad.json: camera: required field missing"},
    {WITH_CAMERA("\"position\": [0, 0, 5]"), "camera.look_at: required field missing"},
    {"{" CAM "}", "objects: required field missing"},
    {"{" CAM ", \"objects\": []}", "objects: must not be empty"},
    {SCENE_OBJS("{" SPHERE "}"), "objects[0].material: required field missing"},
    {SCENE_OBJS("{" SPHERE ", \"material\": {\"reflectance\": [0.5, 0.5, 0.5]}}"),
     "objects[0].material.type: required field missing"},
    {SSS_OBJ("\"reflectance\": [0.5, 0.5, 0.5]"), "objects[0].material.mfp: required field missing"},
    {SSS_OBJ("\"sigma_a\": [0.5, 0.5, 0.5]"), "objects[0].material.sigma_s: required field missing"},
    {WITH_LIGHT("{\"type\": \"point\", \"intensity\": [1, 1, 1]}"), "lights[0].position: required field missing"},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"animation\": {\"type\": \"twist\", \"amplitude\": 10}}"),
     "objects[0].animation.period: required field missing"},
    /* structure */
    {SCENE_OBJS("{\"mesh\": \"assets/dragon.ply\", " SPHERE ", " DIFFUSE "}"), "objects[0]: has both mesh and procedural"},
    {SCENE_OBJS("{" DIFFUSE "}"), "objects[0]: needs either mesh or procedural"},
    {SSS_OBJ("\"medium\": \"Skin1\", \"sigma_a\": [1, 1, 1], \"sigma_s\": [1, 1, 1]"),
     "objects[0].material: medium, sigma_a + sigma_s and reflectance + mfp are mutually exclusive"},
    {SSS_OBJ("\"eta\": 1.3"), "objects[0].material: a subsurface material needs one of"},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"splat_mesh\": \"assets/dragon.ply\", \"splat_triangles\": 100}"),
     "objects[0]: splat_mesh and splat_triangles are mutually exclusive"},
    /* values */
    {SSS_OBJ("\"medium\": \"Jelly\""), "objects[0].material.medium: unknown medium \"Jelly\" (known: Apple"},
    {SSS_OBJ("\"sigma_a\": [0.1, -0.2, 0.1], \"sigma_s\": [1, 1, 1]"), "objects[0].material.sigma_a[1]: -0.2"},
    {SSS_OBJ("\"sigma_a\": [0, 0.2, 0.1], \"sigma_s\": [0, 1, 1]"), "objects[0].material: sigma_a + sigma_s is 0"},
    {SSS_OBJ("\"medium\": \"Skin1\", \"eta\": 0.9"), "objects[0].material.eta: 0.9: out of range [1, "},
    {SSS_OBJ("\"reflectance\": [1.2, 0.5, 0.5], \"mfp\": 1"), "objects[0].material.reflectance[0]: 1.2"},
    {SSS_OBJ("\"reflectance\": [0.5, 0.5, 0.5], \"mfp\": 0"), "objects[0].material.mfp[0]"},
    {SSS_OBJ("\"reflectance\": [0.5, 0.5, 0.5], \"mfp\": 1, \"scale\": 10"), "objects[0].material.scale: not used"},
    {SSS_OBJ("\"medium\": \"Skin1\", \"g\": 0.5"), "objects[0].material.g: not allowed with medium"},
    {SSS_OBJ("\"sigma_a\": [1, 1, 1], \"sigma_s\": [1, 1, 1], \"g\": 1"), "objects[0].material.g: 1: out of range (-1, 1)"},
    {SSS_OBJ("\"medium\": \"Skin1\", \"profile\": \"gauss\""), "objects[0].material.profile: unknown profile"},
    {SSS_OBJ("\"medium\": \"Skin1\", \"profile\": {\"artist\": {\"s\": 0}}"), "objects[0].material.profile.artist.s"},
    {SSS_OBJ("\"medium\": \"Skin1\", \"specular\": {\"roughness\": 1.5}"), "objects[0].material.specular.roughness"},
    {SCENE_OBJS("{\"mesh\": \"assets/dragon.ply\", \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin1\", "
                "\"texture\": \"assets/albedo.png\"}}"),
     "objects[0].material.texture: needs UVs, but the mesh file has none"},
    {SSS_OBJ("\"medium\": \"Skin1\", \"texture\": \"nothere.png\""),
     "objects[0].material.texture: nothere.png: cannot open"},
    {SCENE_OBJS("{" SPHERE ", \"material\": {\"type\": \"glass\"}}"), "objects[0].material.type: unknown material type"},
    {WITH_CAMERA("\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], \"width\": 0"), "camera.width: 0 is out of range 1..16384"},
    {WITH_CAMERA("\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], \"height\": 20000"), "camera.height"},
    {WITH_CAMERA("\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], \"fov\": 0"), "camera.fov: 0: out of range [1e-06, 180)"},
    {WITH_CAMERA("\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], \"fov\": 5e-324"), "camera.fov: 4.94066e-324: out of range"},
    {WITH_CAMERA("\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], \"fov\": 180"), "camera.fov: 180"},
    {WITH_CAMERA("\"position\": [1, 2, 3], \"look_at\": [1, 2, 3]"), "camera.look_at: equals camera.position"},
    {WITH_CAMERA("\"position\": [0, 5, 0], \"look_at\": [0, 0, 0]"), "camera.up: parallel to the view direction"},
    {WITH_CAMERA("\"position\": [0, 0, 5], \"look_at\": [0, 0, 0], \"up\": [0, 0, 0]"), "camera.up: must be a non-zero"},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"transform\": {\"rotate\": [0, 0, 0, 30]}}"),
     "objects[0].transform.rotate: the axis"},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"transform\": {\"rotate\": [0, 1, 0]}}"),
     "objects[0].transform.rotate: expected an array of 4 numbers"},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"transform\": {\"scale\": [1, 0, 1]}}"), "objects[0].transform.scale: must be non-zero"},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"transform\": {\"scale\": [1, 1e-320, 1]}}"),
     "objects[0].transform.scale: 1e-320 is out of range: |scale| in [1e-18, 1e+18]"},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"transform\": {\"scale\": [1, 1, -1e19]}}"),
     "objects[0].transform.scale: -1e+19 is out of range"},
    {SCENE_OBJS("{\"procedural\": {\"shape\": \"cone\"}, " DIFFUSE "}"), "objects[0].procedural.shape: unknown shape \"cone\""},
    {SCENE_OBJS("{\"procedural\": {\"shape\": \"plane\", \"size\": -1}, " DIFFUSE "}"), "objects[0].procedural.size: -1"},
    {SCENE_OBJS("{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1, \"subdivisions\": 9}, " DIFFUSE "}"),
     "objects[0].procedural.subdivisions: 9 is out of range 0..8"},
    {SCENE_OBJS("{\"procedural\": {\"shape\": \"torus\", \"major\": 1, \"minor\": 2}, " DIFFUSE "}"),
     "objects[0].procedural.minor: must be smaller than major"},
    {SCENE_OBJS("{\"procedural\": {\"shape\": \"box\", \"size\": [1, 0, 1]}, " DIFFUSE "}"), "objects[0].procedural.size[1]"},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"animation\": {\"type\": \"twist\", \"amplitude\": 10, \"period\": 0}}"),
     "objects[0].animation.period: 0: must be > 0"},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"animation\": {\"type\": \"spin\", \"amplitude\": 10, \"period\": 1}}"),
     "objects[0].animation.type: unknown animation \"spin\""},
    {SCENE_OBJS("{" SPHERE ", " DIFFUSE ", \"splat_triangles\": 0}"), "objects[0].splat_triangles: 0 is out of range"},
    {WITH_LIGHT("{\"type\": \"laser\"}"), "lights[0].type: unknown light type \"laser\""},
    {WITH_LIGHT("{\"type\": \"spot\", \"position\": [0, 1, 0], \"look_at\": [0, 0, 0], \"cone_angle\": 20, "
                "\"cone_delta\": 30, \"intensity\": [1, 1, 1]}"),
     "lights[0].cone_delta: 30: out of range [0, 20]"},
    {WITH_LIGHT("{\"type\": \"area\", \"center\": [0, 1, 0], \"u\": [1, 0, 0], \"v\": [2, 0, 0], \"radiance\": [1, 1, 1]}"),
     "lights[0].v: parallel to u"},
    {WITH_LIGHT("{\"type\": \"point\", \"position\": [0, 1, 0], \"intensity\": [1, -1, 1]}"), "lights[0].intensity[1]"},
    {WITH_LIGHT("{\"type\": \"directional\", \"direction\": [0, 0, 0], \"radiance\": [1, 1, 1]}"),
     "lights[0].direction: must be a non-zero vector"},
    /* beyond what the real-time renderer carries in float (SSS_SCENE_MAX_LIGHT_VALUE, positions in float) */
    {WITH_LIGHT("{\"type\": \"point\", \"position\": [0, 1, 0], \"intensity\": [1, 1, 1e39]}"),
     "lights[0].intensity[2]: 1e+39: out of range [0, 1e+30]"},
    {WITH_LIGHT("{\"type\": \"directional\", \"direction\": [0, -1, 0], \"radiance\": [2e30, 1, 1]}"),
     "lights[0].radiance[0]: 2e+30: out of range [0, 1e+30]"},
    {WITH_LIGHT("{\"type\": \"point\", \"position\": [0, -1e39, 0], \"intensity\": [1, 1, 1]}"),
     "lights[0].position[1]: -1e+39: out of range [-3.40282e+38, 3.40282e+38]"},
    {WITH_LIGHT("{\"type\": \"area\", \"center\": [0, 1, 0], \"u\": [1e39, 0, 0], \"v\": [0, 0, 1], \"radiance\": [1, 1, 1]}"),
     "lights[0].u[0]: 1e+39"},
    {WITH_LIGHT("{\"type\": \"environment\", \"file\": \"sky.hdr\"}"), "lights[0].file: sky.hdr: cannot open"},
    {"{" CAM ", \"objects\": [" OBJ "], \"lights\": {}}", "lights: expected an array"},
    /* files */
    {SCENE_OBJS("{\"mesh\": \"assets/x.ply\", " DIFFUSE "}"), "bad.json: objects[0].mesh: assets/x.ply: cannot open: "},
    {SCENE_OBJS("{\"mesh\": \"assets\", " DIFFUSE "}"), "objects[0].mesh: assets: not a regular file"},
    {SCENE_OBJS(OBJ ", {\"mesh\": \"\", " DIFFUSE "}"), "objects[1].mesh: empty string"},
    /* the JSON itself */
    {"{\n  \"camera\": {\n    \"position\": [0, 0, 5],,\n", "bad.json: line 3, column "},
    {"", "bad.json: empty file"},
    {" \n\t ", "bad.json: empty file"},
    {"[1, 2, 3]", "bad.json: expected a JSON object at the top level"},
    {"\"scene\"", "bad.json: expected a JSON object at the top level"},
    {"{" CAM ", \"objects\": [" OBJ "]}\n{}", "bad.json: line 2, column 1: unexpected text after the JSON value"},
    {"{\"camera\": {\"position\": [0, 0, 5]", "bad.json: line 1, column"},
};

static void test_bad_scenes(void)
{
    size_t n = sizeof bad_cases / sizeof bad_cases[0];
    CHECK(n >= 25);
    for (size_t i = 0; i < n; i++) {
        sss_scene s;
        sss_error err = {0};
        sss_result res = sss_scene_parse(bad_cases[i].json, strlen(bad_cases[i].json), SCENES, "bad.json", NULL,
                                         &s, &err);
        CHECK_MSG(res != SSS_OK, "case %zu loaded but should fail (%s)", i, bad_cases[i].expect);
        CHECK_MSG(err.code == res, "case %zu: err.code %d != result %d", i, (int)err.code, (int)res);
        CHECK_MSG(strncmp(err.message, "bad.json: ", 10) == 0 && strstr(err.message, bad_cases[i].expect),
                  "case %zu: message \"%s\" lacks \"%s\"", i, err.message, bad_cases[i].expect);
        /* A failed load leaves an empty scene behind. */
        CHECK(s.objects == NULL && s.object_count == 0 && s.name == NULL && s.tables == NULL);
        sss_scene_free(&s);
    }
}

/* The format version (docs/scene-format.md): "version": 1 reads exactly as a file without it; a newer
 * version is refused for its version even when it also has fields this reader does not know. */
static void test_version(void)
{
    sss_scene_load_desc desc = {SSS_SCENE_SKIP_MESHES};
    const char *plain = SCENE_OBJS(OBJ);
    const char *v1 = "{\"version\": 1, " CAM ", \"objects\": [" OBJ "]}";
    sss_scene a, b;
    sss_error err = {0};
    sss_result ra = sss_scene_parse(plain, strlen(plain), SCENES, "plain.json", &desc, &a, &err);
    CHECK_MSG(ra == SSS_OK, "%s", err.message);
    sss_result rb = sss_scene_parse(v1, strlen(v1), SCENES, "v1.json", &desc, &b, &err);
    CHECK_MSG(rb == SSS_OK, "%s", err.message);
    if (ra == SSS_OK && rb == SSS_OK) {
        CHECK(memcmp(&a.camera, &b.camera, sizeof a.camera) == 0 && a.object_count == b.object_count);
        CHECK(memcmp(&a.objects[0].transform, &b.objects[0].transform, sizeof a.objects[0].transform) == 0);
        CHECK(strcmp(a.render.technique, b.render.technique) == 0 && a.light_count == b.light_count);
    }
    sss_scene_free(&a);
    sss_scene_free(&b);

    static const struct {
        const char *json;
        sss_result code;
        const char *expect;
    } bad[] = {
        {"{\"version\": 2, " CAM ", \"objects\": [" OBJ "], \"fog\": {}}", SSS_ERROR_UNSUPPORTED,
         "v.json: version: 2 is newer than this sss reads (scene format version 1)"},
        {"{\"version\": 1.5, " CAM ", \"objects\": [" OBJ "]}", SSS_ERROR_PARSE, "v.json: version: expected an integer"},
        {"{\"version\": \"1\", " CAM ", \"objects\": [" OBJ "]}", SSS_ERROR_PARSE, "v.json: version: expected an integer"},
        {"{\"version\": 0, " CAM ", \"objects\": [" OBJ "]}", SSS_ERROR_INVALID_ARGUMENT, "v.json: version: 0 is out of range"},
        {"{\"version\": 1e300, " CAM ", \"objects\": [" OBJ "]}", SSS_ERROR_INVALID_ARGUMENT, "is out of range 1..2147483647"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        sss_result res = sss_scene_parse(bad[i].json, strlen(bad[i].json), SCENES, "v.json", &desc, &a, &err);
        CHECK_MSG(res == bad[i].code, "version case %zu: result %d, expected %d (%s)", i, (int)res,
                  (int)bad[i].code, err.message);
        CHECK_MSG(strstr(err.message, bad[i].expect), "version case %zu: \"%s\" lacks \"%s\"", i, err.message,
                  bad[i].expect);
        CHECK(a.objects == NULL && a.name == NULL);
        sss_scene_free(&a);
    }
}

/* The location of a syntax error: the second comma of line 3 is at column 27 (cJSON reports the
 * position where it gave up, which may be one past the offending character). */
static void test_syntax_location(void)
{
    const char *json = "{\n  \"camera\": {\n    \"position\": [0, 0, 5],,\n    \"look_at\": [0, 0, 0]}}";
    sss_scene s;
    sss_error err = {0};
    sss_result res = sss_scene_parse(json, strlen(json), SCENES, "syntax.json", NULL, &s, &err);
    unsigned line = 0, col = 0;
    CHECK(res == SSS_ERROR_PARSE);
    CHECK_MSG(sscanf(err.message, "syntax.json: line %u, column %u: malformed JSON", &line, &col) == 2, "%s",
              err.message);
    CHECK(line == 3 && col >= 27 && col <= 28);
}

static void test_files(void)
{
    sss_scene s;
    sss_error err = {0};
    /* A missing scene file names its path. */
    sss_result res = sss_scene_load(SCENES "/no_such_scene.json", NULL, &s, &err);
    CHECK(res == SSS_ERROR_IO && strstr(err.message, "no_such_scene.json"));
    /* Skipping file checks and meshes: a scene away from its assets still validates. */
    const char *json = SCENE_OBJS("{\"mesh\": \"elsewhere/x.ply\", " DIFFUSE "}");
    sss_scene_load_desc desc = {SSS_SCENE_SKIP_MESHES | SSS_SCENE_SKIP_FILE_CHECKS};
    res = sss_scene_parse(json, strlen(json), "/base", "skip.json", &desc, &s, &err);
    CHECK_MSG(res == SSS_OK, "%s", err.message);
    if (res == SSS_OK) {
        CHECK(strcmp(s.objects[0].mesh_path, "/base/elsewhere/x.ply") == 0);
        CHECK(s.objects[0].mesh.vertex_count == 0 && s.objects[0].mesh.positions == NULL);
        sss_scene_free(&s);
    }
    /* Absolute paths are kept; SKIP_MESHES alone still checks that files exist. */
    const char *abs_json = SCENE_OBJS("{\"mesh\": \"" SCENES "/assets/dragon.ply\", " DIFFUSE "}");
    desc.flags = SSS_SCENE_SKIP_MESHES;
    res = sss_scene_parse(abs_json, strlen(abs_json), "/nowhere", NULL, &desc, &s, &err);
    CHECK_MSG(res == SSS_OK, "%s", err.message);
    if (res == SSS_OK) {
        CHECK(strcmp(s.objects[0].mesh_path, SCENES "/assets/dragon.ply") == 0);
        CHECK(strcmp(s.name, "scene") == 0);
        sss_scene_free(&s);
    }
    res = sss_scene_parse(json, strlen(json), "/base", "skip.json", &desc, &s, &err);
    CHECK(res == SSS_ERROR_IO && strstr(err.message, "skip.json: objects[0].mesh: elsewhere/x.ply: cannot open"));
    /* Not NUL-terminated input: only size bytes are read. */
    char buf[512];
    const char *ok = SCENE_OBJS(OBJ);
    size_t len = strlen(ok);
    memcpy(buf, ok, len);
    memset(buf + len, 'x', sizeof buf - len);
    res = sss_scene_parse(buf, len, SCENES, "sized.json", &desc, &s, &err);
    CHECK_MSG(res == SSS_OK, "%s", err.message);
    sss_scene_free(&s);
    /* A byte order mark is tolerated. */
    char bom[512] = "\xEF\xBB\xBF";
    memcpy(bom + 3, ok, len + 1);
    res = sss_scene_parse(bom, len + 3, SCENES, "bom.json", &desc, &s, &err);
    CHECK_MSG(res == SSS_OK, "%s", err.message);
    sss_scene_free(&s);
}

int main(void)
{
    test_example();
    test_defaults();
    test_extreme_values();
    test_bad_scenes();
    test_version();
    test_syntax_location();
    test_files();
    return CHECK_DONE();
}
