#!/usr/bin/env python3
"""Checks that every #include in src/ follows coinroll's layering (docs/architecture.md).

Usage: check_layering.py [SRC_DIR]      (default: the src/ beside this script's tools/)

All libraries share src/ as their include root (headers are included as "folder/x.h"), so
the compiler cannot stop src/render/ from including "scene/...". This script can: it reads
every #include in src/**, and reports, one per line as file:line: message,
  - an include of another coinroll folder that MAY_INCLUDE below does not allow;
  - an include of a third-party or std header that NEVER below forbids to that folder;
  - an include of test or benchmark code (tests/, bench/) or one that climbs out with "../";
  - a folder of src/ that the table does not know (a new library must state its place).
It exits 0 when all is well, 1 on any violation, 2 on a usage error. Python 3 stdlib only.
The table encodes the house style's section 1 ("one direction of flow", the folder table)
and what the code legitimately does today: a new edge needs a reason, written next to it.
"""

import pathlib
import re
import sys

# Which coinroll folders each folder may #include, each edge with the reason it exists.
# A key "folder" allows every header of that folder; a key "folder/x.h" allows that one
# header only (a settings-only header that a lower layer may read without seeing the rest).
# A folder may always include its own headers. Includes point down only (docs/architecture.md):
#   cli > pipeline > scene > {physics, integrate};  pipeline > {render, video} > image > io.
# physics and integrate are independent of each other: pipeline wires the rhs into a stepper.
MAY_INCLUDE = {
    # Leaf utility: atomic file writes. Depends on nothing of ours.
    "io": {},
    # Leaf utility: the RGBA Image type and PNG reading/writing.
    "image": {
        "io": "PNGs are written through io::OutputFile so a crash never leaves half a file",
    },
    # draw(FrameSnapshot) -> Image; never physics/integrate/scene/pipeline/video.
    "render": {
        "image": "the renderer returns an image::Image and reads PNG textures",
        "io": "leaf utility for anything that writes files",
    },
    # FrameSink per format; never render/physics/integrate/scene/pipeline.
    "video": {
        "image": "sinks consume image::Image frames; PNG sequences reuse image's PNG writer",
        "io": "sinks write their output through io::OutputFile (an unfinished sink leaves no file)",
    },
    # CoinModel, CoinState, rhs(): Eigen and std only.
    "physics": {},
    # Steppers, dense output, events: any f(t, y), nothing about coins (Eigen and std only).
    "integrate": {},
    # JSON -> SceneConfig: builds physics and solver types, validates, degrees -> radians.
    "scene": {
        "physics": "a scene is turned into a CoinModel, CoinState and effect parameters",
        "integrate": "scene builds physics/integrate types (solver settings) from JSON",
        "io": "leaf utility for anything that reads or writes files",
        # Settings-only headers (docs/architecture.md): a scene holds render/video options without
        # seeing the renderer or the encoder.
        "render/render_settings.h": "a scene holds RenderSettings (camera, size), not the renderer",
        "video/video_options.h": "a scene holds VideoOptions (codec, crf), not the encoder",
    },
    # The frame loop: wires everything below it; never argv or exit codes (those are cli's).
    "pipeline": {
        "io": "leaf utility for anything that writes files (CSV, results)",
        "image": "frames travel as image::Image from render to the sinks",
        "render": "makeSnapshot(model, state) -> FrameSnapshot -> render::Renderer",
        "video": "frames are pushed into a video::FrameSink",
        "physics": "the pipeline evaluates the model: snapshots, observables, validity events",
        "integrate": "the pipeline drives the integrator and samples dense output at k / fps",
        "scene": "a run is described by a SceneConfig",
    },
    # The installable library's API (include/coinroll/coinroll.h): a peer of cli, never used by it.
    "api": {
        "physics": "steady states and their stability as `coinroll steady` computes them",
        "scene": "loads and validates scenes from files or JSON text",
        "pipeline": "simulate, still and video through the same pipelines as the commands",
        "video": "picks the sink for a video's file name",
    },
    # The WebAssembly core's binding (docs/web.md): `coinroll simulate` as a JavaScript call, and the
    # visual track a page draws from; no GL and no video in a browser's module. A peer of cli and api.
    "wasm": {
        "physics": "steady states and their stability as `coinroll steady` computes them",
        "scene": "reads the scene text and its --set overrides as the command does",
        "pipeline": "runs the command's run (simulateScene) and writes its rows as the command's CSV",
        # The renderer's GL-free headers: what a page draws with, computed by the renderer's code.
        "render/camera.h": "the camera's up, as the renderer's look-at takes it",
        "render/floor_tile.h": "the floor's grid tile the renderer samples",
        "render/theme.h": "the colours each theme draws in",
    },
    # Parse argv, build the pipeline, run, map errors to exit codes: may use everything.
    "cli": {
        "io": "commands write their outputs through io::OutputFile",
        "image": "leaf utility (stills, frames)",
        "render": "everything below cli: render options may surface on the command line",
        "video": "picks and wraps a sink (make_sink, async_sink) for --output",
        "physics": "commands report model facts (observables, steady states)",
        "integrate": "solver options on the command line map to SolverConfig",
        "scene": "loads the scene file named on the command line",
        "pipeline": "runs the commands' pipelines",
    },
}

