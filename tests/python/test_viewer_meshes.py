"""rbview bridge: visual mesh files over HTTP (clients/web/rbview_bridge/meshes.py).

The request path comes from a browser and is not trusted: only regular files
of the kinds the page draws, inside a route's directory, every symbolic link
resolved, are served; everything else is 404 with a log line saying why (and
nothing of the host's paths to the browser). Also the world_t visuals the
bridge hands the page (wire.world_to_dict)."""

import http
import logging
import os
import sys

import pytest

from conftest import REPO

sys.path.insert(0, os.path.join(REPO, "clients", "web"))

from rbsim import body_description_t, visual_t, world_t  # noqa: E402
from rbview_bridge import meshes, wire  # noqa: E402
from rbview_bridge.server import StaticFiles  # noqa: E402

STL = b"solid t\nendsolid t\n"


@pytest.fixture
def tree(tmp_path):
    """world/ (served) with meshes and traps; outside/ (not served) with a secret."""
    world = tmp_path / "world"
    (world / "meshes" / "sub").mkdir(parents=True)
    (world / "meshes" / "link.stl").write_bytes(STL)
    (world / "meshes" / "sub" / "a b#c.obj").write_bytes(b"v 0 0 0\n")
    (world / "meshes" / "notes.txt").write_text("not a mesh\n")
    (world / "robot.urdf").write_text("<robot/>\n")
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.stl").write_bytes(b"secret")
    (world / "meshes" / "escape.stl").symlink_to(outside / "secret.stl")
    (world / "meshes" / "out").symlink_to(outside, target_is_directory=True)
    (world / "meshes" / "inside.stl").symlink_to(world / "meshes" / "link.stl")
    (world / "meshes" / "dir.stl").mkdir()
    os.mkfifo(world / "meshes" / "fifo.stl")
    spawn = tmp_path / "spawn"
    spawn.mkdir()
    (spawn / "part.dae").write_bytes(b"<COLLADA/>")
    return {"world": str(world), "spawn": str(spawn), "outside": str(outside)}


def get(files, path):
    status, headers, body = files.answer(path)
    return status, dict(headers), body


def test_serves_meshes_inside_the_routes(tree):
    files = meshes.MeshFiles({"world": tree["world"], "spawn": tree["spawn"]})
    status, headers, body = get(files, "/meshes/world/meshes/link.stl")
    assert status == http.HTTPStatus.OK and body == STL
    assert headers["Content-Type"] == "model/stl"
    # Escaped as the page escapes each component (encodeURIComponent).
    status, _, body = get(files, "/meshes/world/meshes/sub/a%20b%23c.obj")
    assert status == http.HTTPStatus.OK and body == b"v 0 0 0\n"
    # A link that stays inside is followed.
    assert get(files, "/meshes/world/meshes/inside.stl")[0] == http.HTTPStatus.OK
    assert get(files, "/meshes/spawn/part.dae")[0] == http.HTTPStatus.OK


