/* Placeholder until the export command lands (replaced by its module's owner). */
#include "cli/cli.h"
int sss_cmd_export(int argc, char **argv)
{
    (void)argc; (void)argv;
    return cli_failf("export", "not built yet");
}
