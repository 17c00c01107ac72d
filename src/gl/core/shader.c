/* gl/shader.c — GLSL programs from the embedded *.glsl files.
 *
 * Composition: a line `#include "name.glsl"` is replaced by that embedded file (recursively, each file
 * at most once per stage, like an include guard). Every file gets a GLSL source-string number through
 * `#line N FILE_INDEX`, and compiler logs ("0:12(5): error" on Mesa, "0(12) : error" on NVIDIA) are
 * rewritten to "name.glsl:12(5): error" so errors name the shader file and line.
 * Defines: a block of "#define ..." lines is inserted right after the #version line.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/core/embedded.h"
#include "gl/core/gl_base.h"

#define MAX_FILES 32
#define MAX_DEPTH 8

typedef struct strbuf {
    char *data;
    size_t len, cap;
    int failed;
} strbuf;

static void sb_append(strbuf *b, const char *s, size_t n)
{
    if (b->failed) return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->len + n + 1) cap *= 2;
        char *d = realloc(b->data, cap);
        if (!d) {
            b->failed = 1;
            return;
        }
        b->data = d;
        b->cap = cap;
    }
    memcpy(b->data + b->len, s, n);
    b->len += n;
    b->data[b->len] = '\0';
}

static void sb_printf(strbuf *b, const char *fmt, int a, int c)
{
    char tmp[64];
    int n = snprintf(tmp, sizeof tmp, fmt, a, c);
    if (n > 0) sb_append(b, tmp, (size_t)n);
}

typedef struct expander {
    const char *names[MAX_FILES];
    const char *texts[MAX_FILES];
    int count;
    /* name -> text (NULL when unknown); *stable receives a copy of the name that outlives the call */
    const char *(*lookup)(const char *name, const char **stable);
} expander;

static const char *embedded_lookup(const char *name, const char **stable)
{
    const sss_embedded_file *f = sss_embedded_shader_find(name);
    if (stable) *stable = f ? f->name : NULL;
    return f ? f->data : NULL;
}

static int file_index(expander *x, const char *name, const char *text)
{
    for (int i = 0; i < x->count; i++)
        if (strcmp(x->names[i], name) == 0) return i;
    if (x->count >= MAX_FILES) return -1;
    x->names[x->count] = name;
    x->texts[x->count] = text;
    return x->count++;
}

/* Appends file `index` to out, expanding includes. top: the #version line is followed by defines. */
static sss_result expand(expander *x, int index, int depth, const char *defines, strbuf *out,
                         unsigned char *included, sss_error *err)
{
    const char *p = x->texts[index];
    int line = 1, after_version = 0;
    if (depth > 0) sb_printf(out, "#line 1 %d\n", index, 0);
    while (*p) {
        const char *eol = strchr(p, '\n');
        size_t n = eol ? (size_t)(eol - p) : strlen(p);
        const char *q = p;
        while (q < p + n && (*q == ' ' || *q == '\t')) q++;
        if ((size_t)(p + n - q) > 8 && strncmp(q, "#include", 8) == 0) {
            const char *a = memchr(q, '"', (size_t)(p + n - q));
            const char *b = a ? memchr(a + 1, '"', (size_t)(p + n - a - 1)) : NULL;
            if (!a || !b || b == a + 1 || b - a > 128)
                return sss_error_set(err, SSS_ERROR_PARSE, "%s:%d: malformed #include (expected #include \"name.glsl\")",
                                     x->names[index], line);
            char name[130];
            memcpy(name, a + 1, (size_t)(b - a - 1));
            name[b - a - 1] = '\0';
            if (depth >= MAX_DEPTH)
                return sss_error_set(err, SSS_ERROR_LIMIT, "%s:%d: #include nested deeper than %d",
                                     x->names[index], line, MAX_DEPTH);
            const char *stable = NULL;
            const char *text = x->lookup(name, &stable);
            if (!text)
                return sss_error_set(err, SSS_ERROR_PARSE, "%s:%d: #include \"%s\": no such shader file",
                                     x->names[index], line, name);
            int child = file_index(x, stable, text);
            if (child < 0)
                return sss_error_set(err, SSS_ERROR_LIMIT, "%s: more than %d shader files included",
                                     x->names[index], MAX_FILES);
            if (!included[child]) {
                included[child] = 1;
                sss_result r = expand(x, child, depth + 1, NULL, out, included, err);
                if (r != SSS_OK) return r;
            }
            sb_printf(out, "#line %d %d\n", line + 1, index);
        } else {
            sb_append(out, p, n);
            sb_append(out, "\n", 1);
            if (depth == 0 && !after_version && strncmp(q, "#version", 8) == 0) {
                after_version = 1;
                if (defines && defines[0]) {
                    sb_append(out, defines, strlen(defines));
                    if (defines[strlen(defines) - 1] != '\n') sb_append(out, "\n", 1);
                }
                sb_printf(out, "#line %d %d\n", line + 1, index);
            }
        }
        line++;
        p = eol ? eol + 1 : p + n;
    }
    if (out->failed) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (shader source)");
    return SSS_OK;
}

