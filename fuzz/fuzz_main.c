/* fuzz/fuzz_main.c — the libFuzzer entry point; SSS_FUZZ_FN names the harness function of this binary
 * (fuzz/CMakeLists.txt builds one binary per target). A broken promise aborts with its description,
 * so libFuzzer saves the input as a crash. */
#include <stdio.h>
#include <stdlib.h>

#include "fuzz_harness.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    sss_fuzz_set_fixtures(SSS_FUZZ_FIXTURES);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *bad = SSS_FUZZ_FN(data, size);
    if (bad) {
        fprintf(stderr, "sss fuzz: broken promise: %s\n", bad);
        abort();
    }
    return 0;
}
