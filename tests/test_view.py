"""The case viewer (crashsim.io.viewer): the page's data, its errors, the command line, and the
page itself in a real headless browser (Debian's chromium through selenium and
chromium-driver): it loads without console errors, draws, moves with the slider, poses the
vehicles as Result.state does, and shows the report's numbers.

The browser tests skip (with the reason) only when chromium or its driver is not installed;
scripts/test.sh installs both."""

from __future__ import annotations

import io
import json
import math
import os
import re
import shutil
import time
from pathlib import Path
from typing import Any

import crashsim as cs
import numpy as np
import pytest
from conftest import MISSING, SHARED_MESHES
from crashsim.analysis.report import report_schema
from crashsim.cli import CSV_FILE, GLB_FILE, main
from crashsim.io.scenefile import load_scene
from crashsim.io.viewer import ReportFileError, files, view, view_report
from crashsim.io.viewer.data import keep_samples, page_data
from crashsim.io.viewer.meshes import decimate, pack_array, pack_mesh, unpack_array
from crashsim.io.viewer.page import page_source
from scipy.interpolate import CubicHermiteSpline
from scipy.spatial.transform import Rotation, Slerp
from selenium import webdriver
from selenium.webdriver.chrome.service import Service

REPO = Path(__file__).resolve().parents[1]
EXAMPLES = REPO / "examples"

POSITION_TOL = 1e-6  # m: the page's pose against Result.state
ORIENTATION_TOL = 1e-9  # per quaternion component (1e-9 rad: 5e-9 m at 5 m from the CG)


def run_example(name: str) -> tuple[cs.Result, str]:
    case = load_scene(EXAMPLES / name)
    return case.simulate(duration=case.run.duration, dt=case.run.dt), case.title


@pytest.fixture(scope="module")
def seed() -> cs.Result:
    return run_example("seed-90deg.toml")[0]


@pytest.fixture(scope="module")
def three() -> cs.Result:
    return run_example("three-vehicles.toml")[0]


# -- the page's data, without a browser ---------------------------------------------------


def box_mesh(n: int) -> tuple[np.ndarray, np.ndarray]:
    """A 4 x 2 x 1.5 m box's surface as a fine grid: 12 n^2 triangles."""
    import trimesh

    mesh = trimesh.creation.box(extents=(4.0, 2.0, 1.5))
    while len(mesh.faces) < 12 * n * n:
        mesh = mesh.subdivide()
    return np.asarray(mesh.vertices), np.asarray(mesh.faces)


def test_decimation_keeps_a_small_mesh_and_meets_the_budget_of_a_large_one() -> None:
    v, f = box_mesh(40)  # 49,152 triangles
    same_v, same_f = decimate(v, f, len(f))
    assert len(same_f) == len(f) and np.array_equal(same_v[same_f], v[f])
    for budget in (20_000, 5_000, 500):
        dv, df = decimate(v, f, budget)
        assert 0.5 * budget <= len(df) <= budget  # the finest grid that fits: near the budget
        assert df.min() >= 0 and df.max() < len(dv)
        # clustered vertices are means of the originals: inside their bounding box
        assert np.all(dv >= v.min(axis=0) - 1e-12) and np.all(dv <= v.max(axis=0) + 1e-12)
        # the shape survives: the same bounding box within a cell or two
        assert np.allclose(np.ptp(dv, axis=0), np.ptp(v, axis=0), atol=0.2)
    again = decimate(v, f, 5_000)
    assert all(np.array_equal(a, b) for a, b in zip(again, decimate(v, f, 5_000), strict=True))


def test_packed_arrays_and_quantized_meshes_round_trip() -> None:
    x = np.random.default_rng(1).normal(size=(50, 3))
    assert np.array_equal(unpack_array(pack_array(x, "f8")).reshape(-1, 3), x)
    v, f = box_mesh(4)
    packed = pack_mesh(v - v.mean(axis=0), f, max_triangles=10**6)
    q = unpack_array(packed["positions"]).reshape(-1, 3).astype(np.float64)
    back = np.asarray(packed["lo"]) + q * np.asarray(packed["step"])
    assert packed["triangles"] == packed["triangles_source"] == len(f)
    assert packed["indices"]["dtype"] == "u2"
    # 16-bit positions over a 4 m box: within half a step (30 um)
    used = np.unique(f)
    assert np.max(np.abs(back - (v - v.mean(axis=0))[used])) <= 0.5 * max(packed["step"]) + 1e-12


