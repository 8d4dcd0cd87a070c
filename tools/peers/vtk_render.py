#!/usr/bin/python3
"""vri-peer-vtk: VTK 9's volume ray casters as a peer of vri-render, on the same scene.

Reads the volume, camera and transfer function exactly as vri-render spells them, renders with VTK's
vtkFixedPointVolumeRayCastMapper (CPU) or vtkOpenGLGPUVolumeRayCastMapper (OpenGL; Mesa llvmpipe without a GPU)
and writes a float RGBA EXR, an optional PNG preview and a stats JSON shaped like vri-render's (timing,
stats, options, scene, provenance), so that vri-diff and vri-tabulate take it like any render.

The scene match (issue 16; each point is checked by tests/tools/peers.sh against vri-reference):
- Volume: read through vri's own reader (vri-convert writes the voxels as raw, --info --json says dims, type,
  spacing, origin and value range), so every format and check is vri-render's, and VTK's image reader with its
  y flip (FileLowerLeft off) is never involved.
- Placement: vri's cell convention puts voxel i at origin + (i + 1/2) spacing in the box [origin, origin + n
  spacing] and clamps to the edge; VTK puts point i at its origin + i spacing and renders only between its first
  and last point. So the volume gets one edge-replicated layer on every side (points at -1/2 and n + 1/2, where
  trilinear interpolation between equal values is the clamp), and the rays are cropped to vri's box with the
  mappers' cropping region. The node convention is VTK's own (origin, no padding).
- Camera: VTK's view angle is vertical like --fov; the read-back has row 0 at the bottom and is flipped.
- Transfer function: colour C(s) and opacity alpha(s) = 1 - exp(-tau(s) u) per opacity unit distance u, which
  VTK corrects to 1 - (1 - alpha)^(d / u) = 1 - exp(-tau d) at sample distance d: the composite rule of
  vri-render --method composite with emission C tau. Values come from vri-tf (vri's own evaluation), one point
  per raw value for 8-bit data; shading, gradient opacity, jittering, automatic sample distances and
  intermixed geometry are off.
Steps: --step h is in voxels like vri-render's; VTK's sample distance is h times the smallest spacing (world
units; equal to voxels at unit spacing, as in every paper scene but BluntFin's 1 x 0.75 x 1).
"""

import argparse
import ctypes
import hashlib
import json
import math
import os
import platform
import re
import shlex
import socket
import statistics
import subprocess
import sys
import tempfile
import time

TOOL = "vri-peer-vtk"
EXIT_USAGE = 64
EXIT_ERROR = 1
MAPPERS = {"vtk-fixed-point": "vtkFixedPointVolumeRayCastMapper", "vtk-gpu": "vtkOpenGLGPUVolumeRayCastMapper"}
MAX_PIXELS = 1 << 28  # 268 M pixels: one float RGBA image of at most 4 GiB
MAX_SAMPLES_PER_RAY = 1e9  # vri-render's limit


class InputError(Exception):
    """Bad input or a failed computation: one line on stderr, exit 1."""


class UsageError(Exception):
    """A bad argument: one line on stderr, exit 64."""


def printable(text):
    """Control characters from input shown as \\xNN, as vri's messages do."""
    return "".join(c if c.isprintable() else "\\x%02x" % ord(c) if ord(c) < 256 else c for c in str(text))


class ArgumentParser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message + " (see --help)")


# Numbers as vri's tools read them (libvri/util/parse.h): the whole text, ASCII digits only, no plus and no
# spaces; an integer decimal (a leading 0 is not octal) or hexadecimal after 0x, a number decimal or a
# hexadecimal float after 0x (0x1p-3), inf and nan being numbers whose range the option checks.
INTEGER_TEXT = re.compile(r"-?(?:0[xX][0-9a-fA-F]+|[0-9]+)")
DECIMAL_TEXT = re.compile(r"-?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?")
HEX_FLOAT_TEXT = re.compile(r"-?0[xX](?:[0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+)(?:[pP][-+]?[0-9]+)?")
SPECIAL_TEXT = re.compile(r"-?(?:inf|infinity|nan(?:\([0-9A-Za-z_]*\))?)", re.IGNORECASE)


def integer_from_text(text):
    """The whole text as one integer, or None."""
    if not INTEGER_TEXT.fullmatch(text):
        return None
    digits = text.lstrip("-")
    value = int(digits[2:], 16) if digits[:2] in ("0x", "0X") else int(digits, 10)
    return -value if text.startswith("-") else value


