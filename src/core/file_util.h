/* core/file_util.h — file helpers shared by the modules (internal, not public API).
 *
 * Reading: every reader opens its input with sss_open_input (or sss_fopen_input, sss_read_file),
 * which never blocks: a FIFO, folder or device is refused as "PATH: not a regular file" before a
 * single byte is read, and the size is checked against the reader's limit before anything is
 * allocated.
 *
 * Writing: every writer goes through sss_atomic_open / sss_atomic_close (or sss_commit_temp): the
 * bytes go to a temporary file created exclusively (O_CREAT|O_EXCL|O_NOFOLLOW, a fresh random name) in
 * the output's folder, so a planted symlink is never followed, and are renamed over the output only
 * when complete. Inside an output transaction (sss_outputs_begin on the calling thread) the renames
 * wait for sss_outputs_end: a command with several outputs leaves all of them or none. A transaction
 * that sets create_folders also creates its outputs' missing folders (mkdir, one level at a time, never
 * through a file) and removes them again (when empty) if it aborts; elsewhere a missing folder is an
 * error naming it.
 */
#ifndef SSS_CORE_FILE_UTIL_H
#define SSS_CORE_FILE_UTIL_H

#include <stdint.h>
#include <stdio.h>

#include "sss/common.h"

/* No size limit of the reader's own (it checks that the header is backed by data instead). */
#define SSS_FILE_ANY_SIZE UINT64_MAX

/* Opens path read-only without blocking (O_NONBLOCK|O_NOCTTY|O_CLOEXEC), refuses anything but a
 * regular file and a file larger than max_size (SSS_ERROR_LIMIT), then returns the descriptor in
 * blocking mode with *size (may be NULL) set; -1 with err set on failure. Messages name the path. */
int sss_open_input(const char *path, uint64_t max_size, uint64_t *size, sss_error *err);
/* The same as a stdio stream ("rb"); NULL on failure. */
FILE *sss_fopen_input(const char *path, uint64_t max_size, uint64_t *size, sss_error *err);

/* Reads a whole file through sss_open_input. *data is NUL-terminated (one byte beyond *size) and
 * must be released with free(). */
sss_result sss_read_file(const char *path, size_t max_size, char **data, size_t *size, sss_error *err);

/* Opens a new temporary file for an atomic write of path ("wb"); tmp (cap >= 4096 recommended)
 * receives its name. Refuses a path that is a folder. A missing folder of path is created when the active
 * transaction has create_folders set, else refused ("PATH: cannot write: the folder DIR does not
 * exist"). Close the FILE yourself, then commit or discard, or use sss_atomic_close. */
FILE *sss_atomic_open(const char *path, char *tmp, size_t cap, sss_error *err);
/* Renames tmp to path (inside an output transaction: at its end); on failure removes tmp and reports
 * an error naming path. */
sss_result sss_commit_temp(const char *tmp, const char *path, sss_error *err);
void sss_discard_temp(const char *tmp);
/* fclose(f), checking for write errors, then sss_commit_temp (or discard on any error). */
sss_result sss_atomic_close(FILE *f, const char *tmp, const char *path, sss_error *err);

/* An output transaction: the files committed on this thread between begin and end are staged, and
 * end renames all of them (commit != 0) or removes all of them. A transaction begun inside another
 * hands its files to the outer one on commit (a library call with several outputs inside a command). */
typedef struct sss_staged_output {
    char *tmp, *path;
} sss_staged_output;
typedef struct sss_outputs {
    sss_staged_output *items;
    size_t count, capacity;
    int create_folders; /* set after begin: missing folders of the outputs are created (and are the
                         * transaction's: kept on commit, removed on abort) */
    char **dirs;        /* the folders this transaction created, outermost first */
    size_t dir_count, dir_capacity;
    sss_result failure; /* a staging step that failed (out of memory): end does not commit */
    struct sss_outputs *outer;
} sss_outputs;
void sss_outputs_begin(sss_outputs *t);
sss_result sss_outputs_end(sss_outputs *t, int commit, sss_error *err);
/* Where the content written to path is now: its staged temporary file while a transaction on this
 * thread holds it back, else path itself (a command that reads back what it wrote, as eval's report
 * embeds its sheets). */
const char *sss_outputs_current_path(const char *path);

/* Refuses (SSS_ERROR_INVALID_ARGUMENT) an output that is the same file (device and inode: also
 * through other spellings, symlinks or hard links) as one of the inputs; NULL inputs are skipped.
 * An output that does not exist yet is fine. */
sss_result sss_check_output_not_input(const char *output, const char *const *inputs, size_t input_count,
                                      sss_error *err);

/* A command's files: every file it reads (inputs) and every file it writes (outputs), collected
 * before it writes anything and checked against each other by sss_io_check. Zero-initialise it; the
 * paths are copied, NULL ones skipped; release with sss_io_free. */
typedef struct sss_io_set {
    char **inputs, **outputs;
    size_t input_count, output_count, input_cap, output_cap;
    int out_of_memory; /* an add failed: sss_io_check reports it */
} sss_io_set;
void sss_io_add_input(sss_io_set *io, const char *path);
void sss_io_add_output(sss_io_set *io, const char *path);
/* Refuses (SSS_ERROR_INVALID_ARGUMENT, naming both files) an output that is the same file as an input
 * (sss_check_output_not_input) or as another output: the same existing file (device and inode), or
 * the same name in the same folder however spelled ("a.png", "./a.png", "d/../a.png"), which an
 * output transaction would rename twice, keeping only the last. */
sss_result sss_io_check(const sss_io_set *io, sss_error *err);
void sss_io_free(sss_io_set *io);

/* The extension of path in lower case without the dot ("" when there is none); out has cap bytes. */
void sss_path_extension(const char *path, char *out, size_t cap);

#endif
