/* bench_gltf — glTF import of a 1M-triangle .glb (medians after one warm-up run): the parse into
 * world-space meshes, the whole `sss import` (plus the binary PLY and the scene JSON), and
 * sss_scene_load of the .glb (plus material resolution and its PBD table).
 * Run: build/bench/bench_gltf [folder for temporary files, default /tmp] */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "sss/gltf.h"
#include "sss/scene.h"

#define GRID_X 1000 /* quads: 1000 x 500 = 1,000,000 triangles, 501,501 vertices */
#define GRID_Z 500

typedef struct ctx {
    char glb[512], scene[512];
} ctx;

static void put_u32(unsigned char *p, uint32_t v)
{
    memcpy(p, &v, 4); /* little-endian hosts only (x86-64, arm64) */
}

/* A wavy grid with positions, normals, UVs and 32-bit indices in one BIN chunk, and a subsurface
 * material (KHR_materials_volume + _volume_scatter). */
static int write_glb(const char *path)
{
    size_t nv = (size_t)(GRID_X + 1) * (GRID_Z + 1), nt = 2u * GRID_X * GRID_Z;
    size_t bin_size = nv * 32 + nt * 12;
    char json[2048];
    int json_len = snprintf(json, sizeof json,
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0,\"rotation\":[0,0.3826834,0,0.9238795]}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},\"indices\":3,\"material\":0}]}],"
        "\"materials\":[{\"extensions\":{\"KHR_materials_volume\":{\"thicknessFactor\":1,\"attenuationDistance\":0.05,"
        "\"attenuationColor\":[0.5,0.3,0.2]},\"KHR_materials_volume_scatter\":{\"multiscatterColor\":[0.9,0.7,0.5]}}}],"
        "\"buffers\":[{\"byteLength\":%zu}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},"
        "{\"bufferView\":2,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC2\"},"
        "{\"bufferView\":3,\"componentType\":5125,\"count\":%zu,\"type\":\"SCALAR\"}]}",
        bin_size, nv * 12, nv * 12, nv * 12, nv * 24, nv * 8, nv * 32, nt * 12, nv, nv, nv, 3 * nt);
    while (json_len % 4) json[json_len++] = ' ';
    unsigned char *bin = malloc(bin_size);
    if (!bin) return 0;
    float *pos = (float *)bin, *nrm = pos + 3 * nv, *uv = nrm + 3 * nv;
    uint32_t *idx = (uint32_t *)(uv + 2 * nv);
    for (size_t z = 0, v = 0; z <= GRID_Z; z++)
        for (size_t x = 0; x <= GRID_X; x++, v++) {
            float fx = (float)x / GRID_X, fz = (float)z / GRID_Z;
            pos[3 * v] = fx, pos[3 * v + 1] = 0.01f * (float)((x * 7 + z * 3) % 5), pos[3 * v + 2] = fz;
            nrm[3 * v] = 0, nrm[3 * v + 1] = 1, nrm[3 * v + 2] = 0;
            uv[2 * v] = fx, uv[2 * v + 1] = fz;
        }
    for (size_t z = 0, t = 0; z < GRID_Z; z++)
        for (size_t x = 0; x < GRID_X; x++, t += 2) {
            uint32_t a = (uint32_t)(z * (GRID_X + 1) + x), b = a + 1, c = a + GRID_X + 1, d = c + 1;
            uint32_t tri[6] = {a, c, b, b, c, d}; /* counter-clockwise seen from +y */
            memcpy(idx + 3 * t, tri, sizeof tri);
        }
    unsigned char header[20];
    memcpy(header, "glTF", 4);
    put_u32(header + 4, 2);
    put_u32(header + 8, (uint32_t)(12 + 8 + (size_t)json_len + 8 + bin_size));
    put_u32(header + 12, (uint32_t)json_len);
    memcpy(header + 16, "JSON", 4);
    unsigned char bin_header[8];
    put_u32(bin_header, (uint32_t)bin_size);
    memcpy(bin_header + 4, "BIN", 4);
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(header, 20, 1, f) == 1 && fwrite(json, (size_t)json_len, 1, f) == 1 &&
             fwrite(bin_header, 8, 1, f) == 1 && fwrite(bin, bin_size, 1, f) == 1;
    if (f && fclose(f) != 0) ok = 0;
    free(bin);
    return ok;
}

static void run_load(void *p)
{
    sss_gltf_scene s;
    if (sss_gltf_load(((ctx *)p)->glb, NULL, &s, NULL) == SSS_OK) sss_gltf_scene_free(&s);
}

static void run_import(void *p)
{
    ctx *c = p;
    sss_gltf_scene s;
    if (sss_gltf_load(c->glb, NULL, &s, NULL) != SSS_OK) return;
    sss_gltf_write_scene(&s, c->scene, NULL);
    sss_gltf_scene_free(&s);
}

static void run_scene_load(void *p)
{
    sss_scene s;
    if (sss_scene_load(((ctx *)p)->glb, NULL, &s, NULL) == SSS_OK) sss_scene_free(&s);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "/tmp";
    ctx c;
    snprintf(c.glb, sizeof c.glb, "%s/bench_gltf_1m.glb", dir);
    snprintf(c.scene, sizeof c.scene, "%s/bench_gltf_1m.json", dir);
    if (!write_glb(c.glb)) {
        fprintf(stderr, "bench_gltf: cannot write %s\n", c.glb);
        return 1;
    }
    sss_gltf_scene s;
    sss_error err;
    if (sss_gltf_load(c.glb, NULL, &s, &err) != SSS_OK) { /* also the warm-up of the file cache */
        fprintf(stderr, "bench_gltf: %s\n", err.message);
        return 1;
    }
    printf("%s: %u vertices, %u triangles\n", c.glb, s.objects[0].mesh.vertex_count, s.objects[0].mesh.triangle_count);
    sss_gltf_scene_free(&s);
    bench_run("sss_gltf_load (1M triangles)", 7, run_load, &c);
    run_import(&c);
    bench_run("import: load + binary PLY + scene JSON", 5, run_import, &c);
    run_scene_load(&c);
    bench_run("sss_scene_load of the .glb", 5, run_scene_load, &c);
    char ply[600];
    snprintf(ply, sizeof ply, "%s/bench_gltf_1m_obj0.ply", dir);
    remove(ply);
    remove(c.scene);
    remove(c.glb);
    return 0;
}