def number_from_text(text):
    """The whole text as one number, or None, as parse.h reads it: also None for a number beyond double's range
    either way, past its largest or so small that it would read as 0 (1e-999)."""
    def in_range(value, mantissa):
        underflow = value == 0 and any(d not in "0." for d in mantissa)
        return value if math.isfinite(value) and not underflow else None
    if HEX_FLOAT_TEXT.fullmatch(text):
        try:
            value = float.fromhex(text)
        except OverflowError:
            return None
        return in_range(value, re.split("[pP]", text.lstrip("-")[2:])[0])
    if SPECIAL_TEXT.fullmatch(text):  # nan(chars) is a NaN as std::from_chars reads it
        return float(text.split("(")[0])
    if DECIMAL_TEXT.fullmatch(text):
        return in_range(float(text), re.split("[eE]", text.lstrip("-"))[0])
    return None


def integer_option(text):
    """argparse's type for an integer option."""
    value = integer_from_text(text)
    if value is None:
        raise argparse.ArgumentTypeError("expected an integer (decimal, or hexadecimal after 0x), got '%s'"
                                         % printable(text))
    return value


def number_option(text):
    """argparse's type for a number option."""
    value = number_from_text(text)
    if value is None:
        raise argparse.ArgumentTypeError("expected a number, got '%s'" % printable(text))
    return value


def parse_vector(text, what, count=3):
    values = [number_from_text(v) for v in text.split(",")]
    if len(values) != count or not all(v is not None and math.isfinite(v) for v in values):
        raise UsageError("%s '%s': expected %d finite numbers separated by commas" % (what, text, count))
    return values


def parse_size(text):
    parts = text.split("x")
    if len(parts) != 2 or not all(re.fullmatch("[0-9]+", p) and 0 < int(p) <= 65536 for p in parts):
        raise UsageError("--size '%s': expected WIDTHxHEIGHT, each a whole number in 1..65536" % text)
    width, height = int(parts[0]), int(parts[1])
    if width * height > MAX_PIXELS:
        raise UsageError("--size %s: %d pixels, limit %d" % (text, width * height, MAX_PIXELS))
    return width, height


