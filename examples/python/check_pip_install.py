"""CTest check that the package installs with pip from its folder (python.pip_install):
copies the sources that the build needs into WORK_DIR (pip builds in place and would
otherwise write into the source tree), installs them with pip into a fresh virtual
environment that sees Debian's NumPy, pybind11 and setuptools, and solves with the
installed module from another folder.

    check_pip_install.py SOURCE_DIR WORK_DIR
"""

import pathlib
import shutil
import subprocess
import sys


def main() -> int:
    source, work = (pathlib.Path(arg).resolve() for arg in sys.argv[1:3])
    shutil.rmtree(work, ignore_errors=True)
    tree = work / "src"
    ignore = shutil.ignore_patterns("build", "__pycache__", "*.egg-info")
    for part in ("cmake", "include", "examples"):
        shutil.copytree(source / part, tree / part, ignore=ignore)
    shutil.copy2(source / "CMakeLists.txt", tree / "CMakeLists.txt")
    venv = work / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", str(venv)], check=True)
    python = str(venv / "bin" / "python")
    subprocess.run([python, "-m", "pip", "install", "--no-build-isolation", "--no-index", "-q",
                    str(tree / "examples" / "python")], check=True)
    # From another folder, so that nothing but the installed package can be imported.
    check = (
        "import fastnorm, pathlib\n"
        "assert pathlib.Path(fastnorm.__file__).is_relative_to(pathlib.Path(r'%s')), fastnorm.__file__\n"
        "model = fastnorm.WheelsetContact(solver='elliptic', elements=20)\n"
        "found = model.equilibrium(load_n=2e5, lateral_shift_m=1e-3)\n"
        "assert found.ok, found\n"
        "print('pip-installed', fastnorm.__version__, found)\n" % venv
    )
    subprocess.run([python, "-c", check], check=True, cwd=work)
    return 0


if __name__ == "__main__":
    sys.exit(main())
