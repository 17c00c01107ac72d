/* tests/view/test_view_compose.c — what the viewer draws into the images it composes, checked pixel by
 * pixel against the geometry it promises: the wipe's divider (white core edged in black, centred on
 * the cut) and each side's label (ink inside a shaded box in its own half, top corners; a label that
 * does not fit its half is shortened or left out), drawn so that the viewer's tone map at the scene's
 * exposure shows them white; the error map's fixed range (one DSSIM value gets one colour at every image
 * size, values above the range the top colour), its ticks (white marks over the rule at even steps of
 * the range) and their values; the window's layout (image + panel = window, the image never below its
 * minimum, no panel when hidden). */
#include <math.h>
#include <string.h>

#include "check.h"
#include "sss/image.h"
#include "view/view_internal.h"

static const float *px(const sss_image *img, int x, int y)
{
    return img->pixels + 3 * ((size_t)y * (size_t)img->width + (size_t)x);
}

static int grey(const sss_image *img, int x, int y, float g)
{
    const float *p = px(img, x, y);
    return p[0] == g && p[1] == g && p[2] == g;
}

/* Pixels of value `ink` (all channels) in [x0, x1) x [y0, y1). */
static int count_ink(const sss_image *img, int x0, int x1, int y0, int y1, float ink)
{
    int n = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) n += grey(img, x, y, ink);
    return n;
}

static void fill(sss_image *img, float g)
{
    for (size_t i = 0; i < 3 * (size_t)img->width * (size_t)img->height; i++) img->pixels[i] = g;
}

static void test_wipe(void)
{
    sss_image left = {0}, right = {0}, out = {0};
    sss_error err = {0};
    const int w = 200, h = 100;
    CHECK(sss_image_create(&left, w, h, &err) == SSS_OK && sss_image_create(&right, w, h, &err) == SSS_OK);
    fill(&left, 0.2f);
    fill(&right, 0.3f);
    const double exposure = 2.0;
    const float white = (float)exp2(-exposure); /* shown as 1 after the tone map at exposure 2 */
    CHECK(view_compose_split(&left, &right, 0.5, "maisch2020", "reference", exposure, &out, &err) == SSS_OK);
    int cut = 100, half = VIEW_DIVIDER_WIDTH / 2;
    for (int y = 0; y < h; y++) {
        CHECK_MSG(grey(&out, cut - half, y, 0.0f) && grey(&out, cut + half - 1, y, 0.0f), "divider edges, row %d", y);
        for (int x = cut - half + 1; x < cut + half - 1; x++) CHECK_MSG(grey(&out, x, y, white), "divider core (%d, %d)", x, y);
    }
    /* the labels: ink in a box in the top corner of each half, nothing of it across the divider */
    float lw = view_text_block_width("maisch2020"), rw = view_text_block_width("reference");
    int box = (int)VIEW_TEXT_BLOCK_HEIGHT + 4;
    int left_ink = count_ink(&out, 4, 4 + (int)lw, 4, box, white);
    int right_ink = count_ink(&out, w - 4 - (int)rw, w - 4, 4, box, white);
    CHECK_MSG(left_ink > 10 * 3 && right_ink > 9 * 3, "label ink: %d left, %d right", left_ink, right_ink);
    CHECK(count_ink(&out, 0, cut - half, 0, h, white) == left_ink); /* all the left half's ink is its label */
    CHECK(count_ink(&out, cut + half, w, 0, h, white) == right_ink);
    CHECK(px(&out, 2, 8)[0] == 0.2f && px(&out, 6, 6)[0] < 0.2f); /* the shade darkens, its margin does not */
    /* below the labels and away from the divider: the two images untouched */
    for (int y = box + 1; y < h; y++)
        for (int x = 0; x < w; x++)
            if (x < cut - half || x >= cut + half) CHECK(grey(&out, x, y, x < cut ? 0.2f : 0.3f));
    /* a half too narrow for 3 characters of its label has none; the other keeps its own */
    CHECK(view_compose_split(&left, &right, 0.1, "maisch2020", "ssss", 0.0, &out, &err) == SSS_OK);
    CHECK(count_ink(&out, 0, 20 - half, 0, h, 1.0f) == 0);
    CHECK(count_ink(&out, 20 + half, w, 0, box, 1.0f) > 4 * 3);
    /* tiny images: the divider only */
    sss_image a = {0}, b = {0};
    CHECK(sss_image_create(&a, 16, 16, &err) == SSS_OK && sss_image_create(&b, 16, 16, &err) == SSS_OK);
    CHECK(view_compose_split(&a, &b, 0.5, "maisch2020", "ssss", 0.0, &out, &err) == SSS_OK);
    CHECK(count_ink(&out, 0, 16, 0, 16, 1.0f) == 2 * 16);
    sss_image_free(&a);
    sss_image_free(&b);
    sss_image_free(&left);
    sss_image_free(&right);
    sss_image_free(&out);
}

