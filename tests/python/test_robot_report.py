"""The HTML report of a robot of many bodies (meshgap_report on a robot problem file and its .path) in headless
Chromium: every link is loaded and drawn, one clearance curve per link is plotted, and the per-state data the page
animates (link poses, link clearances) matches link poses composed by hand and RobotScene's per-link clearances at
the path's first and last states. Bad path files get one clear error and nothing is written."""
import base64
import json
import os
import re
import subprocess

import numpy as np
import pytest

import meshgap
from conftest import cli_error, executable
from test_report import browse, chromium, report_available
from test_robot_scene import files, link_frames, write_cfg  # noqa: F401  (files: the fixture)

PATH = np.array([[0.5, 1.0], [1.5, 0.0], [-2.5, 0.25]])


def page_data(html):
    text = html.read_text()
    data = json.loads(re.search(r"var MESHGAP = (\{.*?\});\n", text, re.S).group(1))
    decoded = {k: np.frombuffer(base64.b64decode(data[k]), dtype=np.float32)
               for k in ("poses", "linkClearance", "clearance", "arcLength")}
    return data, decoded


def test_robot_report_draws_every_link(files, tmp_path):  # noqa: F811
    report_available()
    chromium()
    cfg = write_cfg(files)
    path = tmp_path / "arm.path"
    path.write_text("".join("%r %r\n" % tuple(q) for q in PATH))
    out = tmp_path / "arm.html"
    run = subprocess.run([executable("report"), "--cfg", str(cfg), "--path", str(path), "--out", str(out)],
                         capture_output=True, text=True, timeout=300)
    states = int(re.search(r"\((\d+) dense states, (\d+) links", run.stdout).group(1))
    scene = meshgap.RobotScene.from_cfg(cfg)
    links = len(scene.link_names)

    data, d = page_data(out)
    assert data["links"] == scene.link_names and data["states"] == states
    assert d["poses"].shape == (states * links * 7,) and d["linkClearance"].shape == (states * links,)
    poses = d["poses"].reshape(states, links, 7)
    link_clearance = d["linkClearance"].reshape(states, links)
    exact = scene.distance(PATH[[0, -1]])
    for row, k in ((0, 0), (1, states - 1)):
        np.testing.assert_allclose(link_clearance[k], exact["link_clearance"][row], rtol=1e-6, atol=1e-6)
        assert d["clearance"][k] == pytest.approx(exact["distance"][row], rel=1e-6, abs=1e-6)
        frames = link_frames(*PATH[[0, -1]][row])
        for i, name in enumerate(scene.link_names):
            if name in frames:
                np.testing.assert_allclose(poses[k, i, :3], frames[name][:3, 3], atol=1e-6)
    # The per-link clearance is each link's least pair: the whole robot's is their least, at every state.
    np.testing.assert_allclose(d["clearance"], link_clearance.min(axis=1), rtol=0, atol=0)
    assert np.all(np.diff(d["arcLength"]) > 0)
    # The tool says when the path it draws collides (exit 2 and a warning counting the colliding dense states).
    colliding = int(np.count_nonzero(d["clearance"] < 0))
    assert run.returncode == (2 if colliding else 0), run.stderr
    if colliding:
        assert "the path collides at %d of its %d dense states" % (colliding, states) in run.stderr, run.stderr

    status, dom, console = browse(out, tmp_path / "arm.png")
    triangles = sum(len(scene.link_mesh(i)[1]) for i in range(links)) + \
        sum(len(scene.obstacle_mesh(i)[1]) for i in range(scene.obstacles))
    assert status == "ready: loaded %d triangles, %d states" % (triangles, states)
    assert console == []
    plotted = re.findall(r'<polyline[^>]*class="link-clearance"[^>]*data-link="([^"]*)"', dom)
    assert plotted == scene.link_names


def test_robot_report_bad_path(files, tmp_path):  # noqa: F811
    cfg = str(write_cfg(files))
    cli = executable("report")
    out = tmp_path / "r.html"
    (tmp_path / "bad.path").write_text("0.5 1.0\n0.5 1.0 2.0\n")
    assert cli_error([cli, "--cfg", cfg, "--path", str(tmp_path / "bad.path"), "--out", str(out)]) == \
        str(tmp_path / "bad.path") + ":2: a state of this problem has 2 numbers (as start.joints, or the bodies' " \
        "states one after the other), found 3"
    (tmp_path / "nan.path").write_text("0.5 nan\n")
    assert "'nan' is not a finite number" in cli_error([cli, "--cfg", cfg, "--path", str(tmp_path / "nan.path"),
                                                        "--out", str(out)])
    assert cli_error([cli, "--cfg", cfg, "--path", str(tmp_path / "none.path"), "--out", str(out)]).endswith(
        "none.path: no such file")
    assert sorted(os.listdir(tmp_path)) == ["bad.path", "nan.path"]
