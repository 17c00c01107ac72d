/* fuzz/fuzz_harness.h — one checking entry point per parser, shared by the libFuzzer targets
 * (fuzz/fuzz_main.c, clang) and the regression replay test (tests/robustness/, any compiler).
 *
 * Each function feeds one input to a reader from memory and then checks what the library promises
 * (COMMON.md, the headers): on success the result is well formed (counts within the limits, indices in
 * range, finite coordinates, unit normals, ...); on failure the error names the input and the output is
 * left empty. It returns NULL when everything holds, or a short description of the broken promise
 * (the fuzzer aborts on it; the replay test reports it). Memory errors are the sanitizers' business.
 */
#ifndef SSS_FUZZ_HARNESS_H
#define SSS_FUZZ_HARNESS_H

#include <stddef.h>
#include <stdint.h>

typedef const char *(*sss_fuzz_fn)(const uint8_t *data, size_t size);

const char *sss_fuzz_ply(const uint8_t *data, size_t size);   /* sss_mesh_parse_ply (ascii, binary) */
const char *sss_fuzz_obj(const uint8_t *data, size_t size);   /* sss_mesh_parse_obj */
const char *sss_fuzz_scene(const uint8_t *data, size_t size); /* sss_scene_parse, meshes in the fixtures */
const char *sss_fuzz_hdr(const uint8_t *data, size_t size);   /* sss_image_decode, Radiance HDR */
const char *sss_fuzz_pfm(const uint8_t *data, size_t size);   /* sss_image_decode, PFM */
const char *sss_fuzz_exr(const uint8_t *data, size_t size);   /* sss_image_decode, OpenEXR */
const char *sss_fuzz_png(const uint8_t *data, size_t size);   /* sss_image_decode, PNG */
const char *sss_fuzz_jpg(const uint8_t *data, size_t size);   /* sss_image_decode, JPEG */
const char *sss_fuzz_sam(const uint8_t *data, size_t size);   /* sss_sam_decode (checksum fixed up), sss_sam_check */
const char *sss_fuzz_env_cut(const uint8_t *data, size_t size); /* gl_env_median_cut on a small map */
const char *sss_fuzz_gltf(const uint8_t *data, size_t size);  /* sss_gltf_parse (.gltf, .glb), its scene JSON */

/* The folder that scene inputs resolve relative paths against (fuzz/fixtures: small meshes, an image).
 * Must be set before sss_fuzz_scene. */
void sss_fuzz_set_fixtures(const char *dir);

typedef struct sss_fuzz_target {
    const char *name; /* "ply": also the folder name under tests/data/fuzz-regressions/ and fuzz/corpus/ */
    sss_fuzz_fn fn;
} sss_fuzz_target;

extern const sss_fuzz_target sss_fuzz_targets[];
extern const size_t sss_fuzz_target_count;

#endif
