"""Errors raise sss.Error (a RuntimeError) with the library's message naming the input and its result
code; bad input leaves no partial output; a Renderer refuses other threads and use after close; the
lights of a scene change all or not at all; a renderer takes new materials only for the same geometry."""
import json
import os
import threading
import time
import unittest

import numpy as np

import sss
from pyutil import FAST, SCENES, SMALL_SCENE, STABLE, tempdir

AREA = os.path.join(SCENES, "gl_area.json")
# sss_result codes (include/sss/common.h)
INVALID_ARGUMENT, IO, PARSE, NUMERIC = 1, 3, 4, 7


class Errors(unittest.TestCase):
    def assertError(self, code, pattern, fn, *args, **kwargs):
        with self.assertRaises(sss.Error) as caught:
            fn(*args, **kwargs)
        self.assertIsInstance(caught.exception, RuntimeError)
        self.assertEqual(caught.exception.code, code, str(caught.exception))
        self.assertRegex(str(caught.exception), pattern)
        return caught.exception

    def test_bad_scene_files(self):
        with tempdir() as tmp:
            missing = os.path.join(tmp, "missing.json")
            e = self.assertError(IO, "missing.json: cannot open", sss.Scene.load, missing)
            self.assertEqual(e.code_name, "I/O error")  # sss_result_string
            bad = os.path.join(tmp, "bad.json")
            with open(bad, "w") as f:
                f.write('{"camera": {"fov": 40,}')
            self.assertError(PARSE, r"bad.json: line 1, column \d+: malformed JSON", sss.Scene.load, bad)
        broken = dict(SMALL_SCENE, lights=[{"type": "sun"}])
        self.assertError(INVALID_ARGUMENT, r'^mine: lights\[0\].type: unknown light type "sun"',
                         sss.Scene.load, broken, name="mine")

    def test_bad_technique_and_params(self):
        scene = sss.Scene.load(AREA)
        self.assertError(INVALID_ARGUMENT, "nope.*maisch2020", sss.render, scene, technique="nope", width=16,
                         height=16)
        self.assertError(INVALID_ARGUMENT, "bogus", sss.Renderer, scene, params={"bogus": 1}, width=16, height=16)
        self.assertError(INVALID_ARGUMENT, "layers", sss.Renderer, scene, params={"layers": 1000}, width=16,
                         height=16)
        with self.assertRaises(TypeError):
            sss.Renderer(scene, params={"layers": "three"})
        with sss.Renderer(scene, params=FAST, width=16, height=16) as r:
            self.assertError(INVALID_ARGUMENT, "bogus", r.set_params, bogus=2)
            self.assertError(INVALID_ARGUMENT, "bogus", r.get_param, "bogus")
        self.assertError(INVALID_ARGUMENT, "supersample", sss.Renderer, scene, supersample=9)

    def test_bad_images_leave_no_file(self):
        with tempdir() as tmp:
            path = os.path.join(tmp, "nan.exr")
            image = np.ones((12, 12, 3), np.float32)
            image[3, 4, 1] = np.nan
            self.assertError(NUMERIC, "nan", sss.write_image, path, image)
            self.assertEqual(os.listdir(tmp), [])
            self.assertError(INVALID_ARGUMENT, "half=True needs a .exr", sss.write_image,
                             os.path.join(tmp, "x.pfm"), image, half=True)
            junk = os.path.join(tmp, "junk.pfm")
            with open(junk, "wb") as f:
                f.write(b"PF\n4 4\n-1.0\n\x00\x01")
            self.assertError(PARSE, "junk.pfm", sss.read_image, junk)
            self.assertEqual(sorted(os.listdir(tmp)), ["junk.pfm"])
        with self.assertRaises(ValueError):
            sss.write_image("/tmp/never.pfm", np.zeros((4, 4, 4), np.float32))
        self.assertError(INVALID_ARGUMENT, "(12, 13, 3)", sss.compare, np.zeros((12, 12, 3)), np.zeros((12, 13, 3)))

    def test_bad_physics_arguments(self):
        self.assertError(INVALID_ARGUMENT, "Unobtainium", sss.profile, "Unobtainium", [1.0])
        self.assertError(INVALID_ARGUMENT, "radii", sss.profile, "Marble", [1.0, -1.0])
        self.assertError(INVALID_ARGUMENT, "model", sss.lut, "Marble", model="gauss")
        self.assertError(INVALID_ARGUMENT, "size 1", sss.lut, "Marble", size=1)
        self.assertError(INVALID_ARGUMENT, "one of them", sss.kernel)
        self.assertError(INVALID_ARGUMENT, "needs artist", sss.kernel, "Marble", method="artist")
        self.assertError(INVALID_ARGUMENT, "quality", sss.reference, sss.Scene.load(SMALL_SCENE), quality="best")

    def test_renderer_thread_and_close(self):
        scene = sss.Scene.load(AREA)
        r = sss.Renderer(scene, params=FAST, width=16, height=16)
        caught = []

        def other_thread():
            try:
                r.render()
            except sss.Error as e:
                caught.append(str(e))
        t = threading.Thread(target=other_thread)
        t.start()
        t.join()
        self.assertEqual(len(caught), 1)
        self.assertIn("thread that created it", caught[0])
        self.assertEqual(r.render().shape, (16, 16, 3))
        r.close()
        r.close()  # idempotent
        self.assertError(INVALID_ARGUMENT, "closed", r.render)

    def test_render_threads_release_the_gil(self):
        """Two threads, each with its own Renderer, render at once and get the single-thread images."""
        scene = sss.Scene.load(AREA)
        expected = sss.render(scene, params=STABLE, width=24, height=24)
        results = [None, None]

        def work(i):
            with sss.Renderer(scene, params=STABLE, width=24, height=24) as r:
                results[i] = [r.render() for _ in range(3)]
        threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for frames in results:
            for f in frames:
                np.testing.assert_array_equal(f, expected)


