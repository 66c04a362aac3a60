"""The live preview's facets follow its camera (CLI.md, "Live preview"; issue 34
item 3): once the page's camera stops it sends it (``POST /camera``), and the
frames shown are faceted again for it with ``--pixel-error`` 0.5, without
evaluating the scene, and only where the tolerance a curved leaf needs changed
by more than a factor of two; the others keep their facets (no facetization
counted). The request follows the server's rules: JSON from our own page, a
message for anything else, never a traceback."""

from __future__ import annotations

import http.client
import json
import os

import pytest

from castor.csg.tree import leaves
from castor.mesh import primitives as mesh_primitives
from castor.mesh.caches import PROCESS, Bounded
from castor.pictures.camera import make_camera
from castor.serve.evaluation import Facets, PIXEL_ERROR, Watched, evaluate, refaceted
from castor.serve.camera import page_camera
from castor.serve.server import PreviewServer
from castor.settings import Source
from tests.support.serve import get, triangles, wait_for

SIZE = (800, 600)
# three curved leaves in one union down the line of sight (+y), odd sizes so that
# no other test's facets are cached, and a flat slab that never changes
LEAVES = ("TOLERANCE = 1e-4;\n"
          "> $U(@t(0, 2, 0) @h(0.4321) !sp(0.2, 0.4, 0.8),\n"
          "     @t(0.5, 12, 0) @h(0.3321, 0.3321, 1.2) !cy(0.2, 0.6, 0.3),\n"
          "     @t(-1, 60, 0) @h(0.6123) !to(0.7, 0.5, 0.2, 0.37),\n"
          "     @t(-3, 20, -2) @h(6, 7, 0.5) !cu(0.5, 0.5, 0.5));\n")


def _camera(y: float):
    """Looking down +y from (0, y, 0)."""
    return make_camera((0, 0, 0), (0, 0, 0), SIZE, eye=(0.0, y, 0.0), look=(0.0, y + 1, 0.0))


def _tolerances(evaluation) -> dict:
    """The tolerance of each leaf faceted for frame 1, by its kind (one each)."""
    root = evaluation.faceted[1].objects[0].root
    return {leaf.kind: leaf.tolerance for leaf, _, _ in leaves(root)}


@pytest.fixture
def builds(monkeypatch):
    """The kinds of the primitives facetized (built), from empty caches."""
    for cache in vars(PROCESS).values():
        if isinstance(cache, Bounded):
            cache.clear()
    made = []
    build = mesh_primitives.build

    def counted(kind, shape, facets):
        made.append(kind)
        return build(kind, shape, facets)

    monkeypatch.setattr(mesh_primitives, "build", counted)
    return made


def test_a_refacet_keeps_the_leaves_whose_tolerance_changed_less_than_twice(builds):
    first = evaluate(Watched(Source(text=LEAVES, name="leaves.cas"), quiet=True),
                     facets=Facets(_camera(0.0)))
    assert first.errors == 0 and len(first.frames) == 1
    before = _tolerances(first)
    near, middle, far, slab = "sp", "cy", "to", "cu"
    builds.clear()
    # six back: the near sphere is 8 away instead of 2 (it may be 4x coarser), the
    # cylinder 18 instead of 12 (1.5x), the far torus 66 instead of 60 (1.1x)
    moved = refaceted(first, Facets(_camera(-6.0), first.faceted))
    after = _tolerances(moved)
    assert after[near] >= 2.5 * before[near]  # faceted again, coarser
    assert after[middle] == before[middle] and after[far] == before[far]  # kept
    assert after[slab] == before[slab] == 1e-4  # flat: never sized
    assert builds == [near]  # one facetization: the near sphere's
    assert moved.frames[0].triangles < first.frames[0].triangles
    assert moved.frames[0].sources == first.frames[0].sources  # still pointed at
    assert moved.trees is first.trees  # the scene was not evaluated again

    # back where it was: the near sphere's facets come from the cache
    builds.clear()
    again = refaceted(moved, Facets(_camera(0.0), moved.faceted))
    assert _tolerances(again) == before and builds == []
    assert again.frames[0].triangles == first.frames[0].triangles

    # a camera that changes no leaf's need by twice keeps the frame itself
    still = refaceted(first, Facets(_camera(0.3), first.faceted))
    assert still.frames[0] is first.frames[0] and builds == []


def test_an_edit_after_a_refacet_keeps_the_facets_of_what_it_did_not_change(builds):
    watched = Watched(Source(text=LEAVES, name="leaves.cas"), quiet=True)
    first = evaluate(watched, facets=Facets(_camera(0.0)))
    # the cube made higher: every curved leaf keeps its facets (and its tolerance)
    edited = Watched(Source(text=LEAVES.replace("@h(6, 7, 0.5)", "@h(6, 7, 0.75)"),
                            name="leaves.cas"), quiet=True)
    builds.clear()
    second = evaluate(edited, facets=Facets(_camera(0.2), first.faceted))
    assert second.errors == 0
    assert _tolerances(second) == _tolerances(first)
    assert builds == []


