/* kernel/kernel_test.h — internal entry points of the kernel module that its tests check directly.
 * Not part of the public API: libsss.so does not export them (docs/versioning.md). */
#ifndef SSS_KERNEL_TEST_H
#define SSS_KERNEL_TEST_H

#include "sss/profile.h"

/* The discretised objective of Eq. 8 of Jimenez et al. 2019 (with the floor and the same cell averages
 * of R_d as sss_kernel_guided) for one channel's a (grid values):
 * sum_ij (Gamma_ij + floor) (avg R_d_ij - a_i a_j)^2 h^2. NAN on bad input (grid outside [1, 512]) or
 * without memory. For checking that sss_kernel_guided finds its minimum. */
double kernel_guided_objective(const sss_profile *profile, int grid, double extent, double k, double b, int channel,
                               const double *a);

#endif
