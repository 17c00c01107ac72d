/* sss/gltf.h — glTF 2.0 import: a .gltf or .glb asset as the objects, materials, camera and lights of
 * an sss scene (docs/gltf.md).
 *
 * Does: reads .gltf (JSON with external or data: URI buffers) and .glb (binary chunks) with cJSON;
 * flattens the node hierarchy of the default scene (TRS or matrix) and bakes every triangle primitive
 * into a WORLD-space mesh (positions, normals, TEXCOORD_0); maps materials (KHR_materials_volume +
 * KHR_materials_volume_scatter [+ KHR_materials_ior, KHR_materials_diffuse_transmission] ->
 * subsurface coefficients per world unit; everything else -> diffuse from baseColorFactor), the
 * camera (a perspective camera node, or a framing camera) and KHR_lights_punctual lights.
 * Decodes compressed meshes: KHR_draco_mesh_compression (Draco), EXT_meshopt_compression
 * (meshoptimizer) and KHR_mesh_quantization, within SSS_GLTF_MAX_DECODED_SIZE per asset.
 * Does not: animations, skins, morph targets (the rest pose is imported), sparse accessors, points
 * and lines, orthographic cameras, texture transforms. A baseColorTexture is kept as an external file's
 * path, or decoded (PNG or JPEG) when the image is embedded (a bufferView or a data: URI).
 * Every file goes through sss_read_file (sizes checked
 * before allocation). Messages name the file and the JSON path ("a.gltf: accessors[3].count: ...").
 * Memory: sss_gltf_load fills an sss_gltf_scene; release it with sss_gltf_scene_free.
 *
 * Material mapping (world units; c = attenuationColor, d = attenuationDistance, t = thicknessFactor of
 * KHR_materials_volume; per channel; docs/gltf.md "Materials"):
 *     sigma_t = -ln(c) / d                                   (KHR_materials_volume, "attenuation")
 *     rho: the multiple-scattering albedo: KHR_materials_volume_scatter's multiscatterColor;
 *          KHR_materials_scatter's scatterStrengthFactor x multiscatterColorFactor; without either,
 *          KHR_materials_diffuse_transmission's (1 - f) baseColor + f diffuseTransmissionColor exp(-sigma_t t)
 *     s: the root in [0, 1] of rho = (1 - s)(1 - 0.139 s) / (1 + 1.17 s) (Kulla & Conty 2017)
 *     alpha = 1 - s^2 (volume_scatter, diffuse transmission) or (1 - s^2) / (1 - g s^2) (scatter)
 *     sigma_s = alpha sigma_t,  sigma_a = sigma_t - sigma_s,  g = scatterAnisotropy (0 for diffuse
 *     transmission),  eta = KHR_materials_ior.ior (1.5).
 * A material is subsurface when it has KHR_materials_volume with thicknessFactor > 0 and a finite
 * attenuationDistance and one of those three extensions with a weight > 0 (KHR_materials_scatter
 * preferred, then volume_scatter); a volume without scattering is clear, absorbing glass in glTF,
 * which no sss renderer draws: it becomes diffuse like any other material. A scattering extension
 * without such a volume is imported as diffuse and says so in sss_gltf_material.note.
 * Lights: intensity taken 1:1 (point, spot: candela as W/sr; directional: lux as irradiance) times
 * color times light_scale; spot cone_angle = outerConeAngle, cone_delta = outer - inner (degrees);
 * `range` is ignored (sss lights fall off with 1 / r^2 only).
 */
#ifndef SSS_GLTF_H
#define SSS_GLTF_H

#include "sss/common.h"
#include "sss/image.h"
#include "sss/mesh.h"
#include "sss/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SSS_GLTF_MAX_FILE_SIZE (1u << 30)      /* a .gltf, .glb or .bin file */
#define SSS_GLTF_MAX_JSON_SIZE (64u << 20)     /* the JSON of a .gltf or a .glb's JSON chunk */
/* Compressed mesh data decoded per asset: the bytes of EXT_meshopt_compression buffer views plus, per
 * KHR_draco_mesh_compression triangle, SSS_GLTF_DRACO_BYTES_PER_TRIANGLE (the Draco decoder's working
 * memory, bounded by the triangle count its header gives before it allocates). */
