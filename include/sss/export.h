/* sss/export.h — writes a scene for other renderers, so anyone can reproduce the ground truth.
 *
 * Does: PBRT-v3 scene files (`sss_export_pbrt`): perspective camera (fov on the shorter axis, with
 * `Scale -1 1 1` before `LookAt` because PBRT's camera space is left-handed), `subsurface` /
 * `kdsubsurface` / `matte` materials, world-space `plymesh` shapes written next to the .pbrt file
 * (posed at the given time, so animated objects match `sss reference --time`), and the lights of
 * docs/scene-format.md with their PBRT equivalents (area lights as a two-triangle `trianglemesh`, since PBRT-v3
 * has no bilinear patch). The integrator is `path` with maxdepth N (desc.maxdepth, default 16).
 * PBRT-v3's PathIntegrator::Li counts one depth per surface hit of the path: at a subsurface hit the
 * interface's refraction, the BSSRDF probe to the entry point, direct light there (next-event
 * estimation, no depth of its own) and the exit direction drawn from S_w are all one depth. So
 * maxdepth 1 is exactly the single-event integral of docs/physics.md §1 (`sss reference --bounces 1`)
 * and maxdepth N holds N subsurface or diffuse events (`--bounces N`), except that PBRT also spends a
 * depth on every smooth reflection off a subsurface interface, which `sss reference` folds into the
 * bounce it belongs to (docs/reference.md), so from N = 2 on the two differ by those reflections;
 * converged (the default 16 against the default) they differ only by the mirror image of the scene
 * in the camera ray's reflection, which `sss reference` leaves out (`--specular` adds that of
 * environment maps and area lights).
 * Film scale carries render.exposure (2^exposure).
 * Does not: textures (PBRT would need its own texture statements; a scene with a texture exports
 * without it and says so in a comment), the specular interface of `specular` (PBRT's subsurface
 * material always has its smooth dielectric interface; our reference leaves it out by default),
 * artist/dipole profiles (PBRT has only its photon beam diffusion table: a comment says so).
 */
#ifndef SSS_EXPORT_H
#define SSS_EXPORT_H

#include "sss/common.h"
#include "sss/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sss_export_pbrt_desc {
    double time;        /* pose of animated objects (seconds); default 0 */
    int pixel_samples;  /* PBRT sampler's pixelsamples; 0 -> 256 */
    const char *image_name; /* Film filename; NULL -> "<stem of out_path>.exr" */
    int maxdepth;       /* the path integrator's maxdepth, 1..SSS_EXPORT_PBRT_MAXDEPTH_MAX; 0 -> the default */
} sss_export_pbrt_desc;

/* The default maxdepth: sss reference's bounce cap (SSS_REFERENCE_MAX_BOUNCES); and the largest. */
#define SSS_EXPORT_PBRT_MAXDEPTH_DEFAULT 16
#define SSS_EXPORT_PBRT_MAXDEPTH_MAX 1024

/* Writes out_path (e.g. "scene.pbrt") and one binary PLY per object beside it
 * ("<stem>_objN.ply"). All files are written atomically; on failure none is left behind. */
SSS_API sss_result sss_export_pbrt(const sss_scene *scene, const sss_export_pbrt_desc *desc, const char *out_path,
                                   sss_error *err);

/* The extension that carries a subsurface material's scattering in an exported glTF. */
typedef enum sss_export_gltf_scatter {
    SSS_EXPORT_GLTF_VOLUME_SCATTER = 0, /* KHR_materials_volume_scatter + KHR_materials_diffuse_transmission */
    SSS_EXPORT_GLTF_SCATTER = 1         /* KHR_materials_scatter (the draft replacing both) +
                                         * KHR_materials_transmission */
} sss_export_gltf_scatter;

typedef struct sss_export_gltf_desc {
    double time;        /* pose of animated objects (seconds); default 0 */
    int skipped_lights; /* out: area and environment lights, which glTF's punctual lights cannot hold */
    sss_export_gltf_scatter scatter_extension; /* default SSS_EXPORT_GLTF_VOLUME_SCATTER */
} sss_export_gltf_desc;

/* Writes the scene as one binary glTF 2.0 file (docs/gltf.md, "Export"): one node and mesh per object
 * (world space, posed at desc->time), subsurface materials as KHR_materials_volume +
 * KHR_materials_ior + the scattering extension of desc->scatter_extension (the importer's mapping
 * inverted: sss_gltf_load of the file gives back the coefficients), diffuse ones
 * as baseColorFactor, the camera (yfov, aspectRatio), point, spot and directional lights as
 * KHR_lights_punctual (intensities 1:1), albedo textures as embedded PNG baseColorTextures (8-bit
 * sRGB: exact for textures read from PNG or JPEG; HDR values clip at 1). Not written: profiles other
 * than PBD, the render settings, area and environment lights (glTF 2.0 has neither: counted in
 * desc->skipped_lights). The scene must have been loaded with its meshes (textures decoded). desc may
 * be NULL. Written atomically. */
SSS_API sss_result sss_export_gltf(const sss_scene *scene, sss_export_gltf_desc *desc, const char *out_path,
                                   sss_error *err);

#ifdef __cplusplus
}
#endif
#endif
