/* sss_gltf_load: the default scene's node hierarchy flattened (glTF 2.0 spec, section 3.5: world =
 * parent world x local, local = T R S or `matrix`), its mesh primitives baked into world space, the
 * camera and the KHR_lights_punctual lights. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "core/vecmath.h"
#include "scene/gltf_internal.h"
#include "scene/scene_internal.h"

#define GLTF_MAX_DEPTH 1024 /* node hierarchy depth (recursion) */

typedef struct gltf_walk {
    gltf_ctx *c;
    sss_gltf_scene *out;
    size_t object_cap, light_cap;
    unsigned char *visited; /* per node: a node has one parent and appears once (spec 3.5.3) */
    size_t node_count;
    long camera_node;   /* the chosen camera's node, -1 when none yet */
    double camera_world[16];
} gltf_walk;

/* The node's local matrix (row-major): `matrix` (column-major in glTF) or T R S. */
static sss_result local_matrix(gltf_ctx *c, const cJSON *node, const char *path, double m[16])
{
    static const double zero[3] = {0, 0, 0}, one[3] = {1, 1, 1}, id_q[4] = {0, 0, 0, 1};
    double cm[16], t[3], q[4], s[3];
    sss_result res;
    if (gltf_get(node, "matrix")) {
        if ((res = gltf_vec(c, node, path, "matrix", 16, NULL, cm)) != SSS_OK) return res;
        for (int r = 0; r < 4; r++)
            for (int col = 0; col < 4; col++) m[4 * r + col] = cm[4 * col + r];
        return SSS_OK;
    }
    if ((res = gltf_vec(c, node, path, "translation", 3, zero, t)) != SSS_OK ||
        (res = gltf_vec(c, node, path, "rotation", 4, id_q, q)) != SSS_OK ||
        (res = gltf_vec(c, node, path, "scale", 3, one, s)) != SSS_OK)
        return res;
    double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(len > 0)) return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.rotation: a zero quaternion", path);
    double x = q[0] / len, y = q[1] / len, z = q[2] / len, w = q[3] / len;
    const double rot[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
                           2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                           2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
    for (int r = 0; r < 3; r++) {
        for (int col = 0; col < 3; col++) m[4 * r + col] = rot[3 * r + col] * s[col];
        m[4 * r + 3] = t[r];
    }
    m[12] = m[13] = m[14] = 0;
    m[15] = 1;
    return SSS_OK;
}

