#!/usr/bin/env python3
"""Checks that the documentation's links stay true (Python stdlib only).

Fails (exit 1, one line per problem, `file:line: message`) when, in
README.md, BENCHMARKS.md or any Markdown file under docs/guide/:

- a relative link or picture names a file or folder that does not exist
  (a picture must be a file);
- a link's `#anchor` names no heading of the file it points to (headings
  are turned into anchors as GitHub and mdBook do: lower case, spaces to
  hyphens, punctuation dropped, `-1`, `-2` … for repeats);
- the guide (an mdBook in docs/guide) has no book.toml, a chapter under
  docs/guide/src/ is missing from src/SUMMARY.md, or a code block there
  carries no language (`mdbook test` would compile it as Rust);
- README.md does not show the test command that .ci/run runs
  (`scripts/test.sh`), or .ci/run no longer runs it.

Links with a scheme (https:, mailto:) are not fetched. Text inside code
spans and code blocks is not read for links. Run from anywhere:
`python3 scripts/check_docs.py`; it takes well under a second.
"""

import os
import re
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
GUIDE = os.path.join(ROOT, "docs", "guide")
TEST_COMMAND = "scripts/test.sh"

# [text](target) and ![alt](target); the target ends at the first space
# (a title may follow) or at the closing parenthesis.
LINK = re.compile(r"(!?)\[((?:[^\[\]]|\[[^\]]*\])*)\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HTML_SRC = re.compile(r"""<img\b[^>]*\bsrc\s*=\s*["']([^"']+)["']""", re.IGNORECASE)
CODE_SPAN = re.compile(r"(`+)(?:.+?)\1")
FENCE = re.compile(r"^\s{0,3}(```+|~~~+)\s*([^\s`]*)")
SCHEME = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def markdown_files():
    """README.md, BENCHMARKS.md and every .md file of the guide."""
    files = [os.path.join(ROOT, "README.md"), os.path.join(ROOT, "BENCHMARKS.md")]
    for folder, dirs, names in os.walk(GUIDE):
        dirs[:] = sorted(d for d in dirs if d != "book")  # mdBook's output
        files += [os.path.join(folder, n) for n in sorted(names) if n.endswith(".md")]
    return files


def prose_lines(text):
    """(line number, line, in_code) for each line; in_code for lines inside
    fenced code blocks (the fence lines included)."""
    fence = None
    for number, line in enumerate(text.split("\n"), start=1):
        m = FENCE.match(line)
        if fence is None and m:
            fence = m.group(1)[0] * 3
            yield number, line, True
        elif fence is not None:
            if line.strip().startswith(fence) and line.strip().strip(fence[0]) == "":
                fence = None
            yield number, line, True
        else:
            yield number, line, False


def slug(heading):
    """The anchor GitHub (and mdBook) give a heading's text."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # links: their text
    text = re.sub(r"<[^>]+>", "", text).strip().lower()
    kept = "".join(ch for ch in text if ch.isalnum() or ch in " -_")
    return kept.replace(" ", "-")


_anchors = {}


def anchors(path):
    """Every anchor the headings of the Markdown file `path` define."""
    if path not in _anchors:
        found, seen = set(), {}
        with open(path, encoding="utf-8") as f:
            for _, line, in_code in prose_lines(f.read()):
                m = re.match(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$", line)
                if in_code or not m:
                    continue
                base = slug(m.group(2))
                n = seen.get(base, 0)
                seen[base] = n + 1
                found.add(base if n == 0 else f"{base}-{n}")
        _anchors[path] = found
    return _anchors[path]


def rel(path):
    return os.path.relpath(path, ROOT)


def check_links(path, problems):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    for number, line, in_code in prose_lines(text):
        if in_code:
            continue
        prose = CODE_SPAN.sub("", line)
        targets = [(m.group(1) == "!", m.group(3)) for m in LINK.finditer(prose)]
        targets += [(True, m.group(1)) for m in HTML_SRC.finditer(prose)]
        for is_picture, target in targets:
            if SCHEME.match(target) or target.startswith("//"):
                continue
            where = f"{rel(path)}:{number}"
            file_part, _, anchor = target.partition("#")
            file_part = file_part.split("?")[0]
            dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            if not os.path.exists(dest):
                kind = "picture" if is_picture else "link"
                problems.append(f"{where}: {kind} {target}: {rel(dest)} does not exist")
                continue
            if is_picture and not os.path.isfile(dest):
                problems.append(f"{where}: picture {target}: {rel(dest)} is not a file")
                continue
            if anchor and dest.endswith(".md") and anchor not in anchors(dest):
                problems.append(f"{where}: link {target}: {rel(dest)} has no heading with the anchor #{anchor}")


def check_guide(problems):
    if not os.path.isfile(os.path.join(GUIDE, "book.toml")):
        problems.append("docs/guide/book.toml: missing (the guide is an mdBook)")
    src = os.path.join(GUIDE, "src")
    summary = os.path.join(src, "SUMMARY.md")
    if not os.path.isfile(summary):
        problems.append("docs/guide/src/SUMMARY.md: missing")
        return
    with open(summary, encoding="utf-8") as f:
        listed = {
            os.path.normpath(os.path.join(src, m.group(3).partition("#")[0]))
            for m in LINK.finditer(f.read())
        }
    for folder, _, names in os.walk(src):
        for n in names:
            p = os.path.normpath(os.path.join(folder, n))
            if n.endswith(".md") and p != summary and p not in listed:
                problems.append(f"{rel(p)}: a chapter not listed in docs/guide/src/SUMMARY.md")
    for folder, dirs, names in os.walk(GUIDE):
        dirs[:] = [d for d in dirs if d != "book"]
        for n in sorted(names):
            if not n.endswith(".md"):
                continue
            p = os.path.join(folder, n)
            with open(p, encoding="utf-8") as f:
                opening = None
                for number, line, in_code in prose_lines(f.read()):
                    m = FENCE.match(line)
                    if in_code and m and opening is None:
                        opening = number
                        if not m.group(2):
                            problems.append(
                                f"{rel(p)}:{number}: a code block with no language "
                                "(mdbook test compiles it as Rust): give ```sh, ```text, ```toml …"
                            )
                    elif not in_code:
                        opening = None


def check_test_command(problems):
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        readme = [line.strip() for line in f]
    if TEST_COMMAND not in readme:
        problems.append(f"README.md: no line showing the test command `{TEST_COMMAND}` (.ci/run runs it)")
    ci = os.path.join(ROOT, ".ci", "run")
    with open(ci, encoding="utf-8") as f:
        runs = [line.strip() for line in f if not line.lstrip().startswith("#")]
    if TEST_COMMAND not in runs:
        problems.append(f".ci/run: does not run `{TEST_COMMAND}`, the README's test command")


def main():
    problems = []
    for path in markdown_files():
        check_links(path, problems)
    check_guide(problems)
    check_test_command(problems)
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        print(f"check_docs: {len(problems)} problem(s)", file=sys.stderr)
        return 1
    print(f"check_docs: {len(markdown_files())} files, every link and picture found")
    return 0


if __name__ == "__main__":
    sys.exit(main())
