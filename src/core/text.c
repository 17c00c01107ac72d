/* core/text.c — escaping and shortening messages; finding NUL characters in JSON strings. */
#include "core/text.h"

#include <stdio.h>
#include <string.h>

/* Length of the valid UTF-8 sequence at s (at most n bytes), 0 when the bytes are not one. */
static size_t utf8_sequence(const unsigned char *s, size_t n)
{
    unsigned char c = s[0];
    size_t len = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
    if (len == 0 || len > n) return 0;
    /* second byte: no overlong forms, no surrogates, nothing beyond U+10FFFF */
    unsigned char lo = c == 0xE0 ? 0xA0 : c == 0xF0 ? 0x90 : 0x80;
    unsigned char hi = c == 0xED ? 0x9F : c == 0xF4 ? 0x8F : 0xBF;
    if (s[1] < lo || s[1] > hi) return 0;
    for (size_t i = 2; i < len; i++)
        if (s[i] < 0x80 || s[i] > 0xBF) return 0;
    return len;
}

static size_t put_hex(char *dst, unsigned char c)
{
    snprintf(dst, SSS_TEXT_ESCAPE_MAX + 1, "\\x%02x", c);
    return SSS_TEXT_ESCAPE_MAX;
}

size_t sss_text_escape(const char *src, size_t n, char *dst)
{
    const unsigned char *s = (const unsigned char *)src;
    size_t at = 0;
    for (size_t i = 0; i < n;) {
        unsigned char c = s[i];
        if (c >= 0x20 && c < 0x7F) {
            dst[at++] = (char)c;
            i++;
        } else if (c == '\n' || c == '\r' || c == '\t') {
            dst[at++] = '\\';
            dst[at++] = c == '\n' ? 'n' : c == '\r' ? 'r' : 't';
            i++;
        } else if (c < 0x80) { /* other C0 controls (ESC ...) and DEL */
            at += put_hex(dst + at, c);
            i++;
        } else {
            size_t len = utf8_sequence(s + i, n - i);
            int c1_control = len == 2 && c == 0xC2 && s[i + 1] <= 0x9F; /* U+0080..U+009F: CSI is U+009B */
            if (len == 0 || c1_control) {
                size_t bytes = len ? len : 1;
                for (size_t k = 0; k < bytes; k++) at += put_hex(dst + at, s[i + k]);
                i += bytes;
            } else {
                memcpy(dst + at, s + i, len);
                at += len;
                i += len;
            }
        }
    }
    dst[at] = '\0';
    return at;
}

/* ---- Shortening ------------------------------------------------------------------------------ */

#define ELLIPSIS "..."
#define ELLIPSIS_LEN 3
#define RUN_KEEP_MIN 24 /* characters a shortened run keeps: enough to recognise a path's two ends */

static int is_continuation(unsigned char c)
{
    return c >= 0x80 && c <= 0xBF;
}

/* Replaces text[from, to) with "...", moving the cut off UTF-8 continuation bytes; returns the new
 * length. */
static size_t elide(char *text, size_t len, size_t from, size_t to)
{
    while (from > 0 && is_continuation((unsigned char)text[from])) from--;
    while (to < len && is_continuation((unsigned char)text[to])) to++;
    memmove(text + from + ELLIPSIS_LEN, text + to, len - to + 1);
    memcpy(text + from, ELLIPSIS, ELLIPSIS_LEN);
    return len - (to - from) + ELLIPSIS_LEN;
}

static void longest_run(const char *text, size_t len, size_t *start, size_t *run)
{
    *start = *run = 0;
    for (size_t i = 0; i < len;) {
        size_t j = i;
        while (j < len && text[j] != ' ') j++;
        if (j - i > *run) {
            *start = i;
            *run = j - i;
        }
        i = j + 1;
    }
}

size_t sss_text_shorten_middle(char *text, size_t len, size_t max)
{
    if (max < ELLIPSIS_LEN + 2) max = ELLIPSIS_LEN + 2;
    while (len > max) {
        size_t start, run;
        longest_run(text, len, &start, &run);
        if (run <= RUN_KEEP_MIN + ELLIPSIS_LEN) break;
        size_t excess = len - max;
        size_t keep = run > excess + ELLIPSIS_LEN + RUN_KEEP_MIN ? run - excess - ELLIPSIS_LEN : RUN_KEEP_MIN;
        size_t head = keep / 2;
        len = elide(text, len, start + head, start + run - (keep - head));
    }
    if (len > max) { /* no long run left: keep both ends of the whole text */
        size_t keep = max - ELLIPSIS_LEN, head = keep / 2;
        len = elide(text, len, head, len - (keep - head));
    }
    return len;
}

