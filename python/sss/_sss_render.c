/* python/sss/_sss_render.c — the Scene and Renderer types of sss._sss, and reference().
 *
 * A Scene owns an sss_scene. A Renderer owns a headless GL context and an sss_gl_renderer on it, and
 * keeps its Scene alive (the library reads the scene while the renderer lives). A GL context belongs
 * to the thread that made it (sss/gl.h), so a Renderer is used, and closed, on the thread that created
 * it; other threads get sss.Error. Renders and references run with the GIL released; while any runs,
 * the scene's lights cannot be changed (a render reads them). */
#include "_sss.h"

#include <math.h>
#include <pythread.h>
#include <stdlib.h>
#include <string.h>

typedef struct scene_object {
    PyObject_HEAD
    sss_scene scene;
    int busy; /* calls running on this scene with the GIL released */
} scene_object;

/* ---- Scene ------------------------------------------------------------------------------------ */

static void scene_dealloc(scene_object *self)
{
    sss_scene_free(&self->scene);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

/* A new, empty scene object of type cls (a Python subclass included). */
static scene_object *scene_alloc(PyObject *cls)
{
    scene_object *self = (scene_object *)((PyTypeObject *)cls)->tp_alloc((PyTypeObject *)cls, 0);
    if (self) memset(&self->scene, 0, sizeof self->scene);
    return self;
}

static PyObject *scene_load(PyObject *cls, PyObject *args)
{
    PyObject *path_obj;
    if (!PyArg_ParseTuple(args, "O&:_load", PyUnicode_FSConverter, &path_obj)) return NULL;
    scene_object *self = scene_alloc(cls);
    if (!self) {
        Py_DECREF(path_obj);
        return NULL;
    }
    sss_error err = {0};
    sss_result res;
    Py_BEGIN_ALLOW_THREADS
    res = sss_scene_load(PyBytes_AS_STRING(path_obj), NULL, &self->scene, &err);
    Py_END_ALLOW_THREADS
    Py_DECREF(path_obj);
    if (res != SSS_OK) {
        Py_DECREF(self);
        return sss_py_raise(&err);
    }
    return (PyObject *)self;
}

static PyObject *scene_parse(PyObject *cls, PyObject *args)
{
    const char *text, *base_dir, *name;
    Py_ssize_t size;
    if (!PyArg_ParseTuple(args, "s#ss:_parse", &text, &size, &base_dir, &name)) return NULL;
    scene_object *self = scene_alloc(cls);
    if (!self) return NULL;
    sss_error err = {0};
    sss_result res;
    Py_BEGIN_ALLOW_THREADS
    res = sss_scene_parse(text, (size_t)size, base_dir, name, NULL, &self->scene, &err);
    Py_END_ALLOW_THREADS
    if (res != SSS_OK) {
        Py_DECREF(self);
        return sss_py_raise(&err);
    }
    return (PyObject *)self;
}

static PyObject *vec3(const double v[3])
{
    return Py_BuildValue("[ddd]", v[0], v[1], v[2]);
}

/* A light as the scene format spells it (docs/scene-format.md), without an environment map's file. */
static PyObject *light_dict(const sss_light *l)
{
    const char *type = sss_light_type_name(l->type);
    switch (l->type) {
    case SSS_LIGHT_POINT:
        return Py_BuildValue("{s:s,s:N,s:N}", "type", type, "position", vec3(l->position), "intensity",
                             vec3(l->intensity));
    case SSS_LIGHT_SPOT:
        return Py_BuildValue("{s:s,s:N,s:N,s:d,s:d,s:N}", "type", type, "position", vec3(l->position), "look_at",
                             vec3(l->look_at), "cone_angle", l->cone_angle, "cone_delta", l->cone_delta, "intensity",
                             vec3(l->intensity));
    case SSS_LIGHT_DIRECTIONAL:
        return Py_BuildValue("{s:s,s:N,s:N}", "type", type, "direction", vec3(l->direction), "radiance",
                             vec3(l->radiance));
    case SSS_LIGHT_AREA:
        return Py_BuildValue("{s:s,s:N,s:N,s:N,s:N,s:O}", "type", type, "center", vec3(l->center), "u", vec3(l->u),
                             "v", vec3(l->v), "radiance", vec3(l->radiance), "two_sided",
                             l->two_sided ? Py_True : Py_False);
    case SSS_LIGHT_ENVIRONMENT:
        return Py_BuildValue("{s:s,s:N,s:d}", "type", type, "scale", vec3(l->scale), "rotate_y", l->rotate_y);
    }
    return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "lights: unknown light type %d", (int)l->type);
}

