#!/usr/bin/python3
"""The Python module against the tools (ctest python.module): vri.render's array is vri-render's EXR bit for bit
for the same options (four methods), vri.reference's values and bounds are vri-reference's, bad input raises
vri.Error with vri's one-line message (the tools' own line where both read the same thing), and the GIL is
released while a render runs. Needs VRI_BIN (the tools), VRI_SOURCE and VRI_SCRATCH, and the module on
PYTHONPATH (tests/CMakeLists.txt sets them)."""
import json
import os
import shutil
import subprocess
import threading
import time
import unittest

import numpy as np

import vri

BIN = os.environ["VRI_BIN"]
TF = os.path.join(os.environ["VRI_SOURCE"], "experiments", "tf", "bonsai.yaml")
SCRATCH = os.environ["VRI_SCRATCH"]
SIZE = (40, 30)
EYE = (30.0, 20.0, 60.0)


def setUpModule():
    shutil.rmtree(SCRATCH, ignore_errors=True)
    os.makedirs(SCRATCH)


def scratch(name):
    return os.path.join(SCRATCH, name)


def blob_volume():
    """A uint8 24x20x16 blob written as a raw file named by the Open SciVis convention (dims and type in it)."""
    path = scratch("blob_24x20x16_uint8.raw")
    if not os.path.exists(path):
        z, y, x = np.meshgrid(np.arange(16), np.arange(20), np.arange(24), indexing="ij")
        r2 = ((x - 11.5) / 9) ** 2 + ((y - 9.5) / 8) ** 2 + ((z - 7.5) / 6) ** 2
        (255 * np.clip(1.2 - r2, 0, 1)).astype(np.uint8).tofile(path)
    return path


def run_tool(tool, *args):
    """The tool's exit code and its stderr."""
    done = subprocess.run([os.path.join(BIN, tool), *args], capture_output=True, text=True)
    return done.returncode, done.stderr


def bits(a):
    return np.ascontiguousarray(a, dtype=np.float32).view(np.uint32)


