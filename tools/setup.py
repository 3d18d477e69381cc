"""Build step of the rockdem Python package (the project's metadata is in pyproject.toml).

`pip install ./tools` (or of the source distribution) builds the C library and the program with
the repository's own Makefile (no second build description to keep in step) and puts
librockdem.so and bin/rockdem inside the package, where rockdem._lib and rockdem.program()
look first. The C sources are the repository's (the folder above tools/) or, in a source
distribution, the copy under _csrc/ that `python -m build --sdist` puts there. Needs a C
compiler, make and the -dev packages of tools/install-deps.sh (Debian 12: build-essential
pkg-config libhdf5-dev libgsl-dev libsundials-dev libqhull-dev)."""
import os
import shutil
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.command.sdist import sdist
from setuptools.dist import Distribution

HERE = os.path.dirname(os.path.abspath(__file__))
C_TREE = ("Makefile", "src", "include", os.path.join("tools", "install-deps.sh"))
DEV_PACKAGES = "build-essential pkg-config libhdf5-dev libgsl-dev libsundials-dev libqhull-dev"
# headers the library includes from the -dev packages (a missing one is named before make runs)
HEADERS = ("hdf5/serial/hdf5.h", "gsl/gsl_math.h", "cvode/cvode.h", "libqhull_r/libqhull_r.h")


def c_sources():
    """The folder holding the Makefile, src/ and include/: _csrc/ in a source distribution, else
    the repository around tools/."""
    for d in (os.path.join(HERE, "_csrc"), os.path.dirname(HERE)):
        if all(os.path.exists(os.path.join(d, p)) for p in C_TREE):
            return d
    raise SystemExit("rockdem: the C sources (Makefile, src/, include/) are neither in _csrc/ "
                     "nor in the folder above tools/: build from the repository or its sdist")


def check_prerequisites():
    """A clear error, before compiling, when a tool or a -dev package is missing."""
    for tool in ("make", os.environ.get("CC", "cc")):
        if shutil.which(tool) is None:
            raise SystemExit("rockdem: '%s' not found; install a C toolchain (Debian: %s)"
                             % (tool, DEV_PACKAGES))
    missing = [h for h in HEADERS if not os.path.exists(os.path.join("/usr/include", h))]
    if missing:
        raise SystemExit("rockdem: missing C headers %s; install the -dev packages (Debian: "
                         "sudo apt-get install %s, or sudo bash tools/install-deps.sh)"
                         % (", ".join(missing), DEV_PACKAGES))


class BuildWithMake(build_py):
    """build_py, then `make` of librockdem.so and bin/rockdem into the package."""

    def run(self):
        super().run()
        check_prerequisites()
        src = c_sources()
        out = os.path.abspath(os.path.join(self.get_finalized_command("build").build_temp,
                                           "rockdem-c"))
        os.makedirs(out, exist_ok=True)
        # the Makefile's prerequisite check would install missing Debian packages with sudo;
        # check_prerequisites has checked them instead
        stamp = os.path.join(out, ".deps-ok")
        open(stamp, "a").close()
        os.utime(stamp)
        jobs = str(len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else 2)
        lib, prog = os.path.join(out, "librockdem.so"), os.path.join(out, "bin", "rockdem")
        subprocess.check_call(["make", "-C", src, "-j", jobs, "BUILD=" + out,
                               "BIN=" + os.path.join(out, "bin"), lib, prog])
        dest = os.path.join(self.build_lib, "rockdem")
        os.makedirs(os.path.join(dest, "bin"), exist_ok=True)
        shutil.copy2(lib, os.path.join(dest, "librockdem.so"))
        shutil.copy2(prog, os.path.join(dest, "bin", "rockdem"))


class SdistWithSources(sdist):
    """The source distribution carries the C sources under _csrc/ (they live above tools/)."""

    def make_release_tree(self, base_dir, files):
        super().make_release_tree(base_dir, files)
        src = c_sources()
        for p in C_TREE:
            s, d = os.path.join(src, p), os.path.join(base_dir, "_csrc", p)
            os.makedirs(os.path.dirname(d), exist_ok=True)
            if os.path.isdir(s):
                shutil.copytree(s, d, dirs_exist_ok=True)
            else:
                shutil.copy2(s, d)


class BinaryDistribution(Distribution):
    """The wheel holds a compiled library: tag it for the platform, not as pure Python."""

    def has_ext_modules(self):
        return True


setup(cmdclass={"build_py": BuildWithMake, "sdist": SdistWithSources},
      distclass=BinaryDistribution)
