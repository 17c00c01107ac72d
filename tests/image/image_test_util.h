/* tests/image/image_test_util.h — small file helpers shared by the image tests. */
#ifndef SSS_IMAGE_TEST_UTIL_H
#define SSS_IMAGE_TEST_UTIL_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A fresh empty folder under /tmp; its path is written to dir (cap >= 64). */
static inline int make_temp_dir(char *dir, size_t cap)
{
    snprintf(dir, cap, "/tmp/sss_image_test_XXXXXX");
    return mkdtemp(dir) != NULL;
}

/* Number of entries in dir other than . and .. (or -1). */
static inline int count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) n++;
    closedir(d);
    return n;
}

/* Removes every file in dir, then dir itself. */
static inline void remove_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    char path[4096];
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        remove(path);
    }
    closedir(d);
    rmdir(dir);
}

static inline unsigned char *slurp(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *buf = malloc(n > 0 ? (size_t)n : 1);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    *size = (size_t)n;
    return buf;
}

static inline int spit(const char *path, const void *data, size_t size)
{
    remove(path); /* rather than truncate: ext4 flushes truncated-and-rewritten files on close */
    FILE *f = fopen(path, "wb");
    if (!f) return 0;
    int ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok;
}

static inline int file_exists(const char *path) { return access(path, F_OK) == 0; }

#endif
