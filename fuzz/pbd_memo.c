/* fuzz/pbd_memo.c — fuzz builds only: memoises sss_pbd_table_build by (eta, g) through the linker's
 * --wrap, so the scene target spends its time in the loader rather than rebuilding the same ~25 ms
 * table for every input. The table is a deterministic function of (eta, g), so a copy is exactly
 * what a fresh build would return; failures are never cached (they are cheap). */
#include <stdint.h>
#include <string.h>

#include "sss/profile.h"

sss_result __real_sss_pbd_table_build(double eta, double g, sss_pbd_table *table, sss_error *err);
sss_result __wrap_sss_pbd_table_build(double eta, double g, sss_pbd_table *table, sss_error *err);

#define MEMO_SLOTS 8

static sss_pbd_table memo[MEMO_SLOTS];
static double memo_key[MEMO_SLOTS][2];
static int memo_used, memo_next;

sss_result __wrap_sss_pbd_table_build(double eta, double g, sss_pbd_table *table, sss_error *err)
{
    for (int i = 0; i < memo_used; i++)
        if (memcmp(&memo_key[i][0], &eta, sizeof eta) == 0 && memcmp(&memo_key[i][1], &g, sizeof g) == 0) {
            memcpy(table, &memo[i], sizeof *table);
            return SSS_OK;
        }
    sss_result r = __real_sss_pbd_table_build(eta, g, table, err);
    if (r == SSS_OK) {
        memcpy(&memo[memo_next], table, sizeof *table);
        memo_key[memo_next][0] = eta;
        memo_key[memo_next][1] = g;
        memo_next = (memo_next + 1) % MEMO_SLOTS;
        if (memo_used < MEMO_SLOTS) memo_used++;
    }
    return r;
}
