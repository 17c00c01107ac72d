/* examples/engine_gbuffer.c — a minimal deferred "engine" that runs an sss technique as a pass over
 * its own G-buffer (sss/gl_pass.h, docs/integration.md).
 *
 *   engine_gbuffer SCENE.json -o OUT.png [--technique T] [--frames N] [--depth-only]
 *
 * --frames N renders N frames and prints the median wall time of the engine's frame and of the sss
 * pass in it (glFinish around each; the first frames include shader compilation).
 * The engine owns everything but the subsurface pass: its OpenGL context (plain EGL, which sss adopts
 * with sss_gl_context_adopt_current), its G-buffer shaders, its lighting, its shadow
 * maps (a distance cube map per point or spot light, an orthographic depth map per directional
 * light), written here from scratch; meshes, materials and lights come from the scene file through
 * the public scene and mesh API. sss only reads the engine's textures and writes the subsurface
 * radiance (plus the engine's reflected light) into the engine's output texture. The image is the one
 * `sss render SCENE --technique T` writes, within shadow-map details (tests/cli/engine_gbuffer.sh).
 *
 * Scope of this engine: point, spot and directional lights; subsurface and diffuse materials without
 * textures or specular layers; no animation (time 0). Other scenes are refused with a message.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <sss/sss.h>

#define MAX_LIGHTS 4
#define CUBE_SIZE 1024
#define MAP_SIZE 2048

/* ---- Column-major 4x4 matrices ------------------------------------------------------------------ */

static void mat_mul(const float a[16], const float b[16], float out[16])
{
    float t[16];
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++) s += a[4 * k + r] * b[4 * c + k];
            t[4 * c + r] = s;
        }
    memcpy(out, t, sizeof t);
}

static void from_rows(const double m[16], float out[16])
{
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) out[4 * c + r] = (float)m[4 * r + c];
}

static void look_at(const double eye[3], const double dir[3], const double up_in[3], float m[16])
{
    double f[3], s[3], u[3], up[3] = {up_in[0], up_in[1], up_in[2]};
    double fl = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (int i = 0; i < 3; i++) f[i] = dir[i] / fl;
    if (fabs(f[0] * up[0] + f[1] * up[1] + f[2] * up[2]) > 0.999) up[0] = 1, up[1] = 0, up[2] = 0;
    s[0] = f[1] * up[2] - f[2] * up[1], s[1] = f[2] * up[0] - f[0] * up[2], s[2] = f[0] * up[1] - f[1] * up[0];
    double sl = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int i = 0; i < 3; i++) s[i] /= sl;
    u[0] = s[1] * f[2] - s[2] * f[1], u[1] = s[2] * f[0] - s[0] * f[2], u[2] = s[0] * f[1] - s[1] * f[0];
    memset(m, 0, 16 * sizeof(float));
    for (int i = 0; i < 3; i++) {
        m[4 * i + 0] = (float)s[i];
        m[4 * i + 1] = (float)u[i];
        m[4 * i + 2] = (float)-f[i];
    }
    m[12] = (float)-(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
    m[13] = (float)-(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
    m[14] = (float)(f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2]);
    m[15] = 1.0f;
}

static void perspective(double fovy, double n, double f, float m[16])
{
    double t = 1.0 / tan(fovy / 2.0);
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = (float)t;
    m[10] = (float)((f + n) / (n - f));
    m[11] = -1.0f;
    m[14] = (float)(2.0 * f * n / (n - f));
}

static void ortho(double half, double n, double f, float m[16])
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = (float)(1.0 / half);
    m[10] = (float)(-2.0 / (f - n));
    m[14] = (float)(-(f + n) / (f - n));
    m[15] = 1.0f;
}

/* ---- The engine's own context ------------------------------------------------------------------------
 * Headless EGL as a windowed engine would use GLFW or SDL: sss adopts whatever context is current.
 * eglGetPlatformDisplayEXT rather than the EGL 1.5 eglGetPlatformDisplay, which libepoxy cannot
 * resolve before a display exists; surfaceless Mesa first, then the first EGL device. */

typedef struct engine_context {
    EGLDisplay display;
    EGLContext context;
} engine_context;

static EGLDisplay engine_display(void)
{
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base")) return EGL_NO_DISPLAY;
    EGLDisplay dpy = EGL_NO_DISPLAY;
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless"))
        dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (dpy != EGL_NO_DISPLAY && eglInitialize(dpy, NULL, NULL)) return dpy;
    EGLDeviceEXT device;
    EGLint count = 0;
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") ||
        !eglQueryDevicesEXT(1, &device, &count) || count < 1)
        return EGL_NO_DISPLAY;
    dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, NULL);
    return dpy != EGL_NO_DISPLAY && eglInitialize(dpy, NULL, NULL) ? dpy : EGL_NO_DISPLAY;
}

/* An OpenGL 4.5 core context without a surface (the engine renders into its own framebuffers). */
static int engine_context_create(engine_context *c)
{
    c->context = EGL_NO_CONTEXT;
    c->display = engine_display();
    if (c->display == EGL_NO_DISPLAY || !eglBindAPI(EGL_OPENGL_API)) return 0;
    EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    c->context = eglCreateContext(c->display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    return c->context != EGL_NO_CONTEXT &&
           eglMakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, c->context);
}

static void engine_context_destroy(engine_context *c)
{
    if (c->context == EGL_NO_CONTEXT) return;
    eglMakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(c->display, c->context);
    eglReleaseThread(); /* no eglTerminate: Mesa's display is per process (as in sss) */
}

/* ---- The engine's shaders ------------------------------------------------------------------------ */

static const char *vs_mesh =
    "#version 450 core\n"
    "layout(location = 0) in vec3 a_pos;\n"
    "layout(location = 1) in vec3 a_nrm;\n"
    "uniform mat4 u_model, u_view_proj;\n"
    "uniform mat3 u_normal;\n"
    "out vec3 v_pos, v_nrm;\n"
    "void main() {\n"
    "  v_pos = (u_model * vec4(a_pos, 1.0)).xyz;\n"
    "  v_nrm = u_normal * a_nrm;\n"
    "  gl_Position = u_view_proj * vec4(v_pos, 1.0);\n"
    "}\n";

/* G-buffer in the layout sss/gl_pass.h asks for: position + pixel area, normal + id, albedo + eta. */
static const char *fs_gbuffer =
    "#version 450 core\n"
    "in vec3 v_pos, v_nrm;\n"
    "uniform vec3 u_eye, u_albedo;\n"
    "uniform int u_id, u_diffuse;\n"
    "uniform float u_eta, u_grazing;\n"
    "layout(location = 0) out vec4 o_pos;\n"
    "layout(location = 1) out vec4 o_nrm;\n"
    "layout(location = 2) out vec4 o_albedo;\n"
    "void main() {\n"
    "  vec3 n = normalize(v_nrm);\n"
    "  if (u_diffuse != 0 && !gl_FrontFacing) n = -n;\n"
    "  float area = length(cross(dFdx(v_pos), dFdy(v_pos)));\n"
    "  if (u_diffuse != 0 || dot(n, normalize(u_eye - v_pos)) < u_grazing || isinf(area) || isnan(area)) area = 0.0;\n"
    "  o_pos = vec4(v_pos, area);\n"
    "  o_nrm = vec4(n, float(u_id));\n"
    "  o_albedo = vec4(u_albedo, u_eta);\n"
    "}\n";

/* Shadow maps: the distance to the light (cube faces) or the depth (directional). */
static const char *fs_shadow =
    "#version 450 core\n"
    "in vec3 v_pos, v_nrm;\n"
    "uniform vec3 u_light;\n"
    "uniform int u_distance;\n"
    "layout(location = 0) out float o_depth;\n"
    "void main() { o_depth = u_distance != 0 ? length(v_pos - u_light) : gl_FragCoord.z; }\n";

static const char *vs_fullscreen =
    "#version 450 core\n"
    "void main() { vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2); gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0); }\n";

/* Lighting: the reflected radiance of diffuse surfaces, and for subsurface ones the irradiance the
 * pass scatters, times the entry Fresnel transmittance 1 - Fr(n.l) and sqrt(albedo). */
