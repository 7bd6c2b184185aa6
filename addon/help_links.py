# SPDX-License-Identifier: GPL-3.0-or-later
"""Documentation and problem reports point into the README the package carries.

The add-on has no web address of its own, so `bl_info` names sections of the
README beside `__init__.py` (`README.md#blender-add-on`, as the manifest's
`website` does), and `resolve` turns those into `file://` addresses of the
installed copy when the add-on registers. Blender 3.x lists add-ons from a parse
of the `bl_info` text, not from the module: the Documentation and Report a Bug
buttons of the add-on's row read that entry, so it is updated too.
"""

import os
from urllib.parse import quote

README = "README.md"


def readme_path(folder):
    """The README inside the package (zip), or the checkout's (add-on linked from a source tree)."""
    for candidate in (os.path.join(folder, README), os.path.join(os.path.dirname(folder), README)):
        if os.path.isfile(candidate):
            return os.path.abspath(candidate)
    return None


def resolve(info, folder):
    """Point info's doc_url and tracker_url, written as README.md#section, at the README's
    file in `folder`; those of another form, or without a README to point at, stay."""
    path = readme_path(folder)
    if path is None:
        return info
    for key in ("doc_url", "tracker_url"):
        name, _, section = info.get(key, "").partition("#")
        if name == README:
            info[key] = "file://" + quote(path) + (f"#{section}" if section else "")
    return info


def resolve_in_addon_list(module_name, folder):
    """Blender 3.x: the add-on list's entry for `module_name` (its parse of bl_info) gets the
    same addresses. Returns whether there was such an entry (4.2+ extensions have none)."""
    try:
        import addon_utils
    except ImportError:
        return False
    # The list is made on first use (the Preferences drawing it): make it now, so that our
    # entry is there to update; Blender keeps entries until their file changes.
    addon_utils.modules(refresh=False)
    entry = getattr(addon_utils, "addons_fake_modules", {}).get(module_name)
    info = getattr(entry, "bl_info", None)
    if not isinstance(info, dict):
        return False
    resolve(info, folder)
    return True