def test_without_a_camera_the_scene_tolerance_everywhere():
    evaluation = evaluate(Watched(Source(text=LEAVES, name="leaves.cas"), quiet=True),
                          facets=Facets())
    assert set(_tolerances(evaluation).values()) == {1e-4}
    assert PIXEL_ERROR == 0.5


# --- over HTTP

SCENE = ("ground = @h(40, 40, 1) !cu(0.6, 0.6, 0.6);\n"
         "ball = @t(20, 20, 2) !sp(0.2, 0.4, 0.8);\n> ground, ball;\n")


@pytest.fixture
def preview(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "scene.cas").write_text(SCENE)
    server = PreviewServer(Watched(Source(("scene.cas",))), "127.0.0.1", 0).start()
    port = server.httpd.server_address[1]
    wait_for(lambda: get(port, "/scene.json")[2].get("evaluated"))
    yield server
    server.close()


def post(port: int, body, headers: dict | None = None, path: str = "/camera"):
    data = body if isinstance(body, bytes) else json.dumps(body).encode()
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    connection.request("POST", path, body=data,
                       headers={"Content-Type": "application/json", **(headers or {})})
    answer = connection.getresponse()
    text = answer.read()
    connection.close()
    return answer.status, text


def looking(eye, target=(20.0, 20.0, 2.0), **more):
    return {"eye": list(eye), "target": list(target), "up": [0, 0, 1], "fov": 40,
            "width": 900, "height": 600, **more}


def _ball_triangles(port: int) -> tuple[int, int] | None:
    """The version shown and the triangles of the ball (those above the ground);
    None when the frames changed meanwhile."""
    _, _, scene = get(port, "/scene.json")
    frame = scene["frames"][0]
    status, _, data = get(port, frame["url"])
    if status != 200:
        return None
    tris = triangles(data, frame["triangles"])
    return scene["version"], int((tris[:, :, 2].min(axis=1) > 1.0 + 1e-6).sum())


def test_the_camera_refacets_the_frames_for_it(preview):
    port = preview.httpd.server_address[1]
    version, uniform = wait_for(lambda: _ball_triangles(port))
    _, _, scene = get(port, "/scene.json")
    assert scene["refaceted"] is None
    # from far away: coarser than the scene's tolerance
    status, body = post(port, looking((-200.0, -200.0, 80.0), server=scene["server"]))
    assert status == 200, body
    assert json.loads(body)["version"] > version  # answered once faceted for it
    far_version, far = wait_for(lambda: (v := _ball_triangles(port)) and v[0] > version and v)
    assert far < uniform / 3
    _, _, scene = get(port, "/scene.json")
    assert scene["refaceted"] is not None and scene["diagnostics"] == []
    # close to the ball: finer again (the scene's tolerance at most)
    assert post(port, looking((23.0, 17.0, 4.0)))[0] == 200
    near_version, near = wait_for(lambda: (v := _ball_triangles(port)) and v[0] > far_version and v)
    assert far < near <= uniform
    # the ground, flat, is as it was
    _, _, scene = get(port, "/scene.json")
    assert scene["frames"][0]["polygons"] > 0


def test_a_save_after_the_camera_is_faceted_for_it(preview, tmp_path):
    port = preview.httpd.server_address[1]
    version, uniform = wait_for(lambda: _ball_triangles(port))
    assert post(port, looking((-200.0, -200.0, 80.0)))[0] == 200
    version, far = wait_for(lambda: (v := _ball_triangles(port)) and v[0] > version and v)
    # the ground's colour changed, saved: evaluated again, the ball still for the far camera
    path = tmp_path / "scene.cas"
    before = os.stat(path).st_mtime_ns
    path.write_text(SCENE.replace("!cu(0.6, 0.6, 0.6)", "!cu(0.5, 0.6, 0.6)"))
    if os.stat(path).st_mtime_ns == before:  # as an editor's save moves it on
        os.utime(path, ns=(before + 1_000_000, before + 1_000_000))
    _, again = wait_for(lambda: (v := _ball_triangles(port)) and v[0] > version and v)
    _, _, scene = get(port, "/scene.json")
    assert scene["refaceted"] is None  # evaluated, not faceted again
    assert [0.5, 0.6, 0.6] in [o["colour"] for o in scene["frames"][0]["origins"]]
    assert again == far < uniform / 3


