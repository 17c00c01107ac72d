/* Typed cJSON access with path-named errors (see json_reader.h). */
#include "scene/json_reader.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "core/text.h"

void jr_init(jr *r, const char *name, sss_error *err)
{
    r->name = name ? name : "scene";
    r->err = err;
    r->path[0] = '\0';
    r->len = 0;
}

/* Appends text to the path, truncating (with the terminator kept) when it would overflow: a message
 * with a clipped path is still better than none. */
static void path_append(jr *r, const char *text)
{
    size_t n = strlen(text);
    if (r->len + n >= JR_PATH_SIZE) n = JR_PATH_SIZE - 1 - r->len;
    memcpy(r->path + r->len, text, n);
    r->len += n;
    r->path[r->len] = '\0';
}

size_t jr_enter_key(jr *r, const char *key)
{
    size_t mark = r->len;
    if (r->len > 0) path_append(r, ".");
    path_append(r, key);
    return mark;
}

size_t jr_enter_index(jr *r, size_t index)
{
    size_t mark = r->len;
    char buf[32];
    snprintf(buf, sizeof buf, "[%zu]", index);
    path_append(r, buf);
    return mark;
}

void jr_leave(jr *r, size_t mark)
{
    r->len = mark;
    r->path[mark] = '\0';
}

static sss_result vfail(jr *r, sss_result code, const char *fmt, va_list ap)
{
    if (!r->err) return code;
    char msg[SSS_ERROR_MESSAGE_SIZE];
    vsnprintf(msg, sizeof msg, fmt, ap);
    if (r->len > 0) return sss_error_set(r->err, code, "%s: %s: %s", r->name, r->path, msg);
    return sss_error_set(r->err, code, "%s: %s", r->name, msg);
}

sss_result jr_fail(jr *r, sss_result code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sss_result res = vfail(r, code, fmt, ap);
    va_end(ap);
    return res;
}

sss_result jr_fail_key(jr *r, const char *key, sss_result code, const char *fmt, ...)
{
    size_t mark = jr_enter_key(r, key);
    va_list ap;
    va_start(ap, fmt);
    sss_result res = vfail(r, code, fmt, ap);
    va_end(ap);
    jr_leave(r, mark);
    return res;
}

sss_result jr_prefix(jr *r, const char *key, sss_result code)
{
    size_t mark = key ? jr_enter_key(r, key) : r->len;
    if (r->err) {
        char prefix[JR_PATH_SIZE + 256];
        if (r->len > 0) snprintf(prefix, sizeof prefix, "%s: %s", r->name, r->path);
        else snprintf(prefix, sizeof prefix, "%s", r->name);
        sss_error_prefix(r->err, prefix);
        r->err->code = code;
    }
    jr_leave(r, mark);
    return code;
}

static int is_space(char ch)
{
    return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r';
}

/* "line L, column C" (1-based) of offset in text, for messages. */
static sss_result fail_at(jr *r, const char *text, size_t offset, const char *what)
{
    size_t line = 1, col = 1;
    for (size_t i = 0; i < offset; i++) {
        if (text[i] == '\n') {
            line++;
            col = 1;
        } else {
            col++;
        }
    }
    return jr_fail(r, SSS_ERROR_PARSE, "line %zu, column %zu: %s", line, col, what);
}

sss_result jr_parse(jr *r, const char *text, size_t size, cJSON **root)
{
    *root = NULL;
    if (!text && size) return jr_fail(r, SSS_ERROR_INVALID_ARGUMENT, "no text");
    size_t start = size >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0; /* UTF-8 byte order mark */
    size_t k = start;
    while (k < size && is_space(text[k])) k++;
    if (k == size) return jr_fail(r, SSS_ERROR_PARSE, "empty file (expected a JSON object)");
    const char *end = NULL;
    cJSON *value = cJSON_ParseWithLengthOpts(text + start, size - start, &end, 0);
    if (!value) {
        size_t off = end && end >= text + start && end <= text + size ? (size_t)(end - text) : start;
        return fail_at(r, text, off, "malformed JSON");
    }
    size_t off = end ? (size_t)(end - text) : size;
    while (off < size && is_space(text[off])) off++;
    if (off < size) {
        cJSON_Delete(value);
        return fail_at(r, text, off, "unexpected text after the JSON value");
    }
    char nul_path[JR_PATH_SIZE];
    if (sss_json_find_nul(text + start, size - start, nul_path, sizeof nul_path)) {
        cJSON_Delete(value); /* cJSON keeps only the part before the NUL */
        size_t mark = r->len;
        if (nul_path[0] && nul_path[0] != '[' && r->len > 0) path_append(r, ".");
        path_append(r, nul_path);
        sss_result res = jr_fail(r, SSS_ERROR_PARSE, "a string holds a NUL character (\\u0000)");
        jr_leave(r, mark);
        return res;
    }
    *root = value;
    return SSS_OK;
}

