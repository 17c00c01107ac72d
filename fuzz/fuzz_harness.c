/* fuzz/fuzz_harness.c — the checks behind every fuzz target (see fuzz_harness.h). Compiled into each
 * libFuzzer binary and included by tests/robustness/test_fuzz_regressions.c. */
#include "fuzz_harness.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/core/env_cut.h"
#include "sss/gltf.h"
#include "sss/image.h"
#include "sss/material.h"
#include "sss/mesh.h"
#include "sss/sam.h"
#include "sss/scene.h"

static char fuzz_message[640];

static const char *broken(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

static const char *broken(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(fuzz_message, sizeof fuzz_message, fmt, ap);
    va_end(ap);
    return fuzz_message;
}

/* A failed call must say so consistently and name its input (sss/common.h). */
static const char *check_error(sss_result r, const sss_error *err, const char *name)
{
    if (r == SSS_OK) return NULL;
    if (err->code != r) return broken("returned %d but err.code is %d (%s)", (int)r, (int)err->code, err->message);
    if (!err->message[0]) return broken("error %d with an empty message", (int)r);
    if (!strstr(err->message, name)) return broken("error message does not name '%s': %s", name, err->message);
    if (strlen(err->message) >= SSS_ERROR_MESSAGE_SIZE) return broken("unterminated error message");
    return NULL;
}

/* ---- Meshes ------------------------------------------------------------------------------------ */

/* from_file: the mesh came straight from a reader, so source_flags must describe its arrays
 * (procedural shapes have UVs that no file provided). */
static const char *check_mesh(const sss_mesh *m, const char *what, int from_file)
{
    if (m->vertex_count < 1 || m->vertex_count > SSS_MESH_MAX_VERTICES)
        return broken("%s: vertex_count %u out of range", what, m->vertex_count);
    if (m->triangle_count < 1 || m->triangle_count > SSS_MESH_MAX_TRIANGLES)
        return broken("%s: triangle_count %u out of range", what, m->triangle_count);
    if (!m->positions || !m->normals || !m->indices) return broken("%s: missing arrays", what);
    if (from_file && !m->uvs != !(m->source_flags & SSS_MESH_FROM_FILE_UVS))
        return broken("%s: uvs %s but source_flags 0x%x", what, m->uvs ? "present" : "absent", m->source_flags);
    for (size_t i = 0; i < 3 * (size_t)m->vertex_count; i++)
        if (!isfinite(m->positions[i])) return broken("%s: position value %zu is %g", what, i, m->positions[i]);
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *n = m->normals + 3 * (size_t)v;
        double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        if (!(fabs(len - 1.0) <= 1e-4)) return broken("%s: normal %u has length %g", what, v, len);
    }
    if (m->uvs)
        for (size_t i = 0; i < 2 * (size_t)m->vertex_count; i++)
            if (!isfinite(m->uvs[i])) return broken("%s: uv value %zu is %g", what, i, m->uvs[i]);
    for (size_t i = 0; i < 3 * (size_t)m->triangle_count; i++)
        if (m->indices[i] >= m->vertex_count)
            return broken("%s: index %zu = %u, only %u vertices", what, i, m->indices[i], m->vertex_count);
    return NULL;
}

static int mesh_is_empty(const sss_mesh *m)
{
    return !m->positions && !m->normals && !m->uvs && !m->indices && m->vertex_count == 0 && m->triangle_count == 0;
}

