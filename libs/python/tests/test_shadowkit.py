#!/usr/bin/env python3
"""The Python module against the C++ results for the same inputs: `shadowkit setup` and
`shadowkit eval` (the command line's JSON, written with round-trip precision) give the
numbers; the module must give the same. Run by CTest with PYTHONPATH at the module and
SHADOWKIT at the command line."""
import json
import os
import re
import subprocess
import tempfile
import unittest

import numpy as np

import shadowkit

CLI = os.environ["SHADOWKIT"]
SMALL = ["--trees", "300", "--terrain-size", "200", "--terrain-resolution", "32"]


def cli_json(*args):
    out = subprocess.run([CLI, *args], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def column_major(flat):
    """A matrix as the CLI prints it (16 values, column after column) as [row, column]."""
    return np.array(flat, dtype=float).reshape(4, 4).T


class OptionNamesTest(unittest.TestCase):
    def test_every_frame_keyword_is_a_flag_of_the_one_table(self):
        # evaluate()'s keywords that set a frame option are the command line's flags, spelt with
        # underscores: each must name a row of frame/option_table.h.
        flags = {flag for flag, _ in shadowkit.option_flags()}
        self.assertIn("--sun-angle", flags)
        signature = shadowkit.evaluate.__doc__.splitlines()[0]
        keywords = re.findall(r"(\w+): ", signature)
        scene_and_view = {"view", "seed", "trees", "terrain_size", "terrain_resolution", "movers", "forest"}
        frame_keywords = [k for k in keywords if k not in scene_and_view]
        self.assertGreaterEqual(len(frame_keywords), 5, signature)
        for keyword in frame_keywords:
            self.assertIn("--" + keyword.replace("_", "-"), flags, keyword)


class SetupTest(unittest.TestCase):
    def test_equals_the_command_line_for_every_technique(self):
        for technique in ["standard", "focused", "lispsm", "psm", "tsm", "csm"]:
            expected = cli_json("setup", "--view", "perpendicular", "--technique", technique, *SMALL)
            inputs = expected["inputs"]
            cam = inputs["camera"]
            got = shadowkit.setup(eye=cam["eye"], direction=cam["direction"], up=cam["up"], fov=cam["fov_y_degrees"],
                                  aspect=cam["aspect"], near=cam["near"], far=cam["far"],
                                  light=inputs["light"]["direction"], scene_min=inputs["scene_bounds"]["min"],
                                  scene_max=inputs["scene_bounds"]["max"], technique=technique)
            self.assertEqual(got["technique"], expected["technique"])
            self.assertEqual(got["depth_layout"], expected["depth_layout"])
            self.assertEqual(len(got["views"]), len(expected["views"]))
            for view, cli_view in zip(got["views"], expected["views"]):
                # The default conventions are the core's own: the very same doubles.
                np.testing.assert_array_equal(view["clip_from_world"], column_major(cli_view["clip_from_world"]))
                np.testing.assert_array_equal(view["light_from_world"], column_major(cli_view["light_from_world"]))
                np.testing.assert_array_equal(view["clip_from_eye_relative"], column_major(cli_view["clip_from_eye_relative"]))
            self.assertEqual(list(got["eye_relative_origin"]), expected["eye_relative_origin"])

    def test_engine_matrices_give_the_eye_direction_set_up(self):
        eye, target = np.array([3.0, 6.0, 14.0]), np.array([0.0, 0.0, -30.0])
        f = target - eye
        f /= np.linalg.norm(f)
        s = np.cross(f, [0.0, 1.0, 0.0])
        s /= np.linalg.norm(s)
        u = np.cross(s, f)
        view = np.identity(4)
        view[0, :3], view[1, :3], view[2, :3] = s, u, -f
        view[:3, 3] = -view[:3, :3] @ eye
        t, aspect, near, far = 1.0 / np.tan(np.radians(30.0)), 1.5, 0.3, 200.0
        gl_projection = np.array([[t / aspect, 0, 0, 0], [0, t, 0, 0],
                                  [0, 0, -(far + near) / (far - near), -2 * far * near / (far - near)], [0, 0, -1, 0]])
        common = dict(sun=(35.0, 120.0), scene_min=[-100, 0, -100], scene_max=[100, 12, 100], technique="lispsm")
        by_matrices = shadowkit.setup(view_from_world=view, clip_from_view=gl_projection, clip_depth="minus_one_to_one", **common)
        by_eye = shadowkit.setup(eye=list(eye), direction=list(f), fov=60.0, aspect=aspect, near=near, far=far, **common)
        a, b = by_matrices["views"][0]["clip_from_world"], by_eye["views"][0]["clip_from_world"]
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-9 * np.abs(b).max())

    def test_conventions_flip_as_documented(self):
        common = dict(sun=(40.0, 70.0), technique="focused")
        gl = shadowkit.setup(conventions="opengl", **common)["views"][0]
        d3d = shadowkit.setup(conventions="direct3d", reversed_z=True, **common)["views"][0]
        point = np.array([10.0, 2.0, -30.0, 1.0])
        t_gl, t_d3d = gl["texture_from_world"] @ point, d3d["texture_from_world"] @ point
        u_gl, v_gl, d_gl = t_gl[:3] / t_gl[3]
        u_d3d, v_d3d, d_d3d = t_d3d[:3] / t_d3d[3]
        self.assertAlmostEqual(u_gl, u_d3d, places=12)
        self.assertAlmostEqual(v_gl, 1.0 - v_d3d, places=12)
        self.assertAlmostEqual(d_gl, 1.0 - d_d3d, places=12)

    def test_bad_input_raises_with_the_core_message(self):
        with self.assertRaisesRegex(ValueError, "map_size"):
            shadowkit.setup(map_size=3)
        with self.assertRaisesRegex(ValueError, "technique"):
            shadowkit.setup(technique="nope")
        with self.assertRaisesRegex(ValueError, "camera.clip_from_view"):
            shadowkit.setup(view_from_world=np.identity(4), clip_from_view=np.zeros((4, 4)))
        with self.assertRaisesRegex(ValueError, r"sun_angle: must be in \[0, 20\]"):
            shadowkit.setup(sun_angle=21.0)

    def test_the_suns_size_gives_pcss_its_tangent_of_the_angular_radius(self):
        self.assertEqual(shadowkit.setup()["light_tan_half_angle"], 0.0)  # a point-like sun by default
        self.assertAlmostEqual(shadowkit.setup(sun_angle=0.53)["light_tan_half_angle"], 0.004625, places=6)


