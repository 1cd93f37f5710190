"""Articulated vehicles through the API (issue 21, docs/joints.md): a tractor and its
semitrailer, a car and its centre-axle trailer put together by Scene.add(trailers=...), against
closed forms (low-speed off-tracking on a constant radius, the static kingpin load), trailer
brakes, and refusals by name."""

from __future__ import annotations

import math

import crashsim as cs
import numpy as np
import pytest
from crashsim.errors import ParameterError, SceneError
from crashsim.result import rotation_matrix

G = 9.80665
L1, F5, L2 = 3.8, 0.3, 10.0  # tractor wheelbase, fifth-wheel lead, kingpin to trailer axle (m)


def _tractor(**kw: object) -> cs.Vehicle:
    args = dict(
        mass=7000.0,
        wheelbase=L1,
        tandem_spread=1.3,
        driven_axles=1,
        fifth_wheel_ahead=F5,
        fifth_wheel_height=1.2,
        cg_to_front_axle=1.6,
        cg_height=1.0,
        track=2.0,
        radius=0.5,
        length=6.0,
        steering_reference="centre",
        name="tractor",
    )
    args.update(kw)
    return cs.tractor(**args)  # type: ignore[arg-type]


def _semi(**kw: object) -> cs.Vehicle:
    args = dict(
        length=13.6,
        width=2.5,
        height=2.7,
        mass=12000.0,
        ground_clearance=1.25,
        coupler=1.0,
        coupler_height=1.2,
        axles=[1.0 + L2],
        track=2.0,
        radius=0.5,
        cg_height=2.0,
        name="semi",
    )
    args.update(kw)
    return cs.Trailer.box("semitrailer", **args)  # type: ignore[arg-type]


def _circle(points: np.ndarray) -> tuple[float, np.ndarray]:
    """Least-squares circle through (n, 2) points: radius and centre."""
    a = np.c_[2 * points, np.ones(len(points))]
    c = np.linalg.lstsq(a, (points**2).sum(axis=1), rcond=None)[0]
    return math.sqrt(c[2] + c[0] ** 2 + c[1] ** 2), c[:2]


def _path(result: cs.Result, name: str, body_point: np.ndarray) -> np.ndarray:
    """A body point's world path (k, 3)."""
    tr = result.trajectory(name)
    r = rotation_matrix(tr.orientation)  # (k, 3, 3)
    return tr.position + r @ body_point