/* The derived quantities every consumer uses (sss mesh info, the renderers): finite and consistent. */
static const char *check_mesh_derived(const sss_mesh *m, const char *name)
{
    sss_error err = {0};
    sss_mesh_topology topo;
    sss_result r = sss_mesh_topology_compute(m, &topo, &err);
    if (r != SSS_OK) return broken("topology failed on a valid mesh: %s", err.message);
    if (topo.boundary_edges + topo.nonmanifold_edges > topo.edge_count || topo.edge_count > 3ull * m->triangle_count ||
        topo.degenerate_triangles > m->triangle_count)
        return broken("inconsistent topology: %llu edges, %llu boundary, %llu non-manifold, %llu degenerate",
                      (unsigned long long)topo.edge_count, (unsigned long long)topo.boundary_edges,
                      (unsigned long long)topo.nonmanifold_edges, (unsigned long long)topo.degenerate_triangles);
    sss_mesh_adjacency adj = {0};
    r = sss_mesh_adjacency_build(m, &adj, &err);
    if (r != SSS_OK) return broken("adjacency failed on a valid mesh: %s", err.message);
    const char *bad = NULL;
    if (adj.vertex_count != m->vertex_count || adj.offsets[0] != 0) bad = broken("adjacency header wrong");
    for (uint32_t v = 0; !bad && v < m->vertex_count; v++) {
        if (adj.offsets[v + 1] < adj.offsets[v] || adj.offsets[v + 1] - adj.offsets[v] > 6ull * m->triangle_count)
            bad = broken("adjacency offsets not monotone at %u", v);
        for (uint32_t k = adj.offsets[v]; !bad && k < adj.offsets[v + 1]; k++) {
            uint32_t u = adj.neighbors[k];
            if (u >= m->vertex_count || u == v || (k > adj.offsets[v] && adj.neighbors[k - 1] >= u))
                bad = broken("adjacency row %u not sorted, unique, in range, without itself", v);
        }
    }
    sss_mesh_adjacency_free(&adj);
    if (bad) return bad;
    float lo[3], hi[3];
    sss_mesh_bounds(m, lo, hi);
    for (int k = 0; k < 3; k++)
        if (!isfinite(lo[k]) || !isfinite(hi[k]) || lo[k] > hi[k]) return broken("bad bounds on axis %d", k);
    double area = sss_mesh_surface_area(m), vol = sss_mesh_signed_volume(m);
    if (!isfinite(area) || area < 0) return broken("surface area %g", area);
    if (!isfinite(vol)) return broken("signed volume %g", vol);
    /* Simplification of small meshes (the splatting techniques' low-resolution meshes). */
    if (m->triangle_count <= 4096) {
        uint32_t target = m->triangle_count / 2 ? m->triangle_count / 2 : 1;
        sss_mesh s = {0};
        r = sss_mesh_simplify(m, target, &s, &err);
        if (r == SSS_OK) {
            bad = check_mesh(&s, "simplified", 0);
            if (!bad && s.triangle_count > target)
                bad = broken("simplify to %u gave %u triangles", target, s.triangle_count);
        } else if (!err.message[0]) {
            bad = broken("simplify failed without a message");
        } else if (!mesh_is_empty(&s)) {
            bad = broken("simplify failed but left data in its output");
        }
        sss_mesh_free(&s);
    }
    (void)name;
    return bad;
}

static const char *fuzz_mesh(const uint8_t *data, size_t size, int ply)
{
    const char *name = ply ? "fuzz.ply" : "fuzz.obj";
    sss_mesh m;
    memset(&m, 0xa5, sizeof m); /* the reader must initialise its output */
    sss_error err = {0};
    sss_result r = ply ? sss_mesh_parse_ply(data, size, name, &m, &err) : sss_mesh_parse_obj(data, size, name, &m, &err);
    const char *bad = check_error(r, &err, name);
    if (r != SSS_OK) {
        if (!bad && !mesh_is_empty(&m)) bad = broken("failed (%s) but the mesh is not empty", err.message);
        if (mesh_is_empty(&m)) sss_mesh_free(&m);
        return bad;
    }
    bad = check_mesh(&m, name, 1);
    if (!bad) bad = check_mesh_derived(&m, name);
    sss_mesh_free(&m);
    return bad;
}

const char *sss_fuzz_ply(const uint8_t *data, size_t size) { return fuzz_mesh(data, size, 1); }
const char *sss_fuzz_obj(const uint8_t *data, size_t size) { return fuzz_mesh(data, size, 0); }

/* ---- Images ------------------------------------------------------------------------------------ */

