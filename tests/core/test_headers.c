/* Every public header compiles on its own and all together under strict C11 (this file includes the
 * umbrella header; the build's -Wall -Wextra -Wpedantic -Werror applies). */
#include "sss/sss.h"

#include "check.h"

int main(void)
{
    CHECK(SSS_OK == 0);
    CHECK(sizeof(sss_error) >= SSS_ERROR_MESSAGE_SIZE);
    return CHECK_DONE();
}
