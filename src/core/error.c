#include "sss/common.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

sss_result sss_error_set(sss_error *err, sss_result code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        err->code = code;
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return code;
}

void sss_error_prefix(sss_error *err, const char *prefix)
{
    if (!err || !prefix) return;
    /* Build "prefix: message" in place, truncating the old message to what still fits. */
    char old[SSS_ERROR_MESSAGE_SIZE];
    memcpy(old, err->message, sizeof old);
    size_t n = strlen(prefix), cap = sizeof err->message - 1, at = 0;
    for (size_t i = 0; i < n && at < cap; i++) err->message[at++] = prefix[i];
    for (const char *s = ": "; *s && at < cap; s++) err->message[at++] = *s;
    for (size_t i = 0; old[i] && at < cap; i++) err->message[at++] = old[i];
    err->message[at] = '\0';
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
