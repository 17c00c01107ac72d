/* bench/bench.h — run a function N times and report the median (and min/max) wall time in ms. */
#ifndef SSS_BENCH_H
#define SSS_BENCH_H

#include <stdio.h>
#include <stdlib.h>

#include "sss/common.h"

/* Times fn(ctx) runs times; returns the median in milliseconds and prints one line. */
static double bench_run(const char *label, int runs, void (*fn)(void *), void *ctx)
{
    double *ms = malloc(sizeof(double) * (size_t)runs);
    if (!ms) return -1.0;
    for (int i = 0; i < runs; i++) {
        double t0 = sss_time_seconds();
        fn(ctx);
        ms[i] = 1e3 * (sss_time_seconds() - t0);
    }
    double median = sss_median(ms, runs); /* sorts ms: ms[0] and ms[runs - 1] are min and max */
    printf("%-44s median %9.3f ms  min %9.3f  max %9.3f  (%d runs)\n", label, median, ms[0],
           ms[runs - 1], runs);
    free(ms);
    return median;
}

#endif