def test_three_js_and_its_licence_are_installed_with_the_package() -> None:
    from importlib import resources

    three = resources.files("crashsim.io.viewer").joinpath("static", "three")
    assert "The MIT License" in three.joinpath("LICENSE").read_text(encoding="utf-8")
    assert 'REVISION="111"' in three.joinpath("three.min.js").read_text(encoding="utf-8")
    assert "OrbitControls" in three.joinpath("OrbitControls.js").read_text(encoding="utf-8")


def test_sample_thinning_keeps_events_and_the_end() -> None:
    t = np.linspace(0.0, 1.0, 10_001)
    assert np.array_equal(keep_samples(t, [], 20_000), np.arange(t.size))
    events = [t[1234], t[5678]]
    keep = keep_samples(t, events, 500)
    assert keep.size <= 500 and keep[0] == 0 and keep[-1] == t.size - 1
    assert {1234, 5678} <= set(keep.tolist())


def test_page_data_holds_the_report_as_it_is(seed: cs.Result) -> None:
    data = page_data(seed)
    assert data["report"] == cs.report(seed).to_dict()
    assert data["interpolation"] == "torque-free"
    assert [b["name"] for b in data["bodies"]] == seed.vehicles
    assert data["samples"]["kept"] == data["samples"]["total"] == seed.t.size
    assert json.loads(json.dumps(data, allow_nan=False)) == data


def test_bad_input_is_refused_with_typed_errors(seed: cs.Result, tmp_path: Path) -> None:
    bare = cs.Result(
        {
            "t": [0.0],
            "position": [[[0, 0, 0]]],
            "orientation": [[[1, 0, 0, 0]]],
            "velocity": [[[0, 0, 0]]],
            "angular_velocity": [[[0, 0, 0]]],
            "impacts": [],
            "contacts": [],
        },
        ["a"],
    )
    with pytest.raises(cs.SceneError, match="no scene"):
        view(bare, tmp_path / "case.html")
    with pytest.raises(cs.ParameterError, match="does not exist"):
        view(seed, tmp_path / "missing" / "case.html")
    with pytest.raises(cs.ParameterError, match="is a folder"):
        view(seed, tmp_path)
    with pytest.raises(cs.ParameterError, match="max_triangles"):
        view(seed, tmp_path / "case.html", max_triangles=0)
    assert not list(tmp_path.iterdir())  # nothing half-written


def test_report_files_missing_or_malformed(seed: cs.Result, tmp_path: Path) -> None:
    assert issubclass(ReportFileError, cs.InputError)
    assert (files.CSV_FILE, files.GLB_FILE) == (CSV_FILE, GLB_FILE)  # the names run writes
    report = tmp_path / "report.json"
    with pytest.raises(ReportFileError, match="no such file"):
        view_report(report)
    report.write_text("{not json", encoding="utf-8")
    with pytest.raises(ReportFileError, match="not JSON"):
        view_report(report)
    report.write_text(json.dumps({"schema": "something else"}), encoding="utf-8")
    with pytest.raises(ReportFileError, match="not a crashsim report"):
        view_report(report)
    doc = cs.report(seed).to_dict()
    report.write_text(json.dumps(doc), encoding="utf-8")
    with pytest.raises(ReportFileError, match=CSV_FILE):
        view_report(report)
    assert main(["run", str(EXAMPLES / "seed-90deg.toml"), "--out", str(tmp_path / "o")]) == 0
    out = tmp_path / "o"
    (out / GLB_FILE).unlink()
    with pytest.raises(ReportFileError, match="include_meshes"):
        view_report(out / "report.json")
    cs.report(seed).write_json(out / "report.json", include_meshes=True)  # meshes inside
    assert view_report(out / "report.json").name == "case.html"
    broken = dict(cs.report(seed).to_dict(include_meshes=True), impacts=[{"number": 1}])
    (out / "report.json").write_text(json.dumps(broken), encoding="utf-8")
    with pytest.raises(ReportFileError, match="impacts.0"):
        view_report(out / "report.json")


