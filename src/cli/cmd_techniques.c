/* Placeholder until the techniques command lands (replaced by its module's owner). */
#include "cli/cli.h"
int sss_cmd_techniques(int argc, char **argv)
{
    (void)argc; (void)argv;
    return cli_failf("techniques", "not built yet");
}