static PyObject *scene_get_lights(scene_object *self, void *closure)
{
    PyObject *list = PyList_New((Py_ssize_t)self->scene.light_count);
    for (size_t i = 0; list && i < self->scene.light_count; i++) {
        PyObject *d = light_dict(&self->scene.lights[i]);
        if (!d) Py_CLEAR(list);
        else PyList_SET_ITEM(list, (Py_ssize_t)i, d);
    }
    return list;
}

/* Sets lights[index] for each (index, JSON text) pair, all or none: a failure restores them all.
 * Shallow copies of the lights stay valid across sss_scene_set_light (it keeps file pointers). */
static int scene_set_lights(scene_object *self, PyObject *pairs)
{
    if (self->busy) {
        sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "%s: lights cannot change while the scene renders in another thread",
                      self->scene.name);
        return 0;
    }
    PyObject *seq = PySequence_Fast(pairs, "expected a sequence of (index, JSON text) pairs");
    if (!seq) return 0;
    size_t n = self->scene.light_count;
    sss_light *saved = malloc((n ? n : 1) * sizeof *saved);
    if (!saved) {
        Py_DECREF(seq);
        PyErr_NoMemory();
        return 0;
    }
    if (n) memcpy(saved, self->scene.lights, n * sizeof *saved);
    int ok = 1;
    for (Py_ssize_t i = 0; ok && i < PySequence_Fast_GET_SIZE(seq); i++) {
        Py_ssize_t index, size;
        const char *text;
        sss_error err = {0};
        PyObject *pair = PySequence_Fast_GET_ITEM(seq, i);
        ok = PyTuple_Check(pair) ? PyArg_ParseTuple(pair, "ns#", &index, &text, &size)
                                 : (PyErr_SetString(PyExc_TypeError, "expected (index, JSON text) pairs"), 0);
        if (ok && (index < 0 || sss_scene_set_light(&self->scene, (size_t)index, text, (size_t)size, &err) != SSS_OK)) {
            if (index < 0) sss_error_set(&err, SSS_ERROR_INVALID_ARGUMENT, "%s: lights[%zd]: no such light",
                                         self->scene.name, index);
            ok = 0;
            sss_py_raise(&err);
        }
    }
    if (!ok && n) memcpy(self->scene.lights, saved, n * sizeof *saved);
    free(saved);
    Py_DECREF(seq);
    return ok;
}

static PyObject *scene_set_lights_method(scene_object *self, PyObject *pairs)
{
    if (!scene_set_lights(self, pairs)) return NULL;
    Py_RETURN_NONE;
}

static PyObject *scene_get_name(scene_object *self, void *c) { return PyUnicode_FromString(self->scene.name); }
static PyObject *scene_get_width(scene_object *self, void *c) { return PyLong_FromLong(self->scene.camera.width); }
static PyObject *scene_get_height(scene_object *self, void *c) { return PyLong_FromLong(self->scene.camera.height); }
static PyObject *scene_get_exposure(scene_object *self, void *c) { return PyFloat_FromDouble(self->scene.render.exposure); }
static PyObject *scene_get_technique(scene_object *self, void *c) { return PyUnicode_FromString(self->scene.render.technique); }
static PyObject *scene_get_objects(scene_object *self, void *c) { return PyLong_FromSize_t(self->scene.object_count); }

