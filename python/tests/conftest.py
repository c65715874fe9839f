"""The talus module's tests run from CTest (python/CMakeLists.txt), which puts the build tree's
package on PYTHONPATH and names the talus program in TALUS_EXE."""
import os
import shutil

import pytest


@pytest.fixture
def talus_exe():
    exe = os.environ.get("TALUS_EXE") or shutil.which("talus")
    if not exe:
        pytest.skip("TALUS_EXE is not set: run these tests through ctest")
    return exe
