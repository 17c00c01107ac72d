"""The Python module against the sss CLI: the same scene and options give the same bits (renders,
references, LUTs, profiles, kernels), metrics agree with an independent numpy computation, and image
files round-trip exactly."""
import json
import math
import os
import unittest

import numpy as np

import sss
from pyutil import SCENES, SMALL_SCENE, STABLE, cli, tempdir

AREA = os.path.join(SCENES, "gl_area.json")


def cli_render(tmp, scene, *options):
    out = os.path.join(tmp, "cli.pfm")
    cli("render", scene, "-o", out, *options)
    return sss.read_image(out)


class RenderMatchesCli(unittest.TestCase):
    def check(self, options, **kwargs):
        with tempdir() as tmp:
            expected = cli_render(tmp, AREA, *options)
        image = sss.render(sss.Scene.load(AREA), **kwargs)
        self.assertEqual(image.dtype, np.float32)
        self.assertEqual(image.shape, expected.shape)
        # Bit-identical: both run the same library calls on a fresh context.
        np.testing.assert_array_equal(image, expected)
        self.assertGreater(float(image.max()), 0.0)  # not two black images

    def test_default_technique(self):
        self.check(["--width", 64, "--height", 48], width=64, height=48)

    def test_technique_params_supersample(self):
        self.check(["--width", 40, "--height", 32, "--technique", "local", "--param", "shadow_size=256",
                    "--supersample", 2],
                   technique="local", params={"shadow_size": 256}, width=40, height=32, supersample=2)

    def test_time_and_ssss(self):
        twist = os.path.join(SCENES, "gl_twist.json")
        with tempdir() as tmp:
            expected = cli_render(tmp, twist, "--width", 48, "--height", 48, "--technique", "ssss", "--time", 0.7)
        image = sss.render(sss.Scene.load(twist), technique="ssss", width=48, height=48, time=0.7)
        np.testing.assert_array_equal(image, expected)

    def test_renderer_keeps_state(self):
        """Frames of one Renderer equal fresh renders; set_params equals params at creation."""
        scene = sss.Scene.load(AREA)
        fresh = sss.render(scene, params=dict(STABLE, layers=2), width=32, height=32)
        with sss.Renderer(scene, params=STABLE, width=32, height=32, timings=True) as r:
            self.assertEqual(r.size, (32, 32))
            r.render()
            r.set_params({"layers": 2})
            self.assertEqual(r.get_param("layers"), 2.0)
            frames = [r.render(time=0.0) for _ in range(2)]
            t = r.timings()
        for f in frames:
            np.testing.assert_array_equal(f, fresh)
        self.assertEqual(t["method"], "glFinish + monotonic clock")
        self.assertAlmostEqual(t["total_ms"], sum(t["passes"].values()), delta=1e-6 * t["total_ms"])
        self.assertIn("gbuffer", t["passes"])


class ReferenceMatchesCli(unittest.TestCase):
    def test_draft_reference(self):
        with tempdir() as tmp:
            path = os.path.join(tmp, "small.json")
            with open(path, "w") as f:
                json.dump(SMALL_SCENE, f)
            out = os.path.join(tmp, "ref.pfm")
            cli("reference", path, "-o", out, "--quality", "draft", "--bounces", 1, "--quiet")
            expected = sss.read_image(out)
            from_file = sss.reference(sss.Scene.load(path), quality="draft", bounces=1, threads=1)
        from_dict = sss.reference(sss.Scene.load(SMALL_SCENE), quality="draft", bounces=1)
        self.assertEqual(expected.shape, (20, 24, 3))
        np.testing.assert_array_equal(from_file, expected)
        np.testing.assert_array_equal(from_dict, expected)  # the image depends on the seed, not the threads
        self.assertIsNotNone(from_dict.base)  # the library's memory, owned through a capsule

    def test_reference_size(self):
        """width/height as `sss reference --width --height`; the scene keeps its camera."""
        with tempdir() as tmp:
            path = os.path.join(tmp, "small.json")
            with open(path, "w") as f:
                json.dump(SMALL_SCENE, f)
            out = os.path.join(tmp, "ref.pfm")
            cli("reference", path, "-o", out, "--quality", "draft", "--bounces", 1, "--width", 16, "--height", 12,
                "--quiet")
            expected = sss.read_image(out)
        scene = sss.Scene.load(SMALL_SCENE)
        image = sss.reference(scene, quality="draft", bounces=1, width=16, height=12)
        self.assertEqual(image.shape, (12, 16, 3))
        np.testing.assert_array_equal(image, expected)
        self.assertEqual((scene.width, scene.height), (24, 20))
        with self.assertRaises(sss.Error):
            sss.reference(scene, quality="draft", width=-1)


