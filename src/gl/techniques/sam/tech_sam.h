/* gl/techniques/sam/tech_sam.h — internals of the technique "sam" (Maisch & Ropinski 2017): the GPU data of one subsurface object
 * (tech_sam_data.c) and the technique's passes (tech_sam.c). */
#ifndef SSS_GL_TECH_SAM_H
#define SSS_GL_TECH_SAM_H

#include "gl/technique.h"
#include "sss/sam.h"

/* Binding points of src/gl/techniques/sam/sam_vertex.comp.glsl (10..19; the shared ones are 0..9). */
enum {
    SAM_SSBO_TOPO = 10,
    SAM_SSBO_GEOM = 11,
    SAM_SSBO_LINKS = 12,
    SAM_SSBO_COEF = 13,
    SAM_SSBO_LD = 14,
    SAM_SSBO_TRANS = 15,
    SAM_SSBO_RD = 16,
    SAM_SSBO_POS = 17,
    SAM_SSBO_NRM = 18,
    SAM_SSBO_UV = 19,
    SAM_SSBO_SRC_GEOM = 20, /* the sources of Eq. 12: the back-side mesh's geometry, or the mesh's own */
    SAM_SSBO_SRC_TOPO = 21
};

/* Section offsets of a topology buffer: [adjacency offsets (V + 1) | neighbours | incidence offsets
 * (V + 1) | triangles | indices (3 T)]. */
typedef struct sam_topo_offsets {
    uint32_t adj_list, inc_off, inc_list, idx;
} sam_topo_offsets;

typedef struct sam_object {
    int index;                 /* gs.objects / scene->objects index */
    uint32_t vertices, n;
    int deforming;             /* animated: K' path (Eq. 15) + link updates (section 3.4) */
    uint32_t adj_list, inc_off, inc_list, idx; /* section offsets of the topology buffer */
    GLuint topo, geom, links, coef, ld, trans, rd;
    /* The back-side mesh (Maisch & Ropinski 2017, section 4.4) when the map has one: the links index its vertices,
     * L_d (ld, back_vertices entries) is evaluated at them. Object-space positions, normals, UVs (0:
     * none) for the deformation pass; back_geom and back_topo as geom and topo. Without one,
     * back_vertices == vertices and the sources are the mesh's own (ld has `vertices` entries). */
    int has_back;
    uint32_t back_vertices;
    sam_topo_offsets back_off;
    GLuint back_topo, back_geom, back_pos, back_nrm, back_uv;
    float rd_rmax;
    int rd_size;
    size_t bytes;
    uint32_t linked;           /* vertices with at least one link */
    double build_seconds;      /* 0 when read from a file */
    int from_file;
} sam_object;

typedef struct sam_data_desc {
    uint32_t n, samples;
    uint64_t seed;
    uint32_t backside_triangles; /* maps built here: back side on the mesh simplified (0: none) */
    int backside_splat;          /* maps built here: back side on the object's splat mesh / splat_triangles */
    const char *file;          /* a .sam file for the objects whose mesh it matches, or NULL */
    sss_error *mismatch;       /* receives why the file does not fit an object (first one only) */
    const sss_sam *prebuilt;   /* per scene object: maps built beforehand (sss_gl_tables; vertex_count 0:
                                  none), used instead of the file or a build; NULL: none */
} sam_data_desc;

/* The technique's state (tests read the per-object buffers through it). */
enum { SAM_PASS_DEFORM = 0, SAM_PASS_AREA, SAM_PASS_UPDATE, SAM_PASS_LIGHT, SAM_PASS_TRANSFER, SAM_PASS_COUNT };

#define SAM_KEYS 6

typedef struct sam_state {
    GLuint prog[SAM_PASS_COUNT], prog_raster, prog_add, prog_combine;
    sam_object *objs;
    int count;
    int w, h;
    GLuint tex_trans, tex_depth, fbo;
    size_t target_bytes;
    double last_time;
    int have_last;
    /* the surface technique (ssss or screen), run in place with its own parameter values */
    gl_sub_technique surface; /* tech NULL: none */
    double build_seconds;
    double key[SAM_KEYS]; /* n, samples, seed, translucency, backside_triangles, backside_splat of the maps */
    int surface_kind; /* the surface parameter the surface technique was made for */
} sam_state;

/* The map of scene object `index`: read from d->file when it fits the object (*from_file 1), else built
 * (*seconds: the build's time). CPU only. */
sss_result sam_map_build(const sss_scene *scene, int index, const sam_data_desc *d, sss_sam *sam, int *from_file,
                         double *seconds, sss_error *err);
/* Builds (or reads, or takes from d->prebuilt) the map of scene object `index` and uploads it. */
sss_result sam_object_create(const gl_tech_ctx *c, int index, const sam_data_desc *d, sam_object *out, sss_error *err);
void sam_object_free(sam_object *o);

#endif
