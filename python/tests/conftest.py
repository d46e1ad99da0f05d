# SPDX-License-Identifier: MIT
"""Shared fixtures: the `calder` command and the p5.js references.

The ctest that runs these tests (python/CMakeLists.txt) sets CALDER_EXE to
the calder command it built and CALDER_REFERENCE_DIR to the p5.js
references (tests/reference in the repository, the default); run by hand,
set CALDER_EXE the same way.
"""

import os
import pathlib

import pytest

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def calder_exe() -> str:
    exe = os.environ.get("CALDER_EXE")
    if not exe or not os.access(exe, os.X_OK):
        pytest.fail("set CALDER_EXE to the calder command (build/apps/calder); got "
                    f"{exe!r}")
    return exe


@pytest.fixture(scope="session")
def reference_dir() -> pathlib.Path:
    folder = pathlib.Path(os.environ.get("CALDER_REFERENCE_DIR", REPOSITORY / "tests" / "reference"))
    if not folder.is_dir():
        pytest.fail(f"no p5.js references in {folder} (set CALDER_REFERENCE_DIR)")
    return folder