static const char *fuzz_image(const uint8_t *data, size_t size, const char *name)
{
    sss_image img;
    memset(&img, 0xa5, sizeof img);
    sss_error err = {0};
    sss_result r = sss_image_decode(data, size, name, &img, &err);
    const char *bad = check_error(r, &err, name);
    if (r != SSS_OK) {
        if (!bad && (img.pixels || img.width || img.height)) bad = broken("failed (%s) but the image is not empty", err.message);
        if (!img.pixels) sss_image_free(&img);
        return bad;
    }
    if (img.width < 1 || img.height < 1 || img.width > SSS_IMAGE_MAX_DIM || img.height > SSS_IMAGE_MAX_DIM || !img.pixels)
        return broken("decoded image is %dx%d (pixels %p)", img.width, img.height, (void *)img.pixels);
    size_t n = (size_t)img.width * (size_t)img.height * 3, nonfinite = 0;
    int png = strstr(name, ".png") != NULL || strstr(name, ".jpg") != NULL, hdr = strstr(name, ".hdr") != NULL;
    for (size_t i = 0; i < n && !bad; i++) {
        float v = img.pixels[i];
        nonfinite += !isfinite(v);
        /* PNG and JPEG decode 8/16-bit codes with the sRGB curve; RGBE holds non-negative finite values. */
        if (png && !(v >= 0.0f && v <= 1.0f)) bad = broken("PNG/JPEG sample %zu = %g outside [0, 1]", i, v);
        if (hdr && !(v >= 0.0f && isfinite(v))) bad = broken("HDR sample %zu = %g", i, v);
    }
    if (!bad && sss_image_count_nonfinite(&img) != nonfinite) bad = broken("sss_image_count_nonfinite disagrees");
    if (!bad && n <= (size_t)3 << 16) {
        /* The tone map must accept anything a reader returns (NaN maps to 0). */
        uint8_t *rgb = malloc(n);
        if (rgb) {
            sss_image_to_srgb8(&img, 0.0, rgb);
            free(rgb);
        }
    }
    sss_image_free(&img);
    return bad;
}

const char *sss_fuzz_hdr(const uint8_t *data, size_t size) { return fuzz_image(data, size, "fuzz.hdr"); }
const char *sss_fuzz_pfm(const uint8_t *data, size_t size) { return fuzz_image(data, size, "fuzz.pfm"); }
const char *sss_fuzz_exr(const uint8_t *data, size_t size) { return fuzz_image(data, size, "fuzz.exr"); }
const char *sss_fuzz_jpg(const uint8_t *data, size_t size) { return fuzz_image(data, size, "fuzz.jpg"); }
/* A copy of a PNG with every complete chunk's CRC-32 recomputed (PNG specification, Annex D): the
 * reader refuses bad CRCs, and mutations almost always break one, so without the repair the fuzzer
 * would rarely reach the decoder. NULL when out of memory. */
static uint8_t *png_repair_crcs(const uint8_t *data, size_t size)
{
    uint8_t *b = malloc(size ? size : 1);
    if (!b) return NULL;
    memcpy(b, data, size);
    for (size_t at = 8; size >= 8 && at + 12 <= size;) {
        size_t len = (size_t)b[at] << 24 | (size_t)b[at + 1] << 16 | (size_t)b[at + 2] << 8 | b[at + 3];
        if (len > size - at - 12) break;
        uint32_t c = 0xffffffffu;
        for (size_t i = at + 4; i < at + 8 + len; i++) {
            c ^= b[i];
            for (int k = 0; k < 8; k++) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
        }
        c ^= 0xffffffffu;
        for (int i = 0; i < 4; i++) b[at + 8 + len + (size_t)i] = (uint8_t)(c >> (24 - 8 * i));
        at += 12 + len;
    }
    return b;
}

/* The input as it is (CRCs checked), then with repaired CRCs (the decoder behind them). */
const char *sss_fuzz_png(const uint8_t *data, size_t size)
{
    const char *bad = fuzz_image(data, size, "fuzz.png");
    uint8_t *fixed = bad ? NULL : png_repair_crcs(data, size);
    if (fixed) bad = fuzz_image(fixed, size, "fuzz.png");
    free(fixed);
    return bad;
}

