/* sss/scene.h — the JSON scene format of docs/scene-format.md: loading, validation, resolved data for renderers,
 * camera rays, object transforms and the shared animation definition.
 *
 * Does: parses a scene file (cJSON), validates every field with messages that name the file and the
 * JSON path ("scene.json: objects[1].material.sigmaa: unknown field"), applies the scene format's defaults,
 * resolves paths relative to the scene file's folder, loads meshes (sss_mesh_read or the procedural
 * shapes), resolves materials to per-scene-unit coefficients (sss_material) and builds one PBD table
 * per distinct (eta, g) of the subsurface materials (shared; PBRT needs it for kdsubsurface).
 * Textures are decoded once at load (sss_scene.textures, one per distinct file, shared by the
 * materials that name it) and refused when unreadable or holding NaN/Inf, so every command refuses
 * the same texture files and no renderer decodes them again.
 * Does not: render, load environment maps (their paths are resolved and
 * checked), validate technique names (the renderer does; the loader keeps the string).
 * Threads: loading different scenes concurrently is safe except for cJSON's global "last error"
 * pointer, which this loader does not use.
 *
 * Conventions: right-handed world, y up. Matrices are double[16], ROW-major (m[4 * row + col]) and
 * act on column vectors: p' = M p (upload to GL with transpose = GL_TRUE). Times are in seconds.
 *
 * Field rules beyond docs/scene-format.md (how its silences are resolved):
 *  - A field for which docs/scene-format.md gives no default is required, except the tessellation counts of the
 *    procedural shapes (sphere subdivisions 4, torus segments 64, trefoil segments 256).
 *  - Required: camera, camera.position, camera.look_at, objects (at least one), each object's
 *    material and material.type. Optional: lights (default none), render (defaults).
 *  - A subsurface material needs exactly one parameterisation: `medium` | `sigma_a` + `sigma_s` |
 *    `reflectance` + `mfp` (also with an artist profile: every renderer, the CPU reference included,
 *    must be able to render it). `g` is accepted only with the explicit coefficients, as docs/scene-format.md
 *    lists it (measured media are reduced coefficients, g = 0; the scene format's reflectance + mfp form has
 *    no g); `scale` is rejected with reflectance + mfp (mfp is in scene units).
 *  - Profile "artist": `s` (> 0, scene units) required; `near`, `far` ((0, 1] each) and `w` ([0, 1])
 *    default to Jimenez et al. 2019's "production" preset (docs/physics.md §2.4).
 *  - Spot lights: `cone_angle` is the half-angle of the cone in (0, 90] degrees and `cone_delta` the
 *    width of the falloff in [0, cone_angle] (PBRT-v3's coneangle / conedelta).
 *  - `splat_mesh` and `splat_triangles` are mutually exclusive; splat_triangles >= 1.
 *  - `texture` needs UVs (docs/scene-format.md): when meshes are loaded, a mesh without UVs is an error naming
 *    objects[i].material.texture (of the procedural shapes only plane and box have UVs).
 *  - Duplicate keys in one JSON object are an error. Trailing text after the JSON value is an error.
 *  - A negative scale (mirror) is allowed; sss_scene_object_world_mesh then flips the triangle winding
 *    so that triangles stay counter-clockwise seen from outside.
 *
 *  - A .gltf or .glb path given to sss_scene_load is imported with sss_gltf_load's defaults
 *    (sss/gltf.h): its meshes are kept in memory, in world space, with identity transforms.
 *
 * Limits: scene file <= SSS_SCENE_MAX_FILE_SIZE bytes; width, height in 1..SSS_SCENE_MAX_IMAGE_SIZE;
 * at most SSS_SCENE_MAX_OBJECTS objects and SSS_SCENE_MAX_LIGHTS lights; technique names shorter than
 * SSS_SCENE_TECHNIQUE_SIZE; fov in [SSS_SCENE_FOV_MIN, 180); eta in [SSS_ETA_MIN, SSS_ETA_MAX]; g in (-1, 1);
 * kdsubsurface reflectance in (0, 1) exclusive; diffuse reflectance in [0, 1]; procedural sizes > 0 and
 * the tessellation ranges of sss/mesh.h (sphere subdivisions 0..8, torus segments 3..2048 with
 * minor < major, trefoil segments 3..4096 with tube <= radius / 6).
 */
#ifndef SSS_SCENE_H
#define SSS_SCENE_H