def test_the_report_path_and_numbers_are_checked_first(
    seed: cs.Result, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # issue 24: a missing report in a missing folder said "cannot write .../case.html"; a
    # folder, a named pipe or /dev/zero is not opened; deep nesting and a mass of 1e999
    # were tracebacks
    assert main(["view", str(tmp_path / "no" / "report.json")]) == 2
    assert capsys.readouterr().err == (
        f"crashsim: error: {tmp_path / 'no' / 'report.json'}: no such file\n"
    )
    folder = tmp_path / "folder.json"
    folder.mkdir()
    fifo = tmp_path / "pipe.json"
    os.mkfifo(fifo)
    zero = tmp_path / "zero.json"
    zero.symlink_to("/dev/zero")
    for path, kind in ((folder, "a folder"), (fifo, r"a named pipe \(FIFO\)"),
                       (zero, r"a character device \(a link to /dev/zero\)")):  # fmt: skip
        with pytest.raises(ReportFileError, match=f"is {kind}, not a report file"):
            view_report(path)
    report = tmp_path / "report.json"
    report.write_text("[" * 100_000 + "]" * 100_000, encoding="utf-8")
    assert main(["view", str(report)]) == 2
    assert (
        capsys.readouterr().err == f"crashsim: error: {report}: nested too deeply to be a "
        "crashsim report\n"
    )
    text = json.dumps(cs.report(seed).to_dict())
    mass = f'"mass": {seed.vehicle("red").mass!r}'
    assert mass in text
    for number in ("1e999", "-1E+400", "NaN", "Infinity", "1" + "0" * 400):
        report.write_text(text.replace(mass, f'"mass": {number}', 1), encoding="utf-8")
        assert main(["view", str(report)]) == 2
        err = capsys.readouterr().err
        assert err.startswith(f"crashsim: error: {report}: the number {number[:24]} is not finite")
    assert not (tmp_path / "case.html").exists()


def test_command_line_run_html_and_view(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLES / "seed-90deg.toml"), "--out", str(out), "--html"]) == 0
    assert (out / "case.html").stat().st_size > 500_000
    assert f"{out / 'case.html'}" in capsys.readouterr().out
    page = tmp_path / "elsewhere.html"
    assert main(["view", str(out / "report.json"), "--out", str(page)]) == 0
    assert page.read_text(encoding="utf-8").startswith("<!DOCTYPE html>")
    # bad input exits 2 with one line, before any run
    assert main(["run", str(EXAMPLES / "seed-90deg.toml"), "--html", "x.txt"]) == 2
    assert (
        main(["run", str(EXAMPLES / "seed-90deg.toml"), "--html", str(tmp_path / "no/x.html")]) == 2
    )
    assert main(["view", str(tmp_path / "nothing.json")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 3 and all(e.startswith("crashsim: error:") for e in err)


def test_view_keeps_the_richer_page_of_run_html(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Was: `crashsim view out/report.json` silently replaced the case.html that `run --html`
    # wrote from the Result (losing the tyre marks, zones, rest outlines, overlap points).
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLES / "seed-90deg.toml"), "--out", str(out), "--html"]) == 0
    page = out / "case.html"
    rich = page.read_bytes()
    assert page_source(page) == "run"
    capsys.readouterr()
    assert main(["view", str(out / "report.json")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"crashsim: error: {page} exists and is a ")
    assert "--force" in err and "--out" in err
    assert page.read_bytes() == rich  # untouched
    with pytest.raises(cs.ParameterError, match="written from the run"):
        view_report(out / "report.json")
    # another file is not ours either; a page from a report is replaced (nothing is lost)
    other = tmp_path / "notes.html"
    other.write_text("<p>my notes</p>", encoding="utf-8")
    with pytest.raises(cs.ParameterError, match="not a case page written from a report"):
        view_report(out / "report.json", other)
    assert main(["view", str(out / "report.json"), "--force"]) == 0
    assert page_source(page) == "report" and page.read_bytes() != rich
    assert view_report(out / "report.json") == page  # again: a report's page, replaced
    assert page_source(page) == "report"


def test_the_report_marks_a_run_on_the_ground(seed: cs.Result) -> None:
    import jsonschema

    plain = cs.report(seed).to_dict()
    assert "on_ground" not in plain["run"]
    grounded = cs.Result.__new__(cs.Result)
    grounded.__dict__.update(seed.__dict__, on_ground=True)
    doc = cs.report(grounded).to_dict()
    assert doc["run"]["on_ground"] is True
    jsonschema.validate(doc, report_schema())
    assert page_data(grounded)["interpolation"] == "hermite"


# -- a duck-typed result with what the whole-event work adds --------------------------------


@pytest.fixture(scope="module")
def event() -> cs.Result:
    """A whole event: a wheeled box car, its wheels locked, skids at 12 m/s through a grass
    zone into a wall obstacle on the ground and runs to rest (tyre marks, a rest position)."""
    car = cs.Vehicle.box(4.6, 1.8, 1.4, mass=1500.0, name="red", ground_clearance=0.15,
                         cg_height=0.55, wheelbase=2.7, track=1.55, wheel_radius=0.3,
                         cg_to_front_axle=1.1)  # fmt: skip
    grass = cs.FrictionZone([(-6.0, -4.0), (-1.0, -4.0), (-1.0, 4.0), (-6.0, 4.0)], "grass")
    scene = cs.Scene(ground=cs.Ground(zones=[grass]))
    locked = cs.DriverInputs(wheel_states=[("all", "locked", 0.0)])
    scene.add(car, (-8.0, 0.0), heading=0.0, velocity=(12.0, 0.0, 0.0), inputs=locked)
    scene.add_obstacle(cs.Obstacle.wall(6.0, 0.3, 1.0), (4.0, 0.0))
    return scene.run(until="rest", max_duration=10.0)


def test_page_data_reads_what_a_whole_event_result_adds(seed: cs.Result, event: cs.Result) -> None:
    data = page_data(event)
    names = [(b["name"], b["kind"]) for b in data["bodies"]]
    assert names == [("red", "vehicle"), ("wall", "obstacle")]
    assert data["ground"]["zones"][0]["friction"] == pytest.approx(0.35)
    red = data["bodies"][0]
    marks = event.tyre_marks("red")
    assert len(red["tyre_marks"]) == sum(len(m) for m in marks.values()) > 0
    rest = event.rest("red")
    assert rest is not None and red["rest"]["time"] == pytest.approx(rest.time)
    assert page_data(seed)["ground"] == {"modelled": False, "height": 0.0, "zones": []}


# -- the page in a headless browser ----------------------------------------------------------


def _browser() -> tuple[str, str] | None:
    binary = next(
        (p for p in map(shutil.which, ("chromium", "chromium-browser", "google-chrome")) if p),
        None,
    )
    driver = shutil.which("chromedriver") or (
        "/usr/bin/chromedriver" if Path("/usr/bin/chromedriver").exists() else None
    )
    return (binary, driver) if binary and driver else None


def new_driver(width: int = 1400, height: int = 900) -> webdriver.Chrome:
    found = _browser()
    if found is None:
        pytest.skip(
            "chromium and chromedriver are not installed (Debian: apt-get install chromium "
            "chromium-driver; scripts/test.sh does it)"
        )
    binary, driver = found
    options = webdriver.ChromeOptions()
    options.binary_location = binary
    for arg in (
        "--headless=new",
        "--no-sandbox",
        "--disable-dev-shm-usage",
        "--use-angle=swiftshader",  # WebGL on the CPU: no GPU on a test machine
        "--enable-unsafe-swiftshader",
        f"--window-size={width},{height}",
    ):
        options.add_argument(arg)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(driver), options=options)