@pytest.mark.parametrize("body, message", [
    (b"{not json", "not JSON"),
    (b"[1, 2, 3]", "one JSON object"),
    (json.dumps({"eye": [0, 0, 0]}).encode(), "'target' is three numbers"),
    (json.dumps(looking((0, 0, 10), target=(0, 0, 10))).encode(), "one point"),
    (json.dumps(looking((0, 0, 0), up=[10, 10, 1])).encode(), "'up'"),
    (json.dumps(looking((0, 0, 0), fov=180)).encode(), "between 0 and 180"),
    (json.dumps(looking((0, 0, 0), width=0)).encode(), "whole number of pixels"),
    (json.dumps(looking((0, 0, 0), height=1.5)).encode(), "whole number of pixels"),
    (json.dumps(looking((0, 0, 0), width=True)).encode(), "whole number of pixels"),
    (json.dumps(looking((0, "1", 0))).encode(), "'eye' is a number"),
    (json.dumps(looking((0, 1e300, 0))).encode(), "'eye' is a number"),
    (b'{"eye": [0, 0, NaN]}', "'eye' is a number"),
    (json.dumps(looking((0, 0, 0), orthographic="yes")).encode(), "true or false"),
    (b"[" * 2000 + b"]" * 2000, ""),
])
def test_a_malformed_camera_is_refused_with_a_message(preview, body, message):
    port = preview.httpd.server_address[1]
    version = get(port, "/scene.json")[2]["version"]
    status, answer = post(port, body)
    assert status == 400
    assert message in json.loads(answer)["error"]
    assert b"Traceback" not in answer
    assert get(port, "/scene.json")[2]["version"] == version  # nothing faceted again


def test_a_camera_must_be_sent_as_json_and_small(preview):
    port = preview.httpd.server_address[1]
    good = json.dumps(looking((0.0, 0.0, 5.0))).encode()
    assert post(port, good, {"Content-Type": "text/plain"})[0] == 400
    assert post(port, b" " * 5000 + good)[0] == 400


@pytest.mark.parametrize("headers, status", [
    ({"Origin": "http://evil.example"}, 403),
    ({"Host": "attacker.example:80"}, 403),
    ({"Origin": "null"}, 403),
])
def test_a_camera_from_another_site_is_refused(preview, headers, status):
    port = preview.httpd.server_address[1]
    version = get(port, "/scene.json")[2]["version"]
    assert post(port, looking((0.0, 0.0, 5.0)), headers)[0] == status
    assert get(port, "/scene.json")[2]["version"] == version


def test_a_camera_from_a_page_of_another_server_is_refused(preview):
    port = preview.httpd.server_address[1]
    status, answer = post(port, looking((0.0, 0.0, 5.0), server="0123456789ab"))
    assert status == 409 and "load it again" in json.loads(answer)["error"]
    own = get(port, "/scene.json")[2]["server"]
    assert post(port, looking((0.0, 0.0, 5.0), server=own))[0] == 200


def test_the_page_camera_is_the_pictures_camera():
    camera = page_camera(looking((20.0, 10.0, 2.0)))
    assert camera.width == 900 and camera.height == 600 and camera.fov == 40
    assert list(camera.forward) == [0.0, 1.0, 0.0] and list(camera.up) == [0.0, 0.0, 1.0]
    assert list(camera.right) == [1.0, 0.0, 0.0] and not camera.orthographic
    flat = page_camera(looking((20.0, 10.0, 2.0), orthographic=True))
    assert flat.half_height == pytest.approx(10 * 0.36397, rel=1e-4)


# --- the rule itself (castor.mesh.screen.kept_where_close), leaf by leaf

def _sized(text: str, y: float):
    from castor.mesh.screen import sized_to_screen
    from castor.pipeline import evaluated_frames

    [tree], said = evaluated_frames(text, "kept.cas")
    assert not said, said
    return sized_to_screen(tree, None, PIXEL_ERROR, _camera(y))


def test_a_named_object_used_near_and_far_keeps_the_far_use_only():
    from castor.mesh.screen import kept_where_close

    text = ("TOLERANCE = 1e-4;\ncol = @h(0.3, 0.3, 2) !cy(0.5, 0.5, 0.5);\n"
            "> $U(@t(0, 2, 0) col, @t(0, 60, 0) col);\n")
    before, after = _sized(text, 0.0), _sized(text, -6.0)
    kept = kept_where_close(before, after)
    (near_before, far_before), (near_after, far_after), (near, far) = (
        obj.root.operands for obj in (before.objects[0], after.objects[0], kept.objects[0]))
    assert near is near_after and near.shared.key != near_before.shared.key  # 4x: made again
    assert far is far_before  # 1.1x: the same shared subtree, from the caches
    assert kept.objects[0].root.operands[1].shared is far_before.shared


def test_a_leaf_that_moved_is_never_kept_with_its_old_place():
    from castor.mesh.screen import kept_where_close

    text = "TOLERANCE = 1e-4;\n> @t(0, 12, 0) !sp(0.5, 0.5, 0.5), @t(0, 30, 0) !sp(1, 0, 0);\n"
    before = _sized(text, 0.0)
    moved = _sized(text.replace("@t(0, 12, 0)", "@t(0.1, 12, 0)")
                   .replace("!sp(1, 0, 0)", "!sp(0, 1, 0)"), 0.0)
    kept = kept_where_close(before, moved)
    assert kept.objects[0] is moved.objects[0] and kept.objects[1] is moved.objects[1]
    again = kept_where_close(before, _sized(text, 0.0))  # evaluated again, unchanged
    assert all(a is b for a, b in zip(again.objects, before.objects))
