#!/usr/bin/env python3
"""Copy the shared libraries native modules need into a folder beside them, so the
add-on runs on a Linux that never saw the build's distribution.

Every library `ldd` resolves for the modules (the Python module, and the CHOLMOD
plugin it loads when a mesh is large), except those any Linux with Blender
has (glibc's, libstdc++, libgcc_s and the loader), is copied into FOLDER under its
soname (symlinks followed). The module finds them through its `$ORIGIN/lib`
DT_RPATH (CMakeLists.txt), which the loader also searches for the libraries'
own dependencies, so the copies need no change.

    bundle_libraries.py MODULE.so... FOLDER
"""

import os
import re
import shutil
import subprocess
import sys

# Present wherever Blender runs: the C library and its parts, the C++ runtime, the loader.
SYSTEM = re.compile(r"^(linux-vdso|ld-linux|libc|libm|libdl|libpthread|librt|libutil|libresolv|"
                    r"libstdc\+\+|libgcc_s)\.so")
_LDD_LINE = re.compile(r"^\s*(\S+)\s+=>\s+(\S+)\s+\(0x[0-9a-f]+\)$")


def needed_libraries(module):
    """(soname, resolved path) of every library the module loads, per ldd."""
    output = subprocess.run(["ldd", module], check=True, capture_output=True, text=True).stdout
    found = []
    for line in output.splitlines():
        match = _LDD_LINE.match(line)
        if match is None:
            if "not found" in line:
                raise SystemExit(f"bundle_libraries: {line.strip()}")
            continue
        found.append(match.groups())
    return found


def main(modules, folder):
    os.makedirs(folder, exist_ok=True)
    bundled = set()
    for module in modules:
        for soname, path in needed_libraries(module):
            if (SYSTEM.match(soname) or soname in bundled
                    or os.path.dirname(os.path.abspath(path)) == os.path.abspath(folder)):
                continue
            shutil.copy2(os.path.realpath(path), os.path.join(folder, soname))
            bundled.add(soname)
    print(f"Bundled {len(bundled)} libraries into {folder}: {' '.join(sorted(bundled))}")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    main(sys.argv[1:-1], sys.argv[-1])