/* An error map of w x h whose every pixel has the DSSIM e (all channels). */
static void map_of(sss_image *map, int w, int h, float e)
{
    sss_error err = {0};
    sss_image_free(map);
    CHECK(sss_image_create(map, w, h, &err) == SSS_OK);
    fill(map, e);
}

static void test_error_map_range(void)
{
    sss_image map = {0}, small = {0}, large = {0};
    sss_error err = {0};
    float want[3], top[3];
    view_error_colour(0.05 / 0.2, want);
    view_error_colour(1.0, top);
    /* one DSSIM, one colour: at two sizes, the same range */
    map_of(&map, 64, 64, 0.05f);
    CHECK(view_error_map(&map, 0.2, &small, &err) == SSS_OK);
    map_of(&map, 300, 200, 0.05f);
    CHECK(view_error_map(&map, 0.2, &large, &err) == SSS_OK);
    for (int c = 0; c < 3; c++) { /* float inputs: equal to a few ulps */
        CHECK_NEAR(px(&small, 10, 10)[c], want[c], 1e-6);
        CHECK(px(&large, 150, 50)[c] == px(&small, 10, 10)[c]);
    }
    /* above the range: the top colour */
    map_of(&map, 64, 64, 0.7f);
    CHECK(view_error_map(&map, 0.2, &small, &err) == SSS_OK);
    CHECK(memcmp(px(&small, 10, 10), top, sizeof top) == 0);
    sss_image_free(&map);
    sss_image_free(&small);
    sss_image_free(&large);
}

