/* bench_mesh — mesh module timings on the bundled dragon (100k triangles): binary PLY read (with
 * normals), area-weighted normals, adjacency, topology, simplification to 10k, and a sphere.
 * Usage: bench_mesh [PATH/TO/dragon.ply] (default: assets/dragon.ply from the working directory). */
#include <stdio.h>

#include "bench.h"
#include "sss/mesh.h"

typedef struct ctx {
    const char *path;
    sss_mesh mesh;
} ctx;

static void run_read(void *p)
{
    ctx *c = p;
    sss_mesh m;
    if (sss_mesh_read(c->path, &m, NULL) == SSS_OK) sss_mesh_free(&m);
}

static void run_normals(void *p) { sss_mesh_compute_normals(&((ctx *)p)->mesh, NULL); }

static void run_adjacency(void *p)
{
    sss_mesh_adjacency a;
    if (sss_mesh_adjacency_build(&((ctx *)p)->mesh, &a, NULL) == SSS_OK) sss_mesh_adjacency_free(&a);
}

static void run_topology(void *p)
{
    sss_mesh_topology t;
    sss_mesh_topology_compute(&((ctx *)p)->mesh, &t, NULL);
}

static void run_simplify(void *p)
{
    sss_mesh s;
    if (sss_mesh_simplify(&((ctx *)p)->mesh, 10000, &s, NULL) == SSS_OK) sss_mesh_free(&s);
}

static void run_sphere(void *p)
{
    (void)p;
    sss_mesh s;
    if (sss_mesh_sphere(1.0, 6, &s, NULL) == SSS_OK) sss_mesh_free(&s);
}

int main(int argc, char **argv)
{
    ctx c = {argc > 1 ? argv[1] : "assets/dragon.ply", {0}};
    sss_error err;
    if (sss_mesh_read(c.path, &c.mesh, &err) != SSS_OK) {
        fprintf(stderr, "bench_mesh: %s\n", err.message);
        return 1;
    }
    printf("%s: %u vertices, %u triangles\n", c.path, c.mesh.vertex_count, c.mesh.triangle_count);
    bench_run("read binary PLY", 11, run_read, &c);
    bench_run("area-weighted normals", 21, run_normals, &c);
    bench_run("adjacency (CSR)", 21, run_adjacency, &c);
    bench_run("topology (edge sort)", 11, run_topology, &c);
    bench_run("simplify to 10k triangles", 5, run_simplify, &c);
    bench_run("sphere, 6 subdivisions (82k triangles)", 11, run_sphere, &c);
    sss_mesh_free(&c.mesh);
    return 0;
}