class GilReleased(unittest.TestCase):
    def longest_pause(self, fn):
        """Runs fn on a thread while this one counts; returns (longest gap between counts, fn's time)."""
        t = threading.Thread(target=fn)
        start = last = time.perf_counter()
        longest = 0.0
        t.start()
        while t.is_alive():
            now = time.perf_counter()
            longest, last = max(longest, now - last), now
        return longest, time.perf_counter() - start

    def test_render_and_reference_let_python_run(self):
        scene = sss.Scene.load(AREA)
        small = sss.Scene.load(SMALL_SCENE)
        for name, fn in [("render", lambda: sss.render(scene, width=64, height=64)),
                         ("reference", lambda: sss.reference(small, quality="final", threads=1, spp=256))]:
            longest, total = self.longest_pause(fn)
            self.assertGreater(total, 0.1, name)  # long enough to tell
            # Holding the GIL, the whole call would be one pause; released, pauses are switch intervals
            # (plus what the loaded machine adds).
            self.assertLess(longest, 0.5 * total, name)


class Lights(unittest.TestCase):
    def test_update_lights_equals_a_new_renderer(self):
        moved = {"type": "area", "center": [0.5, 2.0, 1.0], "u": [0.4, 0, 0], "v": [0, 0, 0.4],
                 "radiance": [20, 18, 15]}
        with open(os.path.join(SCENES, "gl_area.json")) as f:
            data = json.load(f)
        self.assertEqual(data["lights"][0]["type"], "area")
        scene = sss.Scene.load(AREA)
        with sss.Renderer(scene, params=STABLE, width=32, height=32) as r:
            before = r.render()
            r.update_lights({0: moved})
            after = r.render()
        self.assertEqual(scene.lights[0]["center"], [0.5, 2.0, 1.0])
        fresh = sss.render(sss.Scene.load(dict(data, lights=[moved]), base_dir=SCENES), params=STABLE,
                           width=32, height=32)
        self.assertGreater(float(np.abs(after - before).max()), 0.01)  # the light did move
        # sss_gl_renderer_update_lights: "the next render equals a new renderer's"
        np.testing.assert_array_equal(after, fresh)

    def test_update_materials_equals_a_new_renderer(self):
        with open(AREA) as f:
            data = json.load(f)
        self.assertEqual(data["objects"][0]["material"]["medium"], "Marble")
        ketchup = json.loads(json.dumps(data))
        ketchup["objects"][0]["material"]["medium"] = "Ketchup"
        moved = json.loads(json.dumps(data))
        moved["objects"][0]["transform"]["rotate"] = [1, 0, 0, 30]
        scene = sss.Scene.load(AREA)
        other = sss.Scene.load(ketchup, base_dir=SCENES)
        for technique, params in (("maisch2020", STABLE), ("ssss", FAST)):
            with sss.Renderer(scene, technique=technique, params=params, width=32, height=32) as r:
                before = r.render()
                with self.assertRaisesRegex(sss.Error, r"objects\[0\]") as caught:
                    r.update_materials(sss.Scene.load(moved, base_dir=SCENES))
                self.assertEqual(caught.exception.code, INVALID_ARGUMENT)
                self.assertIs(r.scene, scene)  # refused: it keeps its scene
                np.testing.assert_array_equal(r.render(), before)
                r.update_materials(other)
                self.assertIs(r.scene, other)
                after = r.render()
            fresh = sss.render(other, technique=technique, params=params, width=32, height=32)
            self.assertGreater(float(np.abs(after - before).max()), 0.01, technique)  # Ketchup is not Marble
            # sss_gl_renderer_update_materials: "the next render equals a new renderer's"
            self.assertLess(float(np.abs(after - fresh).max()), 1e-5 * float(fresh.max()), technique)
        with sss.Renderer(scene, params=STABLE, width=16, height=16) as r:
            self.assertRaises(TypeError, r.update_materials, data)

    def test_lights_change_all_or_none(self):
        scene = sss.Scene.load(SMALL_SCENE)
        before = scene.lights
        with self.assertRaises(sss.Error) as caught:
            scene.set_lights([{"type": "point", "position": [0, 5, 0], "intensity": [1, 1, 1]},
                              {"type": "point", "position": [0, 5, 0], "intensity": [1, 1, 1]}])
        self.assertIn("lights[1]: no such light", str(caught.exception))
        self.assertEqual(scene.lights, before)
        for bad, pattern in [({"type": "spot"}, "keeps its type|position"),
                             ({"type": "point", "position": [0, 1, 0], "intensity": [-1, 0, 0]}, "intensity"),
                             ({"type": "point", "position": [0, 1, 0]}, "intensity")]:
            with self.assertRaisesRegex(sss.Error, r"lights\[0\].*(%s)" % pattern):
                scene.set_lights([bad])
            self.assertEqual(scene.lights, before)
        scene.set_lights([None])  # None keeps a light
        self.assertEqual(scene.lights, before)


if __name__ == "__main__":
    unittest.main(verbosity=2)
