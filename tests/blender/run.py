#!/usr/bin/env python3
"""Run the Blender tests: every tests/blender/test_*.py inside real Blender.

The add-on is installed from the package zip into a throwaway user folder
(BLENDER_USER_SCRIPTS / BLENDER_USER_CONFIG) with Blender's own Install operator;
each test file then enables it the way the Preferences checkbox does. Files run in
`blender -b --factory-startup`, except test_ui*.py, which needs Blender's window
and runs under Xvfb. Ends with the line `N passed, N failed`; exits 1 on failure.

    /usr/bin/python3 tests/blender/run.py --blender blender --zip dist/polycube-0.1.0.zip [-k FILTER]
"""

import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
RESULT = re.compile(r"^POLYCUBE-TEST (PASS|FAIL) (\S+)$", re.MULTILINE)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--zip", required=True, help="the add-on zip written by `make package`")
    parser.add_argument("-k", dest="filter", default="",
                        help="only tests whose 'file::name' contains this")
    parser.add_argument("--timeout", type=float, default=900, help="seconds per test file")
    parser.add_argument("--verbose", action="store_true", help="show Blender's output of passing files")
    args = parser.parse_args()

    home = tempfile.mkdtemp(prefix="polycube-blender-tests-")
    env = dict(os.environ,
               BLENDER_USER_SCRIPTS=os.path.join(home, "scripts"),
               BLENDER_USER_CONFIG=os.path.join(home, "config"),
               POLYCUBE_ROOT=ROOT, POLYCUBE_ZIP=os.path.abspath(args.zip),
               POLYCUBE_TEST_FILTER=args.filter, POLYCUBE_TEST_TMP=os.path.join(home, "tmp"))
    try:
        passed, failed = 0, 0
        install = _install(args, env)
        if install is not None:
            print(f"FAIL install from {args.zip}\n{install}")
            failed += 1
        else:
            for path in sorted(glob.glob(os.path.join(HERE, "test_*.py"))):
                file_passed, file_failed = _run_file(path, args, env)
                passed, failed = passed + file_passed, failed + file_failed
        print(f"{passed} passed, {failed} failed", flush=True)
        return 1 if failed else 0
    finally:
        shutil.rmtree(home, ignore_errors=True)


def _install(args, env):
    """Install the zip with Blender's Install operator; None or what went wrong."""
    script = ("import bpy, sys\n"
              f"result = bpy.ops.preferences.addon_install(filepath={os.path.abspath(args.zip)!r})\n"
              "sys.exit(0 if result == {'FINISHED'} else 1)\n")
    done = subprocess.run(
        [args.blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python-expr", script],
        env=env, capture_output=True, text=True, timeout=args.timeout)
    installed = os.path.join(env["BLENDER_USER_SCRIPTS"], "addons", "polycube", "__init__.py")
    if done.returncode != 0 or not os.path.isfile(installed):
        return done.stdout + done.stderr
    return None


def _command(path, args):
    if os.path.basename(path).startswith("test_ui"):
        # Blender's real window, on a virtual X server; no input but simulated events.
        return ["xvfb-run", "-a", "-s", "-screen 0 1600x1000x24", args.blender, "--factory-startup",
                "--enable-event-simulate", "--python-exit-code", "1", "--python", path]
    return [args.blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", path]


def _run_file(path, args, env):
    name = os.path.basename(path)
    try:
        done = subprocess.run(_command(path, args), env=env, capture_output=True, text=True,
                              timeout=args.timeout, cwd=ROOT)
        output, returncode = done.stdout + done.stderr, done.returncode
    except subprocess.TimeoutExpired as timeout:
        output = (timeout.stdout or b"").decode(errors="replace") if isinstance(timeout.stdout, bytes) \
            else (timeout.stdout or "")
        output += f"\n{name} timed out after {args.timeout:.0f} s"
        returncode = None
    results = RESULT.findall(output)
    for outcome, test in results:
        print(f"{outcome} {test}", flush=True)
    passed = sum(1 for outcome, _ in results if outcome == "PASS")
    failed = len(results) - passed
    if returncode != 0 and failed == 0:
        # Blender died or exited wrongly outside any test: that is a failure too.
        print(f"FAIL {name} (exit status {returncode})", flush=True)
        failed += 1
    if failed or args.verbose:
        print(_indent(output), flush=True)
    return passed, failed


def _indent(text):
    return "\n".join("    " + line for line in text.rstrip().splitlines())


if __name__ == "__main__":
    sys.exit(main())