/* The folder of the fixture meshes (sss_fuzz_set_fixtures). */
static const char *fixtures_dir = ".";

/* ---- Spatial Adjacency Maps (.sam) ----------------------------------------------------------- */

/* The file ends with an FNV-1a 64 checksum of everything before it, which random mutations almost
 * never keep: the harness recomputes it (independently of sam_io.c) so that the fuzzer reaches the
 * structure behind it. The checksum test itself is in tests/sam. */
static void sam_fix_checksum(uint8_t *data, size_t size)
{
    if (size < 8) return;
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < size - 8; i++) h = (h ^ data[i]) * 0x100000001b3ull;
    for (int k = 0; k < 8; k++) data[size - 8 + (size_t)k] = (uint8_t)(h >> (8 * k));
}

static int sam_is_empty(const sss_sam *s)
{
    return !s->vertex_count && !s->triangle_count && !s->n && !s->fan_area && !s->links && !s->form_factor &&
           !s->kprime && !s->back_vertex_count && !s->back_positions && !s->back_normals && !s->back_uvs &&
           !s->back_fan_area && !s->back_indices;
}

static int finite_nonneg(const float *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]) || v[i] < 0.0f) return 0;
    return 1;
}

static const char *check_sam(const sss_sam *s)
{
    if (s->vertex_count < 1 || s->vertex_count > SSS_MESH_MAX_VERTICES || s->triangle_count < 1 ||
        s->triangle_count > SSS_MESH_MAX_TRIANGLES)
        return broken("map counts %u vertices, %u triangles", s->vertex_count, s->triangle_count);
    if (s->n < 1 || s->n > SSS_SAM_MAX_N) return broken("n = %u", s->n);
    if (!s->fan_area || !s->links || !s->form_factor || !s->kprime) return broken("missing arrays");
    size_t slots = (size_t)s->vertex_count * s->n;
    uint32_t targets = s->back_vertex_count ? s->back_vertex_count : s->vertex_count;
    for (size_t i = 0; i < slots; i++)
        if (s->links[i] != SSS_SAM_NONE && s->links[i] >= targets)
            return broken("link %zu = %u of %u vertices", i, s->links[i], targets);
    if (!finite_nonneg(s->fan_area, s->vertex_count) || !finite_nonneg(s->form_factor, 3 * slots) ||
        !finite_nonneg(s->kprime, 3 * slots))
        return broken("a fan area, form factor or K' is negative or not finite");
    if (s->back_vertex_count) {
        if (!s->back_positions || !s->back_normals || !s->back_fan_area || !s->back_indices || !s->back_triangle_count)
            return broken("back-side mesh arrays missing");
        for (size_t i = 0; i < 3 * (size_t)s->back_triangle_count; i++)
            if (s->back_indices[i] >= s->back_vertex_count) return broken("back-side index %zu out of range", i);
        for (size_t i = 0; i < 3 * (size_t)s->back_vertex_count; i++)
            if (!isfinite(s->back_positions[i]) || !isfinite(s->back_normals[i]))
                return broken("back-side vertex value %zu not finite", i);
        if (!finite_nonneg(s->back_fan_area, s->back_vertex_count)) return broken("back-side fan area");
    }
    return NULL;
}

