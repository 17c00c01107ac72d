/* python/sss/_sss_physics.c — profile, lut and kernel of sss._sss: the diffusion profile of a measured
 * medium, its disc-integral LUT (Maisch & Ropinski 2020) and the separable or SVD kernels, as numpy
 * arrays. The same medium -> profile path as `sss profile`, `sss lut` and `sss kernel`. */
#include "_sss.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_ETA 1.33 /* the CLI's default */

typedef sss_medium_profile medium_profile;

static void medium_profile_free(medium_profile *mp) { sss_medium_profile_free(mp); }

/* A measured medium's profile under model "pbd" or "dipole" (as the CLI's). */
static sss_result medium_profile_init(const char *medium, double scale, double eta, const char *model,
                                      medium_profile *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    sss_profile_model m;
    if (strcmp(model, "pbd") == 0) m = SSS_PROFILE_PBD;
    else if (strcmp(model, "dipole") == 0) m = SSS_PROFILE_DIPOLE;
    else return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "model must be \"pbd\" or \"dipole\", got \"%s\"", model);
    return sss_medium_profile_init(out, medium, scale, eta, m, err);
}

/* The profile built with the GIL released (a PBD table takes a while). */
static int load_profile(const char *medium, double scale, double eta, const char *model, medium_profile *mp)
{
    sss_error err = {0};
    sss_result res;
    Py_BEGIN_ALLOW_THREADS
    res = medium_profile_init(medium, scale, eta, model, mp, &err);
    Py_END_ALLOW_THREADS
    if (res != SSS_OK) sss_py_raise(&err);
    return res == SSS_OK;
}

static PyObject *py_profile(PyObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"medium", "r", "scale", "eta", "model", NULL};
    const char *medium, *model = "pbd";
    PyObject *r_obj;
    double scale = 1.0, eta = DEFAULT_ETA;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "sO|dds:profile", kwlist, &medium, &r_obj, &scale, &eta, &model))
        return NULL;
    PyArrayObject *r = (PyArrayObject *)PyArray_FROMANY(r_obj, NPY_FLOAT64, 0, 1, NPY_ARRAY_IN_ARRAY);
    if (!r) return NULL;
    npy_intp n = PyArray_SIZE(r);
    const double *radii = PyArray_DATA(r);
    for (npy_intp i = 0; i < n; i++)
        if (!(radii[i] >= 0.0) || !isfinite(radii[i])) {
            Py_DECREF(r);
            return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "profile: r[%zd] = %g: radii must be finite and >= 0",
                                 (Py_ssize_t)i, radii[i]);
        }
    npy_intp dims[2] = {n, 3};
    PyObject *out = PyArray_SimpleNew(2, dims, NPY_FLOAT64);
    medium_profile mp;
    if (!out || !load_profile(medium, scale, eta, model, &mp)) {
        Py_DECREF(r);
        Py_XDECREF(out);
        return NULL;
    }
    double *values = PyArray_DATA((PyArrayObject *)out);
    Py_BEGIN_ALLOW_THREADS
    for (npy_intp i = 0; i < n; i++) sss_profile_eval_rgb(&mp.profile, radii[i], values + 3 * i);
    Py_END_ALLOW_THREADS
    medium_profile_free(&mp);
    Py_DECREF(r);
    return out;
}

