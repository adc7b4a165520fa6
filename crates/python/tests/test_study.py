"""Scenes, maps and measurements from Python: arrays of the documented shapes and types, errors
naming the argument, and an analysis equal to the command-line tool's results.json."""

import json
import subprocess

import numpy as np
import pytest

import shadowlab as sl


def small(name="outdoor", size=(96, 72)):
    return sl.Scene.builtin(name).with_image_size(*size)


def test_built_in_scenes_as_arrays():
    assert "outdoor" in sl.Scene.builtin_names() and "room-point" in sl.Scene.builtin_names()
    scene = small()
    assert scene.positions.shape[1] == 3 and scene.positions.dtype == np.float64
    assert scene.indices.shape[1] == 3 and scene.indices.dtype == np.int64
    assert scene.indices.max() < len(scene.positions)
    assert scene.groups.shape == (len(scene.indices),)
    assert np.allclose(np.linalg.norm(scene.normals, axis=1), 1.0)
    camera = scene.camera
    assert camera["view"].shape == (4, 4) and camera["projection"].shape == (4, 4)
    assert (camera["width"], camera["height"]) == (96, 72)
    assert scene.lights[0]["kind"] == "directional"


def a_quad_under_a_box():
    ground = [[-5, 0, -5], [5, 0, -5], [5, 0, 5], [-5, 0, 5]]
    box = [[-1, 1, -1], [1, 1, -1], [1, 1, 1], [-1, 1, 1]]
    positions = np.array(ground + box, dtype=float)
    indices = np.array([[0, 2, 1], [0, 3, 2], [4, 6, 5], [4, 7, 6]])
    camera = {"eye": (0, 6, 9), "target": (0, 0, 0), "near": 0.5, "far": 40, "width": 80, "height": 60}
    return positions, indices, camera


def test_a_scene_from_arrays_casts_the_shadow_the_truth_says():
    positions, indices, camera = a_quad_under_a_box()
    scene = sl.Scene.from_arrays(positions, indices, camera, [{"kind": "directional", "direction": (0, -1, 0)}])
    lit, visible = sl.truth(scene)
    assert lit.shape == (1, 60, 80) and lit.dtype == np.bool_ and visible.dtype == np.bool_
    eye = sl.eye_pass(scene)
    under = visible & (np.abs(eye["position"][..., 0]) < 0.9) & (np.abs(eye["position"][..., 2]) < 0.9)
    on_ground = under & (eye["position"][..., 1] < 0.5)
    assert on_ground.sum() > 20 and not lit[0][on_ground].any()
    assert lit[0][visible & (np.abs(eye["position"][..., 0]) > 2)].all()


@pytest.mark.parametrize(
    "lights, name",
    [
        ([], "lights"),
        ([{"kind": "sun", "direction": (0, -1, 0)}], "lights[0].kind"),
        ([{"kind": "directional", "direction": (0, 0, 0)}], "lights[0].direction"),
        ([{"kind": "point", "position": (0, 3, 0), "range": -1}], "lights[0].range"),
        ([{"kind": "spot", "position": (0, 3, 0)}], "lights[0].target"),
    ],
)
def test_bad_lights_name_the_field(lights, name):
    positions, indices, camera = a_quad_under_a_box()
    with pytest.raises(ValueError) as error:
        sl.Scene.from_arrays(positions, indices, camera, lights)
    assert str(error.value).startswith(name), str(error.value)


def test_bad_meshes_and_cameras_name_the_argument():
    positions, indices, camera = a_quad_under_a_box()
    light = [{"direction": (0, -1, 0)}]
    with pytest.raises(ValueError, match="^indices"):
        sl.Scene.from_arrays(positions, indices - 100, camera, light)
    with pytest.raises(ValueError, match="^positions"):
        sl.Scene.from_arrays(positions[:, :2].copy(), indices, camera, light)
    with pytest.raises(ValueError, match="^camera.eye"):
        sl.Scene.from_arrays(positions, indices, {"target": (0, 0, 0), "near": 1, "far": 9}, light)