# Why a forbidden folder edge is forbidden, quoted in the report. (folder, target) first,
# then (folder, None) as the folder's general reason.
WHY_NOT = {
    ("render", "scene"): "render never sees the scene; pass RenderSettings",
    ("render", "physics"): "the renderer reads a FrameSnapshot, never the physics",
    ("render", "integrate"): "the renderer reads a FrameSnapshot, never the integrator",
    ("render", "pipeline"): "pipeline drives render, not the other way round",
    ("render", "video"): "render makes Images; pipeline hands them to a sink",
    ("video", "render"): "sinks take Images; pipeline connects render to video",
    ("video", "physics"): "a sink encodes pixels and knows nothing about coins",
    ("video", None): "video depends only on image and io",
    ("physics", None): "physics uses only itself, Eigen and std",
    ("integrate", "physics"): "integrators know nothing about coins: they take any f(t, y)",
    ("integrate", None): "integrate uses only itself, Eigen and std",
    ("scene", "render"): "scene may read only render/render_settings.h, not the renderer",
    ("scene", "video"): "scene may read only video/video_options.h, not the encoder",
    ("scene", None): "scene builds physics/integrate types from JSON and nothing else",
    ("image", None): "image is a leaf utility (io only)",
    ("io", None): "io is the bottom leaf utility",
    ("pipeline", "cli"): "argv and exit codes belong to cli; cli calls pipeline",
    ("wasm", "render"): "the WebAssembly core takes only the renderer's GL-free parts; a page draws with its own GL",
    ("wasm", "video"): "the WebAssembly core is the scene-to-CSV path; it encodes nothing",
}

# Third-party and std headers a folder must never include: (regex on the included name, why).
# The regex is matched from the start of the name inside <...> or "...".
GL = [(r"GL/|GLES|EGL/|osmesa", "OpenGL/OSMesa belong to render alone"),
      (r"glm/", "glm is render's math; elsewhere use Eigen or plain types")]
FFMPEG = [(r"libav|libsw", "FFmpeg belongs to video alone")]
JSON = [(r"nlohmann/", "JSON belongs to scene and above; pass typed structs down")]
CLI = [(r"CLI/", "command-line parsing belongs to cli alone")]
FILES_AND_PRINTING = [
    (r"(fstream|iostream|cstdio|stdio\.h|filesystem|print)$",
     "physics never touches files or prints; return values, throw with a message"),
]
NEVER = {
    "io": GL + FFMPEG + JSON + CLI,
    "image": GL + FFMPEG + JSON + CLI,
    "render": FFMPEG + JSON + CLI,
    "video": GL + JSON + CLI,
    "physics": GL + FFMPEG + JSON + CLI + FILES_AND_PRINTING
               + [(r"stb", "physics never reads or writes images")],
    "integrate": GL + FFMPEG + JSON + CLI,
    "scene": GL + FFMPEG + CLI,
    "pipeline": CLI,
    "wasm": GL + FFMPEG + CLI,
    "cli": [],
}

SOURCE_SUFFIXES = {".h", ".hh", ".hpp", ".hxx", ".inl", ".ipp", ".c", ".cc", ".cpp", ".cxx"}
INCLUDE_RE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
BLOCK_COMMENT_RE = re.compile(r"/\*.*?\*/", re.S)


