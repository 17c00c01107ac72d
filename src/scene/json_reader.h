/* scene/json_reader.h — typed access to cJSON values with the JSON path kept for messages (internal).
 *
 * Every failure produces "<name>: <path>: <problem>", e.g. "scene.json: camera.fov: expected a number",
 * where <path> is the dotted/indexed path of the value being read ("objects[1].material.sigma_a[2]").
 */
#ifndef SSS_SCENE_JSON_READER_H
#define SSS_SCENE_JSON_READER_H

#include <cjson/cJSON.h>
#include <stddef.h>

#include "sss/common.h"

#define JR_PATH_SIZE 256

typedef struct jr {
    const char *name; /* file name for messages */
    sss_error *err;
    char path[JR_PATH_SIZE];
    size_t len;
} jr;

void jr_init(jr *r, const char *name, sss_error *err);

/* Parses size bytes of text (no terminator needed) as one JSON value into *root (NULL on failure;
 * free with cJSON_Delete). Every JSON sss reads goes through here (scenes, lights, glTF, the viewer's
 * edits, reference sidecars), so all of them refuse the same things: empty text, malformed JSON and text
 * after the value ("line L, column C: ..."), and a string holding a NUL character (the escape \u0000 or
 * a raw 0 byte), which cJSON's C strings would silently cut ("a.bin\u0000../x" read as "a.bin"); that
 * message names the string's JSON path after the current one. A UTF-8 byte order mark is skipped. */
sss_result jr_parse(jr *r, const char *text, size_t size, cJSON **root);

/* Path handling: enter returns a mark to pass to jr_leave. */
size_t jr_enter_key(jr *r, const char *key);
size_t jr_enter_index(jr *r, size_t index);
void jr_leave(jr *r, size_t mark);

/* "<name>: <path>: <message>" (or "<name>: <message>" at the root); returns code. */
sss_result jr_fail(jr *r, sss_result code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* The same for the child `key` of the current path. */
sss_result jr_fail_key(jr *r, const char *key, sss_result code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* Prefixes an error produced elsewhere with "<name>: <path>" (current path + optional key). */
sss_result jr_prefix(jr *r, const char *key, sss_result code);

/* The member `key` of obj (case-sensitive), NULL when absent. */
const cJSON *jr_get(const cJSON *obj, const char *key);

/* Fails unless item (at the current path) is an object. */
sss_result jr_expect_object(jr *r, const cJSON *item);
/* Every member of obj must be one of allowed[0..n) and appear once ("unknown field", "duplicate
 * field"). */
sss_result jr_check_fields(jr *r, const cJSON *obj, const char *const *allowed, size_t n);
/* Fails with "required field missing" when obj has no member key. */
sss_result jr_require(jr *r, const cJSON *obj, const char *key);

/* Readers: when the member is absent, required -> error, otherwise *out = def (strings: NULL) and
 * *present (if non-NULL) = 0. Numbers must be finite. */
sss_result jr_number(jr *r, const cJSON *obj, const char *key, int required, double def, double *out);
sss_result jr_int(jr *r, const cJSON *obj, const char *key, int required, long def, long min, long max,
                  long *out);
sss_result jr_bool(jr *r, const cJSON *obj, const char *key, int def, int *out);
sss_result jr_string(jr *r, const cJSON *obj, const char *key, int required, const char **out);
/* An array of exactly n finite numbers. def may be NULL (then out is untouched when absent). */
sss_result jr_vec(jr *r, const cJSON *obj, const char *key, int required, const double *def, int n,
                  double *out, int *present);
/* A number (copied to all n entries) or an array of n numbers. */
sss_result jr_number_or_vec(jr *r, const cJSON *obj, const char *key, int required, double def, int n,
                            double *out, int *present);

/* Range checks of an already read value (message names path.key): lo/hi open when *_open. */
sss_result jr_range(jr *r, const char *key, double value, double lo, int lo_open, double hi, int hi_open);
/* Each of n entries; the message names path.key[i]. */
sss_result jr_range_vec(jr *r, const char *key, const double *v, int n, double lo, int lo_open, double hi,
                        int hi_open);

#endif