/* Rewrites "<idx>:<line>(" (Mesa) and "<idx>(<line>)" (NVIDIA) at line starts into "<file>:<line>". */
static void rewrite_log(const expander *x, const char *log, char *out, size_t cap)
{
    size_t at = 0;
    const char *p = log;
    while (*p && at + 1 < cap) {
        const char *eol = strchr(p, '\n');
        size_t n = eol ? (size_t)(eol - p + 1) : strlen(p);
        int idx = -1, line = -1, used = 0;
        if (sscanf(p, "%d:%d%n", &idx, &line, &used) == 2 && used > 0 && idx >= 0 && idx < x->count) {
            at += (size_t)snprintf(out + at, cap - at, "%s:%d", x->names[idx], line);
        } else if (sscanf(p, "%d(%d)%n", &idx, &line, &used) == 2 && used > 0 && idx >= 0 && idx < x->count) {
            at += (size_t)snprintf(out + at, cap - at, "%s:%d", x->names[idx], line);
        } else {
            used = 0;
        }
        if (at >= cap) break;
        size_t rest = n - (size_t)used;
        if (rest > cap - at - 1) rest = cap - at - 1;
        memcpy(out + at, p + used, rest);
        at += rest;
        p += n;
    }
    if (at >= cap) at = cap - 1;
    out[at] = '\0';
    /* drop a trailing newline: messages are one line in sss_error, logs can still be multi-line */
    while (at > 0 && (out[at - 1] == '\n' || out[at - 1] == '\r')) out[--at] = '\0';
}

static const char *stage_name(GLenum stage)
{
    switch (stage) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_GEOMETRY_SHADER: return "geometry";
    case GL_COMPUTE_SHADER: return "compute";
    case GL_TESS_CONTROL_SHADER: return "tessellation control";
    case GL_TESS_EVALUATION_SHADER: return "tessellation evaluation";
    default: return "unknown";
    }
}

/* In-memory overrides for tests: a single (name, text) pair searched before the embedded files. */
static const char *override_name, *override_text;
static const char *override_lookup(const char *name, const char **stable)
{
    if (override_name && strcmp(name, override_name) == 0) {
        if (stable) *stable = override_name;
        return override_text;
    }
    return embedded_lookup(name, stable);
}

static sss_result compile_stage(const gl_shader_stage *st, const char *defines, GLuint *shader,
                                sss_error *err)
{
    *shader = 0;
    expander x = {.count = 0};
    if (st->text) {
        override_name = st->name;
        override_text = st->text;
        x.lookup = override_lookup;
    } else {
        x.lookup = embedded_lookup;
    }
    const char *text = x.lookup(st->name, NULL);
    if (!text) {
        override_name = override_text = NULL;
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "shader file %s is not embedded (*.glsl under src/gl and src/view)",
                             st->name);
    }
    file_index(&x, st->name, text);
    unsigned char included[MAX_FILES] = {1};
    strbuf src = {0};
    sss_result r = expand(&x, 0, 0, defines, &src, included, err);
    override_name = override_text = NULL;
    if (r != SSS_OK) {
        free(src.data);
        return r;
    }
    GLuint s = glCreateShader(st->stage);
    const GLchar *ptr = src.data;
    glShaderSource(s, 1, &ptr, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = "", msg[SSS_ERROR_MESSAGE_SIZE];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        rewrite_log(&x, log, msg, sizeof msg);
        glDeleteShader(s);
        free(src.data);
        return sss_error_set(err, SSS_ERROR_PARSE, "%s shader %s failed to compile: %s", stage_name(st->stage),
                             st->name, msg);
    }
    free(src.data);
    *shader = s;
    return SSS_OK;
}

sss_result gl_program_build(const gl_shader_stage *stages, int count, const char *defines, GLuint *out,
                            sss_error *err)
{
    *out = 0;
    GLuint shaders[6] = {0};
    if (count < 1 || count > 6)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "a program needs 1..6 stages, got %d", count);
    for (int i = 0; i < count; i++) {
        sss_result r = compile_stage(&stages[i], defines, &shaders[i], err);
        if (r != SSS_OK) {
            for (int k = 0; k < i; k++) glDeleteShader(shaders[k]);
            return r;
        }
    }
    GLuint prog = glCreateProgram();
    for (int i = 0; i < count; i++) glAttachShader(prog, shaders[i]);
    glLinkProgram(prog);
    for (int i = 0; i < count; i++) {
        glDetachShader(prog, shaders[i]);
        glDeleteShader(shaders[i]);
    }
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = "";
        glGetProgramInfoLog(prog, sizeof log, NULL, log);
        size_t n = strlen(log);
        while (n > 0 && (log[n - 1] == '\n' || log[n - 1] == '\r')) log[--n] = '\0';
        glDeleteProgram(prog);
        char names[256] = "";
        size_t at = 0;
        for (int i = 0; i < count && at < sizeof names; i++)
            at += (size_t)snprintf(names + at, sizeof names - at, "%s%s", i ? " + " : "", stages[i].name);
        return sss_error_set(err, SSS_ERROR_PARSE, "program %s failed to link: %s", names, log);
    }
    *out = prog;
    return SSS_OK;
}

sss_result gl_program_vf(const char *vert, const char *frag, const char *defines, GLuint *out, sss_error *err)
{
    gl_shader_stage st[2] = {{GL_VERTEX_SHADER, vert, NULL}, {GL_FRAGMENT_SHADER, frag, NULL}};
    return gl_program_build(st, 2, defines, out, err);
}

sss_result gl_program_compute(const char *comp, const char *defines, GLuint *out, sss_error *err)
{
    gl_shader_stage st[1] = {{GL_COMPUTE_SHADER, comp, NULL}};
    return gl_program_build(st, 1, defines, out, err);
}