#define SSS_GLTF_MAX_DECODED_SIZE (1u << 30)
#define SSS_GLTF_DRACO_BYTES_PER_TRIANGLE 256
#define SSS_GLTF_DEFAULT_WIDTH 960
#define SSS_GLTF_DEFAULT_HEIGHT 540

typedef struct sss_gltf_desc {
    int width, height;  /* image size; 0 = from the camera's aspectRatio, else 960 x 540 */
    int use_camera;     /* nonzero: take cameras[camera] (its first node) instead of the first camera node */
    int camera;
    double light_scale; /* multiplies every light's intensity; 0 = 1 */
} sss_gltf_desc;

typedef struct sss_gltf_material {
    int subsurface;          /* 1: the coefficients below; 0: diffuse with reflectance albedo */
    double albedo[3];        /* diffuse: baseColorFactor (linear rgb) */
    double sigma_a[3], sigma_s[3]; /* subsurface: per world unit */
    double g, eta;
    char *texture;           /* subsurface: baseColorTexture's image file (resolved path) or NULL */
    int image;               /* subsurface: its embedded image, an index into sss_gltf_scene.images; or -1 */
    const char *note;        /* NULL, or what the mapping approximated or left out (a static string:
                              * a volume with diffuse transmission mapped to subsurface, a scattering
                              * extension without a volume imported as diffuse); `sss import` prints it */
} sss_gltf_material;

typedef struct sss_gltf_object {
    sss_mesh mesh;           /* WORLD space (the node's transform applied) */
    sss_gltf_material material;
    int node, mesh_index, primitive; /* where it came from, for messages */
    int material_index;      /* materials[material_index] of the asset; -1: the glTF default material */
} sss_gltf_object;

typedef struct sss_gltf_scene {
    sss_gltf_object *objects;
    size_t object_count;
    sss_camera camera;       /* always set: the asset's camera or a framing one */
    int camera_from_asset;   /* 1 when the asset had the camera */
    sss_light *lights;       /* point, spot, directional */
    size_t light_count;
    sss_image *images;       /* the asset's images[k], decoded when a material uses it embedded; else empty */
    size_t image_count;
    char **files;            /* the files the asset is made of: its external buffers and images (their
                              * uri resolved, used or not) and, from sss_gltf_load, the asset itself;
                              * the inputs that sss_gltf_write_scene must not overwrite */
    size_t file_count;
} sss_gltf_scene;

/* Imports a .gltf or .glb (by content: a .glb starts with "glTF"). desc may be NULL. On failure *out
 * is left empty and err names the file and the JSON path. A scene it returns passes the scene loader's
 * checks (sss_scene_parse of sss_gltf_scene_json's text with these meshes and images), so the scene
 * sss_gltf_write_scene writes from it loads. */
SSS_API sss_result sss_gltf_load(const char *path, const sss_gltf_desc *desc, sss_gltf_scene *out, sss_error *err);
/* The same from memory; base_dir resolves external URIs (NULL = "."), name is used in messages. */
SSS_API sss_result sss_gltf_parse(const void *data, size_t size, const char *base_dir, const char *name,
                                  const sss_gltf_desc *desc, sss_gltf_scene *out, sss_error *err);
SSS_API void sss_gltf_scene_free(sss_gltf_scene *scene);

/* The scene as JSON text of our format (docs/scene-format.md): objects[i] gets "mesh": mesh_paths[i] and an
 * identity transform (the meshes are in world space); a material's texture is its file path as given,
 * or image_paths[k] for its embedded image k (image_paths may be NULL when no material has one).
 * *json is malloc'd (NUL-terminated). */
SSS_API sss_result sss_gltf_scene_json(const sss_gltf_scene *scene, const char *const *mesh_paths,
                                       const char *const *image_paths, char **json, sss_error *err);

/* Writes the scene as scene_path (JSON, written atomically) plus one binary PLY per object beside it
 * (<stem>_objN.ply, world space, referenced by file name) and one PNG per embedded image that a
 * material uses (<stem>_imgK.png: 8-bit sRGB, the decoded pixels exactly). Before writing anything it
 * refuses (SSS_ERROR_INVALID_ARGUMENT) an output that is the same file as one of scene->files or as
 * another output. All the files are written or none (one output transaction, core/file_util.h); the
 * folder of scene_path is created when missing (and removed again if the write fails). */
SSS_API sss_result sss_gltf_write_scene(const sss_gltf_scene *scene, const char *scene_path, sss_error *err);

#ifdef __cplusplus
}
#endif
#endif
