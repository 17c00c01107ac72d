/* export/pbrt.c — a scene of docs/scene-format.md as PBRT-v3 input (see sss/export.h for the mapping). */
#include "sss/export.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "export/export_test.h"
#include "scene/scene_files.h"

#define PATH_CAP 4096

/* Every string from data (file names, the scene's name, texture and medium names) is written through
 * here: quoted, with the escapes PBRT-v3's tokenizer decodes (\b \f \n \r \t \\ \' \"), so a quote
 * cannot end the string and a newline cannot end it or a comment; other bytes go unchanged (its
 * tokenizer keeps them inside a string). */
static void pbrt_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        switch (*s) {
        case '"': fputs("\\\"", f); break;
        case '\\': fputs("\\\\", f); break;
        case '\n': fputs("\\n", f); break;
        case '\r': fputs("\\r", f); break;
        case '\t': fputs("\\t", f); break;
        case '\b': fputs("\\b", f); break;
        case '\f': fputs("\\f", f); break;
        default: fputc(*s, f);
        }
    }
    fputc('"', f);
}

static void rgb(FILE *f, const char *type_name, const double v[3])
{
    fprintf(f, " \"rgb %s\" [%.9g %.9g %.9g]", type_name, v[0], v[1], v[2]);
}

static void point(FILE *f, const char *name, const double v[3])
{
    fprintf(f, " \"point %s\" [%.9g %.9g %.9g]", name, v[0], v[1], v[2]);
}

void export_pbrt_env_light_to_world(double rotate_y_degrees, double m[16])
{
    /* World-to-light W = Rz(rot) M with M d = (d.z, -d.x, d.y): PBRT's phi = atan2(L.y, L.x) then
     * equals 2 pi u of the scene format's map (u = 0.5 + (atan2(d.x, -d.z) + rot) / 2 pi) and its theta,
     * measured from +z, equals the angle from +y. M is a reflection (det -1): PBRT's spherical
     * parameterisation runs the other way round than the scene format's. Light-to-world = W^T. */
    double c = cos(rotate_y_degrees * M_PI / 180.0), s = sin(rotate_y_degrees * M_PI / 180.0);
    const double M[3][3] = {{0, 0, 1}, {-1, 0, 0}, {0, 1, 0}};
    const double Rz[3][3] = {{c, -s, 0}, {s, c, 0}, {0, 0, 1}};
    double W[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) W[i][j] = Rz[i][0] * M[0][j] + Rz[i][1] * M[1][j] + Rz[i][2] * M[2][j];
    memset(m, 0, 16 * sizeof(double));
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) m[4 * i + j] = W[j][i];
    m[15] = 1.0;
}

/* PBRT's Transform directive takes the matrix column by column. */
static void transform_directive(FILE *f, const double m[16])
{
    fprintf(f, "    Transform [");
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) fprintf(f, " %.9g", m[4 * row + col]);
    fprintf(f, " ]\n");
}

static void write_camera(FILE *f, const sss_scene *scene, const char *image_name, int spp, int maxdepth)
{
    const sss_camera *c = &scene->camera;
    double exposure_scale = pow(2.0, scene->render.exposure);
    fprintf(f, "# PBRT-v3's camera space is left-handed; the mirror keeps the image as docs/scene-format.md has it.\n");
    fprintf(f, "Scale -1 1 1\n");
    fprintf(f, "LookAt %.9g %.9g %.9g  %.9g %.9g %.9g  %.9g %.9g %.9g\n", c->position[0], c->position[1],
            c->position[2], c->look_at[0], c->look_at[1], c->look_at[2], c->up[0], c->up[1], c->up[2]);
    fprintf(f, "Camera \"perspective\" \"float fov\" [%.9g]\n", c->fov);
    fprintf(f, "Film \"image\" \"integer xresolution\" [%d] \"integer yresolution\" [%d]\n    \"string filename\" [",
            c->width, c->height);
    pbrt_string(f, image_name);
    fprintf(f, "] \"float scale\" [%.9g]\n", exposure_scale);
    fprintf(f, "Sampler \"halton\" \"integer pixelsamples\" [%d]\n", spp);
    fprintf(f, "# maxdepth 1: refraction at the camera hit, BSSRDF probe, direct light at the entry point\n"
               "# (the single-event subsurface integral: sss reference --bounces 1); each further depth adds\n"
               "# one surface hit: a subsurface or diffuse event (sss reference --bounces N) or a mirror\n"
               "# reflection off a subsurface interface (which sss reference counts within its bounce).\n");
    fprintf(f, "Integrator \"path\" \"integer maxdepth\" [%d]\n\n", maxdepth);
}

