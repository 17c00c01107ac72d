/* examples/render.c — render a scene file in real time, headless, to an image.
 *
 *   example_render SCENE.json TECHNIQUE OUT.png      e.g.  example_render scenes/default.json ssss out.png
 *
 * Loads the JSON scene, creates an OpenGL 4.5 context without a window (EGL; Mesa's llvmpipe works
 * without a GPU), renders one frame with the technique (`sss techniques` lists them) and writes it:
 * PNG tone-mapped with the scene's exposure, or .exr/.pfm/.hdr with the linear values.
 * `sss render SCENE.json --technique TECHNIQUE -o OUT.png` writes the same pixels.
 *
 * Build: cc render.c $(pkg-config --cflags --libs sss), or CMake: find_package(sss) and sss::sss.
 */
#include <stdio.h>

#include <sss/sss.h>

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: %s SCENE.json TECHNIQUE OUT.png\n", argv[0]);
        return 2;
    }
    const char *scene_path = argv[1], *technique = argv[2], *output = argv[3];
    sss_error err = {0};
    int status = 1;

    /* Meshes, materials and lights; paths inside the scene are relative to the scene file. */
    sss_scene scene;
    if (sss_scene_load(scene_path, NULL, &scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    /* Everything below starts empty, so the clean-up at `done` works from any step. */
    sss_gl_context *context = NULL;
    sss_gl_renderer *renderer = NULL;
    sss_image image = {0};

    /* Zero-initialised descriptions mean defaults: a headless context; the renderer at the scene
     * camera's size with the technique's default parameters. */
    sss_gl_context_desc context_desc = {0};
    if (sss_gl_context_create(&context_desc, &context, &err) != SSS_OK) goto done;
    sss_gl_renderer_desc renderer_desc = {0};
    renderer_desc.technique = technique;
    if (sss_gl_renderer_create(context, &scene, &renderer_desc, &renderer, &err) != SSS_OK) goto done;

    int width, height;
    sss_gl_renderer_size(renderer, &width, &height);
    if (sss_image_create(&image, width, height, &err) != SSS_OK) goto done;
    /* One frame at animation time 0, read back as linear RGB floats. */
    if (sss_gl_renderer_render(renderer, 0.0, &err) != SSS_OK) goto done;
    if (sss_gl_renderer_read(renderer, &image, &err) != SSS_OK) goto done;
    if (sss_image_write(output, &image, scene.render.exposure, &err) != SSS_OK) goto done;
    status = 0;

done:
    if (status != 0) fprintf(stderr, "%s\n", err.message);
    sss_image_free(&image);
    sss_gl_renderer_destroy(renderer); /* the renderer before its context, the scene last */
    sss_gl_context_destroy(context);
    sss_scene_free(&scene);
    return status;
}
