/* Reference renderer, building blocks: the tabulated split profile against the physics module and
 * independent quadratures, the hierarchical sum against brute force, the environment-map and spot
 * conventions. */
#include "ref_test_util.h"

#include "reference/ref_internal.h"

/* Independent midpoint quadrature of int_a^b S_c(r) 2 pi r dr in log r (physics module's S_r). */
static double ring_integral(const sss_profile *p, int c, double a, double b, int n)
{
    double la = log(a), lb = log(b), sum = 0.0;
    for (int i = 0; i < n; i++) {
        double r = exp(la + (lb - la) * (i + 0.5) / n);
        sum += sss_profile_eval(p, c, r) * 2.0 * T_PI * r * r * (lb - la) / n;
    }
    return sum;
}

static void check_profile(const sss_reference_object *obj, double r0, const char *label)
{
    ref_profile_source src;
    ref_profile prof;
    sss_error err;
    CHECK(ref_profile_source_init(&src, obj, &err) == SSS_OK);
    CHECK(ref_profile_build(&prof, &src, r0, 1e9, &err) == SSS_OK);
    sss_profile phys;
    sss_profile_model model = obj->profile == SSS_SCENE_PROFILE_DIPOLE ? SSS_PROFILE_DIPOLE : SSS_PROFILE_PBD;
    CHECK(sss_profile_init(&phys, model, &obj->optical, obj->table, &err) == SSS_OK);
    /* Lookups match S_r at random radii between R0 and the cut (linear interpolation on a grid of
     * 256 steps per octave), where the value matters (> 1e-5 of S(R0)). */
    ref_rng rng;
    ref_rng_seed(&rng, 1, 2, 3);
    double worst = 0.0;
    for (int k = 0; k < 5000; k++) {
        double r = r0 * pow(prof.r_cut / r0, ref_rng_uniform(&rng));
        float s[3];
        ref_profile_lookup(&prof, (float)r, s, NULL);
        for (int c = 0; c < 3; c++) {
            double e = sss_profile_eval(&phys, c, r);
            if (e < 1e-5 * prof.s0[c]) continue;
            double rel = fabs(s[c] - e) / e;
            if (rel > worst) worst = rel;
        }
    }
    CHECK_MSG(worst < 2e-3, "%s: worst relative lookup error %g", label, worst);
    /* Below R0 the lookup is flat at S(R0); beyond the cut it is zero. */
    float s[3];
    ref_profile_lookup(&prof, (float)(0.3 * r0), s, NULL);
    CHECK_REL(s[1], sss_profile_eval(&phys, 1, r0), 1e-5);
    ref_profile_lookup(&prof, prof.r_cut * 1.01f, s, NULL);
    CHECK(s[0] == 0.0f && s[1] == 0.0f && s[2] == 0.0f);
    for (int c = 0; c < 3; c++) {
        /* Near part: int_0^R0 (S - S(R0)) 2 pi r dr, here by a midpoint rule in r^2 (area). */
        double near = 0.0;
        int n = 40000;
        for (int i = 0; i < n; i++) {
            double a = r0 * r0 * (i + 0.5) / n, r = sqrt(a);
            near += (sss_profile_eval(&phys, c, r) - sss_profile_eval(&phys, c, r0)) * T_PI * r0 * r0 / n;
        }
        CHECK_MSG(fabs(prof.near[c] - near) <= 2e-3 * fabs(near) + 1e-9 * sss_profile_total(&phys, c),
                  "%s: near[%d] %g vs %g", label, c, prof.near[c], near);
        /* Near + flat core + the rest of the plane = the physics module's plane integral. */
        double rest = ring_integral(&phys, c, r0, fmax(prof.r_cut, 1e4 * r0), 100000);
        double whole = prof.near[c] + T_PI * r0 * r0 * prof.s0[c] + rest;
        CHECK_MSG(fabs(whole - sss_profile_total(&phys, c)) < 2e-3 * sss_profile_total(&phys, c),
                  "%s: channel %d: near + far %g vs total %g", label, c, whole, sss_profile_total(&phys, c));
    }
    ref_profile_free(&prof);
}

static void test_profiles(void)
{
    sss_material marble;
    sss_error err;
    CHECK(sss_material_from_medium("Marble", 1.0, 1.33, &marble, &err) == SSS_OK);
    sss_pbd_table *table;
    sss_reference_object o = object_subsurface(NULL, &marble, &table);
    check_profile(&o, 0.01, "marble pbd R0 0.01");
    check_profile(&o, 0.3, "marble pbd R0 0.3");
    sss_material ketchup;
    CHECK(sss_material_from_medium("Ketchup", 1.0, 1.33, &ketchup, &err) == SSS_OK);
    o.optical = ketchup;
    check_profile(&o, 0.02, "ketchup pbd");
    o.optical = marble;
    o.profile = SSS_SCENE_PROFILE_DIPOLE;
    check_profile(&o, 0.05, "marble dipole");
    free(table);
}

