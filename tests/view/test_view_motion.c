/* tests/view/test_view_motion.c — the viewer's camera and light motion, checked through the scene
 * module's own camera projection (an independent path): orbit keeps look_at at the image centre and
 * the distance, pan moves look_at by exactly the dragged pixels, zoom scales the distance only, the
 * light rotation is a rigid rotation about the vertical through the pivot. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "view/view_internal.h"

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static sss_camera test_camera(void)
{
    sss_camera c;
    memset(&c, 0, sizeof c);
    double p[3] = {1.0, 2.0, 6.0}, l[3] = {0.5, 1.0, -0.5};
    memcpy(c.position, p, sizeof p);
    memcpy(c.look_at, l, sizeof l);
    c.up[1] = 1.0;
    c.fov = 35.0;
    c.width = 160;
    c.height = 120;
    return c;
}

static int project(const sss_camera *c, const double p[3], double raster[2])
{
    sss_camera_basis b;
    if (sss_camera_basis_init(c, &b, NULL) != SSS_OK) return 0;
    return sss_camera_project(&b, p, raster, NULL);
}

static void test_orbit(void)
{
    sss_camera c = test_camera();
    double d0 = dist3(c.position, c.look_at), h0 = c.position[1] - c.look_at[1];
    /* azimuth only: a rotation about the vertical through look_at (height above it is kept) */
    view_orbit(&c, 40.0, 0.0);
    CHECK_NEAR(dist3(c.position, c.look_at), d0, 1e-12 * d0);
    CHECK_NEAR(c.position[1] - c.look_at[1], h0, 1e-12 * d0);
    double r[2];
    CHECK(project(&c, c.look_at, r));
    CHECK_NEAR(r[0], 80.0, 1e-9);
    CHECK_NEAR(r[1], 60.0, 1e-9);
    /* the azimuth angle between the horizontal offsets is the one asked for */
    sss_camera s = test_camera();
    double a0 = atan2(s.position[0] - s.look_at[0], s.position[2] - s.look_at[2]);
    double a1 = atan2(c.position[0] - c.look_at[0], c.position[2] - c.look_at[2]);
    CHECK_NEAR(remainder(a1 - a0, 2.0 * M_PI), 40.0 * M_PI / 180.0, 1e-12);
    /* a full turn returns */
    for (int i = 0; i < 8; i++) view_orbit(&c, 40.0, 0.0);
    for (int k = 0; k < 3; k++) CHECK_NEAR(c.position[k], s.position[k], 1e-9);
    /* elevation: up by 10 degrees raises the camera's polar angle by exactly 10 degrees */
    c = test_camera();
    double pol0 = acos((c.position[1] - c.look_at[1]) / d0);
    view_orbit(&c, 0.0, 10.0);
    double pol1 = acos((c.position[1] - c.look_at[1]) / dist3(c.position, c.look_at));
    CHECK_NEAR(pol0 - pol1, 10.0 * M_PI / 180.0, 1e-12);
    CHECK_NEAR(dist3(c.position, c.look_at), d0, 1e-12 * d0);
    /* elevation stops 1 degree short of the pole: the camera basis stays defined */
    view_orbit(&c, 0.0, 500.0);
    double pol2 = acos((c.position[1] - c.look_at[1]) / dist3(c.position, c.look_at));
    CHECK_NEAR(pol2, M_PI / 180.0, 1e-9);
    sss_camera_basis b;
    CHECK(sss_camera_basis_init(&c, &b, NULL) == SSS_OK);
    view_orbit(&c, 0.0, -500.0);
    double pol3 = acos((c.position[1] - c.look_at[1]) / dist3(c.position, c.look_at));
    CHECK_NEAR(pol3, M_PI - M_PI / 180.0, 1e-9);
}

static void test_pan_zoom(void)
{
    sss_camera c = test_camera();
    double target[3];
    memcpy(target, c.look_at, sizeof target);
    double d0 = dist3(c.position, c.look_at);
    /* dragging by (dx, dy) pixels moves the point that was at look_at by (dx, dy) on screen */
    view_pan(&c, 17.0, -9.0, c.width, c.height);
    double r[2];
    CHECK(project(&c, target, r));
    CHECK_NEAR(r[0], 80.0 + 17.0, 1e-6);
    CHECK_NEAR(r[1], 60.0 - 9.0, 1e-6);
    CHECK_NEAR(dist3(c.position, c.look_at), d0, 1e-12 * d0);
    /* zoom: the distance scales, the direction and look_at stay */
    sss_camera z = test_camera();
    view_zoom(&z, 0.5);
    CHECK_NEAR(dist3(z.position, z.look_at), 0.5 * d0, 1e-12 * d0);
    sss_camera s = test_camera();
    for (int k = 0; k < 3; k++) {
        CHECK_NEAR(z.look_at[k], s.look_at[k], 0.0);
        CHECK_NEAR((z.position[k] - z.look_at[k]) * 2.0, s.position[k] - s.look_at[k], 1e-12 * d0);
    }
    view_zoom(&z, -1.0); /* ignored */
    view_zoom(&z, 0.0);
    CHECK_NEAR(dist3(z.position, z.look_at), 0.5 * d0, 1e-12 * d0);
}

