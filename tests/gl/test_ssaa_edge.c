/* Supersampling antialiasing (sss_gl_renderer_desc.supersample), properties fixed by geometry:
 *  - a flat, uniformly lit Lambertian plane whose straight edge crosses the view at 20.3 degrees from
 *    the vertical (slope and offset chosen so that no render-pixel grid lines up with it), on a black background: with k x k samples per pixel, an edge pixel's value is the
 *    fraction of the pixel the plane covers times the interior value. The fraction is computed here
 *    from the camera's pinhole geometry (docs/scene-format.md: looking down, fov along the shorter axis), not from
 *    the renderer; the interior value must be reflectance / pi x E (E = 1). The rasteriser tests the
 *    k^2 render-pixel centres, so a straight edge puts at most half a sample per row of k samples off
 *    the exact area: |value / interior - fraction| <= 1 / (2k) per pixel (k = 4: 0.125, k = 3: 1/6),
 *    and the mean error over the edge pixels is a fraction of that (bound 1 / (4k)). At k = 1 every
 *    pixel is 0 or the interior value, so the same bound fails there (the test cannot pass without
 *    SSAA);
 *  - the resolve is the k x k box mean: the "supersampled" buffer averaged here equals the read-back;
 *  - supersample 0 is the default (1, identical image); 5 and -1 are errors naming the field; a render
 *    size beyond GL_MAX_TEXTURE_SIZE is an error naming the limit, before any GL allocation;
 *  - sizes: the read-back and "final" at the output size, "supersampled" at k x it, a timed pass
 *    "resolve_ssaa" only with k > 1; sss_gl_renderer_set_supersample and _resize on a live renderer
 *    give the image of a new renderer with those settings. */
#include <unistd.h>

#include "gl_test_util.h"

#define SIZE 48
#define FOV_DEG 30.0
#define REFLECTANCE 0.5

static char obj_path[256];

/* The edge x = EDGE_SLOPE z + EDGE_OFFSET on the plane y = 0 (world units). */
#define EDGE_SLOPE 0.37
#define EDGE_OFFSET 0.0043

/* A triangle in the plane y = 0 whose edge P-Q (z = -0.6 .. 0.6) crosses the whole view; the plane
 * lies to its +x side (counter-clockwise seen from +y). */
static int write_triangle(void)
{
    snprintf(obj_path, sizeof obj_path, "/tmp/sss_test_ssaa_edge_%ld.obj", (long)getpid());
    FILE *f = fopen(obj_path, "w");
    if (!f) return 0;
    fprintf(f, "v %.9g 0 -0.6\nv %.9g 0 0.6\nv 2 0 0\nf 1 2 3\n", -0.6 * EDGE_SLOPE + EDGE_OFFSET,
            0.6 * EDGE_SLOPE + EDGE_OFFSET);
    return fclose(f) == 0;
}

/* Camera 1 unit above the origin looking straight down (image up = -z), directional light straight
 * down with E = 1. */
