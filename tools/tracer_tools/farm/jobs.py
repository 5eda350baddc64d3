"""The farm's jobs: a scene with its command-line overrides and output, checked once before any tile."""

from __future__ import annotations

import hashlib
import json
import os
import re
import subprocess
from dataclasses import dataclass, field

from tracer_tools import option_types

FLOAT_FORMATS = (".exr", ".hdr", ".pfm")  # as tracer: these get unclamped float pixels, others 8 bits
OVERRIDES = ("samples", "width", "height", "max_depth")  # job keys passed on as tracer's options


class JobError(Exception):
    """A job that cannot run: the message to print, the exit code (tracer's codes), and whether the
    message is tracer's own diagnostic (printed as it is, not after "farm: error:")."""

    def __init__(self, message: str, exit_code: int, tracers_own: bool = False) -> None:
        super().__init__(message)
        self.exit_code = exit_code
        self.tracers_own = tracers_own


@dataclass
class Job:
    scene: str  # absolute path
    output: str  # absolute path
    defines: dict[str, str] = field(default_factory=dict)
    overrides: dict[str, str] = field(default_factory=dict)  # samples, width, height, max_depth
    width: int = 0  # the frame, as tracer --check reports it
    height: int = 0
    srgb: bool = False  # 8-bit files sRGB-encoded, as tracer --check reports it (the tiles are; the file says so)
    inputs: list[str] = field(default_factory=list)  # the other files it reads, as tracer --check lists them
    manifest: dict = field(default_factory=dict)  # what its image depends on (resume.identity)
    animation: list[str] = field(default_factory=list)  # tracer's --frames N [--clock A:B] [--cyclic]

    def tracer_arguments(self) -> list[str]:
        """The scene and its overrides as tracer's command line."""
        arguments = [self.scene]
        for name, value in self.defines.items():
            arguments += ["-D", f"{name}={value}"]
        for key, value in self.overrides.items():
            arguments += ["--" + key.replace("_", "-"), str(value)]
        return arguments + self.animation

    def is_float(self) -> bool:
        return os.path.splitext(self.output)[1].lower() in FLOAT_FORMATS

    def key(self, index: int) -> str:
        """A name for the job's tracer processes on the workers, unique within one run."""
        digest = hashlib.sha1(json.dumps([os.getpid(), index, self.tracer_arguments()]).encode()).hexdigest()
        return f"job-{index}-{digest[:12]}"


def jobs_from_file(path: str) -> list[Job]:
    """The jobs of a JSON file: a list of {"scene", "output", "define": {NAME: VALUE}, "samples", "width",
    "height", "max_depth"}; paths relative to the file's folder."""
    try:
        # A FIFO or a device would block or never end: only a regular file of bounded size is read.
        entries = json.loads(option_types.read_regular_file(path))
    except option_types.UnreadableFile as error:
        raise JobError(f"cannot read '{path}': {error}", 3) from error
    except (json.JSONDecodeError, UnicodeDecodeError) as error:
        raise JobError(f"{path}: not a JSON list of jobs: {error}", 2) from error
    if not isinstance(entries, list) or not entries:
        raise JobError(f"{path}: expected a non-empty JSON list of jobs", 2)
    folder = os.path.dirname(os.path.abspath(path))
    jobs = []
    for number, entry in enumerate(entries, 1):
        where = f"{path}: job {number}"
        if (
            not isinstance(entry, dict)
            or not isinstance(entry.get("scene"), str)
            or not isinstance(entry.get("output"), str)
        ):
            raise JobError(f'{where}: each job needs "scene" and "output" paths', 2)
        if "\0" in entry["scene"] or "\0" in entry["output"]:
            raise JobError(f"{where}: a path with a NUL byte (no file can have one)", 2)
        unknown = set(entry) - {"scene", "output", "define", *OVERRIDES}
        if unknown:
            raise JobError(f"{where}: unknown key(s) {', '.join(sorted(unknown))}", 2)
        defines = entry.get("define", {})
        if not isinstance(defines, dict):
            raise JobError(f'{where}: "define" is an object of NAME: VALUE', 2)
        jobs.append(
            Job(
                scene=os.path.join(folder, entry["scene"]),
                output=os.path.join(folder, entry["output"]),
                defines={str(name): str(value) for name, value in defines.items()},
                overrides={key: str(entry[key]) for key in OVERRIDES if key in entry},
            )
        )
    written = set()  # linear in the jobs (a count per output was quadratic: 4x10^4 jobs took 15 s)
    real_folders: dict[str, str] = {}  # each folder's real path, resolved once
    for job in jobs:
        folder, name = os.path.split(job.output)
        real = real_folders.get(folder) or real_folders.setdefault(folder, os.path.realpath(folder))
        output = os.path.join(real, name)
        if output in written:
            raise JobError(f"{path}: two jobs write '{output}'", 2)
        written.add(output)
    return jobs


_IMAGE_LINE = re.compile(r"^  image: (\d+) x (\d+) pixels(.*)$", re.MULTILINE)
_READS_LINE = re.compile(r"^  reads: (.*)$", re.MULTILINE)


def check_job(tracer: str, job: Job, extra: tuple[str, ...] = ()) -> str:
    """Checks the job's scene with `tracer --check` (with its overrides, and `extra` options) and sets its
    frame size; raises JobError with tracer's own diagnostics. Returns tracer's warnings (may be empty)."""
    result = subprocess.run([tracer, "--check", *job.tracer_arguments(), *extra], capture_output=True, text=True)
    if result.returncode != 0:
        raise JobError(result.stderr.rstrip(), result.returncode, tracers_own=True)
    size = _IMAGE_LINE.search(result.stdout)
    if not size:
        raise JobError(f"'{tracer} --check' did not report the image size; is it an older tracer?", 3)
    job.width, job.height = int(size.group(1)), int(size.group(2))
    job.srgb = size.group(3).endswith(", 8-bit files sRGB-encoded")
    job.inputs = _READS_LINE.findall(result.stdout)
    return result.stderr


# The formats tracer writes without OpenImageIO (libpng, its own PPM writer; OpenImageIO, which
# writes the tiles' images, always has both): no need to load its 260 libraries (0.03 s) to know
# they can be written.
TRACERS_OWN_FORMATS = (".png", ".ppm")


class OutputChecks:
    """Whether jobs' outputs can be written, each folder and each format checked once."""

    def __init__(self) -> None:
        self.folders: set[str] = set()
        self.formats: set[str] = set()

    def check(self, job: Job) -> None:
        """Raises JobError if the job's output cannot be written: no such folder, not writable, an
        unknown format (OpenImageIO's), or the scene file itself."""
        folder = os.path.dirname(job.output) or "."
        if folder not in self.folders:
            if not os.path.isdir(folder):
                raise JobError(f"cannot write '{job.output}': no such folder '{folder}'", 3)
            if not os.access(folder, os.W_OK):
                raise JobError(f"cannot write '{job.output}': the folder is not writable", 3)
            self.folders.add(folder)
        extension = os.path.splitext(job.output)[1].lower()
        if extension not in self.formats and extension not in TRACERS_OWN_FORMATS:
            import OpenImageIO as oiio

            if oiio.ImageOutput.create(job.output) is None:
                raise JobError(
                    f"cannot write '{job.output}': unknown image format (use .png, .exr, .jpg, .tif, ...)", 3
                )
            self.formats.add(extension)
        if os.path.exists(job.output) and os.path.samefile(job.output, job.scene):
            raise JobError(f"-o '{job.output}' is the scene file; choose another output path", 2)
