/* File helpers: whole-file reads honour the size limit, atomic writes leave either the complete new
 * file or nothing, extensions are lower-cased; inputs that are not regular files fail without
 * blocking; output transactions rename all their files or none and, when asked, create the missing
 * folders of their outputs (removed again when they abort); outputs that are inputs are found. */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "core/file_util.h"

/* Entries in dir (. and .. excluded). */
static int count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));) n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    if (d) closedir(d);
    return n;
}

static int write_atomic(const char *path, const char *text, sss_error *err)
{
    char tmp[4096];
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) return 0;
    fputs(text, f);
    return sss_atomic_close(f, tmp, path, err) == SSS_OK;
}

static int has_text(const char *path, const char *text)
{
    char *data = NULL;
    size_t size = 0;
    int same = sss_read_file(path, 1000, &data, &size, NULL) == SSS_OK && strcmp(data, text) == 0;
    free(data);
    return same;
}

/* A FIFO without a writer: the old fopen waited forever (the alarm turns a hang into a failure). */
static void test_fifo(const char *dir)
{
    char fifo[512];
    snprintf(fifo, sizeof fifo, "%s/pipe.json", dir);
    CHECK(mkfifo(fifo, 0600) == 0);
    alarm(10);
    sss_error err = {0};
    char *data = NULL;
    size_t size = 0;
    CHECK(sss_read_file(fifo, 100, &data, &size, &err) == SSS_ERROR_IO);
    CHECK_MSG(strstr(err.message, "pipe.json: not a regular file") != NULL, "%s", err.message);
    CHECK(sss_fopen_input(fifo, SSS_FILE_ANY_SIZE, NULL, &err) == NULL);
    CHECK(sss_open_input(dir, SSS_FILE_ANY_SIZE, NULL, &err) < 0 && strstr(err.message, "not a regular file"));
    alarm(0);
    remove(fifo);
}

/* Commit renames every staged file; abort removes them; a nested transaction hands its files over;
 * nothing reaches the final names before the end, and no temporary file is left either way. */
static void test_transaction(const char *dir)
{
    char a[512], b[512];
    snprintf(a, sizeof a, "%s/a.txt", dir);
    snprintf(b, sizeof b, "%s/b.txt", dir);
    sss_error err = {0};
    sss_outputs t, inner;
    sss_outputs_begin(&t);
    CHECK(write_atomic(a, "one", &err));
    sss_outputs_begin(&inner);
    CHECK(write_atomic(b, "two", &err));
    CHECK(sss_outputs_end(&inner, 1, &err) == SSS_OK);
    CHECK(access(a, F_OK) != 0 && access(b, F_OK) != 0);
    CHECK(sss_outputs_end(&t, 0, &err) == SSS_OK); /* abort */
    CHECK(count_entries(dir) == 0);

    sss_outputs_begin(&t);
    CHECK(write_atomic(a, "one", &err));
    CHECK(write_atomic(a, "one again", &err)); /* the newer file replaces the staged one */
    CHECK(write_atomic(b, "two", &err));
    CHECK(sss_outputs_end(&t, 1, &err) == SSS_OK);
    CHECK(has_text(a, "one again") && has_text(b, "two"));
    CHECK(count_entries(dir) == 2);

    /* A folder appears in the way of the second file before the end: the first is not replaced
     * either, and both temporary files go. */
    remove(b);
    sss_outputs_begin(&t);
    CHECK(write_atomic(a, "three", &err));
    CHECK(write_atomic(b, "four", &err));
    CHECK(mkdir(b, 0700) == 0);
    CHECK(sss_outputs_end(&t, 1, &err) == SSS_ERROR_IO);
    CHECK_MSG(strstr(err.message, "b.txt: cannot write: is a folder") != NULL, "%s", err.message);
    CHECK(has_text(a, "one again"));
    CHECK(count_entries(dir) == 2);
    rmdir(b);
    remove(a);
}

/* A transaction with create_folders creates an output's missing folders (sss import -o newdir/scene.json
 * used to fail): kept on commit, also through a nested transaction, removed on abort; never through a
 * file. Elsewhere a missing folder is an error naming it. */
static void test_missing_folders(const char *dir)
{
    char deep[512], top[512], file[512], under_file[512];
    snprintf(top, sizeof top, "%s/new", dir);
    snprintf(deep, sizeof deep, "%s/new/sub/x.txt", dir);
    snprintf(file, sizeof file, "%s/plain.txt", dir);
    snprintf(under_file, sizeof under_file, "%s/plain.txt/sub/y.txt", dir);
    sss_error err = {0};
    sss_outputs t, inner;
    CHECK(!write_atomic(deep, "x", &err)); /* no transaction: refused, the folder named */
    CHECK_MSG(strstr(err.message, "x.txt: cannot write: the folder") && strstr(err.message, "new/sub does not exist"),
              "%s", err.message);
    sss_outputs_begin(&t); /* a transaction that does not ask for folders: the same */
    CHECK(!write_atomic(deep, "x", &err));
    CHECK(sss_outputs_end(&t, 1, &err) == SSS_OK);
    CHECK(count_entries(dir) == 0);

    sss_outputs_begin(&t);
    sss_outputs_begin(&inner);
    inner.create_folders = 1;
    CHECK_MSG(write_atomic(deep, "x", &err), "%s", err.message);
    CHECK(sss_outputs_end(&inner, 1, &err) == SSS_OK);
    CHECK(sss_outputs_end(&t, 0, &err) == SSS_OK); /* abort: the file and both folders go */
    CHECK(count_entries(dir) == 0);

    sss_outputs_begin(&t);
    t.create_folders = 1;
    CHECK_MSG(write_atomic(deep, "x", &err), "%s", err.message);
    CHECK(sss_outputs_end(&t, 1, &err) == SSS_OK);
    CHECK(has_text(deep, "x"));
    remove(deep);
    snprintf(deep, sizeof deep, "%s/new/sub", dir);
    rmdir(deep);
    rmdir(top);

    CHECK(write_atomic(file, "f", &err)); /* a file where a folder is needed: refused, not replaced */
    sss_outputs_begin(&t);
    t.create_folders = 1;
    CHECK(!write_atomic(under_file, "y", &err));
    CHECK_MSG(strstr(err.message, "y.txt: cannot write: Not a directory"), "%s", err.message);
    CHECK(sss_outputs_end(&t, 0, &err) == SSS_OK);
    CHECK(has_text(file, "f"));
    remove(file);
    CHECK(count_entries(dir) == 0);
}

