#include "core/file_util.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* ---- Reading ---------------------------------------------------------------------------------- */

int sss_open_input(const char *path, uint64_t max_size, uint64_t *size, sss_error *err)
{
    if (size) *size = 0;
    /* O_NONBLOCK: opening a FIFO without a writer would otherwise wait forever; the type is
     * checked on the open descriptor (no window between a check and the open). */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) {
        sss_error_set(err, SSS_ERROR_IO, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        int folder = S_ISDIR(st.st_mode);
        close(fd);
        sss_error_set(err, SSS_ERROR_IO, "%s: not a regular file%s", path, folder ? " (a folder)" : "");
        return -1;
    }
    if ((uint64_t)st.st_size > max_size) {
        close(fd);
        sss_error_set(err, SSS_ERROR_LIMIT, "%s: file is %lld bytes, larger than the %llu accepted", path,
                      (long long)st.st_size, (unsigned long long)max_size);
        return -1;
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0) {
        close(fd);
        sss_error_set(err, SSS_ERROR_IO, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    if (size) *size = (uint64_t)st.st_size;
    return fd;
}

FILE *sss_fopen_input(const char *path, uint64_t max_size, uint64_t *size, sss_error *err)
{
    int fd = sss_open_input(path, max_size, size, err);
    if (fd < 0) return NULL;
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: cannot open: %s", path, strerror(errno));
        close(fd);
    }
    return f;
}

sss_result sss_read_file(const char *path, size_t max_size, char **data, size_t *size, sss_error *err)
{
    *data = NULL;
    *size = 0;
    uint64_t len = 0;
    FILE *f = sss_fopen_input(path, max_size, &len, err);
    if (!f) return err ? err->code : SSS_ERROR_IO;
    char *buf = malloc((size_t)len + 1);
    if (!buf) {
        fclose(f);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory reading %llu bytes", path,
                             (unsigned long long)len);
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

/* ---- Writing ---------------------------------------------------------------------------------- */

static _Thread_local sss_outputs *active_outputs;

/* 12 letters from a 64-bit mix of the clock, the pid and a counter: unpredictable enough that a
 * planted name is unlikely, and O_EXCL makes a planted one harmless (another name is tried). */
static void random_suffix(char out[13])
{
    static const char letters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    static _Thread_local uint64_t counter;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t x = (uint64_t)ts.tv_nsec ^ (uint64_t)ts.tv_sec << 30 ^ (uint64_t)getpid() << 40;
    x ^= ++counter * 0x9e3779b97f4a7c15ull;
    for (int i = 0; i < 12; i++) {
        x ^= x >> 30; /* splitmix64's finaliser per letter */
        x *= 0xbf58476d1ce4e5b9ull;
        x ^= x >> 27;
        out[i] = letters[x % (sizeof letters - 1)];
    }
    out[12] = '\0';
}

static char *dup_string(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

/* Appends a copy of dir to t->dirs (the folders t created). */
static sss_result record_dir(sss_outputs *t, const char *dir, sss_error *err)
{
    if (t->dir_count == t->dir_capacity) {
        size_t cap = t->dir_capacity ? 2 * t->dir_capacity : 4;
        char **grown = realloc(t->dirs, cap * sizeof *grown);
        if (!grown) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", dir);
        t->dirs = grown;
        t->dir_capacity = cap;
    }
    if (!(t->dirs[t->dir_count] = dup_string(dir)))
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", dir);
    t->dir_count++;
    return SSS_OK;
}

/* Creates dir (malloc'd, written in place) level by level, recording in t each folder made here; a
 * level that exists must be a folder (mkdir never replaces or follows into a file). */
static sss_result make_folders(sss_outputs *t, char *dir, const char *path, sss_error *err)
{
    for (char *p = dir + 1;; p++) {
        if (*p != '/' && *p != '\0') continue;
        char end = *p;
        *p = '\0';
        struct stat st;
        int made = 0;
        if (stat(dir, &st) != 0) {
            made = mkdir(dir, 0777) == 0;
            int e = errno;
            if (!made && (e != EEXIST || stat(dir, &st) != 0)) /* EEXIST: made by another process meanwhile */
                return sss_error_set(err, SSS_ERROR_IO, "%s: cannot create the folder %s: %s", path, dir, strerror(e));
        }
        if (!made && !S_ISDIR(st.st_mode))
            return sss_error_set(err, SSS_ERROR_IO, "%s: cannot write: %s is not a folder", path, dir);
        sss_result r = made ? record_dir(t, dir, err) : SSS_OK;
        if (r != SSS_OK) return r;
        *p = end;
        if (!end) return SSS_OK;
    }
}

/* The missing folder of an output (its open failed with ENOENT): created, level by level, when the
 * active transaction asks for it (its folders, removed when it aborts); else an error naming it. */
static sss_result missing_folder(const char *path, sss_error *err)
{
    const char *slash = strrchr(path, '/');
    if (!slash || slash == path) return sss_error_set(err, SSS_ERROR_IO, "%s: cannot write: %s", path, strerror(ENOENT));
    char *dir = malloc((size_t)(slash - path) + 1);
    if (!dir) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    memcpy(dir, path, (size_t)(slash - path));
    dir[slash - path] = '\0';
    sss_result r = active_outputs && active_outputs->create_folders
                       ? make_folders(active_outputs, dir, path, err)
                       : sss_error_set(err, SSS_ERROR_IO, "%s: cannot write: the folder %s does not exist", path, dir);
    free(dir);
    return r;
}

FILE *sss_atomic_open(const char *path, char *tmp, size_t cap, sss_error *err)
{
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        sss_error_set(err, SSS_ERROR_IO, "%s: cannot write: is a folder", path);
        return NULL;
    }
    const char *slash = strrchr(path, '/');
    size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
    int folder_made = 0;
    for (int attempt = 0; attempt < 64; attempt++) {
        char suffix[13];
        random_suffix(suffix);
        int n = snprintf(tmp, cap, "%.*s.%s.tmp-%s", (int)dir_len, path, slash ? slash + 1 : path, suffix);
        if (n <= 0 || (size_t)n >= cap) {
            sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: path too long", path);
            return NULL;
        }
        int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd < 0 && errno == EEXIST) continue;
        if (fd < 0 && errno == ENOENT && !folder_made) { /* a folder of the path is missing */
            if (missing_folder(path, err) != SSS_OK) return NULL;
            folder_made = 1;
            attempt--;
            continue;
        }
        if (fd < 0) {
            sss_error_set(err, SSS_ERROR_IO, "%s: cannot write: %s", path, strerror(errno));
            return NULL;
        }
        FILE *f = fdopen(fd, "wb");
        if (!f) {
            sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: cannot write: %s", path, strerror(errno));
            close(fd);
            remove(tmp);
        }
        return f;
    }
    sss_error_set(err, SSS_ERROR_IO, "%s: cannot create a temporary file beside it", path);
    return NULL;
}

static sss_result staging_failed(sss_outputs *t, const char *tmp, const char *path, sss_error *err)
{
    remove(tmp);
    t->failure = SSS_ERROR_OUT_OF_MEMORY;
    return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
}

/* Adds (tmp, path) to the active transaction; a path staged before is replaced by the newer file. */
static sss_result stage(sss_outputs *t, const char *tmp, const char *path, sss_error *err)
{
    char *name = dup_string(tmp);
    if (!name) return staging_failed(t, tmp, path, err);
    for (size_t i = 0; i < t->count; i++)
        if (strcmp(t->items[i].path, path) == 0) {
            remove(t->items[i].tmp);
            free(t->items[i].tmp);
            t->items[i].tmp = name;
            return SSS_OK;
        }
    if (t->count == t->capacity) {
        size_t cap = t->capacity ? 2 * t->capacity : 8;
        sss_staged_output *items = realloc(t->items, cap * sizeof *items);
        if (items) {
            t->items = items;
            t->capacity = cap;
        }
    }
    char *target = t->count < t->capacity ? dup_string(path) : NULL;
    if (!target) {
        free(name);
        return staging_failed(t, tmp, path, err);
    }
    t->items[t->count++] = (sss_staged_output){name, target};
    return SSS_OK;
}

sss_result sss_commit_temp(const char *tmp, const char *path, sss_error *err)
{
    if (active_outputs) return stage(active_outputs, tmp, path, err);
    if (rename(tmp, path) != 0) {
        int e = errno;
        remove(tmp);
        return sss_error_set(err, SSS_ERROR_IO, "%s: cannot write: %s", path, strerror(e));
    }
    return SSS_OK;
}

void sss_discard_temp(const char *tmp) { remove(tmp); }

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

void sss_outputs_begin(sss_outputs *t)
{
    memset(t, 0, sizeof *t);
    t->outer = active_outputs;
    active_outputs = t;
}

/* Renames every staged file, after checking every target first, so that a folder in the way fails
 * before any output is replaced (renames within one folder fail for no other ordinary reason). */
static sss_result rename_all(sss_outputs *t, sss_error *err)
{
    struct stat st;
    for (size_t i = 0; i < t->count; i++)
        if (stat(t->items[i].path, &st) == 0 && S_ISDIR(st.st_mode))
            return sss_error_set(err, SSS_ERROR_IO, "%s: cannot write: is a folder", t->items[i].path);
    for (size_t i = 0; i < t->count; i++) {
        if (rename(t->items[i].tmp, t->items[i].path) != 0)
            return sss_error_set(err, SSS_ERROR_IO, "%s: cannot write: %s", t->items[i].path, strerror(errno));
        t->items[i].tmp[0] = '\0'; /* renamed: nothing to remove */
    }
    return SSS_OK;
}

/* The folders t created: handed to the outer transaction (kept) on commit, removed deepest first
 * otherwise (rmdir: only while empty, so nothing another writer put there goes). */
static void end_folders(sss_outputs *t, int commit, sss_error *err)
{
    for (size_t i = t->dir_count; !commit && i-- > 0;) rmdir(t->dirs[i]);
    for (size_t i = 0; i < t->dir_count; i++) {
        if (commit && t->outer) record_dir(t->outer, t->dirs[i], err); /* out of memory: the folder stays */
        free(t->dirs[i]);
    }
    free(t->dirs);
    t->dirs = NULL;
    t->dir_count = t->dir_capacity = 0;
}

const char *sss_outputs_current_path(const char *path)
{
    for (const sss_outputs *t = active_outputs; t; t = t->outer)
        for (size_t i = t->count; i-- > 0;)
            if (strcmp(t->items[i].path, path) == 0) return t->items[i].tmp;
    return path;
}

sss_result sss_outputs_end(sss_outputs *t, int commit, sss_error *err)
{
    if (active_outputs == t) active_outputs = t->outer;
    sss_result r = commit ? t->failure : SSS_OK;
    if (r != SSS_OK) sss_error_set(err, r, "out of memory staging the outputs");
    /* Nested: the outer transaction takes the files over. */
    for (size_t i = 0; commit && r == SSS_OK && t->outer && i < t->count; i++) {
        r = stage(t->outer, t->items[i].tmp, t->items[i].path, err);
        t->items[i].tmp[0] = '\0';
    }
    if (commit && r == SSS_OK && !t->outer) r = rename_all(t, err);
    for (size_t i = 0; i < t->count; i++) {
        if (t->items[i].tmp[0]) remove(t->items[i].tmp);
        free(t->items[i].tmp);
        free(t->items[i].path);
    }
    free(t->items);
    t->items = NULL;
    t->count = t->capacity = 0;
    end_folders(t, commit && r == SSS_OK, err);
    return r;
}

sss_result sss_check_output_not_input(const char *output, const char *const *inputs, size_t input_count,
                                      sss_error *err)
{
    struct stat out, in;
    if (!output || stat(output, &out) != 0) return SSS_OK;
    for (size_t i = 0; i < input_count; i++)
        if (inputs[i] && stat(inputs[i], &in) == 0 && in.st_dev == out.st_dev && in.st_ino == out.st_ino)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "%s: is the same file as the input %s; refusing to overwrite an input", output,
                                 inputs[i]);
    return SSS_OK;
}