def arguments(argv):
    p = ArgumentParser(
        prog=TOOL, formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Render a volume with VTK's ray casters on vri-render's scene (camera, transfer function, cell "
                    "convention): float RGBA OpenEXR, an optional PNG preview and stats JSON like vri-render's.",
        epilog="Examples:\n"
               "  vri-peer-vtk --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/paper-b-bonsai.yaml \\\n"
               "      --size 800x600 --eye 128,190,-340 --target 128,115,128 --fov 38 --step 0.5 \\\n"
               "      --method vtk-fixed-point --repeat 3 -o vtk.exr --stats vtk.json\n"
               "  vri-peer-vtk ... --method vtk-gpu --step 0.25 -o vtk-gpu.exr      # OpenGL (llvmpipe without a GPU)\n"
               "  vri-peer-vtk ... --image raycast -o raw.exr     # the CPU mapper's 15-bit image, before display\n\n"
               "Without an X display it reruns itself under xvfb-run (Debian xvfb). Bad input is one error line\n"
               "and exit 1, a bad argument exit 64. Frames are timed from Render() through reading the pixels back.")
    p.add_argument("--card", help="a vri scene card (docs/scene-card.md, with its voxels): the volume, transfer "
                                  "function, camera, size and step from it, in place of those options; its stats "
                                  "then follow docs/outside-renderers.md (vri-outside runs the adapter so)")
    p.add_argument("--volume", help="volume file: .raw, .nhdr, .dat, .vdb (read by vri-convert)")
    p.add_argument("--dims", help="raw input: X,Y,Z (else taken from NAME_XxYxZ_TYPE.raw)")
    p.add_argument("--type", help="raw input: uint8, uint16 or float32")
    p.add_argument("--byte-order", help="raw input: little (default) or big")
    p.add_argument("--header-bytes", help="raw input: bytes to skip at the start")
    p.add_argument("--spacing", help="voxel spacing X,Y,Z, overriding what the input says")
    p.add_argument("--range", help="raw value range lo,hi that maps to s = 0..1 (default: vri-render's)")
    p.add_argument("--convention", default="cell", choices=["cell", "node"], help="grid convention (default cell)")
    p.add_argument("--tf", help="transfer function YAML")
    p.add_argument("--size", default="800x600", help="image size WIDTHxHEIGHT (default 800x600)")
    p.add_argument("--eye", help="camera position X,Y,Z")
    p.add_argument("--target", help="point looked at X,Y,Z")
    p.add_argument("--up", default="0,1,0", help="up vector X,Y,Z (default 0,1,0)")
    p.add_argument("--fov", type=number_option, default=30.0, help="vertical field of view, degrees (default 30)")
    p.add_argument("--method", default="vtk-fixed-point", choices=sorted(MAPPERS),
                   help="vtk-fixed-point (CPU, 15-bit fixed point) or vtk-gpu (OpenGL)")
    p.add_argument("--step", type=number_option, default=0.5, help="sample distance in voxels (default 0.5)")
    p.add_argument("--image", default="display", choices=["display", "raycast"],
                   help="display: the 8-bit frame VTK shows (default); raycast: vtk-fixed-point's 15-bit ray-cast "
                        "image, before it is drawn (no display resampling, no 8-bit rounding)")
    p.add_argument("--threads", type=integer_option, help="vtk-fixed-point's threads (default: all usable cores)")
    p.add_argument("--warm-up", type=integer_option, default=1, help="untimed frames first (default 1)")
    p.add_argument("--repeat", type=integer_option, default=3, help="timed frames; the stats give their median (default 3)")
    p.add_argument("-o", "--output", required=True, help="output image (.exr: float RGBA)")
    p.add_argument("--png", help="8-bit preview PNG")
    p.add_argument("--stats", help="statistics and provenance as JSON")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress on stderr")
    # An option's value is the next word, as vri's tools read it, even where it starts with '-' (--eye -20,4,4),
    # which argparse would take for an option: such a pair goes on as one word.
    joined, words = [], iter(argv)
    for word in words:
        action = p._option_string_actions.get(word)
        value = next(words, None) if action is not None and action.nargs is None else None
        if value is None:
            joined.append(word)
        elif value.startswith("-"):
            joined.append(word + "=" + value)
        else:
            joined += [word, value]
    argv = joined
    # As vri's tools (CLI11) do: an unknown option is named before any missing required one.
    for word in argv:
        name = word.split("=", 1)[0]
        if name.startswith("-") and name != "-" and name not in p._option_string_actions:
            raise UsageError("The following argument was not expected: " + word + " (see --help)")
    a = p.parse_args(argv)
    if a.card:
        scene_from_card(a, [w.split("=", 1)[0] for w in argv])
    else:
        missing = [o for o in ("--volume", "--tf", "--eye", "--target") if getattr(a, o[2:]) is None]
        if missing:
            raise UsageError("the following arguments are required: " + ", ".join(missing))

    a.width, a.height = parse_size(a.size)
    a.eye_v = parse_vector(a.eye, "--eye")
    a.target_v = parse_vector(a.target, "--target")
    a.up_v = parse_vector(a.up, "--up")
    a.range_v = parse_vector(a.range, "--range", 2) if a.range else None
    if a.range_v and not a.range_v[0] < a.range_v[1]:
        raise UsageError("--range %s: expected lo < hi" % a.range)
    if not 0 < a.fov < 180:
        raise UsageError("--fov %g: expected degrees in (0, 180)" % a.fov)
    if not 0 < a.step < float("inf"):
        raise UsageError("--step %g: expected a number > 0" % a.step)
    for name, value, lowest in (("--warm-up", a.warm_up, 0), ("--repeat", a.repeat, 1),
                                ("--threads", a.threads, 1)):
        if value is not None and not lowest <= value <= 1000:
            raise UsageError("%s %d: expected a whole number in %d..1000" % (name, value, lowest))
    if a.image == "raycast" and a.method != "vtk-fixed-point":
        raise UsageError("--image raycast: only vtk-fixed-point has a ray-cast image")
    if not a.output.lower().endswith(".exr"):
        raise UsageError("-o %s: expected an .exr file" % printable(a.output))
    if a.png and not a.png.lower().endswith(".png"):
        raise UsageError("--png %s: expected a .png file" % printable(a.png))
    outputs = [o for o in (a.output, a.png, a.stats) if o]
    if len(set(os.path.realpath(o) for o in outputs)) != len(outputs):
        raise UsageError("-o, --png and --stats must name different files")
    for path in outputs:
        check_output_path(path)
    return a


CARD_OPTIONS = ("--volume", "--dims", "--type", "--byte-order", "--header-bytes", "--spacing", "--range",
                "--convention", "--tf", "--size", "--eye", "--target", "--up", "--fov", "--step")


def scene_from_card(a, given):
    """The scene options from a vri scene card: the card's voxels (its plain raw layout), value range, grid
    convention, transfer function (written as YAML beside the outputs' temporary folder), camera, size and
    step. A scene option given beside --card is refused: the card is the scene."""
    both = [o for o in CARD_OPTIONS if o in given]
    if both:
        raise UsageError("--card: %s would override the card's scene (give one or the other)" % ", ".join(both))
    try:
        with open(a.card, encoding="utf-8") as f:
            card = json.load(f)
    except (OSError, ValueError) as e:
        raise InputError("%s: cannot read the card: %s" % (printable(a.card), printable(e)))
    if card.get("format") != "vri-scene-card" or card.get("version") != 1:
        raise InputError("%s: not a version 1 vri scene card" % printable(a.card))
    volume, camera, method = card["volume"], card["camera"], card["method"]
    if volume["kind"] != "volume" or "file" not in volume.get("voxels", {}):
        raise InputError("%s: VTK renders sampled volumes: the card needs its voxels (vri-render --describe-voxels)"
                         % printable(a.card))
    if method.get("kind") != "fixed-step":
        raise InputError("%s: the card's method is %s: VTK's ray casters take a fixed step" % (printable(a.card), method.get("kind")))
    text = lambda v: ",".join(repr(float(x)) for x in v)
    a.volume = os.path.join(os.path.dirname(os.path.abspath(a.card)), volume["voxels"]["file"])
    a.dims = ",".join(str(n) for n in volume["dims"])
    a.type, a.byte_order, a.header_bytes = volume["voxels"]["voxel_type"], "little", None
    a.spacing = text(volume["spacing"])
    a.range = text([volume["value_to_s"]["lo"], volume["value_to_s"]["hi"]])
    a.convention = volume["grid_convention"]
    a.size = "%dx%d" % (camera["width"], camera["height"])
    a.eye, a.target, a.up = text(camera["eye"]), text(camera["target"]), text(camera["up"])
    a.fov = float(camera["fov_y_degrees"])
    if camera["zoom"] != 1.0:
        raise InputError("%s: a zoomed card (zoom %g): VTK's camera has no off-centre close-up" % (printable(a.card), camera["zoom"]))
    a.step = float(method["step"])
    tf = card["transfer_function"]
    a.tf_text = "emission: %s\npoints:\n" % tf["emission"] + "".join(
        "  - [%r, %r, %r, %r, %r]\n" % (p["s"], p["r"], p["g"], p["b"], p["tau"]) for p in tf["points"])


# --- Outputs: written beside themselves and renamed into place once complete (vri's atomic_file.h rule). ---

def check_output_path(path):
    """Only a regular file (or a link to one) is ever replaced; its folder must exist. Checked before any work."""
    target = os.path.realpath(path)
    if os.path.isdir(target):
        raise InputError("%s: cannot write: it is a directory; expected a regular file" % printable(path))
    if os.path.lexists(target) and not os.path.isfile(target):
        raise InputError("%s: cannot write: it is not a regular file (a device, FIFO or socket); %s writes regular "
                         "files only" % (printable(path), TOOL))
    if not os.path.isdir(os.path.dirname(target) or "."):
        raise InputError("%s: cannot write: no such folder" % printable(path))


def write_atomically(path, write):
    """Calls write(temporary path), then fsyncs and renames it over `path` (through a symlink, to its target)."""
    target = os.path.realpath(path)
    folder, name = os.path.split(target)
    fd, temporary = tempfile.mkstemp(prefix="." + name + ".tmp.%d." % os.getpid(), dir=folder or ".")
    os.close(fd)
    try:
        write(temporary)
        with open(temporary, "rb+") as f:
            os.fsync(f.fileno())
        if os.path.exists(target):
            os.chmod(temporary, os.stat(target).st_mode & 0o7777)
        else:
            mask = os.umask(0)
            os.umask(mask)
            os.chmod(temporary, 0o666 & ~mask)
        os.replace(temporary, target)
    except BaseException:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise


def write_image(path, rgba, eight_bit):
    import OpenImageIO as oiio

    def write(temporary):
        height, width, _ = rgba.shape
        # The preview is colour over black, as vri-render's with its default background.
        spec = oiio.ImageSpec(width, height, 3, oiio.UINT8) if eight_bit else \
            oiio.ImageSpec(width, height, 4, oiio.FLOAT)
        out = oiio.ImageOutput.create(path)
        if out is None or not out.open(temporary, spec):
            raise InputError("%s: cannot write: %s" % (printable(path), oiio.geterror()))
        data = (rgba[:, :, :3].clip(0, 1) * 255 + 0.5).astype("uint8") if eight_bit else rgba.astype("float32")
        ok = out.write_image(data)
        ok = out.close() and ok
        if not ok:
            raise InputError("%s: cannot write: %s" % (printable(path), out.geterror()))

    write_atomically(path, write)


def write_json(path, document):
    def write(temporary):
        with open(temporary, "w") as f:
            json.dump(document, f, indent=2, sort_keys=True)
            f.write("\n")

    write_atomically(path, write)


# --- Inputs, through vri's own tools beside this one. ---

def vri_tool(name):
    path = os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), name)
    if not os.access(path, os.X_OK):
        raise InputError("%s: not found beside %s (run the copy in the build's bin folder)" % (name, TOOL))
    return path