static sss_result add_object(gltf_walk *w, const sss_gltf_object *o)
{
    if (w->out->object_count == w->object_cap) {
        size_t cap = w->object_cap ? 2 * w->object_cap : 16;
        if (cap > SSS_SCENE_MAX_OBJECTS) cap = SSS_SCENE_MAX_OBJECTS;
        if (w->out->object_count == cap)
            return gltf_fail(w->c, SSS_ERROR_LIMIT, "more than %d mesh primitives in the scene", SSS_SCENE_MAX_OBJECTS);
        sss_gltf_object *grown = realloc(w->out->objects, cap * sizeof *grown);
        if (!grown) return gltf_fail(w->c, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
        w->out->objects = grown;
        w->object_cap = cap;
    }
    w->out->objects[w->out->object_count++] = *o;
    return SSS_OK;
}

static sss_result node_mesh(gltf_walk *w, long node, long mesh_index, const double world[16])
{
    gltf_ctx *c = w->c;
    const cJSON *mesh = gltf_item(c, GLTF_MESHES, mesh_index);
    if (!mesh) return gltf_fail(c, SSS_ERROR_PARSE, "nodes[%ld].mesh: mesh %ld does not exist", node, mesh_index);
    const cJSON *prims = gltf_get(mesh, "primitives");
    if (!cJSON_IsArray(prims) || !prims->child)
        return gltf_fail(c, SSS_ERROR_PARSE, "meshes[%ld].primitives: expected a non-empty array", mesh_index);
    long p = 0;
    for (const cJSON *prim = prims->child; prim; prim = prim->next, p++) {
        sss_gltf_object o = {.node = (int)node, .mesh_index = (int)mesh_index, .primitive = (int)p};
        long material = -1;
        int has_uvs = 0;
        char path[96];
        snprintf(path, sizeof path, "meshes[%ld].primitives[%ld]", mesh_index, p);
        sss_result res = gltf_primitive_mesh(c, node, mesh_index, p, prim, world, &o.mesh, &has_uvs);
        if (res == SSS_OK) res = gltf_int(c, prim, path, "material", 0, -1, 0, 1L << 30, &material);
        o.material_index = (int)material;
        if (res == SSS_OK) res = gltf_material(c, material, &o.material);
        if (res == SSS_OK && !has_uvs) gltf_material_free(&o.material); /* a texture needs UVs */
        if (res == SSS_OK) res = add_object(w, &o);
        if (res != SSS_OK) {
            sss_mesh_free(&o.mesh);
            gltf_material_free(&o.material);
            return res;
        }
    }
    return SSS_OK;
}

static void transform_point(const double m[16], const double p[3], double out[3])
{
    for (int r = 0; r < 3; r++) out[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
}

/* The unit direction of the node's -z axis (where cameras look and lights shine). */
static int node_forward(const double m[16], double d[3])
{
    for (int r = 0; r < 3; r++) d[r] = -m[4 * r + 2];
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(len > 0) || !isfinite(len)) return 0;
    for (int r = 0; r < 3; r++) d[r] /= len;
    return 1;
}

static sss_result gltf_node_light(gltf_walk *w, long node, long light, const double world[16]);

static sss_result visit(gltf_walk *w, long node, const double parent[16], int depth)
{
    gltf_ctx *c = w->c;
    char path[48];
    snprintf(path, sizeof path, "nodes[%ld]", node);
    if (node < 0 || (size_t)node >= w->node_count)
        return gltf_fail(c, SSS_ERROR_PARSE, "node %ld does not exist (%zu nodes)", node, w->node_count);
    if (w->visited[node])
        return gltf_fail(c, SSS_ERROR_PARSE, "%s: reached twice (a node has one parent; a cycle?)", path);
    if (depth > GLTF_MAX_DEPTH)
        return gltf_fail(c, SSS_ERROR_LIMIT, "%s: the hierarchy is deeper than %d", path, GLTF_MAX_DEPTH);
    w->visited[node] = 1;
    const cJSON *n = gltf_item(c, GLTF_NODES, node);
    double local[16], world[16];
    long mesh = -1, camera = -1, light = -1;
    sss_result res = gltf_object(c, n, path);
    if (res == SSS_OK) res = local_matrix(c, n, path, local);
    if (res != SSS_OK) return res;
    m4_mul_rows(parent, local, world);
    if ((res = gltf_int(c, n, path, "mesh", 0, -1, 0, 1L << 30, &mesh)) != SSS_OK ||
        (res = gltf_int(c, n, path, "camera", 0, -1, 0, 1L << 30, &camera)) != SSS_OK)
        return res;
    const cJSON *lp = gltf_get(gltf_get(n, "extensions"), "KHR_lights_punctual");
    char lpath[128];
    snprintf(lpath, sizeof lpath, "%s.extensions.KHR_lights_punctual", path);
    if (lp && (res = gltf_int(c, lp, lpath, "light", 1, 0, 0, 1L << 30, &light)) != SSS_OK) return res;
    if (mesh >= 0 && (res = node_mesh(w, node, mesh, world)) != SSS_OK) return res;
    if (light >= 0 && (res = gltf_node_light(w, node, light, world)) != SSS_OK) return res;
    if (camera >= 0 && w->camera_node < 0 && (!c->desc.use_camera || camera == c->desc.camera)) {
        w->camera_node = node;
        memcpy(w->camera_world, world, sizeof world);
    }
    const cJSON *children = gltf_get(n, "children");
    if (children && !cJSON_IsArray(children)) return gltf_fail(c, SSS_ERROR_PARSE, "%s.children: expected an array", path);
    int i = 0;
    for (const cJSON *ch = children ? children->child : NULL; ch; ch = ch->next, i++) {
        if (!cJSON_IsNumber(ch) || floor(ch->valuedouble) != ch->valuedouble || !(fabs(ch->valuedouble) < 1e9))
            return gltf_fail(c, SSS_ERROR_PARSE, "%s.children[%d]: expected a node index", path, i);
        if ((res = visit(w, (long)ch->valuedouble, world, depth + 1)) != SSS_OK) return res;
    }
    return SSS_OK;
}

/* ---- Lights (KHR_lights_punctual) ------------------------------------------------------------ */

static sss_result gltf_node_light(gltf_walk *w, long node, long light, const double world[16])
{
    gltf_ctx *c = w->c;
    const cJSON *l = gltf_item(c, GLTF_LIGHTS, light);
    if (!l)
        return gltf_fail(c, SSS_ERROR_PARSE, "nodes[%ld].extensions.KHR_lights_punctual.light: light %ld does not exist",
                         node, light);
    if (w->out->light_count == w->light_cap) {
        size_t cap = w->light_cap ? 2 * w->light_cap : 8;
        if (w->out->light_count >= SSS_SCENE_MAX_LIGHTS)
            return gltf_fail(c, SSS_ERROR_LIMIT, "more than %d lights in the scene", SSS_SCENE_MAX_LIGHTS);
        sss_light *grown = realloc(w->out->lights, cap * sizeof *grown);
        if (!grown) return gltf_fail(c, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
        w->out->lights = grown;
        w->light_cap = cap;
    }
    char path[80];
    snprintf(path, sizeof path, "extensions.KHR_lights_punctual.lights[%ld]", light);
    static const double white[3] = {1, 1, 1}, origin[3] = {0, 0, 0};
    double color[3], intensity = 1, scale = c->desc.light_scale > 0 ? c->desc.light_scale : 1.0, dir[3];
    sss_result res;
    if ((res = gltf_vec(c, l, path, "color", 3, white, color)) != SSS_OK ||
        (res = gltf_number(c, l, path, "intensity", 1.0, &intensity)) != SSS_OK)
        return res;
    if (!(intensity >= 0)) return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.intensity: must be >= 0", path);
    for (int k = 0; k < 3; k++)
        if (!(color[k] >= 0)) return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.color[%d]: must be >= 0", path, k);
    const cJSON *type = gltf_get(l, "type");
    if (!cJSON_IsString(type)) return gltf_fail(c, SSS_ERROR_PARSE, "%s.type: expected a string", path);
    if (!node_forward(world, dir))
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "nodes[%ld]: a light node with a degenerate transform", node);
    sss_light out = {0};
    transform_point(world, origin, out.position);
    int moved = 0;
    for (int k = 0; k < 3; k++) {
        double v = color[k] * intensity * scale;
        out.intensity[k] = out.radiance[k] = v;
        out.direction[k] = dir[k];
        out.look_at[k] = out.position[k] + dir[k];
        moved |= out.look_at[k] != out.position[k];
        if (!(v <= SSS_SCENE_MAX_LIGHT_VALUE))
            return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT,
                             "%s.intensity: %g x color[%d] %g x light scale %g = %g, beyond the %g sss renders "
                             "(docs/limits.md)", path, intensity, k, color[k], scale, v, SSS_SCENE_MAX_LIGHT_VALUE);
        if (!(fabs(out.look_at[k]) <= FLT_MAX))
            return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "nodes[%ld]: places light %ld beyond the float range",
                             node, light);
    }
    if (!moved) /* a spot's look_at, one unit away, must differ from its position in doubles */
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "nodes[%ld]: light %ld is too far from the origin", node, light);
    if (strcmp(type->valuestring, "point") == 0) {
        out.type = SSS_LIGHT_POINT;
    } else if (strcmp(type->valuestring, "directional") == 0) {
        out.type = SSS_LIGHT_DIRECTIONAL;
    } else if (strcmp(type->valuestring, "spot") == 0) {
        const cJSON *spot = gltf_get(l, "spot");
        char sp[160];
        snprintf(sp, sizeof sp, "%s.spot", path);
        double inner = 0, outer = M_PI / 4;
        if ((res = gltf_number(c, spot, sp, "innerConeAngle", 0.0, &inner)) != SSS_OK ||
            (res = gltf_number(c, spot, sp, "outerConeAngle", M_PI / 4, &outer)) != SSS_OK)
            return res;
        if (!(outer > 0 && outer <= M_PI / 2 && inner >= 0 && inner < outer))
            return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT,
                             "%s: needs 0 <= innerConeAngle < outerConeAngle <= pi/2 (%g, %g)", sp, inner, outer);
        out.type = SSS_LIGHT_SPOT;
        out.cone_angle = outer * 180.0 / M_PI;
        out.cone_delta = (outer - inner) * 180.0 / M_PI;
    } else {
        return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s.type: \"%s\" (expected point, spot or directional)", path,
                         type->valuestring);
    }
    w->out->lights[w->out->light_count++] = out;
    return SSS_OK;
}

