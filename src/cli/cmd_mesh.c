/* Placeholder until the mesh command lands (replaced by its module's owner). */
#include "cli/cli.h"
int sss_cmd_mesh(int argc, char **argv)
{
    (void)argc; (void)argv;
    return cli_failf("mesh", "not built yet");
}