static PyGetSetDef scene_getset[] = {
    {"name", (getter)scene_get_name, NULL, "the scene file's path as given (or the name of a parsed scene)", NULL},
    {"width", (getter)scene_get_width, NULL, "the camera's image width", NULL},
    {"height", (getter)scene_get_height, NULL, "the camera's image height", NULL},
    {"exposure", (getter)scene_get_exposure, NULL, "render.exposure (stops)", NULL},
    {"technique", (getter)scene_get_technique, NULL, "render.technique", NULL},
    {"object_count", (getter)scene_get_objects, NULL, "number of objects", NULL},
    {"lights", (getter)scene_get_lights, NULL, "the lights as dicts of the scene format (a copy)", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyMethodDef scene_methods[] = {
    {"_load", scene_load, METH_VARARGS | METH_CLASS, "_load(path): sss_scene_load"},
    {"_parse", scene_parse, METH_VARARGS | METH_CLASS, "_parse(text, base_dir, name): sss_scene_parse"},
    {"_set_lights", (PyCFunction)scene_set_lights_method, METH_O,
     "_set_lights([(index, json_text), ...]): sss_scene_set_light for each, all or none"},
    {NULL, NULL, 0, NULL}};

PyTypeObject sss_py_scene_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "sss._sss.Scene",
    .tp_basicsize = sizeof(scene_object),
    .tp_dealloc = (destructor)scene_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_BASETYPE,
    .tp_doc = "A loaded scene (create it with Scene.load).",
    .tp_methods = scene_methods,
    .tp_getset = scene_getset,
};

/* ---- Renderer --------------------------------------------------------------------------------- */

typedef struct renderer_object {
    PyObject_HEAD
    scene_object *scene;
    sss_gl_context *ctx;
    sss_gl_renderer *r;
    char *data_file;        /* must outlive r */
    unsigned long thread;   /* the thread that created the context */
} renderer_object;

static void renderer_close_gl(renderer_object *self)
{
    sss_gl_renderer_destroy(self->r);
    sss_gl_context_destroy(self->ctx);
    self->r = NULL;
    self->ctx = NULL;
}

static void renderer_dealloc(renderer_object *self)
{
    /* On another thread the context cannot be made current: its GL objects are left to the process. */
    if (self->ctx && PyThread_get_thread_ident() == self->thread) renderer_close_gl(self);
    free(self->data_file);
    Py_XDECREF(self->scene);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

/* 1 when the renderer is open and on its thread, else 0 with sss.Error set. */
static int renderer_usable(renderer_object *self)
{
    if (!self->r) {
        sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "the renderer is closed");
        return 0;
    }
    if (PyThread_get_thread_ident() != self->thread) {
        sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT,
                      "a Renderer is used on the thread that created it (its GL context belongs to that thread)");
        return 0;
    }
    return 1;
}

/* params (None or a mapping name -> number) as an array the library reads; names stay owned by params. */
static int param_array(PyObject *params, sss_gl_param_value **out, int *count)
{
    *out = NULL;
    *count = 0;
    if (!params || params == Py_None) return 1;
    PyObject *items = PyMapping_Items(params);
    if (!items) return 0;
    Py_ssize_t n = PyList_GET_SIZE(items);
    sss_gl_param_value *values = calloc(n ? (size_t)n : 1, sizeof *values);
    int ok = values != NULL;
    if (!ok) PyErr_NoMemory();
    for (Py_ssize_t i = 0; ok && i < n; i++) {
        PyObject *key = PyTuple_GET_ITEM(PyList_GET_ITEM(items, i), 0);
        PyObject *value = PyTuple_GET_ITEM(PyList_GET_ITEM(items, i), 1);
        values[i].name = PyUnicode_Check(key) ? PyUnicode_AsUTF8(key) : NULL;
        values[i].value = PyFloat_AsDouble(value);
        if (!values[i].name || (values[i].value == -1.0 && PyErr_Occurred())) {
            if (!PyErr_Occurred() || PyErr_ExceptionMatches(PyExc_TypeError)) {
                PyErr_Clear();
                PyErr_Format(PyExc_TypeError, "params: expected names (str) mapped to numbers, got %R: %R", key, value);
            }
            ok = 0;
        }
    }
    Py_DECREF(items); /* the keys live on in params */
    if (!ok) free(values);
    *out = ok ? values : NULL;
    *count = ok ? (int)n : 0;
    return ok;
}

static sss_result create_gl(renderer_object *self, const sss_gl_renderer_desc *desc, sss_error *err)
{
    sss_gl_context_desc cdesc;
    memset(&cdesc, 0, sizeof cdesc); /* headless */
    sss_result res = sss_gl_context_create(&cdesc, &self->ctx, err);
    if (res == SSS_OK) res = sss_gl_renderer_create(self->ctx, &self->scene->scene, desc, &self->r, err);
    if (res != SSS_OK) renderer_close_gl(self);
    return res;
}