/* ---- JSON ------------------------------------------------------------------------------------ */

#define JSON_DEPTH_MAX 1100 /* beyond cJSON's nesting limit (1000): deeper text never parsed */

typedef struct json_level {
    int is_object;
    size_t index;                /* arrays: the element being read */
    size_t key_start, key_len;   /* objects: the member being read (raw text between the quotes) */
    int expect_key;              /* objects: the next string is a member name */
} json_level;

/* The path of the value (or member name) being read at levels[0..depth), in the scene loader's
 * notation. */
static void json_path(const char *text, const json_level *levels, size_t depth, char *path, size_t cap)
{
    size_t at = 0;
    path[0] = '\0';
    for (size_t d = 0; d < depth && at < cap; d++) {
        const json_level *l = &levels[d];
        int n;
        if (!l->is_object) n = snprintf(path + at, cap - at, "[%zu]", l->index);
        else n = snprintf(path + at, cap - at, "%s%.*s", at ? "." : "", (int)strnlen(text + l->key_start, l->key_len),
                          text + l->key_start);
        if (n < 0) break;
        at += (size_t)n;
    }
}

/* Scans the string starting at text[*i] (the opening quote); leaves *i on the closing quote. */
static int json_string_has_nul(const char *text, size_t size, size_t *i)
{
    int nul = 0;
    size_t j = *i + 1;
    while (j < size && text[j] != '"') {
        if (text[j] == '\\') {
            if (j + 5 < size && text[j + 1] == 'u' && memcmp(text + j + 2, "0000", 4) == 0) nul = 1;
            j += 2; /* the escaped character: "\\" never starts a second escape */
            continue;
        }
        if (text[j] == '\0') nul = 1;
        j++;
    }
    *i = j;
    return nul;
}

int sss_json_find_nul(const char *text, size_t size, char *path, size_t cap)
{
    json_level levels[JSON_DEPTH_MAX];
    size_t depth = 0;
    if (cap) path[0] = '\0';
    for (size_t i = 0; i < size; i++) {
        char c = text[i];
        json_level *top = depth ? &levels[depth - 1] : NULL;
        if (c == '{' || c == '[') {
            if (depth == JSON_DEPTH_MAX) return 0;
            levels[depth++] = (json_level){c == '{', 0, 0, 0, c == '{'};
        } else if ((c == '}' || c == ']') && depth) {
            depth--;
        } else if (c == ',' && top) {
            if (top->is_object) top->expect_key = 1;
            else top->index++;
        } else if (c == ':' && top) {
            top->expect_key = 0;
        } else if (c == '"') {
            size_t start = i + 1;
            int nul = json_string_has_nul(text, size, &i);
            int is_key = top && top->is_object && top->expect_key;
            if (is_key) {
                top->key_start = start;
                top->key_len = i - start;
            }
            if (nul) {
                if (cap) json_path(text, levels, depth, path, cap);
                return 1;
            }
        }
    }
    return 0;
}

int sss_text_edit_distance(const char *a, const char *b)
{
    size_t n = strlen(a), m = strlen(b);
    if (n > SSS_TEXT_DISTANCE_MAX || m > SSS_TEXT_DISTANCE_MAX) return SSS_TEXT_DISTANCE_MAX;
    /* d[i][j]: distance of the first i bytes of a and the first j of b (Damerau 1964, restricted). */
    int d[SSS_TEXT_DISTANCE_MAX + 1][SSS_TEXT_DISTANCE_MAX + 1];
    for (size_t i = 0; i <= n; i++) d[i][0] = (int)i;
    for (size_t j = 0; j <= m; j++) d[0][j] = (int)j;
    for (size_t i = 1; i <= n; i++)
        for (size_t j = 1; j <= m; j++) {
            int cost = a[i - 1] != b[j - 1];
            int best = d[i - 1][j - 1] + cost;
            if (d[i - 1][j] + 1 < best) best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best) best = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    return d[n][m];
}