def test_low_speed_off_tracking_matches_the_kinematic_closed_form() -> None:
    # Steady low-speed turn (0.5 m/s, so the tyres hardly slip): the tractor's front axle
    # centre on R1, its rear axle on sqrt(R1^2 - L1^2), the kingpin on sqrt(Rr^2 + F5^2),
    # the trailer's axle on sqrt(R5^2 - L2^2) (SAE J695's steady-state off-tracking for
    # single axles). Within 1 % of the off-tracking R1 - Rt.
    tractor, semi = _tractor(), _semi()
    delta = math.radians(15.0)
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    steer = cs.DriverInputs(steer=np.array([[0.0, delta], [1.0, delta]]))
    scene.add(tractor, (0, 0), heading=0.0, velocity=(0.5, 0, 0), inputs=steer, trailers=[semi])
    result = scene.run(320.0, record_interval=1.0)
    front = tractor.wheels.centers[:2].mean(axis=0) * [1, 1, 0]
    axle = semi.wheels.centers.mean(axis=0) * [1, 1, 0]
    settled = slice(len(result.t) // 2, None)
    r1, c1 = _circle(_path(result, "tractor", front)[settled, :2])
    rt, ct = _circle(_path(result, "semi", axle)[settled, :2])
    r5 = math.sqrt(r1**2 - L1**2 + F5**2)
    expected = r1 - math.sqrt(r5**2 - L2**2)
    assert r1 - rt == pytest.approx(expected, rel=1e-2)
    assert np.linalg.norm(c1 - ct) < 0.02  # one centre of turn
    assert r1 == pytest.approx(L1 / math.sin(delta), rel=1e-3)


def test_a_parked_tractor_carries_the_kingpin_load_statics_gives() -> None:
    tractor, semi = _tractor(), _semi(axles=[9.9, 11.2, 12.5], mass=20000.0)
    scene = cs.Scene(ground=cs.Ground())
    scene.add(tractor, (0, 0), heading=0.3, trailers=[semi])
    result = scene.run(2.0)
    joint = result.joints["tractor-semi"]
    assert joint.kind == "fifth_wheel"
    expected = semi.wheels.coupling_load(semi.mass)  # moments about the tridem's axles
    assert joint.force[-1, 2] == pytest.approx(expected, rel=1e-2)
    tractor_wheels = result.wheels("tractor").load[:, -1].sum()
    assert tractor_wheels == pytest.approx(tractor.mass * G + expected, rel=1e-2)
    # Its springs are set for the combination: it stands level, the plate unpitched.
    assert np.abs(joint.angle("pitch")).max() < math.radians(0.1)
    assert np.abs(result.trajectory("tractor").position[:, 2] - 1.0).max() < 1e-3


def test_trailer_brakes_stop_the_combination_sooner() -> None:
    def stop(trailer_brakes: bool) -> float:
        tractor, semi = _tractor(), _semi()
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        brake = cs.DriverInputs(brake=0.5)
        item = (semi, brake) if trailer_brakes else semi
        scene.add(tractor, (0, 0), heading=0.0, velocity=(15, 0, 0), inputs=brake, trailers=[item])
        result = scene.run(until="rest", max_duration=30.0)
        return float(result.rest("tractor").position[0])

    with_brakes, without = stop(True), stop(False)
    # Braking at half the friction on every wheel: the stop is v^2 / (2 * 0.5 mu g), within
    # 3 % (the tractor's and trailer's own load shifts); without the trailer's brakes, longer.
    assert with_brakes == pytest.approx(15.0**2 / (2 * 0.5 * 0.8 * G), rel=3e-2)
    assert without > 1.5 * with_brakes


def _car_and_trailer(tyre: cs.Tyre | None = None) -> tuple[cs.Vehicle, cs.Vehicle]:
    """A generated sedan with a ball 15 cm behind its rear, 0.45 m up, and a 750 kg centre-axle
    trailer (3.0 m box, its axle 1.7 m behind its front, the coupler 1.2 m ahead of it), both
    on ``tyre`` (None: the default)."""
    car = cs.Vehicle.generate("sedan", name="car", tyre=tyre)
    lo = (car.mesh.bounds[0] - car.cg)[0]
    car = car.with_hitch(car.cg + [lo - 0.15, 0.0, 0.45 - car.cg[2]], "ball")
    trailer = cs.Trailer.box(
        "centre_axle",
        length=3.0,
        width=1.6,
        height=1.2,
        mass=750.0,
        ground_clearance=0.5,
        coupler=1.2,
        coupler_height=0.45,
        axles=[1.7],
        track=1.4,
        radius=0.3,
        cg_height=0.7,
        cg_from_front=1.5,
        name="trailer",
        tyre=tyre,
    )
    return car, trailer


def test_a_car_tows_a_centre_axle_trailer_on_its_ball() -> None:
    car, trailer = _car_and_trailer()
    nose = trailer.wheels.coupling_load(trailer.mass)
    assert 0.0 < nose < 0.15 * trailer.mass * G
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(car, (0, 0), heading=0.0, velocity=(20, 0, 0), trailers=[trailer])
    result = scene.run(2.0)
    joint = result.joints["car-trailer"]
    assert joint.kind == "spherical"
    assert joint.force[-1, 2] == pytest.approx(nose, rel=1e-2)
    assert result.impacts == [] and result.contacts == []


def test_bad_combinations_are_refused_by_name() -> None:
    tractor, semi = _tractor(), _semi()
    car = cs.Vehicle.generate("sedan", name="car")
    scene = cs.Scene(ground=cs.Ground())
    with pytest.raises(SceneError, match="has no hitch"):
        scene.add(car, (0, 0), trailers=[semi])
    ball = car.renamed("car2").with_hitch(car.cg + [-2.8, 0, -0.1], "ball")
    with pytest.raises(SceneError, match="kingpin does not go on a ball"):
        cs.Scene(ground=cs.Ground()).add(ball, (0, 0), trailers=[semi])
    with pytest.raises(SceneError, match="more than 10 times as heavy"):
        cs.Scene(ground=cs.Ground()).add(tractor, (0, 0), trailers=[_semi(mass=80000.0)])
    with pytest.raises(SceneError, match="coupler stands"):
        cs.Scene(ground=cs.Ground()).add(tractor, (0, 0), trailers=[_semi(coupler_height=1.4)])
    with pytest.raises(ParameterError, match="outside the body"):
        car.with_hitch(car.cg + [-5.0, 0, 0], "ball")
    with pytest.raises(ParameterError, match="kind 'hook' is unknown"):
        car.with_hitch(car.cg, "hook")
    with pytest.raises(ParameterError, match="trailer kind"):
        cs.Trailer.box("dolly", **{k: v for k, v in _semi_args().items()})


def _semi_args() -> dict[str, object]:
    return dict(
        length=13.6,
        width=2.5,
        height=2.7,
        mass=12000.0,
        ground_clearance=1.25,
        coupler=1.0,
        coupler_height=1.2,
        axles=[11.0],
        track=2.0,
        radius=0.5,
    )


def test_the_presets_come_from_the_combination_classes_and_stand_level() -> None:
    from crashsim.vehicles.combination_data import combination_class

    tractor = cs.Vehicle.generate("tractor")
    data = combination_class("tractor_6x4")
    assert tractor.mass == data["mass"].value
    assert tractor.inertia[2, 2] == pytest.approx(data["yaw_inertia"].value)
    assert tractor.hitch is not None and tractor.hitch.kind == "fifth_wheel"
    van = cs.Trailer.generate("box_van")
    van_data = combination_class("box_van")
    assert van.mass == van_data["mass_laden"].value
    assert cs.Trailer.generate("box_van", laden=False).mass == van_data["mass"].value
    # The caravan's axle is placed for the class's nose-load share (6 %).
    caravan = cs.Trailer.generate("caravan")
    share = caravan.wheels.coupling_load(caravan.mass) / (caravan.mass * G)
    assert share == pytest.approx(combination_class("caravan")["nose_load_share"].value)
    # The laden combination stands level with its kingpin load as statics gives it.
    scene = cs.Scene(ground=cs.Ground())
    scene.add(tractor, (0, 0), heading=0.0, trailers=[van])
    result = scene.run(1.0)
    joint = result.joints["tractor-box_van"]
    assert joint.force[-1, 2] == pytest.approx(van.wheels.coupling_load(van.mass), rel=1e-2)
    assert np.abs(joint.angle("pitch")).max() < math.radians(0.1)
    with pytest.raises(ParameterError, match="has no builder"):
        cs.Trailer.generate("drawbar_trailer")


def test_a_study_varies_a_combination_as_one() -> None:
    # The tractor's speed and heading: the trailer moves with it (its joint's frames meet,
    # the bodies agree), in a batch as in Scene.with_, bit for bit; varying both units'
    # state is refused.
    from crashsim.batch import run_batch
    from crashsim.studies.paths import overrides

    tractor, semi = _tractor(), _semi()
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(tractor, (0, 0), heading=0.0, velocity=(15, 0, 0), trailers=[semi])
    values = {"tractor.speed": [10.0, 20.0], "tractor.heading": [0.0, 0.5]}
    arrays = overrides(scene, values)
    batch = run_batch(scene, arrays, duration=1.0, dt=1e-3)
    assert batch.errors == []
    one = scene.with_({"tractor.speed": 20.0, "tractor.heading": 0.5}).run(1.0)
    semi_v, tractor_v = one.trajectory("semi").velocity, one.trajectory("tractor").velocity
    assert np.linalg.norm(semi_v[0] - tractor_v[0]) < 1e-12
    assert semi_v[0] == pytest.approx(20.0 * np.array([math.cos(0.5), math.sin(0.5), 0.0]))
    x_key = next(k for k in batch.columns if k.startswith("semi") and "x" in k.split(".")[-1])
    assert batch.columns[x_key][1] == one.trajectory("semi").position[-1][0]
    from crashsim.errors import StudyError

    with pytest.raises(StudyError, match="joined"):
        overrides(scene, {"tractor.speed": [10.0], "semi.speed": [10.0]})


def test_a_tridem_shares_its_load_equally_while_braking() -> None:
    # A load-equalising tridem (the default): the three axles carry equal loads at rest and
    # while the combination brakes; on their own springs the front axle takes more under
    # braking (load moves forward); the stop is the same (every wheel braked at 0.5 mu Fz).
    axle_loads, stops = {}, {}
    for sharing in (True, False):
        tractor = cs.tractor("tractor_6x4", load_sharing=sharing)
        van = cs.Trailer.generate("box_van", load_sharing=sharing)
        assert bool(van.wheels.load_groups) is sharing
        static = van.wheels.static_loads(van.mass).reshape(-1, 2).sum(axis=1)
        if sharing:
            assert np.ptp(static) < 1e-6 * static.mean()
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        brake = cs.DriverInputs(brake=0.5)
        scene.add(tractor, (0, 0), heading=0.0, velocity=(20, 0, 0), inputs=brake,
                  trailers=[(van, brake)])  # fmt: skip
        result = scene.run(3.0, record_interval=0.01)
        steady = result.t >= 2.0  # the pitch after the brakes came on has died down
        loads = result.wheels("box_van").load[:, steady].mean(axis=1)
        axle_loads[sharing] = loads.reshape(-1, 2).sum(axis=1)
        stops[sharing] = result.trajectory("tractor_6x4").velocity[-1, 0]
        # The trailer's wheels and its kingpin carry its weight (steady braking: within 1 %).
        kingpin = result.joints["tractor_6x4-box_van"].force[steady, 2].mean()
        assert axle_loads[sharing].sum() + kingpin == pytest.approx(van.mass * G, rel=1e-2)
    shared, own = axle_loads[True], axle_loads[False]
    assert np.ptp(shared) < 1e-6 * shared.mean()
    assert own[0] > 1.5 * own[2]
    assert stops[True] == pytest.approx(stops[False], abs=1e-3)
    with pytest.raises(ParameterError, match="two load groups"):
        cs.Wheels.custom(
            [[1, 0.8, -0.3], [1, -0.8, -0.3], [-1, 0.8, -0.3], [-1, -0.8, -0.3]],
            0.3,
            [True, True, False, False],
            load_groups=[[0, 2], [2, 3]],
        )


def test_a_fit_finds_the_tractors_speed_from_both_units_rest() -> None:
    # Both units braked at 0.6 of the friction to rest from 18 m/s: the fit of the tractor's
    # speed (the trailer moving with it) from the two rest positions finds 18 m/s.
    from crashsim.studies.evidence import RestPosition

    def scene(speed: float) -> cs.Scene:
        s = cs.Scene(ground=cs.Ground(friction=0.7))
        brake = cs.DriverInputs(brake=0.6)
        s.add(_tractor(), (0, 0), heading=0.0, velocity=(speed, 0, 0), inputs=brake,
              trailers=[(_semi(), brake)])  # fmt: skip
        return s

    truth = scene(18.0).run(until="rest", max_duration=20.0, dt=2e-3)
    evidence = [
        RestPosition(name, *truth.rest(name).position[:2], 0.2) for name in ("tractor", "semi")
    ]
    fit = cs.fit(
        scene(15.0),
        {"tractor.speed": (10.0, 25.0)},
        evidence,
        start={"tractor.speed": 14.0},
        dt=2e-3,
        until="rest",
        max_duration=20.0,
    )
    assert fit.values["tractor.speed"] == pytest.approx(18.0, abs=1e-6)


def _drawbar_train(body_mass: float = 2000.0) -> tuple[cs.Vehicle, cs.Vehicle, cs.Vehicle]:
    van = cs.Vehicle.generate("van", name="van")
    rear = (van.mesh.bounds[0] - van.cg)[0]
    van = van.with_hitch(van.cg + [rear - 0.2, 0.0, 0.6 - van.cg[2]], "ball")
    dolly, body = cs.Trailer.drawbar(
        length=7.0,
        width=2.4,
        height=2.2,
        mass=body_mass,
        ground_clearance=1.0,
        turntable=1.2,
        rear_axles=[6.0],
        drawbar=2.5,
        eye_height=0.6,
        track=1.9,
        radius=0.45,
        dolly_mass=600.0,
        name="trailer",
    )
    return van, dolly, body


def test_a_drawbar_trailer_off_tracks_and_carries_as_the_closed_forms_say() -> None:
    # The dolly (drawbar 2.5 m) turns on its eye; the body (turntable 4.8 m ahead of its
    # axle) on the dolly's turntable over the dolly's axle: at 0.5 m/s the dolly's axle runs
    # on sqrt(Rh^2 - 2.5^2) and the body's on sqrt(Rd^2 - 4.8^2), Rh the ball's radius
    # (within 1 % of the off-tracking); parked, the turntable carries the body's weight times
    # the CG's lead over its axle per the turntable's (statics, 1 %).
    van, dolly, body = _drawbar_train()
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    delta = math.radians(12.0)
    steer = cs.DriverInputs(steer=np.array([[0.0, delta], [1.0, delta]]))
    scene.add(van, (0, 0), heading=0.0, velocity=(0.5, 0, 0), inputs=steer,
              trailers=[dolly, body])  # fmt: skip
    result = scene.run(200.0, record_interval=1.0)
    settled = slice(len(result.t) // 2, None)
    rh, _ = _circle(_path(result, "van", van.hitch.point)[settled, :2])
    axle = dolly.wheels.centers.mean(axis=0) * [1, 1, 0]
    rd, _ = _circle(_path(result, "trailer_dolly", axle)[settled, :2])
    rear = body.wheels.centers.mean(axis=0) * [1, 1, 0]
    rb, _ = _circle(_path(result, "trailer", rear)[settled, :2])
    drawbar = float(dolly.coupler.point[0] - dolly.wheels.centers[0, 0])
    span = float(body.coupler.point[0] - body.wheels.centers[0, 0])
    rd_closed = math.sqrt(rh**2 - drawbar**2)
    rb_closed = math.sqrt(rd_closed**2 - span**2)
    assert rh - rb == pytest.approx(rh - rb_closed, rel=1e-2)
    assert rd == pytest.approx(rd_closed, abs=0.01 * (rh - rb_closed))
    parked = cs.Scene(ground=cs.Ground())
    van, dolly, body = _drawbar_train()
    parked.add(van, (0, 0), heading=0.0, trailers=[dolly, body])
    loads = parked.run(1.0).joints["trailer_dolly-trailer"].force[-1, 2]
    # moments about the body's axle (body frame: the axle at x < 0, the CG at 0)
    statics = body.mass * G * -body.wheels.centers[0, 0] / span
    assert loads == pytest.approx(statics, rel=1e-2)


def test_the_report_names_a_jackknife_and_a_trailer_swing() -> None:
    # scripts/articulated_pictures.py's cases: the tractor's drive axles locked on a wet curve
    # fold the combination (a jackknife); rolling freely it does not; a tail-heavy caravan
    # swings at 100 km/h.
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "scripts" / "articulated_pictures.py"
    spec = importlib.util.spec_from_file_location("articulated_pictures", path)
    assert spec is not None and spec.loader is not None
    pictures = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(pictures)
    from crashsim.analysis.joints import JACKKNIFE_ANGLE
    from crashsim.analysis.report import build_report

    locked = build_report(pictures.curve_scene(1.0).run(4.0, record_interval=0.01))
    kinds = [e.kind for e in locked.articulation]
    assert "jackknife" in kinds
    first = next(e for e in locked.articulation if e.kind == "jackknife")
    assert abs(first.angle) > JACKKNIFE_ANGLE and first.speed > 5.0 and 1.0 < first.time < 4.0
    assert "jackknife of 'semitrailer'" in locked.summary_table()
    assert "articulation_events" in locked.to_dict()
    free = build_report(pictures.curve_scene(None).run(4.0, record_interval=0.01))
    assert free.articulation == []
    scene, _ = pictures.sway_scene(3.1)
    swing = build_report(scene.run(6.0, record_interval=0.01))
    assert [e.kind for e in swing.articulation][:1] == ["trailer_swing"]


def test_a_jointed_batch_gives_the_same_bits_on_one_and_two_threads() -> None:
    from crashsim.batch import run_batch
    from crashsim.studies.paths import overrides

    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    brake = cs.DriverInputs(brake=0.4, steer=np.array([[0.0, 0.0], [0.5, 0.05]]))
    scene.add(_tractor(), (0, 0), heading=0.0, velocity=(15, 0, 0), inputs=brake,
              trailers=[_semi()])  # fmt: skip
    arrays = overrides(scene, {"tractor.speed": [12.0, 14.0, 16.0, 18.0]})
    one = run_batch(scene, arrays, duration=1.0, dt=1e-3, threads=1)
    two = run_batch(scene, arrays, duration=1.0, dt=1e-3, threads=2)
    assert one.errors == [] and two.errors == []
    for key, column in one.columns.items():
        assert np.array_equal(column, two.columns[key], equal_nan=True), key


def test_generate_refuses_what_a_tractor_preset_cannot_take() -> None:
    with pytest.raises(ParameterError, match="give width to crashsim.tractor"):
        cs.Vehicle.generate("tractor", width=2.4)


def test_a_study_over_the_trailers_load_keeps_the_tractor_level() -> None:
    # The world sets the towing chain's static loads from the joints when a run starts, so
    # each variant's tractor carries its own semitrailer's kingpin load on preloaded springs
    # (the batch as Scene.with_, bit for bit).
    from crashsim.batch import run_batch
    from crashsim.studies.paths import overrides

    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(_tractor(), (0, 0), heading=0.0, velocity=(15, 0, 0), trailers=[_semi()])
    masses = [8000.0, 20000.0]
    batch = run_batch(scene, overrides(scene, {"semi.mass": masses}), duration=1.0, dt=1e-3)
    for k, mass in enumerate(masses):
        result = scene.with_({"semi.mass": mass}).run(1.0)
        z = result.trajectory("tractor").position[:, 2]
        assert np.abs(z - 1.0).max() < 1e-6
        kingpin = result.joints["tractor-semi"].force[-1, 2]
        # the CG 4.2 m ahead of the axle, the kingpin 10 m ahead of it
        assert kingpin == pytest.approx(mass * G * 4.2 / 10.0, rel=1e-3)
        assert batch.columns["tractor.final_x"][k] == result.trajectory("tractor").position[-1, 0]


def test_a_trailer_from_its_own_mesh_couples_and_carries_as_statics_says() -> None:
    # A tanker's barrel (a closed cylinder mesh, 12 m, 2.2 m across, 1.3 m above the road)
    # made a semitrailer: its kingpin 1.5 m behind its front end at the fifth wheel's height,
    # a tridem 9.0-11.6 m behind its front end.
    import trimesh

    barrel = trimesh.creation.cylinder(radius=1.1, height=12.0, sections=48)
    barrel.apply_transform(trimesh.transformations.rotation_matrix(math.pi / 2, [0, 1, 0]))
    barrel.apply_translation([0.0, 0.0, 1.3 + 1.1])
    mass = 30000.0
    body = cs.Vehicle(barrel, mass, [0.0, 0.0, 2.4], np.diag([1.8e4, 3.8e5, 3.8e5]), name="tank")
    front = 6.0
    tank = cs.Trailer.from_vehicle(
        body,
        "semitrailer",
        coupler_at=[front - 1.5, 0.0, 1.2],
        axles=[front - 9.0, front - 10.3, front - 11.6],
        track=2.0,
        radius=0.5,
    )
    assert tank.coupler is not None and tank.coupler.kind == "kingpin"
    assert len(tank.wheels.load_groups) == 2  # the tridem's two sides
    scene = cs.Scene(ground=cs.Ground())
    scene.add(_tractor(), (0, 0), heading=0.0, trailers=[tank])
    kingpin = scene.run(1.0).joints["tractor-tank"].force[-1, 2]
    # moments about the tridem's middle (10.3 m behind the front; the CG 6.0 m behind it)
    assert kingpin == pytest.approx(mass * G * (10.3 - 6.0) / (10.3 - 1.5), rel=1e-2)
    with pytest.raises(ParameterError, match="outside the body"):
        cs.Trailer.from_vehicle(
            body, "semitrailer", coupler_at=[9.0, 0, 1.2], axles=[-3.0], track=2.0, radius=0.5
        )


def test_a_car_and_trailer_in_a_steady_turn_hold_the_linear_closed_forms() -> None:
    # A car (parallel steer, 2 deg) towing a 750 kg centre-axle trailer on linear tyres
    # (cornering coefficient c = 1 per 10 deg, no rolling resistance) settles into a steady
    # turn at about 0.25 g. In a steady turn each unit's yaw moment vanishes and each tyre's
    # force is c Fz tan(alpha); the closed forms below follow (small angles only where said):
    # 1. moments about the trailer's axle: the hitch's lateral force F_h = m_t a (1 - d / L_t),
    #    d the hitch-to-CG and L_t the hitch-to-axle distance;
    # 2. the trailer's axle: tan(alpha_t) = m_t a (d / L_t) / (c m_t g d / L_t) = a / (c g);
    # 3. the articulation from the hitch's velocity seen from both units:
    #    Gamma = atan(w L_t / u - tan(alpha_t)) - beta_H, u the trailer's forward speed, w the
    #    yaw rate, beta_H the hitch's velocity angle in the car;
    # 4. the car's axles: their lateral forces from the car's force and moment balance with the
    #    hitch's force, their loads from statics with the nose load, tan(alpha) = F / (c Fz).
    # Each within 1 % (measured: 0.35 %, 0.15 %, 0.14 %, 0.05 % and 0.2 %).
    car, trailer = _car_and_trailer(cs.Tyre("linear", rolling_resistance=0.0))
    delta = math.radians(2.0)
    steer = [[0.0, 0.0], [0.5, delta], [30.0, delta]]
    scene = cs.Scene(ground=cs.Ground(friction=0.9))
    scene.add(
        car,
        (0, 0),
        heading=0.0,
        velocity=(15, 0, 0),
        trailers=[trailer],
        inputs=cs.DriverInputs(steer={0: steer, 1: steer}),
    )
    result = scene.run(14.0)
    t = result.t
    steady = t > 10.0
    c = 1.0 / math.radians(10.0)

    def heading(q: np.ndarray) -> np.ndarray:
        w, x, y, z = q.T
        return np.unwrap(np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z)))

    def in_frame(v: np.ndarray, psi: np.ndarray) -> np.ndarray:
        """World (k, 2+) vectors in a unit's axes (x forward, y left), averaged when steady."""
        cs_, sn = np.cos(psi), np.sin(psi)
        return np.c_[cs_ * v[:, 0] + sn * v[:, 1], -sn * v[:, 0] + cs_ * v[:, 1]][steady].mean(0)

    units = {}
    for name in ("car", "trailer"):
        tr = result.trajectory(name)
        psi = heading(tr.orientation)
        accel = np.c_[np.gradient(tr.velocity[:, 0], t), np.gradient(tr.velocity[:, 1], t)]
        units[name] = (psi, in_frame(tr.velocity, psi), in_frame(accel, psi))
    (psi_c, v_c, a_c), (psi_t, v_t, a_t) = units["car"], units["trailer"]
    w = np.gradient(psi_t, t)[steady].mean()
    assert w == pytest.approx(np.gradient(psi_c, t)[steady].mean(), rel=1e-4)
    assert a_t[1] / G > 0.2  # a turn well inside the linear range (the tyres' limit 0.9 g)
    hitch = result.joints["car-trailer"].force  # the car's on the trailer
    # 1. the trailer's yaw moment about its axle
    x_axle = trailer.wheels.contact_points()[0][0]
    x_hitch = trailer.coupler.point[0]
    l_t, d = x_hitch - x_axle, x_hitch  # the CG at x = 0
    f_h = in_frame(hitch, psi_t)[1]
    assert f_h == pytest.approx(trailer.mass * a_t[1] * (1 - d / l_t), rel=1e-2)
    # 2. the trailer's axle slip
    tan_alpha_t = -(v_t[1] + w * x_axle) / v_t[0]
    assert tan_alpha_t == pytest.approx(a_t[1] / (c * G), rel=1e-2)
    # 3. the articulation
    x_ball = car.hitch.point[0]
    beta_h = math.atan2(v_c[1] + w * x_ball, v_c[0])
    gamma = math.atan(w * l_t / v_t[0] - a_t[1] / (c * G)) - beta_h
    assert (psi_c - psi_t)[steady].mean() == pytest.approx(gamma, rel=1e-2)
    # 4. the car's axles
    (x_f, _, _), _, (x_r, _, _), _ = car.wheels.contact_points()
    a_f, b = x_f, -x_r
    nose = trailer.wheels.coupling_load(trailer.mass)
    fz_f = (car.mass * G * b - nose * (-x_ball - b)) / (a_f + b)
    fz_r = car.mass * G + nose - fz_f
    f_hc = in_frame(hitch, psi_c)[1]
    # F_f cos(delta) + F_r = m a + F_hc; F_f cos(delta) a_f - F_r b = x_ball F_hc
    f_f, f_r = np.linalg.solve(
        [[math.cos(delta), 1.0], [math.cos(delta) * a_f, -b]],
        [car.mass * a_c[1] + f_hc, x_ball * f_hc],
    )
    vx, vy = v_c[0], v_c[1] + w * a_f
    tan_alpha_f = -(-math.sin(delta) * vx + math.cos(delta) * vy) / (
        math.cos(delta) * vx + math.sin(delta) * vy
    )
    assert tan_alpha_f == pytest.approx(f_f / (c * fz_f), rel=1e-2)
    assert -(v_c[1] - w * b) / v_c[0] == pytest.approx(f_r / (c * fz_r), rel=1e-2)