/* The temporary file is new (O_EXCL): a symlink at an old-style name is never followed, and two
 * opens of one output get different names. */
static void test_temp_names(const char *dir)
{
    char path[512], tmp1[4096], tmp2[4096];
    snprintf(path, sizeof path, "%s/x.txt", dir);
    sss_error err = {0};
    FILE *f1 = sss_atomic_open(path, tmp1, sizeof tmp1, &err), *f2 = sss_atomic_open(path, tmp2, sizeof tmp2, &err);
    CHECK(f1 && f2 && strcmp(tmp1, tmp2) != 0);
    struct stat st;
    CHECK(lstat(tmp1, &st) == 0 && S_ISREG(st.st_mode) && st.st_size == 0);
    if (f1) fclose(f1);
    if (f2) fclose(f2);
    sss_discard_temp(tmp1);
    sss_discard_temp(tmp2);
    CHECK(count_entries(dir) == 0);
}

/* Same file: the path itself, another spelling, a hard link; a different file or a missing output
 * is not. */
static void test_same_file(const char *dir)
{
    char in[512], other[512], hard[512], spelled[512], missing[512];
    snprintf(in, sizeof in, "%s/in.txt", dir);
    snprintf(other, sizeof other, "%s/other.txt", dir);
    snprintf(hard, sizeof hard, "%s/hard.txt", dir);
    snprintf(spelled, sizeof spelled, "%s/./in.txt", dir);
    snprintf(missing, sizeof missing, "%s/missing.txt", dir);
    sss_error err = {0};
    CHECK(write_atomic(in, "in", &err) && write_atomic(other, "other", &err));
    CHECK(link(in, hard) == 0);
    const char *inputs[2] = {NULL, in};
    CHECK(sss_check_output_not_input(in, inputs, 2, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_check_output_not_input(spelled, inputs, 2, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_check_output_not_input(hard, inputs, 2, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "hard.txt: is the same file as the input") != NULL, "%s", err.message);
    CHECK(sss_check_output_not_input(other, inputs, 2, &err) == SSS_OK);
    CHECK(sss_check_output_not_input(missing, inputs, 2, &err) == SSS_OK);
    remove(in);
    remove(other);
    remove(hard);
}

/* A command's file set: two outputs that name one entry (spelled apart, not written yet) or one
 * existing file (a hard link) are refused, as is an output that is an input; distinct ones pass. */
static void test_io_set(const char *dir)
{
    char in[512], sub[512], a[512], a2[512], a3[512], b[512], hard[512];
    snprintf(in, sizeof in, "%s/in.txt", dir);
    snprintf(sub, sizeof sub, "%s/sub", dir);
    snprintf(a, sizeof a, "%s/a.png", dir);
    snprintf(a2, sizeof a2, "%s/./a.png", dir);
    snprintf(a3, sizeof a3, "%s/sub/../a.png", dir);
    snprintf(b, sizeof b, "%s/b.png", dir);
    snprintf(hard, sizeof hard, "%s/hard.png", dir);
    sss_error err = {0};
    CHECK(write_atomic(in, "in", &err) && mkdir(sub, 0777) == 0);
    const char *pairs[][2] = {{a, a}, {a, a2}, {a3, a}, {in, b}, {b, hard}};
    int refused[] = {1, 1, 1, 1, 0};
    for (int i = 0; i < 5; i++) {
        sss_io_set io = {0};
        sss_io_add_input(&io, in);
        sss_io_add_input(&io, NULL);
        sss_io_add_output(&io, pairs[i][0]);
        sss_io_add_output(&io, pairs[i][1]);
        sss_result r = sss_io_check(&io, &err);
        CHECK_MSG(r == (refused[i] ? SSS_ERROR_INVALID_ARGUMENT : SSS_OK), "pair %d: %s", i, err.message);
        sss_io_free(&io);
    }
    CHECK_MSG(strstr(err.message, "is the same file as the input") != NULL, "%s", err.message);
    CHECK(write_atomic(b, "b", &err) && link(b, hard) == 0); /* now one existing file */
    sss_io_set io = {0};
    sss_io_add_output(&io, b);
    sss_io_add_output(&io, hard);
    CHECK(sss_io_check(&io, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "hard.png: is the same file as the output") != NULL, "%s", err.message);
    sss_io_free(&io);
    remove(in);
    remove(b);
    remove(hard);
    rmdir(sub);
}

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
    CHECK(count_entries(dir) == 0);
    test_fifo(dir);
    test_transaction(dir);
    test_temp_names(dir);
    test_missing_folders(dir);
    test_same_file(dir);
    test_io_set(dir);
    rmdir(dir);
    return CHECK_DONE();
}
