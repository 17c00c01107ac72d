/* maisch2020: grazing pixels at a silhouette get their share of the subsurface integral
 * (grazing_sources, footprint_split; docs/maisch2020.md).
 *
 * The rim of a large Skin1 sphere (radius 1, 200 mm per unit: red 1 / sigma_tr ~ 0.018 units, blue
 * ~ 0.0034) seen from far away (20 units, a 0.4-unit window: 0.0031 units per pixel), lit by a
 * directional light travelling along -x, i.e. straight onto the silhouette at x = 1. Within the
 * kernel's reach of the rim (five red mean free paths, 0.09 radians of the sphere) the surface leaves
 * its tangent plane by 0.4% of the radius and the irradiance varies by 0.4% (cos 0.09): the
 * scattering integral at a rim point is that of a uniformly lit plane, F_t E rho_eff (docs/physics.md §1: the
 * plane integral of R_d is rho_eff), from the surface the camera sees and, within a few mean free
 * paths of the silhouette, from the surface just past it (the splats' part).
 *
 * What is checked is the sum the technique multiplies by the exit factor c_o: the screen-space part
 * plus the upsampled translucency ("screen" + "translucency_full"). Per pixel it must be
 * F_t(n.l) (n.l) E rho_eff whatever n.v is; n.v and n.l are the ideal sphere's at the pixel's ray.
 * Checked in bands of n.v: the grazing pixels 0.06 <= n.v < 0.2, below Eq. 8's cut-off (the default
 * grazing_sources 0.05 leaves steeper ones out), and the ones beside them, 0.2 <= n.v < 0.4, where
 * counting a pixel's area twice would show; rows within 16 pixels of the equator (n.l >= 0.999); and
 * the pixels well inside, 0.4 <= n.v < 0.7. Bound 4% per band and channel. Measured: the paper
 * (grazing_sources 0, footprint_split 1) R -51..-61%, G -68..-77%, B -80..-86% on the grazing bands and
 * +35/+61/+91% at n.v 0.2-0.3 (one disc per oblique pixel reaches the neighbours' kernel peaks); the
 * defaults within -2.8..+1.7% (R at n.v 0.06-0.1 the worst). Before issue 32 the defaults measured
 * -1.4..+13.6% on the grazing bands and R +1.7%, G +6.2%, B +12.8% inside (bound 15%, the inside not
 * checked): the receiver's own oblique pixel was cut into an even number of pieces, with x_o where two
 * of them meet, so both discs held the kernel's peak (maisch2020_screen.frag.glsl, oblique_pixel). */
#include "gl_test_util.h"
#include "sss/material.h"

#define SIZE 128
#define DIST 20.0
#define CX 0.9 /* the window's centre, x */
#define HALF 0.2
#define TOL 0.04

