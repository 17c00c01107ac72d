/* Placeholder until the kernel command lands (replaced by its module's owner). */
#include "cli/cli.h"
int sss_cmd_kernel(int argc, char **argv)
{
    (void)argc; (void)argv;
    return cli_failf("kernel", "not built yet");
}
