#!/usr/bin/env python3
"""Tests of .ci/check_docs.py, the documentation link check: it runs the script on small trees
written here (--root) and checks its exit status and every line it prints. Plain unittest, so
that ctest runs it with /usr/bin/python3 alone (docs.checker) and pytest collects it too."""
import pathlib
import subprocess
import sys
import tempfile
import textwrap
import unittest

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / ".ci" / "check_docs.py"

# A tree whose every link resolves: headings with code, punctuation and a dash, a repeated
# heading, an image, a folder, links inside code that must be ignored, and external links.
GOOD_TREE = {
    "README.md": """\
        # demo

        ![picture](docs/images/shot.png) [the guide](docs/guide.md) and
        [its second part](docs/guide.md#tumble-tool--options-and-more).
        [assets](assets/) and [a section here](#demo).
        [external](https://example.com/missing.md) [mail](mailto:someone@example.com)
        `[in a code span](docs/nowhere.md)`

        ```sh
        [in a fence](docs/nowhere.md)
        ```
        """,
    "docs/guide.md": """\
        # Guide

        ## `tumble tool` — options, and more

        ## Notes
        ## Notes

        See [the second notes](#notes-1), [the physics](../engine/PHYSICS.md#1-state),
        [back](../README.md) and [reference][ref].

        [ref]: other.md#other
        """,
    "docs/other.md": "# Other\n\n[guide](guide.md)\n",
    "docs/images/shot.png": "not really a picture",
    "engine/PHYSICS.md": "# Physics\n\n## §1 State\n",
    "assets/meshes/README.md": "# Meshes\n\n[physics](../../engine/PHYSICS.md)\n",
}


def write_tree(root: pathlib.Path, files: dict) -> None:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text), encoding="utf-8")


def run_check(files: dict) -> tuple[int, list[str]]:
    """The script's exit status and printed lines on a tree of these files."""
    with tempfile.TemporaryDirectory() as folder:
        root = pathlib.Path(folder)
        write_tree(root, files)
        done = subprocess.run([sys.executable, str(SCRIPT), "--root", str(root)],
                              capture_output=True, text=True, check=False)
        return done.returncode, done.stdout.splitlines()


class CheckDocsTest(unittest.TestCase):
    def test_a_tree_whose_links_all_resolve_passes(self):
        status, lines = run_check(GOOD_TREE)
        self.assertEqual(status, 0, lines)
        self.assertEqual(len(lines), 1)
        self.assertIn("all resolve, every docs page is reachable", lines[0])
        self.assertIn("in 5 pages", lines[0])

    def test_a_link_to_a_missing_file_fails_naming_file_line_and_target(self):
        files = dict(GOOD_TREE)
        files["README.md"] = GOOD_TREE["README.md"] + "[gone](docs/missing.md)\n"
        status, lines = run_check(files)
        self.assertEqual(status, 1)
        self.assertEqual(lines[0], "README.md:12: link 'docs/missing.md' points nowhere")
        self.assertEqual(len(lines), 2)
        self.assertTrue(lines[1].startswith("documentation links: 1 problems"))

    def test_a_link_to_a_missing_heading_fails(self):
        files = dict(GOOD_TREE)
        files["docs/other.md"] = "# Other\n\n[guide](guide.md#no-such-heading)\n"
        status, lines = run_check(files)
        self.assertEqual(status, 1)
        self.assertIn("docs/other.md:3: link 'guide.md#no-such-heading' points nowhere", lines)

    def test_an_anchor_is_checked_against_the_page_it_names(self):
        files = dict(GOOD_TREE)
        # '#notes-2' would be a third 'Notes' heading; the page has two.
        files["docs/other.md"] = "# Other\n\n[guide](guide.md#notes-2) [self](#other-heading)\n"
        status, lines = run_check(files)
        self.assertEqual(status, 1)
        self.assertIn("docs/other.md:3: link 'guide.md#notes-2' points nowhere", lines)
        self.assertIn("docs/other.md:3: link '#other-heading' points nowhere", lines)

    def test_a_link_whose_text_runs_over_lines_is_checked(self):
        files = dict(GOOD_TREE)
        files["docs/other.md"] = ("# Other\n\n[guide](guide.md) a stray [ bracket\n\n"
                                  "the [long\nname](guide.md#gone) and `a [code\nspan](x.md)`\n")
        status, lines = run_check(files)
        self.assertEqual(status, 1)
        self.assertEqual(lines[0], "docs/other.md:6: link 'guide.md#gone' points nowhere")
        self.assertEqual(len(lines), 2)

    def test_an_orphan_page_fails(self):
        files = dict(GOOD_TREE)
        files["docs/orphan.md"] = "# Orphan\n\n[back](../README.md)\n"
        status, lines = run_check(files)
        self.assertEqual(status, 1)
        self.assertIn("docs/orphan.md:1: page not reachable from README.md by following links",
                      lines)

    def test_a_page_reached_only_through_another_page_is_reachable(self):
        files = dict(GOOD_TREE)
        files["docs/other.md"] = "# Other\n\n[deeper](deeper.md)\n"
        files["docs/deeper.md"] = "# Deeper\n"
        status, lines = run_check(files)
        self.assertEqual(status, 0, lines)

    def test_broken_links_in_physics_notes_and_asset_readmes_fail(self):
        files = dict(GOOD_TREE)
        files["engine/PHYSICS.md"] = "# Physics\n\n## §1 State\n\n[x](../docs/gone.md)\n"
        files["assets/meshes/README.md"] = "# Meshes\n\n![m](missing.png)\n"
        status, lines = run_check(files)
        self.assertEqual(status, 1)
        self.assertIn("engine/PHYSICS.md:5: link '../docs/gone.md' points nowhere", lines)
        self.assertIn("assets/meshes/README.md:3: link 'missing.png' points nowhere", lines)


if __name__ == "__main__":
    unittest.main()
