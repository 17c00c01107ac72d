/* view/script.c — parsing of `sss view --script` files (view/script.h): one panel action per line,
 * words separated by blanks, '#' starts a comment line. Every name is checked here, so a script with a
 * typo fails before a window opens, naming the file and the line. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "sss/gl.h"
#include "sss/material.h"
#include "view/script.h"
#include "view/viewer.h"

#define SCRIPT_MAX_SIZE (1u << 20)
#define SCRIPT_MAX_WORDS 8
#define SCRIPT_MAX_FRAMES 100000

const char *const view_material_fields[VIEW_MATERIAL_FIELD_COUNT] = {"medium", "scale", "eta",     "g",
                                                                    "sigma_a", "sigma_s", "reflectance", "mfp"};

const char *const view_panel_sections[VIEW_PANEL_SECTION_COUNT] = {"Technique", "View",       "Parameters", "Materials",
                                                                   "Lights",    "Frame time", "Keys"};

int view_panel_section_find(const char *s)
{
    for (int i = 0; i < VIEW_PANEL_SECTION_COUNT; i++) {
        const char *n = view_panel_sections[i], *p = s;
        while (*n && *p && (tolower((unsigned char)*n) == tolower((unsigned char)*p) || (*n == ' ' && (*p == '_' || *p == '-'))))
            n++, p++;
        if (!*n && !*p) return i;
    }
    return -1;
}

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static int bad(char *why, size_t cap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, cap, fmt, ap);
    va_end(ap);
    return -1;
}

/* Splits line in place into at most max words; returns the count, or max + 1 when there are more. */
static int split_words(char *line, char **words, int max)
{
    int n = 0;
    for (char *p = line; *p;) {
        while (*p && isspace((unsigned char)*p)) *p++ = '\0';
        if (!*p) break;
        if (n == max) return max + 1;
        words[n++] = p;
        while (*p && !isspace((unsigned char)*p)) p++;
    }
    return n;
}

static int parse_number(const char *s, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno == ERANGE || !isfinite(v)) return 0;
    *out = v;
    return 1;
}

static int parse_index(const char *s, int *out)
{
    double v;
    if (!parse_number(s, &v) || v < 0 || v > 1e6 || v != floor(v)) return 0;
    *out = (int)v;
    return 1;
}

/* words[0..n) as 1 or 3 numbers (a grey or a colour / vector) into c->values. */
static int parse_values(char **words, int n, int allow_one, view_command *c, char *why, size_t cap)
{
    if (n != 3 && !(allow_one && n == 1))
        return bad(why, cap, "%s: expected %s numbers, got %d", c->name, allow_one ? "1 or 3" : "3", n);
    for (int i = 0; i < n; i++)
        if (!parse_number(words[i], &c->values[i])) return bad(why, cap, "%s: '%s' is not a number", c->name, words[i]);
    c->value_count = n;
    return 1;
}

static int param_known(const sss_gl_technique_info *info, const char *name)
{
    int shared_count = 0;
    const sss_gl_param_info *shared = sss_gl_shared_params(&shared_count);
    for (int i = 0; info && i < info->param_count; i++)
        if (strcmp(info->params[i].name, name) == 0) return 1;
    for (int i = 0; i < shared_count; i++)
        if (strcmp(shared[i].name, name) == 0) return 1;
    return 0;
}

/* "tech.param" (checked against that technique) or "param" (any technique or the shared ones). */
static int parse_param(char **w, int n, view_command *c, char *why, size_t cap)
{
    if (n != 3) return bad(why, cap, "param: expected 'param NAME VALUE'");
    if (strlen(w[1]) >= sizeof c->name) return bad(why, cap, "param: name '%.40s...' is too long", w[1]);
    snprintf(c->name, sizeof c->name, "%s", w[1]);
    char *dot = strchr(c->name, '.');
    if (dot) {
        *dot = '\0';
        const sss_gl_technique_info *info = sss_gl_technique_find(c->name);
        if (!info) return bad(why, cap, "param: unknown technique '%s'", c->name);
        if (!param_known(info, dot + 1)) return bad(why, cap, "param: %s has no parameter '%s'", c->name, dot + 1);
        *dot = '.';
    } else {
        int known = param_known(NULL, c->name);
        for (int t = 0; t < sss_gl_technique_count() && !known; t++) known = param_known(sss_gl_technique_at(t), c->name);
        if (!known) return bad(why, cap, "param: no technique has a parameter '%s'", c->name);
    }
    if (!parse_number(w[2], &c->values[0])) return bad(why, cap, "param %s: '%s' is not a number", w[1], w[2]);
    c->value_count = 1;
    return 1;
}