class LocalSetupTest(unittest.TestCase):
    def test_equals_the_command_line_for_a_spot_and_a_point_light(self):
        lights = ["point:0,3,-20,25,radius=0.05", "spot:0,8,-30,0,-1,-0.3,60,25"]
        expected = cli_json("setup", "--view", "perpendicular", *SMALL, "--light", lights[0], "--light", lights[1])
        camera, box = expected["inputs"]["camera"], expected["inputs"]["scene_bounds"]
        common = dict(eye=camera["eye"], view_direction=camera["direction"], up=camera["up"],
                      fov=camera["fov_y_degrees"], aspect=camera["aspect"], near=camera["near"], far=camera["far"],
                      scene_min=box["min"], scene_max=box["max"], range=25.0)
        for cli in expected["local_lights"]:
            if cli["type"] == "point":
                got = shadowkit.local_setup(kind="point", position=cli["position"], radius=0.05, **common)
            else:
                got = shadowkit.local_setup(kind="spot", position=cli["position"], direction=cli["direction"],
                                            cone=cli["cone_degrees"], **common)
            self.assertEqual(len(got["views"]), len(cli["views"]), cli["type"])
            for view, cli_view in zip(got["views"], cli["views"]):
                # The default conventions are the core's own: the very same doubles.
                np.testing.assert_array_equal(view["clip_from_world"], column_major(cli_view["clip_from_world"]))
                self.assertEqual(view["face"], cli_view.get("face"))
            if cli["type"] == "point":
                self.assertEqual(got["skipped_faces"], cli["skipped_faces"])
                self.assertEqual(len(got["views"]) + got["skipped_faces"], 6)
                self.assertAlmostEqual(got["texel_per_metre"], 2.0 / 1024.0, places=15)  # a 90° face, 1024²
            self.assertEqual(got["radius"], 0.05 if cli["type"] == "point" else 0.0)

    def test_the_stored_distance_and_the_biases_are_what_the_lookup_takes(self):
        common = dict(kind="point", position=[0.0, 3.0, -20.0], range=40.0, eye=[0.0, 5.0, 0.0])
        for reversed_z, near, far in [(False, 0.0, 1.0), (True, 1.0, 0.0)]:
            scale, offset = shadowkit.local_setup(reversed_z=reversed_z, **common)["stored_from_distance"]
            self.assertEqual(offset, near)  # at the light
            self.assertAlmostEqual(40.0 * scale + offset, far, places=15)  # at the range
        bias = shadowkit.local_setup(**common)["bias"]
        self.assertEqual(bias, dict(slope_texels=1.5, normal_offset_texels=0.5, constant_metres=0.005))
        with self.assertRaisesRegex(ValueError, "kind: 'torch' is not one of spot, point, point_one_map, point_aimed_map"):
            shadowkit.local_setup(kind="torch")
        # Named as local_setup's keywords, not as the C++ structs' fields ("spot.cone").
        with self.assertRaisesRegex(ValueError, r"^cone: must be in \(0, 170\] degrees$"):
            shadowkit.local_setup(cone=180.0)
        with self.assertRaisesRegex(ValueError, r"^range: "):
            shadowkit.local_setup(kind="point", range=0.0)


    def test_a_point_light_in_one_map_holds_what_the_camera_sees_in_reach(self):
        # A lamp above and behind the eye: one map, drawn as a spot's, where the cube takes faces.
        common = dict(position=[0.0, 12.0, 6.0], range=40.0, eye=[0.0, 5.0, 0.0], view_direction=[0.0, -0.3, -1.0],
                      scene_min=[-50.0, 0.0, -50.0], scene_max=[50.0, 10.0, 50.0])
        one = shadowkit.local_setup(kind="point_one_map", **common)
        cube = shadowkit.local_setup(kind="point", **common)
        self.assertEqual(one["kind"], "spot")
        self.assertEqual(len(one["views"]), 1)
        self.assertGreater(len(cube["views"]), 1)
        # Ground points the camera sees within reach land inside the one map.
        clip = np.asarray(one["views"][0]["clip_from_world"])
        for z in (-5.0, -15.0, -30.0):
            for x in (-3.0, 0.0, 3.0):
                c = clip @ np.array([x, 0.0, z, 1.0])
                self.assertGreater(c[3], 0.0)
                self.assertLessEqual(abs(c[0] / c[3]), 1.0)
                self.assertLessEqual(abs(c[1] / c[3]), 1.0)
        # Among what the camera sees: refused in local_setup's words.
        with self.assertRaisesRegex(ValueError, r"^position: what the camera sees"):
            shadowkit.local_setup(kind="point_one_map", **dict(common, position=[0.0, 2.0, -10.0]))
        # point_aimed_map: the same map there, and among what the camera sees a 170-degree cone aimed
        # at the middle of it, which holds the ground under the lamp's sight line but says it holds part.
        same = shadowkit.local_setup(kind="point_aimed_map", **common)
        self.assertFalse(same["holds_part_of_view"])
        np.testing.assert_array_equal(same["views"][0]["clip_from_world"], one["views"][0]["clip_from_world"])
        among = shadowkit.local_setup(kind="point_aimed_map", **dict(common, position=[0.0, 2.0, -10.0]))
        self.assertTrue(among["holds_part_of_view"])
        self.assertEqual(among["kind"], "spot")
        self.assertEqual(len(among["views"]), 1)
        self.assertFalse(one["holds_part_of_view"])


