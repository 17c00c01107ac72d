#include "sss/common.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/text.h"

/* Stores text (length n) as err's message: control characters escaped (messages reach terminals and
 * name files and scene strings from data), and, when too long, the middle of the longest path cut
 * rather than the end, which holds the cause. */
static void store_message(sss_error *err, const char *text, size_t n)
{
    char *escaped = malloc(SSS_TEXT_ESCAPE_MAX * n + 1);
    if (!escaped) { /* no memory for the copy: keep what fits of the raw text, still escaped */
        size_t fit = (sizeof err->message - 1) / SSS_TEXT_ESCAPE_MAX;
        sss_text_escape(text, n < fit ? n : fit, err->message);
        return;
    }
    size_t len = sss_text_escape(text, n, escaped);
    len = sss_text_shorten_middle(escaped, len, sizeof err->message - 1);
    memcpy(err->message, escaped, len + 1);
    free(escaped);
}

sss_result sss_error_set(sss_error *err, sss_result code, const char *fmt, ...)
{
    if (!err) return code;
    err->code = code;
    va_list ap, again;
    va_start(ap, fmt);
    va_copy(again, ap);
    char small[SSS_ERROR_MESSAGE_SIZE];
    int n = vsnprintf(small, sizeof small, fmt, ap);
    if (n < 0) {
        small[0] = '\0';
        n = 0;
    }
    char *text = (size_t)n < sizeof small ? small : malloc((size_t)n + 1);
    if (text && text != small) vsnprintf(text, (size_t)n + 1, fmt, again);
    if (text) store_message(err, text, (size_t)n);
    else store_message(err, small, strlen(small)); /* no memory: the part that fitted */
    if (text != small) free(text);
    va_end(again);
    va_end(ap);
    return code;
}

void sss_error_prefix(sss_error *err, const char *prefix)
{
    if (!err || !prefix) return;
    /* "prefix: message", then fitted like any message (the old one is already escaped). */
    size_t np = strlen(prefix), nm = strlen(err->message);
    char *text = malloc(np + 2 + nm + 1);
    if (!text) return;
    memcpy(text, prefix, np);
    memcpy(text + np, ": ", 2);
    memcpy(text + np + 2, err->message, nm + 1);
    store_message(err, text, np + 2 + nm);
    free(text);
}

const char *sss_result_string(sss_result code)
{
    switch (code) {
    case SSS_OK: return "ok";
    case SSS_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case SSS_ERROR_OUT_OF_MEMORY: return "out of memory";
    case SSS_ERROR_IO: return "I/O error";
    case SSS_ERROR_PARSE: return "parse error";
    case SSS_ERROR_UNSUPPORTED: return "unsupported";
    case SSS_ERROR_LIMIT: return "size limit exceeded";
    case SSS_ERROR_NUMERIC: return "numerical failure";
    }
    return "unknown error";
}
