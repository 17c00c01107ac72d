/* view/status.c — the overlay's text (technique, part, buffer, frame time, milliseconds per pass,
 * material, light, animation, reference and DSSIM, the last message, the key help), the key help itself
 * (sss_view_help_text, also the panel's and `sss view --help`'s) and the window title (the frame time).
 * It reads the viewer's state and calls nothing above it. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "sss/material.h"
#include "view/viewer.h"

/* The key bindings of input.c (handle_key, on_button, on_scroll): keep the two in step. */
static const char help_text[] =
    "mouse: left drag orbit around look_at, right/middle drag pan, wheel zoom\n"
    "Tab / Shift+Tab   next / previous technique (all registered techniques)\n"
    "1 / 2 / 3         all parts / translucency alone / screen-space part alone\n"
    "B / Shift+B       next / previous intermediate buffer (final, reflected, ...)\n"
    "R / Shift+R       reference of this view in the background (Shift: draft), then DSSIM\n"
    "M / Shift+M       next / previous measured medium for every subsurface material\n"
    "+ / -             scattering scale x2 / /2 (coefficients; mean free path /2 / x2)\n"
    "L / Shift+L       turn the first light +15 / -15 degrees about the vertical through look_at\n"
    "Space             start / stop the animation\n"
    "S or F12          screenshot sss-view-NNNN.png (the image without the overlay)\n"
    "C                 camera back to the scene's\n"
    "O                 panel on / off        H or F1  this help on / off (text overlay)\n"
    "Esc or Q          quit\n";

const char *sss_view_help_text(void) { return help_text; }

typedef struct text_buf {
    char *p;
    size_t cap, len;
} text_buf;

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void put(text_buf *b, const char *fmt, ...)
{
    if (b->len + 1 >= b->cap) return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(b->p + b->len, b->cap - b->len, fmt, ap);
    va_end(ap);
    if (n > 0) b->len += (size_t)n < b->cap - b->len ? (size_t)n : b->cap - b->len - 1;
}

static const char *part_name(int part)
{
    return part == PART_TRANSLUCENCY ? "translucency alone" : part == PART_SCREEN ? "screen-space part alone" : "all";
}

void view_overlay_text(viewer *v, char *buf, size_t cap)
{
    text_buf b = {buf, cap, 0};
    buf[0] = '\0';
    const sss_gl_technique_info *info = sss_gl_technique_at(v->tech);
    const char *shown = v->part_buffer ? v->part_buffer : view_buffer_names[v->buffer];
    put(&b, "%s (%d/%d)   part: %s   buffer: %s   %dx%d\n", info ? info->name : "?", v->tech + 1,
        sss_gl_technique_count(), part_name(v->part), shown, v->width, v->height);
    put(&b, "frame %.1f ms (%.1f fps)", v->frame_ms, v->frame_ms > 0.0 ? 1000.0 / v->frame_ms : 0.0);
    if (v->timings.pass_count > 0)
        put(&b, "   passes %.1f ms (median of %d frames after %d warm-up) [%s]", v->timings.total_ms,
            v->timing_series.timed, v->timing_series.warmup, v->timings.method);
    else if (v->timing_series.added > 0)
        put(&b, "   passes: warming up (%d of %d frames)", v->timing_series.added, v->timing_series.warmup);
    put(&b, "\n");
    for (int i = 0; i < v->timings.pass_count; i++)
        put(&b, "  %-14s %8.2f ms\n", v->timings.passes[i].name, v->timings.passes[i].ms);
    if (v->medium >= 0) put(&b, "material: %s", sss_measured_medium_at((size_t)v->medium)->name);
    else put(&b, "material: the scene's");
    put(&b, ", scale x%g   light: %+.0f deg   animation: %s t = %.2f s\n", v->scale_factor, v->light_angle,
        v->playing ? "playing" : "stopped", v->t);
    if (v->job) {
        double progress = 0.0;
        const char *stage = "";
        view_ref_poll(v->job, &progress, &stage);
        put(&b, "reference: rendering %.0f%% (%s)", 100.0 * progress, stage ? stage : "");
        if (v->ref) put(&b, "   DSSIM %.4f (%s)", v->dssim, v->ref_draft ? "draft" : "final");
        put(&b, "\n");
    } else if (v->ref && v->dssim_gen) {
        put(&b, "DSSIM vs reference: %.4f (%s reference of this view)\n", v->dssim, v->ref_draft ? "draft" : "final");
    } else {
        put(&b, "DSSIM: no reference of this view (R computes one)\n");
    }
    if (view_rebuild_busy(v)) put(&b, "rebuilding the materials in the background (%d frames so far)\n", v->build_frames);
    if (v->message[0] && sss_time_seconds() < v->message_until) put(&b, "%s\n", v->message);
    if (v->help) put(&b, "\n%s", sss_view_help_text());
    else put(&b, "H: keys and mouse");
}

void view_update_title(viewer *v)
{
    double now = sss_time_seconds();
    if (now < v->title_at) return;
    v->title_at = now + 0.5;
    const sss_gl_technique_info *info = sss_gl_technique_at(v->tech);
    char title[512];
    snprintf(title, sizeof title, "sss view: %s [%s] %.1f ms", v->scene->name ? v->scene->name : "scene",
             info ? info->name : "?", v->frame_ms);
    glfwSetWindowTitle(v->window, title);
}
