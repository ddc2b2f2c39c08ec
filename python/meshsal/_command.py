"""The `meshsal` command that `pip install` puts on PATH: runs the command-line tool built
and installed beside this package (meshsal/_bin/meshsal), with the same arguments."""
import os
import sys
from pathlib import Path


def main():
    exe = Path(__file__).resolve().parent / "_bin" / "meshsal"
    if not exe.exists():
        sys.exit(f"meshsal: the command-line tool is not installed beside the module ({exe})")
    os.execv(str(exe), [str(exe), *sys.argv[1:]])