static PyObject *renderer_new(PyTypeObject *type, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"scene", "technique", "params", "width", "height", "supersample", "timings", "data", NULL};
    PyObject *scene, *params = NULL;
    const char *technique = NULL, *data = NULL;
    sss_gl_renderer_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.supersample = 1;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O!|zOiiipz:Renderer", kwlist, &sss_py_scene_type, &scene,
                                     &technique, &params, &desc.width, &desc.height, &desc.supersample, &desc.timings,
                                     &data))
        return NULL;
    if (desc.width < 0 || desc.height < 0)
        return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "Renderer: width and height must be >= 1 (0: the camera's)");
    renderer_object *self = (renderer_object *)type->tp_alloc(type, 0);
    if (!self) return NULL;
    Py_INCREF(scene);
    self->scene = (scene_object *)scene;
    self->thread = PyThread_get_thread_ident();
    if (data && !(self->data_file = strdup(data))) {
        Py_DECREF(self);
        return PyErr_NoMemory();
    }
    if (!param_array(params, (sss_gl_param_value **)&desc.params, &desc.param_count)) {
        Py_DECREF(self);
        return NULL;
    }
    desc.technique = technique;
    desc.data_file = self->data_file;
    sss_error err = {0};
    sss_result res;
    self->scene->busy++;
    Py_BEGIN_ALLOW_THREADS
    res = create_gl(self, &desc, &err);
    Py_END_ALLOW_THREADS
    self->scene->busy--;
    free((void *)desc.params);
    if (res != SSS_OK) {
        Py_DECREF(self);
        return sss_py_raise(&err);
    }
    return (PyObject *)self;
}

static PyObject *renderer_render(renderer_object *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"time", NULL};
    double time = 0.0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "|d:render", kwlist, &time) || !renderer_usable(self)) return NULL;
    int w, h;
    sss_gl_renderer_size(self->r, &w, &h);
    sss_image view;
    PyArrayObject *arr = sss_py_new_image_array(w, h, &view);
    if (!arr) return NULL;
    sss_error err = {0};
    sss_result res;
    self->scene->busy++;
    Py_BEGIN_ALLOW_THREADS
    res = sss_gl_renderer_render(self->r, time, &err);
    if (res == SSS_OK) res = sss_gl_renderer_read(self->r, &view, &err);
    Py_END_ALLOW_THREADS
    self->scene->busy--;
    if (res != SSS_OK) {
        Py_DECREF(arr);
        return sss_py_raise(&err);
    }
    return (PyObject *)arr;
}

/* The last frame's pass timings: {"method", "total_ms", "passes": {name: ms}} (a name repeated within
 * a frame adds up, as in sss_gl_timing_series). */
static PyObject *renderer_timings(renderer_object *self, PyObject *unused)
{
    if (!renderer_usable(self)) return NULL;
    sss_gl_timings t;
    sss_gl_renderer_timings(self->r, &t);
    PyObject *passes = PyDict_New();
    for (int i = 0; passes && i < t.pass_count; i++) {
        PyObject *prev = PyDict_GetItemString(passes, t.passes[i].name); /* borrowed */
        PyObject *ms = PyFloat_FromDouble(t.passes[i].ms + (prev ? PyFloat_AsDouble(prev) : 0.0));
        if (!ms || PyDict_SetItemString(passes, t.passes[i].name, ms) != 0) Py_CLEAR(passes);
        Py_XDECREF(ms);
    }
    if (!passes) return NULL;
    return Py_BuildValue("{s:s,s:d,s:N}", "method", t.method ? t.method : "off", "total_ms", t.total_ms, "passes",
                         passes);
}

static PyObject *renderer_set_params(renderer_object *self, PyObject *args, PyObject *kwargs)
{
    PyObject *params = NULL;
    if (!PyArg_ParseTuple(args, "|O:set_params", &params) || !renderer_usable(self)) return NULL;
    PyObject *sources[2] = {params, kwargs};
    for (int s = 0; s < 2; s++) {
        sss_gl_param_value *values;
        int count;
        if (!param_array(sources[s], &values, &count)) return NULL;
        sss_error err = {0};
        sss_result res = SSS_OK;
        Py_BEGIN_ALLOW_THREADS
        for (int i = 0; i < count && res == SSS_OK; i++)
            res = sss_gl_renderer_set_param(self->r, values[i].name, values[i].value, &err);
        Py_END_ALLOW_THREADS
        free(values);
        if (res != SSS_OK) return sss_py_raise(&err);
    }
    Py_RETURN_NONE;
}