const cJSON *jr_get(const cJSON *obj, const char *key)
{
    return cJSON_GetObjectItemCaseSensitive(obj, key);
}

sss_result jr_expect_object(jr *r, const cJSON *item)
{
    if (!cJSON_IsObject(item)) return jr_fail(r, SSS_ERROR_PARSE, "expected an object");
    return SSS_OK;
}

sss_result jr_check_fields(jr *r, const cJSON *obj, const char *const *allowed, size_t n)
{
    for (const cJSON *c = obj->child; c; c = c->next) {
        const char *key = c->string ? c->string : "";
        size_t i = 0;
        while (i < n && strcmp(allowed[i], key) != 0) i++;
        if (i == n) {
            char list[256] = "";
            size_t at = 0;
            for (size_t k = 0; k < n && at < sizeof list; k++) {
                int w = snprintf(list + at, sizeof list - at, "%s%s", k ? ", " : "", allowed[k]);
                if (w < 0) break;
                at += (size_t)w;
            }
            return jr_fail_key(r, key, SSS_ERROR_PARSE, "unknown field (expected one of: %s)", list);
        }
        for (const cJSON *d = obj->child; d != c; d = d->next)
            if (d->string && strcmp(d->string, key) == 0)
                return jr_fail_key(r, key, SSS_ERROR_PARSE, "duplicate field");
    }
    return SSS_OK;
}

sss_result jr_require(jr *r, const cJSON *obj, const char *key)
{
    if (!jr_get(obj, key)) return jr_fail_key(r, key, SSS_ERROR_PARSE, "required field missing");
    return SSS_OK;
}

/* Reads item (at the current path) as a finite number. */
static sss_result item_number(jr *r, const cJSON *item, double *out)
{
    if (!cJSON_IsNumber(item)) return jr_fail(r, SSS_ERROR_PARSE, "expected a number");
    if (!isfinite(item->valuedouble)) return jr_fail(r, SSS_ERROR_INVALID_ARGUMENT, "must be finite");
    *out = item->valuedouble;
    return SSS_OK;
}

sss_result jr_number(jr *r, const cJSON *obj, const char *key, int required, double def, double *out)
{
    const cJSON *item = jr_get(obj, key);
    if (!item) {
        if (required) return jr_fail_key(r, key, SSS_ERROR_PARSE, "required field missing");
        *out = def;
        return SSS_OK;
    }
    size_t mark = jr_enter_key(r, key);
    sss_result res = item_number(r, item, out);
    jr_leave(r, mark);
    return res;
}

sss_result jr_int(jr *r, const cJSON *obj, const char *key, int required, long def, long min, long max,
                  long *out)
{
    const cJSON *item = jr_get(obj, key);
    if (!item) {
        if (required) return jr_fail_key(r, key, SSS_ERROR_PARSE, "required field missing");
        *out = def;
        return SSS_OK;
    }
    size_t mark = jr_enter_key(r, key);
    sss_result res = SSS_OK;
    double v = 0;
    if (!cJSON_IsNumber(item) || !isfinite(item->valuedouble) || floor(item->valuedouble) != item->valuedouble)
        res = jr_fail(r, SSS_ERROR_PARSE, "expected an integer");
    else if ((v = item->valuedouble) < (double)min || v > (double)max)
        res = jr_fail(r, SSS_ERROR_INVALID_ARGUMENT, "%.17g is out of range %ld..%ld", v, min, max);
    else
        *out = (long)v;
    jr_leave(r, mark);
    return res;
}

sss_result jr_bool(jr *r, const cJSON *obj, const char *key, int def, int *out)
{
    const cJSON *item = jr_get(obj, key);
    if (!item) {
        *out = def;
        return SSS_OK;
    }
    if (!cJSON_IsBool(item)) return jr_fail_key(r, key, SSS_ERROR_PARSE, "expected true or false");
    *out = cJSON_IsTrue(item) ? 1 : 0;
    return SSS_OK;
}