static int edge_scene(sss_scene *scene)
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 1, 0], \"look_at\": [0, 0, 0], \"up\": [0, 0, -1], \"fov\": %g,"
             " \"width\": %d, \"height\": %d},"
             " \"objects\": [{\"mesh\": \"%s\", \"material\": {\"type\": \"diffuse\", \"reflectance\": [%g, %g, %g]}}],"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0, -1, 0], \"radiance\": [1, 1, 1]}],"
             " \"render\": {\"technique\": \"local\"}}",
             FOV_DEG, SIZE, SIZE, obj_path, REFLECTANCE, REFLECTANCE, REFLECTANCE);
    sss_error err = {0};
    if (sss_scene_parse(json, strlen(json), ".", "ssaa_edge", NULL, scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

/* Fraction of pixel (col, row) (row 0 at the top) the plane covers. The camera's right is +x and its
 * up -z, all of the plane at depth 1: image point (u, v) = (W/2 + x / s, H/2 + z / s), s = tan(fov/2)
 * / (W/2) per pixel; covered where x > EDGE_SLOPE z + EDGE_OFFSET. Midpoint rule over v of the covered
 * length of the row segment (exact per v). */
static double covered(int col, int row)
{
    const int n = 4096;
    const double s = tan(0.5 * FOV_DEG * M_PI / 180.0) / (SIZE / 2.0);
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        double v = row + (i + 0.5) / n;
        double u0 = SIZE / 2.0 + EDGE_SLOPE * (v - SIZE / 2.0) + EDGE_OFFSET / s; /* the edge at this v */
        double len = (col + 1) - (u0 > col ? u0 : col);
        sum += len < 0 ? 0 : len > 1 ? 1 : len;
    }
    return sum / n;
}

typedef struct edge_stats {
    double worst, mean, interior;
    int edge_pixels, binary; /* pixels strictly between 0 and 1 coverage; of them, rendered 0 or interior */
} edge_stats;

static edge_stats edge_errors(const sss_image *im)
{
    edge_stats st = {0};
    double sum_in = 0.0;
    int n_in = 0;
    for (int y = 2; y < SIZE - 2; y++)
        for (int x = 2; x < SIZE - 2; x++)
            if (covered(x, y) == 1.0) {
                sum_in += im->pixels[3 * ((size_t)y * SIZE + x)];
                n_in++;
            }
    st.interior = n_in ? sum_in / n_in : 0.0;
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++) {
            double f = covered(x, y);
            if (f <= 1e-9 || f >= 1.0 - 1e-9) continue;
            double v = im->pixels[3 * ((size_t)y * SIZE + x)] / st.interior;
            double e = fabs(v - f);
            st.edge_pixels++;
            st.mean += e;
            if (e > st.worst) st.worst = e;
            if (fabs(v) < 1e-3 || fabs(v - 1.0) < 1e-3) st.binary++;
        }
    if (st.edge_pixels) st.mean /= st.edge_pixels;
    return st;
}

static void test_edge(const sss_scene *scene)
{
    const double interior = REFLECTANCE / M_PI; /* Lambertian radiance under E = 1 */
    for (int k = 1; k <= 4; k++) {
        if (k == 2) continue;
        sss_image im;
        if (!gt_render_k(scene, "local", 0.0, NULL, 0, k, &im)) {
            CHECK(0);
            continue;
        }
        edge_stats st = edge_errors(&im);
        printf("k = %d: interior %.6f (reflectance / pi %.6f), %d edge pixels, |value / interior - coverage| "
               "worst %.4f mean %.4f (bounds %.4f, %.4f), %d of them 0 or the interior value\n",
               k, st.interior, interior, st.edge_pixels, st.worst, st.mean, 0.5 / k, 0.25 / k, st.binary);
        CHECK_REL(st.interior, interior, 1e-3);
        CHECK(st.edge_pixels >= SIZE); /* the edge crosses every row */
        if (k == 1) {
            CHECK_MSG(st.binary == st.edge_pixels, "k = 1: %d of %d edge pixels are 0 or the interior value",
                      st.binary, st.edge_pixels);
            CHECK_MSG(st.worst > 0.5 / 4, "without SSAA the k = 4 bound should fail (worst %.3f)", st.worst);
        } else {
            CHECK_MSG(st.worst <= 0.5 / k + 1e-3, "k = %d: worst edge pixel off by %.4f", k, st.worst);
            CHECK_MSG(st.mean <= 0.25 / k, "k = %d: mean edge error %.4f", k, st.mean);
        }
        CHECK(sss_image_count_nonfinite(&im) == 0);
        sss_image_free(&im);
    }
}

static int has_pass(const sss_gl_renderer *r, const char *name)
{
    sss_gl_timings t;
    sss_gl_renderer_timings(r, &t);
    for (int i = 0; i < t.pass_count; i++)
        if (strcmp(t.passes[i].name, name) == 0) return 1;
    return 0;
}

