/* tests/view/test_view_text.c — overlay text geometry: every glyph quad lies inside the block's
 * background, the block grows by one 12-pixel line per newline and by the font's advance per
 * character (stb_easy_font's own width function is the independent measure), scaling scales all of it,
 * and bytes outside printable ASCII neither crash nor draw outside. */
#include <string.h>

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wshadow"
#endif
#include <stb/stb_easy_font.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include "check.h"
#include "view/view_internal.h"

/* The background quad (the first) and whether all others are inside it. */
static int inside(const view_text *t, int first)
{
    const view_text_vertex *bg = &t->vertices[4 * first];
    float x0 = bg[0].x, y0 = bg[0].y, x1 = bg[2].x, y1 = bg[2].y;
    for (int q = first + 1; q < t->quads; q++)
        for (int j = 0; j < 4; j++) {
            const view_text_vertex *p = &t->vertices[4 * q + j];
            if (p->x < x0 || p->x > x1 || p->y < y0 || p->y > y1) return 0;
        }
    return 1;
}

int main(void)
{
    view_text t = {0};
    sss_error err = {0};
    char line[] = "maisch2020 (1/2)   frame 12.5 ms";
    CHECK(view_text_build(&t, line, 10.0f, 20.0f, 1.0f, &err) == SSS_OK);
    CHECK(t.quads > (int)strlen(line)); /* the background + several bars per glyph */
    CHECK(inside(&t, 0));
    const view_text_vertex *bg = t.vertices;
    CHECK_NEAR(bg[0].x, 10.0, 0.0);
    CHECK_NEAR(bg[0].y, 20.0, 0.0);
    CHECK_NEAR(bg[2].x - bg[0].x, stb_easy_font_width(line) + 8.0, 1e-6); /* 4 pixels of padding each side */
    CHECK_NEAR(bg[2].y - bg[0].y, 12.0 + 8.0, 1e-6);
    CHECK(bg[0].rgba[3] < 255 && bg[0].rgba[0] == 0); /* translucent dark shade */
    CHECK(t.vertices[4].rgba[3] == 255);            /* opaque ink */
    int one_line = t.quads;
    view_text_free(&t);

    /* three lines: three times the height; scale 2 doubles every extent */
    CHECK(view_text_build(&t, "abc\ndef\nghi", 0.0f, 0.0f, 2.0f, &err) == SSS_OK);
    CHECK_NEAR(t.vertices[2].y - t.vertices[0].y, 2.0 * (36.0 + 8.0), 1e-6);
    CHECK(inside(&t, 0));
    /* appending a second block keeps the first and adds its own background */
    int before = t.quads;
    CHECK(view_text_build(&t, line, 0.0f, 100.0f, 1.0f, &err) == SSS_OK);
    CHECK(t.quads == before + one_line);
    CHECK(inside(&t, before));
    view_text_free(&t);
    CHECK(t.vertices == NULL && t.quads == 0);

    /* control characters and bytes >= 127 are drawn as '?', inside the box */
    const char odd[] = {'a', '\t', (char)0xff, (char)0x7f, 'b', '\0'};
    CHECK(view_text_build(&t, odd, 0.0f, 0.0f, 1.0f, &err) == SSS_OK);
    CHECK(inside(&t, 0));
    view_text_free(&t);
    CHECK(view_text_build(&t, "", 0.0f, 0.0f, 1.0f, &err) == SSS_OK);
    CHECK(t.quads == 1); /* only the background */
    view_text_free(&t);
    return CHECK_DONE();
}
