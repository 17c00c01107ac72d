/* sss_median: the middle value of an odd count, the mean of the middle two of an even count, 0 for no
 * values; the values end up sorted (callers read the extremes from them). */
#include "check.h"
#include "sss/common.h"

int main(void)
{
    double odd[5] = {7.0, -1.0, 3.0, 3.0, 10.0};
    CHECK(sss_median(odd, 5) == 3.0);
    for (int i = 1; i < 5; i++) CHECK(odd[i - 1] <= odd[i]);
    CHECK(odd[0] == -1.0 && odd[4] == 10.0);
    double even[4] = {4.0, 1.0, 3.0, 2.0};
    CHECK(sss_median(even, 4) == 2.5);
    double one = 42.0;
    CHECK(sss_median(&one, 1) == 42.0);
    CHECK(sss_median(NULL, 0) == 0.0);
    CHECK(sss_median(even, -3) == 0.0);
    return CHECK_DONE();
}
