/* gl/technique.c — what techniques share through their interface (technique.h): drawing helpers on
 * their context, and one technique run by another. */
#include <stdlib.h>
#include <string.h>

#include "gl/technique.h"

void gl_draw_fullscreen(const gl_tech_ctx *c) { gl_fullscreen_triangle(c->vao_empty); }

void gl_resolve_begin(const gl_tech_ctx *c, GLuint prog)
{
    glBindFramebuffer(GL_FRAMEBUFFER, c->frame.fbo_final);
    glViewport(0, 0, c->width, c->height);
    glUseProgram(prog);
    glBindTextureUnit(0, c->frame.pos);
    glBindTextureUnit(1, c->frame.nrm);
    glBindTextureUnit(2, c->frame.albedo);
    glBindTextureUnit(3, c->frame.refl);
}

void gl_uniform_i(GLuint prog, const char *name, int v) { glUniform1i(glGetUniformLocation(prog, name), v); }

void gl_uniform_f(GLuint prog, const char *name, double v)
{
    glUniform1f(glGetUniformLocation(prog, name), (float)v);
}

void gl_delete_programs(const GLuint *progs, int n)
{
    for (int i = 0; i < n; i++)
        if (progs[i]) glDeleteProgram(progs[i]);
}

void gl_delete_samplers(const GLuint *samplers, int n)
{
    for (int i = 0; i < n; i++)
        if (samplers[i]) glDeleteSamplers(1, &samplers[i]);
}

void gl_draw_objects(const gl_tech_ctx *c, GLint object_uniform, int subsurface_only)
{
    gl_scene_draw_objects(c->gs, object_uniform, subsurface_only);
}

void gl_dispatch_splat_triangles(const gl_tech_ctx *c, GLuint prog)
{
    for (int i = 0; i < c->gs->object_count; i++) {
        const gl_object *o = &c->gs->objects[i];
        if (!o->subsurface || o->splat_triangle_count == 0) continue;
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_MESH_POS, o->splat_pos);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_MESH_IDX, o->splat_idx);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_SSBO_MESH_UV, o->splat_uv ? o->splat_uv : o->splat_pos);
        glUniform1i(glGetUniformLocation(prog, "u_has_uv"), o->splat_uv != 0);
        glUniform1i(glGetUniformLocation(prog, "u_object"), i);
        glUniform1ui(glGetUniformLocation(prog, "u_triangles"), o->splat_triangle_count);
        glDispatchCompute((o->splat_triangle_count + 63) / 64, 1, 1);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

sss_result gl_materials_read_at_render(const gl_tech_ctx *c, void *state, sss_error *err)
{
    (void)c, (void)state, (void)err;
    return SSS_OK;
}

/* ---- One technique run by another -------------------------------------------------------------- */

void gl_sub_init(gl_sub_technique *sub, const gl_technique *tech)
{
    memset(sub, 0, sizeof *sub);
    sub->tech = tech;
    gl_params_defaults(&tech->info, sub->params);
}

/* c with sub's parameters. */
static gl_tech_ctx sub_ctx(const gl_sub_technique *sub, const gl_tech_ctx *c)
{
    gl_tech_ctx s = *c;
    s.params = sub->params;
    s.tables_data = NULL; /* the tables were built for the caller's technique */
    return s;
}

sss_result gl_sub_create(gl_sub_technique *sub, const gl_tech_ctx *c, sss_error *err)
{
    const gl_technique *t = sub->tech;
    sub->state = calloc(1, t->state_size ? t->state_size : 1);
    if (!sub->state) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (%s state)", t->info.name);
    gl_tech_ctx s = sub_ctx(sub, c);
    sss_result res = t->create ? t->create(&s, sub->state, err) : SSS_OK;
    if (res != SSS_OK) sss_error_prefix(err, t->info.name);
    return res;
}

sss_result gl_sub_resize(gl_sub_technique *sub, const gl_tech_ctx *c, sss_error *err)
{
    if (!sub->state || !sub->tech->resize) return SSS_OK;
    gl_tech_ctx s = sub_ctx(sub, c);
    return sub->tech->resize(&s, sub->state, err);
}

sss_result gl_sub_render(gl_sub_technique *sub, const gl_tech_ctx *c, sss_error *err)
{
    gl_tech_ctx s = sub_ctx(sub, c);
    return sub->tech->render(&s, sub->state, err);
}

sss_result gl_sub_materials_changed(gl_sub_technique *sub, const gl_tech_ctx *c, sss_error *err)
{
    if (sub->tech->materials_changed) {
        gl_tech_ctx s = sub_ctx(sub, c);
        return sub->tech->materials_changed(&s, sub->state, err);
    }
    gl_sub_destroy(sub);
    return gl_sub_create(sub, c, err);
}

void gl_sub_stats(gl_sub_technique *sub, const gl_tech_ctx *c, sss_gl_stats *out)
{
    if (!sub->state || !sub->tech->stats) return;
    gl_tech_ctx s = sub_ctx(sub, c);
    sub->tech->stats(&s, sub->state, out);
}

GLuint gl_sub_target(gl_sub_technique *sub, const char *name)
{
    return sub->state && sub->tech->target ? sub->tech->target(sub->state, name) : 0;
}

void gl_sub_destroy(gl_sub_technique *sub)
{
    if (sub->state && sub->tech->destroy) sub->tech->destroy(sub->state);
    free(sub->state);
    sub->state = NULL;
}