def run_vri_tool(words):
    """Runs a vri tool; its one error line becomes ours, with its exit code's meaning."""
    done = subprocess.run(words, stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL)
    if done.returncode != 0:
        lines = done.stderr.decode(errors="replace").strip().splitlines() or ["failed"]
        message = lines[-1].split(": error: ", 1)[-1]
        raise (UsageError if done.returncode == EXIT_USAGE else InputError)(message)
    return done.stdout


def read_volume(a, folder):
    """The voxels as vri reads them: (numpy array indexed [z, y, x], info JSON of vri-convert --info)."""
    import numpy as np

    raw_options = []
    for option in ("dims", "type", "byte_order", "header_bytes", "spacing"):
        value = getattr(a, option)
        if value is not None:
            raw_options += ["--" + option.replace("_", "-"), value]
    convert = vri_tool("vri-convert")
    info = json.loads(run_vri_tool([convert, "--info", "--json", *raw_options, "--", a.volume]))
    voxels = os.path.join(folder, "voxels.raw")
    run_vri_tool([convert, "-q", *raw_options, "--", a.volume, voxels])
    dtype = {"uint8": "<u1", "uint16": "<u2", "float32": "<f4"}.get(info["voxel_type"])
    if dtype is None:
        raise InputError("%s: voxel type %s is not supported" % (printable(a.volume), info["voxel_type"]))
    nx, ny, nz = info["dims"]
    if a.convention == "node" and min(info["dims"]) < 2:
        raise InputError("the node-centred convention needs at least 2 voxels along every axis")
    data = np.fromfile(voxels, dtype=dtype)
    if data.size != nx * ny * nz:
        raise InputError("%s: vri-convert wrote %d voxels, expected %d"
                         % (printable(a.volume), data.size, nx * ny * nz))
    return data.reshape(nz, ny, nx), info


