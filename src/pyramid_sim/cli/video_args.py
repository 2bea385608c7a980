"""The film's and the still's flags (`--video`, `--snapshot` and what they take), turned into a
VideoConfig; a setting given without the output it sets is refused."""

from __future__ import annotations

import argparse

from ..choices import CAMERAS, in_words
from ..config import (
    SPEEDUP,
    VIDEO_FPS,
    VIDEO_HEIGHT,
    VIDEO_WIDTH,
    VideoConfig,
    antialias_text,
)
from ..errors import ConfigError
from .args import number, one_of, output_path, whole

# dest -> (flag, what it sets: the film alone or the film and the still, VideoConfig field)
VIDEO_OPTIONS = {
    "fps": ("--fps", "film", "fps"),
    "speedup": ("--speedup", "film", "speedup"),
    "video_width": ("--video-width", "both", "width"),
    "video_height": ("--video-height", "both", "height"),
    "camera": ("--camera", "both", "camera"),
    "shadows": ("--shadows", "both", "shadows"),
    "antialias": ("--antialias", "both", "antialias"),
}


def renamed(new: str, note: str) -> type[argparse.Action]:
    """A flag that is no more: refused in one line giving its new name, with or without a
    value after it."""

    class Renamed(argparse.Action):
        def __call__(
            self,
            parser: argparse.ArgumentParser,
            namespace: argparse.Namespace,
            values: object,
            option_string: str | None = None,
        ) -> None:
            parser.error(f"{option_string} is now {new} ({note})")

    return Renamed


def add_video_args(p: argparse.ArgumentParser) -> None:
    """The film's and the still's flags. Their defaults are None here (the help text names the
    real ones) so a setting given without --video or --snapshot can be told and refused."""
    p.add_argument(
        "--video",
        type=output_path("mp4 path", folder=False),
        metavar="PATH.mp4",
        help="render the build to this MP4 (H.264)",
    )
    p.add_argument(
        "--snapshot",
        type=output_path("png path", folder=False),
        metavar="PATH.png",
        help="write a PNG of the final structure",
    )
    add_film_settings(p)


def add_film_settings(p: argparse.ArgumentParser) -> None:
    """What a film or a still is made with: its size, camera, shadows and samples; the film's
    rate and speed."""
    d = VideoConfig()
    p.add_argument(
        "--fps",
        type=whole("fps"),
        help=f"video frames a second, {VIDEO_FPS.text} (default {d.fps})",
    )
    p.add_argument(
        "--video-width",
        type=whole("video width"),
        metavar="PIXELS",
        help=f"of the video and the snapshot, even, {VIDEO_WIDTH.text} (default {d.width})",
    )
    p.add_argument(
        "--video-height",
        type=whole("video height"),
        metavar="PIXELS",
        help=f"of the video and the snapshot, even, {VIDEO_HEIGHT.text} (default {d.height})",
    )
    add_renamed_size_flags(p)
    p.add_argument(
        "--camera",
        type=one_of("camera", CAMERAS),
        metavar="|".join(CAMERAS),
        help=f"{in_words(CAMERAS)} (default {d.camera})",
    )
    p.add_argument(
        "--shadows",
        action=argparse.BooleanOptionalAction,
        help="render shadows, about 4x the render cost (default off)",
    )
    p.add_argument(
        "--speedup",
        type=number("speedup"),
        metavar="K",
        help="simulated seconds a second of video: one frame every K/fps simulated "
        f"seconds, so K=4 makes a 4-minute build a 1-minute film; {SPEEDUP.text} "
        f"(default {d.speedup:g})",
    )
    p.add_argument(
        "--antialias",
        type=whole("antialias"),
        metavar="SAMPLES",
        help=f"multisample anti-aliasing: {antialias_text()}, 4 costing ~1.7x "
        f"(default {d.antialias})",
    )


def add_renamed_size_flags(p: argparse.ArgumentParser) -> None:
    """--width and --height, refused naming their new names (hidden from the help)."""
    p.add_argument(
        "--width",
        nargs="?",
        help=argparse.SUPPRESS,
        action=renamed(
            "--video-width", "the video's width in pixels; a wall's course width is --wall-width"
        ),
    )
    p.add_argument(
        "--height",
        nargs="?",
        help=argparse.SUPPRESS,
        action=renamed("--video-height", "the video's height in pixels"),
    )


def video_config_from_args(args: argparse.Namespace) -> VideoConfig:
    """The film's and the still's settings, the defaults where none is given; ConfigError for
    one out of range or given without the output it sets."""
    refuse_idle_video_options(args)
    given = {field: getattr(args, dest) for dest, (_, _, field) in VIDEO_OPTIONS.items()}
    return VideoConfig(**{field: value for field, value in given.items() if value is not None})


def refuse_idle_video_options(args: argparse.Namespace) -> None:
    """ConfigError for a video setting given without --video (or --snapshot, for those that
    set the still too): ignored, it would let the user believe it did something."""
    for dest, (flag, needs, _) in VIDEO_OPTIONS.items():
        if getattr(args, dest) is None:
            continue
        if needs == "film" and args.video is None:
            raise ConfigError(
                f"{flag}: a setting of the video, but no --video is given; "
                "accepted with --video PATH.mp4"
            )
        if args.video is None and args.snapshot is None:
            raise ConfigError(
                f"{flag}: a setting of the video and the snapshot, but neither "
                "--video nor --snapshot is given; accepted with --video PATH.mp4 "
                "or --snapshot PATH.png"
            )
