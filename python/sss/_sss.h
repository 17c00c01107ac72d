/* python/sss/_sss.h — what the files of the CPython extension sss._sss share (internal).
 *
 * Does: the one exception type (sss.Error, a RuntimeError carrying the library's message and result
 * code), images as numpy float32 H x W x 3 arrays in both directions, and the types and functions each
 * file adds to the module. Does not: parse arguments for other files, or hold any GL state of its own.
 */
#ifndef SSS_PYTHON_SSS_H
#define SSS_PYTHON_SSS_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#define PY_ARRAY_UNIQUE_SYMBOL sss_python_array_api
#ifndef SSS_PYTHON_IMPORT_ARRAY /* only _sss.c imports numpy's C API; the other files use its table */
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

#include "sss/sss.h"

/* sss.Error (created at import). */
extern PyObject *sss_py_error;

/* Raises sss.Error with err's message and code; returns NULL for `return sss_py_raise(&err);`. */
PyObject *sss_py_raise(const sss_error *err);
/* Raises sss.Error with a formatted message and code (for checks made by the binding itself). */
PyObject *sss_py_raisef(sss_result code, const char *fmt, ...);

/* An image the library allocated, as an array over its pixels (no copy): the array's base is a
 * capsule that frees them. Takes img over (it is emptied) even on failure. */
PyObject *sss_py_array_from_image(sss_image *img);
/* A new float32 height x width x 3 array and an sss_image over its memory, which the array owns: not
 * initialised, for a library call that writes every pixel. */
PyArrayObject *sss_py_new_image_array(int width, int height, sss_image *view);
/* A read-only view of obj as an image: obj converted (copied only when it is not already a
 * C-contiguous float32 H x W x 3 array) into *keep, which the caller releases after using view.
 * what names the argument in errors (ValueError / TypeError). Returns 0 with an exception set. */
int sss_py_image_view(PyObject *obj, const char *what, PyArrayObject **keep, sss_image *view);

/* A float64 1-D array of count values copied from src (float or double). */
PyObject *sss_py_vector_f(const float *src, npy_intp count);
PyObject *sss_py_vector_d(const double *src, npy_intp count);

/* _sss_render.c: the Scene and Renderer types, render and reference. */
extern PyTypeObject sss_py_scene_type;
extern PyTypeObject sss_py_renderer_type;
extern PyMethodDef sss_py_render_methods[];
/* _sss_physics.c: profile, lut, kernel. */
extern PyMethodDef sss_py_physics_methods[];

#endif