def strip_block_comments(text):
    """Blanks /* ... */ comments, keeping their newlines so line numbers stay right."""
    return BLOCK_COMMENT_RE.sub(lambda m: "\n" * m.group(0).count("\n"), text)


def includes(path):
    """Yields (line number, delimiter, included name) for each #include of a file."""
    text = strip_block_comments(path.read_text(encoding="utf-8", errors="replace"))
    for number, line in enumerate(text.splitlines(), start=1):
        match = INCLUDE_RE.match(line)
        if match:
            yield number, match.group(1), match.group(2).strip()


def why_not(folder, target):
    return WHY_NOT.get((folder, target)) or WHY_NOT.get((folder, None)) or \
        f"{target} is not among {folder}'s allowed dependencies"


def table_problems(folders):
    """The table itself: every src/ folder listed, every edge to a known folder, no cycle."""
    problems = []
    for folder in sorted(folders - MAY_INCLUDE.keys()):
        problems.append(f"src/{folder}: folder is not in MAY_INCLUDE of tests/lint/check_layering.py "
                        "(state which folders it may include, and why)")
    for folder, edges in MAY_INCLUDE.items():
        for key in edges:
            if key.split("/")[0] not in MAY_INCLUDE:
                problems.append(f"tests/lint/check_layering.py: {folder} -> {key}: unknown folder")
    # Depth-first search for a cycle among folder-level edges.
    state = {}

    def visit(folder, trail):
        state[folder] = "open"
        for key in MAY_INCLUDE.get(folder, {}):
            target = key.split("/")[0]
            if state.get(target) == "open":
                problems.append("tests/lint/check_layering.py: dependency cycle "
                                + " -> ".join(trail + [folder, target]))
            elif target not in state:
                visit(target, trail + [folder])
        state[folder] = "done"

    for folder in MAY_INCLUDE:
        if folder not in state:
            visit(folder, [])
    return problems


def check_include(src, path, folder, delimiter, name, folders):
    """The message for one include, or None when it is allowed."""
    first = name.split("/")[0]
    if ".." in pathlib.PurePosixPath(name).parts:
        return f'"{name}": no "../" includes; include as "folder/header.h"'
    if first in ("tests", "bench"):
        return f"src may not include {name} (tests and benchmarks are separate targets)"
    for rule, reason in NEVER.get(folder, []):
        if re.match(rule, name):
            return f"{folder} may not include {name} ({reason})"
    if delimiter != '"' or first not in folders:
        return None  # a system/third-party header, or a same-folder "x.h"
    # A coinroll header: it must live in src/ (not only in tests/ or bench/) ...
    if not (src / name).exists():
        for other in ("tests", "bench"):
            if (src.parent / other / name).exists():
                return f"src may not include {name}: it is {other}/{name}, not part of src"
    # ... and its folder must be an allowed dependency.
    if first == folder:
        return None
    allowed = MAY_INCLUDE.get(folder, {})
    if first in allowed or name in allowed:
        return None
    return f"{folder} may not include {name} ({why_not(folder, first)})"


def main(argv):
    if len(argv) > 2:
        print(__doc__, file=sys.stderr)
        return 2
    src = pathlib.Path(argv[1] if len(argv) == 2 else pathlib.Path(__file__).parents[2] / "src")
    if not src.is_dir():
        print(f"check_layering.py: {src}: not a directory", file=sys.stderr)
        return 2
    src = src.resolve()
    folders = {p.name for p in src.iterdir() if p.is_dir()}
    problems = table_problems(folders)
    files = checked = 0
    for path in sorted(src.rglob("*")):
        if path.suffix not in SOURCE_SUFFIXES or not path.is_file():
            continue
        folder = path.relative_to(src).parts[0]
        if folder not in folders:
            continue  # a file directly in src/ has no layer; none exists today
        files += 1
        for number, delimiter, name in includes(path):
            checked += 1
            message = check_include(src, path, folder, delimiter, name, folders)
            if message:
                problems.append(f"{path}:{number}: {message}")
    for problem in problems:
        print(problem)
    if problems:
        print(f"check_layering.py: {len(problems)} layering violation(s); the allowed "
              "dependencies are the table at the top of tests/lint/check_layering.py", file=sys.stderr)
        return 1
    print(f"check_layering.py: {files} files, {checked} includes, layering OK")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
