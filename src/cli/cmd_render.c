/* Placeholder until the render command lands (replaced by its module's owner). */
#include "cli/cli.h"
int sss_cmd_render(int argc, char **argv)
{
    (void)argc; (void)argv;
    return cli_failf("render", "not built yet");
}
