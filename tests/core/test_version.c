/* sss/version.h and sss_version(): the macros, the string and the run-time calls all give the
 * version that CMakeLists.txt declares in project(sss VERSION MAJOR.MINOR.PATCH), read here from the
 * file itself. */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "sss/sss.h"

/* Parses "project(sss VERSION a.b.c" from the top-level CMakeLists.txt; 1 on success. */
static int project_version(int *major, int *minor, int *patch)
{
    FILE *f = fopen(SSS_SOURCE_DIR "/CMakeLists.txt", "r");
    if (!f) return 0;
    char line[512];
    int found = 0;
    while (!found && fgets(line, sizeof line, f))
        found = sscanf(line, "project(sss VERSION %d.%d.%d", major, minor, patch) == 3;
    fclose(f);
    return found;
}

int main(void)
{
    int major = -1, minor = -1, patch = -1;
    CHECK_MSG(project_version(&major, &minor, &patch), "no project(sss VERSION ...) in CMakeLists.txt");
    CHECK(SSS_VERSION_MAJOR == major && SSS_VERSION_MINOR == minor && SSS_VERSION_PATCH == patch);

    char expected[64];
    snprintf(expected, sizeof expected, "%d.%d.%d", major, minor, patch);
    CHECK_MSG(strcmp(SSS_VERSION_STRING, expected) == 0, "SSS_VERSION_STRING %s, project %s", SSS_VERSION_STRING,
              expected);
    CHECK_MSG(strcmp(sss_version(), expected) == 0, "sss_version() %s, project %s", sss_version(), expected);
    CHECK(sss_version_number() == major * 10000 + minor * 100 + patch);
    CHECK(SSS_VERSION_NUMBER == sss_version_number());
    return CHECK_DONE();
}