class RenderEqualsTools(unittest.TestCase):
    def setUp(self):
        self.path = blob_volume()
        self.volume = vri.load_volume(self.path)
        self.tf = vri.load_transfer_function(TF)
        self.camera = vri.Camera(size=SIZE, eye=EYE)
        self.camera_args = ["--size", "%dx%d" % SIZE, "--eye", ",".join(map(str, EYE))]

    def test_image_is_vri_render_exr_bit_for_bit(self):
        cases = {
            "riemann_float": dict(method="riemann", step=0.7, precision="float"),
            "composite_scalar": dict(method="composite", step=0.5, simd="off", early_termination=0.01),
            "coupled": dict(method="coupled", tolerance=1e-3, h_max="none"),
            "exact": dict(method="exact", tolerance=1e-9, clamp=True),
            # Issue 32's methods: pre-integration of order 2 and jittered frames, as vri-render makes them.
            "preintegrated": dict(method="preintegrated", preint_order=2, preint_size=64, step=0.7, precision="float"),
            "jittered": dict(method="riemann", step=0.7, jitter=True, seed=9, frames=3),
        }
        for name, options in cases.items():
            with self.subTest(name):
                flags = []
                for key, value in options.items():
                    flag = "--" + key.replace("_", "-")
                    flags += [flag] if value is True else [flag, str(value)]
                exr = scratch(name + ".exr")
                code, err = run_tool("vri-render", "--volume", self.path, "--tf", TF, *self.camera_args,
                                     "-o", exr, "-q", "--threads", "2", *flags)
                self.assertEqual(code, 0, err)
                image, stats = vri.render(self.volume, self.tf, self.camera, threads=2, **options)
                self.assertEqual(image.dtype, np.float32)
                self.assertEqual(image.shape, (SIZE[1], SIZE[0], 4))
                self.assertTrue(np.array_equal(bits(image), bits(vri.read_image(exr))), name)
                self.assertGreater(image[..., 3].max(), 0.1, "the blob is in view")
                self.assertEqual(stats["rays"], SIZE[0] * SIZE[1])
                self.assertEqual(stats["options"]["method"], options["method"])

    def test_reference_values_and_bounds_are_vri_reference(self):
        code, err = run_tool("vri-reference", "--volume", self.path, "--tf", TF, *self.camera_args, "-q",
                             "--tolerance", "1e-10", "-o", scratch("ref.exr"), "--error-image", scratch("bound.exr"))
        self.assertEqual(code, 0, err)
        values, bounds, stats = vri.reference(self.volume, self.tf, self.camera, tolerance=1e-10)
        self.assertEqual(values.dtype, np.float64)
        self.assertTrue(np.array_equal(bits(values.astype(np.float32)), bits(vri.read_image(scratch("ref.exr")))))
        # The error image bounds the EXR's float32 values: the double's bound plus its float32 rounding,
        # rounded up to a float.
        total = bounds + np.abs(values.astype(np.float32).astype(np.float64) - values)
        stored = total.astype(np.float32)
        stored = np.where(stored.astype(np.float64) >= total, stored, np.nextafter(stored, np.float32(np.inf)))
        self.assertTrue(np.array_equal(bits(stored), bits(vri.read_image(scratch("bound.exr")))))
        self.assertTrue((bounds >= 0).all() and bounds.max() < 1e-6)
        self.assertEqual(stats["options"]["tolerance"], 1e-10)

    def test_render_flow_is_vri_renders(self):
        """vri.render runs vri-render's RenderJob: --max-error's search, the Vulkan backend and the provenance
        record are the tool's, and vri.describe is vri-render --describe."""
        stats_path = scratch("max_error.json")
        code, err = run_tool("vri-render", "--volume", self.path, "--tf", TF, *self.camera_args, "-q", "--threads", "2",
                             "--method", "exact", "--max-error", "1e-4", "-o", scratch("max_error.exr"),
                             "--stats", stats_path)
        self.assertEqual(code, 0, err)
        image, stats = vri.render(self.volume, self.tf, self.camera, threads=2, method="exact", max_error=1e-4)
        self.assertTrue(np.array_equal(bits(image), bits(vri.read_image(scratch("max_error.exr")))))
        with open(stats_path) as f:
            tool = json.load(f)
        tolerances = lambda search: [r["tolerance"] for r in search["renders"]]
        self.assertEqual(tolerances(stats["max_error_search"]), tolerances(tool["stats"]["max_error_search"]))
        bound = stats["error_bound"]["max"]
        self.assertLessEqual(max(bound) if isinstance(bound, list) else bound, 1e-4)
        record = stats["record"]
        self.assertEqual(record["tool"], "python")
        self.assertEqual(record["command"]["python"], "vri.render")
        self.assertEqual(record["command"]["keywords"]["max_error"], "0.0001")
        for key in ("build", "machine", "scene", "camera", "options", "timing", "transfer_function"):
            self.assertEqual(type(record[key]), type(tool[key]), key)
        self.assertEqual(record["scene"], tool["scene"])
        self.assertEqual(record["camera"], tool["camera"])
        self.assertEqual(record["options"], tool["options"])

        card_path = scratch("card.json")
        code, err = run_tool("vri-render", "--volume", self.path, "--tf", TF, *self.camera_args, "-q",
                             "--step", "0.7", "--describe", card_path)
        self.assertEqual(code, 0, err)
        with open(card_path) as f:
            card = json.load(f)
        mine = vri.describe(self.volume, self.tf, self.camera, step=0.7)
        for key in ("camera", "method", "worked_rays", "transfer_function", "integration", "output"):
            self.assertEqual(mine[key], card[key] if key != "transfer_function" else {**card[key], "source": None}, key)
        self.assertIsNone(mine["volume"]["source"])  # built in Python: no file

        if os.environ.get("VRI_VULKAN", "ON") != "ON" or run_tool("vri-render", "--list-devices")[0] != 0:
            return  # no Vulkan backend or device here: the CPU part above still ran
        options = dict(method="riemann", step=0.7, precision="float", backend="vulkan")
        code, err = run_tool("vri-render", "--volume", self.path, "--tf", TF, *self.camera_args, "-q",
                             "--method", "riemann", "--step", "0.7", "--precision", "float", "--backend", "vulkan",
                             "-o", scratch("vulkan.exr"))
        self.assertEqual(code, 0, err)
        image, stats = vri.render(self.volume, self.tf, self.camera, **options)
        self.assertEqual(stats["backend"], "vulkan")
        self.assertTrue(np.array_equal(bits(image), bits(vri.read_image(scratch("vulkan.exr")))))

    def test_compare_is_vri_diff(self):
        a, _ = vri.render(self.volume, self.tf, self.camera, method="riemann", step=1.0)
        b, _ = vri.render(self.volume, self.tf, self.camera, method="coupled", tolerance=1e-4)
        vri.write_exr(scratch("a.exr"), a)
        vri.write_exr(scratch("b.exr"), b)
        code, err = run_tool("vri-diff", scratch("a.exr"), scratch("b.exr"), "--json", scratch("diff.json"))
        self.assertIn(code, (0, 2, 3), err)  # its verdict against its default --warn and --fail
        with open(scratch("diff.json")) as f:
            tool = json.load(f)
        mine = vri.compare(a, b)
        for key in ("width", "height", "pixels", "pixels_counted", "thresholds", "channels", "metrics"):
            self.assertEqual(mine[key], tool[key], key)
        self.assertGreater(mine["channels"][0]["max_abs"], 0.0)
        # The mask, as vri-diff's --mask: the same record over the pixels the volume covers.
        code, err = run_tool("vri-diff", scratch("a.exr"), scratch("b.exr"), "--mask", "hit", "--json",
                             scratch("hit.json"))
        with open(scratch("hit.json")) as f:
            tool = json.load(f)
        hit = vri.compare(a, b, mask="hit")
        self.assertEqual(hit["metrics"], tool["metrics"])
        self.assertEqual(hit["pixels"], tool["pixels"])
        self.assertLess(hit["pixels"], mine["pixels"])
        with self.assertRaisesRegex(vri.Error, "alpha>T"):
            vri.compare(a, b, mask="alpha>2")
        for bad in (float("nan"), -1.0, float("inf")):
            with self.assertRaisesRegex(vri.Error, "thresholds: expected numbers >= 0"):
                vri.compare(a, b, [0.01, bad])
        # FLIP, as vri-diff's: LDR always (the same numbers in both records, checked above), HDR on request.
        self.assertGreater(mine["metrics"]["flip"]["ldr"]["mean"], 0.0)
        self.assertNotIn("hdr", mine["metrics"]["flip"])
        code, err = run_tool("vri-diff", scratch("a.exr"), scratch("b.exr"), "--hdr-flip", "--json", scratch("hdr.json"))
        with open(scratch("hdr.json")) as f:
            tool = json.load(f)
        self.assertEqual(vri.compare(a, b, hdr_flip=True)["metrics"]["flip"], tool["metrics"]["flip"])
        self.assertGreater(tool["metrics"]["flip"]["hdr"]["exposures"]["count"], 1)


