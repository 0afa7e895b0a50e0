"""Shared fixtures: the reference data beside the repository, fastnorm-solve, an output folder.

CTest (examples/python/CMakeLists.txt) sets PYTHONPATH to the built package and names the
folders; run by hand, the defaults are the repository's ../shared and a temporary folder.
"""

import os
import pathlib

import pytest

repository = pathlib.Path(__file__).resolve().parents[3]


def _folder(variable, configured, default):
    return pathlib.Path(os.environ.get(variable) or os.environ.get(configured) or default)


def _missing(what):
    # As the C++ tests: a skip, or a failure where CI requires the data (FASTNORM_REQUIRE_SHARED).
    if os.environ.get("FASTNORM_REQUIRE_SHARED"):
        pytest.fail(f"{what} (FASTNORM_REQUIRE_SHARED is set)")
    pytest.skip(f"{what}: skipped")


@pytest.fixture(scope="session")
def peer_cases():
    """The folder of CONTACT's reference cases."""
    folder = _folder("FASTNORM_PEER_CASES", "FASTNORM_PEER_CASES_DIR", repository.parent / "shared" / "peer-cases")
    if not folder.is_dir():
        _missing(f"{folder} is absent")
    return folder


@pytest.fixture(scope="session")
def fastnorm_solve():
    """The C++ command-line solver, whose answers the module must give bit for bit."""
    path = os.environ.get("FASTNORM_SOLVE")
    if not path or not os.access(path, os.X_OK):
        pytest.skip("FASTNORM_SOLVE does not name the fastnorm-solve program (run the tests through CTest)")
    return path


@pytest.fixture
def output_dir(tmp_path):
    """Where a test writes its files: under the build tree when CTest names it, else a temporary folder."""
    configured = os.environ.get("FASTNORM_TEST_OUTPUT")
    if not configured:
        return tmp_path
    folder = pathlib.Path(configured)
    folder.mkdir(parents=True, exist_ok=True)
    return folder
