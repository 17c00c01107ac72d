/* eval/eval_util.c — technique specs, size lists, reference file names, results bookkeeping. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sys/stat.h>

#include "core/file_util.h"
#include "core/text.h"
#include "eval/eval_internal.h"

const char *sss_eval_kind_name(sss_eval_kind kind)
{
    switch (kind) {
    case SSS_EVAL_QUALITY: return "quality";
    case SSS_EVAL_TIMING: return "timing";
    case SSS_EVAL_SAM_SWEEP: return "sam_sweep";
    }
    return "?";
}

static int valid_name_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
           c == '.';
}

sss_result eval_parse_spec(const char *text, eval_spec *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    if (!text || !text[0]) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "empty technique spec");
    const char *p = text;
    size_t n = strcspn(p, ":");
    if (n == 0 || n >= sizeof out->name)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "technique spec '%s': bad technique name", text);
    for (size_t i = 0; i < n; i++)
        if (!valid_name_char(p[i]))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "technique spec '%s': bad character '%c' in the name",
                                 text, p[i]);
    memcpy(out->name, p, n);
    p += n;
    while (*p == ':') {
        p++;
        size_t len = strcspn(p, ":");
        const char *eq = memchr(p, '=', len);
        if (!eq || eq == p)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "technique spec '%s': expected name:param=value[:param=value...]", text);
        if (out->param_count >= EVAL_MAX_SPEC_PARAMS)
            return sss_error_set(err, SSS_ERROR_LIMIT, "technique spec '%s': more than %d parameters", text,
                                 EVAL_MAX_SPEC_PARAMS);
        size_t klen = (size_t)(eq - p);
        if (klen >= sizeof out->names[0])
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "technique spec '%s': parameter name too long", text);
        char value[64];
        size_t vlen = len - klen - 1;
        if (vlen == 0 || vlen >= sizeof value)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "technique spec '%s': bad value", text);
        memcpy(value, eq + 1, vlen);
        value[vlen] = '\0';
        memcpy(out->names[out->param_count], p, klen);
        out->names[out->param_count][klen] = '\0';
        double v = 0.0;
        sss_error perr = {0};
        if (sss_gl_param_parse(out->names[out->param_count], value, &v, &perr) != SSS_OK)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "technique spec '%s': %s", text, perr.message);
        out->params[out->param_count].name = out->names[out->param_count];
        out->params[out->param_count].value = v;
        out->param_count++;
        p += len;
    }
    if (*p != '\0') return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "technique spec '%s': trailing text", text);
    return SSS_OK;
}

sss_result sss_eval_check_spec(const char *spec, sss_error *err)
{
    eval_spec s;
    return eval_parse_spec(spec, &s, err);
}

sss_result sss_eval_parse_sizes(const char *text, sss_eval_size **out, int *count, sss_error *err)
{
    *out = NULL;
    *count = 0;
    if (!text || !text[0]) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "empty size list");
    int cap = 1;
    for (const char *c = text; *c; c++) cap += *c == ',';
    sss_eval_size *v = calloc((size_t)cap, sizeof *v);
    if (!v) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    const char *p = text;
    int n = 0;
    for (;;) {
        char *end = NULL;
        errno = 0;
        long w = strtol(p, &end, 10);
        long h = 0;
        int okw = end != p && *end == 'x' && errno == 0;
        if (okw) {
            const char *q = end + 1;
            errno = 0;
            h = strtol(q, &end, 10);
            okw = end != q && (*end == ',' || *end == '\0') && errno == 0;
        }
        if (!okw || w < 11 || h < 11 || w > SSS_SCENE_MAX_IMAGE_SIZE || h > SSS_SCENE_MAX_IMAGE_SIZE) {
            free(v);
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "size list '%s': expected WxH[,WxH...] with each side in 11..%d", text,
                                 SSS_SCENE_MAX_IMAGE_SIZE);
        }
        v[n].width = (int)w;
        v[n].height = (int)h;
        n++;
        if (*end == '\0') break;
        p = end + 1;
    }
    *out = v;
    *count = n;
    return SSS_OK;
}

int eval_frames_note(const sss_eval_results *res, const sss_eval_entry *e, char *out, size_t cap)
{
    int cut = e->ok && !e->external && (e->frames < res->frames || e->warmup_frames < res->warmup_frames);
    if (cut) snprintf(out, cap, " (%d frame%s%s)", e->frames, e->frames == 1 ? "" : "s", e->warmup_frames ? "" : ", no warm-up");
    else if (cap) out[0] = '\0';
    return cut;
}

int sss_eval_reference_path(const char *dir, const char *stem, int width, int height, int has_time, double time,
                            char *out, size_t cap)
{
    int n;
    if (has_time) n = snprintf(out, cap, "%s/%s_%dx%d_t%g.exr", dir, stem, width, height, time);
    else n = snprintf(out, cap, "%s/%s_%dx%d.exr", dir, stem, width, height);
    return n > 0 && (size_t)n < cap;
}

void eval_escape(const char *text, char *out, size_t cap)
{
    if (cap == 0) return;
    char *escaped = eval_escaped(text);
    size_t n = escaped ? strlen(escaped) : 0;
    if (n >= cap) /* cut before a whole UTF-8 sequence: the text must stay UTF-8 */
        for (n = cap - 1; n > 0 && ((unsigned char)escaped[n] & 0xC0) == 0x80;) n--;
    if (n) memcpy(out, escaped, n);
    out[n] = '\0';
    free(escaped);
}