@pytest.fixture(scope="module")
def browser() -> Any:
    d = new_driver()
    yield d
    d.quit()


def open_page(driver: webdriver.Chrome, path: Path, timeout: float = 60.0) -> list[dict]:
    """Loads a page and waits until it has drawn; returns the console's entries."""
    driver.get(path.resolve().as_uri())
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        ready, error = driver.execute_script("return [crashsim.ready, crashsim.error]")
        if error:
            pytest.fail(f"the page failed: {error}")
        if ready:
            return driver.get_log("browser")
        time.sleep(0.05)
    pytest.fail(f"the page did not draw within {timeout} s")


def canvas_png(driver: webdriver.Chrome) -> np.ndarray:
    from matplotlib.image import imread

    png = driver.find_element("id", "canvas").screenshot_as_png
    return imread(io.BytesIO(png), format="png")[..., :3]


def check_poses(
    driver: webdriver.Chrome, result: Any, times: list[float], expect: Any = None
) -> float:
    """The page's state at each time against Result.state (or ``expect(name, t)``);
    returns the largest position error (m)."""
    worst = 0.0
    for t in times:
        for name in result.vehicles:
            page = driver.execute_script(
                "return crashsim.state(arguments[0], arguments[1])", name, t
            )
            want = (expect or result.state)(name, t)
            dp = float(np.max(np.abs(np.array(page["position"]) - want["position"])))
            q_page, q_want = np.array(page["orientation"]), np.asarray(want["orientation"])
            dq = float(min(np.max(np.abs(q_page - q_want)), np.max(np.abs(q_page + q_want))))
            assert dp <= POSITION_TOL, (name, t, dp)
            assert dq <= ORIENTATION_TOL, (name, t, dq)
            worst = max(worst, dp)
    return worst


