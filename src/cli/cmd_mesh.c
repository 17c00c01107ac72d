/* sss mesh — inspect, simplify or convert a triangle mesh (PLY or OBJ). */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "sss/mesh.h"

static const char *const CMD = "mesh";

enum { OPT_OUTPUT, OPT_TRIANGLES };
#define OUTPUT_OPTION                                                                                              \
    {OPT_OUTPUT, "--output", "-o", CLI_ARG_FILE, "OUT.ply", "the mesh to write (binary little-endian PLY)", NULL, \
     CLI_REQUIRED}
static const cli_option convert_options[] = {OUTPUT_OPTION};
static const cli_option simplify_options[] = {
    {OPT_TRIANGLES, "--triangles", NULL, CLI_ARG_NUMBER, "N", "at most N triangles", NULL, CLI_REQUIRED},
    OUTPUT_OPTION,
};
const cli_command_spec cli_spec_mesh_info = {
    "mesh info", NULL, 0, CLI_ARG_FILE, "info simplify convert", "FILE",
    "info      counts, whether the file had normals/UVs, bounding box, surface area, edges,\n"
    "          signed volume (exact for closed meshes) and degenerate triangles\n"
    "simplify  reduce to at most N triangles (meshoptimizer) and write binary PLY\n"
    "convert   write the mesh as binary little-endian PLY with positions, normals (and UVs)\n\n"
    "FILE is .ply (ascii or binary) or .obj.\n",
    "Exit status: 0 ok, 1 bad input, 2 usage error.\n", NULL};
const cli_command_spec cli_spec_mesh_simplify = {"mesh simplify", simplify_options, CLI_COUNT(simplify_options),
                                                 CLI_ARG_FILE, NULL, "FILE", NULL, NULL, NULL};
const cli_command_spec cli_spec_mesh_convert = {"mesh convert", convert_options, CLI_COUNT(convert_options),
                                                CLI_ARG_FILE, NULL, "FILE", NULL, NULL, NULL};

static int cmd_info(const char *path)
{
    sss_mesh m;
    sss_error err;
    if (sss_mesh_read(path, &m, &err) != SSS_OK) return cli_fail(CMD, &err);
    sss_mesh_topology topo;
    if (sss_mesh_topology_compute(&m, &topo, &err) != SSS_OK) {
        sss_mesh_free(&m);
        return cli_fail(CMD, &err);
    }
    float lo[3], hi[3];
    sss_mesh_bounds(&m, lo, hi);
    int closed = topo.boundary_edges == 0 && topo.nonmanifold_edges == 0;
    printf("file: %s\n", path);
    printf("vertices: %u\n", m.vertex_count);
    printf("triangles: %u\n", m.triangle_count);
    printf("normals: %s\n", m.source_flags & SSS_MESH_FROM_FILE_NORMALS ? "from file" : "computed (not in file)");
    printf("uvs: %s\n", m.source_flags & SSS_MESH_FROM_FILE_UVS ? "from file" : "none");
    printf("bounds min: %.9g %.9g %.9g\n", lo[0], lo[1], lo[2]);
    printf("bounds max: %.9g %.9g %.9g\n", hi[0], hi[1], hi[2]);
    printf("size: %.9g %.9g %.9g\n", (double)hi[0] - lo[0], (double)hi[1] - lo[1], (double)hi[2] - lo[2]);
    printf("surface area: %.9g\n", sss_mesh_surface_area(&m));
    printf("edges: %llu (%llu boundary, %llu non-manifold)\n", (unsigned long long)topo.edge_count,
           (unsigned long long)topo.boundary_edges, (unsigned long long)topo.nonmanifold_edges);
    printf("closed: %s\n", closed ? "yes" : "no");
    printf("signed volume: %.9g%s\n", sss_mesh_signed_volume(&m), closed ? "" : " (approximate: the mesh has holes)");
    printf("degenerate triangles: %llu\n", (unsigned long long)topo.degenerate_triangles);
    sss_mesh_free(&m);
    return CLI_EXIT_OK;
}