static const char *fs_lighting =
    "#version 450 core\n"
    "#define MAX_LIGHTS " "4" "\n"
    "layout(binding = 0) uniform sampler2D g_pos;\n"
    "layout(binding = 1) uniform sampler2D g_nrm;\n"
    "layout(binding = 2) uniform sampler2D g_albedo;\n"
    "layout(binding = 3) uniform samplerCube u_cube[MAX_LIGHTS];\n"
    "layout(binding = 7) uniform sampler2D u_map[MAX_LIGHTS];\n"
    "uniform int u_count;\n"
    "uniform int u_type[MAX_LIGHTS];\n" /* 0 point, 1 spot, 2 directional */
    "uniform vec3 u_lpos[MAX_LIGHTS], u_ldir[MAX_LIGHTS], u_color[MAX_LIGHTS];\n"
    "uniform vec2 u_cone[MAX_LIGHTS];\n" /* cos total width, cos falloff start */
    "uniform mat4 u_light_vp[MAX_LIGHTS];\n"
    "uniform float u_texel[MAX_LIGHTS];\n" /* world size of a shadow texel (at distance 1 for cubes) */
    "layout(location = 0) out vec4 o_irr;\n"
    "layout(location = 1) out vec4 o_refl;\n"
    "float fresnel(float ci, float eta) {\n" /* unpolarised dielectric reflectance, from air */
    "  ci = clamp(ci, 0.0, 1.0); float si = sqrt(1.0 - ci * ci) / eta;\n"
    "  if (si >= 1.0) return 1.0;\n"
    "  float ct = sqrt(1.0 - si * si);\n"
    "  float rs = (ci - eta * ct) / (ci + eta * ct), rp = (eta * ci - ct) / (eta * ci + ct);\n"
    "  return 0.5 * (rs * rs + rp * rp);\n"
    "}\n"
    "float visibility(int i, vec3 p, vec3 n) {\n"
    "  if (u_type[i] != 2) {\n"
    "    float texel = length(p - u_lpos[i]) * u_texel[i];\n"
    "    vec3 d = p + n * 1.5 * texel - u_lpos[i];\n"
    "    return length(d) - 1.5 * texel <= texture(u_cube[i], d).r ? 1.0 : 0.0;\n"
    "  }\n"
    "  vec4 c = u_light_vp[i] * vec4(p + n * 1.5 * u_texel[i], 1.0);\n"
    "  vec3 q = c.xyz / c.w * 0.5 + 0.5;\n"
    "  if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0))) || q.z >= 1.0) return 1.0;\n"
    "  return q.z <= texture(u_map[i], q.xy).r ? 1.0 : 0.0;\n"
    "}\n"
    "void main() {\n"
    "  ivec2 px = ivec2(gl_FragCoord.xy);\n"
    "  vec4 N = texelFetch(g_nrm, px, 0);\n"
    "  o_irr = vec4(0.0, 0.0, 0.0, N.w); o_refl = vec4(0.0, 0.0, 0.0, 1.0);\n"
    "  if (N.w < 0.5) return;\n"
    "  vec3 p = texelFetch(g_pos, px, 0).xyz, n = normalize(N.xyz);\n"
    "  vec4 A = texelFetch(g_albedo, px, 0);\n"
    "  bool diffuse = A.a == 0.0;\n" /* the engine writes eta 0 for opaque surfaces */
    "  vec3 et = vec3(0.0), refl = vec3(0.0);\n"
    "  for (int i = 0; i < u_count; i++) {\n"
    "    vec3 l, E;\n"
    "    if (u_type[i] == 2) { l = -u_ldir[i]; E = u_color[i]; }\n"
    "    else {\n"
    "      vec3 d = u_lpos[i] - p; float d2 = dot(d, d); l = d / sqrt(d2); E = u_color[i] / d2;\n"
    "      if (u_type[i] == 1) {\n"
    "        float ct = dot(u_ldir[i], -l);\n"
    "        float s = ct < u_cone[i].x ? 0.0 : ct >= u_cone[i].y ? 1.0 : (ct - u_cone[i].x) / (u_cone[i].y - u_cone[i].x);\n"
    "        E *= (s * s) * (s * s);\n"
    "      }\n"
    "    }\n"
    "    float cl = dot(n, l);\n"
    "    if (cl <= 0.0) continue;\n"
    "    E *= cl * visibility(i, p, n);\n"
    "    if (diffuse) refl += A.rgb / 3.14159265358979 * E;\n"
    "    else et += (1.0 - fresnel(cl, A.a)) * E;\n"
    "  }\n"
    "  o_irr = vec4(diffuse ? vec3(0.0) : et * sqrt(A.rgb), N.w);\n"
    "  o_refl = vec4(refl, 1.0);\n"
    "}\n";