static int parse_material(char **w, int n, view_command *c, char *why, size_t cap)
{
    if (n < 4 || !parse_index(w[1], &c->index))
        return bad(why, cap, "material: expected 'material OBJECT FIELD VALUE...' (OBJECT an index of objects[])");
    int field = -1;
    for (int i = 0; i < VIEW_MATERIAL_FIELD_COUNT; i++)
        if (strcmp(w[2], view_material_fields[i]) == 0) field = i;
    if (field < 0)
        return bad(why, cap, "material: unknown field '%s' (medium, scale, eta, g, sigma_a, sigma_s, reflectance, mfp)",
                   w[2]);
    snprintf(c->name, sizeof c->name, "%s", w[2]);
    if (field == 0) {
        if (n != 4) return bad(why, cap, "material medium: expected one medium name");
        if (!sss_measured_medium_find(w[3])) return bad(why, cap, "material medium: unknown medium '%s'", w[3]);
        snprintf(c->text, sizeof c->text, "%s", sss_measured_medium_find(w[3])->name);
        return 1;
    }
    int colour = field >= 4; /* sigma_a, sigma_s, reflectance: colours; mfp: number or colour */
    return parse_values(w + 3, n - 3, !colour || field == 7, c, why, cap);
}

static int parse_light(char **w, int n, view_command *c, char *why, size_t cap)
{
    if (n < 4 || !parse_index(w[1], &c->index))
        return bad(why, cap, "light: expected 'light LIGHT FIELD VALUE...' (LIGHT an index of lights[])");
    if (strcmp(w[2], "position") && strcmp(w[2], "intensity") && strcmp(w[2], "colour") && strcmp(w[2], "color"))
        return bad(why, cap, "light: unknown field '%s' (position, intensity, colour)", w[2]);
    snprintf(c->name, sizeof c->name, "%s", strcmp(w[2], "color") == 0 ? "colour" : w[2]);
    int one = strcmp(c->name, "intensity") == 0;
    if (parse_values(w + 3, n - 3, one, c, why, cap) < 0) return -1;
    if (one && n - 3 != 1) return bad(why, cap, "light intensity: expected 1 number (the colour is 'colour R G B')");
    return 1;
}

static int parse_switch(char **w, int n, view_command *c, char *why, size_t cap)
{
    if (n != 2 || (strcmp(w[1], "on") && strcmp(w[1], "off"))) return bad(why, cap, "%s: expected 'on' or 'off'", w[0]);
    c->index = strcmp(w[1], "on") == 0;
    snprintf(c->name, sizeof c->name, "%s", w[1]);
    return 1;
}

/* errormap on [RANGE] | off */
static int parse_errormap(char **w, int n, view_command *c, char *why, size_t cap)
{
    if (n == 3 && strcmp(w[1], "on") == 0) {
        if (!parse_number(w[2], &c->values[0]) || !(c->values[0] > 0.0 && c->values[0] <= 1.0))
            return bad(why, cap, "errormap on: range '%s' must be a DSSIM in (0, 1]", w[2]);
        c->index = 1;
        c->value_count = 1;
        return 1;
    }
    if (n != 2) return bad(why, cap, "errormap: expected 'errormap on [RANGE]' or 'errormap off'");
    return parse_switch(w, n, c, why, cap);
}

