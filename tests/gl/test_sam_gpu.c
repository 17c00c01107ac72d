/* The GPU passes of "sam" against the C reference of the SAM module, on the twisting bunny
 * (scenes/gl_twist.json) rendered at the twist's peak (t = 1): deformed world positions (the scene
 * module's animation), fan areas (Eq. 16), the link update of section 3.4 (sss_sam_update), and the
 * per-vertex translucency of Eq. 12 with Eq. 15's approximate form factors (sss_sam_approximate times
 * the GPU's own L_d). The same with a lower-tessellation back-side mesh (Maisch & Ropinski 2017, 4.4) given in object
 * space through a .sam file: its vertices are posed as the scene module poses that mesh (so the GPU's
 * return from the file's scene units to object space is exact), its fan areas, the link update over its
 * adjacency (sss_sam_update_back) and Eq. 12 gathering L_d from it. Also: a static object's links are
 * the map's, unchanged by rendering. */
#include <unistd.h>

#include "gl_test_util.h"
#include "gl/gl_test.h"
#include "gl/techniques/sam/tech_sam.h"
#include "sss/sam.h"

static void *read_buffer(GLuint b, size_t bytes)
{
    void *p = malloc(bytes);
    if (p) glGetNamedBufferSubData(b, 0, (GLsizeiptr)bytes, p);
    return p;
}

/* Per receiver vertex: its GPU position vs the posed mesh (within 1e-5 of the extent), its GPU links vs
 * the C update's, and where the links agree its GPU translucency vs Eq. 12 evaluated here with the
 * GPU's L_d of the linked (back-side) vertices: sum_k L_d(b_k) K'_k F'_k R_d(|v_k - v_o|). */
typedef struct receiver_counts {
    int pos_ok, link_same, trans_ok, compared;
} receiver_counts;

static receiver_counts compare_receivers(uint32_t V, uint32_t n, const float *geom, const sss_mesh *world, double extent,
                                         const uint32_t *links, const sss_sam *sam, const float *ld, const float *approx,
                                         const float *trans)
{
    receiver_counts c = {0, 0, 0, 0};
    for (uint32_t v = 0; v < V; v++) {
        double dp = 0.0;
        for (int k = 0; k < 3; k++) dp = fmax(dp, fabs(geom[8 * v + k] - world->positions[3 * v + k]));
        c.pos_ok += dp <= 1e-5 * extent;
        int same = 1;
        for (uint32_t k = 0; k < n; k++) same &= links[v * n + k] == sam->links[v * n + k];
        c.link_same += same;
        if (!same) continue;
        double t[3] = {0, 0, 0};
        for (uint32_t k = 0; k < n; k++) {
            uint32_t b = sam->links[v * n + k];
            if (b == SSS_SAM_NONE) continue;
            for (int ch = 0; ch < 3; ch++) t[ch] += ld[4 * b + ch] * approx[3 * (v * n + k) + ch];
        }
        c.compared++;
        int good = 1;
        for (int ch = 0; ch < 3; ch++) good &= fabs(trans[4 * v + ch] - t[ch]) <= 2e-3 * fabs(t[ch]) + 1e-9;
        c.trans_ok += good;
    }
    return c;
}