static GLuint program(const char *vs, const char *fs)
{
    GLuint p = glCreateProgram();
    const char *src[2] = {vs, fs};
    GLenum kinds[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    for (int i = 0; i < 2; i++) {
        GLuint s = glCreateShader(kinds[i]);
        glShaderSource(s, 1, &src[i], NULL);
        glCompileShader(s);
        GLint ok = 0;
        glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[2048];
            glGetShaderInfoLog(s, sizeof log, NULL, log);
            fprintf(stderr, "engine_gbuffer: shader: %s\n", log);
        }
        glAttachShader(p, s);
        glDeleteShader(s);
    }
    glLinkProgram(p);
    return p;
}

static GLuint texture_2d(GLenum format, int w, int h, int levels)
{
    GLuint t;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, levels, format, w, h);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, levels > 1 ? GL_LINEAR : GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

static int mip_levels(int w, int h)
{
    int m = w > h ? w : h, n = 1;
    while (m > 1) m >>= 1, n++;
    return n;
}

/* ---- The engine ----------------------------------------------------------------------------------- */

typedef struct mesh_gpu {
    GLuint vao, buffers[3];
    GLsizei index_count;
} mesh_gpu;

typedef struct engine {
    const sss_scene *scene;
    int width, height;
    mesh_gpu *meshes;
    GLuint prog_gbuffer, prog_shadow, prog_lighting, vao_empty;
    GLuint pos, nrm, albedo, depth, irr, refl, out, fbo_gbuffer, fbo_light;
    GLuint shadow[MAX_LIGHTS], shadow_depth[MAX_LIGHTS], fbo_shadow;
    float light_vp[MAX_LIGHTS][16], texel[MAX_LIGHTS];
    double center[3], radius;
    int depth_only; /* --depth-only: the pass gets the depth buffer instead of world positions */
} engine;

static void upload(mesh_gpu *g, const sss_mesh *m)
{
    glCreateVertexArrays(1, &g->vao);
    glCreateBuffers(3, g->buffers);
    glNamedBufferStorage(g->buffers[0], sizeof(float) * 3 * m->vertex_count, m->positions, 0);
    glNamedBufferStorage(g->buffers[1], sizeof(float) * 3 * m->vertex_count, m->normals, 0);
    glNamedBufferStorage(g->buffers[2], sizeof(uint32_t) * 3 * m->triangle_count, m->indices, 0);
    for (GLuint a = 0; a < 2; a++) {
        glVertexArrayVertexBuffer(g->vao, a, g->buffers[a], 0, 3 * sizeof(float));
        glVertexArrayAttribFormat(g->vao, a, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(g->vao, a, a);
        glEnableVertexArrayAttrib(g->vao, a);
    }
    glVertexArrayElementBuffer(g->vao, g->buffers[2]);
    g->index_count = (GLsizei)(3 * m->triangle_count);
}

/* What this engine does not do is refused rather than rendered differently. */
static int check_scope(const sss_scene *s)
{
    if (s->light_count > MAX_LIGHTS) return fprintf(stderr, "engine_gbuffer: at most %d lights\n", MAX_LIGHTS), 0;
    for (size_t i = 0; i < s->light_count; i++)
        if (s->lights[i].type > SSS_LIGHT_DIRECTIONAL)
            return fprintf(stderr, "engine_gbuffer: lights[%zu]: only point, spot and directional lights\n", i), 0;
    for (size_t i = 0; i < s->object_count; i++) {
        const sss_scene_object *o = &s->objects[i];
        if (o->animation.type != SSS_ANIMATION_NONE || o->material.texture || o->material.has_specular ||
            o->material.type > SSS_SCENE_MATERIAL_DIFFUSE)
            return fprintf(stderr, "engine_gbuffer: objects[%zu]: animation, textures, specular and emitters are "
                                   "not supported by this example\n", i), 0;
    }
    return 1;
}

static void draw_meshes(engine *e, GLuint prog, const float view_proj[16])
{
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE, view_proj);
    for (size_t i = 0; i < e->scene->object_count; i++) {
        const sss_scene_object *o = &e->scene->objects[i];
        float model[16], nm[9];
        from_rows(o->transform.matrix, model);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) nm[3 * c + r] = (float)o->transform.normal_matrix[3 * r + c];
        glUniformMatrix4fv(glGetUniformLocation(prog, "u_model"), 1, GL_FALSE, model);
        glUniformMatrix3fv(glGetUniformLocation(prog, "u_normal"), 1, GL_FALSE, nm);
        const sss_scene_material *m = &o->material;
        int diffuse = m->type == SSS_SCENE_MATERIAL_DIFFUSE;
        float albedo[3] = {1, 1, 1};
        for (int c = 0; diffuse && c < 3; c++) albedo[c] = (float)m->albedo[c];
        glUniform3fv(glGetUniformLocation(prog, "u_albedo"), 1, albedo);
        glUniform1i(glGetUniformLocation(prog, "u_id"), (int)i + 1);
        glUniform1i(glGetUniformLocation(prog, "u_diffuse"), diffuse);
        glUniform1f(glGetUniformLocation(prog, "u_eta"), diffuse ? 0.0f : (float)m->optical.eta);
        glBindVertexArray(e->meshes[i].vao);
        glDrawElements(GL_TRIANGLES, e->meshes[i].index_count, GL_UNSIGNED_INT, NULL);
    }
}

