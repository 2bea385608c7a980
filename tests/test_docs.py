"""The README and docs/ are read by users of the repository alone: every link they hold opens a
file in it, and they state no figure that goes stale by hand (a count of the tests)."""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
LINK = re.compile(r"\]\(([^)#\s]+)(?:#[^)]*)?\)")


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_link_opens_a_file_of_the_repository(page):
    text = page.read_text()
    assert "../shared" not in text, f"{page.name} points outside the repository"
    for target in LINK.findall(text):
        if re.match(r"[a-z]+://", target):
            continue
        path = (page.parent / target).resolve()
        assert path.is_relative_to(ROOT) and path.exists(), f"{page.name}: {target}"


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_no_hand_counted_test_totals(page):
    counted = re.findall(r"\b\d+ (?:tests|passed)\b", page.read_text())
    assert not counted, f"{page.name} states {counted}: such counts go stale"


def test_code_and_docs_describe_the_present_not_the_issue_tracker():
    """History lives in CHANGELOG.md; code, tests and docs say what is meant, not 'issue N'."""
    pattern = re.compile(r"\b(?:[Ii]ssues? \d+|[Ss]essions? \d+|[Ss]tops? \d+\b(?! mm))")
    files = [
        *PAGES,
        *(ROOT / "src").rglob("*.py"),
        *(ROOT / "tests").rglob("*.py"),
        *(ROOT / "benchmarks").rglob("*.py"),
        *(ROOT / "scripts").rglob("*.py"),
    ]
    found = [
        f"{f.relative_to(ROOT)}: {m.group(0)}"
        for f in files
        for m in pattern.finditer(f.read_text())
        if f.name != "test_docs.py"
    ]
    assert not found, found


def test_the_performance_page_stays_short_and_present():
    """docs/performance.md is the present's figures; the history goes to CHANGELOG.md."""
    lines = (ROOT / "docs" / "performance.md").read_text().splitlines()
    assert len(lines) < 200, len(lines)
    assert (ROOT / "CHANGELOG.md").exists()


# Reference pages say what is true now; a dated line or study goes to docs/notes/, a note a date.
REFERENCE = ("performance.md", "robots.md", "measurements.md", "design.md", "code_map.md")
DATE = re.compile(r"\b20\d\d-\d\d-\d\d\b")
NOTE_LINK = re.compile(r"notes/20\d\d-\d\d-\d\d[\w.-]*")


def _dated(text: str) -> list[str]:
    """The lines of `text` that carry a date, a link to a dated note aside."""
    return [line for line in text.splitlines() if DATE.search(NOTE_LINK.sub("", line))]


@pytest.mark.parametrize("name", REFERENCE)
def test_a_reference_page_carries_no_dated_line(name):
    assert _dated((ROOT / "docs" / name).read_text()) == []


def test_every_note_is_named_by_its_date():
    notes = sorted(p.name for p in (ROOT / "docs" / "notes").glob("*.md"))
    assert notes and [n for n in notes if not re.match(r"20\d\d-\d\d-\d\d-", n)] == []


def test_the_date_check_finds_a_dated_line_and_passes_a_link():
    text = "Measured on 2026-11-25.\nSee [the study](notes/2026-11-25-study.md#x).\nNo date."
    assert _dated(text) == ["Measured on 2026-11-25."]
