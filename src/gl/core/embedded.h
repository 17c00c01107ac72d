/* gl/embedded.h — the GLSL sources (src/gl/core/shaders, src/gl/<technique>, src/view/shaders), embedded
 * into the binary at build time (cmake/embed_files.cmake). Looked up by file name, e.g.
 * "gbuffer.vert.glsl". */
#ifndef SSS_GL_EMBEDDED_H
#define SSS_GL_EMBEDDED_H

#include <stddef.h>

typedef struct sss_embedded_file {
    const char *name;
    const char *data; /* NUL-terminated */
    size_t size;      /* without the NUL */
} sss_embedded_file;

extern const sss_embedded_file sss_embedded_shaders[]; /* ends with a {0} entry */
extern const int sss_embedded_shader_count;

/* The embedded file with this name, or NULL. */
const sss_embedded_file *sss_embedded_shader_find(const char *name);

#endif