def probe_times(result: cs.Result, n: int = 25) -> list[float]:
    """Random times in the run plus every impact's instants and the ends."""
    rng = np.random.default_rng(7)
    t0, t1 = float(result.t[0]), float(result.t[-1])
    times = list(rng.uniform(t0, t1, n))
    for imp in result.impacts:
        times += [imp.first_contact_time, imp.time, imp.time + 3.3e-4]
    return [*times, t0, t1]


def test_seed_page_loads_draws_and_moves_with_the_slider(
    browser: webdriver.Chrome, seed: cs.Result, tmp_path: Path
) -> None:
    logs = open_page(browser, view(seed, tmp_path / "case.html"))
    assert [e for e in logs if e["level"] in ("SEVERE", "WARNING")] == []
    assert browser.execute_script("return THREE.REVISION") == "111"
    before = canvas_png(browser)
    # not blank: many colours, and much of it unlike the background
    assert len(np.unique((before * 255).astype(int).reshape(-1, 3), axis=0)) > 50
    assert np.mean(np.any(np.abs(before - before[2, 2]) > 0.05, axis=-1)) > 0.2
    # move the slider as a user does (its value, then the input event)
    t = browser.execute_script(
        "const s = document.getElementById('slider'); s.value = 80000;"
        "s.dispatchEvent(new Event('input')); return crashsim.time();"
    )
    span = float(seed.t[-1] - seed.t[0])
    assert t == pytest.approx(float(seed.t[0]) + 0.8 * span, abs=1e-12)
    after = canvas_png(browser)
    assert np.mean(np.any(np.abs(after - before) > 0.05, axis=-1)) > 0.01
    # the drawn poses are the result's at the slider's time
    poses = browser.execute_script("return crashsim.poses()")
    for name in seed.vehicles:
        want = seed.state(name, t)["position"]
        assert np.max(np.abs(np.array(poses[name]["position"]) - want)) <= POSITION_TOL
        assert np.max(np.abs(np.array(poses[name]["drawn"]) - want)) <= 1e-4  # float32 scene
    assert (
        browser.execute_script("return getComputedStyle(document.getElementById('status')).display")
        == "none"
    )


