/* python/sss/_sss.c — the module sss._sss: its exception, images as numpy arrays, image files, image
 * metrics and the technique tables. The scene and renderers are in _sss_render.c, the scattering
 * profiles and kernels in _sss_physics.c; sss/__init__.py is the documented Python face of all of it.
 *
 * Every call that does real work (file I/O, metrics, rendering) releases the GIL around the library
 * call. Arrays returned own their memory: either numpy allocated it and the library filled it, or the
 * library allocated it and a capsule base frees it with the array (no copies, no dangling views). */
#define SSS_PYTHON_IMPORT_ARRAY
#include "_sss.h"

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

PyObject *sss_py_error;

PyObject *sss_py_raise(const sss_error *err)
{
    sss_result code = err->code != SSS_OK ? err->code : SSS_ERROR_INVALID_ARGUMENT;
    const char *message = err->message[0] ? err->message : sss_result_string(code);
    /* File names in messages need not be UTF-8: undecodable bytes show as \xNN instead of failing. */
    PyObject *text = PyUnicode_DecodeUTF8(message, (Py_ssize_t)strlen(message), "backslashreplace");
    PyObject *exc = text ? PyObject_CallOneArg(sss_py_error, text) : NULL;
    Py_XDECREF(text);
    if (!exc) return NULL;
    PyObject *code_obj = PyLong_FromLong((long)code), *name = PyUnicode_FromString(sss_result_string(code));
    if (code_obj && name && PyObject_SetAttrString(exc, "code", code_obj) == 0 &&
        PyObject_SetAttrString(exc, "code_name", name) == 0)
        PyErr_SetObject(sss_py_error, exc);
    Py_XDECREF(code_obj);
    Py_XDECREF(name);
    Py_DECREF(exc);
    return NULL;
}

PyObject *sss_py_raisef(sss_result code, const char *fmt, ...)
{
    sss_error err = {code, ""};
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err.message, sizeof err.message, fmt, ap);
    va_end(ap);
    return sss_py_raise(&err);
}

/* ---- Images as arrays ------------------------------------------------------------------------- */

#define IMAGE_CAPSULE "sss.image"

static void free_image_capsule(PyObject *capsule)
{
    sss_image *img = PyCapsule_GetPointer(capsule, IMAGE_CAPSULE);
    sss_image_free(img);
    free(img);
}

PyObject *sss_py_array_from_image(sss_image *img)
{
    sss_image *owned = malloc(sizeof *owned);
    if (!owned) {
        sss_image_free(img);
        return PyErr_NoMemory();
    }
    *owned = *img;
    memset(img, 0, sizeof *img);
    PyObject *capsule = PyCapsule_New(owned, IMAGE_CAPSULE, free_image_capsule);
    if (!capsule) {
        sss_image_free(owned);
        free(owned);
        return NULL;
    }
    npy_intp dims[3] = {owned->height, owned->width, 3};
    PyObject *arr = PyArray_SimpleNewFromData(3, dims, NPY_FLOAT32, owned->pixels);
    if (!arr || PyArray_SetBaseObject((PyArrayObject *)arr, capsule) != 0) {
        Py_XDECREF(arr);
        Py_DECREF(capsule); /* frees the pixels */
        return NULL;
    }
    return arr;
}

PyArrayObject *sss_py_new_image_array(int width, int height, sss_image *view)
{
    npy_intp dims[3] = {height, width, 3};
    PyArrayObject *arr = (PyArrayObject *)PyArray_EMPTY(3, dims, NPY_FLOAT32, 0);
    if (!arr) return NULL;
    view->width = width;
    view->height = height;
    view->pixels = PyArray_DATA(arr);
    return arr;
}

int sss_py_image_view(PyObject *obj, const char *what, PyArrayObject **keep, sss_image *view)
{
    PyArrayObject *arr = (PyArrayObject *)PyArray_FROMANY(obj, NPY_FLOAT32, 3, 3, NPY_ARRAY_IN_ARRAY | NPY_ARRAY_FORCECAST);
    if (!arr) {
        PyErr_Format(PyExc_TypeError, "%s: expected an H x W x 3 array of linear RGB", what);
        return 0;
    }
    npy_intp *d = PyArray_DIMS(arr);
    if (d[2] != 3 || d[0] < 1 || d[1] < 1 || d[0] > SSS_IMAGE_MAX_DIM || d[1] > SSS_IMAGE_MAX_DIM) {
        PyErr_Format(PyExc_ValueError, "%s: expected an H x W x 3 array with 1 <= H, W <= %d, got %zd x %zd x %zd",
                     what, SSS_IMAGE_MAX_DIM, (Py_ssize_t)d[0], (Py_ssize_t)d[1], (Py_ssize_t)d[2]);
        Py_DECREF(arr);
        return 0;
    }
    view->height = (int)d[0];
    view->width = (int)d[1];
    view->pixels = PyArray_DATA(arr);
    *keep = arr;
    return 1;
}