def read_transfer_function(a, voxel_type, folder):
    """(s, r, g, b, tau) rows from vri-tf: one per raw value for 8-bit data (s = k / 255), else 4097 evenly
    spaced and every breakpoint. At a jump the right-hand value is kept, as vri evaluates it."""
    import yaml

    with open(a.tf, "rb") as f:
        emission = (yaml.safe_load(f) or {}).get("emission", "color-times-extinction")
    table = os.path.join(folder, "tf.csv")
    samples = 256 if voxel_type == "uint8" else 4097
    run_vri_tool([vri_tool("vri-tf"), "--samples", str(samples), "-o", table, "--", a.tf])
    if emission != "color-times-extinction":
        raise InputError("%s: emission %s: VTK composites colour times opacity, i.e. emission colour times extinction "
                         "(color-times-extinction) only" % (printable(a.tf), printable(emission)))
    rows = {}
    with open(table) as f:
        next(f)
        for line in f:
            s, r, g, b, tau = (float(v) for v in line.split(",")[:5])
            if voxel_type == "uint8" and abs(s * 255 - round(s * 255)) > 1e-9:
                continue  # a breakpoint between raw values: VTK's 8-bit table never reads it
            rows[s] = (s, r, g, b, tau)  # a jump's right-hand value replaces the left
    return sorted(rows.values())


# --- The VTK scene. ---