/* ---- Camera ---------------------------------------------------------------------------------- */

/* Image size: the desc's, else from the camera's aspect ratio (aspect 0: unknown), else 960 x 540. */
static void image_size(const sss_gltf_desc *d, double aspect, sss_camera *cam)
{
    int w = d->width, h = d->height;
    if (aspect > 0 && (!w || !h)) {
        if (!w && !h) h = SSS_GLTF_DEFAULT_HEIGHT;
        if (!w) w = (int)fmin(lround(h * aspect), SSS_SCENE_MAX_IMAGE_SIZE);
        else h = (int)fmin(lround(w / aspect), SSS_SCENE_MAX_IMAGE_SIZE);
    }
    cam->width = w ? w : SSS_GLTF_DEFAULT_WIDTH;
    cam->height = h ? h : SSS_GLTF_DEFAULT_HEIGHT;
    /* an extreme aspect ratio is kept as far as the scene format's size limit allows */
    cam->width = cam->width < 1 ? 1 : cam->width > SSS_SCENE_MAX_IMAGE_SIZE ? SSS_SCENE_MAX_IMAGE_SIZE : cam->width;
    cam->height = cam->height < 1 ? 1 : cam->height > SSS_SCENE_MAX_IMAGE_SIZE ? SSS_SCENE_MAX_IMAGE_SIZE : cam->height;
}

