#include "core/file_util.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

sss_result sss_read_file(const char *path, size_t max_size, char **data, size_t *size, sss_error *err)
{
    *data = NULL;
    *size = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return sss_error_set(err, SSS_ERROR_IO, "%s: cannot open: %s", path, strerror(errno));
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
        fclose(f);
        return sss_error_set(err, SSS_ERROR_IO, "%s: not a regular file", path);
    }
    if (fseek(f, 0, SEEK_END) != 0) {
        fclose(f);
        return sss_error_set(err, SSS_ERROR_IO, "%s: cannot seek (not a regular file?)", path);
    }
    long len = ftell(f);
    if (len < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return sss_error_set(err, SSS_ERROR_IO, "%s: cannot determine the file size", path);
    }
    if ((unsigned long)len > max_size) {
        fclose(f);
        return sss_error_set(err, SSS_ERROR_LIMIT, "%s: file is %ld bytes, larger than the %zu accepted",
                             path, len, max_size);
    }
    char *buf = malloc((size_t)len + 1);
    if (!buf) {
        fclose(f);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory reading %ld bytes", path, len);
    }
    size_t got = fread(buf, 1, (size_t)len, f);
    int failed = ferror(f);
    fclose(f);
    if (failed || got != (size_t)len) {
        free(buf);
        return sss_error_set(err, SSS_ERROR_IO, "%s: read error", path);
    }
    buf[len] = '\0';
    *data = buf;
    *size = (size_t)len;
    return SSS_OK;
}

int sss_temp_path(const char *path, char *tmp, size_t cap)
{
    const char *slash = strrchr(path, '/');
    size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
    int n = snprintf(tmp, cap, "%.*s.%s.tmp-%ld", (int)dir_len, path, slash ? slash + 1 : path,
                     (long)getpid());
    return n > 0 && (size_t)n < cap;
}

sss_result sss_commit_temp(const char *tmp, const char *path, sss_error *err)
{
    if (rename(tmp, path) != 0) {
        int e = errno;
        remove(tmp);
        return sss_error_set(err, SSS_ERROR_IO, "%s: cannot write: %s", path, strerror(e));
    }
    return SSS_OK;
}

void sss_discard_temp(const char *tmp) { remove(tmp); }

FILE *sss_atomic_open(const char *path, char *tmp, size_t cap, sss_error *err)
{
    if (!sss_temp_path(path, tmp, cap)) {
        sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: path too long", path);
        return NULL;
    }
    FILE *f = fopen(tmp, "wb");
    if (!f) sss_error_set(err, SSS_ERROR_IO, "%s: cannot write: %s", path, strerror(errno));
    return f;
}

sss_result sss_atomic_close(FILE *f, const char *tmp, const char *path, sss_error *err)
{
    int bad = ferror(f);
    if (fclose(f) != 0) bad = 1;
    if (bad) {
        sss_discard_temp(tmp);
        return sss_error_set(err, SSS_ERROR_IO, "%s: write error (disk full?)", path);
    }
    return sss_commit_temp(tmp, path, err);
}

void sss_path_extension(const char *path, char *out, size_t cap)
{
    if (cap == 0) return;
    out[0] = '\0';
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(path, '.');
    if (!dot || (slash && dot < slash)) return;
    size_t i = 0;
    for (const char *p = dot + 1; *p && i + 1 < cap; p++) out[i++] = (char)tolower((unsigned char)*p);
    out[i] = '\0';
}