/* panel on | off | open SECTION | close SECTION | scroll SECTION | width PIXELS */
static int parse_panel(char **w, int n, view_command *c, char *why, size_t cap)
{
    if (n == 2) return parse_switch(w, n, c, why, cap);
    if (n != 3) return bad(why, cap, "panel: expected 'panel on|off', 'panel open|close|scroll SECTION' or 'panel width PIXELS'");
    snprintf(c->name, sizeof c->name, "%s", w[1]);
    if (strcmp(w[1], "width") == 0) {
        if (!parse_index(w[2], &c->index) || c->index < VIEW_PANEL_MIN_WIDTH || c->index > VIEW_PANEL_MAX_WIDTH)
            return bad(why, cap, "panel width: '%s' must be a whole number of pixels in %d..%d", w[2],
                       VIEW_PANEL_MIN_WIDTH, VIEW_PANEL_MAX_WIDTH);
        c->values[0] = c->index;
        c->value_count = 1;
        return 1;
    }
    if (strcmp(w[1], "open") && strcmp(w[1], "close") && strcmp(w[1], "scroll"))
        return bad(why, cap, "panel: unknown action '%s' (on, off, open, close, scroll, width)", w[1]);
    if ((c->index = view_panel_section_find(w[2])) < 0)
        return bad(why, cap, "panel %s: unknown section '%s' (Technique, View, Parameters, Materials, Lights, "
                   "Frame_time, Keys)", w[1], w[2]);
    return 1;
}

static int parse_split(char **w, int n, view_command *c, char *why, size_t cap)
{
    if (n < 2 || n > 3) return bad(why, cap, "split: expected 'split off|reference|TECHNIQUE [POSITION]'");
    if (strcmp(w[1], "off") && strcmp(w[1], "reference") && !sss_gl_technique_find(w[1]))
        return bad(why, cap, "split: '%s' is neither off, reference nor a technique", w[1]);
    snprintf(c->name, sizeof c->name, "%s", w[1]);
    c->values[0] = 0.5;
    if (n == 3 && (!parse_number(w[2], &c->values[0]) || c->values[0] <= 0.0 || c->values[0] >= 1.0))
        return bad(why, cap, "split: position '%s' must be a number in (0, 1)", w[2]);
    c->value_count = 1;
    return 1;
}

static int parse_buffer(char **w, int n, view_command *c, char *why, size_t cap)
{
    if (n != 2) return bad(why, cap, "buffer: expected one name");
    for (int i = 0; i < VIEW_BUFFER_COUNT; i++)
        if (strcmp(w[1], view_buffer_names[i]) == 0) {
            c->index = i;
            snprintf(c->name, sizeof c->name, "%s", w[1]);
            return 1;
        }
    return bad(why, cap, "buffer: unknown buffer '%s' (final, reflected, irradiance, translucency, translucency_full, "
               "screen)", w[1]);
}

static int parse_screenshot(char **w, int n, view_command *c, char *why, size_t cap)
{
    if (n != 2) return bad(why, cap, "screenshot: expected one file name (no blanks)");
    char ext[16];
    sss_path_extension(w[1], ext, sizeof ext);
    if (strcmp(ext, "png") != 0) return bad(why, cap, "screenshot: needs a .png file name, got '%s'", w[1]);
    if (strlen(w[1]) >= sizeof c->text) return bad(why, cap, "screenshot: file name too long");
    snprintf(c->text, sizeof c->text, "%s", w[1]);
    return 1;
}