static void scene_bounds(const sss_gltf_scene *s, double center[3], double *radius)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < s->object_count; i++) {
        float a[3], b[3];
        sss_mesh_bounds(&s->objects[i].mesh, a, b);
        for (int k = 0; k < 3; k++) {
            lo[k] = a[k] < lo[k] ? a[k] : lo[k];
            hi[k] = b[k] > hi[k] ? b[k] : hi[k];
        }
    }
    double r2 = 0;
    for (int k = 0; k < 3; k++) {
        center[k] = s->object_count ? 0.5 * ((double)lo[k] + hi[k]) : 0.0;
        double e = s->object_count ? 0.5 * ((double)hi[k] - lo[k]) : 1.0;
        r2 += e * e;
    }
    *radius = r2 > 0 ? sqrt(r2) : 1.0;
}

/* The perspective camera of the chosen node: looks down its -z with +y up (spec 3.10). look_at is
 * placed at the depth of the scene's centre so that orbiting viewers turn around the content. */
static sss_result asset_camera(gltf_ctx *c, gltf_walk *w, long index, sss_camera *cam)
{
    const cJSON *def = gltf_item(c, GLTF_CAMERAS, index);
    char path[48];
    snprintf(path, sizeof path, "cameras[%ld]", index);
    if (!def) return gltf_fail(c, SSS_ERROR_PARSE, "nodes[%ld].camera: camera %ld does not exist", w->camera_node, index);
    const cJSON *persp = gltf_get(def, "perspective");
    if (!persp) return gltf_fail(c, SSS_ERROR_UNSUPPORTED, "%s: only perspective cameras are supported", path);
    char pp[96];
    snprintf(pp, sizeof pp, "%s.perspective", path);
    double yfov = 0, aspect = 0;
    sss_result res;
    /* NAN: absent (a present value is finite) */
    if ((res = gltf_number(c, persp, pp, "yfov", NAN, &yfov)) != SSS_OK ||
        (res = gltf_number(c, persp, pp, "aspectRatio", NAN, &aspect)) != SSS_OK)
        return res;
    if (!(yfov > 0 && yfov < M_PI)) return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.yfov: must be in (0, pi)", pp);
    /* an aspect ratio given is used (0 or less is no ratio: refused, not taken as absent) */
    if (!isnan(aspect) && !(aspect >= 1.0 / SSS_SCENE_MAX_IMAGE_SIZE && aspect <= SSS_SCENE_MAX_IMAGE_SIZE))
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.aspectRatio: %g is outside [1/%d, %d]", pp, aspect,
                         SSS_SCENE_MAX_IMAGE_SIZE, SSS_SCENE_MAX_IMAGE_SIZE);
    image_size(&c->desc, isnan(aspect) ? 0.0 : aspect, cam);
    /* yfov is vertical; sss's fov is along the shorter image axis. */
    double half = yfov / 2;
    if (cam->height > cam->width) half = atan(tan(half) * cam->width / cam->height);
    cam->fov = 2 * half * 180.0 / M_PI;
    if (!(cam->fov >= SSS_SCENE_FOV_MIN))
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "%s.yfov: %g gives a field of view below %g degrees", pp, yfov,
                         SSS_SCENE_FOV_MIN);
    static const double origin[3] = {0, 0, 0};
    double fwd[3], center[3], radius;
    if (!node_forward(w->camera_world, fwd))
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "nodes[%ld]: a camera node with a degenerate transform",
                         w->camera_node);
    transform_point(w->camera_world, origin, cam->position);
    scene_bounds(w->out, center, &radius);
    double depth = 0;
    for (int k = 0; k < 3; k++) depth += (center[k] - cam->position[k]) * fwd[k];
    if (!(depth > 1e-6 * radius)) depth = radius;
    double side[3], up_len2 = 0, side_len2 = 0;
    for (int k = 0; k < 3; k++) {
        cam->look_at[k] = cam->position[k] + depth * fwd[k];
        cam->up[k] = w->camera_world[4 * k + 1]; /* the node's +y */
        up_len2 += cam->up[k] * cam->up[k];
    }
    for (int k = 0; k < 3; k++) {
        side[k] = fwd[(k + 1) % 3] * cam->up[(k + 2) % 3] - fwd[(k + 2) % 3] * cam->up[(k + 1) % 3];
        side_len2 += side[k] * side[k];
    }
    /* what sss_camera_basis_init needs: finite, look_at != position, up not along the view */
    int finite = 1;
    for (int k = 0; k < 3; k++) finite &= isfinite(cam->position[k]) && isfinite(cam->look_at[k]);
    if (!finite || !(side_len2 > 1e-12 * up_len2) || !isfinite(up_len2) ||
        (cam->look_at[0] == cam->position[0] && cam->look_at[1] == cam->position[1] && cam->look_at[2] == cam->position[2]))
        return gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "nodes[%ld]: a camera node with a degenerate transform",
                         w->camera_node);
    return SSS_OK;
}