@pytest.mark.parametrize("path, why", [
    ("/meshes/world/meshes/escape.stl", "leads out"),                 # a link to a file outside
    ("/meshes/world/meshes/out/secret.stl", "leads out"),             # through a linked directory
    ("/meshes/world/../outside/secret.stl", "'..'"),
    ("/meshes/world/meshes/%2e%2e/%2e%2e/outside/secret.stl", "'..'"),  # escaped dots
    ("/meshes/world/meshes/..%2f..%2foutside%2fsecret.stl", "'..'"),  # an escaped slash
    ("/meshes/world//etc/passwd.stl", "empty"),
    ("/meshes/world/./meshes/link.stl", "'.'"),
    ("/meshes/world/meshes\\link.stl", "backslash"),
    ("/meshes/world/meshes/link.stl%00.png", "NUL"),
    ("/meshes/world/robot.urdf", "kind of file"),                     # not a mesh
    ("/meshes/world/meshes/notes.txt", "kind of file"),
    ("/meshes/world/meshes/missing.stl", "cannot open"),
    ("/meshes/world/meshes/dir.stl", "not a regular file"),
    ("/meshes/world/meshes/fifo.stl", "not a regular file"),          # would block a reader
    ("/meshes/elsewhere/meshes/link.stl", "no route"),
    ("/meshes/world", "relative path"),
    ("/meshes/%ff.stl", "not UTF-8"),
    ("/meshes/world/" + "a/" * 600 + "x.stl", "longer"),
])
def test_refuses_what_is_not_a_mesh_inside_a_route(tree, caplog, path, why):
    files = meshes.MeshFiles({"world": tree["world"], "spawn": tree["spawn"]})
    with caplog.at_level(logging.WARNING, logger="rbview"):
        status, _, body = get(files, path)
    assert status == http.HTTPStatus.NOT_FOUND
    assert body == b"not found\n"  # nothing of the host's paths
    assert any("refused" in r.getMessage() and why in r.getMessage() for r in caplog.records), \
        [r.getMessage() for r in caplog.records]


def test_an_absolute_root_on_the_request_stays_inside(tree):
    # "/meshes/world//outside/..." would join to an absolute path without the
    # empty-component rule; and the secret is not reachable by any route.
    files = meshes.MeshFiles({"world": tree["world"]})
    assert get(files, "/meshes/world/" + tree["outside"].lstrip("/") + "/secret.stl")[0] == http.HTTPStatus.NOT_FOUND
    assert get(files, "/meshes/spawn/part.dae")[0] == http.HTTPStatus.NOT_FOUND  # no spawn route given


def test_static_files_pass_mesh_requests_on_and_serve_none_without_routes(tree, tmp_path):
    page = tmp_path / "dist"
    page.mkdir()
    (page / "index.html").write_text("<html></html>")
    with_meshes = StaticFiles(str(page), meshes.MeshFiles({"world": tree["world"]}))
    assert with_meshes.process_request("/meshes/world/meshes/link.stl", {})[0] == http.HTTPStatus.OK
    without = StaticFiles(str(page))
    assert without.process_request("/meshes/world/meshes/link.stl", {})[0] == http.HTTPStatus.NOT_FOUND
    with pytest.raises(FileNotFoundError):
        meshes.MeshFiles({"world": str(tmp_path / "nowhere")})


def test_world_dict_carries_the_visuals():
    visual = visual_t()
    visual.kind = "mesh"
    visual.position = [0.1, 0.0, 0.2]
    visual.orientation = [1.0, 0.0, 0.0, 0.0]
    visual.mesh_url = "world/meshes/link.stl"
    visual.scale = [2.0, 2.0, 0.5]
    visual.has_color = True
    visual.rgba = [1.0, 0.0, 1.0, float("nan")]
    body = body_description_t()
    body.name = "arm/block"
    body.shape_type = "box"
    body.visuals = [visual]
    body.num_visuals = 1
    page = world_t()
    page.num_pages = 1
    page.bodies = [body]
    page.num_bodies = 1
    page.total_bodies = 1
    # Through the wire and back, as the bridge gets it.
    decoded = world_t.decode(page.encode())
    drawn = wire.world_to_dict([decoded])["bodies"][0]["visuals"]
    assert drawn == [{
        "kind": "mesh", "position": [0.1, 0.0, 0.2], "orientation": [1.0, 0.0, 0.0, 0.0],
        "half_extents": [0.0, 0.0, 0.0], "radius": 0.0, "half_length": 0.0,
        "mesh_url": "world/meshes/link.stl", "scale": [2.0, 2.0, 0.5], "has_color": True,
        "rgba": [1.0, 0.0, 1.0, 0.0],
    }]
    # A URL the page could not use is dropped (the HTTP side refuses it anyway).
    decoded.bodies[0].visuals[0].mesh_url = "world/\x1b[2J.stl"
    assert wire.world_to_dict([decoded])["bodies"][0]["visuals"][0]["mesh_url"] == ""