static PyObject *py_lut(PyObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"medium", "size", "scale", "eta", "model", "axes", "r_max", "source_cutoff", NULL};
    const char *medium, *model = "pbd", *axes = "linear";
    int size = 512;
    double scale = 1.0, eta = DEFAULT_ETA, r_max = 0.0, cutoff = 0.0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "s|iddssdd:lut", kwlist, &medium, &size, &scale, &eta, &model, &axes,
                                     &r_max, &cutoff))
        return NULL;
    sss_lut_desc desc;
    memset(&desc, 0, sizeof desc);
    if (strcmp(axes, "linear") == 0) desc.axes = SSS_LUT_AXES_LINEAR;
    else if (strcmp(axes, "sqrt") == 0) desc.axes = SSS_LUT_AXES_SQRT;
    else return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "lut: axes must be \"linear\" or \"sqrt\", got \"%s\"", axes);
    desc.size = size;
    desc.r_max = r_max;
    desc.source_cutoff = cutoff;
    medium_profile mp;
    if (!load_profile(medium, scale, eta, model, &mp)) return NULL;
    sss_lut lut;
    sss_error err = {0};
    sss_result res;
    Py_BEGIN_ALLOW_THREADS
    res = sss_lut_build(&mp.profile, &desc, &lut, &err);
    Py_END_ALLOW_THREADS
    medium_profile_free(&mp);
    if (res != SSS_OK) return sss_py_raise(&err);
    double lut_r_max = lut.r_max, a_max = lut.a_max;
    /* Texel (i along r, j along A) is pixel (x = i, y = j) of an image; both are malloc'd float RGB, so
     * the array's capsule frees the texels as it frees an image's pixels. */
    sss_image img = {lut.size, lut.size, lut.texels};
    PyObject *texels = sss_py_array_from_image(&img);
    if (!texels) return NULL;
    return Py_BuildValue("{s:N,s:d,s:d,s:s}", "texels", texels, "r_max", lut_r_max, "a_max", a_max, "axes", axes);
}

static PyObject *separable_dict(const char *method, const sss_separable_kernel *k)
{
    npy_intp dims[2] = {k->taps, 3};
    PyObject *weights = PyArray_SimpleNew(2, dims, NPY_FLOAT64);
    if (!weights) return NULL;
    double *w = PyArray_DATA((PyArrayObject *)weights);
    for (npy_intp i = 0; i < 3 * (npy_intp)k->taps; i++) w[i] = k->weights[i];
    return Py_BuildValue("{s:s,s:N,s:N,s:N,s:d}", "method", method, "offsets", sss_py_vector_f(k->offsets, k->taps),
                         "weights", weights, "total", sss_py_vector_d(k->total, 3), "range", k->range);
}

static PyObject *svd_dict(const sss_svd_kernel *k)
{
    PyObject *sv = sss_py_vector_d(k->singular_values, 3 * (npy_intp)k->grid);
    PyObject *vec = sss_py_vector_f(k->vectors, (npy_intp)k->rank * 3 * k->grid);
    PyObject *signs = sss_py_vector_f(k->signs, (npy_intp)k->rank * 3);
    npy_intp sv_dims[2] = {3, k->grid}, vec_dims[3] = {k->rank, 3, k->grid}, sign_dims[2] = {k->rank, 3};
    PyArray_Dims sv_shape = {sv_dims, 2}, vec_shape = {vec_dims, 3}, sign_shape = {sign_dims, 2};
    PyObject *sv2 = sv ? PyArray_Newshape((PyArrayObject *)sv, &sv_shape, NPY_CORDER) : NULL;
    PyObject *vec2 = vec ? PyArray_Newshape((PyArrayObject *)vec, &vec_shape, NPY_CORDER) : NULL;
    PyObject *signs2 = signs ? PyArray_Newshape((PyArrayObject *)signs, &sign_shape, NPY_CORDER) : NULL;
    Py_XDECREF(sv);
    Py_XDECREF(vec);
    Py_XDECREF(signs);
    if (!sv2 || !vec2 || !signs2) {
        Py_XDECREF(sv2);
        Py_XDECREF(vec2);
        Py_XDECREF(signs2);
        return NULL;
    }
    return Py_BuildValue("{s:s,s:i,s:i,s:d,s:N,s:N,s:N}", "method", "svd", "grid", k->grid, "rank", k->rank, "extent",
                         k->extent, "singular_values", sv2, "vectors", vec2, "signs", signs2);
}

typedef struct kernel_args {
    const char *medium, *artist, *method, *model;
    int taps, rank, grid;
    double range, extent, scale, eta;
} kernel_args;

