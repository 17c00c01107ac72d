/* examples/lut.c — a measured medium's diffusion profile and its disc-integrated LUT.
 *
 *   example_lut MEDIUM OUT.exr [SIZE]      e.g.  example_lut Marble lut.exr 64
 *
 * Prints R_d(r) of the medium (PBRT-v3's photon beam diffusion profile, per mm^2) at r = 0, 0.5, ...,
 * 2 mm as TSV, then builds the pre-integrated kernel R'_d(r, A) of Maisch & Ropinski 2020 (the mean
 * of R_d over a disc of area A whose centre lies at distance r) as a SIZE x SIZE float texture and
 * writes it as OpenEXR. `sss profile MEDIUM --r 0:2:5` and `sss lut MEDIUM --size SIZE -o OUT.exr`
 * give the same numbers.
 *
 * Build: cc lut.c $(pkg-config --cflags --libs sss), or CMake: find_package(sss) and sss::sss.
 */
#include <stdio.h>
#include <stdlib.h>

#include <sss/sss.h>

int main(int argc, char **argv)
{
    char *end = NULL;
    long size = argc == 4 ? strtol(argv[3], &end, 10) : 512;
    if (argc < 3 || argc > 4 || (end && (*end != '\0' || end == argv[3])) || size < 2 || size > 8192) {
        fprintf(stderr, "usage: %s MEDIUM OUT.exr [SIZE in 2..8192]\n", argv[0]);
        return 2;
    }
    const char *medium = argv[1], *output = argv[2];

    /* Every fallible call returns an sss_result (SSS_OK = 0) and fills err with a message naming the
     * input; the library itself never prints. */
    sss_error err = {0};

    /* The medium's coefficients (mm^-1) times scale 1: one scene unit = 1 mm; eta 1.33. */
    sss_material material;
    if (sss_material_from_medium(medium, 1.0, 1.33, &material, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    /* The photon beam diffusion table (about 100 kB, so on the heap) depends on eta and g only. */
    sss_pbd_table *table = malloc(sizeof *table);
    sss_profile profile;
    if (!table || sss_pbd_table_build(material.eta, material.g, table, &err) != SSS_OK ||
        sss_profile_init(&profile, SSS_PROFILE_PBD, &material, table, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", table ? err.message : "out of memory");
        free(table);
        return 1;
    }

    printf("r\tR\tG\tB\n");
    for (int k = 0; k < 5; k++) {
        double r = 0.5 * k, rgb[3];
        sss_profile_eval_rgb(&profile, r, rgb);
        printf("%.6g\t%.6e\t%.6e\t%.6e\n", r, rgb[0], rgb[1], rgb[2]);
    }

    /* A zero-initialised description means the defaults (linear axes, the paper's r_max); only the
     * size is set here. */
    sss_lut_desc desc = {0};
    desc.size = (int)size;
    sss_lut lut;
    sss_result result = sss_lut_build(&profile, &desc, &lut, &err);
    free(table); /* the LUT no longer needs the profile */
    if (result != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    /* The texels are laid out as an RGB float image: x = r (column 0: r = 0), y = A (row 0: A = 0).
     * An EXR keeps the linear values (the exposure argument only applies to PNG). */
    sss_image image = {lut.size, lut.size, lut.texels};
    result = sss_image_write(output, &image, 0.0, &err);
    sss_lut_free(&lut);
    if (result != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    return 0;
}