#include <stdint.h>

#include "sss/common.h"
#include "sss/image.h"
#include "sss/material.h"
#include "sss/mesh.h"
#include "sss/profile.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The scene format version this library reads and writes (docs/scene-format.md): a file's optional
 * top-level "version" (absent = 1) greater than this is refused with SSS_ERROR_UNSUPPORTED. */
#define SSS_SCENE_FORMAT_VERSION 1
#define SSS_SCENE_MAX_FILE_SIZE (64u << 20)
#define SSS_SCENE_MAX_IMAGE_SIZE 16384
#define SSS_SCENE_FOV_MIN 1e-6 /* degrees: below, 1 / tan(fov / 2) leaves the float range of GL matrices */
#define SSS_SCENE_MAX_OBJECTS 65536
#define SSS_SCENE_MAX_LIGHTS 4096
#define SSS_SCENE_TECHNIQUE_SIZE 64
#define SSS_SCENE_DEFAULT_TECHNIQUE "maisch2020"

/* ---- Camera ---------------------------------------------------------------------------------- */

typedef struct sss_camera {
    double position[3], look_at[3], up[3]; /* up defaults to [0, 1, 0] */
    double fov;                            /* full field of view, degrees, along the SHORTER axis */
    int width, height;                     /* pixels */
} sss_camera;

/* The camera frame: forward = normalize(look_at - position), right = normalize(forward x up),
 * up = right x forward. Camera space is (right, up, -forward): the camera looks down its -z axis.
 * tan_half[0], tan_half[1]: half extents of the image plane at distance 1 along right and up; the
 * shorter image axis gets tan(fov / 2) and the longer one that times the aspect ratio, exactly as
 * PBRT-v3's perspective camera (screen window [-aspect, aspect] x [-1, 1] or its transpose).
 * PBRT-v3's LookAt is left-handed (its raster x runs along up x forward = -right): an exporter that
 * wants the same image writes `Scale -1 1 1` before `LookAt`. */
typedef struct sss_camera_basis {
    double origin[3], right[3], up[3], forward[3];
    double tan_half[2];
    int width, height;
} sss_camera_basis;

/* Validates the camera (finite vectors, look_at != position, up not parallel to the view direction,
 * fov in [SSS_SCENE_FOV_MIN, 180), width and height in 1..SSS_SCENE_MAX_IMAGE_SIZE) and builds its basis. */
SSS_API sss_result sss_camera_basis_init(const sss_camera *camera, sss_camera_basis *basis, sss_error *err);

/* Primary ray through the raster point (px, py) = (x + dx, y + dy): pixel (x, y) covers
 * [x, x + 1) x [y, y + 1), x to the right, y DOWN (row 0 is the top row of the image, as stored);
 * (x + 0.5, y + 0.5) is the pixel centre. origin = the camera position, direction unit length. */
SSS_API void sss_camera_ray(const sss_camera_basis *basis, double px, double py, double origin[3],
                            double direction[3]);

/* Inverse of sss_camera_ray: the raster point of a world point. Returns 0 (and leaves raster
 * untouched) when p is not in front of the camera; *depth (may be NULL) receives the distance along
 * forward. */
SSS_API int sss_camera_project(const sss_camera_basis *basis, const double p[3], double raster[2], double *depth);

/* OpenGL matrices (row-major, see above): the view matrix maps world to camera space (camera at the
 * origin looking down -z); the projection is the standard glFrustum-style perspective with the same
 * image-plane extents as sss_camera_ray (NDC x right, y up: raster y = (1 - ndc_y) / 2 * height).
 * 0 < z_near < z_far. */
SSS_API void sss_camera_view_matrix(const sss_camera_basis *basis, double m[16]);
SSS_API void sss_camera_projection_matrix(const sss_camera_basis *basis, double z_near, double z_far, double m[16]);

/* ---- Transforms ------------------------------------------------------------------------------ */

typedef struct sss_transform {
    double translate[3];  /* default 0 */
    double rotate[4];     /* axis x, y, z (non-zero, not necessarily unit) and angle in degrees;
                             default [0, 1, 0, 0] */
    double scale[3];      /* default 1; |scale| in [SSS_SCENE_SCALE_MIN, SSS_SCENE_SCALE_MAX], may be
                             negative */
    double matrix[16];    /* M = T R S: scale, then rotate (right-handed about the axis), then translate */
    double normal_matrix[9]; /* row-major 3x3 inverse transpose of M's upper 3x3, = R S^-1 */
} sss_transform;

