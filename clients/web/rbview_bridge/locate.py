"""Which build tree rbview takes its page and the lcm-gen message types from.

Both are build outputs (``BUILD/clients/web/dist`` and
``BUILD/lcmtypes/python/rbsim``), and a build may live anywhere, so the build
is looked for, in order, in
  1. ``$RBSIM_BUILD_DIR`` (set by the copy of the launcher in a build tree,
     ``BUILD/clients/web/rbview``, to that tree; or by the user),
  2. the build tree the launcher was started in: the current directory or the
     nearest folder above it holding a ``CMakeCache.txt`` of this source tree
     (``cd build-release && ../clients/web/rbview``),
  3. ``<source tree>/build``.
The first one that exists is taken. Without the types there, :func:`locate`
gives the one line to print instead of the rbsim package's import traceback.
"""

import os

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_TREE = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))

TYPES_SUBDIR = os.path.join("lcmtypes", "python")
PAGE_SUBDIR = os.path.join("clients", "web", "dist")
# One generated module stands for all of them (as in rbsim/__init__.py).
_TYPES_MARKER = os.path.join(TYPES_SUBDIR, "rbsim", "world_state_t.py")


def has_types(build):
    return os.path.isfile(os.path.join(build, _TYPES_MARKER))


def _cache_source_dir(cache_file):
    """CMAKE_HOME_DIRECTORY of a CMakeCache.txt (the tree it builds), or None."""
    try:
        with open(cache_file, encoding="utf-8", errors="replace") as f:
            for line in f:
                if line.startswith("CMAKE_HOME_DIRECTORY:"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return None


def enclosing_build(start, source_tree=SOURCE_TREE):
    """The nearest folder at or above `start` that is a CMake build of
    `source_tree`, or None (a build of another project does not count)."""
    source = os.path.realpath(source_tree)
    folder = os.path.realpath(start)
    while True:
        cache = os.path.join(folder, "CMakeCache.txt")
        if os.path.isfile(cache):
            home = _cache_source_dir(cache)
            if home and os.path.realpath(home) == source:
                return folder
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        folder = parent


class NotFound(Exception):
    """No build with the message types; str() is the one line to print."""


def locate(environ=None, cwd=None, source_tree=SOURCE_TREE):
    """The build tree to take the page and the message types from.

    Returns (build, how): `how` says why this one, for the log. Raises
    NotFound when the types are in none of the places looked in. With
    $RBSIM_LCMTYPES_PYTHON_DIR set, the rbsim package takes the types from
    there and any build will do for the page.
    """
    environ = os.environ if environ is None else environ
    cwd = os.getcwd() if cwd is None else cwd
    explicit = environ.get("RBSIM_BUILD_DIR")
    if explicit:
        candidates = [(os.path.abspath(explicit), "$RBSIM_BUILD_DIR")]
    else:
        candidates = []
        around = enclosing_build(cwd, source_tree)
        if around:
            candidates.append((around, "the build tree rbview was started in"))
        candidates.append((os.path.join(source_tree, "build"), "the source tree's build/"))
    if environ.get("RBSIM_LCMTYPES_PYTHON_DIR"):
        return candidates[0]
    for build, how in candidates:
        if has_types(build):
            return build, how
    looked = " or ".join(os.path.join(build, TYPES_SUBDIR) for build, _ in candidates)
    if explicit:
        hint = ("build it first (cmake --build %s), or set RBSIM_BUILD_DIR to a build that has them"
                % candidates[0][0])
    else:
        hint = ("build first (cmake --build BUILD), then run BUILD/clients/web/rbview "
                "or set RBSIM_BUILD_DIR=BUILD")
    raise NotFound("no lcm-gen Python message types (rbsim/world_state_t.py ...) in %s: %s"
                   % (looked, hint))
