/* core/file_util.h — file helpers shared by the modules (internal, not public API).
 *
 * Atomic writes: write to sss_temp_path(path) in the same folder, then sss_commit_temp() renames it
 * over path (or sss_discard_temp() removes it on failure), so an interrupted run never leaves a
 * truncated output file behind.
 */
#ifndef SSS_CORE_FILE_UTIL_H
#define SSS_CORE_FILE_UTIL_H

#include <stdio.h>

#include "sss/common.h"

/* Reads a whole file. Fails with SSS_ERROR_LIMIT (before allocating) when it is larger than
 * max_size bytes, SSS_ERROR_IO when it cannot be opened or read. *data is NUL-terminated (one byte
 * beyond *size) and must be released with free(). Messages name the path. */
sss_result sss_read_file(const char *path, size_t max_size, char **data, size_t *size, sss_error *err);

/* Fills tmp (capacity cap) with "<dir>/.<name>.tmp-<pid>"; returns 0 if it does not fit. */
int sss_temp_path(const char *path, char *tmp, size_t cap);
/* Renames tmp to path; on failure removes tmp and reports an error naming path. */
sss_result sss_commit_temp(const char *tmp, const char *path, sss_error *err);
void sss_discard_temp(const char *tmp);

/* Opens a temporary file for an atomic write of path ("wb"). tmp receives its name (cap >= 4096
 * recommended). Close the FILE yourself, then commit or discard. */
FILE *sss_atomic_open(const char *path, char *tmp, size_t cap, sss_error *err);
/* fclose(f), checking for write errors, then sss_commit_temp (or discard on any error). */
sss_result sss_atomic_close(FILE *f, const char *tmp, const char *path, sss_error *err);

/* The extension of path in lower case without the dot ("" when there is none); out has cap bytes. */
void sss_path_extension(const char *path, char *out, size_t cap);

#endif