/* Hierarchical sum vs brute force over samples on a sphere and a plane with random T A. */
static void test_tree(void)
{
    sss_material m = material_coeffs(0.02, 0.05, 0.1, 2.0, 2.5, 3.0, 1.4);
    sss_pbd_table *table;
    sss_reference_object o = object_subsurface(NULL, &m, &table);
    ref_profile_source src;
    ref_profile prof;
    sss_error err;
    CHECK(ref_profile_source_init(&src, &o, &err) == SSS_OK);
    CHECK(ref_profile_build(&prof, &src, 0.02, 20.0, &err) == SSS_OK);
    ref_tree tree;
    memset(&tree, 0, sizeof tree);
    size_t n = 100000;
    tree.points = malloc(sizeof(ref_point) * n);
    tree.point_count = n;
    ref_rng rng;
    ref_rng_seed(&rng, 7, 7, 7);
    for (size_t i = 0; i < n; i++) {
        ref_point *p = &tree.points[i];
        if (i % 2) {
            double z = 2.0 * ref_rng_uniform(&rng) - 1.0, ph = 2.0 * T_PI * ref_rng_uniform(&rng);
            double s = sqrt(1.0 - z * z);
            p->p[0] = (float)(2.0 * s * cos(ph)), p->p[1] = (float)(2.0 * z), p->p[2] = (float)(2.0 * s * sin(ph));
        } else {
            p->p[0] = (float)(8.0 * ref_rng_uniform(&rng) - 4.0), p->p[1] = -2.5f;
            p->p[2] = (float)(8.0 * ref_rng_uniform(&rng) - 4.0);
        }
        /* Lit where x > 0 (a shadow edge), random strength per channel. */
        for (int c = 0; c < 3; c++) p->ta[c] = p->p[0] > 0.0f ? (float)(1e-4 * (0.5 + ref_rng_uniform(&rng))) : 0.0f;
    }
    CHECK(ref_tree_build(&tree, &err) == SSS_OK);
    CHECK(tree.point_count == n);
    CHECK(tree.leaf_count > 0 && tree.node_count == 2 * tree.leaf_count - 1);
    double worst = 0.0;
    uint64_t visits_tree = 0, visits_brute = 0;
    for (int k = 0; k < 100; k++) {
        const ref_point *q = &tree.points[(size_t)(ref_rng_uniform(&rng) * n)];
        double a[3], b[3];
        ref_tree_sum(&tree, &prof, q->p, NULL, a, &visits_tree);
        ref_brute_sum(&tree, &prof, q->p, b, &visits_brute);
        double ma = fmax(b[0], fmax(b[1], b[2]));
        for (int c = 0; c < 3; c++)
            if (b[c] > 1e-3 * ma && b[c] > 0.0) worst = fmax(worst, fabs(a[c] - b[c]) / b[c]);
    }
    CHECK_MSG(worst < 5e-3, "tree vs brute: worst relative difference %g", worst);
    CHECK_MSG(visits_tree * 5 < visits_brute, "tree visits %llu vs brute %llu", (unsigned long long)visits_tree,
              (unsigned long long)visits_brute);
    ref_tree_free(&tree);
    ref_profile_free(&prof);
    free(table);
}

static void test_env_convention(void)
{
    double d[3], u, v;
    sss_reference_env_direction(0.5, 0.5, 0.0, d); /* docs/scene-format.md: u = 0.5 at -z */
    CHECK_NEAR(d[0], 0.0, 1e-12);
    CHECK_NEAR(d[1], 0.0, 1e-12);
    CHECK_NEAR(d[2], -1.0, 1e-12);
    sss_reference_env_direction(0.3, 0.0, 0.0, d); /* +y up: the top row */
    CHECK_NEAR(d[1], 1.0, 1e-12);
    sss_reference_env_direction(0.75, 0.5, 0.0, d); /* not mirrored: right of -z is +x */
    CHECK_NEAR(d[0], 1.0, 1e-12);
    sss_reference_env_direction(0.5, 0.5, 90.0, d); /* right-handed about +y: -z turns to -x */
    CHECK_NEAR(d[0], -1.0, 1e-12);
    CHECK_NEAR(d[2], 0.0, 1e-12);
    for (int k = 0; k < 100; k++) {
        double uu = (k * 0.6180339887) - floor(k * 0.6180339887), vv = 0.01 + 0.98 * ((k * 0.37) - floor(k * 0.37));
        double rot = 17.0 * k - 300.0;
        sss_reference_env_direction(uu, vv, rot, d);
        CHECK_NEAR(v3_len(d), 1.0, 1e-12);
        sss_reference_env_uv(d, rot, &u, &v);
        double du = fabs(u - uu);
        CHECK(fmin(du, 1.0 - du) < 1e-9 && fabs(v - vv) < 1e-9);
    }
}

static void test_spot(void)
{
    /* PBRT-v3: 1 inside cone_angle - cone_delta, 0 outside cone_angle, delta^4 between. */
    CHECK(sss_reference_spot_falloff(30, 10, cos(10 * T_PI / 180)) == 1.0);
    CHECK(sss_reference_spot_falloff(30, 10, cos(31 * T_PI / 180)) == 0.0);
    double ct = cos(30 * T_PI / 180), cs = cos(20 * T_PI / 180);
    CHECK_NEAR(sss_reference_spot_falloff(30, 10, 0.5 * (ct + cs)), 1.0 / 16.0, 1e-12);
    double prev = 0.0;
    for (int k = 0; k <= 100; k++) {
        double f = sss_reference_spot_falloff(30, 10, ct + (cs - ct) * k / 100.0);
        CHECK(f >= prev);
        prev = f;
    }
    CHECK(sss_reference_spot_falloff(30, 0, cos(29.9 * T_PI / 180)) == 1.0);
}

int main(void)
{
    test_profiles();
    test_tree();
    test_env_convention();
    test_spot();
    return CHECK_DONE();
}
