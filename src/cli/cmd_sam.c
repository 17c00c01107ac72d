/* cli/cmd_sam.c — `sss sam build` writes the Spatial Adjacency Map of a mesh (Maisch & Ropinski 2017) for a medium,
 * or of a scene object for its material and transform; `sss sam info` prints a .sam file's header and
 * checks it against a mesh or scene object. */
#include <limits.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "sss/sam.h"
#include "sss/scene.h"

#define CMD "sam"

enum {
    OPT_OUTPUT, OPT_MEDIUM, OPT_SCALE, OPT_ETA, OPT_MODEL, OPT_OBJECT, OPT_LINKS, OPT_SAMPLES, OPT_SEED, OPT_THREADS,
    OPT_BRUTE_FORCE, OPT_BACKSIDE_TRIANGLES, OPT_BACKSIDE_MESH, OPT_BACKSIDE_SPLAT
};
#define DEFAULT_LINKS 3
#define DEFAULT_SAMPLES 64
#define OBJECT_OPTION                                                                                                \
    {OPT_OBJECT, "--object", NULL, CLI_ARG_NUMBER, "K", "scene object index", NULL, "the first subsurface object"}
static const cli_option build_options[] = {
    {OPT_OUTPUT, "--output", "-o", CLI_ARG_FILE, "FILE", "output .sam file (written atomically)", NULL, CLI_REQUIRED},
    {OPT_MEDIUM, "--medium", NULL, CLI_ARG_MEDIUM, "NAME", "measured medium (mesh input, required there), e.g. Marble",
     NULL, NULL},
    {OPT_SCALE, "--scale", NULL, CLI_ARG_NUMBER, "S", "millimetres per mesh unit", NULL, "1"},
    {OPT_ETA, "--eta", NULL, CLI_ARG_NUMBER, "E", "relative index of refraction", NULL,
     CLI_STR(CLI_DEFAULT_ETA)},
    {OPT_MODEL, "--model", NULL, CLI_ARG_TEXT, "M", "pbd (as PBRT-v3) or dipole", "pbd dipole", "pbd"},
    OBJECT_OPTION,
    {OPT_LINKS, "--links", "-n", CLI_ARG_NUMBER, "N", "back-side links per vertex, 1.." CLI_STR(SSS_SAM_MAX_N), NULL,
     CLI_STR(DEFAULT_LINKS) ", the paper's"},
    {OPT_SAMPLES, "--samples", NULL, CLI_ARG_NUMBER, "S",
     "Monte Carlo pairs per form factor, 1.." CLI_STR(SSS_SAM_MAX_SAMPLES), NULL, CLI_STR(DEFAULT_SAMPLES)},
    {OPT_SEED, "--seed", NULL, CLI_ARG_NUMBER, "X", "seed of the sample shifts", NULL, "0"},
    {OPT_THREADS, "--threads", NULL, CLI_ARG_NUMBER, "T", "OpenMP threads", NULL, "all cores"},
    {OPT_BRUTE_FORCE, "--brute-force", NULL, CLI_ARG_NONE, NULL, "test every vertex pair instead of the tree (for checks; O(V^2))",
     NULL, NULL},
    {OPT_BACKSIDE_TRIANGLES, "--backside-triangles", NULL, CLI_ARG_NUMBER, "N",
     "the back side: the mesh simplified to at most N triangles (meshoptimizer)", NULL, NULL},
    {OPT_BACKSIDE_MESH, "--backside-mesh", NULL, CLI_ARG_FILE, "FILE",
     "the back side: a given coarse mesh (.ply/.obj) in the same space as the\n"
     "mesh (a scene object's: object space, posed by its transform)",
     NULL, NULL},
    {OPT_BACKSIDE_SPLAT, "--backside-splat", NULL, CLI_ARG_NONE, NULL,
     "the back side: a scene object's splat_mesh, or its mesh simplified to\n"
     "splat_triangles",
     NULL, NULL},
};
static const cli_option info_options[] = {OBJECT_OPTION};
const cli_command_spec cli_spec_sam_build = {
    "sam build", build_options, CLI_COUNT(build_options), CLI_ARG_FILE, "build info", "MESH|SCENE.json",
    "Builds a Spatial Adjacency Map (Maisch & Ropinski 2017): for every vertex the n back-side vertices\n"
    "(Eq. 13-14) with the largest Monte Carlo form factors between reduced triangle fans (Eq. 11), with\n"
    "the constants K' of Eq. 15 for deforming meshes. The search is best-first branch and bound over a\n"
    "vertex tree (exact: the same links as testing every pair). A mesh is taken in its own units with\n"
    "--medium, --scale millimetres per unit and --eta (as a scene's measured medium); a scene object\n"
    "(--object) with its transform and material. The file records the mesh (counts and a hash of\n"
    "positions and indices), n and the material; `sss render --technique sam` and `sss sam info`\n"
    "reject a file that does not match.\n"
    "\n"
    "back side on a lower-tessellation mesh (Maisch & Ropinski 2017, section 4.4 and its appendix): every vertex links\n"
    "to n vertices of a coarser mesh of the same surface, whose larger reduced fans (Eq. 16) are the\n"
    "sources of Eq. 11; n links then cover more of the back side of a finely tessellated mesh, and the\n"
    "search is faster. The file (version 2) holds the coarse mesh; the renderer lights its vertices\n"
    "(--backside-triangles, --backside-mesh, --backside-splat).\n",
    "Prints vertex and triangle counts, the build time, and how much of the (back-side) mesh the search\n"
    "visited.\n",
    NULL};