/* Without a camera: the whole scene in view from the front (+z) and a little above, with sss's
 * default fov of 35 degrees. */
static void framing_camera(const sss_gltf_scene *s, const sss_gltf_desc *d, sss_camera *cam)
{
    double center[3], radius;
    scene_bounds(s, center, &radius);
    image_size(d, 0, cam);
    cam->fov = 35;
    double dist = 1.1 * radius / sin(cam->fov / 2 * M_PI / 180.0);
    const double dir[3] = {0, 0.3 / sqrt(1.09), 1 / sqrt(1.09)};
    for (int k = 0; k < 3; k++) {
        cam->look_at[k] = center[k];
        cam->position[k] = center[k] + dist * dir[k];
        cam->up[k] = k == 1;
    }
}

/* ---- Entry points ---------------------------------------------------------------------------- */

static sss_result walk_scene(gltf_ctx *c, sss_gltf_scene *out)
{
    gltf_walk w = {.c = c, .out = out, .camera_node = -1, .node_count = gltf_count(c, GLTF_NODES)};
    size_t scene_count = gltf_count(c, GLTF_SCENES);
    long scene = 0;
    sss_result res = gltf_int(c, c->root, "(root)", "scene", 0, 0, 0, 1L << 30, &scene);
    if (res == SSS_OK && (size_t)scene >= scene_count)
        res = gltf_fail(c, SSS_ERROR_PARSE, "scene: scene %ld does not exist (%zu scenes)", scene, scene_count);
    if (res == SSS_OK && w.node_count && !(w.visited = calloc(w.node_count, 1)))
        res = gltf_fail(c, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    const cJSON *roots = res == SSS_OK ? gltf_get(gltf_item(c, GLTF_SCENES, scene), "nodes") : NULL;
    if (res == SSS_OK && roots && !cJSON_IsArray(roots))
        res = gltf_fail(c, SSS_ERROR_PARSE, "scenes[%ld].nodes: expected an array", scene);
    static const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    int i = 0;
    for (const cJSON *r = roots ? roots->child : NULL; r && res == SSS_OK; r = r->next, i++) {
        if (!cJSON_IsNumber(r) || floor(r->valuedouble) != r->valuedouble || !(fabs(r->valuedouble) < 1e9))
            res = gltf_fail(c, SSS_ERROR_PARSE, "scenes[%ld].nodes[%d]: expected a node index", scene, i);
        else
            res = visit(&w, (long)r->valuedouble, identity, 0);
    }
    free(w.visited);
    if (res == SSS_OK && out->object_count == 0)
        res = gltf_fail(c, SSS_ERROR_PARSE, "scenes[%ld]: no mesh primitive to render", scene);
    if (res == SSS_OK && c->desc.use_camera && w.camera_node < 0)
        res = gltf_fail(c, SSS_ERROR_INVALID_ARGUMENT, "cameras[%d]: no node of scenes[%ld] uses it", c->desc.camera,
                        scene);
    if (res == SSS_OK && w.camera_node >= 0) {
        long cam = -1;
        gltf_int(c, gltf_item(c, GLTF_NODES, w.camera_node), "node", "camera", 0, -1, 0, 1L << 30, &cam);
        res = asset_camera(c, &w, cam, &out->camera);
        out->camera_from_asset = 1;
    } else if (res == SSS_OK) {
        framing_camera(out, &c->desc, &out->camera);
    }
    return res;
}

static sss_result gltf_parse(const void *data, size_t size, const char *base_dir, const char *name,
                             const sss_gltf_desc *desc, int check, sss_gltf_scene *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    gltf_ctx c = {.name = name ? name : "gltf", .base_dir = base_dir ? base_dir : ".", .err = err, .out = out};
    if (desc) c.desc = *desc;
    if (c.desc.width < 0 || c.desc.height < 0 || c.desc.width > SSS_SCENE_MAX_IMAGE_SIZE ||
        c.desc.height > SSS_SCENE_MAX_IMAGE_SIZE || c.desc.light_scale < 0 || !isfinite(c.desc.light_scale) ||
        (c.desc.use_camera && c.desc.camera < 0))
        return gltf_fail(&c, SSS_ERROR_INVALID_ARGUMENT, "invalid import options");
    if (!data) return gltf_fail(&c, SSS_ERROR_INVALID_ARGUMENT, "no data");
    sss_result res = gltf_open(&c, data, size);
    if (res == SSS_OK) res = gltf_list_files(&c, out);
    if (res == SSS_OK) res = walk_scene(&c, out);
    gltf_close(&c);
    if (res == SSS_OK && check) res = scene_check_gltf(c.name, c.base_dir, out, err);
    if (res != SSS_OK) sss_gltf_scene_free(out);
    return res;
}

sss_result sss_gltf_parse(const void *data, size_t size, const char *base_dir, const char *name,
                          const sss_gltf_desc *desc, sss_gltf_scene *out, sss_error *err)
{
    return gltf_parse(data, size, base_dir, name, desc, 1, out, err);
}

sss_result gltf_load(const char *path, const sss_gltf_desc *desc, int check, sss_gltf_scene *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    char *data = NULL;
    size_t size = 0;
    sss_result res = sss_read_file(path, SSS_GLTF_MAX_FILE_SIZE, &data, &size, err);
    if (res != SSS_OK) return res;
    char *dir = scene_folder_of(path);
    if (!dir) {
        free(data);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    res = gltf_parse(data, size, dir, path, desc, check, out, err);
    if (res == SSS_OK && gltf_add_file(out, path) != SSS_OK) {
        sss_gltf_scene_free(out);
        res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    free(dir);
    free(data);
    return res;
}

sss_result sss_gltf_load(const char *path, const sss_gltf_desc *desc, sss_gltf_scene *out, sss_error *err)
{
    return gltf_load(path, desc, 1, out, err);
}

void sss_gltf_scene_free(sss_gltf_scene *scene)
{
    if (!scene) return;
    for (size_t i = 0; i < scene->object_count; i++) {
        sss_mesh_free(&scene->objects[i].mesh);
        gltf_material_free(&scene->objects[i].material);
    }
    for (size_t i = 0; i < scene->image_count; i++) sss_image_free(&scene->images[i]);
    free(scene->images);
    free(scene->objects);
    free(scene->lights);
    for (size_t i = 0; i < scene->file_count; i++) free(scene->files[i]);
    free(scene->files);
    memset(scene, 0, sizeof *scene);
}