def build_scene(a, voxels, info, tf_rows):
    import numpy as np
    import vtk
    from vtk.util import numpy_support

    spacing = info["spacing"]
    origin = info["origin"]
    dims = info["dims"]
    lo, hi = a.range_v or info["normalisation_range"]
    # The GPU mapper of VTK 9.1 on llvmpipe ignores the cropping box inside the padding (and clipping planes
    # likewise): it gets VTK's own placement, origin 1/2, and loses vri's half-voxel rim of clamped values.
    padded = a.convention == "cell" and a.method == "vtk-fixed-point"
    if padded:
        voxels = np.pad(voxels, 1, mode="edge")
        vtk_origin = [o - 0.5 * d for o, d in zip(origin, spacing)]
    else:
        vtk_origin = [o + 0.5 * d for o, d in zip(origin, spacing)] if a.convention == "cell" else list(origin)
    box = [(o, o + (n if a.convention == "cell" else n - 1) * d) for o, n, d in zip(origin, dims, spacing)]
    image = vtk.vtkImageData()
    image.SetDimensions(voxels.shape[2], voxels.shape[1], voxels.shape[0])
    image.SetSpacing(*spacing)
    image.SetOrigin(*vtk_origin)
    scalars = numpy_support.numpy_to_vtk(np.ascontiguousarray(voxels).ravel(), deep=True)
    image.GetPointData().SetScalars(scalars)

    unit = min(spacing)  # the opacity unit distance: one voxel of the finest axis
    colour = vtk.vtkColorTransferFunction()
    opacity = vtk.vtkPiecewiseFunction()
    for s, r, g, b, tau in tf_rows:
        value = lo + s * (hi - lo)
        colour.AddRGBPoint(value, r, g, b)
        opacity.AddPoint(value, -np.expm1(-tau * unit))
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(colour)
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(unit)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()
    prop.DisableGradientOpacityOn()

    distance = a.step * unit
    if a.method == "vtk-fixed-point":
        mapper = vtk.vtkFixedPointVolumeRayCastMapper()
        mapper.SetNumberOfThreads(a.threads)
        mapper.SetImageSampleDistance(1.0)
        mapper.SetMinimumImageSampleDistance(1.0)
        mapper.SetMaximumImageSampleDistance(1.0)
        mapper.SetInteractiveSampleDistance(distance)
        mapper.IntermixIntersectingGeometryOff()
    else:
        mapper = vtk.vtkOpenGLGPUVolumeRayCastMapper()
        mapper.SetUseJittering(0)
    mapper.SetSampleDistance(distance)
    mapper.AutoAdjustSampleDistancesOff()
    mapper.LockSampleDistanceToInputSpacingOff()
    mapper.SetBlendModeToComposite()
    mapper.SetInputData(image)
    if padded:
        mapper.SetCropping(1)
        mapper.SetCroppingRegionPlanes(box[0][0], box[0][1], box[1][0], box[1][1], box[2][0], box[2][1])
        mapper.SetCroppingRegionFlagsToSubVolume()

    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtk.vtkRenderer()
    renderer.AddVolume(volume)
    renderer.SetBackground(0, 0, 0)
    renderer.SetBackgroundAlpha(0)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(*a.eye_v)
    camera.SetFocalPoint(*a.target_v)
    camera.SetViewUp(*a.up_v)
    camera.SetViewAngle(a.fov)
    camera.UseHorizontalViewAngleOff()
    renderer.ResetCameraClippingRange()
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetAlphaBitPlanes(1)
    window.SetSize(a.width, a.height)
    window.AddRenderer(renderer)
    scene = {"convention": a.convention, "kind": "volume", "voxel_type": info["voxel_type"], "dims": dims,
             "spacing": spacing, "box_lo": [b[0] for b in box], "box_hi": [b[1] for b in box],
             "normalisation_range": [lo, hi], "vtk_origin": vtk_origin,
             "vtk_dims": [voxels.shape[2], voxels.shape[1], voxels.shape[0]],
             "vtk_placement": "edge-replicated layer, cropped to the box" if padded else
                              "VTK's points from origin 1/2 (no rim)" if a.convention == "cell" else "VTK's points"}
    options = {"method": a.method, "mapper": MAPPERS[a.method], "step_voxels": a.step,
               "sample_distance_world": distance, "opacity_unit_distance": unit, "image": a.image,
               "interpolation": "linear", "shading": False, "gradient_opacity": False,
               "auto_adjust_sample_distances": False, "transfer_function_points": len(tf_rows),
               "early_termination": "VTK's own (not configurable)"}
    if a.method == "vtk-fixed-point":
        options["image_sample_distance"] = 1.0
    else:
        options["jittering"] = False
    return window, mapper, scene, options