static int parse_words(char **w, int n, view_command *c, char *why, size_t cap)
{
    const char *verb = w[0];
    if (strcmp(verb, "technique") == 0) {
        c->kind = VIEW_CMD_TECHNIQUE;
        if (n != 2) return bad(why, cap, "technique: expected one name");
        if (!sss_gl_technique_find(w[1])) return bad(why, cap, "technique: unknown technique '%s'", w[1]);
        snprintf(c->name, sizeof c->name, "%s", w[1]);
        return 1;
    }
    if (strcmp(verb, "param") == 0) return c->kind = VIEW_CMD_PARAM, parse_param(w, n, c, why, cap);
    if (strcmp(verb, "material") == 0) return c->kind = VIEW_CMD_MATERIAL, parse_material(w, n, c, why, cap);
    if (strcmp(verb, "light") == 0) return c->kind = VIEW_CMD_LIGHT, parse_light(w, n, c, why, cap);
    if (strcmp(verb, "split") == 0) return c->kind = VIEW_CMD_SPLIT, parse_split(w, n, c, why, cap);
    if (strcmp(verb, "errormap") == 0) return c->kind = VIEW_CMD_ERRORMAP, parse_errormap(w, n, c, why, cap);
    if (strcmp(verb, "panel") == 0) return c->kind = VIEW_CMD_PANEL, parse_panel(w, n, c, why, cap);
    if (strcmp(verb, "buffer") == 0) return c->kind = VIEW_CMD_BUFFER, parse_buffer(w, n, c, why, cap);
    if (strcmp(verb, "reference") == 0) {
        c->kind = VIEW_CMD_REFERENCE;
        if (n > 2 || (n == 2 && strcmp(w[1], "draft"))) return bad(why, cap, "reference: expected 'reference [draft]'");
        c->index = n == 2;
        return 1;
    }
    if (strcmp(verb, "key") == 0) {
        c->kind = VIEW_CMD_KEY;
        if (n != 2 || strlen(w[1]) >= sizeof c->name) return bad(why, cap, "key: expected one input event");
        snprintf(c->name, sizeof c->name, "%s", w[1]);
        return 1; /* the event itself is checked by view_input_event when the viewer starts */
    }
    if (strcmp(verb, "frames") == 0) {
        c->kind = VIEW_CMD_FRAMES;
        if (n != 2 || !parse_index(w[1], &c->index) || c->index < 1 || c->index > SCRIPT_MAX_FRAMES)
            return bad(why, cap, "frames: expected a count in 1..%d", SCRIPT_MAX_FRAMES);
        return 1;
    }
    if (strcmp(verb, "wait") == 0) {
        c->kind = VIEW_CMD_WAIT;
        return n == 1 ? 1 : bad(why, cap, "wait: takes no arguments");
    }
    if (strcmp(verb, "screenshot") == 0) return c->kind = VIEW_CMD_SCREENSHOT, parse_screenshot(w, n, c, why, cap);
    return bad(why, cap,
               "unknown action '%s' (technique, param, material, light, buffer, split, errormap, panel, reference, "
               "key, frames, wait, screenshot)",
               verb);
}

int view_script_parse_line(const char *line, view_command *out, char *why, size_t why_cap)
{
    memset(out, 0, sizeof *out);
    size_t len = strlen(line);
    if (len >= 4 * VIEW_SCRIPT_TEXT) return bad(why, why_cap, "line too long");
    char buf[4 * VIEW_SCRIPT_TEXT];
    memcpy(buf, line, len + 1);
    char *words[SCRIPT_MAX_WORDS];
    int n = split_words(buf, words, SCRIPT_MAX_WORDS);
    if (n == 0 || words[0][0] == '#') return 0;
    if (n > SCRIPT_MAX_WORDS) return bad(why, why_cap, "too many words (at most %d)", SCRIPT_MAX_WORDS);
    return parse_words(words, n, out, why, why_cap);
}

sss_result view_script_load(const char *path, view_script *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    char *text = NULL;
    size_t size = 0;
    sss_result res = sss_read_file(path, SCRIPT_MAX_SIZE, &text, &size, err);
    if (res != SSS_OK) return res;
    if (memchr(text, '\0', size)) {
        free(text);
        return sss_error_set(err, SSS_ERROR_PARSE, "%s: holds a NUL byte (not a text file)", path);
    }
    int lines = 1;
    for (size_t i = 0; i < size; i++) lines += text[i] == '\n';
    out->commands = calloc((size_t)lines, sizeof *out->commands);
    if (!out->commands) res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (script %s)", path);
    char *line = text;
    for (int k = 1; res == SSS_OK && line; k++) {
        char *nl = strchr(line, '\n');
        if (nl) *nl = '\0';
        if (nl && nl > line && nl[-1] == '\r') nl[-1] = '\0';
        char why[512];
        int r = view_script_parse_line(line, &out->commands[out->count], why, sizeof why);
        if (r < 0) res = sss_error_set(err, SSS_ERROR_PARSE, "%s:%d: %s", path, k, why);
        else if (r > 0) out->commands[out->count++].line = k;
        line = nl ? nl + 1 : NULL;
    }
    free(text);
    if (res == SSS_OK && out->count == 0)
        res = sss_error_set(err, SSS_ERROR_PARSE, "%s: no actions (only blank or comment lines)", path);
    if (res != SSS_OK) view_script_free(out);
    return res;
}

void view_script_free(view_script *s)
{
    free(s->commands);
    s->commands = NULL;
    s->count = 0;
}
