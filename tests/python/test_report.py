"""The HTML plan report (meshgap_plan --report, meshgap_report) in a real browser: headless Chromium loads it from
disk, the page reports the triangles and states it loaded in its status element once the scene is loaded and its
first frame drawn (read back with --dump-dom; the test waits for that "ready" status, so a busy machine only makes
it slower), nothing but the software GL driver's performance notes reaches the console, and a screenshot of the 3D
view, taken in the same run after the page is ready, shows the scene (many colours, the robot's blue). Bad input
writes nothing."""
import os
import re
import shutil
import subprocess
import tempfile
import time

import numpy as np
import pytest

import meshgap
from conftest import MAPS, RESOURCES, box, cli_error, executable, omplapp, write_obj

CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader", "--disable-quic",
                  "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  "--window-size=1200,900", "--enable-logging=stderr", "--v=0"]
STATUS = re.compile(r'<div id="status">([^<]*)</div>')
# How long to wait for the page to be ready: Chromium is run again with a longer virtual time budget (the time the
# page may take, in its own clock) until the status is no longer "loading", within a wall-clock deadline generous
# enough for a machine busy with other work.
VIRTUAL_TIME_BUDGETS_MS = (10000, 30000, 90000, 270000)
READY_DEADLINE_S = 600


def chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        if shutil.which(name):
            return shutil.which(name)
    pytest.skip("headless Chromium not found (Debian: apt-get install chromium): the report is not tested in a browser")


def report_available():
    if not meshgap.REPORT_AVAILABLE:
        pytest.skip("three.js (Debian: libjs-three) was not found when meshgap was built: no reports")


def browse(html, screenshot):
    """Run Chromium on the file with a fresh profile, dumping the DOM and saving a screenshot in the same run, again
    with a longer virtual time budget while the page still says "loading"; return (the page's status, the DOM, its
    console lines). The screenshot is taken after the DOM is read, so a "ready" status holds for it too."""
    deadline = time.monotonic() + READY_DEADLINE_S
    for budget in VIRTUAL_TIME_BUDGETS_MS:
        with tempfile.TemporaryDirectory() as profile:
            run = subprocess.run([chromium()] + CHROMIUM_FLAGS +
                                 ["--user-data-dir=" + profile, "--virtual-time-budget=%d" % budget, "--dump-dom",
                                  "--screenshot=" + str(screenshot), "file://" + os.path.abspath(html)],
                                 capture_output=True, timeout=max(1.0, deadline - time.monotonic()))
        dom = run.stdout.decode("utf-8", "replace")
        console = [line for line in run.stderr.decode("utf-8", "replace").splitlines()
                   if ":CONSOLE" in line and "GL Driver Message (OpenGL, Performance" not in line]
        status = STATUS.search(dom)
        assert status, (run.returncode, dom[-2000:], run.stderr.decode("utf-8", "replace")[-2000:])
        if status.group(1) != "loading":
            return status.group(1), dom, console
    pytest.fail("the report still says 'loading' after a virtual time budget of %d ms" % budget)


