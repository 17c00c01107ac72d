/* File helpers: whole-file reads honour the size limit, atomic writes leave either the complete new
 * file or nothing, extensions are lower-cased. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "core/file_util.h"

int main(void)
{
    char dir[] = "/tmp/sss-test-file-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char path[512], tmp[4096];
    snprintf(path, sizeof path, "%s/out.txt", dir);

    sss_error err = {0};
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, &err);
    CHECK(f != NULL);
    fputs("hello", f);
    CHECK(access(path, F_OK) != 0); /* nothing at the final name until committed */
    CHECK(sss_atomic_close(f, tmp, path, &err) == SSS_OK);
    CHECK(access(tmp, F_OK) != 0);

    char *data = NULL;
    size_t size = 0;
    CHECK(sss_read_file(path, 100, &data, &size, &err) == SSS_OK);
    CHECK(size == 5 && data && strcmp(data, "hello") == 0);
    free(data);
    CHECK(sss_read_file(path, 4, &data, &size, &err) == SSS_ERROR_LIMIT);
    CHECK(data == NULL && strstr(err.message, path) != NULL);
    CHECK(sss_read_file("/nonexistent/x.ply", 100, &data, &size, &err) == SSS_ERROR_IO);
    CHECK(strstr(err.message, "/nonexistent/x.ply") != NULL);

    CHECK(sss_read_file(dir, 100, &data, &size, &err) == SSS_ERROR_IO); /* a folder is not a file */
    CHECK_MSG(strstr(err.message, "not a regular file") != NULL, "%s", err.message);

    /* Writing into a missing folder fails with the path named and leaves nothing. */
    CHECK(sss_atomic_open("/nonexistent/dir/x.png", tmp, sizeof tmp, &err) == NULL);
    CHECK(strstr(err.message, "/nonexistent/dir/x.png") != NULL);

    char ext[16];
    sss_path_extension("a/b.c/Mesh.PLY", ext, sizeof ext);
    CHECK(strcmp(ext, "ply") == 0);
    sss_path_extension("a.d/noext", ext, sizeof ext);
    CHECK(ext[0] == '\0');

    remove(path);
    rmdir(dir);
    return CHECK_DONE();
}
