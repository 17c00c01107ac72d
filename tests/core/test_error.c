/* The error helpers: messages are formatted, truncated safely and prefixed. */
#include <string.h>

#include "check.h"
#include "sss/common.h"

int main(void)
{
    sss_error err = {0};
    CHECK(sss_error_set(&err, SSS_ERROR_PARSE, "line %d: bad %s", 12, "index") == SSS_ERROR_PARSE);
    CHECK(err.code == SSS_ERROR_PARSE);
    CHECK(strcmp(err.message, "line 12: bad index") == 0);
    sss_error_prefix(&err, "mesh.ply");
    CHECK(strcmp(err.message, "mesh.ply: line 12: bad index") == 0);

    /* An over-long message is truncated, never overflowed. */
    char longs[2000];
    memset(longs, 'x', sizeof longs - 1);
    longs[sizeof longs - 1] = 0;
    sss_error_set(&err, SSS_ERROR_IO, "%s", longs);
    CHECK(strlen(err.message) == SSS_ERROR_MESSAGE_SIZE - 1);
    sss_error_prefix(&err, "p");
    CHECK(strlen(err.message) == SSS_ERROR_MESSAGE_SIZE - 1 && strncmp(err.message, "p: x", 4) == 0);

    /* A NULL error is allowed everywhere. */
    CHECK(sss_error_set(NULL, SSS_ERROR_IO, "ignored") == SSS_ERROR_IO);
    CHECK(strcmp(sss_result_string(SSS_ERROR_LIMIT), "size limit exceeded") == 0);

    double t0 = sss_time_seconds(), t1 = sss_time_seconds();
    CHECK(t1 >= t0);
    return CHECK_DONE();
}