class AsUsersExpect(unittest.TestCase):
    def test_a_path_of_other_bytes_is_named(self):
        # Not UTF-8: the message escapes the bytes instead of arriving empty (issue 48, class 8).
        with self.assertRaisesRegex(vri.Error, r"\\xFF\\xFE\.raw: no such file"):
            vri.load_volume(b"/nonexistent/\xff\xfe.raw")

    def test_float64_is_rounded_to_float32(self):
        values = np.linspace(0.0, 1.0, 3 * 4 * 5).reshape(3, 4, 5)  # float64, NumPy's default
        volume = vri.Volume.from_array(values)
        self.assertEqual(volume.voxel_type, "float32")
        self.assertTrue(np.array_equal(volume.values(), values.astype(np.float32)))  # nearest float32, each

    def test_load_volume_looks_in_vri_data_dir(self):
        name = os.path.basename(blob_volume())
        old = os.environ.get("VRI_DATA_DIR")
        os.environ["VRI_DATA_DIR"] = SCRATCH
        try:
            self.assertEqual(vri.load_volume(name).dims, (24, 20, 16))
        finally:
            if old is None:
                del os.environ["VRI_DATA_DIR"]
            else:
                os.environ["VRI_DATA_DIR"] = old

    def test_compare_gives_vri_diffs_verdict(self):
        a = np.zeros((4, 4, 4), np.float32)
        b = a.copy()
        b[1, 2, 0:2] = 0.25  # one pixel, two channels: 2 of 64 pixel-channels, 1 of 16 pixels
        vri.write_exr(scratch("v-a.exr"), a)
        vri.write_exr(scratch("v-b.exr"), b)
        for options, kwargs in (([], {}), (["--fail", "0.5"], dict(fail=0.5)),
                                (["--fail", "0.5", "--warn", "0.5"], dict(fail=0.5, warn=0.5)),
                                (["--per-pixel", "--failpercent", "5"], dict(per_pixel=True, failpercent=5))):
            code, err = run_tool("vri-diff", scratch("v-a.exr"), scratch("v-b.exr"), *options, "--json",
                                 scratch("v.json"))
            with open(scratch("v.json")) as f:
                tool = json.load(f)
            mine = vri.compare(a, b, **kwargs)
            self.assertEqual(mine["exit_code"], code, options)
            for key in ("verdict", "fail", "warn"):
                self.assertEqual(mine[key], tool[key], (options, key))
        self.assertEqual(vri.compare(a, b)["verdict"], "fail")
        self.assertEqual(vri.compare(a, b, fail=0.5, warn=0.5)["verdict"], "pass")

    def test_reprs_say_what_they_hold(self):
        self.assertEqual(repr(vri.load_volume(blob_volume())),
                         "vri.Volume(dims=(24, 20, 16), voxel_type='uint8', spacing=(1.0, 1.0, 1.0), "
                         "origin=(0.0, 0.0, 0.0))")
        self.assertEqual(repr(vri.LinearField((5, 5, 5))), "vri.LinearField(dims=(5, 5, 5))")
        self.assertEqual(repr(vri.Camera(size=(32, 24), eye=(1, 2, 3))),
                         "vri.Camera(size=(32, 24), eye=(1.0, 2.0, 3.0), up=(0.0, 1.0, 0.0), fov=30)")
        self.assertEqual(repr(vri.TransferFunction([[0, 0, 0, 0, 0], [1, 1, 1, 1, 1]])),
                         "vri.TransferFunction(2 points, s from 0 to 1, emission='color-times-extinction')")