/* Scale factors of a transform: beyond them float positions (or 1/scale for normals) lose everything. */
#define SSS_SCENE_SCALE_MIN 1e-18
#define SSS_SCENE_SCALE_MAX 1e18

/* Fills matrix and normal_matrix from translate, rotate, scale (which the caller set). Errors: zero
 * or non-finite axis, |scale| outside [SSS_SCENE_SCALE_MIN, SSS_SCENE_SCALE_MAX] or non-finite,
 * non-finite angle or translation. */
SSS_API sss_result sss_transform_update(sss_transform *t, sss_error *err);
SSS_API void sss_transform_identity(sss_transform *t);
SSS_API void sss_transform_point(const double m[16], const double p[3], double out[3]);
/* normal_matrix * n, normalised (a zero vector stays zero). */
SSS_API void sss_transform_normal(const double normal_matrix[9], const double n[3], double out[3]);

/* ---- Animation (one definition for every renderer) -------------------------------------------- */

typedef enum sss_animation_type {
    SSS_ANIMATION_NONE = 0,
    SSS_ANIMATION_TWIST,
    SSS_ANIMATION_BEND,
    SSS_ANIMATION_WAVE
} sss_animation_type;

typedef struct sss_animation {
    sss_animation_type type;
    double amplitude; /* twist, bend: degrees; wave: object-space length units */
    double period;    /* seconds, > 0 */
} sss_animation;

/* The deformation is applied in OBJECT space (before the object's transform), with the bounding box
 * [lo, hi] = (bounds_min, bounds_max) of the object's render mesh at rest (sss_scene_object.bounds_*;
 * use the same bounds for its splat mesh so both deform identically). With
 *     c = (lo + hi) / 2,   H = hi.y - lo.y,   W = hi.x - lo.x,
 *     h = (p.y - lo.y) / H   (0 when H <= 0; not clamped, so the map stays smooth outside the box),
 *     s = sin(2 pi t / period),   A = amplitude,   rad(a) = a pi / 180:
 *
 *  twist: theta = rad(A) h s;  q = p - c;  rotation about the vertical axis through c (right-handed
 *         about +y):  x' = c.x + q.x cos(theta) + q.z sin(theta),  y' = p.y,
 *                     z' = c.z - q.x sin(theta) + q.z cos(theta).
 *         A is the angle at the top of the box at the peak (s = 1). Identity at t = 0 and at the base.
 *  bend:  phi = rad(A) h^2 s;  q = (p.x - c.x, p.y - lo.y);  rotation about +z around the pivot
 *         (c.x, lo.y):  x' = c.x + q.x cos(phi) - q.y sin(phi),  y' = lo.y + q.x sin(phi) + q.y cos(phi),
 *         z' = p.z.  A (degrees) is the tilt of the top at the peak; positive A bends the top towards
 *         -x. Identity at t = 0 and at the base. Keep |A| moderate (<= 45) for objects wider than tall,
 *         or the inner side folds (det J = 1 + phi_y q.x, with phi_y = rad(A) s 2 h / H).
 *  wave:  a wave travelling along -x:  y' = p.y + A sin(2 pi ((p.x - lo.x) / W + t / period)),
 *         x' = p.x, z' = p.z (the x term is 0 when W <= 0). NOT the identity at t = 0 (a travelling
 *         wave); volume preserving (det J = 1).
 *
 * Normals: n' = normalize(sign(det J) cof(J) n) with the ANALYTIC Jacobian J = dp'/dp, cof(J) =
 * det(J) J^-T; with J's columns a = dp'/dx, b = dp'/dy, c = dp'/dz:  cof(J) n = (b x c) n.x +
 * (c x a) n.y + (a x b) n.z.  The columns are:
 *  twist: a = (cos, 0, -sin)(theta), c = (sin, 0, cos)(theta),
 *         b = (0, 1, 0) + theta_y (-q.x sin(theta) + q.z cos(theta), 0, -q.x cos(theta) - q.z sin(theta)),
 *         theta_y = rad(A) s / H (0 when H <= 0);
 *  bend:  a = (cos, sin, 0)(phi), c = (0, 0, 1),
 *         b = (-sin(phi), cos(phi), 0) + phi_y (-q.x sin(phi) - q.y cos(phi), q.x cos(phi) - q.y sin(phi), 0),
 *         phi_y = 2 rad(A) s h / H;
 *  wave:  a = (1, A (2 pi / W) cos(2 pi ((p.x - lo.x) / W + t / period)), 0), b = (0, 1, 0), c = (0, 0, 1).
 * The functions compute in double and store float. NONE copies p (and n). */
