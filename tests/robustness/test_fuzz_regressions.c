/* Replays every fuzzer finding (tests/data/fuzz-regressions/<target>/) and every seed (fuzz/corpus/
 * <target>/) through the fuzz targets' own checks (fuzz/fuzz_harness.c), in the normal build: each
 * input must be accepted or refused as the library promises (well-formed result, or an error naming
 * the input with an empty output). Under `make sanitize` this also re-checks memory safety and leaks.
 * The inputs are files whose bytes the fuzzer found; see fuzz/README.md for what each one was.
 * A regression named open-* is a bug found in a module whose owner has not fixed it yet: it is run and
 * reported (OPEN) without failing the test; once it passes, the test says so (drop the prefix then). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "../../fuzz/fuzz_harness.c"

static unsigned char *slurp(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, n = 0;
    unsigned char *b = malloc(cap);
    size_t got;
    while (b && (got = fread(b + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            unsigned char *g = realloc(b, cap *= 2);
            if (!g) free(b);
            b = g;
        }
    }
    fclose(f);
    *size = n;
    return b;
}

/* Runs fn on every regular file of dir; returns how many there were (0 when dir is absent). */
static int open_bugs, fixed_bugs;

static int replay_dir(const sss_fuzz_target *t, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int count = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.' || strcmp(e->d_name, "README.md") == 0) continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        size_t size = 0;
        unsigned char *data = slurp(path, &size);
        CHECK_MSG(data != NULL, "cannot read %s", path);
        if (!data) continue;
        const char *bad = t->fn(data, size);
        if (strncmp(e->d_name, "open-", 5) == 0) {
            if (bad) {
                open_bugs++;
                printf("OPEN: %s (%s target): %s\n", path, t->name, bad);
            } else {
                fixed_bugs++;
                printf("FIXED: %s now passes: rename it without 'open-'\n", path);
            }
        } else {
            CHECK_MSG(bad == NULL, "%s (%s target): %s", path, t->name, bad);
        }
        free(data);
        count++;
    }
    closedir(d);
    return count;
}

int main(void)
{
    sss_fuzz_set_fixtures(SSS_SOURCE_DIR "/fuzz/fixtures");
    int regressions = 0, seeds = 0;
    for (size_t i = 0; i < sss_fuzz_target_count; i++) {
        const sss_fuzz_target *t = &sss_fuzz_targets[i];
        char dir[1024];
        snprintf(dir, sizeof dir, "%s/fuzz-regressions/%s", SSS_TEST_DATA, t->name);
        regressions += replay_dir(t, dir);
        snprintf(dir, sizeof dir, "%s/fuzz/corpus/%s", SSS_SOURCE_DIR, t->name);
        int n = replay_dir(t, dir);
        CHECK_MSG(n > 0, "no seeds for the %s target in %s", t->name, dir);
        seeds += n;
    }
    printf("replayed %d regression inputs (%d open bugs, %d fixed) and %d seeds\n", regressions, open_bugs,
           fixed_bugs, seeds);
    return CHECK_DONE();
}