class EvaluateTest(unittest.TestCase):
    def test_equals_shadowkit_eval_and_its_buffers_agree_with_its_figures(self):
        evaluator = shadowkit.Evaluator(trees=300, terrain_size=200, terrain_resolution=32)
        for technique in ["tsm", "lispsm"]:
            args = ["--view", "perpendicular", "--technique", technique, "--size", "160x90", "--map-size", "512"]
            with tempfile.TemporaryDirectory() as folder:
                report = os.path.join(folder, "eval.json")
                subprocess.run([CLI, "eval", *args, *SMALL, "--json", report], check=True, capture_output=True)
                with open(report) as f:
                    expected = json.load(f)["views"][0]
            got = evaluator.evaluate(view="perpendicular", technique=technique, size=(160, 90), map_size=512)
            for key, value in got["figures"].items():
                self.assertEqual(value, expected[key], f"{technique} {key}")
            classes = got["pixel_class"]
            self.assertEqual(classes.shape, (90, 160))
            valid = np.isin(classes, [1, 2, 3, 4])
            self.assertEqual(int(valid.sum()), expected["valid_px"])
            wrong = np.isin(classes, [3, 4]).sum() / valid.sum() * 100
            self.assertAlmostEqual(wrong, expected["wrong_pct"], places=9)
            # A correct shadow is shadowed in the map's test and in truth.
            correct_shadow = classes == 2
            self.assertGreater(int(correct_shadow.sum()), 100)
            self.assertTrue(np.all(got["shadow_term"][correct_shadow] < 0.5))
            self.assertTrue(np.all(got["truth_lit"][correct_shadow] == 0))
            self.assertTrue(np.all(np.isnan(got["pixels_per_texel"][~valid])))

    def test_the_leafy_forest_equals_shadowkit_eval_and_an_unknown_forest_is_named(self):
        got = shadowkit.evaluate(view="perpendicular", technique="lispsm", size=(160, 90), map_size=512,
                                 forest="leafy", trees=60, terrain_size=200, terrain_resolution=32)
        args = ["--view", "perpendicular", "--technique", "lispsm", "--size", "160x90", "--map-size", "512",
                "--forest", "leafy", "--trees", "60", "--terrain-size", "200", "--terrain-resolution", "32"]
        with tempfile.TemporaryDirectory() as folder:
            report = os.path.join(folder, "eval.json")
            subprocess.run([CLI, "eval", *args, "--json", report], check=True, capture_output=True)
            with open(report) as f:
                expected = json.load(f)["views"][0]
        for key, value in got["figures"].items():
            self.assertEqual(value, expected[key], key)
        with self.assertRaisesRegex(ValueError, "forest: must be 'simple' or 'leafy'"):
            shadowkit.Evaluator(trees=10, terrain_size=100, terrain_resolution=8, forest="bushy")

    def test_soft_shadows_of_the_real_sun_equal_shadowkit_evals(self):
        evaluator = shadowkit.Evaluator(trees=300, terrain_size=200, terrain_resolution=32)
        args = ["--view", "perpendicular", "--technique", "tsm", "--size", "160x90", "--map-size", "512"]
        soft = ["--filter", "pcss", "--sun-angle", "0.53"]
        with tempfile.TemporaryDirectory() as folder:
            report = os.path.join(folder, "eval.json")
            dump = os.path.join(folder, "dump")
            subprocess.run([CLI, "eval", *args, *soft, *SMALL, "--json", report, "--dump", dump], check=True,
                           capture_output=True)
            with open(report) as f:
                expected = json.load(f)["views"][0]
            dumped = np.load(os.path.join(dump, "soft_visibility.npy"))
            error = np.load(os.path.join(dump, "soft_standard_error.npy"))
        got = evaluator.evaluate(view="perpendicular", technique="tsm", size=(160, 90), map_size=512, filter="pcss",
                                 sun_angle=0.53)
        for key in ["sun_angle_deg", "soft_compared_px", "penumbra_px", "soft_mae", "penumbra_mae", "soft_wrong_pct",
                    "penumbra_width_ratio"]:
            self.assertAlmostEqual(got["soft"][key], expected[key], places=9, msg=key)
        self.assertGreater(got["soft"]["penumbra_px"], 0)
        # The per-pixel truth behind the figures: the dump's, a fraction where there is a surface.
        visibility = got["soft_visibility"]
        np.testing.assert_array_equal(visibility, dumped)
        surface = np.isfinite(visibility)
        self.assertTrue(np.all((visibility[surface] >= 0) & (visibility[surface] <= 1)))
        penumbra = surface & (visibility > 0.02) & (visibility < 0.98)
        self.assertTrue(np.all(error[penumbra] > 0))  # the penumbrae's estimates carry their error
        self.assertNotIn("soft", evaluator.evaluate(view="perpendicular", size=(160, 90), map_size=512))
        with self.assertRaisesRegex(ValueError, "sun_angle"):
            evaluator.evaluate(view="perpendicular", size=(160, 90), sun_angle=-1)


if __name__ == "__main__":
    unittest.main(verbosity=2)
