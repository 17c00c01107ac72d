#!/usr/bin/python3
"""tools/ssim_reference.py -- writes the committed test images of tests/image and their reference
numbers, independently of the C code under test.

  * PNG, PFM and OpenEXR files are written byte by byte here (zlib + struct), not with the project's
    writers nor with stb/OpenEXR, so the C readers are checked against an outside encoder.
  * SSIM, PSNR and RMSE come from scikit-image (Debian python3-skimage 0.19), with the settings of
    docs/physics.md §5: structural_similarity(a, b, gaussian_weights=True, sigma=1.5,
    use_sample_covariance=False, data_range=255, channel_axis=2).

Run once from the repository root with Debian's python (skimage is not in CI):
    /usr/bin/python3 tools/ssim_reference.py
and commit tests/data/images/. The images are deterministic (fixed seeds), so rerunning reproduces
the same files and numbers.
"""
import os
import struct
import sys
import zlib

import numpy as np
import scipy
import skimage
from skimage.metrics import mean_squared_error, peak_signal_noise_ratio, structural_similarity

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "images")


# ---------------------------------------------------------------- PNG (hand-made encoder)
def png_bytes(arr, color_type, bit_depth=8, palette=None):
    """arr: H x W x C uint8/uint16 array (C matching color_type), filter 0 on every row."""
    h, w = arr.shape[:2]
    dt = ">u2" if bit_depth == 16 else "u1"
    raw = b"".join(b"\x00" + arr[y].astype(dt).tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, bit_depth, color_type, 0, 0, 0))
    if palette is not None:
        out += chunk(b"PLTE", bytes(np.asarray(palette, dtype=np.uint8).ravel()))
    return out + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def write(name, data):
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data)


# ---------------------------------------------------------------- PFM (hand-made encoder)
def pfm_bytes(arr, little, scale):
    """arr: H x W x 3 or H x W float32, top row first; PFM stores the bottom row first."""
    grey = arr.ndim == 2
    head = ("Pf" if grey else "PF") + "\n%d %d\n%s\n" % (arr.shape[1], arr.shape[0], repr(-abs(scale) if little else abs(scale)))
    return head.encode() + np.ascontiguousarray(arr[::-1]).astype("<f4" if little else ">f4").tobytes()


# ---------------------------------------------------------------- OpenEXR (hand-made, uncompressed)
EXR_UINT, EXR_HALF, EXR_FLOAT = 0, 1, 2
NUMPY_TYPE = {EXR_UINT: "<u4", EXR_HALF: "<f2", EXR_FLOAT: "<f4"}


