/* Every number of every scene seed (fuzz/corpus/scene/), replaced in turn by each value at the edges
 * of the double range, goes through the scene fuzz target's checks (fuzz/fuzz_harness.c): the scene
 * is refused with an error naming it, or it loads well formed (finite matrices, unit directions,
 * unit normals, ...). The fuzzers found two of these classes by chance (a subnormal scale in CI,
 * session 3); this walks them all deterministically: sqrt(x^2 + ...) overflowing near DBL_MAX,
 * 1 / subnormal, degrees overflowing to inf radians, float positions underflowing to 0. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "check.h"
#include "../../fuzz/fuzz_harness.c"

static const double extremes[] = {1e308, -1e308, 1e300, 1e-300, -1e-300, 2.2250738585072014e-308, 1e-320,
                                  -1e-320, 4.9406564584124654e-324, 1e19, 1e-19, 3.5e38, 1e-39};
enum { EXTREME_COUNT = sizeof extremes / sizeof extremes[0] };

/* Collects the number nodes of a JSON tree (depth first) into nodes[0..*n). */
static void collect_numbers(cJSON *item, cJSON **nodes, int cap, int *n)
{
    for (; item; item = item->next) {
        if (cJSON_IsNumber(item) && *n < cap) nodes[(*n)++] = item;
        collect_numbers(item->child, nodes, cap, n);
    }
}

static char *slurp_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *b = calloc(1, 1 << 20);
    size_t n = b ? fread(b, 1, (1 << 20) - 1, f) : 0;
    (void)n;
    fclose(f);
    return b;
}

int main(void)
{
    sss_fuzz_set_fixtures(SSS_SOURCE_DIR "/fuzz/fixtures");
    const char *dir = SSS_SOURCE_DIR "/fuzz/corpus/scene";
    DIR *d = opendir(dir);
    CHECK_MSG(d != NULL, "cannot open %s", dir);
    if (!d) return CHECK_DONE();
    int seeds = 0, variants = 0, failures = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.') continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        char *text = slurp_text(path);
        CHECK_MSG(text != NULL, "cannot read %s", path);
        cJSON *root = text ? cJSON_Parse(text) : NULL;
        free(text);
        if (!root) continue; /* seeds that are not JSON test the syntax errors, not the values */
        seeds++;
        cJSON *nodes[4096];
        int n = 0;
        collect_numbers(root, nodes, 4096, &n);
        for (int i = 0; i < n; i++) {
            double keep = nodes[i]->valuedouble;
            for (int k = 0; k < EXTREME_COUNT; k++) {
                cJSON_SetNumberValue(nodes[i], extremes[k]);
                char *json = cJSON_PrintUnformatted(root);
                CHECK(json != NULL);
                if (!json) continue;
                const char *bad = sss_fuzz_scene((const uint8_t *)json, strlen(json));
                variants++;
                if (bad && failures++ < 20) CHECK_MSG(0, "%s, number %d set to %g: %s", e->d_name, i, extremes[k], bad);
                free(json);
            }
            cJSON_SetNumberValue(nodes[i], keep);
        }
        cJSON_Delete(root);
    }
    closedir(d);
    CHECK_MSG(failures == 0, "%d of %d variants broke a promise", failures, variants);
    CHECK_MSG(seeds >= 5, "only %d JSON seeds in %s", seeds, dir);
    printf("%d seeds, %d variants with extreme numbers\n", seeds, variants);
    return CHECK_DONE();
}
