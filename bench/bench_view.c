/* bench_view — the cost of the viewer's panel per frame: median frame time (render, show, panel, swap)
 * of `sss view --script` frames with the panel shown (docked beside the image: the frame is read back
 * and drawn into the image's part of the window, and the panel drawn) and, at the same image size,
 * with the panel hidden from the start (`--no-overlay`: the window is the image, presented directly);
 * and material edits: the worker's time (scene loader, LUTs), the frames drawn meanwhile, and the
 * longest frame on the window thread (the one that creates the renderer from the worker's tables).
 * Needs a display (`xvfb-run -a bench_view`); without one it says so and exits 0.
 * Usage: bench_view [scene.json] [frames] [rounds]   (defaults scenes/gl_area.json 40 3) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sss/view.h"

static void print_message(void *user, const char *message)
{
    (void)user;
    if (strstr(message, "frames:") || strstr(message, "rebuilt") || strstr(message, "wait:")) printf("  %s\n", message);
}

/* One viewer run of a script of rounds x frames (after as many frames of warm-up), then the edits. */
static int run(const char *scene, int frames, int rounds, int edits, int no_overlay)
{
    char path[] = "/tmp/bench_view_XXXXXX";
    int fd = mkstemp(path);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f) {
        fprintf(stderr, "bench_view: cannot write a temporary script\n");
        return 1;
    }
    fprintf(f, "frames %d\n", frames); /* warm-up */
    for (int r = 0; r < rounds; r++) fprintf(f, "frames %d\n", frames);
    static const double scales[] = {2.0, 0.5, 1.0};
    /* each edit builds in the background: `wait` draws frames until it is applied and reports the
     * longest of them (the window thread's stall: the frame that creates the renderer) */
    for (int r = 0; r < (edits ? 3 : 0); r++) fprintf(f, "material 0 scale %g\nwait\n", scales[r]);
    fclose(f);
    printf("bench_view: %s, %d frames per measurement, %d rounds, panel %s\n", scene, frames, rounds,
           no_overlay ? "hidden (--no-overlay)" : "shown");
    sss_view_desc d;
    memset(&d, 0, sizeof d);
    d.scene_path = scene;
    d.script = path;
    d.no_overlay = no_overlay;
    d.log = print_message;
    sss_error err = {0};
    sss_result res = sss_view_run(&d, &err);
    unlink(path);
    if (res != SSS_OK) fprintf(stderr, "bench_view: %s\n", err.message);
    return res == SSS_OK ? 0 : 1;
}

int main(int argc, char **argv)
{
    const char *scene = argc > 1 ? argv[1] : "scenes/gl_area.json";
    int frames = argc > 2 ? atoi(argv[2]) : 40, rounds = argc > 3 ? atoi(argv[3]) : 3;
    if (!getenv("DISPLAY") && !getenv("WAYLAND_DISPLAY")) {
        printf("bench_view: skipped (no display; run under xvfb-run -a)\n");
        return 0;
    }
    return run(scene, frames, rounds, 1, 0) || run(scene, frames, rounds, 0, 1);
}