SSS_API void sss_animation_deform_point(const sss_animation *anim, const float bounds_min[3],
                                        const float bounds_max[3], double t, const float p[3], float out[3]);
SSS_API void sss_animation_deform_normal(const sss_animation *anim, const float bounds_min[3],
                                         const float bounds_max[3], double t, const float p[3], const float n[3],
                                         float out[3]);
/* Validates an animation (known type, finite amplitude, finite period > 0). */
SSS_API sss_result sss_animation_validate(const sss_animation *anim, sss_error *err);
/* A deep copy of mesh with positions and normals deformed at time t (in the mesh's own space). */
SSS_API sss_result sss_animation_deform_mesh(const sss_animation *anim, const float bounds_min[3],
                                             const float bounds_max[3], double t, const sss_mesh *mesh,
                                             sss_mesh *out, sss_error *err);

/* ---- Materials -------------------------------------------------------------------------------- */

typedef enum sss_scene_material_type {
    SSS_SCENE_MATERIAL_SUBSURFACE = 0,
    SSS_SCENE_MATERIAL_DIFFUSE
} sss_scene_material_type;

typedef enum sss_subsurface_source {
    SSS_SUBSURFACE_MEDIUM = 0,   /* `medium` (+ scale, eta): PBRT subsurface "name" */
    SSS_SUBSURFACE_COEFFICIENTS, /* `sigma_a`, `sigma_s` (+ scale, eta, g): PBRT subsurface */
    SSS_SUBSURFACE_REFLECTANCE   /* `reflectance`, `mfp` (+ eta): PBRT kdsubsurface */
} sss_subsurface_source;

typedef enum sss_scene_profile {
    SSS_SCENE_PROFILE_PBD = 0, /* "pbd" (default) */
    SSS_SCENE_PROFILE_DIPOLE,  /* "dipole" */
    SSS_SCENE_PROFILE_ARTIST   /* {"artist": {...}} */
} sss_scene_profile;

typedef struct sss_scene_material {
    sss_scene_material_type type;
    /* DIFFUSE: reflectance. SUBSURFACE: the total diffuse reflectance of the resolved material under
     * its PBD table (rho_eff per channel, what a flat slab shows; the given reflectance for
     * kdsubsurface), a base colour for displays. */
    double albedo[3];

    /* ---- SUBSURFACE only ---- */
    sss_subsurface_source source;
    const sss_measured_medium *medium; /* MEDIUM: the table entry (canonical name in medium->name) */
    double scale;                      /* MEDIUM, COEFFICIENTS: as given (default 1); 1 otherwise */
    double input_sigma_a[3], input_sigma_s[3]; /* COEFFICIENTS: as given, before scale */
    double reflectance[3], mfp[3];     /* REFLECTANCE: as given (mfp as a number -> all channels) */
    sss_material optical;              /* resolved: per scene unit, scale applied; eta, g */
    const sss_pbd_table *table;        /* borrowed from the scene's cache, built for (eta, g) */
    sss_scene_profile profile;
    sss_profile rd;                    /* resolved by the loader: R_d(r) of `optical` under `profile`
                                        * (sss_scene_material_profile_model) and `table`, which it borrows */
    sss_artist_params artist;          /* ARTIST: s in scene units */
    char *texture;                     /* resolved path of `texture` (checked readable), or NULL */
    const sss_image *texture_image;    /* its decoded pixels in sss_scene.textures; NULL without a
                                        * texture or with SSS_SCENE_SKIP_MESHES */
    int has_specular;
    double roughness;                  /* specular.roughness in [0, 1] when has_specular */
} sss_scene_material;

/* The sss_profile_model of a material's profile (ARTIST maps to PBD: the artist model lives in
 * sss_artist_params, evaluated by the techniques that accept it). */
SSS_API sss_profile_model sss_scene_material_profile_model(const sss_scene_material *m);

/* ---- Objects ---------------------------------------------------------------------------------- */