def check_cells(driver: webdriver.Chrome, report: dict[str, Any]) -> list[list[str]]:
    """Every element of the page that carries a report path shows that value of ``report``
    to the digits shown; returns the [path, text] pairs."""
    cells = driver.execute_script(
        "return Array.from(document.querySelectorAll('[data-path]'))"
        ".map((e) => [e.getAttribute('data-path'), e.textContent])"
    )
    for path, text in cells:
        value: Any = report
        for key in path.split("."):
            value = value[int(key)] if isinstance(value, list) else value[key]
        if value is None:
            assert text in ("unknown", "n/a"), (path, text)
            continue
        decimals = len(text.split(".")[1]) if "." in text else 0
        assert abs(float(text) - value) <= 0.5 * 10.0**-decimals + 1e-9, (path, text, value)
    return cells


def test_the_tables_show_the_reports_numbers(
    browser: webdriver.Chrome, three: cs.Result, tmp_path: Path
) -> None:
    open_page(browser, view(three, tmp_path / "case.html"))
    report = cs.report(three).to_dict()
    cells = check_cells(browser, report)
    # every impact's table: its times, |J|, energy, and per vehicle delta-V, EDR components,
    # PDOF, clock, energy, EES, crush
    party_keys = [
        "delta_v.magnitude",
        "delta_v.longitudinal",
        "delta_v.lateral",
        "pdof_deg",
        "clock",
        "yaw_rate_change_deg_s",
        "speed_before",
        "speed_after",
        "effective_mass",
        "energy.share",
        "energy.ees",
        "deformation.bounding_box",
        "deformation.mesh",
        "deformation.overlap_depth",
        "deformation.spring_model.max_crush",
        "deformation.spring_model.residual_crush",
    ]
    shown = {path for path, _ in cells}
    for k, imp in enumerate(report["impacts"]):
        for key in ("first_contact_time", "exchange_time", "closing_speed", "energy.dissipated"):
            assert f"impacts.{k}.{key}" in shown
        # the impact's figures, each in a row of its own label (ImpactReport.figures)
        assert [f"impacts.{k}.figures.{m}.value" in shown for m in range(len(imp["figures"]))] == [
            True
        ] * len(imp["figures"]) and len(imp["figures"]) == 2
        for j in range(len(imp["parties"])):
            missing = [key for key in party_keys if f"impacts.{k}.parties.{j}.{key}" not in shown]
            assert missing == []
    text = browser.find_element("id", "report").text
    for imp in report["impacts"]:
        assert f"Impact {imp['number']}: {imp['vehicles'][0]} (1)" in text
        assert all(f["label"] in text for f in imp["figures"])
    for v in report["scene"]["vehicles"]:
        assert f"{v['mass']:.1f}" in text
    assert len(browser.find_elements("css selector", "svg.plot")) == len(three.vehicles)


def test_poses_equal_result_state(
    browser: webdriver.Chrome, three: cs.Result, tmp_path: Path
) -> None:
    open_page(browser, view(three, tmp_path / "case.html"))
    assert any(np.ptp(three.trajectory(n).orientation, axis=0).max() > 0.01 for n in three.vehicles)
    check_poses(browser, three, probe_times(three))


def test_poses_from_thinned_samples_stay_exact_without_a_ground(
    browser: webdriver.Chrome, three: cs.Result, tmp_path: Path
) -> None:
    # 60 of 509 samples: the page carries the state over up to 10 ms by torque-free motion
    open_page(browser, view(three, tmp_path / "case.html", max_samples=60))
    kept = browser.execute_script(
        "return JSON.parse(document.getElementById('crashsim-data').textContent).samples"
    )
    assert kept["kept"] <= 60 < kept["total"]
    check_poses(browser, three, probe_times(three))


def test_poses_on_the_ground_are_hermite_and_slerp(
    browser: webdriver.Chrome, three: cs.Result, tmp_path: Path
) -> None:
    grounded = cs.Result.__new__(cs.Result)
    grounded.__dict__.update(three.__dict__, on_ground=True)
    open_page(browser, view(grounded, tmp_path / "case.html"))

    def expect(name: str, t: float) -> dict[str, np.ndarray]:
        # scipy's Hermite spline and slerp, between the samples around t (the last at t)
        tr = three.trajectory(name)
        k = int(np.searchsorted(tr.t, t, side="right")) - 1
        if tr.t[k] == t:
            return {"position": tr.position[k], "orientation": tr.orientation[k]}
        seg = slice(k, k + 2)
        spline = CubicHermiteSpline(tr.t[seg], tr.position[seg], tr.velocity[seg])
        q = tr.orientation[seg][:, [1, 2, 3, 0]]
        xyzw = Slerp(tr.t[seg], Rotation.from_quat(q))([t]).as_quat()[0]
        wxyz = np.array([xyzw[3], *xyzw[:3]])
        return {"position": spline(t), "orientation": wxyz}

    check_poses(browser, three, probe_times(three), expect)


