/* export/export_test.h — internal entry points of the export module that its tests check directly.
 * Not part of the public API: libsss.so does not export them (docs/versioning.md). */
#ifndef SSS_EXPORT_TEST_H
#define SSS_EXPORT_TEST_H

/* The PBRT-v3 light-to-world matrix (row-major 4x4) of an environment light with the given rotate_y,
 * so that PBRT's infinite-light lookup (u = phi/2pi about +z, v = theta/pi from +z) shows the
 * equirectangular map where docs/scene-format.md puts it (+y up, u = 0.5 at -z, u growing towards +x...
 * exactly as sss_reference's environment lookup). */
void export_pbrt_env_light_to_world(double rotate_y_degrees, double m[16]);

#endif