static PyObject *renderer_get_param(renderer_object *self, PyObject *args)
{
    const char *name;
    if (!PyArg_ParseTuple(args, "s:get_param", &name) || !renderer_usable(self)) return NULL;
    double v = sss_gl_renderer_get_param(self->r, name);
    if (isnan(v)) return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "get_param: unknown parameter \"%s\"", name);
    return PyFloat_FromDouble(v);
}

/* Changes lights of the scene (all or none) and passes them to the GL renderer. */
static PyObject *renderer_update_lights(renderer_object *self, PyObject *pairs)
{
    if (!renderer_usable(self)) return NULL;
    size_t n = self->scene->scene.light_count;
    sss_light *saved = malloc((n ? n : 1) * sizeof *saved);
    if (!saved) return PyErr_NoMemory();
    if (n) memcpy(saved, self->scene->scene.lights, n * sizeof *saved);
    if (!scene_set_lights(self->scene, pairs)) {
        free(saved);
        return NULL;
    }
    sss_error err = {0};
    sss_result res = sss_gl_renderer_update_lights(self->r, &err);
    if (res != SSS_OK && n) memcpy(self->scene->scene.lights, saved, n * sizeof *saved); /* the renderer kept them */
    free(saved);
    if (res != SSS_OK) return sss_py_raise(&err);
    Py_RETURN_NONE;
}

/* New materials for the same geometry (sss_gl_renderer_update_materials): `scene` is the renderer's
 * own scene (re-read) or another one with equal geometry, which the renderer then draws and keeps. */
static PyObject *renderer_update_materials(renderer_object *self, PyObject *arg)
{
    if (!renderer_usable(self)) return NULL;
    if (!PyObject_TypeCheck(arg, &sss_py_scene_type))
        return PyErr_Format(PyExc_TypeError, "update_materials: expected an sss.Scene, got %s", Py_TYPE(arg)->tp_name);
    scene_object *next = (scene_object *)arg;
    sss_error err = {0};
    sss_result res;
    self->scene->busy++, next->busy++;
    Py_BEGIN_ALLOW_THREADS
    res = sss_gl_renderer_update_materials(self->r, next == self->scene ? NULL : &next->scene, NULL, &err);
    Py_END_ALLOW_THREADS
    self->scene->busy--, next->busy--;
    if (res != SSS_OK) return sss_py_raise(&err);
    if (next != self->scene) {
        scene_object *old = self->scene;
        Py_INCREF(next);
        self->scene = next;
        Py_DECREF(old);
    }
    Py_RETURN_NONE;
}

static PyObject *renderer_close(renderer_object *self, PyObject *unused)
{
    if (self->r && !renderer_usable(self)) return NULL;
    renderer_close_gl(self);
    Py_RETURN_NONE;
}

static PyObject *renderer_get_size(renderer_object *self, void *c)
{
    if (!renderer_usable(self)) return NULL;
    int w, h;
    sss_gl_renderer_size(self->r, &w, &h);
    return Py_BuildValue("(ii)", w, h);
}

static PyObject *renderer_get_scene(renderer_object *self, void *c)
{
    Py_INCREF(self->scene);
    return (PyObject *)self->scene;
}