/* The kernel of a medium: "preintegrated" (Jimenez et al. 2019, Eq. 5) or "svd". */
static PyObject *medium_kernel(const kernel_args *a)
{
    medium_profile mp;
    if (!load_profile(a->medium, a->scale, a->eta, a->model, &mp)) return NULL;
    sss_error err = {0};
    sss_result res;
    PyObject *out = NULL;
    if (strcmp(a->method, "svd") == 0) {
        double extent = a->extent;
        sss_svd_kernel k;
        memset(&k, 0, sizeof k);
        Py_BEGIN_ALLOW_THREADS
        if (!(extent > 0.0)) extent = sss_profile_reach(&mp.profile, 0.999); /* the CLI's default */
        res = sss_kernel_svd(&mp.profile, a->grid, extent, a->rank, &k, &err);
        Py_END_ALLOW_THREADS
        out = res == SSS_OK ? svd_dict(&k) : sss_py_raise(&err);
        sss_svd_kernel_free(&k);
    } else {
        sss_separable_kernel k;
        memset(&k, 0, sizeof k);
        Py_BEGIN_ALLOW_THREADS
        res = sss_kernel_preintegrated(&mp.profile, a->taps, a->range, &k, &err);
        Py_END_ALLOW_THREADS
        out = res == SSS_OK ? separable_dict("preintegrated", &k) : sss_py_raise(&err);
        sss_separable_kernel_free(&k);
    }
    medium_profile_free(&mp);
    return out;
}

/* The artist model of a preset (Jimenez et al. 2019, Table 2; s in mm, divided by scale). */
static PyObject *artist_kernel(const kernel_args *a)
{
    sss_artist_params ap;
    sss_error err = {0};
    if (sss_artist_preset(a->artist, &ap, &err) != SSS_OK) return sss_py_raise(&err);
    if (!(a->scale > 0.0) || !isfinite(a->scale))
        return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "kernel: scale %g is not a positive number", a->scale);
    ap.s /= a->scale;
    sss_separable_kernel k;
    memset(&k, 0, sizeof k);
    sss_result res;
    Py_BEGIN_ALLOW_THREADS
    res = sss_kernel_artist(&ap, a->taps, &k, &err);
    Py_END_ALLOW_THREADS
    PyObject *out = res == SSS_OK ? separable_dict("artist", &k) : sss_py_raise(&err);
    sss_separable_kernel_free(&k);
    return out;
}

static PyObject *py_kernel(PyObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"medium", "method", "taps", "range", "rank", "grid", "extent",
                             "artist", "scale", "eta", "model", NULL};
    kernel_args a = {NULL, NULL, NULL, "pbd", 7, 3, 64, 0.0, 0.0, 1.0, DEFAULT_ETA};
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "|zzidiidzdds:kernel", kwlist, &a.medium, &a.method, &a.taps,
                                     &a.range, &a.rank, &a.grid, &a.extent, &a.artist, &a.scale, &a.eta, &a.model))
        return NULL;
    if (!a.medium == !a.artist)
        return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "kernel: give a medium or artist=PRESET (one of them)");
    if (!a.method) a.method = a.artist ? "artist" : "preintegrated";
    int artist = strcmp(a.method, "artist") == 0;
    if (!artist && strcmp(a.method, "preintegrated") != 0 && strcmp(a.method, "svd") != 0)
        return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT,
                             "kernel: method must be \"preintegrated\", \"svd\" or \"artist\", got \"%s\"", a.method);
    if (artist != !!a.artist)
        return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "kernel: method \"%s\" needs %s", a.method,
                             artist ? "artist=PRESET, not a medium" : "a medium, not artist=PRESET");
    return artist ? artist_kernel(&a) : medium_kernel(&a);
}

PyMethodDef sss_py_physics_methods[] = {
    {"profile", (PyCFunction)(void (*)(void))py_profile, METH_VARARGS | METH_KEYWORDS,
     "profile(medium, r, scale=1.0, eta=1.33, model='pbd') -> len(r) x 3 array of R_d(r)"},
    {"lut", (PyCFunction)(void (*)(void))py_lut, METH_VARARGS | METH_KEYWORDS,
     "lut(medium, size=512, scale=1.0, eta=1.33, model='pbd', axes='linear', r_max=0, source_cutoff=0) -> dict"},
    {"kernel", (PyCFunction)(void (*)(void))py_kernel, METH_VARARGS | METH_KEYWORDS,
     "kernel(medium=None, method=None, taps=7, range=0, rank=3, grid=64, extent=0, artist=None, scale=1.0, "
     "eta=1.33, model='pbd') -> dict"},
    {NULL, NULL, 0, NULL}};