def read_display(window, width, height):
    """The frame as VTK shows it: 8 bits per channel, row 0 at the bottom, flipped to vri's row 0 at the top."""
    import vtk
    from vtk.util import numpy_support

    pixels = vtk.vtkUnsignedCharArray()
    window.GetRGBACharPixelData(0, 0, width - 1, height - 1, 0, pixels)
    rgba = numpy_support.vtk_to_numpy(pixels).reshape(height, width, 4)[::-1]
    return rgba.astype("float64") / 255.0


def read_raycast_image(mapper, width, height):
    """vtk-fixed-point's ray-cast image, 15 bits per channel (32767 = 1), placed at its image origin in the
    viewport, row 0 at the bottom. Python sees the buffer only as an address ('_<hex>_p_void')."""
    import numpy as np

    image = mapper.GetRayCastImage()
    memory_x, memory_y = image.GetImageMemorySize()
    used_x, used_y = image.GetImageInUseSize()
    origin_x, origin_y = image.GetImageOrigin()
    if image.GetImageSampleDistance() != 1.0 or image.GetImageViewportSize() != (width, height):
        raise InputError("the ray-cast image does not cover the viewport one ray per pixel")
    address = int(image.GetImage().split("_")[1], 16)
    buffer = (ctypes.c_ushort * (memory_x * memory_y * 4)).from_address(address)
    raw = np.frombuffer(buffer, dtype=np.uint16).reshape(memory_y, memory_x, 4)
    rgba = np.zeros((height, width, 4))
    ux, uy = min(used_x, width - origin_x), min(used_y, height - origin_y)
    rgba[origin_y:origin_y + uy, origin_x:origin_x + ux] = raw[:uy, :ux] / 32767.0
    return rgba[::-1]


# --- Provenance. ---

def sha512(path):
    digest = hashlib.sha512()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def os_release():
    try:
        with open("/etc/os-release") as f:
            for line in f:
                if line.startswith("PRETTY_NAME="):
                    return line.split("=", 1)[1].strip().strip('"')
    except OSError:
        pass
    return "unknown"


def machine():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((l.split(":", 1)[1].strip() for l in f if l.startswith("model name")), cpu)
    except OSError:
        pass
    return {"cpu_model": cpu, "logical_cores": os.cpu_count(), "usable_cores": len(os.sched_getaffinity(0)),
            "memory_bytes": os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"), "os": os_release(),
            "kernel": platform.release(), "hostname": socket.gethostname()}


def opengl_renderer(window):
    for line in window.ReportCapabilities().splitlines():
        if line.startswith("OpenGL renderer string:"):
            return line.split(":", 1)[1].strip()
    return "unknown"


# --- Main. ---