const char *sss_fuzz_sam(const uint8_t *data, size_t size)
{
    uint8_t *copy = malloc(size ? size : 1);
    if (!copy) return NULL;
    if (size) memcpy(copy, data, size);
    sam_fix_checksum(copy, size);
    sss_sam sam;
    memset(&sam, 0xa5, sizeof sam);
    sss_error err = {0};
    sss_result r = sss_sam_decode(copy, size, "fuzz.sam", &sam, &err);
    free(copy);
    const char *bad = check_error(r, &err, "fuzz.sam");
    if (r != SSS_OK) {
        if (!bad && !sam_is_empty(&sam)) bad = broken("failed (%s) but the map is not empty", err.message);
        return bad;
    }
    bad = check_sam(&sam);
    if (!bad) {
        /* Matching against a mesh must answer, never crash: the fixture tetrahedron, Marble (read
         * once per process, kept for every later input). */
        static int fixture = 0; /* 0 not read yet, 1 ready, -1 unreadable */
        static sss_mesh tetra;
        static sss_material marble;
        sss_error e2 = {0};
        if (fixture == 0) {
            char path[1024];
            snprintf(path, sizeof path, "%s/tetra.ply", fixtures_dir);
            fixture = sss_mesh_read(path, &tetra, &e2) == SSS_OK &&
                              sss_material_from_medium("Marble", 1.0, 1.33, &marble, &e2) == SSS_OK
                          ? 1
                          : -1;
        }
        if (fixture < 0) {
            bad = broken("the fixture tetra.ply or the Marble material is unavailable");
        } else {
            sss_result rc = sss_sam_check(&sam, &tetra, &marble, sam.model, NULL, "fuzz.sam", &e2);
            bad = check_error(rc, &e2, "fuzz.sam");
        }
    }
    sss_sam_free(&sam);
    return bad;
}

/* ---- Scenes ------------------------------------------------------------------------------------ */

void sss_fuzz_set_fixtures(const char *dir) { fixtures_dir = dir; }

/* Full loads are skipped above this many procedural triangles (the limits allow 2^27 per object:
 * a legitimate but slow input, not a bug). */
#define SCENE_TRIANGLE_BUDGET 300000.0

static double procedural_triangles(const sss_procedural *p)
{
    switch (p->shape) {
    case SSS_SHAPE_SPHERE: return 20.0 * pow(4.0, p->subdivisions);
    case SSS_SHAPE_TORUS: return 2.0 * p->segments * (double)p->segments;
    case SSS_SHAPE_TREFOIL: return 2.0 * p->segments * (p->segments / 8 > 3 ? p->segments / 8 : 3);
    default: return 12.0;
    }
}

