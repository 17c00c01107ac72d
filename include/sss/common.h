/* sss/common.h — results, errors and small shared types of the sss library.
 *
 * Every fallible sss function returns an sss_result and, when given a non-NULL sss_error, fills it
 * with a one-line message that names the input and the problem ("bunny.ply: line 12: vertex index
 * 4096 out of range (4000 vertices)"). The library never prints, exits or aborts; callers decide.
 * Functions that cannot fail return their value directly.
 */
#ifndef SSS_COMMON_H
#define SSS_COMMON_H

#include <stddef.h>

#include "sss/api.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sss_result {
    SSS_OK = 0,
    SSS_ERROR_INVALID_ARGUMENT, /* a parameter is out of its documented range (negative coefficient, ...) */
    SSS_ERROR_OUT_OF_MEMORY,
    SSS_ERROR_IO,               /* a file could not be opened, read or written */
    SSS_ERROR_PARSE,            /* a file or string is malformed */
    SSS_ERROR_UNSUPPORTED,      /* valid input that this version does not handle (format variant, ...) */
    SSS_ERROR_LIMIT,            /* input exceeds a documented size limit */
    SSS_ERROR_NUMERIC           /* a computation did not converge or produced a non-finite value */
} sss_result;

#define SSS_ERROR_MESSAGE_SIZE 512

typedef struct sss_error {
    sss_result code;
    char message[SSS_ERROR_MESSAGE_SIZE];
} sss_error;

/* Sets err (if non-NULL) to code and a printf-formatted message; returns code. */
SSS_API sss_result sss_error_set(sss_error *err, sss_result code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Prefixes an existing message with "prefix: " (used to add a file name to a lower-level error). */
SSS_API void sss_error_prefix(sss_error *err, const char *prefix);

/* A short, static English name of a result code ("parse error", ...). */
SSS_API const char *sss_result_string(sss_result code);

/* Monotonic clock in seconds, for timings printed by tools and benchmarks. */
SSS_API double sss_time_seconds(void);

/* The median of count values (the mean of the middle two for an even count; 0 for count <= 0). Sorts
 * values in place (ascending), so values[0] and values[count - 1] are then the extremes. */
SSS_API double sss_median(double *values, int count);

#ifdef __cplusplus
}
#endif
#endif