static PyObject *vector_new(npy_intp count, double **data)
{
    PyObject *arr = PyArray_SimpleNew(1, &count, NPY_FLOAT64);
    if (arr) *data = PyArray_DATA((PyArrayObject *)arr);
    return arr;
}

PyObject *sss_py_vector_f(const float *src, npy_intp count)
{
    double *dst;
    PyObject *arr = vector_new(count, &dst);
    for (npy_intp i = 0; arr && i < count; i++) dst[i] = src[i];
    return arr;
}

PyObject *sss_py_vector_d(const double *src, npy_intp count)
{
    double *dst;
    PyObject *arr = vector_new(count, &dst);
    if (arr && count > 0) memcpy(dst, src, (size_t)count * sizeof *dst);
    return arr;
}

/* ---- Image files and metrics ------------------------------------------------------------------ */

static PyObject *py_read_image(PyObject *self, PyObject *args)
{
    PyObject *path_obj;
    if (!PyArg_ParseTuple(args, "O&:read_image", PyUnicode_FSConverter, &path_obj)) return NULL;
    sss_image img = {0};
    sss_error err = {0};
    sss_result res;
    Py_BEGIN_ALLOW_THREADS
    res = sss_image_read(PyBytes_AS_STRING(path_obj), &img, &err);
    Py_END_ALLOW_THREADS
    Py_DECREF(path_obj);
    if (res != SSS_OK) return sss_py_raise(&err);
    return sss_py_array_from_image(&img);
}

static PyObject *py_write_image(PyObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"path", "image", "exposure", "half", NULL};
    PyObject *path_obj, *image;
    double exposure = 0.0;
    int half = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O&O|dp:write_image", kwlist, PyUnicode_FSConverter, &path_obj,
                                     &image, &exposure, &half))
        return NULL;
    PyArrayObject *keep = NULL;
    sss_image view;
    if (!sss_py_image_view(image, "write_image: image", &keep, &view)) {
        Py_DECREF(path_obj);
        return NULL;
    }
    const char *path = PyBytes_AS_STRING(path_obj);
    size_t n = strlen(path);
    sss_error err = {0};
    sss_result res;
    if (half && (n < 4 || strcasecmp(path + n - 4, ".exr") != 0)) {
        res = sss_error_set(&err, SSS_ERROR_INVALID_ARGUMENT, "%s: half=True needs a .exr file name", path);
    } else {
        Py_BEGIN_ALLOW_THREADS
        res = half ? sss_image_write_exr(path, &view, 1, &err) : sss_image_write(path, &view, exposure, &err);
        Py_END_ALLOW_THREADS
    }
    Py_DECREF(keep);
    Py_DECREF(path_obj);
    if (res != SSS_OK) return sss_py_raise(&err);
    Py_RETURN_NONE;
}

/* The fields of sss_image_metrics that compare() returns: a new metric is one line here. */
static const struct {
    const char *name;
    size_t offset;
} metric_fields[] = {
    {"ssim", offsetof(sss_image_metrics, ssim)},
    {"dssim", offsetof(sss_image_metrics, dssim)},
    {"psnr", offsetof(sss_image_metrics, psnr)},
    {"flip", offsetof(sss_image_metrics, flip)},
    {"rmse", offsetof(sss_image_metrics, rmse)},
    {"max_abs", offsetof(sss_image_metrics, max_abs)},
};

static PyObject *metrics_dict(const sss_image_metrics *m)
{
    PyObject *d = PyDict_New();
    for (size_t i = 0; d && i < sizeof metric_fields / sizeof metric_fields[0]; i++) {
        double v = *(const double *)((const char *)m + metric_fields[i].offset);
        PyObject *value = PyFloat_FromDouble(v);
        if (!value || PyDict_SetItemString(d, metric_fields[i].name, value) != 0) Py_CLEAR(d);
        Py_XDECREF(value);
    }
    return d;
}