def report(tmp_path, name):
    """The report of a map planned by meshgap_plan --report, or of cubicles' own .path by meshgap_report; with the
    scene it shows and its number of dense states, as the executables print them."""
    out = tmp_path / (name + ".html")
    if name == "blocked":
        # A planar problem with no path (a wall across the whole volume): meshgap.plan() writes the report of the
        # start and the goal (BIT* gives no approximate path).
        write_obj(tmp_path / "wall.obj", box(0.3, 6, 0.5, (0, 0, 0.5)))
        write_obj(tmp_path / "bar.obj", box(0.6, 0.2, 0.5, (0.25, 0.1, 0.5)))
        cfg = tmp_path / "blocked.cfg"
        cfg.write_text("[problem]\nname = blocked\nrobot = bar.obj\nworld = wall.obj\nstart.x = -3\nstart.y = 0.5\n"
                       "start.theta = 0\ngoal.x = 3\ngoal.y = -0.5\ngoal.theta = 0\n"
                       "volume.min.x = -5\nvolume.min.y = -5\nvolume.max.x = 5\nvolume.max.y = 5\n")
        path, summary = meshgap.plan(cfg, planner="bitstar", time=0.3, report=out)
        assert not summary["solved"] and path.shape == (0, 3)
        states = 2
    elif name == "cubicles":
        cfg = omplapp("cubicles.cfg")
        run = subprocess.run([executable("report"), "--cfg", str(cfg), "--path", str(omplapp("cubicles.path")),
                              "--out", str(out), "-q"], capture_output=True, text=True, timeout=300)
        assert run.returncode == 0, run.stderr
        states = int(re.search(r"\((\d+) dense states", run.stdout).group(1))
    else:
        cfg = MAPS / name / (name + ".cfg")
        run = subprocess.run([executable("plan"), "--cfg", str(cfg), "--time", "300", "--seed", "1", "-q",
                              "--report", str(out)], capture_output=True, text=True, timeout=300)
        assert run.returncode == 0, run.stderr
        states = int(re.search(r"\(dense: (\d+)\)", run.stdout).group(1))
    assert out.exists() and not [p for p in os.listdir(tmp_path) if ".tmp." in p]
    return out, meshgap.Scene.from_cfg(cfg), states


@pytest.mark.parametrize("name", ["hand_bowl", "slotted_wall", "cubicles", "blocked"])
def test_report_loads_and_draws(tmp_path, name):
    report_available()
    chromium()
    html, scene, states = report(tmp_path, name)
    png = tmp_path / (name + ".png")
    status, dom, console = browse(html, png)
    match = re.fullmatch(r"ready: loaded (\d+) triangles, (\d+) states", status)
    assert match, status
    assert int(match.group(1)) == scene.world_triangles + scene.robot_triangles
    assert int(match.group(2)) == states
    assert console == []
    assert "<table" in dom and ("<polyline" in dom) == (name != "blocked")  # the summary, the clearance plot

    from PIL import Image
    pixels = np.asarray(Image.open(png).convert("RGB")).astype(int)
    height, width, _ = pixels.shape
    view = pixels[int(0.08 * height):int(0.55 * height), int(0.05 * width):int(0.65 * width)]  # inside the 3D view
    colours = len(np.unique(view.reshape(-1, 3), axis=0))
    drawn = np.mean(np.any(view < 245, axis=2))
    robot_blue = np.sum((view[:, :, 2] > view[:, :, 0] + 60) & (view[:, :, 2] > view[:, :, 1] + 30))
    assert colours > 50 and drawn > 0.05 and robot_blue > 30, (colours, drawn, robot_blue)


def test_report_bad_input_writes_nothing(tmp_path):
    cfg = str(MAPS / "hand_bowl" / "hand_bowl.cfg")
    out = tmp_path / "report.html"
    cli = executable("report")
    assert cli_error([cli, "--cfg", cfg, "--path", str(tmp_path / "none.path"), "--out", str(out)]).endswith(
        "none.path: no such file")
    (tmp_path / "bad.path").write_text("1 2 3 0 0 0 1\n1 2 3\n")
    assert cli_error([cli, "--cfg", cfg, "--path", str(tmp_path / "bad.path"), "--out", str(out)]).startswith(
        str(tmp_path / "bad.path") + ":2: a state of this problem has 7 numbers")  # as every kind's, x y z q
    garbage = str(RESOURCES / "bad" / "garbage.obj")
    assert cli_error([cli, "--cfg", garbage, "--path", str(tmp_path / "bad.path"), "--out", str(out)]).startswith(
        garbage + ":1:")
    assert cli_error([cli, "--cfg", cfg, "--path", str(tmp_path / "bad.path")]).startswith("command line:")
    assert os.listdir(tmp_path) == ["bad.path"]
    # A folder that does not exist: the error names the file, nothing is left behind.
    (tmp_path / "one.path").write_text(" ".join(map(str, meshgap.Scene.from_cfg(cfg).start)) + "\n")
    assert "cannot" in cli_error([cli, "--cfg", cfg, "--path", str(tmp_path / "one.path"),
                                  "--out", str(tmp_path / "nowhere" / "r.html")])
    assert sorted(os.listdir(tmp_path)) == ["bad.path", "one.path"]
