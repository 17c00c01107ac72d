/* bench_pbd — PBD table build (docs/physics.md §2.2: 100 albedos x 64 radii x 200 quadrature samples) and the
 * per-call cost of S_r evaluation and sampling. Target for the build: median < 50 ms. */
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "sss/profile.h"

static sss_pbd_table *table;
static volatile double sink;

static void build(void *ctx)
{
    (void)ctx;
    sss_pbd_table_build(1.33, 0.0, table, NULL);
}

static void eval_many(void *ctx)
{
    (void)ctx;
    double s = 0.0;
    for (int i = 0; i < 1000000; i++) s += sss_pbd_sr(table, 0.0041, 2.62, 1e-3 + 1e-5 * (i % 3000));
    sink = s;
}

static void sample_many(void *ctx)
{
    (void)ctx;
    double s = 0.0;
    for (int i = 0; i < 1000000; i++) s += sss_pbd_sample_radius(table, 0.17, 0.88, (i + 0.5) / 1e6);
    sink = s;
}

int main(void)
{
    table = malloc(sizeof *table);
    if (!table) return 1;
    double ms = bench_run("pbd table build (eta 1.33, g 0)", 21, build, NULL);
    bench_run("pbd S_r eval x 1e6", 5, eval_many, NULL);
    bench_run("pbd sample radius x 1e6", 5, sample_many, NULL);
    printf("table build median %.2f ms (target < 50 ms): %s\n", ms, ms < 50.0 ? "ok" : "ABOVE TARGET");
    free(table);
    return 0;
}