def test_the_page_from_report_json_matches_the_run(
    browser: webdriver.Chrome, seed: cs.Result, tmp_path: Path
) -> None:
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLES / "seed-90deg.toml"), "--out", str(out)]) == 0
    logs = open_page(browser, view_report(out / "report.json"))
    assert [e for e in logs if e["level"] == "SEVERE"] == []
    check_poses(browser, seed, probe_times(seed, 10))
    shown = browser.execute_script(
        "return document.querySelector(arguments[0]).textContent",
        '[data-path="impacts.0.parties.0.delta_v.longitudinal"]',
    )
    want = cs.report(seed).impacts[0].parties[0].longitudinal
    assert float(shown) == pytest.approx(want, abs=5e-4)


def test_whole_event_parts_are_drawn(
    browser: webdriver.Chrome, event: cs.Result, tmp_path: Path
) -> None:
    logs = open_page(browser, view(event, tmp_path / "case.html"))
    assert [e for e in logs if e["level"] == "SEVERE"] == []
    labels = browser.execute_script(
        "return Array.from(document.querySelectorAll('#labels .label')).map((e) => e.textContent)"
    )
    assert any(re.fullmatch(r".*grass.*: friction 0\.35", x) for x in labels), labels
    assert any(re.fullmatch(r"red at rest \(t = [0-9.]+ s\)", x) for x in labels)
    assert "wall" in browser.execute_script("return Object.keys(crashsim.poses())")
    # the vehicles' wheels as run, in the scene inputs' table (issue 19: tyre, steering,
    # suspension listed)
    table = browser.find_element("id", "inputs").text
    for needed in ("tyre linear, 1 per 10.0 deg", "steering ratio, Ackermann", "roll gradient",
                   "springs 1.30, 1.30, 1.30, 1.30 Hz", "ABS on"):  # fmt: skip
        assert needed in table, (needed, table)


CYCLIST = "cyclist-sedan-side-40kmh.toml"
CYCLIST_RUN = 0.08  # s: the legs, the frame and the front wheel touch the car (0.3 s wall)


