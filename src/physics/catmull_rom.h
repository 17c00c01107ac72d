/* physics/catmull_rom.h — Catmull-Rom spline helpers with the semantics of PBRT-v3
 * core/interpolation.cpp (CatmullRomWeights, SampleCatmullRom2D, IntegrateCatmullRom,
 * InvertCatmullRom), written in double precision. Internal to the physics module. */
#ifndef SSS_PHYSICS_CATMULL_ROM_H
#define SSS_PHYSICS_CATMULL_ROM_H

/* Weights of the four nodes offset..offset+3 for x; returns 0 when x is outside [nodes[0],
 * nodes[size-1]] (or NaN). Nodes outside the array get weight 0. */
int cr_weights(int size, const double *nodes, double x, int *offset, double weights[4]);

/* 1D Catmull-Rom interpolation (PBRT CatmullRom); 0 outside the nodes. */
double cr_eval(int size, const double *nodes, const double *values, double x);

/* Integral of the spline through (x, values) over [x[0], x[n-1]]; cdf[i] = integral up to x[i]. */
double cr_integrate(int n, const double *x, const double *values, double *cdf);

/* The x whose spline value is u, for monotone increasing values; clamps to x[0] / x[n-1]. */
double cr_invert(int n, const double *x, const double *values, double u);

/* Samples the second coordinate of a 2D table (rows: size1 values of the first parameter at nodes1,
 * each holding size2 values at nodes2, with running integrals cdf) interpolated at alpha, by inverting
 * the interpolated CDF at u in [0, 1). Returns the sample; *fval the interpolated function value
 * there; *pdf fval divided by the interpolated total. Returns 0 with *pdf = 0 if alpha is outside. */
double cr_sample_2d(int size1, int size2, const double *nodes1, const double *nodes2,
                    const double *values, const double *cdf, double alpha, double u, double *fval,
                    double *pdf);

#endif
