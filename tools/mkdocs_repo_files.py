"""MkDocs hook: the guide links to files outside `docs/` as GitHub shows them.

The guide's pages live in `docs/` and link to repository files by their relative path
(`../BENCHMARKS.md`, `../configs/grains.toml`), so the links work when the pages are
read on GitHub. MkDocs only knows files under `docs/`, and `mkdocs build --strict`
fails on a link it cannot resolve. This hook adds the repository files below to the
site (Markdown rendered as pages, others copied) and rewrites each link that leaves
`docs/` to the added file's place in the site. A link to a repository file not listed
here is left alone, so `--strict` still fails on it.
"""

import glob
import os
import posixpath
import re

from mkdocs.structure.files import File

# Repository files the guide may link to, as globs relative to the repository root.
REPO_FILES = [
    "BENCHMARKS.md",
    "CHANGELOG.md",
    "configs/*.toml",
    "configs/*.csv",
    "examples/*.py",
    "examples/*.rs",
    "tools/*.py",
]

# Inline Markdown links and images: [text](target) with an optional #anchor.
LINK = re.compile(r"(\]\()([^)\s#]+)(#[^)\s]*)?\)")


def _root(config):
    return os.path.dirname(os.path.abspath(config["config_file_path"]))


def on_files(files, config):
    root = _root(config)
    for pattern in REPO_FILES:
        for path in sorted(glob.glob(os.path.join(root, pattern))):
            rel = os.path.relpath(path, root).replace(os.sep, "/")
            files.append(
                File(rel, root, config["site_dir"], config["use_directory_urls"])
            )
    return files


def on_page_markdown(markdown, page, config, files):
    # The page's folder inside docs/ (src_uri of a repository file added above is its
    # path from the root, and such pages' links are already relative to the root).
    src = page.file.src_uri
    if not os.path.abspath(page.file.abs_src_path).startswith(
        os.path.abspath(config["docs_dir"]) + os.sep
    ):
        return markdown
    here = posixpath.dirname(src)

    def rewrite(match):
        target = match.group(2)
        if "://" in target or target.startswith("mailto:"):
            return match.group(0)
        resolved = posixpath.normpath(posixpath.join("docs", here, target))
        if resolved.startswith("docs/"):
            return match.group(0)
        if files.get_file_from_path(resolved) is None:
            return match.group(0)
        new = posixpath.relpath(resolved, here or ".")
        return f"{match.group(1)}{new}{match.group(3) or ''})"

    return LINK.sub(rewrite, markdown)