const cli_command_spec cli_spec_sam_info = {
    "sam info", info_options, CLI_COUNT(info_options), CLI_ARG_FILE, NULL, "FILE.sam [MESH | SCENE.json]",
    NULL, "sam info prints a .sam file's header and checks it against a mesh or a scene object.\n"
          "Exit status: 0 success, 1 error, 2 usage error.\n",
    NULL};

static int is_scene(const char *path)
{
    size_t n = strlen(path);
    return n > 5 && strcmp(path + n - 5, ".json") == 0;
}

static int first_subsurface(const sss_scene *s)
{
    for (size_t i = 0; i < s->object_count; i++)
        if (s->objects[i].material.type == SSS_SCENE_MATERIAL_SUBSURFACE) return (int)i;
    return -1;
}

static void print_map(const sss_sam *s)
{
    static const char *models[] = {"pbd", "dipole", "gauss6"};
    printf("vertices %u\ntriangles %u\nmesh_hash %016llx\nn %u\nsamples %u\nseed %llu\nmodel %s\n", s->vertex_count,
           s->triangle_count, (unsigned long long)s->mesh_hash, s->n, s->samples, (unsigned long long)s->seed,
           (int)s->model >= 0 && (int)s->model < 3 ? models[s->model] : "?");
    printf("sigma_a %g %g %g\nsigma_s %g %g %g\neta %g\n", s->material.sigma_a[0], s->material.sigma_a[1],
           s->material.sigma_a[2], s->material.sigma_s[0], s->material.sigma_s[1], s->material.sigma_s[2],
           s->material.eta);
    uint64_t used = 0, slots = (uint64_t)s->vertex_count * s->n;
    uint32_t linked = 0;
    for (uint32_t v = 0; v < s->vertex_count; v++) {
        int any = 0;
        for (uint32_t k = 0; k < s->n; k++)
            if (s->links[(size_t)v * s->n + k] != SSS_SAM_NONE) {
                used++;
                any = 1;
            }
        linked += (uint32_t)any;
    }
    printf("linked_vertices %u\nlinks_used %llu of %llu\n", linked, (unsigned long long)used, (unsigned long long)slots);
    if (s->back_vertex_count)
        printf("backside_vertices %u\nbackside_triangles %u\nbackside_hash %016llx\n", s->back_vertex_count,
               s->back_triangle_count, (unsigned long long)s->back_hash);
}

typedef struct sam_info_options {
    const char *file, *against;
    int object;
} sam_info_options;

static int info_set(void *opts, int id, const char *a, const char *v)
{
    sam_info_options *o = opts;
    if (id == OPT_OBJECT) {
        if (!cli_parse_int_in(CMD, a, v, 0, INT_MAX, &o->object)) return CLI_EXIT_USAGE;
    } else if (!o->file) {
        o->file = v;
    } else if (!o->against) {
        o->against = v;
    } else {
        return cli_usage_error(CMD, "unexpected argument '%s'", v);
    }
    return CLI_EXIT_OK;
}

