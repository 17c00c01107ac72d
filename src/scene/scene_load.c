/* The scene loader: JSON text -> validated sss_scene (docs/scene-format.md), then the load phase (PBD tables,
 * material resolution, meshes). */
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/file_util.h"
#include "sss/image.h"
#include "scene/scene_internal.h"

char *scene_strdup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

char *scene_folder_of(const char *path)
{
    char *dir = malloc(strlen(path) + 2); /* room for "." */
    if (!dir) return NULL;
    strcpy(dir, path);
    char *slash = strrchr(dir, '/');
    if (!slash) strcpy(dir, ".");
    else if (slash == dir) dir[1] = '\0';
    else *slash = '\0';
    return dir;
}

/* base_dir + "/" + rel, or rel when it is absolute. */
static char *join_path(const char *base_dir, const char *rel)
{
    if (rel[0] == '/' || !base_dir || !base_dir[0]) return scene_strdup(rel);
    size_t nb = strlen(base_dir), nr = strlen(rel);
    int slash = base_dir[nb - 1] != '/';
    char *p = malloc(nb + (size_t)slash + nr + 1);
    if (!p) return NULL;
    memcpy(p, base_dir, nb);
    if (slash) p[nb] = '/';
    memcpy(p + nb + (size_t)slash, rel, nr + 1);
    return p;
}