static double max_abs_diff(const sss_image *a, const sss_image *b)
{
    if (a->width != b->width || a->height != b->height) return INFINITY;
    double d = 0.0;
    for (size_t i = 0; i < 3 * (size_t)a->width * a->height; i++) d = fmax(d, fabs(a->pixels[i] - b->pixels[i]));
    return d;
}

static sss_gl_renderer *make(const sss_scene *scene, const char *tech, int k, int width, int height, sss_error *err)
{
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = tech;
    d.supersample = k;
    d.width = width;
    d.height = height;
    d.timings = 1;
    sss_gl_renderer *r = NULL;
    if (sss_gl_renderer_create(gt_ctx(), scene, &d, &r, err) != SSS_OK) return NULL;
    return r;
}

static int read_out(sss_gl_renderer *r, sss_image *im)
{
    sss_error err = {0};
    int w, h;
    sss_gl_renderer_size(r, &w, &h);
    memset(im, 0, sizeof *im);
    if (sss_image_create(im, w, h, &err) != SSS_OK || sss_gl_renderer_read(r, im, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

static void test_api(const sss_scene *scene)
{
    sss_error err = {0};
    /* bad factors name the field; nothing is created */
    int bad[2] = {5, -1};
    for (int i = 0; i < 2; i++) {
        memset(&err, 0, sizeof err);
        sss_gl_renderer *r = make(scene, "local", bad[i], 0, 0, &err);
        CHECK(r == NULL && err.code == SSS_ERROR_INVALID_ARGUMENT);
        CHECK_MSG(strstr(err.message, "supersample") != NULL, "message: %s", err.message);
        printf("supersample %d: %s\n", bad[i], err.message);
        sss_gl_renderer_destroy(r);
    }
    /* a render size beyond the texture limit (16384 on llvmpipe; any GL: 5000 x 4 > 16384 would pass
     * only on a GL with larger textures, then the check is skipped) */
    memset(&err, 0, sizeof err);
    sss_gl_renderer *big = make(scene, "local", 4, 5000, 16, &err);
    if (big) {
        printf("this GL renders 20000 pixels wide: limit check skipped\n");
        sss_gl_renderer_destroy(big);
    } else {
        printf("5000 x 16 at supersample 4: %s\n", err.message);
        CHECK(err.code == SSS_ERROR_LIMIT);
        CHECK(strstr(err.message, "supersample") && strstr(err.message, "GL_MAX_TEXTURE_SIZE"));
    }

    /* 0 is the default: the image of k = 1, no resolve pass */
    sss_gl_renderer *r0 = make(scene, "local", 0, 0, 0, &err), *r1 = make(scene, "local", 1, 0, 0, &err);
    sss_gl_renderer *r3 = make(scene, "local", 3, 0, 0, &err);
    CHECK(r0 && r1 && r3);
    if (!r0 || !r1 || !r3) {
        fprintf(stderr, "%s\n", err.message);
        sss_gl_renderer_destroy(r0);
        sss_gl_renderer_destroy(r1);
        sss_gl_renderer_destroy(r3);
        return;
    }
    CHECK(sss_gl_renderer_get_supersample(r0) == 1 && sss_gl_renderer_get_supersample(r3) == 3);
    CHECK(sss_gl_renderer_render(r0, 0.0, &err) == SSS_OK && sss_gl_renderer_render(r1, 0.0, &err) == SSS_OK &&
          sss_gl_renderer_render(r3, 0.0, &err) == SSS_OK);
    sss_image i0, i1, i3, fin, ss;
    CHECK(read_out(r0, &i0) && read_out(r1, &i1) && read_out(r3, &i3));
    CHECK(max_abs_diff(&i0, &i1) == 0.0);
    CHECK(!has_pass(r1, "resolve_ssaa") && has_pass(r3, "resolve_ssaa"));
    int w, h;
    sss_gl_renderer_size(r3, &w, &h);
    CHECK(w == SIZE && h == SIZE);

    /* the resolve is the 3 x 3 box mean of the supersampled image */
    CHECK(sss_gl_renderer_read_buffer(r3, "final", &fin, &err) == SSS_OK);
    CHECK(sss_gl_renderer_read_buffer(r3, "supersampled", &ss, &err) == SSS_OK);
    CHECK(fin.width == SIZE && fin.height == SIZE && ss.width == 3 * SIZE && ss.height == 3 * SIZE);
    CHECK(max_abs_diff(&fin, &i3) == 0.0);
    double worst = 0.0;
    if (ss.width == 3 * SIZE && ss.height == 3 * SIZE)
        for (int y = 0; y < SIZE; y++)
            for (int x = 0; x < SIZE; x++)
                for (int c = 0; c < 3; c++) {
                    double s = 0.0;
                    for (int j = 0; j < 3; j++)
                        for (int i = 0; i < 3; i++) s += ss.pixels[3 * ((size_t)(3 * y + j) * ss.width + 3 * x + i) + c];
                    worst = fmax(worst, fabs(s / 9.0 - i3.pixels[3 * ((size_t)y * SIZE + x) + c]));
                }
    printf("read-back vs the 3 x 3 mean of \"supersampled\": largest difference %.2e\n", worst);
    CHECK(worst < 1e-6);
    sss_gl_stats s1, s3;
    sss_gl_renderer_stats(r1, &s1);
    sss_gl_renderer_stats(r3, &s3);
    printf("per output pixel: %zu bytes at k = 1, %zu at k = 3\n", s1.per_pixel_bytes, s3.per_pixel_bytes);
    CHECK(s3.per_pixel_bytes >= 9 * s1.per_pixel_bytes);

    /* a live renderer switched to k = 3 (and back) renders what new renderers do */
    CHECK(sss_gl_renderer_set_supersample(r1, 3, &err) == SSS_OK && sss_gl_renderer_render(r1, 0.0, &err) == SSS_OK);
    sss_image sw;
    CHECK(read_out(r1, &sw));
    CHECK(max_abs_diff(&sw, &i3) == 0.0);
    sss_image_free(&sw);
    CHECK(sss_gl_renderer_set_supersample(r1, 7, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_gl_renderer_get_supersample(r1) == 3);
    CHECK(sss_gl_renderer_set_supersample(r1, 0, &err) == SSS_OK && sss_gl_renderer_render(r1, 0.0, &err) == SSS_OK);
    CHECK(read_out(r1, &sw));
    CHECK(max_abs_diff(&sw, &i1) == 0.0);
    sss_image_free(&sw);
    /* resize keeps the factor: output 32 x 24 */
    CHECK(sss_gl_renderer_resize(r3, 32, 24, &err) == SSS_OK && sss_gl_renderer_render(r3, 0.0, &err) == SSS_OK);
    sss_gl_renderer *r3s = make(scene, "local", 3, 32, 24, &err);
    CHECK(r3s && sss_gl_renderer_render(r3s, 0.0, &err) == SSS_OK);
    sss_image a, b;
    CHECK(read_out(r3, &a) && read_out(r3s, &b));
    CHECK(a.width == 32 && a.height == 24 && max_abs_diff(&a, &b) == 0.0);
    sss_image_free(&a);
    sss_image_free(&b);
    sss_gl_renderer_destroy(r3s);

    sss_image_free(&i0);
    sss_image_free(&i1);
    sss_image_free(&i3);
    sss_image_free(&fin);
    sss_image_free(&ss);
    sss_gl_renderer_destroy(r0);
    sss_gl_renderer_destroy(r1);
    sss_gl_renderer_destroy(r3);
}

int main(void)
{
    sss_scene scene;
    if (!write_triangle() || !edge_scene(&scene)) {
        CHECK(0);
        return CHECK_DONE();
    }
    test_edge(&scene);
    test_api(&scene);
    sss_scene_free(&scene);
    unlink(obj_path);
    return CHECK_DONE();
}