static int cmd_write(const char *path, const char *output, int triangles)
{
    sss_mesh m, s;
    sss_error err;
    if (cli_check_outputs(CMD, &output, 1, &path, 1, NULL) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    if (sss_mesh_read(path, &m, &err) != SSS_OK) return cli_fail(CMD, &err);
    const sss_mesh *result = &m;
    if (triangles > 0) {
        if (sss_mesh_simplify(&m, (uint32_t)triangles, &s, &err) != SSS_OK) {
            sss_mesh_free(&m);
            sss_error_prefix(&err, path);
            return cli_fail(CMD, &err);
        }
        result = &s;
    }
    sss_result r = sss_mesh_write_ply(output, result, &err);
    if (r == SSS_OK) {
        if (triangles > 0)
            printf("%s: %u -> %u triangles (%u vertices), wrote %s\n", path, m.triangle_count, s.triangle_count,
                   s.vertex_count, output);
        else
            printf("%s: %u triangles, %u vertices, wrote %s\n", path, m.triangle_count, m.vertex_count, output);
    }
    if (triangles > 0) sss_mesh_free(&s);
    sss_mesh_free(&m);
    return r == SSS_OK ? CLI_EXIT_OK : cli_fail(CMD, &err);
}

typedef struct mesh_options {
    const char *sub, *input, *output;
    int is_info, is_simplify;
    int triangles, have_triangles;
} mesh_options;

static int set_option(void *opts, int id, const char *given, const char *v)
{
    (void)given;
    mesh_options *o = opts;
    if (id == OPT_OUTPUT) {
        o->output = v;
    } else if (id == OPT_TRIANGLES) {
        if (!cli_parse_int(CMD, "--triangles", v, &o->triangles)) return CLI_EXIT_USAGE;
        if (o->triangles < 1) return cli_usage_error(CMD, "--triangles must be at least 1");
        o->have_triangles = 1;
    } else if (!o->input) {
        o->input = v;
    } else {
        return cli_usage_error(CMD, "unexpected argument '%s'", v);
    }
    return CLI_EXIT_OK;
}

/* argv[1] is the subcommand (info, simplify, convert), its options follow. */
static int mesh_parse(int argc, char **argv, mesh_options *o)
{
    memset(o, 0, sizeof *o);
    if (argc < 2) return cli_usage_error(CMD, "missing subcommand (info, simplify or convert)");
    o->sub = argv[1];
    o->is_info = strcmp(o->sub, "info") == 0;
    o->is_simplify = strcmp(o->sub, "simplify") == 0;
    if (!o->is_info && !o->is_simplify && strcmp(o->sub, "convert") != 0) {
        const char *subs[] = {"info", "simplify", "convert"};
        return cli_unknown(CMD, "subcommand", o->sub, subs, 3);
    }
    const cli_command_spec *spec =
        o->is_info ? &cli_spec_mesh_info : o->is_simplify ? &cli_spec_mesh_simplify : &cli_spec_mesh_convert;
    int status = cli_parse(spec, argc, argv, 2, set_option, o, NULL);
    if (status != CLI_EXIT_OK) return status;
    if (!o->input) return cli_usage_error(CMD, "missing FILE");
    if (o->is_info) return CLI_EXIT_OK;
    if (o->is_simplify && !o->have_triangles) return cli_usage_error(CMD, "simplify needs --triangles N");
    if (!o->output) return cli_usage_error(CMD, "%s needs -o OUT.ply", o->sub);
    if (!cli_require_extension(CMD, "-o", o->output, "ply")) return CLI_EXIT_USAGE;
    return CLI_EXIT_OK;
}

static int mesh_run(const mesh_options *o)
{
    if (o->is_info) return cmd_info(o->input);
    return cmd_write(o->input, o->output, o->is_simplify ? o->triangles : 0);
}

int sss_cmd_mesh(int argc, char **argv)
{
    mesh_options o;
    int status = mesh_parse(argc, argv, &o);
    return status == CLI_EXIT_OK ? mesh_run(&o) : status;
}
