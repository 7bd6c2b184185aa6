# SPDX-License-Identifier: GPL-3.0-or-later
"""The files one run writes, all of them or none (as the native program does).

Each is first written under a temporary name beside its target (same folder,
so the final rename is atomic) and only when every one is written are they
renamed into place. On any failure the temporaries, and the folders made for
them, are removed: no file is new or half-written, and an existing file at a
target keeps its old contents.

    with OutputFiles() as outputs:
        save_blend(outputs.temporary("out.blend"))
        write_json(outputs.temporary("out.json"))
        outputs.commit()
"""

import os
import tempfile


class OutputFiles:
    def __init__(self):
        self._staged = []          # (target, temporary)
        self._made_folders = []    # created for a target, deepest last

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        self.discard()
        return False

    def temporary(self, path, suffix=None):
        """A new, empty temporary file beside path (its folder made if missing), to write the
        output to; its name ends with suffix (default: path's extension), for writers that
        choose the format by it. Raises ValueError with one sentence naming path when it
        cannot be made."""
        if "\0" in path:
            raise ValueError(f"cannot write {path!r}: the path contains a NUL character")
        target = os.path.abspath(path)
        if os.path.isdir(target):
            raise ValueError(f"cannot write {path}: it is a directory")
        folder, name = os.path.split(target)
        try:
            self._make_folder(folder)
            descriptor, temporary = tempfile.mkstemp(
                prefix=f".{name}.", suffix=os.path.splitext(name)[1] if suffix is None else suffix, dir=folder)
        except OSError as error:
            raise ValueError(f"cannot write {path}: {error.strerror or error}") from None
        os.close(descriptor)
        os.chmod(temporary, 0o666 & ~_umask())
        self._staged.append((target, temporary))
        return temporary

    def commit(self):
        """Renames every temporary onto its target. If one cannot be renamed, the targets
        made so far are removed (the ones replaced cannot come back) and ValueError says why."""
        done = []
        for target, temporary in self._staged:
            existed = os.path.exists(target)
            try:
                os.replace(temporary, target)
            except OSError as error:
                for made in done:
                    os.remove(made)
                raise ValueError(f"cannot write {target}: {error.strerror or error}") from None
            if not existed:
                done.append(target)
        self._staged, self._made_folders = [], []

    def discard(self):
        for _, temporary in self._staged:
            try:
                os.remove(temporary)
            except OSError:
                pass
        for folder in reversed(self._made_folders):
            try:
                os.rmdir(folder)
            except OSError:
                pass
        self._staged, self._made_folders = [], []

    def _make_folder(self, folder):
        missing = []
        while folder and not os.path.exists(folder):
            missing.append(folder)
            folder = os.path.dirname(folder)
        for made in reversed(missing):
            os.mkdir(made)
            self._made_folders.append(made)


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask
