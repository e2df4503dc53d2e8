"""The robots' visual mesh files, over HTTP under /meshes/ROUTE/PATH.

world_t names a visual's mesh by a URL path relative to a route, never by the
host's path (lcmtypes/rbsim/visual_t.lcm): "world/meshes/link1.stl" is under
the world file's directory (rbview --meshes), "spawn/..." under the server's
spawn directory (--spawn-meshes). The request path comes from a browser and
is not trusted, so a file is served only when it keeps the rules rbserver
keeps for a spawned body's mesh (server/meshio/contained_path.h):
 - a relative path under a route the bridge was given, with no empty, '.' or
   '..' component, no backslash and no NUL;
 - whose real path, every symbolic link resolved, is still under the route's
   real directory (a link inside that points out is refused);
 - that is a regular file (not a FIFO or a device), of at most MAX_BYTES;
 - of a kind the page reads (STL, OBJ, COLLADA and the images a COLLADA
   file may name).
Anything else is 404 with a log line that says why (never the host's path
to the browser). The file is opened by its resolved path, with O_NOFOLLOW,
and checked again on the open descriptor.
"""

import http
import logging
import os
import stat
import urllib.parse

log = logging.getLogger("rbview")

PREFIX = "/meshes/"
MAX_BYTES = 64 << 20  # as rbserver's largest URDF; meshes of real robots are a few MB
MAX_PATH = 1024  # characters of a request path
KINDS = {
    ".stl": "model/stl",
    ".obj": "model/obj",
    ".dae": "model/vnd.collada+xml",
    ".png": "image/png",
    ".jpg": "image/jpeg",
    ".jpeg": "image/jpeg",
}


class Refused(Exception):
    """Why a request path is not served (for the log)."""


class MeshFiles:
    """``routes``: {route name: directory}; a route whose directory is None is off."""

    def __init__(self, routes):
        self.roots = {}
        for name, directory in routes.items():
            if directory is None:
                continue
            real = os.path.realpath(directory)
            if not os.path.isdir(real):
                raise FileNotFoundError("%s: not a directory (meshes route %r)" % (directory, name))
            self.roots[name] = real

    def resolve(self, request_path):
        """The real path of the file `request_path` (after /meshes/) names, or Refused."""
        if len(request_path) > MAX_PATH:
            raise Refused("path longer than %d characters" % MAX_PATH)
        try:
            path = urllib.parse.unquote(request_path, errors="strict")
        except UnicodeDecodeError:
            raise Refused("not UTF-8") from None
        if "\0" in path or "\\" in path:
            raise Refused("a NUL or a backslash")
        parts = path.split("/")
        route, inside = parts[0], parts[1:]
        if route not in self.roots:
            raise Refused("no route %r (rbview serves %s)" % (route, ", ".join(sorted(self.roots)) or "none"))
        if not inside or any(part in ("", ".", "..") for part in inside):
            raise Refused("not a relative path without empty, '.' or '..' components")
        extension = os.path.splitext(inside[-1])[1].lower()
        if extension not in KINDS:
            raise Refused("not a kind of file the page draws (%s)" % ", ".join(sorted(KINDS)))
        root = self.roots[route]
        real = os.path.realpath(os.path.join(root, *inside))
        if os.path.commonpath([real, root]) != root:
            raise Refused("leads out of the %s directory (a symbolic link)" % route)
        return real

    def read(self, real):
        """The bytes of the resolved file, checked on its open descriptor."""
        try:
            fd = os.open(real, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
        except OSError as error:
            raise Refused("cannot open it (%s)" % error.strerror) from None
        try:
            info = os.fstat(fd)
            if not stat.S_ISREG(info.st_mode):
                raise Refused("not a regular file")
            if info.st_size > MAX_BYTES:
                raise Refused("larger than %d bytes" % MAX_BYTES)
            chunks, size = [], 0
            while size <= MAX_BYTES:
                chunk = os.read(fd, 1 << 20)
                if not chunk:
                    break
                chunks.append(chunk)
                size += len(chunk)
            body = b"".join(chunks)
        finally:
            os.close(fd)
        if len(body) > MAX_BYTES:
            raise Refused("larger than %d bytes" % MAX_BYTES)
        return body

    def answer(self, path):
        """The HTTP answer (status, headers, body) to GET `path`, which starts with PREFIX."""
        request = path[len(PREFIX):]
        try:
            real = self.resolve(request)
            body = self.read(real)
        except Refused as why:
            log.warning("mesh %r refused: %s", request[:200], why)
            return (http.HTTPStatus.NOT_FOUND, [("Content-Type", "text/plain")], b"not found\n")
        kind = KINDS[os.path.splitext(real)[1].lower()]
        return (http.HTTPStatus.OK, [("Content-Type", kind), ("Cache-Control", "no-cache"),
                                     ("Content-Length", str(len(body)))], body)