@pytest.fixture(scope="module")
def cyclist_out(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The cyclist example, run for CYCLIST_RUN by the command line with its case page."""
    out = tmp_path_factory.mktemp("cyclist")
    args = ["run", str(EXAMPLES / CYCLIST), "--out", str(out), "--duration", str(CYCLIST_RUN)]
    assert main([*args, "--html"]) == 0
    return out


def test_a_cyclist_is_one_person_on_the_page(
    browser: webdriver.Chrome, cyclist_out: Path, tmp_path: Path
) -> None:
    """The page of a run and the page of its report.json list the cyclist once (one legend
    entry, one label, one speed plot, no column per body in the inputs), pose its 19 bodies
    as the run does, and show its panel's numbers from the report."""
    report = json.loads((cyclist_out / "report.json").read_text(encoding="utf-8"))
    (entry,) = report["pedestrians"]
    case = load_scene(EXAMPLES / CYCLIST)
    result = case.simulate(duration=CYCLIST_RUN, dt=case.run.dt)
    from_report = view_report(cyclist_out / "report.json", tmp_path / "from-report.html")
    for page in (cyclist_out / "case.html", from_report):
        logs = open_page(browser, page)
        assert [e for e in logs if e["level"] in ("SEVERE", "WARNING")] == []
        legend = browser.find_element("id", "legend").text
        assert "car cyclist (cyclist, bicycle)" in legend and "cyclist/" not in legend
        browser.execute_script("crashsim.setTime(0.05)")
        labels = browser.execute_script(
            "return Array.from(document.querySelectorAll('#labels .label'))"
            ".filter((e) => e.style.display !== 'none').map((e) => e.textContent)"
        )
        assert sorted(labels) == ["car", "cyclist"]
        plots = browser.find_elements("css selector", "svg.plot")
        assert [p.get_attribute("data-vehicle") for p in plots] == ["car", "cyclist"]
        heads = browser.execute_script(
            "return Array.from(document.querySelector('#inputs table.data').rows[0].cells)"
            ".map((c) => c.textContent)"
        )
        assert heads == ["vehicle", "car", "unit"]
        # the panel: the rider's and the bicycle's throw distances, as the report gives them
        panel = browser.find_element("id", "person-cyclist")
        for path, value in (
            ("pedestrians.0.struck_by.0.throw_distance", entry["struck_by"][0]["throw_distance"]),
            ("pedestrians.0.bicycle.struck_by.0.throw_distance",
             entry["bicycle"]["struck_by"][0]["throw_distance"]),
        ):  # fmt: skip
            shown = panel.find_element("css selector", f"[data-path='{path}']").text
            assert shown == f"{value:.2f}" and value > 0.1
        assert "whole-body CG at 0.08 s" in panel.text
        # the rider's trajectory type, as the report gives it (the bicycle's throw has none)
        assert f"trajectory {entry['struck_by'][0]['trajectory']}" in panel.text
        assert panel.text.count("trajectory") == 1
        paths = {p for p, _ in check_cells(browser, report)}
        assert "pedestrians.0.rest.0" in paths and "pedestrians.0.bicycle.rest_speed" in paths
        # each body still posed as the run, and moving
        check_poses(browser, result, [0.0, 0.021, 0.05, CYCLIST_RUN])
        heads_at = [browser.execute_script("return crashsim.state('cyclist/head', arguments[0])"
                                           ".position", t) for t in (0.0, CYCLIST_RUN)]  # fmt: skip
        assert np.linalg.norm(np.subtract(*heads_at)) > 0.3
    # a click on the person's title brings the camera to it: the whole-body CG in the middle
    browser.execute_script("crashsim.setTime(arguments[0])", CYCLIST_RUN)
    before = canvas_png(browser)
    panel.find_element("tag name", "h3").click()
    after = canvas_png(browser)
    assert np.mean(np.any(np.abs(after - before) > 0.05, axis=-1)) > 0.2
    centre = browser.execute_script("return crashsim.focusTarget()")
    cg = sum(result.state(s.name, CYCLIST_RUN)["position"] * s.mass
             for s in case.scene.cyclists["cyclist"].rider.segments) / 75.0  # fmt: skip
    assert np.max(np.abs(np.array(centre) - cg)) < 1e-6


@pytest.mark.skipif(not SHARED_MESHES.is_dir(), reason=MISSING)
def test_real_meshes_page(browser: webdriver.Chrome, tmp_path: Path) -> None:
    result, title = run_example("mesh-sedan-into-pickup.toml")
    path = view(result, tmp_path / "case.html", title=title, max_triangles=600)
    open_page(browser, path)
    data = browser.execute_script(
        "return JSON.parse(document.getElementById('crashsim-data').textContent).bodies"
        ".map((b) => [b.mesh.triangles_source, b.mesh.triangles])"
    )
    for source, drawn in data:
        assert drawn <= 600 < source
    check_poses(browser, result, probe_times(result, 8))


def test_views_buttons_move_the_camera(
    browser: webdriver.Chrome, seed: cs.Result, tmp_path: Path
) -> None:
    open_page(browser, view(seed, tmp_path / "case.html"))
    shots = []
    for button in ("view-top", "view-side", "view-3d"):
        browser.find_element("id", button).click()
        shots.append(canvas_png(browser))
    for a, b in ((0, 1), (1, 2), (0, 2)):
        assert np.mean(np.any(np.abs(shots[a] - shots[b]) > 0.05, axis=-1)) > 0.05
    assert math.isfinite(browser.execute_script("return crashsim.firstDrawMs"))
