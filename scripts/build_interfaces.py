#!/usr/bin/env python3
"""Build a ROS 2 interface package (.msg files) into a venv that holds the Jazzy wheels.

vision_msgs is on no package registry, so ``setup_env.sh`` builds it here from its message
definitions with the rosidl generator wheels and cmake (recipe in shared/ROS_NOTES.md).
The generator wheels export cmake files that hard-code their builder's Python include and
numpy paths; those are rewritten to this interpreter's before configuring.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

BUILDER_PYTHON_INCLUDE = "/opt/python/cp311-cp311/include/python3.11"
BUILDER_NUMPY_INCLUDE = "/opt/python/cp311-cp311/lib/python3.11/site-packages/numpy/_core/include"


def venv_python_paths(python: Path) -> tuple[str, str]:
    """Return (python include dir, numpy include dir) of the venv interpreter."""
    code = "import sysconfig, numpy; print(sysconfig.get_paths()['include']); print(numpy.get_include())"
    out = subprocess.run([str(python), "-c", code], check=True, capture_output=True, text=True)
    include, numpy_include = out.stdout.split()
    return include, numpy_include


def rewrite_exported_paths(share: Path, include: str, numpy_include: str) -> int:
    """Point the generator wheels' exported cmake files at this interpreter; return files changed."""
    changed = 0
    for cmake_file in share.rglob("*.cmake"):
        text = cmake_file.read_text(errors="surrogateescape")
        if BUILDER_PYTHON_INCLUDE not in text and BUILDER_NUMPY_INCLUDE not in text:
            continue
        text = text.replace(BUILDER_NUMPY_INCLUDE, numpy_include).replace(BUILDER_PYTHON_INCLUDE, include)
        cmake_file.write_text(text, errors="surrogateescape")
        changed += 1
    return changed


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--venv", type=Path, required=True)
    parser.add_argument("--package", type=Path, required=True, help="folder with package.xml and msg/")
    args = parser.parse_args()
    venv = args.venv.resolve()
    python = venv / "bin" / "python"
    include, numpy_include = venv_python_paths(python)
    rewrite_exported_paths(venv / "share", include, numpy_include)
    env = {k: v for k, v in os.environ.items() if k != "_ROS_WHEELS_BOOTSTRAP_COMPLETE"}
    env["AMENT_PREFIX_PATH"] = str(venv)
    env["PATH"] = f"{venv / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    with tempfile.TemporaryDirectory(prefix="trap-msgbuild-") as build:
        configure = ["cmake", "-S", str(args.package), "-B", build, f"-DCMAKE_PREFIX_PATH={venv}",
                     f"-DCMAKE_INSTALL_PREFIX={venv}", f"-DPython3_EXECUTABLE={python}",
                     "-DBUILD_TESTING=OFF", "-DCMAKE_BUILD_TYPE=Release"]
        for step in (configure, ["cmake", "--build", build, "-j2"], ["cmake", "--install", build]):
            done = subprocess.run(step, env=env, capture_output=True, text=True)
            if done.returncode != 0:
                sys.stderr.write(done.stdout[-4000:] + done.stderr[-4000:])
                print(f"error: '{' '.join(step[:2])}' failed for {args.package.name}", file=sys.stderr)
                return 1
    probe = subprocess.run([str(python), "-c", f"import {args.package.name}.msg"], env=env,
                           capture_output=True, text=True)
    if probe.returncode != 0:
        sys.stderr.write(probe.stderr)
        print(f"error: {args.package.name} was built but does not import", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