sss_result scene_file_field(scene_ctx *c, const cJSON *obj, const char *key, int required, char **out)
{
    jr *r = &c->r;
    const char *rel = NULL;
    *out = NULL;
    sss_result res = jr_string(r, obj, key, required, &rel);
    if (res != SSS_OK || !rel) return res;
    char *path = join_path(c->base_dir, rel);
    if (!path) return jr_fail_key(r, key, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    if (!(c->flags & SSS_SCENE_SKIP_FILE_CHECKS)) {
        /* Opened as every reader opens it (a FIFO fails at once); the message names the file as the
         * scene spells it, after the JSON path. */
        sss_error open_err;
        int fd = sss_open_input(path, SSS_FILE_ANY_SIZE, NULL, &open_err);
        if (fd < 0) {
            size_t n = strlen(path);
            const char *why = strncmp(open_err.message, path, n) == 0 ? open_err.message + n : ": cannot open";
            sss_result failed = jr_fail_key(r, key, open_err.code, "%s%s", rel, why);
            free(path);
            return failed;
        }
        close(fd);
    }
    *out = path;
    return SSS_OK;
}

static sss_result parse_camera(scene_ctx *c, const cJSON *item, sss_camera *cam)
{
    jr *r = &c->r;
    static const char *const fields[] = {"position", "look_at", "up", "fov", "width", "height"};
    static const double y_up[3] = {0, 1, 0};
    sss_result res;
    if ((res = jr_expect_object(r, item)) != SSS_OK) return res;
    if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
    if ((res = jr_vec(r, item, "position", 1, NULL, 3, cam->position, NULL)) != SSS_OK) return res;
    if ((res = jr_vec(r, item, "look_at", 1, NULL, 3, cam->look_at, NULL)) != SSS_OK) return res;
    if ((res = jr_vec(r, item, "up", 0, y_up, 3, cam->up, NULL)) != SSS_OK) return res;
    if ((res = jr_number(r, item, "fov", 0, 35, &cam->fov)) != SSS_OK) return res;
    if ((res = jr_range(r, "fov", cam->fov, SSS_SCENE_FOV_MIN, 0, 180, 1)) != SSS_OK) return res;
    long w = 0, h = 0;
    if ((res = jr_int(r, item, "width", 0, 512, 1, SSS_SCENE_MAX_IMAGE_SIZE, &w)) != SSS_OK) return res;
    if ((res = jr_int(r, item, "height", 0, 512, 1, SSS_SCENE_MAX_IMAGE_SIZE, &h)) != SSS_OK) return res;
    cam->width = (int)w;
    cam->height = (int)h;

    double f[3] = {cam->look_at[0] - cam->position[0], cam->look_at[1] - cam->position[1],
                   cam->look_at[2] - cam->position[2]};
    /* hypot: no overflow for components near DBL_MAX (a difference beyond it is "too far"). */
    double fl = hypot(hypot(f[0], f[1]), f[2]), ul = hypot(hypot(cam->up[0], cam->up[1]), cam->up[2]);
    if (!(fl > 0)) return jr_fail_key(r, "look_at", SSS_ERROR_INVALID_ARGUMENT, "equals camera.position");
    if (!isfinite(fl)) return jr_fail_key(r, "look_at", SSS_ERROR_INVALID_ARGUMENT, "too far from camera.position");
    if (!(ul > 0)) return jr_fail_key(r, "up", SSS_ERROR_INVALID_ARGUMENT, "must be a non-zero vector");
    /* |sin| of the angle between up and the view direction, from unit vectors. */
    double fu[3], uu[3];
    for (int i = 0; i < 3; i++) {
        fu[i] = f[i] / fl;
        uu[i] = cam->up[i] / ul;
    }
    double cx = fu[1] * uu[2] - fu[2] * uu[1], cy = fu[2] * uu[0] - fu[0] * uu[2], cz = fu[0] * uu[1] - fu[1] * uu[0];
    if (!(hypot(hypot(cx, cy), cz) > 1e-6))
        return jr_fail_key(r, "up", SSS_ERROR_INVALID_ARGUMENT, "parallel to the view direction (look_at - position)");
    return SSS_OK;
}

static sss_result parse_render(scene_ctx *c, const cJSON *item, sss_render_settings *rs)
{
    jr *r = &c->r;
    static const char *const fields[] = {"technique", "exposure"};
    sss_result res;
    if ((res = jr_expect_object(r, item)) != SSS_OK) return res;
    if ((res = jr_check_fields(r, item, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
    const char *tech = NULL;
    if ((res = jr_string(r, item, "technique", 0, &tech)) != SSS_OK) return res;
    if (tech) {
        if (strlen(tech) >= SSS_SCENE_TECHNIQUE_SIZE)
            return jr_fail_key(r, "technique", SSS_ERROR_LIMIT, "longer than %d characters",
                               SSS_SCENE_TECHNIQUE_SIZE - 1);
        snprintf(rs->technique, sizeof rs->technique, "%s", tech);
    }
    return jr_number(r, item, "exposure", 0, 0, &rs->exposure);
}

/* Parses an array member `key` of root with a per-element parser. */
static sss_result parse_array(scene_ctx *c, const cJSON *root, const char *key, int required, size_t max,
                              size_t elem_size, void **out, size_t *count,
                              sss_result (*parse)(scene_ctx *, const cJSON *, void *))
{
    jr *r = &c->r;
    const cJSON *arr = jr_get(root, key);
    if (!arr) {
        if (required) return jr_fail_key(r, key, SSS_ERROR_PARSE, "required field missing");
        return SSS_OK;
    }
    size_t mark = jr_enter_key(r, key);
    sss_result res = SSS_OK;
    int n = cJSON_GetArraySize(arr);
    if (!cJSON_IsArray(arr)) res = jr_fail(r, SSS_ERROR_PARSE, "expected an array");
    else if (required && n == 0) res = jr_fail(r, SSS_ERROR_INVALID_ARGUMENT, "must not be empty");
    else if ((size_t)n > max) res = jr_fail(r, SSS_ERROR_LIMIT, "%d entries, more than the %zu accepted", n, max);
    else if (n > 0 && !(*out = calloc((size_t)n, elem_size))) res = jr_fail(r, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    if (res == SSS_OK) {
        size_t i = 0;
        for (const cJSON *e = arr->child; e; e = e->next, i++) {
            size_t m2 = jr_enter_index(r, i);
            res = parse((scene_ctx *)c, e, (char *)*out + i * elem_size);
            *count = i + 1; /* so that sss_scene_free releases what this element allocated */
            jr_leave(r, m2);
            if (res != SSS_OK) break;
        }
    }
    jr_leave(r, mark);
    return res;
}

static sss_result parse_object_cb(scene_ctx *c, const cJSON *e, void *out)
{
    return scene_parse_object(c, e, out);
}

static sss_result parse_light_cb(scene_ctx *c, const cJSON *e, void *out)
{
    return scene_parse_light(c, e, out);
}

/* The optional top-level "version" (docs/scene-format.md): absent = 1. Checked before the field names,
 * so that a newer file is refused for its version rather than for a field this reader does not know. */
static sss_result parse_version(jr *r, const cJSON *root)
{
    long version = 0;
    sss_result res = jr_int(r, root, "version", 0, 1, 1, INT_MAX, &version);
    if (res != SSS_OK) return res;
    if (version > SSS_SCENE_FORMAT_VERSION)
        return jr_fail_key(r, "version", SSS_ERROR_UNSUPPORTED,
                           "%ld is newer than this sss reads (scene format version %d)", version,
                           SSS_SCENE_FORMAT_VERSION);
    return SSS_OK;
}

static sss_result parse_root(scene_ctx *c, const cJSON *root, sss_scene *s)
{
    jr *r = &c->r;
    static const char *const fields[] = {"version", "camera", "objects", "lights", "render"};
    sss_result res;
    if (!cJSON_IsObject(root)) return jr_fail(r, SSS_ERROR_PARSE, "expected a JSON object at the top level");
    if ((res = parse_version(r, root)) != SSS_OK) return res;
    if ((res = jr_check_fields(r, root, fields, SCENE_COUNT(fields))) != SSS_OK) return res;
    if ((res = jr_require(r, root, "camera")) != SSS_OK) return res;
    size_t mark = jr_enter_key(r, "camera");
    res = parse_camera(c, jr_get(root, "camera"), &s->camera);
    jr_leave(r, mark);
    if (res != SSS_OK) return res;
    if ((res = sss_camera_basis_init(&s->camera, &s->basis, NULL)) != SSS_OK)
        return jr_fail_key(r, "camera", res, "degenerate camera");

    if ((res = parse_array(c, root, "objects", 1, SSS_SCENE_MAX_OBJECTS, sizeof(sss_scene_object),
                           (void **)&s->objects, &s->object_count, parse_object_cb)) != SSS_OK)
        return res;
    if ((res = parse_array(c, root, "lights", 0, SSS_SCENE_MAX_LIGHTS, sizeof(sss_light), (void **)&s->lights,
                           &s->light_count, parse_light_cb)) != SSS_OK)
        return res;

    snprintf(s->render.technique, sizeof s->render.technique, "%s", SSS_SCENE_DEFAULT_TECHNIQUE);
    s->render.exposure = 0;
    const cJSON *render = jr_get(root, "render");
    if (render) {
        mark = jr_enter_key(r, "render");
        res = parse_render(c, render, &s->render);
        jr_leave(r, mark);
    }
    return res;
}

/* ---- Load phase ------------------------------------------------------------------------------ */

const sss_pbd_table *sss_scene_find_table(const sss_scene *scene, double eta, double g)
{
    for (size_t i = 0; i < scene->table_count; i++)
        if (scene->tables[i]->eta == eta && scene->tables[i]->g == g) return scene->tables[i];
    return NULL;
}

/* The cached table for (eta, g), built on first use. */
static sss_result scene_table(scene_ctx *c, sss_scene *s, double eta, double g, const sss_pbd_table **out)
{
    *out = sss_scene_find_table(s, eta, g);
    if (*out) return SSS_OK;
    sss_pbd_table **grown = realloc(s->tables, (s->table_count + 1) * sizeof *grown);
    if (!grown) return jr_fail(&c->r, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    s->tables = grown;
    sss_pbd_table *t = malloc(sizeof *t);
    if (!t) return jr_fail(&c->r, SSS_ERROR_OUT_OF_MEMORY, "out of memory for a PBD table");
    sss_result res = sss_pbd_table_build(eta, g, t, c->r.err);
    if (res != SSS_OK) {
        free(t);
        return jr_prefix(&c->r, NULL, res);
    }
    s->tables[s->table_count++] = t;
    *out = t;
    return SSS_OK;
}

static sss_result build_procedural(const sss_procedural *p, sss_mesh *m, sss_error *err)
{
    switch (p->shape) {
    case SSS_SHAPE_SPHERE: return sss_mesh_sphere(p->radius, p->subdivisions, m, err);
    case SSS_SHAPE_TORUS: return sss_mesh_torus(p->major, p->minor, p->segments, m, err);
    case SSS_SHAPE_TREFOIL: return sss_mesh_trefoil(p->radius, p->tube, p->segments, m, err);
    case SSS_SHAPE_PLANE: return sss_mesh_plane(p->size, m, err);
    case SSS_SHAPE_BOX: return sss_mesh_box(p->box_size, m, err);
    default: return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "not a procedural shape");
    }
}

/* Refuses an object whose world-space positions leave the range every renderer can handle, naming
 * the field that puts it there (the transform, or the mesh itself when it is that large at rest). */
static sss_result check_world_reach(jr *r, const sss_scene_object *o)
{
    double reach = sss_scene_object_world_reach(o);
    if (reach <= SSS_SCENE_MAX_WORLD_COORD) return SSS_OK;
    sss_scene_object at_rest = *o;
    sss_transform_identity(&at_rest.transform);
    const char *key = sss_scene_object_world_reach(&at_rest) <= SSS_SCENE_MAX_WORLD_COORD ? "transform"
                      : o->mesh_path                                                       ? "mesh"
                                                                                           : "procedural";
    return jr_fail_key(r, key, SSS_ERROR_LIMIT,
                       "world-space positions reach %g%s, beyond %g (the real-time renderer's single-precision "
                       "range; docs/limits.md)",
                       reach, reach > FLT_MAX ? " (not finite in single precision)" : "", SSS_SCENE_MAX_WORLD_COORD);
}

/* A texture file's path and whose it is (an object's or a given texture's index). */
typedef struct scene_path_index {
    char *path;
    size_t index;
} scene_path_index;

static int cmp_path(const void *a, const void *b)
{
    return strcmp(((const scene_path_index *)a)->path, ((const scene_path_index *)b)->path);
}

static int cmp_path_then_index(const void *a, const void *b)
{
    const scene_path_index *x = a, *y = b;
    int order = strcmp(x->path, y->path);
    return order ? order : (x->index > y->index) - (x->index < y->index);
}

/* c->texture_owner[i]: the first object whose texture is object i's file, so that each file is decoded
 * once; and the given textures by resolved path. Both sorted once: comparing every texture with every
 * earlier one (and resolving every given path each time) took 9 s for 32,000 objects with distinct
 * embedded images, quadratically more up to the 65,536 objects a scene may have. */
static sss_result index_textures(scene_ctx *c, const sss_scene *s)
{
    size_t n = 0, g = 0;
    scene_path_index *by_path = malloc((s->object_count ? s->object_count : 1) * sizeof *by_path);
    c->texture_owner = malloc((s->object_count ? s->object_count : 1) * sizeof *c->texture_owner);
    c->given_by_path = calloc(c->given_texture_count ? c->given_texture_count : 1, sizeof *c->given_by_path);
    int ok = by_path && c->texture_owner && c->given_by_path;
    for (size_t i = 0; ok && i < s->object_count; i++)
        if (s->objects[i].material.texture) by_path[n++] = (scene_path_index){s->objects[i].material.texture, i};
    if (ok) qsort(by_path, n, sizeof *by_path, cmp_path_then_index);
    for (size_t k = 0; ok && k < n; k++)
        c->texture_owner[by_path[k].index] = k > 0 && strcmp(by_path[k].path, by_path[k - 1].path) == 0
                                                 ? c->texture_owner[by_path[k - 1].index]
                                                 : by_path[k].index;
    free(by_path);
    for (size_t k = 0; ok && k < c->given_texture_count; k++) {
        if (!c->given_textures[k].image.pixels) continue;
        ok = (c->given_by_path[g].path = join_path(c->base_dir, c->given_textures[k].path)) != NULL;
        c->given_by_path[g++].index = k;
    }
    c->given_by_path_count = g;
    if (ok) qsort(c->given_by_path, g, sizeof *c->given_by_path, cmp_path);
    return ok ? SSS_OK : jr_fail(&c->r, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
}

static void free_texture_index(scene_ctx *c)
{
    for (size_t k = 0; c->given_by_path && k < c->given_by_path_count; k++) free(c->given_by_path[k].path);
    free(c->given_by_path);
    free(c->texture_owner);
    c->given_by_path = NULL;
    c->texture_owner = NULL;
}

/* A given texture (an imported asset's embedded image) standing in for the file at t->path. */
static int take_given_texture(scene_ctx *c, sss_scene_texture *t)
{
    scene_path_index key = {t->path, 0};
    scene_path_index *found = bsearch(&key, c->given_by_path, c->given_by_path_count, sizeof key, cmp_path);
    sss_scene_texture *g = found ? &c->given_textures[found->index] : NULL;
    if (!g || !g->image.pixels) return 0;
    t->image = g->image;
    if (!c->given_lent) memset(&g->image, 0, sizeof g->image);
    return 1;
}

/* The material's texture, decoded once per file into s->textures (room for one per object) and refused
 * as the real-time renderer would refuse it (unreadable, NaN or Inf), so that every command that loads
 * the scene refuses the same files. */
static sss_result load_texture(scene_ctx *c, sss_scene *s, size_t index, sss_scene_material *m)
{
    size_t owner = c->texture_owner[index];
    if (owner != index) { /* an earlier object's file, loaded with it */
        m->texture_image = s->objects[owner].material.texture_image;
        return SSS_OK;
    }
    sss_scene_texture *t = &s->textures[s->texture_count];
    if (!(t->path = scene_strdup(m->texture))) return sss_error_set(c->r.err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    int given = take_given_texture(c, t);
    sss_result res = given ? SSS_OK : sss_image_read(m->texture, &t->image, c->r.err);
    if (res == SSS_OK && sss_image_count_nonfinite(&t->image))
        res = sss_error_set(c->r.err, SSS_ERROR_NUMERIC, "%s: albedo texture holds NaN or Inf", m->texture);
    if (given && c->given_lent) memset(&t->image, 0, sizeof t->image); /* checked; stays with its owner */
    if (res != SSS_OK) {
        free(t->path);
        sss_image_free(&t->image);
        memset(t, 0, sizeof *t);
        return res;
    }
    s->texture_count++;
    m->texture_image = &t->image;
    return SSS_OK;
}

static sss_result load_object(scene_ctx *c, sss_scene *s, sss_scene_object *o)
{
    jr *r = &c->r;
    sss_result res;
    if (o->material.type == SSS_SCENE_MATERIAL_SUBSURFACE) {
        const sss_pbd_table *t = NULL;
        size_t mark = jr_enter_key(r, "material");
        res = scene_table(c, s, o->material.optical.eta, o->material.optical.g, &t);
        if (res == SSS_OK) res = scene_resolve_material(c, &o->material, t);
        jr_leave(r, mark);
        if (res != SSS_OK) return res;
    }
    if (c->flags & SSS_SCENE_SKIP_MESHES) return SSS_OK;
    size_t index = (size_t)(o - s->objects);
    if (index < c->given_count) {
        o->mesh = c->given_meshes[index];
        if (!c->given_lent) memset(&c->given_meshes[index], 0, sizeof c->given_meshes[index]);
        res = SSS_OK;
    } else if (o->mesh_path) {
        res = sss_mesh_read(o->mesh_path, &o->mesh, r->err);
    } else {
        res = build_procedural(&o->procedural, &o->mesh, r->err);
    }
    if (res != SSS_OK) return jr_prefix(r, o->mesh_path ? "mesh" : "procedural", res);
    sss_mesh_bounds(&o->mesh, o->bounds_min, o->bounds_max);
    if ((res = check_world_reach(r, o)) != SSS_OK) return res;
    /* docs/scene-format.md: a texture needs UVs in the mesh. */
    if (o->material.texture && !o->mesh.uvs) {
        size_t mark = jr_enter_key(r, "material");
        res = jr_fail_key(r, "texture", SSS_ERROR_INVALID_ARGUMENT, "needs UVs, but the %s has none",
                          o->mesh_path ? "mesh file" : "procedural shape");
        jr_leave(r, mark);
        return res;
    }
    if (o->material.texture && (res = load_texture(c, s, index, &o->material)) != SSS_OK) {
        size_t mark = jr_enter_key(r, "material");
        res = jr_prefix(r, "texture", res);
        jr_leave(r, mark);
        return res;
    }
    if (o->splat_mesh_path && (res = sss_mesh_read(o->splat_mesh_path, &o->splat_mesh, r->err)) != SSS_OK)
        return jr_prefix(r, "splat_mesh", res);
    return SSS_OK;
}

static sss_result load_phase(scene_ctx *c, sss_scene *s)
{
    jr *r = &c->r;
    if (!(c->flags & SSS_SCENE_SKIP_MESHES) && s->object_count &&
        !(s->textures = calloc(s->object_count, sizeof *s->textures)))
        return jr_fail(r, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    sss_result res = c->flags & SSS_SCENE_SKIP_MESHES ? SSS_OK : index_textures(c, s);
    size_t mark = jr_enter_key(r, "objects");
    for (size_t i = 0; i < s->object_count && res == SSS_OK; i++) {
        size_t m2 = jr_enter_index(r, i);
        res = load_object(c, s, &s->objects[i]);
        jr_leave(r, m2);
        if (c->given_lent && i < c->given_count) /* checked; stays with its owner */
            memset(&s->objects[i].mesh, 0, sizeof s->objects[i].mesh);
    }
    jr_leave(r, mark);
    free_texture_index(c);
    return res;
}

/* ---- Entry points ---------------------------------------------------------------------------- */

sss_result sss_scene_parse(const char *json_text, size_t size, const char *base_dir, const char *name,
                           const sss_scene_load_desc *desc, sss_scene *scene, sss_error *err)
{
    return scene_parse_given(json_text, size, base_dir, name, desc, NULL, scene, err);
}

sss_result scene_parse_given(const char *json_text, size_t size, const char *base_dir, const char *name,
                             const sss_scene_load_desc *desc, scene_given *given, sss_scene *scene, sss_error *err)
{
    scene_ctx ctx;
    memset(&ctx, 0, sizeof ctx);
    memset(scene, 0, sizeof *scene);
    ctx.given_meshes = given ? given->meshes : NULL;
    ctx.given_count = given && given->meshes ? given->mesh_count : 0;
    ctx.given_textures = given ? given->textures : NULL;
    ctx.given_texture_count = given && given->textures ? given->texture_count : 0;
    ctx.given_lent = given ? given->lent : 0;
    if (!name) name = "scene";
    jr_init(&ctx.r, name, err);
    ctx.base_dir = base_dir ? base_dir : ".";
    ctx.flags = desc ? desc->flags : 0;
    if (!json_text && size > 0) return jr_fail(&ctx.r, SSS_ERROR_INVALID_ARGUMENT, "no text");
    if (size > SSS_SCENE_MAX_FILE_SIZE)
        return jr_fail(&ctx.r, SSS_ERROR_LIMIT, "%zu bytes, more than the %u accepted", size,
                       (unsigned)SSS_SCENE_MAX_FILE_SIZE);

    cJSON *root = NULL;
    sss_result res = jr_parse(&ctx.r, json_text, size, &root);
    if (res != SSS_OK) return res;
    scene->name = scene_strdup(name);
    scene->base_dir = scene_strdup(ctx.base_dir);
    if (!scene->name || !scene->base_dir) res = jr_fail(&ctx.r, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    if (res == SSS_OK) res = parse_root(&ctx, root, scene);
    cJSON_Delete(root);
    if (res == SSS_OK) res = load_phase(&ctx, scene);
    if (res != SSS_OK) sss_scene_free(scene);
    return res;
}

sss_result sss_scene_load(const char *path, const sss_scene_load_desc *desc, sss_scene *scene, sss_error *err)
{
    memset(scene, 0, sizeof *scene);
    char ext[8];
    sss_path_extension(path, ext, sizeof ext);
    if (strcmp(ext, "gltf") == 0 || strcmp(ext, "glb") == 0) return scene_load_gltf(path, desc, scene, err);
    char *text = NULL;
    size_t size = 0;
    sss_result res = sss_read_file(path, SSS_SCENE_MAX_FILE_SIZE, &text, &size, err);
    if (res != SSS_OK) return res;
    /* The folder of the scene file: relative paths inside it start there. */
    char *dir = scene_folder_of(path);
    if (!dir) {
        free(text);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    res = sss_scene_parse(text, size, dir, path, desc, scene, err);
    free(dir);
    free(text);
    return res;
}

void sss_scene_free(sss_scene *scene)
{
    if (!scene) return;
    for (size_t i = 0; i < scene->object_count; i++) scene_object_free(&scene->objects[i]);
    for (size_t i = 0; i < scene->light_count; i++) scene_light_free(&scene->lights[i]);
    for (size_t i = 0; i < scene->table_count; i++) free(scene->tables[i]);
    for (size_t i = 0; i < scene->texture_count; i++) {
        free(scene->textures[i].path);
        sss_image_free(&scene->textures[i].image);
    }
    free(scene->textures);
    for (size_t i = 0; i < scene->file_count; i++) free(scene->files[i]);
    free(scene->files);
    free(scene->objects);
    free(scene->lights);
    free(scene->tables);
    free(scene->name);
    free(scene->base_dir);
    memset(scene, 0, sizeof *scene);
}

const char *sss_animation_type_name(sss_animation_type type)
{
    switch (type) {
    case SSS_ANIMATION_NONE: return "none";
    case SSS_ANIMATION_TWIST: return "twist";
    case SSS_ANIMATION_BEND: return "bend";
    case SSS_ANIMATION_WAVE: return "wave";
    }
    return "unknown";
}

const char *sss_light_type_name(sss_light_type type)
{
    static const char *const names[] = {"point", "spot", "directional", "area", "environment"};
    return (unsigned)type < SCENE_COUNT(names) ? names[type] : "unknown";
}

const char *sss_scene_profile_name(sss_scene_profile profile)
{
    static const char *const names[] = {"pbd", "dipole", "artist"};
    return (unsigned)profile < SCENE_COUNT(names) ? names[profile] : "unknown";
}
