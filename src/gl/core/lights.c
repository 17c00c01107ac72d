/* gl/lights.c — light records, virtual point lights for area and environment lights, and shadow maps
 * (Maisch & Ropinski 2020, pass 2): cube maps for point lights and area-light VPLs, 2D maps for spot, directional and
 * environment lights.
 *
 * Documented approximations (the CPU reference integrates these lights with many samples per point):
 *  - an area light (rectangle center +- u +- v, radiance L) becomes n x n virtual point lights at the
 *    centres of a regular grid of cells, each a cosine emitter of intensity L * A / n^2 * cos(theta_e)
 *    (|cos| when two-sided) with its own cube shadow map; exact in the far field, too bright/too
 *    peaked within about a cell size of the rectangle.
 *  - an environment map becomes K directional lights by median cut (Debevec 2005): the map is split
 *    recursively into regions of equal energy (solid-angle weighted luminance), each replaced by one
 *    directional light at its energy centroid carrying the region's integral of L d(omega) as its
 *    irradiance at normal incidence, with an orthographic shadow map.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/vecmath.h"
#include "gl/core/env_cut.h"
#include "gl/core/gl_core.h"

#define ENV_MAX_WIDTH 256

typedef struct vec3d {
    double x, y, z;
} vec3d;

static vec3d v3(const double *a) { return (vec3d){a[0], a[1], a[2]}; }
static vec3d vsub(vec3d a, vec3d b) { return (vec3d){a.x - b.x, a.y - b.y, a.z - b.z}; }
static vec3d vadd(vec3d a, vec3d b) { return (vec3d){a.x + b.x, a.y + b.y, a.z + b.z}; }
static vec3d vscale(vec3d a, double s) { return (vec3d){a.x * s, a.y * s, a.z * s}; }
static double vdot(vec3d a, vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static vec3d vcross(vec3d a, vec3d b)
{
    return (vec3d){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static double vlen(vec3d a) { return sqrt(vdot(a, a)); }
static vec3d vnorm(vec3d a)
{
    double l = vlen(a);
    return l > 0.0 ? vscale(a, 1.0 / l) : (vec3d){0, 1, 0};
}

/* A view matrix from vec3d points (core/vecmath.h's m4_look_at). */
static void look_at(vec3d eye, vec3d target, vec3d up, float m[16])
{
    const double e[3] = {eye.x, eye.y, eye.z}, t[3] = {target.x, target.y, target.z}, u[3] = {up.x, up.y, up.z};
    m4_look_at(e, t, u, m);
}

/* An environment map as read once per renderer: the file downsampled (box filter) to at most
 * ENV_MAX_WIDTH columns, radiance x the cell's exact solid angle, before the light's scale. Light
 * updates re-cut it (scale and rotation may change) without reading the file again. */
struct gl_env_cache {
    char *file;
    int w, h;
    double *rgb;
};

static sss_result env_downsample(const sss_image *img, struct gl_env_cache *c, sss_error *err)
{
    int f = 1;
    while (img->width / f > ENV_MAX_WIDTH) f *= 2;
    c->w = img->width / f > 0 ? img->width / f : 1;
    c->h = img->height / f > 0 ? img->height / f : 1;
    c->rgb = calloc((size_t)c->w * c->h * 3, sizeof *c->rgb);
    if (!c->rgb) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (environment map)");
    for (int y = 0; y < c->h; y++) {
        double th0 = M_PI * y / c->h, th1 = M_PI * (y + 1) / c->h;
        double domega = (cos(th0) - cos(th1)) * 2.0 * M_PI / c->w; /* exact solid angle of the cell */
        for (int x = 0; x < c->w; x++) {
            double sum[3] = {0, 0, 0};
            int n = 0;
            for (int j = 0; j < f; j++)
                for (int i = 0; i < f; i++) {
                    int sx = x * f + i, sy = y * f + j;
                    if (sx >= img->width || sy >= img->height) continue;
                    const float *p = img->pixels + 3 * ((size_t)sy * img->width + sx);
                    for (int k = 0; k < 3; k++) sum[k] += isfinite(p[k]) && p[k] > 0.0f ? p[k] : 0.0;
                    n++;
                }
            size_t idx = (size_t)y * c->w + x;
            for (int k = 0; k < 3; k++) c->rgb[3 * idx + k] = sum[k] / (n ? n : 1) * domega;
        }
    }
    return SSS_OK;
}