/* ---- A command's inputs and outputs ------------------------------------------------------------- */

static void io_add(char ***list, size_t *count, size_t *cap, int *oom, const char *path)
{
    if (!path) return;
    if (*count == *cap) {
        size_t n = *cap ? 2 * *cap : 16;
        char **grown = realloc(*list, n * sizeof *grown);
        if (!grown) {
            *oom = 1;
            return;
        }
        *list = grown;
        *cap = n;
    }
    char *copy = dup_string(path);
    if (!copy) *oom = 1;
    else (*list)[(*count)++] = copy;
}

void sss_io_add_input(sss_io_set *io, const char *path)
{
    io_add(&io->inputs, &io->input_count, &io->input_cap, &io->out_of_memory, path);
}

void sss_io_add_output(sss_io_set *io, const char *path)
{
    io_add(&io->outputs, &io->output_count, &io->output_cap, &io->out_of_memory, path);
}

/* The folder part of path ("." when it has none) into dir (cap bytes); returns its file name, or NULL
 * when the folder does not fit. */
static const char *split_path(const char *path, char *dir, size_t cap)
{
    const char *slash = strrchr(path, '/');
    size_t n = slash ? (size_t)(slash - path) + 1 : 0; /* "/" stays "/": the root keeps its slash */
    if (n == 0) n = (size_t)snprintf(dir, cap, ".");
    else if (n < cap) snprintf(dir, cap, "%.*s", (int)n, path);
    else return NULL;
    return slash ? slash + 1 : path;
}

