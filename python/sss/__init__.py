"""sss: real-time subsurface scattering and its CPU ground truth, from Python (docs/python.md).

Images are numpy float32 arrays of shape (height, width, 3), linear RGB, top row first. Every error of
the library raises sss.Error (a RuntimeError) carrying its message, which names the input, and its
result code (.code, .code_name). Renders and references release the GIL.

    import sss
    scene = sss.Scene.load("scenes/dragon.json")
    image = sss.render(scene, technique="maisch2020", params={"layers": 3})
    truth = sss.reference(scene, quality="draft")
    print(sss.compare(image, truth))   # {'ssim': ..., 'dssim': ..., 'psnr': ..., 'rmse': ..., 'max_abs': ...}
"""
import json as _json
import os as _os

from . import _sss
from ._sss import (Error, compare, kernel, lut, media, read_image, reference, shared_params, techniques,
                   to_srgb, version, write_image)

__all__ = ["Error", "Scene", "Renderer", "render", "reference", "compare", "profile", "lut", "kernel",
           "techniques", "shared_params", "media", "read_image", "write_image", "to_srgb", "version"]


class Scene(_sss.Scene):
    """A loaded scene (docs/scene-format.md). Create it with Scene.load."""

    @classmethod
    def load(cls, source, base_dir=None, name=None):
        """Loads a scene file (path) or a scene given as a dict of the scene format.

        For a dict, relative paths (meshes, textures, maps) are resolved against base_dir (default:
        the current folder), and name (default "scene") names it in error messages."""
        if isinstance(source, dict):
            text = _json.dumps(source, allow_nan=False)
            return cls._parse(text, _os.fspath(base_dir) if base_dir is not None else ".", name or "scene")
        if base_dir is not None or name is not None:
            raise TypeError("Scene.load: base_dir and name are for a scene given as a dict")
        return cls._load(source)

    def set_lights(self, lights):
        """Changes lights in place: lights is {index: light dict} or a list with one entry per light
        (None keeps it). A light keeps its type (and an environment light its file, which may be left
        out). All change or none: the first bad field raises sss.Error naming lights[i].field."""
        self._set_lights(_light_pairs(lights))

    def __repr__(self):
        return "<sss.Scene %r %dx%d, %d objects, %d lights>" % (self.name, self.width, self.height,
                                                              self.object_count, len(self.lights))


def _light_pairs(lights):
    items = lights.items() if isinstance(lights, dict) else enumerate(lights)
    return [(int(i), l if isinstance(l, str) else _json.dumps(l, allow_nan=False))
            for i, l in items if l is not None]


class Renderer(_sss.Renderer):
    """Renderer(scene, technique=None, params=None, width=0, height=0, supersample=1, timings=False, data=None)

    A real-time renderer on its own headless GL context, keeping its GL state (programs, shadow maps,
    LUTs, targets) across frames. technique None: the scene's render.technique; width/height 0: the
    camera's; params: {name: value} of the technique's or the shared parameters (sss.techniques(),
    sss.shared_params()); data: a technique's precomputed file (sam: a .sam file). Use it on the thread
    that created it; close() (or a with block) frees the GL context at once."""

    def update_lights(self, lights):
        """Moves, turns or recolours lights without rebuilding anything (sss_gl_renderer_update_lights):
        lights as for Scene.set_lights. The scene's lights change too (other renderers of this scene
        keep what they had until their own update_lights; references see the new lights)."""
        self._update_lights(_light_pairs(lights))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def render(scene, technique=None, params=None, width=0, height=0, supersample=1, time=0.0, data=None):
    """One frame of a real-time technique as `sss render` makes it: a fresh renderer, one frame at
    time, the linear image (float32 H x W x 3). For several frames keep a Renderer."""
    with Renderer(scene, technique=technique, params=params, width=width or 0, height=height or 0,
                  supersample=supersample, data=data) as r:
        return r.render(time=time)


def profile(medium, r, scale=1.0, eta=1.33, model="pbd"):
    """R_d(r) of a measured medium (as `sss profile`): an array of shape r.shape + (3,), float64,
    per scene unit^2 before the 1/pi and Fresnel factors (docs/physics.md §2.2); model "pbd" or "dipole"."""
    import numpy
    radii = numpy.asarray(r, dtype=numpy.float64)
    values = _sss.profile(medium, radii.ravel(), scale=scale, eta=eta, model=model)
    return values.reshape(radii.shape + (3,))