/* Adds a map (an image allocated by the library) to d under key; d is cleared on failure. */
static PyObject *add_map(PyObject *d, const char *key, sss_image *map)
{
    if (!d) {
        sss_image_free(map);
        return NULL;
    }
    PyObject *arr = sss_py_array_from_image(map);
    if (!arr || PyDict_SetItemString(d, key, arr) != 0) Py_CLEAR(d);
    Py_XDECREF(arr);
    return d;
}

static PyObject *py_compare(PyObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"a", "b", "exposure", "dssim_map", "flip_map", NULL};
    PyObject *a_obj, *b_obj;
    double exposure = 0.0;
    int want_dssim = 0, want_flip = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|dpp:compare", kwlist, &a_obj, &b_obj, &exposure, &want_dssim,
                                     &want_flip))
        return NULL;
    PyArrayObject *keep_a = NULL, *keep_b = NULL;
    sss_image a, b, dssim = {0}, flip = {0};
    if (!sss_py_image_view(a_obj, "compare: a", &keep_a, &a)) return NULL;
    if (!sss_py_image_view(b_obj, "compare: b", &keep_b, &b)) {
        Py_DECREF(keep_a);
        return NULL;
    }
    if (a.width != b.width || a.height != b.height) { /* numpy's shapes, height first */
        Py_DECREF(keep_a);
        Py_DECREF(keep_b);
        return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "compare: the shapes differ: a is (%d, %d, 3), b is (%d, %d, 3)",
                             a.height, a.width, b.height, b.width);
    }
    sss_image_metrics m;
    sss_error err = {0};
    sss_result res;
    Py_BEGIN_ALLOW_THREADS
    res = sss_image_compare_maps(&a, &b, exposure, &m, want_dssim ? &dssim : NULL, want_flip ? &flip : NULL, &err);
    Py_END_ALLOW_THREADS
    Py_DECREF(keep_a);
    Py_DECREF(keep_b);
    if (res != SSS_OK) return sss_py_raise(&err);
    PyObject *d = metrics_dict(&m);
    if (want_dssim) d = add_map(d, "dssim_map", &dssim);
    if (want_flip) d = add_map(d, "flip_map", &flip);
    return d;
}

/* The 8-bit sRGB image the metrics compare (and PNGs hold): uint8 H x W x 3. */
static PyObject *py_to_srgb(PyObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"image", "exposure", NULL};
    PyObject *obj;
    double exposure = 0.0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|d:to_srgb", kwlist, &obj, &exposure)) return NULL;
    if (!isfinite(exposure)) return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "to_srgb: exposure %g is not finite", exposure);
    PyArrayObject *keep = NULL;
    sss_image img;
    if (!sss_py_image_view(obj, "to_srgb: image", &keep, &img)) return NULL;
    npy_intp dims[3] = {img.height, img.width, 3};
    PyObject *out = PyArray_SimpleNew(3, dims, NPY_UINT8);
    if (out) {
        Py_BEGIN_ALLOW_THREADS
        sss_image_to_srgb8(&img, exposure, (uint8_t *)PyArray_DATA((PyArrayObject *)out));
        Py_END_ALLOW_THREADS
    }
    Py_DECREF(keep);
    return out;
}

/* ---- Techniques ------------------------------------------------------------------------------- */

static PyObject *param_dict(const sss_gl_param_info *p)
{
    static const char *const type_names[] = {"bool", "int", "float"};
    const char *type = (unsigned)p->type < 3 ? type_names[p->type] : "?";
    return Py_BuildValue("{s:s,s:s,s:d,s:d,s:d,s:s}", "name", p->name, "type", type, "default", p->default_value,
                         "min", p->min_value, "max", p->max_value, "doc", p->doc ? p->doc : "");
}

static PyObject *param_list(const sss_gl_param_info *params, int count)
{
    PyObject *list = PyList_New(count);
    for (int i = 0; list && i < count; i++) {
        PyObject *d = param_dict(&params[i]);
        if (!d) Py_CLEAR(list);
        else PyList_SET_ITEM(list, i, d);
    }
    return list;
}

