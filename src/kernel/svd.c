/* kernel/svd.c — rank-N separable approximation of a discretised 2D profile by its singular value
 * decomposition (Jimenez et al. 2019, section 3 and Figure 4; Eckart-Young: the truncated SVD is the best rank-N
 * approximation in the Frobenius norm) of the matrix of R_d's cell integrals (kernel/cells.c).
 * LAPACKE dgesdd per channel. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernel/kernel_internal.h"
#include "sss/kernel.h"

#define SVD_MAX_GRID 1024

void sss_svd_kernel_free(sss_svd_kernel *k)
{
    if (!k) return;
    free(k->singular_values);
    free(k->vectors);
    free(k->signs);
    memset(k, 0, sizeof *k);
}

sss_result sss_kernel_svd(const sss_profile *profile, int grid, double extent, int rank,
                          sss_svd_kernel *out, sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "SVD kernel: output is NULL");
    memset(out, 0, sizeof *out);
    if (!profile) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "SVD kernel: profile is NULL");
    if (grid < 1 || grid > SVD_MAX_GRID)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "SVD kernel: grid %d is outside [1, %d]", grid,
                             SVD_MAX_GRID);
    if (!(extent > 0.0) || !isfinite(extent))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "SVD kernel: extent %g is not positive", extent);
    if (rank < 1 || rank > grid)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "SVD kernel: rank %d is outside [1, grid = %d]",
                             rank, grid);
    size_t n = (size_t)grid;
    double *a = malloc(sizeof(double) * n * n), *u = malloc(sizeof(double) * n * n);
    double *vt = malloc(sizeof(double) * n * n), *rd = malloc(sizeof(double) * 3 * n * n);
    out->singular_values = malloc(sizeof(double) * 3 * n);
    out->vectors = malloc(sizeof(float) * (size_t)rank * 3 * n);
    out->signs = malloc(sizeof(float) * (size_t)rank * 3);
    if (!a || !u || !vt || !rd || !out->singular_values || !out->vectors || !out->signs) {
        free(a);
        free(u);
        free(vt);
        free(rd);
        sss_svd_kernel_free(out);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "SVD kernel: no memory for a %d x %d grid", grid, grid);
    }
    out->grid = grid;
    out->rank = rank;
    out->extent = extent;
    /* Cell (i, j) holds the integral of R_d over it (the header's discretisation): finite for either
     * grid parity, and the cells sum to the profile's energy in the square. */
    kq_cell_integrals(profile, grid, extent, rd);
    sss_result res = SSS_OK;
    for (int c = 0; c < 3 && res == SSS_OK; c++) {
        memcpy(a, rd + c * n * n, sizeof(double) * n * n);
        double *s = out->singular_values + c * n;
        lapack_int info = LAPACKE_dgesdd(LAPACK_ROW_MAJOR, 'S', (lapack_int)n, (lapack_int)n, a, (lapack_int)n,
                                         s, u, (lapack_int)n, vt, (lapack_int)n);
        if (info != 0) {
            res = sss_error_set(err, info < 0 ? SSS_ERROR_INVALID_ARGUMENT : SSS_ERROR_NUMERIC,
                                "SVD kernel: LAPACKE_dgesdd failed for channel %d (info %d)", c, (int)info);
            break;
        }
        for (int k = 0; k < rank; k++) {
            /* u_k is column k of U; v_k row k of V^T. The matrix is symmetric, so v_k = +-u_k:
             * the sign of their dot product is that of the eigenvalue. */
            double dot = 0.0, sq = sqrt(s[k]);
            for (size_t x = 0; x < n; x++) dot += u[x * n + k] * vt[k * n + x];
            out->signs[k * 3 + c] = dot < 0.0 ? -1.0f : 1.0f;
            float *vec = out->vectors + ((size_t)k * 3 + c) * n;
            for (size_t x = 0; x < n; x++) vec[x] = (float)(sq * u[x * n + k]);
            /* Orient each vector to a positive sum (an SVD's sign is arbitrary). */
            double sum = 0.0;
            for (size_t x = 0; x < n; x++) sum += vec[x];
            if (sum < 0.0)
                for (size_t x = 0; x < n; x++) vec[x] = -vec[x];
        }
        for (size_t k = 0; k < n; k++)
            if (!isfinite(s[k])) res = sss_error_set(err, SSS_ERROR_NUMERIC, "SVD kernel: non-finite singular value");
    }
    free(a);
    free(u);
    free(vt);
    free(rd);
    if (res != SSS_OK) sss_svd_kernel_free(out);
    return res;
}