def render(a):
    import numpy as np
    import OpenImageIO as oiio

    if a.threads is None:
        a.threads = len(os.sched_getaffinity(0))
    with tempfile.TemporaryDirectory(prefix="vri-peer-vtk.") as folder:
        if a.card:  # the card's transfer function as the YAML vri-tf reads; the card names it in the stats
            a.tf = os.path.join(folder, "card-tf.yaml")
            with open(a.tf, "w", encoding="utf-8") as f:
                f.write(a.tf_text)
        voxels, info = read_volume(a, folder)
        tf_rows = read_transfer_function(a, info["voxel_type"], folder)
        inputs = [{"path": p, "sha512": sha512(p)} for p in ((a.card, a.volume) if a.card else (a.volume, a.tf))]
    longest = sum((n * d / min(info["spacing"])) ** 2 for n, d in zip(info["dims"], info["spacing"])) ** 0.5
    if longest / a.step > MAX_SAMPLES_PER_RAY:
        raise UsageError("--step %g would put more than 1e9 samples on a ray through this volume" % a.step)
    import vtk  # after every check: VTK's libraries alone make a quarter of a gigabyte resident
    window, mapper, scene, options = build_scene(a, voxels, info, tf_rows)
    read = (lambda: read_raycast_image(mapper, a.width, a.height)) if a.image == "raycast" else \
        (lambda: read_display(window, a.width, a.height))
    for _ in range(a.warm_up):
        window.Render()
        read()
    seconds, frames = [], []
    for frame in range(a.repeat):
        start = time.perf_counter()
        window.Render()
        rgba = read()
        seconds.append(time.perf_counter() - start)
        frames.append(rgba)
        if not a.quiet:
            print("%s: frame %d/%d: %.3f s" % (TOOL, frame + 1, a.repeat, seconds[-1]), file=sys.stderr)
    differing = sum(1 for f in frames[1:] if not np.array_equal(f, frames[0]))
    if differing and not a.quiet:
        print("%s: warning: %d of %d frames differ from the first (VTK's threads)" % (TOOL, differing, a.repeat),
              file=sys.stderr)
    image = frames[0].astype("float32")

    write_image(a.output, image, eight_bit=False)
    if a.png:
        write_image(a.png, image, eight_bit=True)
    if a.stats:
        stats = {"wall_seconds": seconds[0], "threads": a.threads if a.method == "vtk-fixed-point" else None,
                 "rays": a.width * a.height, "backend": "vtk", "frames_differing": differing,
                 "nonfinite_pixels": int(np.count_nonzero(~np.isfinite(image)))}
        if a.method == "vtk-gpu":
            stats["device"] = opengl_renderer(window)
            stats["llvmpipe_threads"] = os.environ.get("LP_NUM_THREADS", "all cores")
        rows = [[s, r, g, b, tau] for s, r, g, b, tau in tf_rows]
        argv = [TOOL] + sys.argv[1:]
        document = {
            "tool": TOOL,
            "time_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
            "build": {"vtk": vtk.vtkVersion.GetVTKVersion(), "python": platform.python_version(),
                      "numpy": np.__version__, "openimageio": oiio.__version__,
                      "adapter_sha512": sha512(os.path.abspath(sys.argv[0]))},
            "command": {"argv": argv, "shell": shlex.join(argv)},
            "inputs": inputs,
            "machine": machine(),
            "camera": {"eye": a.eye_v, "target": a.target_v, "up": a.up_v, "fov_y_degrees": a.fov,
                       "width": a.width, "height": a.height, "zoom": 1.0, "zoom_centre": None},
            "options": options,
            "scene": scene,
            "stats": stats,
            "timing": {"median_wall_seconds": statistics.median(seconds), "repeats": a.repeat,
                       "warm_up": a.warm_up, "wall_seconds": seconds,
                       "timed": "Render() through reading the frame back"},
            "transfer_function": {"emission": "color-times-extinction", "points_s_r_g_b_tau": rows,
                                  "source": a.card or a.tf},
        }
        if a.card:  # the outside-renderer record vri-outside reads (docs/outside-renderers.md)
            document.update({"format": "vri-outside-stats", "version": 1,
                             "renderer": {"name": "VTK " + MAPPERS[a.method], "version": vtk.vtkVersion.GetVTKVersion()},
                             "image": {"quantisation": "8-bit" if a.image == "display" else "15-bit fixed point"}})
            document["timing"]["what"] = "frame"
        write_json(a.stats, document)


def rerun_under_xvfb(a):
    """VTK's Debian build draws through X: without a display, run again inside a private Xvfb."""
    if os.environ.get("DISPLAY") or os.environ.get("VRI_PEER_XVFB"):
        return
    xvfb = "/usr/bin/xvfb-run"
    if not os.access(xvfb, os.X_OK):
        raise InputError("no X display and no xvfb-run (install Debian's xvfb, or set DISPLAY)")
    screen = "-screen 0 %dx%dx24" % (max(a.width, 640), max(a.height, 480))
    env = dict(os.environ, VRI_PEER_XVFB="1")
    script = os.path.abspath(sys.argv[0])
    done = subprocess.run([xvfb, "-a", "-s", screen, sys.executable, script, *sys.argv[1:]], env=env)
    sys.exit(done.returncode)


def version_text():
    """vri's --version form: the adapter carries the version and build of the vri tools beside it."""
    convert = subprocess.run([vri_tool("vri-convert"), "--version"], capture_output=True, text=True, check=True)
    lines = convert.stdout.splitlines()
    return "\n".join([lines[0].replace("vri-convert", TOOL, 1)] + lines[1:])


def main():
    try:
        if "--version" in sys.argv[1:]:
            print(version_text())
            return 0
        a = arguments(sys.argv[1:])
        rerun_under_xvfb(a)
        render(a)
    except UsageError as e:
        print("%s: error: %s" % (TOOL, printable(e)), file=sys.stderr)
        return EXIT_USAGE
    except (InputError, OSError, ValueError) as e:
        print("%s: error: %s" % (TOOL, printable(e)), file=sys.stderr)
        return EXIT_ERROR
    except ImportError as e:
        print("%s: error: %s (install python3-vtk9, python3-numpy, python3-openimageio, python3-yaml)"
              % (TOOL, printable(e)), file=sys.stderr)
        return EXIT_ERROR
    return 0


if __name__ == "__main__":
    sys.exit(main())