class BadInput(unittest.TestCase):
    def assertOneLine(self, expected, call, *args, **kwargs):
        with self.assertRaises(vri.Error) as raised:
            call(*args, **kwargs)
        message = str(raised.exception)
        self.assertNotIn("\n", message)
        self.assertEqual(message, expected)
        self.assertIsInstance(raised.exception, ValueError)

    def setUp(self):
        self.tf = vri.load_transfer_function(TF)
        self.field = vri.LinearField()

    def test_the_tools_line_for_the_same_file(self):
        missing = scratch("missing_8x8x8_uint8.raw")
        for path, extra in ((missing, []), (blob_volume(), ["--dims", "8,8,8", "--type", "uint8"])):
            code, err = run_tool("vri-render", "--volume", path, "--tf", TF, "-o", scratch("x.exr"), *extra)
            self.assertEqual(code, 1)
            tool_line = err.strip().removeprefix("vri-render: error: ")
            kwargs = dict(dims=(8, 8, 8), type="uint8") if extra else {}
            self.assertOneLine(tool_line, vri.load_volume, path, **kwargs)
        self.assertFalse(os.path.exists(scratch("x.exr")))

    def test_option_values(self):
        self.assertOneLine("step: expected a number > 0, got '-1'", vri.render, self.field, self.tf, step=-1)
        self.assertOneLine("method: unknown method 'simpsons' (expected riemann, composite, simpson, coupled, "
                           "decoupled or preintegrated)", vri.render, self.field, self.tf, method="simpsons")
        self.assertOneLine("--step, --rate: --method exact has no step", vri.render, self.field, self.tf,
                           method="exact", step=0.5)
        self.assertOneLine("threads: expected a whole number >= 1, got '0'", vri.render, self.field, self.tf, threads=0)
        self.assertOneLine("size: expected a positive image size WIDTHxHEIGHT, got '0x10'", vri.Camera, size=(0, 10))
        self.assertOneLine("convention: unknown grid convention 'corner' (expected cell or node)", vri.render,
                           self.field, self.tf, convention="corner")

    def test_unknown_keyword_names_the_known_ones(self):
        with self.assertRaises(vri.Error) as raised:
            vri.render(self.field, self.tf, stepsize=0.5)
        self.assertTrue(str(raised.exception).startswith("render: unknown keyword 'stepsize' (expected threads, "))
        with self.assertRaises(vri.Error):
            vri.reference(self.field, self.tf, step=0.5)  # the exact method has no step

    def test_arrays(self):
        self.assertOneLine("points: point 2 has s = 0.2 below the previous point's s = 0.5 (points must be sorted by s)",
                           vri.TransferFunction, [[0, 0, 0, 0, 0], [0.5, 1, 1, 1, 1], [0.2, 1, 1, 1, 1]])
        self.assertOneLine("array: expected uint8, uint16 or float32 voxels (kept), or int8, int16, int32, uint32 or "
                           "float64 (converted to float32), in native byte order; got int64", vri.Volume.from_array,
                           np.zeros((2, 2, 2), dtype=np.int64))
        self.assertOneLine("array: expected 3 dimensions [z, y, x], got 2 (one 2-D slice is array[None], a volume of "
                           "depth 1)", vri.Volume.from_array, np.zeros((4, 4), dtype=np.float64))
        self.assertOneLine("array: float64 voxel 1 is 1e+300, beyond float32's range (float64 volumes are kept as "
                           "float32)", vri.Volume.from_array, np.array([[[0.0, 1e300]]]))
        # A broadcast view of one byte standing for 64 GiB: refused by size before NumPy is asked for a copy (it
        # used to be copied first, and a failed copy dereferenced: SIGSEGV); a small one is copied and kept.
        with self.assertRaisesRegex(vri.Error, r"^array: needs 68719476736 bytes, limit"):
            vri.Volume.from_array(np.broadcast_to(np.zeros(1, np.uint8), (4096, 4096, 4096)))
        small = vri.Volume.from_array(np.broadcast_to(np.arange(3, dtype=np.uint8), (2, 2, 3)))
        self.assertTrue(np.array_equal(small.values(), np.broadcast_to(np.arange(3, dtype=np.uint8), (2, 2, 3))))
        self.assertOneLine("a: expected an image array of shape (height, width, channels)", vri.compare,
                           np.zeros((4, 4)), np.zeros((4, 4)))


class Gil(unittest.TestCase):
    def test_other_threads_run_while_it_renders(self):
        volume = vri.load_volume(blob_volume())
        tf = vri.load_transfer_function(TF)
        camera = vri.Camera(size=(160, 120), eye=EYE)
        done = {}

        def work():
            start = time.perf_counter()
            done["image"], _ = vri.render(volume, tf, camera, method="riemann", step=0.02, threads=1)
            done["seconds"] = time.perf_counter() - start

        thread = threading.Thread(target=work)
        thread.start()
        counted = 0
        while thread.is_alive():
            counted += 1
        thread.join()
        # Holding the GIL, the render would leave this loop a few switch intervals at most (5 ms each).
        self.assertGreater(done["seconds"], 0.1, "the render is long enough to tell")
        self.assertGreater(counted, 10000, f"{counted} loop turns in {done['seconds']:.2f} s")


if __name__ == "__main__":
    unittest.main(verbosity=2)