static void test_error_map_ticks(void)
{
    sss_image map = {0}, out = {0};
    sss_error err = {0};
    const int w = 300, h = 200;
    map_of(&map, w, h, 0.0f);
    CHECK(view_error_map(&map, 0.2, &out, &err) == SSS_OK);
    view_ticks t;
    view_colour_bar_ticks(w, 0.2, 1, &t);
    static const char *const labels[5] = {"0", "0.05", "0.1", "0.15", "0.2 DSSIM"};
    CHECK(t.count == 5);
    for (int k = 0; k < t.count && t.count == 5; k++) {
        CHECK_MSG(strcmp(t.label[k], labels[k]) == 0, "tick %d: '%s'", k, t.label[k]);
        CHECK(t.x[k] == (int)lround(k / 4.0 * (w - 1)));
    }
    int rule = h - VIEW_COLOUR_BAR_HEIGHT - 1;
    /* the marks: white over the rule and VIEW_TICK_HEIGHT rows above it; the rule black elsewhere */
    for (int x = 0; x < w; x++) {
        int tick = 0;
        for (int k = 0; k < t.count; k++) tick |= t.x[k] == x;
        CHECK_MSG(grey(&out, x, rule, tick ? 1.0f : 0.0f), "rule at x %d (tick %d)", x, tick);
        for (int y = rule - VIEW_TICK_HEIGHT; tick && y < rule; y++) CHECK(grey(&out, x, y, 1.0f));
    }
    /* the values: ink in each label's box above its mark; the bar's colours untouched */
    int band = rule - VIEW_TICK_HEIGHT - (int)VIEW_TEXT_BLOCK_HEIGHT;
    for (int k = 0; k < t.count; k++) {
        int x0 = (int)t.label_x[k], x1 = x0 + (int)view_text_block_width(t.label[k]);
        CHECK_MSG(count_ink(&out, x0, x1, band, rule - VIEW_TICK_HEIGHT, 1.0f) >= 3 * (int)strlen(t.label[k]) / 2,
                  "tick %d: no text", k);
    }
    float c[3];
    for (int x = 0; x < w; x += 37) {
        view_error_colour((double)x / (w - 1), c);
        CHECK(memcmp(px(&out, x, h - 1), c, sizeof c) == 0);
    }
    /* narrower bars: fewer ticks, labels never overlapping, the first at 0, the last at the right */
    for (int width = 40; width <= 400; width += 7) {
        view_colour_bar_ticks(width, 0.2, 1, &t);
        CHECK(t.count == 5 || t.count == 3 || t.count == 2);
        CHECK(t.x[0] == 0 && t.x[t.count - 1] == width - 1);
        for (int k = 1; k < t.count && width >= 80; k++)
            CHECK_MSG(t.label_x[k - 1] + view_text_block_width(t.label[k - 1]) <= t.label_x[k], "width %d: overlap", width);
    }
    /* below VIEW_TICK_LABEL_MIN_HEIGHT rows: the marks, no values */
    map_of(&map, w, 64, 0.0f);
    CHECK(view_error_map(&map, 0.2, &out, &err) == SSS_OK);
    rule = 64 - VIEW_COLOUR_BAR_HEIGHT - 1;
    CHECK(count_ink(&out, 0, w, 0, rule - VIEW_TICK_HEIGHT, 1.0f) == 0);
    CHECK(grey(&out, 0, rule, 1.0f) && grey(&out, w - 1, rule, 1.0f));
    sss_image_free(&map);
    sss_image_free(&out);
}

static void test_layout(void)
{
    CHECK(view_dock_width(800, 330.0, 1, VIEW_IMAGE_MIN_WIDTH) == 330);
    CHECK(view_dock_width(800, 330.0, 0, VIEW_IMAGE_MIN_WIDTH) == 0);
    CHECK(view_dock_width(800, 10.0, 1, VIEW_IMAGE_MIN_WIDTH) == VIEW_PANEL_MIN_WIDTH);
    CHECK(view_dock_width(800, NAN, 1, VIEW_IMAGE_MIN_WIDTH) == VIEW_PANEL_MIN_WIDTH);
    CHECK(view_dock_width(300, 330.0, 1, VIEW_IMAGE_MIN_WIDTH) == 300 - VIEW_IMAGE_MIN_WIDTH); /* the image keeps its minimum */
    CHECK(view_dock_width(40 + 330, 330.0, 1, 40) == 330); /* an image asked 40 wide keeps 40, not 64 */
    CHECK(view_dock_width(VIEW_IMAGE_MIN_WIDTH, 330.0, 1, VIEW_IMAGE_MIN_WIDTH) == 0);
    for (int win = 1; win < 2000; win += 13)
        for (double want = 0.0; want < 1500.0; want += 97.0) {
            int d = view_dock_width(win, want, 1, VIEW_IMAGE_MIN_WIDTH);
            CHECK_MSG(d >= 0 && (win - d >= VIEW_IMAGE_MIN_WIDTH || d == 0), "window %d, want %g: panel %d", win, want, d);
        }
}

int main(void)
{
    test_wipe();
    test_error_map_range();
    test_error_map_ticks();
    test_layout();
    return CHECK_DONE();
}