static int info_parse(int argc, char **argv, sam_info_options *o)
{
    *o = (sam_info_options){.object = -1};
    int status = cli_parse(&cli_spec_sam_info, argc, argv, 2, info_set, o, NULL);
    if (status == CLI_EXIT_OK && !o->file) return cli_usage_error(CMD, "missing FILE.sam");
    return status;
}

/* The map file against the object of a scene (its mesh, transform and material) or against a mesh. */
static int info_check(const sam_info_options *o, const sss_sam *s)
{
    sss_error err = {0};
    int status = CLI_EXIT_OK;
    if (is_scene(o->against)) {
        sss_scene scene;
        if (sss_scene_load(o->against, NULL, &scene, &err) != SSS_OK) return cli_fail(CMD, &err);
        int k = o->object >= 0 ? o->object : first_subsurface(&scene);
        sss_sam t;
        if (k < 0) status = cli_failf(CMD, "%s: no subsurface object", o->against);
        else if (sss_sam_read_object(o->file, &scene, (size_t)k, &t, &err) != SSS_OK) status = cli_fail(CMD, &err);
        else sss_sam_free(&t);
        sss_scene_free(&scene);
        return status;
    }
    sss_mesh mesh;
    if (sss_mesh_read(o->against, &mesh, &err) != SSS_OK) return cli_fail(CMD, &err);
    if (sss_sam_check(s, &mesh, NULL, s->model, NULL, o->file, &err) != SSS_OK) status = cli_fail(CMD, &err);
    sss_mesh_free(&mesh);
    return status;
}

static int info_run(const sam_info_options *o)
{
    sss_error err = {0};
    sss_sam s;
    if (sss_sam_read(o->file, &s, &err) != SSS_OK) return cli_fail(CMD, &err);
    int status = o->against ? info_check(o, &s) : CLI_EXIT_OK;
    if (status == CLI_EXIT_OK) {
        print_map(&s);
        if (o->against) printf("matches %s\n", o->against);
    }
    sss_sam_free(&s);
    return status;
}

typedef struct sam_build_options {
    const char *input, *output, *medium, *model, *back_file;
    double scale, eta;
    int n, samples, threads, object, brute, scale_given, eta_given, back_tris, back_splat, scene_input;
    long long seed;
} sam_build_options;

static int build_set_number(sam_build_options *o, int id, const char *a, const char *v)
{
    switch (id) {
    case OPT_SCALE:
    case OPT_ETA:
        if (!cli_parse_double(CMD, a, v, id == OPT_SCALE ? &o->scale : &o->eta)) return CLI_EXIT_USAGE;
        *(id == OPT_SCALE ? &o->scale_given : &o->eta_given) = 1;
        break;
    case OPT_LINKS:
    case OPT_SAMPLES:
        if (!cli_parse_int(CMD, a, v, id == OPT_LINKS ? &o->n : &o->samples)) return CLI_EXIT_USAGE;
        break;
    case OPT_OBJECT: /* -1 (and --threads 0) are the defaults' sentinels */
        if (!cli_parse_int_in(CMD, a, v, 0, INT_MAX, &o->object)) return CLI_EXIT_USAGE;
        break;
    case OPT_THREADS:
        if (!cli_parse_int_in(CMD, a, v, 1, 4096, &o->threads)) return CLI_EXIT_USAGE;
        break;
    case OPT_SEED: {
        double x;
        if (!cli_parse_double(CMD, a, v, &x)) return CLI_EXIT_USAGE;
        if (x < 0 || x > 9e15 || x != (double)(long long)x) return cli_usage_error(CMD, "--seed must be an integer >= 0");
        o->seed = (long long)x;
        break;
    }
    default: /* OPT_BACKSIDE_TRIANGLES */
        if (!cli_parse_int(CMD, a, v, &o->back_tris)) return CLI_EXIT_USAGE;
        if (o->back_tris < 1) return cli_usage_error(CMD, "--backside-triangles must be >= 1");
    }
    return CLI_EXIT_OK;
}

