/* tests/gl/gl_probe_util.h — a compute "probe" of common.glsl functions: a headless context, a compute
 * program built from a test's source (which #includes common.glsl), the SSBOs common.glsl declares
 * bound to placeholders (objects: one gl_object_record the test may write), and an io buffer at
 * binding 4 for the probe's inputs and outputs. */
#ifndef SSS_GL_PROBE_UTIL_H
#define SSS_GL_PROBE_UTIL_H

#include <stdio.h>
#include <string.h>

#include "check.h"
#include "gl/core/gl_base.h"

typedef struct gt_probe {
    sss_gl_context *ctx;
    GLuint prog;
    GLuint objs, io, mats, lights, scales;
} gt_probe;

/* 1 on success; on failure prints why and leaves nothing to destroy. */
static inline int gt_probe_create(gt_probe *p, const char *name, const char *src, size_t io_bytes)
{
    memset(p, 0, sizeof *p);
    sss_error err = {0};
    if (sss_gl_context_create(NULL, &p->ctx, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    gl_shader_stage st = {GL_COMPUTE_SHADER, name, src};
    if (gl_program_build(&st, 1, NULL, &p->prog, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        sss_gl_context_destroy(p->ctx);
        p->ctx = NULL;
        return 0;
    }
    GLuint *b[5] = {&p->objs, &p->io, &p->mats, &p->lights, &p->scales};
    for (int i = 0; i < 5; i++) glCreateBuffers(1, b[i]);
    glNamedBufferStorage(p->objs, sizeof(gl_object_record), NULL, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(p->io, (GLsizeiptr)io_bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(p->mats, 64, NULL, 0);
    glNamedBufferStorage(p->lights, 144, NULL, 0);
    glNamedBufferStorage(p->scales, 16, NULL, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_OBJECTS, p->objs);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_MATERIALS, p->mats);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_LIGHTS, p->lights);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_LUT_SCALES, p->scales);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, p->io);
    return 1;
}

/* Writes io, runs `count` invocations (uniform u_count; local size 64), reads io back. */
static inline void gt_probe_run(gt_probe *p, void *io, size_t io_bytes, unsigned count)
{
    glNamedBufferSubData(p->io, 0, (GLsizeiptr)io_bytes, io);
    glUseProgram(p->prog);
    glUniform1ui(glGetUniformLocation(p->prog, "u_count"), count);
    glDispatchCompute((count + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(p->io, 0, (GLsizeiptr)io_bytes, io);
}

/* Checks for GL errors (CHECK), then frees everything. */
static inline void gt_probe_destroy(gt_probe *p, const char *what)
{
    sss_error err = {0};
    CHECK_MSG(gl_check(p->ctx, what, &err) == SSS_OK, "%s", err.message);
    GLuint bufs[5] = {p->objs, p->io, p->mats, p->lights, p->scales};
    glDeleteBuffers(5, bufs);
    glDeleteProgram(p->prog);
    sss_gl_context_destroy(p->ctx);
    memset(p, 0, sizeof *p);
}

#endif