static void scene_sphere(engine *e)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < e->scene->object_count; i++) {
        const sss_scene_object *o = &e->scene->objects[i];
        const double *M = o->transform.matrix;
        for (uint32_t v = 0; v < o->mesh.vertex_count; v++) {
            const float *p = &o->mesh.positions[3 * v];
            for (int r = 0; r < 3; r++) {
                double w = M[4 * r] * p[0] + M[4 * r + 1] * p[1] + M[4 * r + 2] * p[2] + M[4 * r + 3];
                lo[r] = fmin(lo[r], w), hi[r] = fmax(hi[r], w);
            }
        }
    }
    double d2 = 0.0;
    for (int k = 0; k < 3; k++) e->center[k] = 0.5 * (lo[k] + hi[k]), d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    e->radius = 0.5 * sqrt(d2);
}

/* One shadow map per light: six distance faces, or an orthographic depth map over the scene. */
static void render_shadows(engine *e)
{
    glUseProgram(e->prog_shadow);
    glEnable(GL_DEPTH_TEST);
    for (size_t i = 0; i < e->scene->light_count; i++) {
        const sss_light *L = &e->scene->lights[i];
        GLuint loc_light = (GLuint)glGetUniformLocation(e->prog_shadow, "u_light");
        if (L->type == SSS_LIGHT_DIRECTIONAL) {
            double eye[3], up[3] = {0, 1, 0};
            for (int k = 0; k < 3; k++) eye[k] = e->center[k] - 2.0 * e->radius * L->direction[k];
            float V[16], P[16];
            look_at(eye, L->direction, up, V);
            ortho(e->radius * 1.01, e->radius * 0.9, e->radius * 3.1, P);
            mat_mul(P, V, e->light_vp[i]);
            e->texel[i] = (float)(2.0 * e->radius * 1.01 / MAP_SIZE);
            glNamedFramebufferTexture(e->fbo_shadow, GL_COLOR_ATTACHMENT0, e->shadow[i], 0);
            glNamedFramebufferTexture(e->fbo_shadow, GL_DEPTH_ATTACHMENT, e->shadow_depth[i], 0);
            glBindFramebuffer(GL_FRAMEBUFFER, e->fbo_shadow);
            glViewport(0, 0, MAP_SIZE, MAP_SIZE);
            glClearColor(1, 1, 1, 1);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glUniform1i(glGetUniformLocation(e->prog_shadow, "u_distance"), 0);
            draw_meshes(e, e->prog_shadow, e->light_vp[i]);
            continue;
        }
        static const double dirs[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        static const double ups[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
        double far_d = 0.0;
        for (int k = 0; k < 3; k++) far_d += (L->position[k] - e->center[k]) * (L->position[k] - e->center[k]);
        far_d = sqrt(far_d) + e->radius;
        e->texel[i] = 2.0f / CUBE_SIZE;
        glUniform3f((GLint)loc_light, (float)L->position[0], (float)L->position[1], (float)L->position[2]);
        glUniform1i(glGetUniformLocation(e->prog_shadow, "u_distance"), 1);
        for (int f = 0; f < 6; f++) {
            float V[16], P[16], VP[16];
            look_at(L->position, dirs[f], ups[f], V);
            perspective(M_PI / 2.0, far_d * 1e-4, far_d * 1.01, P);
            mat_mul(P, V, VP);
            glNamedFramebufferTextureLayer(e->fbo_shadow, GL_COLOR_ATTACHMENT0, e->shadow[i], 0, f);
            glNamedFramebufferTexture(e->fbo_shadow, GL_DEPTH_ATTACHMENT, e->shadow_depth[i], 0);
            glBindFramebuffer(GL_FRAMEBUFFER, e->fbo_shadow);
            glViewport(0, 0, CUBE_SIZE, CUBE_SIZE);
            glClearColor(1e30f, 1e30f, 1e30f, 1e30f);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            draw_meshes(e, e->prog_shadow, VP);
        }
    }
    glDisable(GL_DEPTH_TEST);
}

static void create_targets(engine *e, const sss_gl_pass_info *info)
{
    int w = e->width, h = e->height, levels = mip_levels(w, h);
    e->pos = texture_2d(GL_RGBA32F, w, h, info->needs_mips ? levels : 1);
    e->nrm = texture_2d(GL_RGBA32F, w, h, info->needs_normal_mips ? levels : 1);
    e->albedo = texture_2d(GL_RGBA16F, w, h, 1);
    e->depth = texture_2d(GL_DEPTH_COMPONENT32F, w, h, 1);
    e->irr = texture_2d(GL_RGBA32F, w, h, info->needs_mips ? levels : 1);
    e->refl = texture_2d(GL_RGBA16F, w, h, 1);
    e->out = texture_2d(GL_RGBA32F, w, h, 1);
    static const GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glCreateFramebuffers(1, &e->fbo_gbuffer);
    GLuint g[3] = {e->pos, e->nrm, e->albedo};
    for (int i = 0; i < 3; i++) glNamedFramebufferTexture(e->fbo_gbuffer, bufs[i], g[i], 0);
    glNamedFramebufferTexture(e->fbo_gbuffer, GL_DEPTH_ATTACHMENT, e->depth, 0);
    glNamedFramebufferDrawBuffers(e->fbo_gbuffer, 3, bufs);
    glCreateFramebuffers(1, &e->fbo_light);
    glNamedFramebufferTexture(e->fbo_light, bufs[0], e->irr, 0);
    glNamedFramebufferTexture(e->fbo_light, bufs[1], e->refl, 0);
    glNamedFramebufferDrawBuffers(e->fbo_light, 2, bufs);
    glCreateFramebuffers(1, &e->fbo_shadow);
    for (size_t i = 0; i < e->scene->light_count; i++) {
        int cube = e->scene->lights[i].type != SSS_LIGHT_DIRECTIONAL, size = cube ? CUBE_SIZE : MAP_SIZE;
        glCreateTextures(cube ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D, 1, &e->shadow[i]);
        glTextureStorage2D(e->shadow[i], 1, GL_R32F, size, size);
        glTextureParameteri(e->shadow[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(e->shadow[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(e->shadow[i], GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(e->shadow[i], GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        e->shadow_depth[i] = texture_2d(GL_DEPTH_COMPONENT32F, size, size, 1);
    }
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* The engine's frame: G-buffer, shadow maps, lighting; then the sss pass (its time in *pass_ms). */
static sss_result render_frame(engine *e, sss_gl_pass *pass, sss_gl_pass_frame *f, double *pass_ms, sss_error *err)
{
    sss_camera_basis b;
    sss_result res = sss_camera_basis_init(&e->scene->camera, &b, err);
    if (res != SSS_OK) return res;
    double far_d = 0.0;
    for (int k = 0; k < 3; k++) far_d += (b.origin[k] - e->center[k]) * (b.origin[k] - e->center[k]);
    far_d = sqrt(far_d) + 1.05 * e->radius;
    double v[16], p[16];
    sss_camera_view_matrix(&b, v);
    sss_camera_projection_matrix(&b, far_d * 1e-4, far_d, p);
    from_rows(v, f->view);
    from_rows(p, f->proj);
    float view_proj[16];
    mat_mul(f->proj, f->view, view_proj);

    glBindFramebuffer(GL_FRAMEBUFFER, e->fbo_gbuffer);
    glViewport(0, 0, e->width, e->height);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glUseProgram(e->prog_gbuffer);
    glUniform3f(glGetUniformLocation(e->prog_gbuffer, "u_eye"), (float)b.origin[0], (float)b.origin[1], (float)b.origin[2]);
    glUniform1f(glGetUniformLocation(e->prog_gbuffer, "u_grazing"), 0.2f); /* maisch2020's grazing_cutoff */
    draw_meshes(e, e->prog_gbuffer, view_proj);
    glDisable(GL_DEPTH_TEST);

    render_shadows(e);

    GLuint L = e->prog_lighting;
    glUseProgram(L);
    glBindFramebuffer(GL_FRAMEBUFFER, e->fbo_light);
    glViewport(0, 0, e->width, e->height);
    GLuint gtex[3] = {e->pos, e->nrm, e->albedo};
    for (GLuint u = 0; u < 3; u++) glBindTextureUnit(u, gtex[u]);
    glUniform1i(glGetUniformLocation(L, "u_count"), (int)e->scene->light_count);
    char name[64];
    for (size_t i = 0; i < e->scene->light_count; i++) {
        const sss_light *lt = &e->scene->lights[i];
        int type = lt->type == SSS_LIGHT_POINT ? 0 : lt->type == SSS_LIGHT_SPOT ? 1 : 2;
        float pos[3], dir[3], col[3];
        double axis[3], len = 0.0;
        for (int k = 0; k < 3; k++) axis[k] = lt->look_at[k] - lt->position[k], len += axis[k] * axis[k];
        for (int k = 0; k < 3; k++) {
            pos[k] = (float)lt->position[k];
            dir[k] = (float)(type == 2 ? lt->direction[k] : type == 1 ? axis[k] / sqrt(len) : 0.0);
            col[k] = (float)(type == 2 ? lt->radiance[k] : lt->intensity[k]);
        }
#define SET(fn, field, ...) (snprintf(name, sizeof name, "%s[%zu]", field, i), fn(glGetUniformLocation(L, name), __VA_ARGS__))
        SET(glUniform1i, "u_type", type);
        SET(glUniform3fv, "u_lpos", 1, pos);
        SET(glUniform3fv, "u_ldir", 1, dir);
        SET(glUniform3fv, "u_color", 1, col);
        SET(glUniform2f, "u_cone", (float)cos(lt->cone_angle * M_PI / 180.0),
            (float)cos((lt->cone_angle - lt->cone_delta) * M_PI / 180.0));
        SET(glUniformMatrix4fv, "u_light_vp", 1, GL_FALSE, e->light_vp[i]);
        SET(glUniform1f, "u_texel", e->texel[i]);
#undef SET
        glBindTextureUnit((GLuint)(type == 2 ? 7 + i : 3 + i), e->shadow[i]);
    }
    glBindVertexArray(e->vao_empty);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    /* The subsurface pass reads the engine's textures and writes e->out. An engine that keeps depth
     * rather than world positions hands its depth buffer over instead (--depth-only). */
    f->position = e->depth_only ? 0 : e->pos;
    f->depth = e->depth_only ? e->depth : 0;
    f->normal = e->nrm;
    f->albedo = e->albedo;
    f->irradiance = e->irr;
    f->reflected = e->refl;
    f->output = e->out;
    f->time = 0.0;
    glFinish();
    double t0 = now_ms();
    res = sss_gl_pass_execute(pass, f, err);
    glFinish();
    *pass_ms = now_ms() - t0;
    return res;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, by_value);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static int write_output(engine *e, const char *path, sss_error *err)
{
    size_t n = (size_t)e->width * (size_t)e->height;
    float *rgba = malloc(n * 4 * sizeof(float));
    sss_image img = {0};
    int ok = rgba && sss_image_create(&img, e->width, e->height, err) == SSS_OK;
    if (ok) {
        glGetTextureImage(e->out, 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * 4 * sizeof(float)), rgba);
        for (int y = 0; y < e->height; y++) /* GL rows run bottom-up */
            for (int x = 0; x < e->width; x++)
                for (int c = 0; c < 3; c++)
                    img.pixels[3 * ((size_t)y * e->width + x) + c] = rgba[4 * ((size_t)(e->height - 1 - y) * e->width + x) + c];
        ok = sss_image_write(path, &img, e->scene->render.exposure, err) == SSS_OK;
    }
    sss_image_free(&img);
    free(rgba);
    return ok;
}

int main(int argc, char **argv)
{
    const char *scene_path = NULL, *output = NULL, *technique = NULL;
    int frames = 1, depth_only = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) output = argv[++i];
        else if (strcmp(argv[i], "--frames") == 0 && i + 1 < argc && atoi(argv[i + 1]) >= 1 && atoi(argv[i + 1]) <= 1000)
            frames = atoi(argv[++i]);
        else if (strcmp(argv[i], "--technique") == 0 && i + 1 < argc) technique = argv[++i];
        else if (strcmp(argv[i], "--depth-only") == 0) depth_only = 1;
        else if (argv[i][0] != '-' && !scene_path) scene_path = argv[i];
        else scene_path = NULL, i = argc;
    }
    if (!scene_path || !output) {
        fprintf(stderr, "usage: %s SCENE.json -o OUT.png [--technique T] [--frames N (1..1000)] [--depth-only]\n",
                argv[0]);
        return 2;
    }
    sss_error err = {0};
    sss_scene scene;
    if (sss_scene_load(scene_path, NULL, &scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    if (!check_scope(&scene)) {
        sss_scene_free(&scene);
        return 1;
    }
    engine_context own = {EGL_NO_DISPLAY, EGL_NO_CONTEXT};
    sss_gl_context *context = NULL;
    sss_gl_pass *pass = NULL;
    engine e;
    memset(&e, 0, sizeof e);
    e.scene = &scene;
    e.depth_only = depth_only;
    e.width = scene.camera.width;
    e.height = scene.camera.height;
    int status = 1;
    if (!engine_context_create(&own)) {
        snprintf(err.message, sizeof err.message, "engine_gbuffer: no headless OpenGL 4.5 core context (EGL)");
        goto done;
    }
    /* sss uses the engine's context (current on this thread) without owning it. */
    if (sss_gl_context_adopt_current(&context, &err) != SSS_OK) goto done;
    /* The pass: the scene registers the materials (surface id i + 1 = objects[i]) and, for
     * translucency techniques, the meshes and lights it lights its splats with. */
    sss_gl_pass_desc pd = {0};
    pd.technique = technique;
    pd.scene = &scene;
    pd.width = e.width;
    pd.height = e.height;
    if (sss_gl_pass_create(context, &pd, &pass, &err) != SSS_OK) goto done;
    sss_gl_pass_info info;
    sss_gl_pass_get_info(pass, &info);
    e.meshes = calloc(scene.object_count ? scene.object_count : 1, sizeof *e.meshes);
    if (!e.meshes) goto done;
    for (size_t i = 0; i < scene.object_count; i++) upload(&e.meshes[i], &scene.objects[i].mesh);
    e.prog_gbuffer = program(vs_mesh, fs_gbuffer);
    e.prog_shadow = program(vs_mesh, fs_shadow);
    e.prog_lighting = program(vs_fullscreen, fs_lighting);
    glCreateVertexArrays(1, &e.vao_empty);
    scene_sphere(&e);
    create_targets(&e, &info);
    sss_gl_pass_frame frame = {0};
    double frame_ms[1000], pass_ms[1000];
    for (int k = 0; k < frames; k++) {
        double t0 = now_ms();
        if (render_frame(&e, pass, &frame, &pass_ms[k], &err) != SSS_OK) goto done;
        frame_ms[k] = now_ms() - t0;
    }
    if (frames > 1)
        printf("%d frames %dx%d: median engine frame %.1f ms, of which the sss pass %.1f ms\n", frames, e.width,
               e.height, median(frame_ms, frames), median(pass_ms, frames));
    if (!write_output(&e, output, &err)) goto done;
    status = 0;
done:
    if (status) fprintf(stderr, "%s\n", err.message[0] ? err.message : "engine_gbuffer: out of memory");
    sss_gl_pass_destroy(pass);
    free(e.meshes);
    sss_gl_context_destroy(context); /* the wrapper only: the engine's context stays */
    /* The engine's GL objects go with its context. */
    engine_context_destroy(&own);
    sss_scene_free(&scene);
    return status;
}
