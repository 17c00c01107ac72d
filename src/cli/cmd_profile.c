/* Placeholder until the profile command lands (replaced by its module's owner). */
#include "cli/cli.h"
int sss_cmd_profile(int argc, char **argv)
{
    (void)argc; (void)argv;
    return cli_failf("profile", "not built yet");
}
