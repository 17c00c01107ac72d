/* Placeholder until the lut command lands (replaced by its module's owner). */
#include "cli/cli.h"
int sss_cmd_lut(int argc, char **argv)
{
    (void)argc; (void)argv;
    return cli_failf("lut", "not built yet");
}
