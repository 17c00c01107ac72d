/* Placeholder until the reference command lands (replaced by its module's owner). */
#include "cli/cli.h"
int sss_cmd_reference(int argc, char **argv)
{
    (void)argc; (void)argv;
    return cli_failf("reference", "not built yet");
}