static int finite_n(const double *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

static int unit3(const double *v)
{
    return finite_n(v, 3) && fabs(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 1.0) < 1e-9;
}

static const char *check_material(const sss_scene *s, const sss_scene_material *m, size_t i)
{
    if (!finite_n(m->albedo, 3)) return broken("objects[%zu]: non-finite albedo", i);
    for (int k = 0; k < 3; k++)
        if (m->albedo[k] < 0 || m->albedo[k] > 1.05) return broken("objects[%zu]: albedo %g", i, m->albedo[k]);
    if (m->type == SSS_SCENE_MATERIAL_DIFFUSE) return NULL;
    if (m->type != SSS_SCENE_MATERIAL_SUBSURFACE) return broken("objects[%zu]: material type %d", i, (int)m->type);
    const sss_material *o = &m->optical;
    for (int k = 0; k < 3; k++)
        if (!isfinite(o->sigma_a[k]) || !isfinite(o->sigma_s[k]) || o->sigma_a[k] < 0 || o->sigma_s[k] < 0 ||
            !(o->sigma_a[k] + o->sigma_s[k] > 0))
            return broken("objects[%zu]: coefficients sigma_a %g sigma_s %g", i, o->sigma_a[k], o->sigma_s[k]);
    if (!(o->eta >= SSS_ETA_MIN && o->eta <= SSS_ETA_MAX) || !(o->g > -1 && o->g < 1))
        return broken("objects[%zu]: eta %g g %g", i, o->eta, o->g);
    if (!m->table || m->table->eta != o->eta || m->table->g != o->g || sss_scene_find_table(s, o->eta, o->g) != m->table)
        return broken("objects[%zu]: PBD table missing or not the one for its eta and g", i);
    return NULL;
}

static const char *check_scene(const sss_scene *s, int meshes, double *triangles)
{
    if (s->object_count < 1 || s->object_count > SSS_SCENE_MAX_OBJECTS || !s->objects)
        return broken("object_count %zu", s->object_count);
    if (s->light_count > SSS_SCENE_MAX_LIGHTS || (s->light_count && !s->lights))
        return broken("light_count %zu", s->light_count);
    const sss_camera *c = &s->camera;
    if (!finite_n(c->position, 3) || !finite_n(c->look_at, 3) || !finite_n(c->up, 3) || !(c->fov >= SSS_SCENE_FOV_MIN && c->fov < 180) ||
        c->width < 1 || c->height < 1 || c->width > SSS_SCENE_MAX_IMAGE_SIZE || c->height > SSS_SCENE_MAX_IMAGE_SIZE)
        return broken("camera out of its documented ranges");
    const sss_camera_basis *b = &s->basis;
    if (!unit3(b->right) || !unit3(b->up) || !unit3(b->forward) || !(b->tan_half[0] > 0 && isfinite(b->tan_half[0])) ||
        !(b->tan_half[1] > 0 && isfinite(b->tan_half[1])))
        return broken("camera basis not orthonormal/finite");
    if (!isfinite(s->render.exposure) || !memchr(s->render.technique, 0, sizeof s->render.technique))
        return broken("render settings");
    *triangles = 0;
    for (size_t i = 0; i < s->object_count; i++) {
        const sss_scene_object *o = &s->objects[i];
        if (!finite_n(o->transform.matrix, 16) || !finite_n(o->transform.normal_matrix, 9))
            return broken("objects[%zu]: non-finite transform", i);
        const char *bad = check_material(s, &o->material, i);
        if (bad) return bad;
        if (o->animation.type != SSS_ANIMATION_NONE && (!isfinite(o->animation.amplitude) || !(o->animation.period > 0)))
            return broken("objects[%zu]: animation", i);
        if (o->procedural.shape != SSS_SHAPE_MESH) {
            *triangles += procedural_triangles(&o->procedural);
        }
        else if (!o->mesh_path) return broken("objects[%zu]: mesh object without a path", i);
        if (!meshes) {
            if (!mesh_is_empty(&o->mesh)) return broken("objects[%zu]: mesh loaded with SKIP_MESHES", i);
            continue;
        }
        char what[64];
        snprintf(what, sizeof what, "objects[%zu].mesh", i);
        if ((bad = check_mesh(&o->mesh, what, o->procedural.shape == SSS_SHAPE_MESH))) return bad;
        float lo[3], hi[3];
        sss_mesh_bounds(&o->mesh, lo, hi);
        if (memcmp(lo, o->bounds_min, sizeof lo) || memcmp(hi, o->bounds_max, sizeof hi))
            return broken("objects[%zu]: bounds differ from the mesh's", i);
        if (o->splat_mesh_path) {
            snprintf(what, sizeof what, "objects[%zu].splat_mesh", i);
            if ((bad = check_mesh(&o->splat_mesh, what, 1))) return bad;
        }
        /* What every renderer does with an object: pose it in the world. */
        sss_mesh world = {0};
        sss_error err = {0};
        sss_result r = sss_scene_object_world_mesh(o, 0.3, &world, &err);
        if (r == SSS_OK) {
            snprintf(what, sizeof what, "objects[%zu] world mesh", i);
            bad = check_mesh(&world, what, 0);
        } else if (!err.message[0]) {
            bad = broken("objects[%zu]: world mesh failed without a message", i);
        }
        sss_mesh_free(&world);
        if (bad) return bad;
    }
    for (size_t i = 0; i < s->light_count; i++) {
        const sss_light *l = &s->lights[i];
        const double *vals[] = {l->position, l->look_at, l->intensity, l->direction, l->radiance, l->center, l->u, l->v, l->scale};
        for (size_t k = 0; k < sizeof vals / sizeof vals[0]; k++)
            if (!finite_n(vals[k], 3)) return broken("lights[%zu]: non-finite values", i);
        if (l->type == SSS_LIGHT_DIRECTIONAL && !unit3(l->direction)) return broken("lights[%zu]: direction not unit", i);
        if (l->type == SSS_LIGHT_ENVIRONMENT && !l->file) return broken("lights[%zu]: environment without a file", i);
    }
    return NULL;
}

static int scene_is_empty(const sss_scene *s)
{
    return !s->name && !s->base_dir && !s->objects && !s->object_count && !s->lights && !s->light_count && !s->tables &&
           !s->table_count;
}

static const char *load_scene(const uint8_t *data, size_t size, unsigned flags, int *ok, double *triangles)
{
    static const char *const name = "fuzz.json";
    sss_scene s;
    memset(&s, 0xa5, sizeof s);
    sss_scene_load_desc desc = {flags};
    sss_error err = {0};
    sss_result r = sss_scene_parse((const char *)data, size, fixtures_dir, name, &desc, &s, &err);
    const char *bad = check_error(r, &err, name);
    *ok = r == SSS_OK;
    if (r != SSS_OK) {
        if (!scene_is_empty(&s)) return bad ? bad : broken("failed (%s) but the scene is not empty", err.message);
        sss_scene_free(&s);
        return bad;
    }
    bad = check_scene(&s, !(flags & SSS_SCENE_SKIP_MESHES), triangles);
    sss_scene_free(&s);
    return bad;
}

const char *sss_fuzz_scene(const uint8_t *data, size_t size)
{
    int ok = 0;
    double triangles = 0;
    /* Validation alone first (fast); then the full load (meshes read from the fixtures, shapes
     * generated) when its size is reasonable. */
    const char *bad = load_scene(data, size, SSS_SCENE_SKIP_MESHES, &ok, &triangles);
    if (bad || !ok || triangles > SCENE_TRIANGLE_BUDGET) return bad;
    return load_scene(data, size, 0, &ok, &triangles);
}

/* Environment-map lights (gl/env_cut.h). Input: width, height (1..64), the light count (1..128), a
 * scale class and one byte per cell choosing its value: mostly zero, small, single spikes and extremes
 * up to the float range (what a map can hold: the loader zeroes NaN, Inf and negatives). The cut must
 * make at most the lights it has room for, each finite with a unit direction, together carrying the
 * map's energy. */
static double env_cell_value(uint8_t b)
{
    if (b < 128) return 0.0;
    if (b < 248) return (b - 127) * 0.01;
    static const double extremes[8] = {1e-30, 1e-6, 1.0, 1e3, 1e6, 1e12, 1e30, 3.4e38};
    return extremes[b - 248];
}

const char *sss_fuzz_env_cut(const uint8_t *data, size_t size)
{
    if (size < 4) return NULL;
    int w = data[0] % 64 + 1, h = data[1] % 64 + 1, max_lights = data[2] % 128 + 1;
    static const double scales[4] = {1.0, 0.0, 1e-30, 1e30};
    double scale[3] = {scales[data[3] % 4], scales[(data[3] >> 2) % 4], scales[(data[3] >> 4) % 4]};
    size_t cells = (size_t)w * h;
    double *map = calloc(cells * 3, sizeof *map), total[3] = {0, 0, 0}, sum[3] = {0, 0, 0};
    gl_env_light *lights = calloc((size_t)max_lights, sizeof *lights);
    const char *bad = NULL;
    if (!map || !lights) bad = broken("env_cut: test harness out of memory");
    for (size_t i = 0; !bad && i < cells; i++)
        for (int k = 0; k < 3; k++) {
            size_t at = 4 + 3 * i + (size_t)k;
            map[3 * i + k] = at < size ? env_cell_value(data[at]) : 0.0;
            total[k] += map[3 * i + k] * scale[k];
        }
    int count = -1;
    sss_error err = {0};
    if (!bad && gl_env_median_cut(map, w, h, scale, data[3] * 7.0, max_lights, lights, &count, &err) != SSS_OK)
        bad = broken("env_cut: %dx%d into %d lights failed: %s", w, h, max_lights, err.message);
    if (!bad && (count < 0 || count > max_lights))
        bad = broken("env_cut: %dx%d map gave %d lights for room of %d", w, h, count, max_lights);
    for (int i = 0; !bad && i < count; i++) {
        const double *d = lights[i].to_light;
        if (!finite_n(d, 3) || fabs(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - 1.0) > 1e-9)
            bad = broken("env_cut: light %d has direction (%g, %g, %g)", i, d[0], d[1], d[2]);
        for (int k = 0; !bad && k < 3; k++) {
            if (!isfinite(lights[i].rgb[k]) || lights[i].rgb[k] < 0.0)
                bad = broken("env_cut: light %d carries %g", i, lights[i].rgb[k]);
            sum[k] += lights[i].rgb[k];
        }
    }
    /* a region whose luminance underflows to 0 gives no light: allow that energy to go */
    for (int k = 0; !bad && k < 3; k++)
        if (fabs(sum[k] - total[k]) > 1e-9 * total[k] + 1e-290)
            bad = broken("env_cut: lights carry %.17g of the map's %.17g (channel %d)", sum[k], total[k], k);
    free(map);
    free(lights);
    return bad;
}

/* ---- glTF import --------------------------------------------------------------------------------- */

/* sss_gltf_parse from memory (external URIs resolve in the fixtures). On success every object mesh is
 * well formed and the scene JSON it becomes loads as a valid scene of our format. */
const char *sss_fuzz_gltf(const uint8_t *data, size_t size)
{
    static const char *const name = "fuzz.glb";
    sss_gltf_scene g;
    memset(&g, 0xa5, sizeof g);
    sss_error err = {0};
    sss_result r = sss_gltf_parse(data, size, fixtures_dir, name, NULL, &g, &err);
    const char *bad = check_error(r, &err, name);
    if (r != SSS_OK) {
        if (g.objects || g.object_count || g.lights || g.light_count || g.images || g.image_count)
            return bad ? bad : broken("failed (%s) but the import is not empty", err.message);
        return bad;
    }
    char what[64], **names = calloc(g.object_count, sizeof *names), *json = NULL;
    for (size_t i = 0; !bad && i < g.object_count; i++) {
        snprintf(what, sizeof what, "gltf objects[%zu]", i);
        bad = check_mesh(&g.objects[i].mesh, what, 1);
        names[i] = "fixture.ply";
    }
    const char **images = calloc(g.image_count ? g.image_count : 1, sizeof *images);
    for (size_t k = 0; !bad && k < g.image_count; k++) {
        if (g.images[k].pixels && sss_image_count_nonfinite(&g.images[k]))
            bad = broken("gltf images[%zu] holds NaN or Inf", k);
        images[k] = "fixture.png";
    }
    if (!bad && sss_gltf_scene_json(&g, (const char *const *)names, images, &json, &err) != SSS_OK)
        bad = broken("scene JSON failed: %s", err.message);
    sss_scene s;
    sss_scene_load_desc desc = {SSS_SCENE_SKIP_MESHES | SSS_SCENE_SKIP_FILE_CHECKS};
    double triangles = 0;
    if (!bad && sss_scene_parse(json, strlen(json), fixtures_dir, "fuzz.json", &desc, &s, &err) != SSS_OK)
        bad = broken("the imported scene does not load: %s", err.message);
    else if (!bad) {
        bad = check_scene(&s, 0, &triangles);
        sss_scene_free(&s);
    }
    free(json);
    free(names);
    free(images);
    sss_gltf_scene_free(&g);
    return bad;
}

const sss_fuzz_target sss_fuzz_targets[] = {
    {"ply", sss_fuzz_ply}, {"obj", sss_fuzz_obj}, {"scene", sss_fuzz_scene}, {"hdr", sss_fuzz_hdr},
    {"pfm", sss_fuzz_pfm}, {"exr", sss_fuzz_exr}, {"png", sss_fuzz_png}, {"sam", sss_fuzz_sam}, {"env_cut", sss_fuzz_env_cut},
    {"gltf", sss_fuzz_gltf}, {"jpg", sss_fuzz_jpg},
};
const size_t sss_fuzz_target_count = sizeof sss_fuzz_targets / sizeof sss_fuzz_targets[0];