def test_plan_and_maps_of_every_kind_of_light():
    for name, technique, faces in [("outdoor", "lispsm", 1), ("room-point", "cube", 6), ("room-point", "dual-paraboloid", 2)]:
        scene = small(name)
        planned = sl.plan(scene, technique, resolution=128)
        assert len(planned) == 1 and len(planned[0]) == faces
        part = planned[0][0]
        assert part["focus_body"].shape[1] == 3
        if technique == "dual-paraboloid":
            assert part["view"] is None and part["projection"] is None
        else:
            assert part["projection"].shape == (4, 4)
        depth = sl.render_map(scene, technique, resolution=128, partition=faces - 1)
        assert depth.shape == (128, 128) and depth.dtype == np.float64
        assert depth.min() >= 0.0 and depth.max() <= 1.0 and depth.min() < 1.0


def test_errors_of_planning_are_value_errors():
    with pytest.raises(ValueError, match="^technique"):
        sl.plan(small(), "vsm")
    with pytest.raises(ValueError, match="cannot serve a point light"):
        sl.plan(small("room-point"), "lispsm")
    with pytest.raises(ValueError, match="^partition"):
        sl.render_map(small(), "lispsm", resolution=64, partition=3)


def without_times(value):
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items() if k not in ("ms", "truth_ms")}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def test_analyze_equals_the_command_line_results(tmp_path, shadowlab_binary):
    out = tmp_path / "analysis"
    subprocess.run(
        [shadowlab_binary, "analyze", "chess-point", "--techniques", "cube,psm", "--resolutions", "256,512",
         "--filters", "nearest,pcf:3", "--timing-runs", "1", "--out", str(out)],
        check=True, capture_output=True,
    )
    cli = json.loads((out / "results.json").read_text())
    ours = sl.analyze(sl.Scene.builtin("chess-point"), ["cube", "psm"], [256, 512], filters=["nearest", "pcf:3"], timing_runs=1)
    assert without_times(ours.results) == without_times(cli)
    assert len(ours.records) == 8 and all(isinstance(v, (int, float, str, bool, type(None))) for v in ours.records[0].values())


def test_analyze_records_make_a_dataframe():
    import pandas

    frame = pandas.DataFrame(sl.analyze(small(), ["lispsm", "uniform"], [128], timing_runs=1).records)
    assert list(frame["setting_technique"]) == ["lispsm", "uniform"]
    assert (frame["misclassified"] >= 0).all()


def test_scene_files_of_every_kind_load(tmp_path):
    obj = tmp_path / "tri.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n")
    from_obj = sl.Scene.load(obj)
    assert from_obj.indices.shape == (1, 3) and from_obj.lights[0]["kind"] == "directional"
    toml = tmp_path / "lamp.toml"
    toml.write_text(f'[[mesh]]\nobj = "tri.obj"\n\n[[light]]\nkind = "point"\nposition = [0.2, 1.0, 0.2]\n')
    assert sl.Scene.load(toml).lights == [{"kind": "point", "position": [0.2, 1.0, 0.2], "range": None}]
    with pytest.raises(ValueError, match="^path"):
        sl.Scene.load(tmp_path / "missing.toml")


def test_analyze_keeps_every_combinations_pixels_when_asked():
    scene = small()
    analysis = sl.analyze(scene, ["lispsm", "uniform"], [128, 256], timing_runs=1, pixels=True)
    lit_truth, visible = sl.truth(scene)
    assert len(analysis.pixels) == 4
    for record in analysis.records:
        key = (record["setting_technique"], record["setting_resolution"], record["setting_maps"], record["setting_filter"])
        arrays = analysis.pixels[key]
        lit, footprint = arrays["lit"], arrays["footprint"]
        assert lit.shape == (1, 72, 96) and footprint.shape == (72, 96)
        assert np.all(lit[0][~visible] == 1.0) and np.all(np.isnan(footprint[~visible]))
        # The per-pixel lookups reproduce the record's counts against the truth.
        classified = lit[0] >= 0.5
        wrong = visible & (classified != lit_truth[0])
        assert wrong.sum() == record["misclassified"], key
    assert sl.analyze(scene, ["lispsm"], [128], timing_runs=1).pixels == {}