static PyGetSetDef renderer_getset[] = {
    {"size", (getter)renderer_get_size, NULL, "(width, height) of the images render() returns", NULL},
    {"scene", (getter)renderer_get_scene, NULL, "the scene it renders", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyMethodDef renderer_methods[] = {
    {"render", (PyCFunction)(void (*)(void))renderer_render, METH_VARARGS | METH_KEYWORDS,
     "render(time=0.0) -> float32 H x W x 3 linear RGB"},
    {"timings", (PyCFunction)renderer_timings, METH_NOARGS,
     "timings() -> {'method', 'total_ms', 'passes': {name: ms}} of the last frame (needs timings=True)"},
    {"set_params", (PyCFunction)(void (*)(void))renderer_set_params, METH_VARARGS | METH_KEYWORDS,
     "set_params(params=None, **named): technique or shared parameters, applied in order"},
    {"get_param", (PyCFunction)renderer_get_param, METH_VARARGS, "get_param(name) -> float"},
    {"_update_lights", (PyCFunction)renderer_update_lights, METH_O,
     "_update_lights([(index, json_text), ...]): sss_scene_set_light each, then sss_gl_renderer_update_lights"},
    {"update_materials", (PyCFunction)renderer_update_materials, METH_O,
     "update_materials(scene): new materials for the same geometry without a new renderer; scene is the\n"
     "renderer's own (re-read) or another with the same meshes, transforms, lights and textures, which it\n"
     "then draws. Different geometry raises sss.Error and the renderer keeps its scene."},
    {"close", (PyCFunction)renderer_close, METH_NOARGS, "close(): frees the GL context now (idempotent)"},
    {NULL, NULL, 0, NULL}};

PyTypeObject sss_py_renderer_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "sss._sss.Renderer",
    .tp_basicsize = sizeof(renderer_object),
    .tp_dealloc = (destructor)renderer_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_BASETYPE,
    .tp_doc = "Renderer(scene, technique=None, params=None, width=0, height=0, supersample=1, timings=False, "
              "data=None): a real-time renderer keeping its GL state across frames.",
    .tp_methods = renderer_methods,
    .tp_getset = renderer_getset,
    .tp_new = renderer_new,
};

/* ---- reference -------------------------------------------------------------------------------- */

static PyObject *py_reference(PyObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = {"scene", "quality", "bounces", "threads", "time", "seed", "spp",
                             "density", "specular", "exact", "width", "height", NULL};
    PyObject *scene_obj;
    const char *quality = "final";
    unsigned long long seed = 0;
    int width = 0, height = 0;
    sss_reference_desc desc;
    memset(&desc, 0, sizeof desc);
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O!|siidKidppii:reference", kwlist, &sss_py_scene_type, &scene_obj,
                                     &quality, &desc.bounces, &desc.threads, &desc.time, &seed, &desc.spp,
                                     &desc.density, &desc.specular, &desc.exact, &width, &height))
        return NULL;
    desc.seed = seed;
    if (strcmp(quality, "final") == 0) desc.quality = SSS_REFERENCE_FINAL;
    else if (strcmp(quality, "draft") == 0) desc.quality = SSS_REFERENCE_DRAFT;
    else return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "reference: quality must be \"draft\" or \"final\", got \"%s\"", quality);
    /* The CLI's ranges (0: the default); the library checks the rest. */
    if (desc.threads > 4096 || desc.spp > 4096 || desc.density > 1024.0)
        return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "reference: threads and spp must be <= 4096, density <= 1024");
    if (width < 0 || height < 0)
        return sss_py_raisef(SSS_ERROR_INVALID_ARGUMENT, "reference: width and height must be >= 1 (0: the camera's)");
    scene_object *scene = (scene_object *)scene_obj;
    /* Another size renders a shallow copy of the scene with its camera resized, as `sss reference --width`. */
    sss_scene sized = scene->scene;
    if (width) sized.camera.width = width;
    if (height) sized.camera.height = height;
    sss_image img = {0};
    sss_error err = {0};
    sss_result res = sss_camera_basis_init(&sized.camera, &sized.basis, &err);
    if (res != SSS_OK) return sss_py_raise(&err);
    scene->busy++;
    Py_BEGIN_ALLOW_THREADS
    res = sss_reference_render(&sized, &desc, &img, NULL, NULL, NULL, &err);
    if (res == SSS_OK && sss_image_count_nonfinite(&img) != 0)
        res = sss_error_set(&err, SSS_ERROR_NUMERIC, "%s: the reference image has NaN or Inf values", scene->scene.name);
    Py_END_ALLOW_THREADS
    scene->busy--;
    if (res != SSS_OK) {
        sss_image_free(&img);
        return sss_py_raise(&err);
    }
    return sss_py_array_from_image(&img);
}

PyMethodDef sss_py_render_methods[] = {
    {"reference", (PyCFunction)(void (*)(void))py_reference, METH_VARARGS | METH_KEYWORDS,
     "reference(scene, quality='final', bounces=0, threads=0, time=0.0, seed=0, spp=0, density=0.0, "
     "specular=False, exact=False, width=0, height=0) -> float32 H x W x 3 linear RGB (the CPU ground truth; "
     "width/height 0: the camera's)"},
    {NULL, NULL, 0, NULL}};