static void test_light(void)
{
    const double pivot[3] = {0.5, 1.0, -0.5};
    sss_light L;
    memset(&L, 0, sizeof L);
    L.type = SSS_LIGHT_POINT;
    double p0[3] = {3.0, 4.0, 2.0};
    memcpy(L.position, p0, sizeof p0);
    view_rotate_light_y(&L, pivot, 90.0);
    /* right-handed about +y: the offset (x, z) = (2.5, 2.5) goes to (z, -x) = (2.5, -2.5) */
    CHECK_NEAR(L.position[0], pivot[0] + 2.5, 1e-12);
    CHECK_NEAR(L.position[1], 4.0, 1e-12);
    CHECK_NEAR(L.position[2], pivot[2] - 2.5, 1e-12);
    for (int i = 0; i < 3; i++) view_rotate_light_y(&L, pivot, 90.0);
    for (int k = 0; k < 3; k++) CHECK_NEAR(L.position[k], p0[k], 1e-12);

    /* an area light: centre moves, the edges turn, the emitting normal u x v turns with them */
    memset(&L, 0, sizeof L);
    L.type = SSS_LIGHT_AREA;
    double c0[3] = {-1.0, 1.8, 0.5}, u0[3] = {0.5, 0, 0}, v0[3] = {0, 0, 0.5};
    memcpy(L.center, c0, sizeof c0);
    memcpy(L.u, u0, sizeof u0);
    memcpy(L.v, v0, sizeof v0);
    view_rotate_light_y(&L, pivot, 30.0);
    CHECK_NEAR(hypot(L.center[0] - pivot[0], L.center[2] - pivot[2]), hypot(c0[0] - pivot[0], c0[2] - pivot[2]), 1e-12);
    CHECK_NEAR(L.center[1], c0[1], 1e-12);
    double n[3] = {L.u[1] * L.v[2] - L.u[2] * L.v[1], L.u[2] * L.v[0] - L.u[0] * L.v[2], L.u[0] * L.v[1] - L.u[1] * L.v[0]};
    CHECK_NEAR(n[0], 0.0, 1e-12); /* u x v = (0, -0.25, 0) stays vertical */
    CHECK_NEAR(n[1], -0.25, 1e-12);
    CHECK_NEAR(n[2], 0.0, 1e-12);
    CHECK_NEAR(hypot(L.u[0], L.u[2]), 0.5, 1e-12);

    /* directional: the direction turns, spot: position and target turn together */
    memset(&L, 0, sizeof L);
    L.type = SSS_LIGHT_DIRECTIONAL;
    L.direction[0] = 1.0;
    view_rotate_light_y(&L, pivot, 90.0);
    CHECK_NEAR(L.direction[0], 0.0, 1e-12);
    CHECK_NEAR(L.direction[2], -1.0, 1e-12);
    memset(&L, 0, sizeof L);
    L.type = SSS_LIGHT_SPOT;
    double sp[3] = {2, 3, 1}, st[3] = {0.5, 0, -0.5};
    memcpy(L.position, sp, sizeof sp);
    memcpy(L.look_at, st, sizeof st);
    view_rotate_light_y(&L, pivot, 45.0);
    CHECK_NEAR(dist3(L.position, L.look_at), dist3(sp, st), 1e-12);
    CHECK_NEAR(L.look_at[0], st[0], 1e-12); /* the target on the axis stays */
    CHECK_NEAR(L.look_at[2], st[2], 1e-12);
    memset(&L, 0, sizeof L);
    L.type = SSS_LIGHT_ENVIRONMENT;
    L.rotate_y = 350.0;
    view_rotate_light_y(&L, pivot, 15.0);
    CHECK_NEAR(L.rotate_y, 5.0, 1e-12);
}

int main(void)
{
    test_orbit();
    test_pan_zoom();
    test_light();
    return CHECK_DONE();
}
