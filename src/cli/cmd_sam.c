/* cli/cmd_sam.c — `sss sam build` writes the Spatial Adjacency Map of a mesh (Maisch & Ropinski 2017) for a medium,
 * or of a scene object for its material and transform; `sss sam info` prints a .sam file's header and
 * checks it against a mesh or scene object. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "sss/sam.h"
#include "sss/scene.h"

#define CMD "sam"

enum {
    OPT_OUTPUT, OPT_MEDIUM, OPT_SCALE, OPT_ETA, OPT_MODEL, OPT_OBJECT, OPT_LINKS, OPT_SAMPLES, OPT_SEED, OPT_THREADS,
    OPT_BRUTE_FORCE, OPT_BACKSIDE_TRIANGLES, OPT_BACKSIDE_MESH, OPT_BACKSIDE_SPLAT
};
#define OBJECT_OPTION {OPT_OBJECT, "--object", NULL, CLI_ARG_NUMBER, "K", "scene object index (default: the first subsurface object)", NULL}
static const cli_option build_options[] = {
    {OPT_OUTPUT, "--output", "-o", CLI_ARG_FILE, "FILE", "output .sam file (written atomically)", NULL},
    {OPT_MEDIUM, "--medium", NULL, CLI_ARG_MEDIUM, "NAME", "measured medium (mesh input), e.g. Marble", NULL},
    {OPT_SCALE, "--scale", NULL, CLI_ARG_NUMBER, "S", "millimetres per mesh unit (default 1)", NULL},
    {OPT_ETA, "--eta", NULL, CLI_ARG_NUMBER, "E", "relative index of refraction (default 1.33)", NULL},
    {OPT_MODEL, "--model", NULL, CLI_ARG_TEXT, "M", "pbd (default, as PBRT-v3) or dipole", "pbd dipole"},
    OBJECT_OPTION,
    {OPT_LINKS, "--links", "-n", CLI_ARG_NUMBER, "N", "back-side links per vertex, 1.." CLI_STR(SSS_SAM_MAX_N) " (default 3, the paper's)",
     NULL},
    {OPT_SAMPLES, "--samples", NULL, CLI_ARG_NUMBER, "S",
     "Monte Carlo pairs per form factor, 1.." CLI_STR(SSS_SAM_MAX_SAMPLES) " (default 64)", NULL},
    {OPT_SEED, "--seed", NULL, CLI_ARG_NUMBER, "X", "seed of the sample shifts (default 0)", NULL},
    {OPT_THREADS, "--threads", NULL, CLI_ARG_NUMBER, "T", "OpenMP threads (default: all cores)", NULL},
    {OPT_BRUTE_FORCE, "--brute-force", NULL, CLI_ARG_NONE, NULL, "test every vertex pair instead of the tree (for checks; O(V^2))",
     NULL},
    {OPT_BACKSIDE_TRIANGLES, "--backside-triangles", NULL, CLI_ARG_NUMBER, "N",
     "the back side: the mesh simplified to at most N triangles (meshoptimizer)", NULL},
    {OPT_BACKSIDE_MESH, "--backside-mesh", NULL, CLI_ARG_FILE, "FILE",
     "the back side: a given coarse mesh (.ply/.obj) in the same space as the\n"
     "mesh (a scene object's: object space, posed by its transform)",
     NULL},
    {OPT_BACKSIDE_SPLAT, "--backside-splat", NULL, CLI_ARG_NONE, NULL,
     "the back side: a scene object's splat_mesh, or its mesh simplified to\n"
     "splat_triangles",
     NULL},
};
static const cli_option info_options[] = {OBJECT_OPTION};
const cli_command_spec cli_spec_sam_build = {"sam build", build_options, CLI_COUNT(build_options), CLI_ARG_FILE,
                                             "build info"};
const cli_command_spec cli_spec_sam_info = {"sam info", info_options, CLI_COUNT(info_options), CLI_ARG_FILE, NULL};

static void print_usage(FILE *f)
{
    fprintf(f,
            "usage: sss sam build MESH --medium NAME [--scale S] [--eta E] [options] -o FILE.sam\n"
            "       sss sam build SCENE.json [--object K] [options] -o FILE.sam\n"
            "       sss sam info FILE.sam [MESH | SCENE.json [--object K]]\n"
            "\n"
            "Builds a Spatial Adjacency Map (Maisch & Ropinski 2017): for every vertex the n back-side vertices\n"
            "(Eq. 13-14) with the largest Monte Carlo form factors between reduced triangle fans (Eq. 11), with\n"
            "the constants K' of Eq. 15 for deforming meshes. The search is best-first branch and bound over a\n"
            "vertex tree (exact: the same links as testing every pair). A mesh is taken in its own units with\n"
            "--scale millimetres per unit (as a scene's measured medium); a scene object with its transform and\n"
            "material. The file records the mesh (counts and a hash of positions and indices), n and the\n"
            "material; `sss render --technique sam` and `sss sam info` reject a file that does not match.\n"
            "\n"
            "back side on a lower-tessellation mesh (Maisch & Ropinski 2017, section 4.4 and its appendix): every vertex links\n"
            "to n vertices of a coarser mesh of the same surface, whose larger reduced fans (Eq. 16) are the\n"
            "sources of Eq. 11; n links then cover more of the back side of a finely tessellated mesh, and the\n"
            "search is faster. The file (version 2) holds the coarse mesh; the renderer lights its vertices\n"
            "(--backside-triangles, --backside-mesh, --backside-splat).\n"
            "\n");
    cli_print_options(f, &cli_spec_sam_build);
    fprintf(f,
            "\n"
            "Prints vertex and triangle counts, the build time, and how much of the (back-side) mesh the search\n"
            "visited.\n"
            "Exit status: 0 success, 1 error, 2 usage error.\n");
}

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

static int cmd_info(int argc, char **argv)
{
    const char *file = NULL, *against = NULL;
    int object = -1;
    cli_parser args;
    cli_parser_init(&args, &cli_spec_sam_info, argc, argv, 2);
    for (int o; (o = cli_next(&args)) != CLI_DONE;) {
        const char *a = args.given, *v = args.value;
        if (o == CLI_BAD) {
            return CLI_EXIT_USAGE;
        } else if (o == OPT_OBJECT) {
            if (!cli_parse_int_in(CMD, a, v, 0, INT_MAX, &object)) return CLI_EXIT_USAGE;
        } else if (!file) {
            file = v;
        } else if (!against) {
            against = v;
        } else {
            return cli_usage_error(CMD, "unexpected argument '%s'", v);
        }
    }
    if (!file) return cli_usage_error(CMD, "missing FILE.sam");
    sss_error err = {0};
    sss_sam s;
    if (sss_sam_read(file, &s, &err) != SSS_OK) return cli_fail(CMD, &err);
    int status = CLI_EXIT_OK;
    if (against && is_scene(against)) {
        sss_scene scene;
        if (sss_scene_load(against, NULL, &scene, &err) != SSS_OK) {
            sss_sam_free(&s);
            return cli_fail(CMD, &err);
        }
        int k = object >= 0 ? object : first_subsurface(&scene);
        sss_sam t;
        if (k < 0) status = cli_failf(CMD, "%s: no subsurface object", against);
        else if (sss_sam_read_object(file, &scene, (size_t)k, &t, &err) != SSS_OK) status = cli_fail(CMD, &err);
        else sss_sam_free(&t);
        sss_scene_free(&scene);
    } else if (against) {
        sss_mesh mesh;
        if (sss_mesh_read(against, &mesh, &err) != SSS_OK) status = cli_fail(CMD, &err);
        else {
            if (sss_sam_check(&s, &mesh, NULL, s.model, NULL, file, &err) != SSS_OK) status = cli_fail(CMD, &err);
            sss_mesh_free(&mesh);
        }
    }
    if (status == CLI_EXIT_OK) {
        print_map(&s);
        if (against) printf("matches %s\n", against);
    }
    sss_sam_free(&s);
    return status;
}

static int cmd_build(int argc, char **argv)
{
    const char *input = NULL, *output = NULL, *medium = NULL, *model_text = "pbd", *back_file = NULL;
    double scale = 1.0, eta = 1.33;
    int n = 3, samples = 64, threads = 0, object = -1, brute = 0, scale_given = 0, eta_given = 0, back_tris = 0;
    int back_splat = 0;
    long long seed = 0;
    cli_parser args;
    cli_parser_init(&args, &cli_spec_sam_build, argc, argv, 2);
    for (int o; (o = cli_next(&args)) != CLI_DONE;) {
        const char *a = args.given, *v = args.value;
        switch (o) {
        case CLI_BAD: return CLI_EXIT_USAGE;
        case OPT_OUTPUT: output = v; break;
        case OPT_MEDIUM: medium = v; break;
        case OPT_MODEL:
            model_text = v;
            if (strcmp(model_text, "pbd") != 0 && strcmp(model_text, "dipole") != 0)
                return cli_usage_error(CMD, "--model expects pbd or dipole, got '%s'", model_text);
            break;
        case OPT_SCALE:
        case OPT_ETA:
            if (!cli_parse_double(CMD, a, v, o == OPT_SCALE ? &scale : &eta)) return CLI_EXIT_USAGE;
            *(o == OPT_SCALE ? &scale_given : &eta_given) = 1;
            break;
        case OPT_LINKS:
        case OPT_SAMPLES:
            if (!cli_parse_int(CMD, a, v, o == OPT_LINKS ? &n : &samples)) return CLI_EXIT_USAGE;
            break;
        case OPT_OBJECT: /* -1 (and --threads 0) are the defaults' sentinels */
            if (!cli_parse_int_in(CMD, a, v, 0, INT_MAX, &object)) return CLI_EXIT_USAGE;
            break;
        case OPT_THREADS:
            if (!cli_parse_int_in(CMD, a, v, 1, 4096, &threads)) return CLI_EXIT_USAGE;
            break;
        case OPT_SEED: {
            double x;
            if (!cli_parse_double(CMD, a, v, &x)) return CLI_EXIT_USAGE;
            if (x < 0 || x > 9e15 || x != (double)(long long)x) return cli_usage_error(CMD, "--seed must be an integer >= 0");
            seed = (long long)x;
            break;
        }
        case OPT_BRUTE_FORCE: brute = 1; break;
        case OPT_BACKSIDE_TRIANGLES:
            if (!cli_parse_int(CMD, a, v, &back_tris)) return CLI_EXIT_USAGE;
            if (back_tris < 1) return cli_usage_error(CMD, "--backside-triangles must be >= 1");
            break;
        case OPT_BACKSIDE_MESH: back_file = v; break;
        case OPT_BACKSIDE_SPLAT: back_splat = 1; break;
        default: /* CLI_OPERAND */
            if (input) return cli_usage_error(CMD, "unexpected argument '%s'", v);
            input = v;
        }
    }
    if (!input) return cli_usage_error(CMD, "missing MESH or SCENE.json");
    if (!output) return cli_usage_error(CMD, "missing -o FILE.sam");
    if (!cli_require_extension(CMD, "-o", output, "sam")) return CLI_EXIT_USAGE;
    if (n < 1 || n > SSS_SAM_MAX_N) return cli_usage_error(CMD, "-n must be in 1..%d", SSS_SAM_MAX_N);
    if (samples < 1 || samples > SSS_SAM_MAX_SAMPLES)
        return cli_usage_error(CMD, "--samples must be in 1..%d", SSS_SAM_MAX_SAMPLES);
    int scene_input = is_scene(input);
    if (scene_input && (medium || scale_given || eta_given))
        return cli_usage_error(CMD, "--medium, --scale and --eta apply to a mesh; a scene object has its material");
    if (!scene_input && object >= 0) return cli_usage_error(CMD, "--object needs a SCENE.json");
    if (!scene_input && !medium) return cli_usage_error(CMD, "missing --medium NAME (the mesh's material)");
    if ((back_tris > 0) + (back_file != NULL) + back_splat > 1)
        return cli_usage_error(CMD, "--backside-triangles, --backside-mesh and --backside-splat exclude each other");
    if (back_splat && !scene_input) return cli_usage_error(CMD, "--backside-splat needs a SCENE.json");

    sss_sam_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.n = (uint32_t)n;
    desc.samples = (uint32_t)samples;
    desc.seed = (uint64_t)seed;
    desc.threads = threads;
    desc.brute_force = brute;
    desc.backside_triangles = (uint32_t)back_tris;
    sss_error err = {0};
    sss_sam s;
    sss_sam_stats st;
    sss_result res;
    sss_mesh back;
    memset(&back, 0, sizeof back);
    const char *inputs[2] = {input, back_file};
    if (cli_check_outputs(CMD, &output, 1, inputs, 2, NULL) != CLI_EXIT_OK) return CLI_EXIT_ERROR;
    if (back_file) {
        if (sss_mesh_read(back_file, &back, &err) != SSS_OK) return cli_fail(CMD, &err);
        desc.backside = &back;
    }
    if (scene_input) {
        sss_scene scene;
        if (sss_scene_load(input, NULL, &scene, &err) != SSS_OK) {
            sss_mesh_free(&back);
            return cli_fail(CMD, &err);
        }
        if (cli_check_outputs(CMD, &output, 1, NULL, 0, &scene) != CLI_EXIT_OK) {
            sss_scene_free(&scene);
            sss_mesh_free(&back);
            return CLI_EXIT_ERROR;
        }
        int k = object >= 0 ? object : first_subsurface(&scene);
        if (k < 0) {
            sss_scene_free(&scene);
            sss_mesh_free(&back);
            return cli_failf(CMD, "%s: no subsurface object", input);
        }
        const sss_scene_object *o = (size_t)k < scene.object_count ? &scene.objects[k] : NULL;
        if (back_splat && o) {
            /* the scene's own low-resolution mesh of the object (docs/scene-format.md: splat_mesh, splat_triangles) */
            if (o->splat_mesh.vertex_count) desc.backside = &o->splat_mesh;
            else if (o->splat_triangles) desc.backside_triangles = o->splat_triangles;
            else {
                sss_scene_free(&scene);
                return cli_failf(CMD, "%s: objects[%d] has neither splat_mesh nor splat_triangles (--backside-splat)",
                                 input, k);
            }
        }
        res = sss_sam_build_object(&scene, (size_t)k, &desc, &s, &st, &err);
        sss_scene_free(&scene);
    } else {
        sss_material m;
        if (sss_material_from_medium(medium, scale, eta, &m, &err) != SSS_OK) return cli_fail(CMD, &err);
        sss_profile_model model = strcmp(model_text, "dipole") == 0 ? SSS_PROFILE_DIPOLE : SSS_PROFILE_PBD;
        sss_pbd_table *table = NULL;
        if (model == SSS_PROFILE_PBD) {
            table = malloc(sizeof *table);
            if (!table) return cli_failf(CMD, "out of memory for the PBD table");
            if (sss_pbd_table_build(m.eta, m.g, table, &err) != SSS_OK) {
                free(table);
                return cli_fail(CMD, &err);
            }
        }
        sss_profile p;
        sss_mesh mesh;
        res = sss_profile_init(&p, model, &m, table, &err);
        if (res == SSS_OK) res = sss_mesh_read(input, &mesh, &err);
        if (res == SSS_OK) {
            res = sss_sam_build(&mesh, &p, &desc, &s, &st, &err);
            sss_mesh_free(&mesh);
        }
        free(table);
    }
    sss_mesh_free(&back);
    if (res != SSS_OK) return cli_fail(CMD, &err);
    res = sss_sam_write(output, &s, &err);
    if (res != SSS_OK) {
        sss_sam_free(&s);
        return cli_fail(CMD, &err);
    }
    printf("wrote %s\n", output);
    print_map(&s);
    double pairs = (double)s.vertex_count * (s.back_vertex_count ? s.back_vertex_count : s.vertex_count);
    printf("build_s %.3f\n", st.seconds);
    printf("nodes_visited %llu\nvertices_tested %llu (%.4f%% of all pairs)\nform_factors %llu\n",
           (unsigned long long)st.nodes_visited, (unsigned long long)st.vertices_tested,
           pairs > 0 ? 100.0 * (double)st.vertices_tested / pairs : 0.0, (unsigned long long)st.form_factors);
    sss_sam_free(&s);
    if (fflush(stdout) != 0 || ferror(stdout)) return cli_failf(CMD, "error writing the output");
    return CLI_EXIT_OK;
}

int sss_cmd_sam(int argc, char **argv)
{
    if (cli_wants_help(argc, argv) || argc < 2) {
        print_usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? CLI_EXIT_USAGE : CLI_EXIT_OK;
    }
    if (strcmp(argv[1], "build") == 0) return cmd_build(argc, argv);
    if (strcmp(argv[1], "info") == 0) return cmd_info(argc, argv);
    const char *subs[] = {"build", "info"};
    return cli_unknown(CMD, "subcommand", argv[1], subs, 2);
}