def attr(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def exr_bytes(planes, ptype, origin=(0, 0), tile=None):
    """planes: dict channel name -> H x W array; uncompressed scanline (one line per chunk) or
    tiled (one level, tile = (tw, th)) file with the data window starting at origin."""
    names = sorted(planes)
    h, w = planes[names[0]].shape
    x0, y0 = origin
    chl = b"".join(n.encode() + b"\0" + struct.pack("<iB3xii", ptype, 0, 1, 1) for n in names) + b"\0"
    box = struct.pack("<iiii", x0, y0, x0 + w - 1, y0 + h - 1)
    head = attr("channels", "chlist", chl) + attr("compression", "compression", b"\0")
    head += attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", struct.pack("<iiii", 0, 0, x0 + w + 4, y0 + h + 6))
    head += attr("lineOrder", "lineOrder", b"\0") + attr("pixelAspectRatio", "float", struct.pack("<f", 1.0))
    head += attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) + attr("screenWindowWidth", "float", struct.pack("<f", 1.0))
    blocks = []
    if tile is None:
        version = 2
        for y in range(h):
            data = b"".join(planes[n][y].astype(NUMPY_TYPE[ptype]).tobytes() for n in names)
            blocks.append(struct.pack("<ii", y0 + y, len(data)) + data)
    else:
        version = 2 | 0x200
        tw, th = tile
        head += attr("tiles", "tiledesc", struct.pack("<IIB", tw, th, 0))
        for ty in range((h + th - 1) // th):
            for tx in range((w + tw - 1) // tw):
                ys, xs = slice(ty * th, min(h, (ty + 1) * th)), slice(tx * tw, min(w, (tx + 1) * tw))
                rows = planes[names[0]][ys, xs].shape[0]
                data = b"".join(planes[n][ys, xs][r].astype(NUMPY_TYPE[ptype]).tobytes() for r in range(rows) for n in names)
                blocks.append(struct.pack("<iiiii", tx, ty, 0, 0, len(data)) + data)
    head = b"\x76\x2f\x31\x01" + struct.pack("<i", version) + head + b"\0"
    offset = len(head) + 8 * len(blocks)
    table = b""
    for b in blocks:
        table += struct.pack("<Q", offset)
        offset += len(b)
    return head + table + b"".join(blocks)


# ---------------------------------------------------------------- test images for SSIM
def base_image(w, h):
    y, x = np.mgrid[0:h, 0:w].astype(np.float64)
    r = 128 + 90 * np.sin(x / 5.0) * np.cos(y / 7.0)
    g = 40 + 3.0 * x + 1.5 * y
    b = 200 - 2.5 * y + 30 * ((x // 8 + y // 8) % 2)
    img = np.stack([r, g, b], axis=2)
    img[10:20, 30:50] = [250, 20, 60]  # a saturated block with hard edges
    return np.clip(np.rint(img), 0, 255).astype(np.uint8)


def box_blur3(img):
    p = np.pad(img.astype(np.float64), ((1, 1), (1, 1), (0, 0)), mode="edge")
    acc = sum(p[dy:dy + img.shape[0], dx:dx + img.shape[1]] for dy in range(3) for dx in range(3))
    return np.clip(np.rint(acc / 9.0), 0, 255).astype(np.uint8)


def main():
    os.makedirs(OUT, exist_ok=True)
    rng = np.random.default_rng(20240601)
    W, H = 64, 48
    base = base_image(W, H)
    noise = np.clip(base + rng.normal(0, 12, base.shape), 0, 255).round().astype(np.uint8)
    blur = box_blur3(base)
    shift = np.roll(base, 2, axis=1)
    colour = np.clip(base.astype(np.float64) * [0.9, 1.0, 1.0] + [0, 0, 20], 0, 255).round().astype(np.uint8)
    small_a = rng.integers(0, 256, (17, 23, 3), dtype=np.uint8)
    small_b = np.clip(small_a.astype(np.int64) + rng.integers(-40, 41, small_a.shape), 0, 255).astype(np.uint8)
    images = {"base.png": base, "noise.png": noise, "blur.png": blur, "shift.png": shift, "colour.png": colour,
              "small_a.png": small_a, "small_b.png": small_b}
    for name, img in images.items():
        write(name, png_bytes(img, 2))

    pairs = [("base.png", "noise.png"), ("base.png", "blur.png"), ("base.png", "shift.png"),
             ("base.png", "colour.png"), ("noise.png", "blur.png"), ("small_a.png", "small_b.png")]
    lines = ["# SSIM / PSNR / RMSE reference numbers for tests/image/test_metrics.c.",
             "# Written by tools/ssim_reference.py with scikit-image %s, scipy %s, numpy %s:" % (
                 skimage.__version__, scipy.__version__, np.__version__),
             "#   structural_similarity(a, b, gaussian_weights=True, sigma=1.5, use_sample_covariance=False,",
             "#                         data_range=255, channel_axis=2); peak_signal_noise_ratio(data_range=255)",
             "# pair A B ssim psnr rmse max_abs",
             "# map A B x y S_R S_G S_B   (full SSIM map, full=True, at border and interior pixels)"]
    for a_name, b_name in pairs:
        a, b = images[a_name], images[b_name]
        ssim, smap = structural_similarity(a, b, gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
                                           data_range=255, channel_axis=2, full=True)
        psnr = peak_signal_noise_ratio(a, b, data_range=255)
        rmse = np.sqrt(mean_squared_error(a, b))
        maxd = np.abs(a.astype(np.int64) - b.astype(np.int64)).max()
        lines.append("pair %s %s %.12f %.9f %.9f %d" % (a_name, b_name, ssim, psnr, rmse, maxd))
        h, w = a.shape[:2]
        for x, y in [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1), (2, 3), (w // 2, h // 2), (5, 5), (w - 3, h - 2)]:
            s = smap[y, x]
            lines.append("map %s %s %d %d %.12f %.12f %.12f" % (a_name, b_name, x, y, s[0], s[1], s[2]))
    write("ssim_reference.txt", ("\n".join(lines) + "\n").encode())

    # ---- format test files (values chosen exactly representable in their sample type)
    ref = ["# Pixel values of the hand-written format test files (tools/ssim_reference.py).",
           "# pixel FILE x y r g b   (x, y from the top-left corner of the image / data window)"]

    def record(name, rgb):
        for y in range(rgb.shape[0]):
            for x in range(rgb.shape[1]):
                ref.append("pixel %s %d %d %.9g %.9g %.9g" % (name, x, y, *[float(v) for v in rgb[y, x]]))

    # PNG: every 8-bit grey level once (16x16), 16-bit grey+alpha with codes 257 k, a palette image.
    grey = np.arange(256, dtype=np.uint8).reshape(16, 16)
    write("grey256.png", png_bytes(grey[:, :, None], 0))
    g16 = (np.arange(256, dtype=np.uint16) * 257).reshape(16, 16)
    alpha = rng.integers(0, 65536, (16, 16), dtype=np.uint16)
    write("grey16_alpha.png", png_bytes(np.stack([g16, alpha], axis=2), 4, bit_depth=16))
    palette = [[255, 0, 0], [0, 255, 0], [0, 0, 255], [10, 20, 30]]
    idx = np.array([[0, 1, 2, 3], [3, 2, 1, 0]], dtype=np.uint8)
    write("palette.png", png_bytes(idx[:, :, None], 3, palette=palette))
    ref.append("# PNG files hold sRGB codes: the lines below give codes, not linear values")
    record("palette.png", np.asarray(palette)[idx])

    # PFM: asymmetric RGB little-endian (scale -1) and grey big-endian with scale 2 (PBRT-v3 multiplies
    # by |scale|, so the expected values are twice the stored ones).
    y, x = np.mgrid[0:2, 0:3].astype(np.float32)
    asym = np.stack([x + 10 * y + 0.25, -(x + 1) * 0.5, np.float32(1e-3) * (y + 1) + x], axis=2).astype(np.float32)
    write("asym_le.pfm", pfm_bytes(asym, little=True, scale=1.0))
    record("asym_le.pfm", asym)
    gy, gx = np.mgrid[0:3, 0:2].astype(np.float32)
    g = (gx + 4 * gy + 0.5).astype(np.float32)
    write("grey_be.pfm", pfm_bytes(g, little=False, scale=2.0))
    record("grey_be.pfm", np.repeat((2 * g)[:, :, None], 3, axis=2))

    # OpenEXR: half scanline RGB, float tiled RGBA with an offset data window, lone Y float, uint RGB.
    hy, hx = np.mgrid[0:3, 0:5].astype(np.float32)
    hr, hg, hb = (hx + 8 * hy + 0.5), -(hx * 0.25 + hy), (hy + 1) * np.float32(0.0009765625) + 100 * hx
    rgb = np.stack([hr, hg, hb], axis=2).astype(np.float16).astype(np.float32)
    write("asym_half.exr", exr_bytes({"R": rgb[..., 0], "G": rgb[..., 1], "B": rgb[..., 2]}, EXR_HALF))
    record("asym_half.exr", rgb)
    ty, tx = np.mgrid[0:5, 0:7].astype(np.float32)
    trgb = np.stack([tx + 0.125, ty * 3.5, tx * ty - 7.0], axis=2).astype(np.float32)
    write("tiled_rgba.exr", exr_bytes({"R": trgb[..., 0], "G": trgb[..., 1], "B": trgb[..., 2],
                                       "A": np.full((5, 7), 0.5, np.float32)}, EXR_FLOAT, origin=(10, 20), tile=(3, 2)))
    record("tiled_rgba.exr", trgb)
    yy, yx = np.mgrid[0:4, 0:3].astype(np.float32)
    lum = (yx * 2 + yy * 0.75 + 1e-6).astype(np.float32)
    write("grey_y.exr", exr_bytes({"Y": lum}, EXR_FLOAT))
    record("grey_y.exr", np.repeat(lum[:, :, None], 3, axis=2))
    uy, ux = np.mgrid[0:2, 0:3]
    urgb = np.stack([ux + 1, uy * 1000, ux * uy + 70000], axis=2).astype(np.uint32)
    write("rgb_uint.exr", exr_bytes({"R": urgb[..., 0], "G": urgb[..., 1], "B": urgb[..., 2]}, EXR_UINT))
    record("rgb_uint.exr", urgb)
    write("formats_reference.txt", ("\n".join(ref) + "\n").encode())
    print("wrote", OUT)


if __name__ == "__main__":
    sys.exit(main())