static void write_material(FILE *f, const sss_scene_material *m)
{
    if (m->type == SSS_SCENE_MATERIAL_DIFFUSE) {
        fprintf(f, "    Material \"matte\"");
        rgb(f, "Kd", m->albedo);
        fprintf(f, "\n");
        return;
    }
    if (m->profile != SSS_SCENE_PROFILE_PBD) {
        fprintf(f, "    # profile ");
        pbrt_string(f, sss_scene_profile_name(m->profile));
        fprintf(f, " has no PBRT equivalent: PBRT uses its photon beam diffusion table\n");
    }
    if (m->texture) {
        fprintf(f, "    # texture ");
        pbrt_string(f, m->texture);
        fprintf(f, " is not exported\n");
    }
    switch (m->source) {
    case SSS_SUBSURFACE_MEDIUM:
        fprintf(f, "    Material \"subsurface\" \"string name\" [");
        pbrt_string(f, m->medium->name);
        fprintf(f, "] \"float scale\" [%.9g] \"float eta\" [%.9g]\n", m->scale, m->optical.eta);
        break;
    case SSS_SUBSURFACE_COEFFICIENTS:
        fprintf(f, "    Material \"subsurface\"");
        rgb(f, "sigma_a", m->input_sigma_a);
        rgb(f, "sigma_s", m->input_sigma_s);
        fprintf(f, " \"float scale\" [%.9g] \"float eta\" [%.9g] \"float g\" [%.9g]\n", m->scale,
                m->optical.eta, m->optical.g);
        break;
    case SSS_SUBSURFACE_REFLECTANCE:
        fprintf(f, "    Material \"kdsubsurface\"");
        rgb(f, "Kd", m->reflectance);
        rgb(f, "mfp", m->mfp);
        fprintf(f, " \"float eta\" [%.9g]\n", m->optical.eta);
        break;
    }
}

static void write_light(FILE *f, const sss_light *l)
{
    switch (l->type) {
    case SSS_LIGHT_POINT:
        fprintf(f, "LightSource \"point\"");
        point(f, "from", l->position);
        rgb(f, "I", l->intensity);
        fprintf(f, "\n");
        break;
    case SSS_LIGHT_SPOT:
        fprintf(f, "LightSource \"spot\"");
        point(f, "from", l->position);
        point(f, "to", l->look_at);
        fprintf(f, " \"float coneangle\" [%.9g] \"float conedelta\" [%.9g]", l->cone_angle, l->cone_delta);
        rgb(f, "I", l->intensity);
        fprintf(f, "\n");
        break;
    case SSS_LIGHT_DIRECTIONAL: {
        /* PBRT's distant light travels from "from" to "to". */
        const double zero[3] = {0, 0, 0};
        fprintf(f, "LightSource \"distant\"");
        point(f, "from", zero);
        point(f, "to", l->direction);
        rgb(f, "L", l->radiance);
        fprintf(f, "\n");
        break;
    }
    case SSS_LIGHT_AREA: {
        /* Corners counter-clockwise about u x v: PBRT's triangle normal (p0 - p2) x (p1 - p2) is then
         * u x v, the side the scene format's area light emits towards. */
        double p[4][3];
        const double su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
        for (int k = 0; k < 4; k++)
            for (int i = 0; i < 3; i++) p[k][i] = l->center[i] + su[k] * l->u[i] + sv[k] * l->v[i];
        fprintf(f, "AttributeBegin\n    AreaLightSource \"diffuse\"");
        rgb(f, "L", l->radiance);
        fprintf(f, " \"bool twosided\" [\"%s\"]\n", l->two_sided ? "true" : "false");
        fprintf(f, "    Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"point P\" [");
        for (int k = 0; k < 4; k++) fprintf(f, " %.9g %.9g %.9g", p[k][0], p[k][1], p[k][2]);
        fprintf(f, " ]\nAttributeEnd\n");
        break;
    }
    case SSS_LIGHT_ENVIRONMENT: {
        double m[16];
        export_pbrt_env_light_to_world(l->rotate_y, m);
        fprintf(f, "AttributeBegin\n");
        transform_directive(f, m);
        /* PBRT resolves relative names against the .pbrt file's folder: write an absolute path. */
        char *abs = realpath(l->file, NULL);
        fprintf(f, "    LightSource \"infinite\" \"string mapname\" [");
        pbrt_string(f, abs ? abs : l->file);
        fprintf(f, "]");
        free(abs);
        rgb(f, "L", l->scale);
        fprintf(f, "\nAttributeEnd\n");
        break;
    }
    }
}

/* "<dir>/<stem>" of out_path, and the file name part of a sibling "<stem><suffix>". */
static int sibling(const char *out_path, const char *suffix, char *path, size_t cap, const char **name)
{
    const char *slash = strrchr(out_path, '/');
    const char *base = slash ? slash + 1 : out_path;
    const char *dot = strrchr(base, '.');
    size_t stem = dot ? (size_t)(dot - out_path) : strlen(out_path);
    int n = snprintf(path, cap, "%.*s%s", (int)stem, out_path, suffix);
    if (name) *name = path + (base - out_path);
    return n > 0 && (size_t)n < cap;
}

