/* core/version.c — the library's version, fixed when the library is compiled (sss/version.h). */
#include "sss/version.h"

const char *sss_version(void) { return SSS_VERSION_STRING; }

int sss_version_number(void) { return SSS_VERSION_NUMBER; }