/* Two outputs are one file when both exist as one inode, or when they name the same entry: equal
 * file names in one folder (the folders compared by device and inode when both exist). */
static int same_output(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    char da[4096], db[4096];
    const char *na = split_path(a, da, sizeof da), *nb = split_path(b, db, sizeof db);
    if (!na || !nb) return strcmp(a, b) == 0;
    if (strcmp(na, nb) != 0) return 0;
    if (stat(da, &sa) == 0 && stat(db, &sb) == 0) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    return strcmp(da, db) == 0;
}

sss_result sss_io_check(const sss_io_set *io, sss_error *err)
{
    if (io->out_of_memory) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory listing the files");
    for (size_t i = 0; i < io->output_count; i++) {
        const char *const *inputs = (const char *const *)io->inputs;
        sss_result r = sss_check_output_not_input(io->outputs[i], inputs, io->input_count, err);
        if (r != SSS_OK) return r;
        for (size_t j = 0; j < i; j++)
            if (same_output(io->outputs[j], io->outputs[i]))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                     "%s: is the same file as the output %s; refusing to write one output over "
                                     "another",
                                     io->outputs[i], io->outputs[j]);
    }
    return SSS_OK;
}

void sss_io_free(sss_io_set *io)
{
    for (size_t i = 0; i < io->input_count; i++) free(io->inputs[i]);
    for (size_t i = 0; i < io->output_count; i++) free(io->outputs[i]);
    free(io->inputs);
    free(io->outputs);
    memset(io, 0, sizeof *io);
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
