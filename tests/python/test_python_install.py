"""`cmake --install` puts the module into the Python's site folder under the prefix, where it finds the
installed libsss.so.0 (RUNPATH relative to itself, not the build tree) and renders."""
import os
import subprocess
import sys
import unittest

from pyutil import SCENES, tempdir

BUILD = os.environ["SSS_BUILD_DIR"]


class Install(unittest.TestCase):
    def test_installed_module_imports_and_renders(self):
        with tempdir() as prefix:
            subprocess.run(["cmake", "--install", BUILD, "--prefix", prefix], check=True, capture_output=True)
            sites = [os.path.join(root) for root, dirs, files in os.walk(prefix)
                     if os.path.basename(root) == "sss" and "__init__.py" in files]
            self.assertEqual(len(sites), 1, sites)
            site = os.path.dirname(sites[0])
            # docs/python.md: a prefix off Debian's sys.path gets lib/python3.X/site-packages
            self.assertEqual(os.path.relpath(site, prefix), "lib/python%d.%d/site-packages" % sys.version_info[:2])
            code = ("import sss, sys; s = sss.Scene.load(sys.argv[1]); "
                    "img = sss.render(s, technique='local', params={'shadow_size': 64}, width=16, height=16); "
                    "print(sss.__file__, img.shape, float(img.max()) > 0)")
            env = dict(os.environ, PYTHONPATH=site, LD_LIBRARY_PATH="")
            scene = os.path.join(SCENES, "gl_area.json")
            out = subprocess.run([sys.executable, "-c", code, scene], env=env, cwd=prefix, check=True,
                                 capture_output=True, text=True).stdout.split()
            self.assertTrue(out[0].startswith(prefix), out)
            self.assertEqual(out[1:], ["(16,", "16,", "3)", "True"])
            # the extension's libsss is the installed one, not the build tree's
            maps = subprocess.run([sys.executable, "-c", "import sss._sss; print(open('/proc/self/maps').read())"],
                                  env=env, cwd=prefix, check=True, capture_output=True, text=True).stdout
            libs = {line.split()[-1] for line in maps.splitlines() if "libsss.so" in line}
            self.assertEqual(len(libs), 1, libs)
            self.assertTrue(libs.pop().startswith(os.path.realpath(prefix)))

    def test_system_prefix_gets_its_dist_packages(self):
        """docs/python.md: under /usr/local the module goes where Debian's python3 looks (dist-packages),
        also when the build was configured for another prefix (DESTDIR stages the install)."""
        with tempdir() as stage:
            env = dict(os.environ, DESTDIR=stage)
            subprocess.run(["cmake", "--install", BUILD, "--prefix", "/usr/local", "--component", "Unspecified"],
                           env=env, check=True, capture_output=True)
            want = os.path.join(stage, "usr/local/lib/python%d.%d/dist-packages/sss/__init__.py" % sys.version_info[:2])
            self.assertTrue(os.path.isfile(want), want)


if __name__ == "__main__":
    unittest.main(verbosity=2)