static int build_set(void *opts, int id, const char *a, const char *v)
{
    sam_build_options *o = opts;
    switch (id) {
    case OPT_OUTPUT: o->output = v; break;
    case OPT_MEDIUM: o->medium = v; break;
    case OPT_MODEL:
        o->model = v;
        if (strcmp(v, "pbd") != 0 && strcmp(v, "dipole") != 0)
            return cli_usage_error(CMD, "--model expects pbd or dipole, got '%s'", v);
        break;
    case OPT_BRUTE_FORCE: o->brute = 1; break;
    case OPT_BACKSIDE_MESH: o->back_file = v; break;
    case OPT_BACKSIDE_SPLAT: o->back_splat = 1; break;
    case CLI_OPERAND:
        if (o->input) return cli_usage_error(CMD, "unexpected argument '%s'", v);
        o->input = v;
        break;
    default: return build_set_number(o, id, a, v);
    }
    return CLI_EXIT_OK;
}

static int build_parse(int argc, char **argv, sam_build_options *o)
{
    *o = (sam_build_options){.model = "pbd", .scale = 1.0, .eta = CLI_DEFAULT_ETA, .n = DEFAULT_LINKS,
                             .samples = DEFAULT_SAMPLES, .object = -1};
    int status = cli_parse(&cli_spec_sam_build, argc, argv, 2, build_set, o, NULL);
    if (status != CLI_EXIT_OK) return status;
    if (!o->input) return cli_usage_error(CMD, "missing MESH or SCENE.json");
    if (!o->output) return cli_usage_error(CMD, "missing -o FILE.sam");
    if (!cli_require_extension(CMD, "-o", o->output, "sam")) return CLI_EXIT_USAGE;
    if (o->n < 1 || o->n > SSS_SAM_MAX_N) return cli_usage_error(CMD, "-n must be in 1..%d", SSS_SAM_MAX_N);
    if (o->samples < 1 || o->samples > SSS_SAM_MAX_SAMPLES)
        return cli_usage_error(CMD, "--samples must be in 1..%d", SSS_SAM_MAX_SAMPLES);
    o->scene_input = is_scene(o->input);
    if (o->scene_input && (o->medium || o->scale_given || o->eta_given))
        return cli_usage_error(CMD, "--medium, --scale and --eta apply to a mesh; a scene object has its material");
    if (!o->scene_input && o->object >= 0) return cli_usage_error(CMD, "--object needs a SCENE.json");
    if (!o->scene_input && !o->medium) return cli_usage_error(CMD, "missing --medium NAME (the mesh's material)");
    if ((o->back_tris > 0) + (o->back_file != NULL) + o->back_splat > 1)
        return cli_usage_error(CMD, "--backside-triangles, --backside-mesh and --backside-splat exclude each other");
    if (o->back_splat && !o->scene_input) return cli_usage_error(CMD, "--backside-splat needs a SCENE.json");
    return CLI_EXIT_OK;
}

/* The map of a scene object (its material and transform; --backside-splat: its splat mesh). */
static int build_scene(const sam_build_options *o, sss_sam_desc *desc, sss_sam *s, sss_sam_stats *st)
{
    sss_error err = {0};
    sss_scene scene;
    if (sss_scene_load(o->input, NULL, &scene, &err) != SSS_OK) return cli_fail(CMD, &err);
    int status = cli_check_outputs(CMD, &o->output, 1, NULL, 0, &scene);
    int k = o->object >= 0 ? o->object : first_subsurface(&scene);
    if (status == CLI_EXIT_OK && k < 0) status = cli_failf(CMD, "%s: no subsurface object", o->input);
    const sss_scene_object *obj = k >= 0 && (size_t)k < scene.object_count ? &scene.objects[k] : NULL;
    if (status == CLI_EXIT_OK && o->back_splat && obj) {
        /* the scene's own low-resolution mesh of the object (docs/scene-format.md: splat_mesh, splat_triangles) */
        if (obj->splat_mesh.vertex_count) desc->backside = &obj->splat_mesh;
        else if (obj->splat_triangles) desc->backside_triangles = obj->splat_triangles;
        else status = cli_failf(CMD, "%s: objects[%d] has neither splat_mesh nor splat_triangles (--backside-splat)",
                                o->input, k);
    }
    if (status == CLI_EXIT_OK && sss_sam_build_object(&scene, (size_t)k, desc, s, st, &err) != SSS_OK)
        status = cli_fail(CMD, &err);
    sss_scene_free(&scene);
    return status;
}