/* The meshes' paths "<stem>_objN.ply" beside out_path, and the export's files checked before anything
 * is written: no output may be one of the files the scene reads (a mesh named like a sibling) or
 * another output. */
static sss_result mesh_files(const sss_scene *scene, const char *out_path, char (*mesh_paths)[PATH_CAP],
                             sss_error *err)
{
    sss_io_set io = {0};
    scene_add_inputs(&io, scene);
    sss_io_add_output(&io, out_path);
    sss_result res = SSS_OK;
    for (size_t i = 0; i < scene->object_count && res == SSS_OK; i++) {
        char suffix[64];
        snprintf(suffix, sizeof suffix, "_obj%zu.ply", i);
        if (!sibling(out_path, suffix, mesh_paths[i], PATH_CAP, NULL))
            res = sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: path too long", out_path);
        sss_io_add_output(&io, mesh_paths[i]);
    }
    if (res == SSS_OK) res = sss_io_check(&io, err);
    sss_io_free(&io);
    return res;
}

sss_result sss_export_pbrt(const sss_scene *scene, const sss_export_pbrt_desc *desc, const char *out_path,
                           sss_error *err)
{
    sss_export_pbrt_desc d = desc ? *desc : (sss_export_pbrt_desc){0};
    if (d.pixel_samples <= 0) d.pixel_samples = 256;
    if (d.maxdepth == 0) d.maxdepth = SSS_EXPORT_PBRT_MAXDEPTH_DEFAULT;
    if (d.maxdepth < 1 || d.maxdepth > SSS_EXPORT_PBRT_MAXDEPTH_MAX)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "export pbrt: maxdepth must be in 1..%d, got %d",
                             SSS_EXPORT_PBRT_MAXDEPTH_MAX, d.maxdepth);
    if (!isfinite(d.time))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: export time is not finite", out_path);

    char image_buf[PATH_CAP];
    const char *image_name = d.image_name;
    if (!image_name) {
        if (!sibling(out_path, ".exr", image_buf, sizeof image_buf, &image_name))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: path too long", out_path);
    }

    /* The meshes and the .pbrt file are one transaction: all of them or none. */
    char (*mesh_paths)[PATH_CAP] = calloc(scene->object_count ? scene->object_count : 1, PATH_CAP);
    if (!mesh_paths) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: out of memory", out_path);
    sss_result res = mesh_files(scene, out_path, mesh_paths, err);
    sss_outputs outputs;
    sss_outputs_begin(&outputs);
    for (size_t i = 0; i < scene->object_count && res == SSS_OK; i++) {
        sss_mesh world = {0};
        res = sss_scene_object_world_mesh(&scene->objects[i], d.time, &world, err);
        if (res != SSS_OK) {
            char prefix[512]; /* the scene file and the object, like the loader's messages */
            snprintf(prefix, sizeof prefix, "%s: objects[%zu]", scene->name ? scene->name : "scene", i);
            sss_error_prefix(err, prefix);
        }
        if (res == SSS_OK) res = sss_mesh_write_ply(mesh_paths[i], &world, err);
        sss_mesh_free(&world);
    }

    char tmp[PATH_CAP];
    FILE *f = NULL;
    if (res == SSS_OK) f = sss_atomic_open(out_path, tmp, sizeof tmp, err);
    if (res == SSS_OK && !f) res = err ? err->code : SSS_ERROR_IO;
    if (f) {
        fprintf(f, "# Written by sss export pbrt from ");
        pbrt_string(f, scene->name ? scene->name : "a scene");
        fprintf(f, " (time %.9g s).\n", d.time);
        write_camera(f, scene, image_name, d.pixel_samples, d.maxdepth);
        fprintf(f, "WorldBegin\n");
        for (size_t i = 0; i < scene->light_count; i++) write_light(f, &scene->lights[i]);
        for (size_t i = 0; i < scene->object_count; i++) {
            const char *slash = strrchr(mesh_paths[i], '/');
            fprintf(f, "AttributeBegin\n");
            write_material(f, &scene->objects[i].material);
            fprintf(f, "    Shape \"plymesh\" \"string filename\" [");
            pbrt_string(f, slash ? slash + 1 : mesh_paths[i]);
            fprintf(f, "]\nAttributeEnd\n");
        }
        fprintf(f, "WorldEnd\n");
        res = sss_atomic_close(f, tmp, out_path, err);
    }
    sss_result ended = sss_outputs_end(&outputs, res == SSS_OK, err);
    if (res == SSS_OK) res = ended;
    free(mesh_paths);
    return res;
}