class PhysicsMatchesCli(unittest.TestCase):
    def test_lut(self):
        with tempdir() as tmp:
            out = os.path.join(tmp, "lut.pfm")
            text = cli("lut", "Marble", "--size", 16, "--axes", "sqrt", "-o", out)
            expected = sss.read_image(out)
        lut = sss.lut("Marble", size=16, axes="sqrt")
        np.testing.assert_array_equal(lut["texels"], expected)
        r_max = float(text.split("r_max ")[1].split()[0])
        self.assertAlmostEqual(lut["r_max"], r_max, delta=1e-8 * r_max)
        self.assertAlmostEqual(lut["a_max"], math.pi * lut["r_max"] ** 2, delta=1e-9 * lut["a_max"])

    def test_profile(self):
        rows = [line.split("\t") for line in cli("profile", "Ketchup", "--r", "0:3:7", "--scale", 2).splitlines()[1:]]
        expected = np.array([[float(v) for v in row[1:]] for row in rows])
        r = np.array([float(row[0]) for row in rows])
        values = sss.profile("Ketchup", r, scale=2)
        self.assertEqual(values.shape, (7, 3))
        np.testing.assert_allclose(values, expected, rtol=1e-6)  # the CLI prints 7 digits
        self.assertEqual(sss.profile("Ketchup", [[0.5, 1.0]], scale=2).shape, (1, 2, 3))

    def test_kernels(self):
        lines = cli("kernel", "Marble", "--taps", 5).splitlines()
        taps = np.array([[float(v) for v in line.split("\t")] for line in lines[3:]])
        k = sss.kernel("Marble", taps=5)
        self.assertEqual(k["method"], "preintegrated")
        np.testing.assert_allclose(k["offsets"], taps[:, 0], rtol=1e-8)
        np.testing.assert_allclose(k["weights"], taps[:, 1:], rtol=1e-8)
        np.testing.assert_allclose(k["weights"].sum(axis=0), 1.0, rtol=1e-6)  # energy: sum to 1 per channel
        svd = sss.kernel("Marble", method="svd", rank=2, grid=16)
        self.assertEqual(svd["vectors"].shape, (2, 3, 16))
        self.assertEqual(svd["singular_values"].shape, (3, 16))
        self.assertTrue(np.all(np.diff(svd["singular_values"], axis=1) <= 0))  # descending
        art = sss.kernel(artist="production", taps=5)
        np.testing.assert_allclose(art["weights"].sum(axis=0), 1.0, rtol=1e-6)

    def test_techniques(self):
        names = [line.split()[0] for line in cli("techniques").splitlines() if line and not line[0].isspace()]
        techniques = sss.techniques()
        self.assertEqual([t["name"] for t in techniques], names)
        maisch = techniques[0]
        layers = [p for p in maisch["params"] if p["name"] == "layers"][0]
        self.assertEqual((layers["type"], layers["default"], layers["min"], layers["max"]), ("int", 10, 0, 64))
        self.assertIn("shadow_size", [p["name"] for p in sss.shared_params()])