static int sphere_scene(sss_scene *scene)
{
    char json[2048];
    double fov = 2.0 * atan(HALF / DIST) * 180.0 / M_PI;
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [%g, 0, %g], \"look_at\": [%g, 0, 0], \"up\": [0, 1, 0], \"fov\": %.9g,"
             " \"width\": %d, \"height\": %d},"
             " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1, \"subdivisions\": 6},"
             " \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin1\", \"scale\": 200.0, \"eta\": 1.33}}],"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [-1, 0, 0], \"radiance\": [1, 1, 1]}]}",
             CX, DIST, CX, fov, SIZE, SIZE);
    sss_error err = {0};
    if (sss_scene_parse(json, strlen(json), ".", "rim", NULL, scene, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    return 1;
}

/* n.v and n.l at the ideal sphere where pixel (x, y) (top row first) looks; 0 when the ray misses. */
static int pixel_geometry(int x, int y, double *nv, double *nl)
{
    double t = HALF / DIST; /* tan of half the field of view */
    double d[3] = {((x + 0.5) / (SIZE / 2.0) - 1.0) * t, (1.0 - (y + 0.5) / (SIZE / 2.0)) * t, -1.0};
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; k++) d[k] /= len;
    double o[3] = {CX, 0.0, DIST};
    double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
    double c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - 1.0;
    double disc = b * b - c;
    if (disc <= 0.0) return 0;
    double s = -b - sqrt(disc);
    double n[3] = {o[0] + s * d[0], o[1] + s * d[1], o[2] + s * d[2]};
    *nv = -(n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
    *nl = n[0];
    return 1;
}

/* Mean relative deviation of screen + translucency from F_t(n.l) n.l E rho_eff over the pixels of a
 * band of n.v, per channel. */
static void band_error(const sss_image *sum, double eta, const double rho[3], double lo, double hi, double dev[3],
                       int *count)
{
    double acc[3] = {0, 0, 0};
    *count = 0;
    for (int y = SIZE / 2 - 16; y < SIZE / 2 + 16; y++)
        for (int x = 0; x < SIZE; x++) {
            double nv, nl;
            if (!pixel_geometry(x, y, &nv, &nl) || nv < lo || nv >= hi) continue;
            double e = (1.0 - sss_fresnel_dielectric(nl, 1.0, eta)) * nl;
            for (int c = 0; c < 3; c++) acc[c] += sum->pixels[3 * ((size_t)y * SIZE + x) + c] / (e * rho[c]) - 1.0;
            (*count)++;
        }
    for (int c = 0; c < 3; c++) dev[c] = *count ? acc[c] / *count : 1.0;
}

static int render_sum(const sss_scene *scene, const sss_gl_param_value *p, int np, sss_image *sum)
{
    static const char *const names[2] = {"screen", "translucency_full"};
    sss_image b[2];
    memset(sum, 0, sizeof *sum);
    if (!gt_render_buffers(scene, "maisch2020", p, np, names, b, 2)) return 0;
    int ok = b[0].width == SIZE && b[0].height == SIZE && b[1].width == SIZE && b[1].height == SIZE;
    for (size_t i = 0; ok && i < 3 * (size_t)SIZE * SIZE; i++) b[0].pixels[i] += b[1].pixels[i];
    sss_image_free(&b[1]);
    if (ok) *sum = b[0];
    else sss_image_free(&b[0]);
    return ok;
}

int main(void)
{
    sss_scene scene;
    if (!sphere_scene(&scene)) {
        CHECK(0);
        return CHECK_DONE();
    }
    const sss_scene_material *m = &scene.objects[0].material;
    double eta = m->optical.eta;
    /* sub-bands of n.v: the grazing ones (Eq. 8: below 0.2), the ones beside them, and one well inside */
    static const double edge[] = {0.06, 0.1, 0.15, 0.2, 0.3, 0.4};
    enum { BANDS = 5 };
    for (int fixed = 0; fixed <= 1; fixed++) {
        /* fixed = 1: the defaults; 0: the paper (no grazing sources, one disc per sample) */
        sss_gl_param_value p[3] = {{"brightening", 0}, {"grazing_sources", 0}, {"footprint_split", 1}};
        sss_image sum;
        if (!render_sum(&scene, p, fixed ? 1 : 3, &sum)) {
            CHECK(0);
            continue;
        }
        CHECK(sss_image_count_nonfinite(&sum) == 0);
        printf("%s: (screen + translucency) / (F_t E rho_eff) - 1 by n.v:\n",
               fixed ? "default" : "paper (grazing_sources 0, footprint_split 1)");
        for (int k = 0; k <= BANDS; k++) {
            double lo = k < BANDS ? edge[k] : 0.4, hi = k < BANDS ? edge[k + 1] : 0.7, dev[3];
            int n;
            band_error(&sum, eta, m->albedo, lo, hi, dev, &n);
            printf("  n.v %.2f..%.2f (%4d px): R %+6.1f%% G %+6.1f%% B %+6.1f%%\n", lo, hi, n, 100 * dev[0],
                   100 * dev[1], 100 * dev[2]);
            CHECK(n >= 20);
            if (!fixed) continue;
            for (int c = 0; c < 3; c++)
                CHECK_MSG(fabs(dev[c]) < TOL, "n.v %.2f..%.2f, channel %d: %+.3f off F_t E rho_eff", lo, hi, c, dev[c]);
        }
        sss_image_free(&sum);
    }
    sss_scene_free(&scene);
    return CHECK_DONE();
}
