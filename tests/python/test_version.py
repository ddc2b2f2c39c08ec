# Issue 22 (5): the module's version is the project's (CMakeLists.txt), as the CLI's.
import re

import meshsal
from conftest import ROOT


def test_version_is_the_projects(cli):
    project = re.search(r"project\(meshsal VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text()).group(1)
    assert meshsal.__version__ == project
    major, minor, patch = map(int, project.split("."))
    assert meshsal.version == major * 10000 + minor * 100 + patch
    assert cli("--version").stdout == f"meshsal {project}\n"