/* The map of a mesh with a measured medium (--medium, --scale, --eta, --model). */
static int build_mesh(const sam_build_options *o, const sss_sam_desc *desc, sss_sam *s, sss_sam_stats *st)
{
    cli_medium_profile mp;
    if (cli_medium_profile_init(CMD, o->medium, o->scale, o->eta, o->model, &mp) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    sss_error err = {0};
    sss_mesh mesh;
    sss_result res = sss_mesh_read(o->input, &mesh, &err);
    if (res == SSS_OK) {
        res = sss_sam_build(&mesh, &mp.profile, desc, s, st, &err);
        sss_mesh_free(&mesh);
    }
    cli_medium_profile_free(&mp);
    return res == SSS_OK ? CLI_EXIT_OK : cli_fail(CMD, &err);
}

static int build_report(const sam_build_options *o, const sss_sam *s, const sss_sam_stats *st)
{
    sss_error err = {0};
    if (sss_sam_write(o->output, s, &err) != SSS_OK) return cli_fail(CMD, &err);
    printf("wrote %s\n", o->output);
    print_map(s);
    double pairs = (double)s->vertex_count * (s->back_vertex_count ? s->back_vertex_count : s->vertex_count);
    printf("build_s %.3f\n", st->seconds);
    printf("nodes_visited %llu\nvertices_tested %llu (%.4f%% of all pairs)\nform_factors %llu\n",
           (unsigned long long)st->nodes_visited, (unsigned long long)st->vertices_tested,
           pairs > 0 ? 100.0 * (double)st->vertices_tested / pairs : 0.0, (unsigned long long)st->form_factors);
    return CLI_EXIT_OK;
}

static int build_run(const sam_build_options *o)
{
    sss_sam_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.n = (uint32_t)o->n;
    desc.samples = (uint32_t)o->samples;
    desc.seed = (uint64_t)o->seed;
    desc.threads = o->threads;
    desc.brute_force = o->brute;
    desc.backside_triangles = (uint32_t)o->back_tris;
    const char *inputs[2] = {o->input, o->back_file};
    if (cli_check_outputs(CMD, &o->output, 1, inputs, 2, NULL) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    sss_error err = {0};
    sss_mesh back;
    memset(&back, 0, sizeof back);
    if (o->back_file) {
        if (sss_mesh_read(o->back_file, &back, &err) != SSS_OK) return cli_fail(CMD, &err);
        desc.backside = &back;
    }
    sss_sam s;
    sss_sam_stats st;
    int status = o->scene_input ? build_scene(o, &desc, &s, &st) : build_mesh(o, &desc, &s, &st);
    sss_mesh_free(&back);
    if (status != CLI_EXIT_OK) return status;
    status = build_report(o, &s, &st);
    sss_sam_free(&s);
    if (status == CLI_EXIT_OK && (fflush(stdout) != 0 || ferror(stdout)))
        return cli_failf(CMD, "error writing the output");
    return status;
}

/* argv[1] is the subcommand (build, info), its options follow. */
int sss_cmd_sam(int argc, char **argv)
{
    if (argc < 2) {
        cli_print_help(stderr, cli_find_command(CMD));
        return CLI_EXIT_USAGE;
    }
    int status;
    if (strcmp(argv[1], "build") == 0) {
        sam_build_options o;
        status = build_parse(argc, argv, &o);
        return status == CLI_EXIT_OK ? build_run(&o) : status;
    }
    if (strcmp(argv[1], "info") == 0) {
        sam_info_options o;
        status = info_parse(argc, argv, &o);
        return status == CLI_EXIT_OK ? info_run(&o) : status;
    }
    const char *subs[] = {"build", "info"};
    return cli_unknown(CMD, "subcommand", argv[1], subs, 2);
}