char *eval_escaped(const char *text)
{
    size_t n = strlen(text);
    char *escaped = malloc(SSS_TEXT_ESCAPE_MAX * n + 1);
    if (escaped) sss_text_escape(text, n, escaped);
    return escaped;
}

int eval_cached_reference_path(const sss_eval_desc *desc, const sss_eval_scene *es, int w, int h, char *out,
                               size_t cap)
{
    char dir[1024];
    const char *slash = strrchr(es->path, '/');
    if (desc->reference_dir) snprintf(dir, sizeof dir, "%s", desc->reference_dir);
    else if (!slash) snprintf(dir, sizeof dir, "references");
    else snprintf(dir, sizeof dir, "%.*s/references", (int)(slash - es->path), es->path);
    return sss_eval_reference_path(dir, desc->reference_dir ? es->stem : es->file_stem, w, h, es->has_time, es->time,
                                   out, cap);
}

uint64_t eval_file_hash(const char *path)
{
    FILE *f = sss_fopen_input(path, SSS_FILE_ANY_SIZE, NULL, NULL);
    if (!f) return 0;
    uint64_t h = 1469598103934665603ull; /* FNV-1a 64 */
    unsigned char buf[8192];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        for (size_t i = 0; i < n; i++) h = (h ^ buf[i]) * 1099511628211ull;
    fclose(f);
    return h;
}

sss_eval_entry *eval_add_entry(sss_eval_results *res)
{
    if (res->entry_count == res->entry_capacity) {
        int cap = res->entry_capacity ? 2 * res->entry_capacity : 32;
        sss_eval_entry *e = realloc(res->entries, (size_t)cap * sizeof *e);
        if (!e) return NULL;
        res->entries = e;
        res->entry_capacity = cap;
    }
    sss_eval_entry *e = &res->entries[res->entry_count++];
    memset(e, 0, sizeof *e);
    return e;
}

const sss_eval_entry *eval_find(const sss_eval_results *res, int scene, sss_eval_kind kind, const char *label,
                                int width, int height)
{
    for (int i = 0; i < res->entry_count; i++) {
        const sss_eval_entry *e = &res->entries[i];
        if (e->scene == scene && e->kind == kind && strcmp(e->label, label) == 0 &&
            (width <= 0 || (e->width == width && e->height == height)))
            return e;
    }
    return NULL;
}

void eval_primary_size(const sss_eval_results *res, int scene, int *width, int *height)
{
    const sss_eval_scene *s = &res->scenes[scene];
    if (s->reference_count > 0) {
        *width = s->references[0].width;
        *height = s->references[0].height;
    } else {
        *width = s->width;
        *height = s->height;
    }
}

void sss_eval_results_free(sss_eval_results *res)
{
    if (!res) return;
    for (int i = 0; i < res->scene_count; i++) {
        free(res->scenes[i].path);
        sss_image_free(&res->scenes[i].reference);
        sss_image_free(&res->scenes[i].object_ids);
    }
    free(res->scenes);
    for (int i = 0; i < res->entry_count; i++) {
        sss_image_free(&res->entries[i].image);
        sss_image_free(&res->entries[i].dssim_map);
        sss_image_free(&res->entries[i].flip_map);
    }
    free(res->entries);
    for (int i = 0; i < res->label_count; i++) free(res->labels[i]);
    free(res->labels);
    for (int i = 0; i < res->external_count && res->external_patterns; i++) free(res->external_patterns[i]);
    free(res->external_patterns);
    memset(res, 0, sizeof *res);
}

void eval_sheet_file(const sss_eval_scene *s, char *out, size_t cap)
{
    if (s->has_time) snprintf(out, cap, "sheet_%s_t%g.png", s->stem, s->time);
    else snprintf(out, cap, "sheet_%s.png", s->stem);
}

/* mkdir -p (eval_internal.h). */
sss_result eval_make_dirs(const char *dir, sss_error *err)
{
    char buf[1024];
    size_t n = strlen(dir);
    if (n == 0 || n >= sizeof buf) return sss_error_set(err, SSS_ERROR_LIMIT, "folder name too long: %s", dir);
    memcpy(buf, dir, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] == '/' || buf[i] == '\0') {
            char c = buf[i];
            buf[i] = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return sss_error_set(err, SSS_ERROR_IO, "cannot create folder %s: %s", buf, strerror(errno));
            buf[i] = c;
        }
    }
    return SSS_OK;
}

void eval_mean_ratio(const sss_image *img, const sss_image *ref, double out[3])
{
    double sum[2][3] = {{0}};
    const sss_image *im[2] = {img, ref};
    for (int k = 0; k < 2; k++) {
        size_t n = (size_t)im[k]->width * (size_t)im[k]->height;
        for (size_t i = 0; im[k]->pixels && i < n; i++)
            for (int c = 0; c < 3; c++) sum[k][c] += im[k]->pixels[3 * i + c];
    }
    for (int c = 0; c < 3; c++) out[c] = sum[1][c] != 0.0 ? sum[0][c] / sum[1][c] : NAN;
}
