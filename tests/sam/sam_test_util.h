/* tests/sam/sam_test_util.h — helpers shared by the SAM tests: a Marble PBD profile, distances, the
 * closed-form view factor of parallel plates and its integrand, file sizes, link scores. Each test
 * program builds `sam_test_table` (sss_pbd_table_build) before calling sam_test_profile. */
#ifndef SSS_SAM_TEST_UTIL_H
#define SSS_SAM_TEST_UTIL_H

#include <math.h>
#include <stdio.h>

#include "check.h"
#include "sss/sam.h"

static sss_pbd_table sam_test_table;

/* Marble at `scale` mm per unit, eta 1.33, PBD (the table above). */
static inline void sam_test_profile(double scale, sss_profile *p)
{
    sss_error err = {0};
    sss_material mat;
    CHECK(sss_material_from_medium("Marble", scale, 1.33, &mat, &err) == SSS_OK);
    CHECK(sss_profile_init(p, SSS_PROFILE_PBD, &mat, &sam_test_table, &err) == SSS_OK);
}

static inline double sam_test_dist(const float *a, const float *b)
{
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Hottel's view factor between directly opposed parallel rectangles a x b at distance c. */
static inline double sam_test_plates(double a, double b, double c)
{
    double X = a / c, Y = b / c, x1 = 1.0 + X * X, y1 = 1.0 + Y * Y;
    return 2.0 / (M_PI * X * Y) *
           (0.5 * log(x1 * y1 / (1.0 + X * X + Y * Y)) + X * sqrt(y1) * atan(X / sqrt(y1)) +
            Y * sqrt(x1) * atan(Y / sqrt(x1)) - X * atan(X) - Y * atan(Y));
}

/* The radiative kernel between the planes y = 0 (facing +y) and y = c (facing -y); user: &c. */
static inline void sam_test_view_kernel(const double xo[3], const double xi[3], void *user, double out[3])
{
    double c = *(const double *)user, dx = xi[0] - xo[0], dy = xi[1] - xo[1], dz = xi[2] - xo[2];
    double r2 = dx * dx + dy * dy + dz * dz;
    out[0] = out[1] = out[2] = c * c / (M_PI * r2 * r2);
}

static inline long sam_test_file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fclose(f);
    return n;
}

/* A link's score F'_j R_d(|x_j - x_o|) summed over the channels (what the links maximise), or -1 when
 * it fails the back-side criteria (Eq. 13-14). Receiver o of m, source j of src (m itself, or the
 * back-side mesh). */
static inline double sam_test_score(const sss_mesh *m, const sss_mesh *src, const float *area,
                                    const sss_sam_profile_table *t, uint32_t o, uint32_t j)
{
    const float *xo = m->positions + 3 * o, *xj = src->positions + 3 * j;
    if (!sss_sam_is_back(xo, m->normals + 3 * o, xj, src->normals + 3 * j)) return -1.0;
    double rd[3];
    sss_sam_profile_table_eval(t, sam_test_dist(xo, xj), rd);
    return area[j] * (rd[0] + rd[1] + rd[2]);
}

#endif