static void test_twist(void)
{
    sss_scene scene;
    if (!gt_load("gl_twist.json", &scene)) {
        CHECK(0);
        return;
    }
    sss_gl_param_value params[3] = {{"surface", 0}, {"samples", 16}, {"n", 4}};
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = "sam";
    d.params = params;
    d.param_count = 3;
    sss_gl_renderer *r = NULL;
    sss_error err = {0};
    if (sss_gl_renderer_create(gt_ctx(), &scene, &d, &r, &err) != SSS_OK || sss_gl_renderer_render(r, 1.0, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        CHECK(0);
        sss_gl_renderer_destroy(r);
        sss_scene_free(&scene);
        return;
    }
    sam_state *st = gl_test_renderer_state(r);
    CHECK(st->count == 1);
    const sam_object *o = &st->objs[0];
    uint32_t V = o->vertices, n = o->n;
    float *geom = read_buffer(o->geom, sizeof(float) * 8 * V);
    uint32_t *links = read_buffer(o->links, sizeof(uint32_t) * V * n);
    float *ld = read_buffer(o->ld, sizeof(float) * 4 * V), *trans = read_buffer(o->trans, sizeof(float) * 4 * V);

    /* the same map on the CPU (deterministic), the deformed world mesh, one update step */
    sss_sam_desc bd;
    memset(&bd, 0, sizeof bd);
    bd.n = n;
    bd.samples = 16;
    sss_sam sam;
    CHECK(sss_sam_build_object(&scene, 0, &bd, &sam, NULL, &err) == SSS_OK);
    sss_mesh world;
    CHECK(sss_scene_object_world_mesh(&scene.objects[0], 1.0, &world, &err) == SSS_OK);
    sss_profile prof;
    sss_sam_profile_table table;
    CHECK(sss_sam_object_profile(&scene.objects[0], &prof, &err) == SSS_OK);
    CHECK(sss_sam_profile_table_build(&prof, sam.energy, 0, &table, &err) == SSS_OK);
    sss_mesh_adjacency adj;
    CHECK(sss_mesh_adjacency_build(&world, &adj, &err) == SSS_OK);
    float *area = malloc(sizeof(float) * V), *approx = malloc(sizeof(float) * 3 * V * n);
    sss_sam_update(&sam, &world, &adj, &table, area);
    sss_sam_approximate(&sam, &world, area, &table, approx);

    double extent = 0.0;
    for (uint32_t i = 0; i < 3 * V; i++) extent = fmax(extent, fabs(world.positions[i]));
    int area_ok = 0;
    for (uint32_t v = 0; v < V; v++) area_ok += fabs(geom[8 * v + 3] - area[v]) <= 1e-3 * area[v] + 1e-12;
    receiver_counts rc = compare_receivers(V, n, geom, &world, extent, links, &sam, ld, approx, trans);
    int pos_ok = rc.pos_ok, link_same = rc.link_same, trans_ok = rc.trans_ok, compared = rc.compared;
    printf("twist t = 1: positions %d/%u, fan areas %d/%u, links equal to sss_sam_update %d/%u, translucency %d/%d\n",
           pos_ok, V, area_ok, V, link_same, V, trans_ok, compared);
    CHECK(pos_ok == (int)V);
    CHECK(area_ok == (int)V);
    /* float against double near ties of the update's scores: allow 1% */
    CHECK(link_same >= (int)(0.99 * V));
    CHECK(trans_ok >= (int)(0.99 * compared));
    free(area);
    free(approx);
    free(geom);
    free(links);
    free(ld);
    free(trans);
    sss_mesh_adjacency_free(&adj);
    sss_sam_profile_table_free(&table);
    sss_mesh_free(&world);
    sss_sam_free(&sam);
    sss_gl_renderer_destroy(r);
    sss_scene_free(&scene);
}

/* The bunny's twist with the back side on its own simplification to 800 triangles (object space). */
static void test_twist_back(void)
{
    sss_scene scene;
    if (!gt_load("gl_twist.json", &scene)) {
        CHECK(0);
        return;
    }
    sss_error err = {0};
    const sss_scene_object *obj = &scene.objects[0];
    sss_mesh coarse;
    CHECK(sss_mesh_simplify(&obj->mesh, 800, &coarse, &err) == SSS_OK);
    sss_sam_desc bd;
    memset(&bd, 0, sizeof bd);
    bd.n = 4;
    bd.samples = 16;
    bd.backside = &coarse;
    sss_sam sam;
    CHECK(sss_sam_build_object(&scene, 0, &bd, &sam, NULL, &err) == SSS_OK);
    char dir[] = "/tmp/sss_sam_gpuXXXXXX", path[256];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/bunny.sam", dir);
    CHECK(sss_sam_write(path, &sam, &err) == SSS_OK);
    sss_gl_param_value params[1] = {{"surface", 0}};
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = "sam";
    d.params = params;
    d.param_count = 1;
    d.data_file = path;
    sss_gl_renderer *r = NULL;
    if (sss_gl_renderer_create(gt_ctx(), &scene, &d, &r, &err) != SSS_OK || sss_gl_renderer_render(r, 1.0, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        CHECK(0);
    } else {
        sam_state *st = gl_test_renderer_state(r);
        const sam_object *o = &st->objs[0];
        uint32_t V = o->vertices, n = o->n, B = o->back_vertices;
        CHECK(o->from_file && o->has_back && B == coarse.vertex_count && V == obj->mesh.vertex_count);
        float *bgeom = read_buffer(o->back_geom, sizeof(float) * 8 * B), *geom = read_buffer(o->geom, sizeof(float) * 8 * V);
        uint32_t *links = read_buffer(o->links, sizeof(uint32_t) * V * n);
        float *ld = read_buffer(o->ld, sizeof(float) * 4 * B), *trans = read_buffer(o->trans, sizeof(float) * 4 * V);
        /* the C reference: both meshes posed at t = 1 by the scene module, one update step */
        sss_mesh world, bworld;
        CHECK(sss_scene_object_world_mesh(obj, 1.0, &world, &err) == SSS_OK);
        CHECK(sss_scene_object_pose_mesh(obj, &coarse, 1.0, &bworld, &err) == SSS_OK);
        sss_profile prof;
        sss_sam_profile_table table;
        CHECK(sss_sam_object_profile(obj, &prof, &err) == SSS_OK);
        CHECK(sss_sam_profile_table_build(&prof, sam.energy, 0, &table, &err) == SSS_OK);
        sss_mesh_adjacency adj;
        CHECK(sss_mesh_adjacency_build(&bworld, &adj, &err) == SSS_OK);
        float *area = malloc(sizeof(float) * B), *approx = malloc(sizeof(float) * 3 * V * n);
        sss_sam_update_back(&sam, &world, &bworld, &adj, &table, area);
        sss_sam_approximate_back(&sam, &world, &bworld, area, &table, approx);
        double extent = 0.0;
        for (uint32_t i = 0; i < 3 * V; i++) extent = fmax(extent, fabs(world.positions[i]));
        int pos_ok = 0, bpos_ok = 0, bnrm_ok = 0, area_ok = 0, link_same = 0, trans_ok = 0, compared = 0, lit = 0;
        for (uint32_t v = 0; v < B; v++) {
            double dp = 0.0, dn = 0.0;
            for (int k = 0; k < 3; k++) {
                dp = fmax(dp, fabs(bgeom[8 * v + k] - bworld.positions[3 * v + k]));
                dn = fmax(dn, fabs(bgeom[8 * v + 4 + k] - bworld.normals[3 * v + k]));
            }
            bpos_ok += dp <= 1e-5 * extent;
            bnrm_ok += dn <= 1e-4;
            area_ok += fabs(bgeom[8 * v + 3] - area[v]) <= 1e-3 * area[v] + 1e-12;
            lit += isfinite(ld[4 * v]) && ld[4 * v] > 0.0f;
        }
        receiver_counts rc = compare_receivers(V, n, geom, &world, extent, links, &sam, ld, approx, trans);
        pos_ok = rc.pos_ok;
        link_same = rc.link_same;
        trans_ok = rc.trans_ok;
        compared = rc.compared;
        printf("twist t = 1, back side %u vertices: positions %d/%u, back-side positions %d/%u, normals %d/%u, fan "
               "areas %d/%u, lit %d, links equal to sss_sam_update_back %d/%u, translucency %d/%d\n",
               B, pos_ok, V, bpos_ok, B, bnrm_ok, B, area_ok, B, lit, link_same, V, trans_ok, compared);
        CHECK(pos_ok == (int)V);
        CHECK(bpos_ok == (int)B && bnrm_ok == (int)B);
        CHECK(area_ok == (int)B);
        CHECK(lit > (int)B / 10); /* the light reaches part of the back-side mesh */
        CHECK(link_same >= (int)(0.99 * V));
        CHECK(trans_ok >= (int)(0.99 * compared));
        free(area);
        free(approx);
        free(bgeom);
        free(geom);
        free(links);
        free(ld);
        free(trans);
        sss_mesh_adjacency_free(&adj);
        sss_sam_profile_table_free(&table);
        sss_mesh_free(&world);
        sss_mesh_free(&bworld);
    }
    sss_gl_renderer_destroy(r);
    unlink(path);
    rmdir(dir);
    sss_sam_free(&sam);
    sss_mesh_free(&coarse);
    sss_scene_free(&scene);
}

static void test_static(void)
{
    sss_scene scene;
    char path[1024];
    snprintf(path, sizeof path, "%s/gl/sam_backlit.json", SSS_TEST_DATA);
    sss_error err = {0};
    if (sss_scene_load(path, NULL, &scene, &err) != SSS_OK) {
        CHECK(0);
        return;
    }
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = "sam";
    sss_gl_renderer *r = NULL;
    CHECK(sss_gl_renderer_create(gt_ctx(), &scene, &d, &r, &err) == SSS_OK);
    for (int f = 0; r && f < 3; f++) CHECK(sss_gl_renderer_render(r, 0.1 * f, &err) == SSS_OK);
    if (r) {
        sam_state *st = gl_test_renderer_state(r);
        const sam_object *o = &st->objs[0];
        uint32_t *links = read_buffer(o->links, sizeof(uint32_t) * o->vertices * o->n);
        sss_sam sam;
        sss_sam_desc bd;
        memset(&bd, 0, sizeof bd);
        CHECK(sss_sam_build_object(&scene, 0, &bd, &sam, NULL, &err) == SSS_OK);
        CHECK(memcmp(links, sam.links, sizeof(uint32_t) * o->vertices * o->n) == 0);
        CHECK(!o->deforming);
        free(links);
        sss_sam_free(&sam);
        sss_gl_stats stats;
        sss_gl_renderer_stats(r, &stats);
        CHECK(stats.buffer_bytes > o->bytes);
    }
    sss_gl_renderer_destroy(r);
    sss_scene_free(&scene);
}

int main(void)
{
    test_twist();
    test_twist_back();
    test_static();
    return CHECK_DONE();
}