class ImagesAndMetrics(unittest.TestCase):
    def setUp(self):
        rng = np.random.default_rng(7)
        self.a = rng.uniform(0, 1.2, (24, 32, 3)).astype(np.float32)
        self.b = np.clip(self.a + rng.normal(0, 0.05, self.a.shape), 0, None).astype(np.float32)

    def test_compare_against_numpy(self):
        m = sss.compare(self.a, self.b)

        def srgb8(x):  # sss_image_to_srgb8 at exposure 0: PBRT's float sRGB and rounding
            x = np.clip(x.astype(np.float32), 0, 1)
            s = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, np.float32(1 / 2.4)) - 0.055)
            return np.clip(np.round(255 * s), 0, 255)

        d = srgb8(self.a) - srgb8(self.b)
        rmse = math.sqrt(float(np.mean(d * d)))
        self.assertAlmostEqual(m["rmse"], rmse, delta=1e-7 * rmse)  # the library sums in float
        self.assertEqual(m["max_abs"], float(np.abs(d).max()))
        self.assertAlmostEqual(m["psnr"], 20 * math.log10(255 / rmse), delta=1e-6)
        self.assertAlmostEqual(m["dssim"], (1 - m["ssim"]) / 2, delta=1e-12)
        same = sss.compare(self.a, self.a.copy())
        self.assertEqual((same["dssim"], same["rmse"], same["psnr"], same["flip"]), (0.0, 0.0, math.inf, 0.0))
        with_map = sss.compare(self.a, self.b, dssim_map=True)
        self.assertEqual(with_map["dssim_map"].shape, self.a.shape)

    def test_flip_map(self):
        """The FLIP map's mean is the FLIP value (its definition), one value per pixel in [0, 1]."""
        m = sss.compare(self.a, self.b, flip_map=True, dssim_map=True)
        fm = m["flip_map"]
        self.assertEqual(fm.shape, self.a.shape)
        np.testing.assert_array_equal(fm[..., 0], fm[..., 2])
        self.assertTrue(0.0 <= float(fm.min()) and float(fm.max()) <= 1.0)
        self.assertAlmostEqual(float(np.mean(fm[..., 0], dtype=np.float64)), m["flip"], delta=1e-6)
        self.assertIn("dssim_map", m)

    def test_to_srgb(self):
        """to_srgb is the sRGB OETF of the clamped, exposed image, rounded to 8 bits (IEC 61966-2-1)."""
        x = np.array([[[0.0, 0.002, 0.0031308], [0.18, 0.5, 1.0], [2.0, -1.0, 0.75]]], dtype=np.float32)
        got = sss.to_srgb(x, exposure=1.0)
        self.assertEqual(got.dtype, np.uint8)
        self.assertEqual(got.shape, x.shape)
        v = np.clip(x.astype(np.float64) * 2.0, 0, 1)
        want = np.round(255 * np.where(v <= 0.0031308, 12.92 * v, 1.055 * v ** (1 / 2.4) - 0.055))
        self.assertLessEqual(int(np.abs(got.astype(int) - want.astype(int)).max()), 1)
        self.assertEqual(got[0, 1, 2], 255)

    def test_size_mismatch_names_numpy_shapes(self):
        with self.assertRaises(sss.Error) as e:
            sss.compare(self.a, self.a[:20])
        self.assertIn("(24, 32, 3)", str(e.exception))
        self.assertIn("(20, 32, 3)", str(e.exception))

    def test_compare_matches_cli(self):
        with tempdir() as tmp:
            pa, pb = os.path.join(tmp, "a.exr"), os.path.join(tmp, "b.exr")
            sss.write_image(pa, self.a)
            sss.write_image(pb, self.b)
            fields = dict(kv.split("=") for kv in cli("compare", pa, pb).split())
        m = sss.compare(self.a, self.b)
        self.assertAlmostEqual(m["dssim"], float(fields["dssim"]), delta=1e-6)
        self.assertAlmostEqual(m["rmse"], float(fields["rmse"]), delta=1e-4)
        self.assertAlmostEqual(m["flip"], float(fields["flip"]), delta=1e-6)

    def test_round_trips(self):
        with tempdir() as tmp:
            for ext in ("pfm", "exr"):
                path = os.path.join(tmp, "x." + ext)
                sss.write_image(path, self.a)
                np.testing.assert_array_equal(sss.read_image(path), self.a)
            half = os.path.join(tmp, "h.exr")
            sss.write_image(half, self.a, half=True)
            np.testing.assert_allclose(sss.read_image(half), self.a, rtol=2 ** -11)
            # a strided float64 view is converted, not misread
            wide = np.zeros((24, 64, 3))
            wide[:, ::2] = self.a
            path = os.path.join(tmp, "v.pfm")
            sss.write_image(path, wide[:, ::2])
            np.testing.assert_array_equal(sss.read_image(path), self.a)
            png = os.path.join(tmp, "x.png")
            sss.write_image(png, self.a, exposure=0.0)
            self.assertEqual(sss.read_image(png).shape, self.a.shape)


if __name__ == "__main__":
    unittest.main(verbosity=2)
