/* gl/textures.c — albedo textures of subsurface materials (decoded by the scene loader) as layers of
 * one 2D array texture.
 * Layers share one size (the largest, at most 2048), so smaller images are resampled bilinearly.
 * Images are stored top row first; texture coordinates have v = 0 at the bottom (OBJ/PLY convention),
 * so rows are flipped on upload. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/core/gl_base.h"

#define MAX_ALBEDO_SIZE 2048

static void sample_bilinear(const sss_image *img, double x, double y, float out[3])
{
    /* x, y in pixel units with pixel centres at +0.5 */
    x -= 0.5;
    y -= 0.5;
    int x0 = (int)floor(x), y0 = (int)floor(y);
    double fx = x - x0, fy = y - y0;
    for (int c = 0; c < 3; c++) out[c] = 0.0f;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            int xi = x0 + i, yj = y0 + j;
            xi = xi < 0 ? 0 : xi >= img->width ? img->width - 1 : xi;
            yj = yj < 0 ? 0 : yj >= img->height ? img->height - 1 : yj;
            double w = (i ? fx : 1.0 - fx) * (j ? fy : 1.0 - fy);
            const float *p = img->pixels + 3 * ((size_t)yj * (size_t)img->width + (size_t)xi);
            for (int c = 0; c < 3; c++) out[c] += (float)(w * p[c]);
        }
}

sss_result gl_albedo_upload(gl_scene *gs, const sss_scene_texture *textures, size_t count, sss_error *err)
{
    if (count == 0) {
        glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &gs->albedo_array);
        glTextureStorage3D(gs->albedo_array, 1, GL_RGBA16F, 1, 1, 1);
        float white[4] = {1, 1, 1, 1};
        glTextureSubImage3D(gs->albedo_array, 0, 0, 0, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, white);
        gs->texture_bytes += 8;
        return SSS_OK;
    }
    int size = 1;
    for (size_t i = 0; i < count; i++) {
        if (!textures[i].image.pixels)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: texture not decoded (scene loaded without meshes)",
                                 textures[i].path);
        if (textures[i].image.width > size) size = textures[i].image.width;
        if (textures[i].image.height > size) size = textures[i].image.height;
    }
    if (size > MAX_ALBEDO_SIZE) size = MAX_ALBEDO_SIZE;
    float *layer = malloc((size_t)size * (size_t)size * 4 * sizeof(float));
    if (!layer) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (albedo textures)");
    int levels = gl_mip_levels(size, size);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &gs->albedo_array);
    glTextureStorage3D(gs->albedo_array, levels, GL_RGBA16F, size, size, (GLsizei)count);
    glTextureParameteri(gs->albedo_array, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(gs->albedo_array, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(gs->albedo_array, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(gs->albedo_array, GL_TEXTURE_WRAP_T, GL_REPEAT);
    for (size_t i = 0; i < count; i++) {
        const sss_image *im = &textures[i].image;
        for (int y = 0; y < size; y++)
            for (int x = 0; x < size; x++) {
                float c[3];
                /* GL row y (from the bottom) samples image row from the top */
                sample_bilinear(im, (x + 0.5) * im->width / size, (size - y - 0.5) * im->height / size, c);
                float *d = layer + 4 * ((size_t)y * (size_t)size + (size_t)x);
                for (int k = 0; k < 3; k++) d[k] = c[k] < 0.0f ? 0.0f : c[k];
                d[3] = 1.0f;
            }
        glTextureSubImage3D(gs->albedo_array, 0, 0, 0, (GLint)i, size, size, 1, GL_RGBA, GL_FLOAT, layer);
    }
    glGenerateTextureMipmap(gs->albedo_array);
    gs->texture_bytes += (size_t)size * size * 8 * count * 4 / 3;
    free(layer);
    return SSS_OK;
}
