/* Placeholder until the compare command lands (replaced by its module's owner). */
#include "cli/cli.h"
int sss_cmd_compare(int argc, char **argv)
{
    (void)argc; (void)argv;
    return cli_failf("compare", "not built yet");
}