static PyObject *py_techniques(PyObject *self, PyObject *unused)
{
    int count = sss_gl_technique_count();
    PyObject *list = PyList_New(count);
    for (int i = 0; list && i < count; i++) {
        const sss_gl_technique_info *t = sss_gl_technique_at(i);
        PyObject *params = param_list(t->params, t->param_count);
        PyObject *d = params ? Py_BuildValue("{s:s,s:s,s:N}", "name", t->name, "summary", t->summary, "params", params)
                             : NULL;
        if (!d) Py_CLEAR(list);
        else PyList_SET_ITEM(list, i, d);
    }
    return list;
}

static PyObject *py_shared_params(PyObject *self, PyObject *unused)
{
    int count = 0;
    const sss_gl_param_info *params = sss_gl_shared_params(&count);
    return param_list(params, count);
}

static PyObject *py_media(PyObject *self, PyObject *unused)
{
    size_t count = sss_measured_medium_count();
    PyObject *list = PyList_New((Py_ssize_t)count);
    for (size_t i = 0; list && i < count; i++) {
        PyObject *name = PyUnicode_FromString(sss_measured_medium_at(i)->name);
        if (!name) Py_CLEAR(list);
        else PyList_SET_ITEM(list, (Py_ssize_t)i, name);
    }
    return list;
}

static PyMethodDef module_methods[] = {
    {"read_image", py_read_image, METH_VARARGS, "read_image(path) -> float32 H x W x 3 linear RGB"},
    {"write_image", (PyCFunction)(void (*)(void))py_write_image, METH_VARARGS | METH_KEYWORDS,
     "write_image(path, image, exposure=0.0, half=False)"},
    {"compare", (PyCFunction)(void (*)(void))py_compare, METH_VARARGS | METH_KEYWORDS,
     "compare(a, b, exposure=0.0, dssim_map=False, flip_map=False) -> dict of metrics (and the maps asked for)"},
    {"to_srgb", (PyCFunction)(void (*)(void))py_to_srgb, METH_VARARGS | METH_KEYWORDS,
     "to_srgb(image, exposure=0.0) -> uint8 H x W x 3: the 8-bit sRGB image the metrics compare and PNGs hold"},
    {"techniques", py_techniques, METH_NOARGS, "techniques() -> list of dicts with their parameter tables"},
    {"shared_params", py_shared_params, METH_NOARGS, "shared_params() -> parameters every technique accepts"},
    {"media", py_media, METH_NOARGS, "media() -> names of the measured media"},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module_def = {
    PyModuleDef_HEAD_INIT,
    .m_name = "sss._sss",
    .m_doc = "The C extension behind the sss package (see sss/__init__.py).",
    .m_size = -1,
    .m_methods = module_methods,
};

static int add_methods(PyObject *module, PyMethodDef *methods)
{
    for (PyMethodDef *m = methods; m->ml_name; m++) {
        PyObject *f = PyCFunction_NewEx(m, NULL, PyModule_GetNameObject(module));
        if (!f || PyModule_AddObject(module, m->ml_name, f) != 0) {
            Py_XDECREF(f);
            return -1;
        }
    }
    return 0;
}

static int add_type(PyObject *module, const char *name, PyTypeObject *type)
{
    if (PyType_Ready(type) != 0) return -1;
    Py_INCREF(type);
    if (PyModule_AddObject(module, name, (PyObject *)type) != 0) {
        Py_DECREF(type);
        return -1;
    }
    return 0;
}

PyMODINIT_FUNC PyInit__sss(void)
{
    import_array();
    PyObject *m = PyModule_Create(&module_def);
    if (!m) return NULL;
    sss_py_error = PyErr_NewExceptionWithDoc("sss.Error",
                                             "An error of the sss library: str() is its message (naming the input), "
                                             ".code its sss_result and .code_name that code's name.",
                                             PyExc_RuntimeError, NULL);
    if (!sss_py_error || PyModule_AddObject(m, "Error", sss_py_error) != 0) goto fail;
    Py_INCREF(sss_py_error); /* the module's reference was stolen; keep ours */
    if (add_methods(m, sss_py_render_methods) != 0 || add_methods(m, sss_py_physics_methods) != 0) goto fail;
    if (add_type(m, "Scene", &sss_py_scene_type) != 0 || add_type(m, "Renderer", &sss_py_renderer_type) != 0)
        goto fail;
    if (PyModule_AddStringConstant(m, "version", sss_version()) != 0) goto fail;
    return m;
fail:
    Py_DECREF(m);
    return NULL;
}