/* The first environment map at full resolution, for camera rays that miss (sss/reference.h). */
static sss_result env_upload(gl_scene *gs, const sss_light *L, sss_image *img, int max_size, sss_error *err)
{
    if (img->width > max_size || img->height > max_size)
        return sss_error_set(err, SSS_ERROR_LIMIT, "%s: environment map of %dx%d exceeds the GL texture limit %d",
                             L->file, img->width, img->height, max_size);
    for (size_t i = 0; i < (size_t)img->width * img->height * 3; i++)
        if (!isfinite(img->pixels[i]) || img->pixels[i] < 0.0f) img->pixels[i] = 0.0f;
    /* A full mip chain: the specular reflection of rough interfaces reads coarser levels. */
    int levels = 1;
    while ((img->width >> levels) > 0 || (img->height >> levels) > 0) levels++;
    glCreateTextures(GL_TEXTURE_2D, 1, &gs->env_tex);
    glTextureStorage2D(gs->env_tex, levels, GL_RGB32F, img->width, img->height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    /* row 0 of the texture = the top row of the image (v = 0), so no flip: the shader uses v directly */
    glTextureSubImage2D(gs->env_tex, 0, 0, 0, img->width, img->height, GL_RGB, GL_FLOAT, img->pixels);
    glGenerateTextureMipmap(gs->env_tex);
    glTextureParameteri(gs->env_tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(gs->env_tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(gs->env_tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(gs->env_tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gs->texture_bytes += (size_t)img->width * img->height * 12 * 4 / 3; /* with its mip chain */
    return SSS_OK;
}

/* The light's map from the cache, reading (and, for the first map, uploading) it on first use. */
static sss_result env_cached(gl_core *core, const sss_light *L, const struct gl_env_cache **out,
                             sss_error *err)
{
    gl_scene *gs = &core->gs;
    for (int i = 0; i < gs->env_cache_count; i++)
        if (strcmp(gs->env_cache[i].file, L->file) == 0) {
            *out = &gs->env_cache[i];
            return SSS_OK;
        }
    struct gl_env_cache *grown = realloc(gs->env_cache, (size_t)(gs->env_cache_count + 1) * sizeof *grown);
    if (!grown) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (environment map)");
    gs->env_cache = grown;
    struct gl_env_cache c = {0};
    sss_image img;
    sss_result res = sss_image_read(L->file, &img, err);
    if (res != SSS_OK) return res;
    if ((res = sss_image_require_finite(&img, L->file, err)) != SSS_OK) { /* as the reference: refused, not zeroed */
        sss_image_free(&img);
        const sss_scene *sc = core->scene;
        for (size_t i = 0; i < sc->light_count; i++)
            if (&sc->lights[i] == L) {
                char prefix[512];
                snprintf(prefix, sizeof prefix, "%s: lights[%zu].file", sc->name ? sc->name : "scene", i);
                sss_error_prefix(err, prefix);
            }
        return res;
    }
    res = env_downsample(&img, &c, err);
    if (res == SSS_OK && !gs->env_tex) res = env_upload(gs, L, &img, core->ctx->max_texture_size, err);
    if (res == SSS_OK && !(c.file = strdup(L->file)))
        res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (environment map)");
    sss_image_free(&img);
    if (res != SSS_OK) {
        free(c.rgb);
        return res;
    }
    gs->env_cache[gs->env_cache_count] = c;
    *out = &gs->env_cache[gs->env_cache_count++];
    return SSS_OK;
}

void gl_env_cache_free(gl_scene *gs)
{
    for (int i = 0; i < gs->env_cache_count; i++) {
        free(gs->env_cache[i].file);
        free(gs->env_cache[i].rgb);
    }
    free(gs->env_cache);
    gs->env_cache = NULL;
    gs->env_cache_count = 0;
}

static int env_light_count(const gl_core *core)
{
    int k = (int)core->shared[GL_P_ENV_LIGHTS], p = 1;
    while (p * 2 <= k) p *= 2; /* median cut produces powers of two */
    return p;
}

static int area_grid(const gl_core *core)
{
    int n = (int)floor(sqrt(core->shared[GL_P_AREA_SAMPLES]) + 0.5);
    return n < 1 ? 1 : n;
}

typedef struct light_set {
    gl_light_record *lights;
    int light_count, vpl_count;
    int cube_size, map_size, cube_count, map_count;
    int cubes_vpl, maps_env; /* of the cube and 2D maps: those of area-light VPLs, environment lights */
} light_set;

/* Records for every light (area lights: n_area^2 VPLs; environment maps: n_env directions). */
static sss_result records_alloc(const sss_scene *s, int n_area, int n_env, light_set *ls, sss_error *err)
{
    size_t cap = 0;
    for (size_t i = 0; i < s->light_count; i++) {
        switch (s->lights[i].type) {
        case SSS_LIGHT_AREA: cap += (size_t)n_area * n_area; break;
        case SSS_LIGHT_ENVIRONMENT: cap += (size_t)n_env; break;
        default: cap += 1; break;
        }
    }
    ls->lights = calloc(cap ? cap : 1, sizeof *ls->lights);
    return ls->lights ? SSS_OK : sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (lights)");
}

/* An area light as n x n cosine-emitting VPLs at the cell centres, each with a cube map. */
static void area_vpls(const sss_light *L, int n_area, light_set *ls)
{
    vec3d u = v3(L->u), v = v3(L->v), ce = v3(L->center);
    vec3d nrm = vnorm(vcross(u, v));
    double area = 4.0 * vlen(vcross(u, v));
    for (int a = 0; a < n_area; a++)
        for (int b = 0; b < n_area; b++) {
            gl_light_record *g = &ls->lights[ls->light_count++];
            double su = 2.0 * (a + 0.5) / n_area - 1.0, sv = 2.0 * (b + 0.5) / n_area - 1.0;
            vec3d p = vadd(ce, vadd(vscale(u, su), vscale(v, sv)));
            g->position[0] = (float)p.x;
            g->position[1] = (float)p.y;
            g->position[2] = (float)p.z;
            g->position[3] = GL_LIGHT_VPL;
            g->direction[0] = (float)nrm.x;
            g->direction[1] = (float)nrm.y;
            g->direction[2] = (float)nrm.z;
            g->direction[3] = L->two_sided ? 1.0f : 0.0f;
            for (int k = 0; k < 3; k++) g->color[k] = (float)(L->radiance[k] * area / (n_area * n_area));
            g->spot[2] = GL_SHADOW_CUBE;
            g->spot[3] = (float)ls->cube_count++;
            ls->cubes_vpl++;
        }
    ls->vpl_count += n_area * n_area;
}

/* An environment map as up to n_env directional lights by median cut, each with a 2D map. */
static sss_result environment_lights(gl_core *core, const sss_light *L, int n_env, light_set *ls, sss_error *err)
{
    gl_scene *gs = &core->gs;
    const struct gl_env_cache *cache = NULL;
    sss_result res = env_cached(core, L, &cache, err);
    /* the background shows the first map (cached first, uploaded); its rotation and scale may
     * change after the upload (sss_gl_renderer_update_lights) */
    if (res == SSS_OK && strcmp(gs->env_cache[0].file, L->file) == 0) {
        gs->env_rotate_y = (float)L->rotate_y;
        for (int k = 0; k < 3; k++) gs->env_scale[k] = (float)L->scale[k];
    }
    int cut = 0;
    gl_env_light *env = res == SSS_OK ? calloc((size_t)n_env, sizeof *env) : NULL;
    if (res == SSS_OK && !env) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (environment lights)");
    if (res == SSS_OK) res = gl_env_median_cut(cache->rgb, cache->w, cache->h, L->scale, L->rotate_y, n_env, env, &cut, err);
    for (int k = 0; res == SSS_OK && k < cut; k++) {
        gl_light_record *g = &ls->lights[ls->light_count++];
        g->position[3] = GL_LIGHT_DIRECTIONAL;
        g->direction[3] = GL_LIGHT_FROM_ENVIRONMENT; /* its specular comes from the map itself */
        for (int ch = 0; ch < 3; ch++) {
            g->direction[ch] = (float)-env[k].to_light[ch];
            g->color[ch] = (float)env[k].rgb[ch];
        }
        g->spot[2] = GL_SHADOW_2D;
        g->spot[3] = (float)ls->map_count++;
        ls->maps_env++;
        ls->vpl_count++;
    }
    free(env);
    return res;
}

/* A point (cube map), spot (2D map, or a cube when wider than 75 degrees) or directional light (2D). */
static void delta_light(const sss_light *L, light_set *ls)
{
    gl_light_record *g = &ls->lights[ls->light_count++];
    for (int k = 0; k < 3; k++) {
        g->position[k] = (float)L->position[k];
        g->color[k] = (float)(L->type == SSS_LIGHT_DIRECTIONAL ? L->radiance[k] : L->intensity[k]);
    }
    int cube = L->type == SSS_LIGHT_POINT || (L->type == SSS_LIGHT_SPOT && L->cone_angle > 75.0);
    if (L->type == SSS_LIGHT_POINT) {
        g->position[3] = GL_LIGHT_POINT;
    } else if (L->type == SSS_LIGHT_SPOT) {
        g->position[3] = GL_LIGHT_SPOT;
        vec3d axis = vnorm(vsub(v3(L->look_at), v3(L->position)));
        g->direction[0] = (float)axis.x;
        g->direction[1] = (float)axis.y;
        g->direction[2] = (float)axis.z;
        g->spot[0] = (float)cos(L->cone_angle * M_PI / 180.0);
        g->spot[1] = (float)cos((L->cone_angle - L->cone_delta) * M_PI / 180.0);
    } else {
        g->position[3] = GL_LIGHT_DIRECTIONAL;
        vec3d d = vnorm(v3(L->direction));
        g->direction[0] = (float)d.x;
        g->direction[1] = (float)d.y;
        g->direction[2] = (float)d.z;
    }
    g->spot[2] = cube ? GL_SHADOW_CUBE : GL_SHADOW_2D;
    g->spot[3] = (float)(cube ? ls->cube_count++ : ls->map_count++);
}

/* One size per array (full-size maps when any light needs them, else the VPL size); the maps must fit
 * the GL's array layers and 2 GB. */
static sss_result shadow_sizes(const gl_core *core, light_set *ls, sss_error *err)
{
    int cubes = ls->cube_count, maps = ls->map_count;
    ls->cube_size = (int)core->shared[cubes > ls->cubes_vpl ? GL_P_SHADOW_CUBE_SIZE : GL_P_SHADOW_VPL_SIZE];
    ls->map_size = (int)core->shared[maps > ls->maps_env ? GL_P_SHADOW_2D_SIZE : GL_P_SHADOW_VPL_SIZE];
    GLint max_layers = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    double shadow_mb = ((double)ls->cube_size * ls->cube_size * 24.0 * cubes +
                        (double)ls->map_size * ls->map_size * 4.0 * maps) / 1048576.0;
    if (6 * cubes > max_layers || maps > max_layers)
        return sss_error_set(err, SSS_ERROR_LIMIT,
                             "%d cube and %d 2D shadow maps exceed the GL limit of %d array layers (fewer lights, "
                             "area_samples or env_lights)",
                             cubes, maps, (int)max_layers);
    if (shadow_mb > 2048.0)
        return sss_error_set(err, SSS_ERROR_LIMIT,
                             "the shadow maps would take %.0f MB (limit 2048 MB): lower shadow_cube_size, "
                             "shadow_size, shadow_vpl_size, area_samples or env_lights",
                             shadow_mb);
    return SSS_OK;
}

/* Each record's shadow transform: depth range of its cube map, or the projection of its 2D map (spot:
 * perspective along the axis; directional: orthographic over the scene's bounding sphere). */
static void shadow_transforms(const gl_scene *gs, light_set *ls)
{
    vec3d c = {0.5 * (gs->bounds_min[0] + gs->bounds_max[0]), 0.5 * (gs->bounds_min[1] + gs->bounds_max[1]),
               0.5 * (gs->bounds_min[2] + gs->bounds_max[2])};
    vec3d ext = {gs->bounds_max[0] - gs->bounds_min[0], gs->bounds_max[1] - gs->bounds_min[1],
                 gs->bounds_max[2] - gs->bounds_min[2]};
    double radius = 0.5 * vlen(ext);
    if (!(radius > 0.0)) radius = 1.0;
    for (int i = 0; i < ls->light_count; i++) {
        gl_light_record *g = &ls->lights[i];
        vec3d p = {g->position[0], g->position[1], g->position[2]};
        double far_d = vlen(vsub(p, c)) + radius;
        float V[16], P[16];
        if (g->spot[2] == GL_SHADOW_CUBE) {
            g->shadow[0] = (float)(far_d * 1e-4);
            g->shadow[1] = (float)(far_d * 1.01);
            g->shadow[2] = (float)(2.0 / ls->cube_size);
        } else if ((int)g->position[3] == GL_LIGHT_SPOT) {
            double cone = acos(g->spot[0]);
            look_at(p, vadd(p, (vec3d){g->direction[0], g->direction[1], g->direction[2]}), (vec3d){0, 1, 0}, V);
            m4_perspective(2.0 * cone * 1.02, far_d * 1e-4, far_d * 1.01, P);
            m4_mul(P, V, g->shadow_matrix);
            g->shadow[0] = (float)(far_d * 1e-4);
            g->shadow[1] = (float)(far_d * 1.01);
            g->shadow[2] = (float)(2.0 * tan(cone * 1.02) / ls->map_size);
        } else {
            vec3d d = {g->direction[0], g->direction[1], g->direction[2]};
            vec3d eye = vsub(c, vscale(d, 2.0 * radius));
            look_at(eye, c, (vec3d){0, 1, 0}, V);
            m4_ortho(radius * 1.01, radius * 0.9, radius * 3.1, P);
            m4_mul(P, V, g->shadow_matrix);
            g->shadow[0] = (float)(radius * 0.9);
            g->shadow[1] = (float)(radius * 3.1);
            g->shadow[2] = (float)(2.0 * radius * 1.01 / ls->map_size);
            g->shadow[3] = 1.0f;
        }
    }
}

/* Light records of the scene's lights as they are now (VPLs of area lights, median-cut directions of
 * environment maps, shadow-map slots and transforms). Uploads the environment map once. */
static sss_result light_records(gl_core *core, light_set *ls, sss_error *err)
{
    memset(ls, 0, sizeof *ls);
    const sss_scene *s = core->scene;
    int n_area = area_grid(core), n_env = env_light_count(core);
    sss_result res = records_alloc(s, n_area, n_env, ls, err);
    for (size_t i = 0; i < s->light_count && res == SSS_OK; i++) {
        const sss_light *L = &s->lights[i];
        if (L->type == SSS_LIGHT_AREA) area_vpls(L, n_area, ls);
        else if (L->type == SSS_LIGHT_ENVIRONMENT) res = environment_lights(core, L, n_env, ls, err);
        else delta_light(L, ls);
    }
    if (res == SSS_OK) res = shadow_sizes(core, ls, err);
    if (res == SSS_OK) shadow_transforms(&core->gs, ls);
    return res;
}

sss_result gl_lights_build(gl_core *core, sss_error *err)
{
    gl_scene *gs = &core->gs;
    light_set ls;
    sss_result res = light_records(core, &ls, err);
    if (res != SSS_OK) {
        free(ls.lights);
        return res;
    }
    gs->lights = ls.lights;
    gs->light_count = ls.light_count;
    gs->vpl_count = ls.vpl_count;
    gs->shadow_cube_size = ls.cube_size;
    gs->shadow_2d_size = ls.map_size;
    gs->shadow_cube_count = ls.cube_count;
    gs->shadow_2d_count = ls.map_count;
    int n = ls.light_count, cubes = ls.cube_count, maps = ls.map_count;
    glCreateBuffers(1, &gs->ssbo_lights);
    /* dynamic: sss_gl_renderer_update_lights rewrites the records when lights move */
    glNamedBufferStorage(gs->ssbo_lights, (GLsizeiptr)(sizeof *gs->lights * (size_t)(n ? n : 1)), gs->lights,
                         GL_DYNAMIC_STORAGE_BIT);
    gs->buffer_bytes += sizeof *gs->lights * (size_t)(n ? n : 1);
    /* Shadow textures (a 1-layer dummy when unused keeps the samplers complete). */
    glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &gs->shadow_cube);
    glTextureStorage3D(gs->shadow_cube, 1, GL_DEPTH_COMPONENT32F, gs->shadow_cube_size, gs->shadow_cube_size,
                       6 * (cubes ? cubes : 1));
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &gs->shadow_2d);
    glTextureStorage3D(gs->shadow_2d, 1, GL_DEPTH_COMPONENT32F, gs->shadow_2d_size, gs->shadow_2d_size,
                       maps ? maps : 1);
    GLuint t[2] = {gs->shadow_cube, gs->shadow_2d};
    for (int i = 0; i < 2; i++) {
        glTextureParameteri(t[i], GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(t[i], GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(t[i], GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t[i], GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t[i], GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(t[i], GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
    gs->texture_bytes += (size_t)gs->shadow_cube_size * gs->shadow_cube_size * 4 * 6 * (size_t)(cubes ? cubes : 1) +
                         (size_t)gs->shadow_2d_size * gs->shadow_2d_size * 4 * (size_t)(maps ? maps : 1);
    glCreateFramebuffers(1, &gs->shadow_fbo);
    glNamedFramebufferDrawBuffer(gs->shadow_fbo, GL_NONE);
    glNamedFramebufferReadBuffer(gs->shadow_fbo, GL_NONE);
    /* Cleared once so that lights without casters read "lit". */
    return gl_check(core->ctx, "the light setup", err);
}

sss_result gl_lights_record_kinds(gl_core *core, sss_error *err)
{
    gl_scene *gs = &core->gs;
    size_t n = core->scene->light_count;
    free(gs->light_kinds);
    gs->light_kinds = n ? malloc(sizeof *gs->light_kinds * n) : NULL;
    gs->light_kind_count = gs->light_kinds ? n : 0;
    if (n && !gs->light_kinds) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (light kinds)");
    for (size_t i = 0; i < n; i++) gs->light_kinds[i] = core->scene->lights[i].type;
    return SSS_OK;
}

sss_result gl_lights_check_kinds(const gl_core *core, sss_error *err)
{
    const gl_scene *gs = &core->gs;
    const sss_scene *s = core->scene;
    if (s->light_count != gs->light_kind_count)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "the scene has %zu light%s, it had %zu when it was uploaded (lights keep their number "
                             "and kinds: a new renderer or pass is needed)",
                             s->light_count, s->light_count == 1 ? "" : "s", gs->light_kind_count);
    for (size_t i = 0; i < s->light_count; i++)
        if (s->lights[i].type != gs->light_kinds[i])
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "lights[%zu] is a %s light, it was a %s light when the scene was uploaded (lights "
                                 "keep their number and kinds: a new renderer or pass is needed)",
                                 i, sss_light_type_name(s->lights[i].type), sss_light_type_name(gs->light_kinds[i]));
    return SSS_OK;
}

sss_result gl_lights_update(gl_core *core, sss_error *err)
{
    gl_scene *gs = &core->gs;
    sss_result res = gl_lights_check_kinds(core, err);
    if (res != SSS_OK) return res;
    light_set ls;
    res = light_records(core, &ls, err);
    if (res == SSS_OK && (ls.light_count != gs->light_count || ls.cube_count != gs->shadow_cube_count ||
                          ls.map_count != gs->shadow_2d_count || ls.cube_size != gs->shadow_cube_size ||
                          ls.map_size != gs->shadow_2d_size))
        res = sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                            "the lights changed in number or kind (%d records, %d cube and %d 2D shadow maps; the "
                            "renderer has %d, %d, %d): create a new renderer",
                            ls.light_count, ls.cube_count, ls.map_count, gs->light_count, gs->shadow_cube_count,
                            gs->shadow_2d_count);
    for (int i = 0; res == SSS_OK && i < ls.light_count; i++)
        if (ls.lights[i].spot[2] != gs->lights[i].spot[2] || ls.lights[i].spot[3] != gs->lights[i].spot[3] ||
            ls.lights[i].position[3] != gs->lights[i].position[3])
            res = sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                "light record %d changed its type or shadow map: create a new renderer", i);
    if (res != SSS_OK) {
        free(ls.lights);
        return res;
    }
    memcpy(gs->lights, ls.lights, sizeof *ls.lights * (size_t)ls.light_count);
    free(ls.lights);
    if (ls.light_count > 0)
        glNamedBufferSubData(gs->ssbo_lights, 0, (GLsizeiptr)(sizeof *gs->lights * (size_t)ls.light_count), gs->lights);
    return gl_check(core->ctx, "the light update", err);
}

sss_result gl_shadows_render(gl_core *core, sss_error *err)
{
    gl_scene *gs = &core->gs;
    if (gs->light_count == 0) return SSS_OK;
    glUseProgram(core->prog_shadow);
    GLint u_obj = glGetUniformLocation(core->prog_shadow, "u_object");
    GLint u_vp = glGetUniformLocation(core->prog_shadow, "u_light_view_proj");
    GLint u_cube = glGetUniformLocation(core->prog_shadow, "u_cube");
    GLint u_lpos = glGetUniformLocation(core->prog_shadow, "u_light_pos");
    GLint u_far = glGetUniformLocation(core->prog_shadow, "u_far");
    glBindFramebuffer(GL_FRAMEBUFFER, gs->shadow_fbo);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    static const double face_dir[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const double face_up[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    const float one = 1.0f;
    for (int i = 0; i < gs->light_count; i++) {
        const gl_light_record *g = &gs->lights[i];
        int kind = (int)g->spot[2], layer = (int)g->spot[3];
        if (kind == GL_SHADOW_CUBE) {
            vec3d p = {g->position[0], g->position[1], g->position[2]};
            float P[16];
            m4_perspective(M_PI / 2.0, g->shadow[0], g->shadow[1], P);
            glViewport(0, 0, gs->shadow_cube_size, gs->shadow_cube_size);
            glUniform1i(u_cube, 1);
            glUniform3f(u_lpos, g->position[0], g->position[1], g->position[2]);
            glUniform1f(u_far, g->shadow[1]);
            glDisable(GL_POLYGON_OFFSET_FILL);
            for (int f = 0; f < 6; f++) {
                float V[16], VP[16];
                look_at(p, vadd(p, v3(face_dir[f])), v3(face_up[f]), V);
                m4_mul(P, V, VP);
                glNamedFramebufferTextureLayer(gs->shadow_fbo, GL_DEPTH_ATTACHMENT, gs->shadow_cube, 0, 6 * layer + f);
                glClearBufferfv(GL_DEPTH, 0, &one);
                glUniformMatrix4fv(u_vp, 1, GL_FALSE, VP);
                for (int o = 0; o < gs->object_count; o++) {
                    if (gs->objects[o].emitter) continue;
                    glUniform1i(u_obj, o);
                    glBindVertexArray(gs->objects[o].vao);
                    glDrawElements(GL_TRIANGLES, (GLsizei)(3 * gs->objects[o].triangle_count), GL_UNSIGNED_INT, NULL);
                }
            }
        } else if (kind == GL_SHADOW_2D) {
            glViewport(0, 0, gs->shadow_2d_size, gs->shadow_2d_size);
            glUniform1i(u_cube, 0);
            glEnable(GL_POLYGON_OFFSET_FILL);
            glPolygonOffset(1.5f, 2.0f);
            glNamedFramebufferTextureLayer(gs->shadow_fbo, GL_DEPTH_ATTACHMENT, gs->shadow_2d, 0, layer);
            glClearBufferfv(GL_DEPTH, 0, &one);
            glUniformMatrix4fv(u_vp, 1, GL_FALSE, g->shadow_matrix);
            for (int o = 0; o < gs->object_count; o++) {
                if (gs->objects[o].emitter) continue;
                glUniform1i(u_obj, o);
                glBindVertexArray(gs->objects[o].vao);
                glDrawElements(GL_TRIANGLES, (GLsizei)(3 * gs->objects[o].triangle_count), GL_UNSIGNED_INT, NULL);
            }
            glDisable(GL_POLYGON_OFFSET_FILL);
        }
    }
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    return gl_check(core->ctx, "the shadow-map pass", err);
}
