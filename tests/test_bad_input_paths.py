"""Output paths and numbers the OS or Python would take wrongly, or refuse only midway, are
refused up front: one line naming the problem and what is accepted, exit status 2, nothing
written. Every --out, --video and --snapshot goes through one check (cli/args.output_path)."""

import importlib.util
import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
LONG = "a" * 300  # over any file system's NAME_MAX (255 on Linux and macOS)

# Each command with an output path, as [command, options..., flag]: the path follows.
PATH_FLAGS = {
    "build --out": ["build", "--layers", "1", "--out"],
    "build --video": ["build", "--layers", "1", "--out", "run", "--video"],
    "build --snapshot": ["build", "--layers", "1", "--out", "run", "--snapshot"],
    "scene --out": ["scene", "--layers", "1", "--out"],
    "sweep --out": ["sweep", "--layers", "1", "--out"],
    "record --out": ["record", "--layers", "1", "--out"],
    "evaluate --out": ["evaluate", "--layers", "1", "--out"],
}
SUFFIX = {"--video": ".mp4", "--snapshot": ".png", "scene": ".xml"}


def _suffix(key: str) -> str:
    return next((s for k, s in SUFFIX.items() if k in key), "")


@pytest.fixture
def in_empty_folder(tmp_path, monkeypatch):
    """The working folder is a new empty one, so `nothing written` can be checked whole."""
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.mark.parametrize("key", PATH_FLAGS)
def test_an_empty_output_path_is_refused_not_taken_as_the_working_folder(
    in_empty_folder, refused, key
):
    err = refused([*PATH_FLAGS[key], ""])
    assert "'' is not a path; accepted a" in err
    assert list(in_empty_folder.iterdir()) == []


@pytest.mark.parametrize("key", PATH_FLAGS)
def test_a_name_over_name_max_is_refused_before_anything_runs(in_empty_folder, refused, key):
    err = refused([*PATH_FLAGS[key], LONG + _suffix(key)])
    limit = os.pathconf(in_empty_folder, "PC_NAME_MAX")
    assert f"a name of {300 + len(_suffix(key))} bytes ('aaaaaaaaaaaaaaaaaaaa...')" in err
    assert f"over the {limit} a name may have" in err
    assert list(in_empty_folder.iterdir()) == []


def test_a_long_name_deeper_in_the_path_is_refused_too(in_empty_folder, refused):
    err = refused(["build", "--layers", "1", "--out", f"runs/{LONG}/x"])
    assert "out: a name of 300 bytes" in err
    assert list(in_empty_folder.iterdir()) == []


@pytest.mark.parametrize("key", ["scene --out", "build --video", "build --snapshot"])
def test_a_file_path_that_names_a_folder_is_refused_and_writes_nothing(
    in_empty_folder, refused, key
):
    """A folder called f.xml: scene used to write its meshes, then fail to rename the XML onto
    the folder (exit 1), leaving f_meshes/ behind."""
    name = "f" + _suffix(key)
    (in_empty_folder / name).mkdir()
    err = refused([*PATH_FLAGS[key], name])
    assert f"{name!r} is a folder; accepted a file's path" in err
    assert sorted(p.name for p in in_empty_folder.iterdir()) == [name]
    assert list((in_empty_folder / name).iterdir()) == []


@pytest.mark.parametrize("key", [k for k in PATH_FLAGS if k.endswith("--out")])
def test_an_output_folder_that_is_a_link_to_nothing_is_refused_naming_the_link(
    in_empty_folder, refused, key
):
    """The OS said only "[Errno 17] File exists: 'dangling'" (exit 1) when it came to make the
    folder; refused up front, the link left as it was."""
    (in_empty_folder / "dangling").symlink_to("nowhere")
    path = "dangling/scene.xml" if key == "scene --out" else "dangling"
    err = refused([*PATH_FLAGS[key], path])
    assert "out: 'dangling' is a link to 'nowhere', which does not exist; accepted a folder" in err
    assert [p.name for p in in_empty_folder.iterdir()] == ["dangling"]
    assert os.readlink(in_empty_folder / "dangling") == "nowhere"


@pytest.mark.parametrize(
    "args, words",
    [
        (["build", "--brick-mass", "0_5"], "brick mass (kg): '0_5' is not a number"),
        (["build", "--friction", "1_0"], "brick friction: '1_0' is not a number"),
        (["build", "--layers", "1_0"], "layers: '1_0' is not a whole number"),
        (["build", "--seed", "1_000"], "seed: '1_000' is not a whole number"),
        (["build", "--layers", "\u0663"], "is not a whole number"),  # Arabic-Indic three
        (["build", "--video", "b.mp4", "--fps", "3_0"], "fps: '3_0' is not a whole number"),
        (["sweep", "--spawn-jitter", "1_0"], "spawn jitter: '1_0' is not a number"),
        (["record", "--image-size", "2_24"], "image size: '2_24' is not a size"),
        (["record", "--episodes", "1_0"], "episodes: '1_0' is not a whole number"),
    ],
)
def test_a_number_with_digit_separators_is_refused_not_read_as_another(
    in_empty_folder, refused, args, words
):
    """Python's float() and int() read `0_5` as 5: a 5 kg brick where 0.5 was meant."""
    err = refused([*args, "--out", "run"])
    assert words in err
    assert list(in_empty_folder.iterdir()) == []


def test_the_one_number_reader_refuses_separators_and_reads_the_rest():
    from pyramid_sim.params import parse_number, parse_whole

    assert parse_number(" 0.5 ") == 0.5 and parse_number("-1e-3") == -0.001
    assert parse_whole("42") == 42
    for text in ("0_5", "1_000", "\u0663", "\uff15"):  # separators, non-ASCII digits
        with pytest.raises(ValueError):
            parse_number(text)
        with pytest.raises(ValueError):
            parse_whole(text)


def test_the_benchmark_refuses_an_empty_json_path(capsys):
    spec = importlib.util.spec_from_file_location("bench_run", ROOT / "benchmarks" / "run.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    with pytest.raises(SystemExit) as exit_info:
        module.main(["--json", ""])
    err = capsys.readouterr().err
    assert exit_info.value.code == 2 and len(err.strip().splitlines()) == 1
    assert "json path: '' is not a path; accepted a file's path" in err