sss_result jr_string(jr *r, const cJSON *obj, const char *key, int required, const char **out)
{
    const cJSON *item = jr_get(obj, key);
    *out = NULL;
    if (!item) {
        if (required) return jr_fail_key(r, key, SSS_ERROR_PARSE, "required field missing");
        return SSS_OK;
    }
    if (!cJSON_IsString(item) || !item->valuestring)
        return jr_fail_key(r, key, SSS_ERROR_PARSE, "expected a string");
    if (item->valuestring[0] == '\0') return jr_fail_key(r, key, SSS_ERROR_INVALID_ARGUMENT, "empty string");
    *out = item->valuestring;
    return SSS_OK;
}

static sss_result item_vec(jr *r, const cJSON *item, int n, double *out)
{
    if (!cJSON_IsArray(item) || cJSON_GetArraySize(item) != n)
        return jr_fail(r, SSS_ERROR_PARSE, "expected an array of %d numbers", n);
    double tmp[16];
    int i = 0;
    for (const cJSON *c = item->child; c; c = c->next, i++) {
        size_t mark = jr_enter_index(r, (size_t)i);
        sss_result res = item_number(r, c, &tmp[i]);
        jr_leave(r, mark);
        if (res != SSS_OK) return res;
    }
    for (i = 0; i < n; i++) out[i] = tmp[i];
    return SSS_OK;
}

sss_result jr_vec(jr *r, const cJSON *obj, const char *key, int required, const double *def, int n,
                  double *out, int *present)
{
    const cJSON *item = jr_get(obj, key);
    if (present) *present = item != NULL;
    if (!item) {
        if (required) return jr_fail_key(r, key, SSS_ERROR_PARSE, "required field missing");
        if (def)
            for (int i = 0; i < n; i++) out[i] = def[i];
        return SSS_OK;
    }
    size_t mark = jr_enter_key(r, key);
    sss_result res = item_vec(r, item, n, out);
    jr_leave(r, mark);
    return res;
}

sss_result jr_number_or_vec(jr *r, const cJSON *obj, const char *key, int required, double def, int n,
                            double *out, int *present)
{
    const cJSON *item = jr_get(obj, key);
    if (present) *present = item != NULL;
    if (!item) {
        if (required) return jr_fail_key(r, key, SSS_ERROR_PARSE, "required field missing");
        for (int i = 0; i < n; i++) out[i] = def;
        return SSS_OK;
    }
    size_t mark = jr_enter_key(r, key);
    sss_result res;
    if (cJSON_IsNumber(item)) {
        double v = 0;
        res = item_number(r, item, &v);
        if (res == SSS_OK)
            for (int i = 0; i < n; i++) out[i] = v;
    } else if (cJSON_IsArray(item)) {
        res = item_vec(r, item, n, out);
    } else {
        res = jr_fail(r, SSS_ERROR_PARSE, "expected a number or an array of %d numbers", n);
    }
    jr_leave(r, mark);
    return res;
}

static int in_range(double v, double lo, int lo_open, double hi, int hi_open)
{
    if (lo_open ? !(v > lo) : !(v >= lo)) return 0;
    if (hi_open ? !(v < hi) : !(v <= hi)) return 0;
    return 1;
}

/* "out of range [lo, hi)" or "must be > lo" when hi is infinite. */
static void range_text(char *buf, size_t cap, double lo, int lo_open, double hi, int hi_open)
{
    if (isinf(hi)) snprintf(buf, cap, "must be %s %g", lo_open ? ">" : ">=", lo);
    else snprintf(buf, cap, "out of range %c%g, %g%c", lo_open ? '(' : '[', lo, hi, hi_open ? ')' : ']');
}

sss_result jr_range(jr *r, const char *key, double value, double lo, int lo_open, double hi, int hi_open)
{
    if (in_range(value, lo, lo_open, hi, hi_open)) return SSS_OK;
    char text[128];
    range_text(text, sizeof text, lo, lo_open, hi, hi_open);
    return jr_fail_key(r, key, SSS_ERROR_INVALID_ARGUMENT, "%g: %s", value, text);
}

sss_result jr_range_vec(jr *r, const char *key, const double *v, int n, double lo, int lo_open, double hi,
                        int hi_open)
{
    for (int i = 0; i < n; i++) {
        if (in_range(v[i], lo, lo_open, hi, hi_open)) continue;
        char text[128];
        range_text(text, sizeof text, lo, lo_open, hi, hi_open);
        size_t mark = jr_enter_key(r, key);
        jr_enter_index(r, (size_t)i);
        sss_result res = jr_fail(r, SSS_ERROR_INVALID_ARGUMENT, "%g: %s", v[i], text);
        jr_leave(r, mark);
        return res;
    }
    return SSS_OK;
}