typedef enum sss_shape {
    SSS_SHAPE_MESH = 0, /* a mesh file */
    SSS_SHAPE_SPHERE,
    SSS_SHAPE_TORUS,
    SSS_SHAPE_TREFOIL,
    SSS_SHAPE_PLANE,
    SSS_SHAPE_BOX
} sss_shape;

typedef struct sss_procedural {
    sss_shape shape;
    double radius;       /* sphere, trefoil */
    int subdivisions;    /* sphere (default 4) */
    double major, minor; /* torus */
    int segments;        /* torus (default 64), trefoil (default 256) */
    double tube;         /* trefoil */
    double size;         /* plane: edge length */
    double box_size[3];  /* box: edge lengths (a number is accepted for a cube) */
} sss_procedural;

typedef struct sss_scene_object {
    char *mesh_path;           /* resolved path of `mesh`, NULL for procedural shapes; a scene loaded
                                  from a glTF asset has "<asset>#meshes[m].primitives[p]" (in memory) */
    sss_procedural procedural; /* shape == SSS_SHAPE_MESH for mesh files */
    sss_mesh mesh;             /* object space; empty (zeroed) with SSS_SCENE_SKIP_MESHES */
    float bounds_min[3], bounds_max[3]; /* of mesh (zero when not loaded); the animation's box */
    sss_transform transform;
    sss_scene_material material;
    char *splat_mesh_path;     /* resolved `splat_mesh`, or NULL */
    sss_mesh splat_mesh;       /* loaded splat_mesh (object space), empty when none or skipped */
    uint32_t splat_triangles;  /* `splat_triangles`, 0 = the technique's choice */
    sss_animation animation;   /* type NONE when the object has none */
} sss_scene_object;

/* A world-space copy of the object's mesh at time t: the animation (object space, with the object's
 * bounds), then the transform (positions by matrix, normals by normal_matrix, winding flipped when
 * det M < 0). t is ignored without animation. */
SSS_API sss_result sss_scene_object_world_mesh(const sss_scene_object *obj, double t, sss_mesh *out,
                                               sss_error *err);
/* The same for any mesh in the object's space (e.g. its splat mesh or a simplification of it). */
SSS_API sss_result sss_scene_object_pose_mesh(const sss_scene_object *obj, const sss_mesh *mesh, double t,
                                              sss_mesh *out, sss_error *err);
/* The box that holds the object's mesh (object space) at every time of its animation: its bounds,
 * padded by the twist's and bend's diagonal or the wave's amplitude. */
SSS_API void sss_scene_object_animated_bounds(const sss_scene_object *obj, float lo[3], float hi[3]);
/* The largest |coordinate| of the object's world-space positions at any time (the animated box's
 * corners through the transform: exact bounds for an affine map); INFINITY when one is not finite.
 * The loader refuses objects beyond SSS_SCENE_MAX_WORLD_COORD: the real-time renderer works in
 * float, where products of larger coordinates (areas, depths) overflow to Inf and NaN. */
SSS_API double sss_scene_object_world_reach(const sss_scene_object *obj);
#define SSS_SCENE_MAX_WORLD_COORD 1e18
/* A deep copy of a mesh (positions, normals, uvs, indices, source_flags). */
SSS_API sss_result sss_scene_mesh_copy(const sss_mesh *mesh, sss_mesh *out, sss_error *err);

/* ---- Lights ----------------------------------------------------------------------------------- */

typedef enum sss_light_type {
    SSS_LIGHT_POINT = 0,
    SSS_LIGHT_SPOT,
    SSS_LIGHT_DIRECTIONAL,
    SSS_LIGHT_AREA,
    SSS_LIGHT_ENVIRONMENT
} sss_light_type;

typedef struct sss_light {
    sss_light_type type;
    double position[3];  /* point, spot */
    double look_at[3];   /* spot (!= position) */
    double cone_angle, cone_delta; /* spot, degrees */
    double intensity[3]; /* point, spot: W/sr, 0..SSS_SCENE_MAX_LIGHT_VALUE */
    double direction[3]; /* directional: unit direction the light TRAVELS (normalised on load) */
    double radiance[3];  /* directional (irradiance at normal incidence), area: 0..SSS_SCENE_MAX_LIGHT_VALUE */
    double center[3], u[3], v[3]; /* area: half-extent vectors, non-zero and not parallel */
    int two_sided;       /* area, default 0: emits towards u x v only */
    char *file;          /* environment: resolved path */
    double scale[3];     /* environment, default [1, 1, 1], 0..SSS_SCENE_MAX_LIGHT_VALUE */
    double rotate_y;     /* environment, degrees, default 0 */
} sss_light;

