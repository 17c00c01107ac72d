/* GPU memory accounting (src/gl/core/gpu_memory.c: counted where the GL allocates and frees storage, the
 * size read back from the GL) against independent computations from the declared render targets:
 *  - ssss (Jimenez et al. 2015, two 1D passes): its own screen-sized targets are three RGBA32F
 *    textures (the prepared signal, the horizontal pass, the sum; tech_ssss.c make_targets), so from
 *    W1 x H1 to W2 x H2 its bytes grow by 3 x 16 x (W2 H2 - W1 H1); its kernel block and T(s) table do
 *    not depend on the size and cancel;
 *  - the shared frame targets (frame.c gl_frame_create): position and irradiance RGBA32F with full
 *    mip chains (halving down to 1 x 1), normal and linear result RGBA32F, albedo and reflected light
 *    RGBA16F, depth DEPTH_COMPONENT32F, one level each; with supersampling k they are k W x k H and the
 *    output image adds an RGBA32F W x H target (ssaa.c);
 *  - nothing leaks: after a renderer of every technique is destroyed the thread's count is back where
 *    it was, and a frame rendered in between changes nothing for ssss (it allocates at creation only). */
#include "gl_test_util.h"

static const char *SCENE =
    "{\"camera\": {\"position\": [0, 0, 4], \"look_at\": [0, 0, 0], \"fov\": 40, \"width\": 64, \"height\": 48},"
    " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1.0},"
    "   \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin1\", \"scale\": 10.0, \"eta\": 1.33}}],"
    " \"lights\": [{\"type\": \"point\", \"position\": [2, 2, 4], \"intensity\": [20, 20, 20]}]}";

/* Texels of a full mip chain of w x h (each level halves, rounding down, to at least 1). */
static size_t chain_texels(size_t w, size_t h)
{
    size_t n = w * h;
    while (w > 1 || h > 1) {
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
        n += w * h;
    }
    return n;
}

/* The shared targets of a w x h frame without normal mips (ssss asks for none). */
static size_t frame_bytes(size_t w, size_t h)
{
    size_t one = w * h;
    return 16 * chain_texels(w, h) * 2 /* pos, irr */ + 16 * one /* nrm */ + 8 * one /* albedo */ +
           4 * one /* depth */ + 8 * one /* refl */ + 16 * one /* final */;
}

static sss_gl_renderer *create(const sss_scene *scene, const char *technique, int w, int h, int k)
{
    sss_gl_renderer_desc d = gt_desc(technique, NULL, 0, k);
    d.width = w;
    d.height = h;
    sss_gl_renderer *r = NULL;
    sss_error err = {0};
    if (sss_gl_renderer_create(gt_ctx(), scene, &d, &r, &err) != SSS_OK)
        fprintf(stderr, "%s at %dx%d: %s\n", technique, w, h, err.message);
    return r;
}

static void check_ssss_sizes(const sss_scene *scene)
{
    size_t base = sss_gl_allocated_bytes(), tech1 = 0, frame1 = 0, tech2 = 0, frame2 = 0, tech3 = 0;
    sss_gl_renderer *r = create(scene, "ssss", 64, 48, 0);
    CHECK(r != NULL);
    if (!r) return;
    sss_gl_renderer_gpu_memory(r, &tech1, &frame1);
    CHECK_MSG(frame1 == frame_bytes(64, 48), "frame %zu, expected %zu", frame1, frame_bytes(64, 48));
    sss_error err = {0};
    CHECK(sss_gl_renderer_resize(r, 96, 80, &err) == SSS_OK);
    sss_gl_renderer_gpu_memory(r, &tech2, &frame2);
    CHECK_MSG(frame2 == frame_bytes(96, 80), "frame %zu, expected %zu", frame2, frame_bytes(96, 80));
    CHECK_MSG(tech2 - tech1 == 3u * 16u * (96u * 80u - 64u * 48u), "ssss grew by %zu bytes, expected %u", tech2 - tech1,
              3u * 16u * (96u * 80u - 64u * 48u));
    CHECK(tech1 > 3u * 16u * 64u * 48u); /* plus the kernel block and T(s) table */
    CHECK(sss_gl_renderer_render(r, 0.0, &err) == SSS_OK);
    sss_gl_renderer_gpu_memory(r, &tech3, NULL);
    CHECK(tech3 == tech2);
    /* the scene's meshes, records, LUTs and shadow maps come on top of both */
    CHECK(sss_gl_allocated_bytes() - base > tech2 + frame2);
    sss_gl_renderer_destroy(r);
    CHECK_MSG(sss_gl_allocated_bytes() == base, "%zu bytes left after destroy", sss_gl_allocated_bytes() - base);
}

static void check_supersampled_frame(const sss_scene *scene)
{
    size_t frame = 0;
    sss_gl_renderer *r = create(scene, "ssss", 32, 24, 2);
    CHECK(r != NULL);
    if (!r) return;
    sss_gl_renderer_gpu_memory(r, NULL, &frame);
    CHECK_MSG(frame == frame_bytes(64, 48) + 16u * 32u * 24u, "frame %zu, expected %zu", frame,
              frame_bytes(64, 48) + 16u * 32u * 24u);
    sss_gl_renderer_destroy(r);
}

static void check_no_leaks(const sss_scene *scene)
{
    size_t base = sss_gl_allocated_bytes();
    for (int i = 0; i < sss_gl_technique_count(); i++) {
        const char *name = sss_gl_technique_at(i)->name;
        sss_gl_renderer *r = create(scene, name, 48, 32, 0);
        CHECK_MSG(r != NULL, "%s", name);
        sss_error err = {0};
        if (r) CHECK(sss_gl_renderer_resize(r, 40, 40, &err) == SSS_OK);
        sss_gl_renderer_destroy(r);
        CHECK_MSG(sss_gl_allocated_bytes() == base, "%s: %zu bytes left after destroy", name,
                  sss_gl_allocated_bytes() - base);
    }
}

int main(void)
{
    sss_scene scene;
    sss_error err = {0};
    if (sss_scene_parse(SCENE, strlen(SCENE), ".", "gpu_memory", NULL, &scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    gt_ctx();
    check_ssss_sizes(&scene);
    check_supersampled_frame(&scene);
    check_no_leaks(&scene);
    /* llvmpipe offers no GL_NVX_gpu_memory_info: the query says so instead of inventing numbers */
    size_t total = 1, available = 1;
    sss_gl_context_info info;
    sss_gl_context_get_info(gt_ctx(), &info);
    if (info.software)
        CHECK(sss_gl_context_video_memory(gt_ctx(), &total, &available) == 0 && total == 0 && available == 0);
    sss_scene_free(&scene);
    sss_gl_context_destroy(gt_ctx());
    return CHECK_DONE();
}
