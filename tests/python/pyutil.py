"""Shared by tests/python/test_*.py (run by ctest with PYTHONPATH=build/python, SSS_CLI = the sss
binary and SSS_SOURCE_DIR = the repository): the CLI to compare the module with, and small scenes."""
import os
import subprocess
import tempfile

CLI = os.environ["SSS_CLI"]
SOURCE = os.environ["SSS_SOURCE_DIR"]
SCENES = os.path.join(SOURCE, "scenes")

# Shadow maps of 64 texels, one area-light sample: frames of a few milliseconds on llvmpipe, for the
# tests that render many of them (what is compared does not depend on these sizes).
FAST = {"shadow_size": 64, "shadow_cube_size": 64, "area_samples": 1}
# maisch2020 without its splatted translucency, for comparing later frames of a renderer bit for bit:
# additive splats sum in an order that varies from frame to frame on llvmpipe (a half-float step here
# and there, tests/gl/test_gl_lights_update.c); first frames of fresh renderers agree exactly.
STABLE = dict(FAST, translucency=0)

# A sphere on a plane, 24 x 20 pixels (tests/cli/test_reference.sh's scene).
SMALL_SCENE = {
    "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "fov": 40, "width": 24, "height": 20},
    "objects": [
        {"procedural": {"shape": "sphere", "radius": 0.8, "subdivisions": 3},
         "transform": {"translate": [0, 0.8, 0]},
         "material": {"type": "subsurface", "medium": "Marble", "scale": 2.0}},
        {"procedural": {"shape": "plane", "size": 6},
         "material": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}},
    ],
    "lights": [{"type": "point", "position": [1, 3, -2], "intensity": [8, 8, 8]}],
    "render": {"exposure": 0.5},
}


def cli(*args):
    """Runs `sss ARGS...`; returns its stdout (raises with its stderr when it fails)."""
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    if done.returncode != 0:
        raise AssertionError("sss %s: exit %d: %s" % (" ".join(map(str, args)), done.returncode, done.stderr))
    return done.stdout


def tempdir():
    return tempfile.TemporaryDirectory(prefix="sss_python_")