/* The largest intensity, radiance or environment scale (per channel) the loader accepts; positions,
 * look_at and area extents must be within the float range. The real-time renderer carries lights in
 * float (at most 3.4e38) and multiplies them by 1/r^2, the profiles and the sum over lights: 3e38 already
 * overflowed to NaN with a light 0.02 units from a surface; 1e30 leaves a factor 3.4e8 (a light 1e-4
 * units away). docs/limits.md. */
#define SSS_SCENE_MAX_LIGHT_VALUE 1e30

/* ---- The scene -------------------------------------------------------------------------------- */

typedef struct sss_render_settings {
    char technique[SSS_SCENE_TECHNIQUE_SIZE]; /* default SSS_SCENE_DEFAULT_TECHNIQUE */
    double exposure;                          /* stops, default 0, finite */
} sss_render_settings;

/* A decoded albedo texture: linear RGB, top row first (sss/image.h). */
typedef struct sss_scene_texture {
    char *path;      /* as in the materials' `texture` (resolved); for a glTF asset's embedded image,
                      * "<asset path>#images[k]" */
    sss_image image;
} sss_scene_texture;

typedef struct sss_scene {
    char *name;      /* the scene file's path as given (or the name given to sss_scene_parse) */
    char *base_dir;  /* folder that relative paths are resolved against */
    sss_camera camera;
    sss_camera_basis basis;
    sss_scene_object *objects;
    size_t object_count;
    sss_light *lights;
    size_t light_count;
    sss_render_settings render;
    sss_pbd_table **tables; /* cache: one table per distinct (eta, g) of the subsurface materials */
    size_t table_count;
    sss_scene_texture *textures; /* one per distinct texture file (empty with SSS_SCENE_SKIP_MESHES) */
    size_t texture_count;
    char **files;    /* a glTF asset loaded as a scene: the files it is made of (sss_gltf_scene.files:
                      * the asset, its external buffers and images); empty for a scene file, whose
                      * files are name and the paths of its objects and lights */
    size_t file_count;
} sss_scene;

/* Flags of sss_scene_load_desc. */
#define SSS_SCENE_SKIP_MESHES 1u      /* parse and validate only: no mesh is read or generated */
#define SSS_SCENE_SKIP_FILE_CHECKS 2u /* do not check that referenced files can be opened */

typedef struct sss_scene_load_desc {
    unsigned flags; /* SSS_SCENE_* bits; 0 = load everything */
} sss_scene_load_desc;

/* Loads a scene file. desc may be NULL (defaults). On failure *scene is left empty (zeroed) and err
 * names the file, the JSON path and the problem. Release with sss_scene_free. */
SSS_API sss_result sss_scene_load(const char *path, const sss_scene_load_desc *desc, sss_scene *scene,
                                  sss_error *err);
/* The same from memory (size bytes; need not be NUL-terminated). base_dir: folder for relative paths
 * (NULL = "."); name: used in messages (NULL = "scene"). */
SSS_API sss_result sss_scene_parse(const char *json_text, size_t size, const char *base_dir, const char *name,
                                   const sss_scene_load_desc *desc, sss_scene *scene, sss_error *err);
SSS_API void sss_scene_free(sss_scene *scene);
/* Replaces lights[index] of a loaded scene with one light given as JSON text (an element of the scene
 * file's "lights" array), checked as sss_scene_load checks it; messages read "<scene name>:
 * lights[index].<field>: ...". The light must keep its type, and an environment light its file (what a
 * renderer's sss_gl_renderer_update_lights can take over; "file" may be left out, and lights[index].file
 * stays the same pointer). On any error the scene is unchanged. */
SSS_API sss_result sss_scene_set_light(sss_scene *scene, size_t index, const char *json_text, size_t size,
                                     sss_error *err);

/* The cached table for (eta, g), or NULL. */
SSS_API const sss_pbd_table *sss_scene_find_table(const sss_scene *scene, double eta, double g);

/* Short names for messages and tools: "twist", "point", "pbd", ... */
SSS_API const char *sss_animation_type_name(sss_animation_type type);
SSS_API const char *sss_light_type_name(sss_light_type type);
SSS_API const char *sss_scene_profile_name(sss_scene_profile profile);

#ifdef __cplusplus
}
#endif
#endif
