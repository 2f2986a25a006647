#!/usr/bin/env python3
"""Checks that every relative link in the repository's Markdown pages resolves.

Usage: check_doc_links.py REPO_ROOT [PAGE.md ...]

Without pages it checks every .md page of the repository (README.md, docs/, the folders' READMEs,
the schema changelog), skipping hidden folders, node_modules, out/ and build trees. A link is an inline link or image,
`[text](target)` or `![alt](target)`, or a reference definition `[label]: target`, outside code
blocks and code spans. For each relative target it checks that the file or folder exists, that it
stays inside the repository (a clone has nothing beside it), and, for `page.md#anchor`, that the
page has a heading with that anchor (GitHub's rule: lower case, punctuation dropped, spaces to
hyphens, repeats numbered -1, -2, ...). Links with a scheme (https:, mailto:) are not followed.
Exit 0 when all resolve, 1 with one line per broken link otherwise.
"""
import os
import re
import sys

INLINE = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$")
FENCE = re.compile(r"^\s{0,3}(```|~~~)")
CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1")
HEADING = re.compile(r"^\s{0,3}#{1,6}\s+(.*?)\s*#*\s*$")
SCHEME = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def prose_lines(text, blank_code_spans=True):
    """(line number, line) for the lines outside fenced code blocks, code spans blanked."""
    fence = None
    for number, line in enumerate(text.splitlines(), 1):
        match = FENCE.match(line)
        if match:
            if fence is None:
                fence = match.group(1)
            elif match.group(1) == fence:
                fence = None
            continue
        if fence is None:
            yield number, CODE_SPAN.sub(lambda m: " " * len(m.group(0)), line) \
                if blank_code_spans else line


def github_anchor(heading):
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link in a heading keeps its text
    text = text.replace("`", "").strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    seen = {}
    result = set()
    with open(path, encoding="utf-8") as page:
        for _, line in prose_lines(page.read(), blank_code_spans=False):
            match = HEADING.match(line)
            if not match:
                continue
            base = github_anchor(match.group(1))
            count = seen.get(base, 0)
            seen[base] = count + 1
            result.add(base if count == 0 else f"{base}-{count}")
    return result


def links(path):
    with open(path, encoding="utf-8") as page:
        text = page.read()
    for number, line in prose_lines(text):
        for match in INLINE.finditer(line):
            yield number, match.group(1)
        match = REFERENCE.match(line)
        if match:
            yield number, match.group(1)


def check(root, page):
    root = os.path.realpath(root)
    problems = []
    for number, target in links(page):
        where = f"{os.path.relpath(page, root)}:{number}: {target}"
        if SCHEME.match(target):
            continue
        file_part, _, anchor = target.partition("#")
        if file_part.startswith("/"):
            problems.append(f"{where}: an absolute path (write it relative to the page)")
            continue
        resolved = os.path.realpath(os.path.join(os.path.dirname(page), file_part)) if file_part \
            else os.path.realpath(page)
        if os.path.commonpath([root, resolved]) != root:
            problems.append(f"{where}: leaves the repository")
        elif not os.path.exists(resolved):
            problems.append(f"{where}: no such file or folder")
        elif anchor and resolved.endswith(".md") and anchor not in anchors(resolved):
            problems.append(f"{where}: no heading with the anchor #{anchor}")
    return problems


def markdown_pages(root):
    pages = []
    for folder, subfolders, files in os.walk(root):
        subfolders[:] = sorted(d for d in subfolders
                               if not d.startswith(".") and d not in ("node_modules", "out")
                               and not os.path.exists(os.path.join(folder, d, "CMakeCache.txt")))
        pages += [os.path.join(folder, f) for f in sorted(files) if f.endswith(".md")]
    return pages


def main(argv):
    if len(argv) < 2:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    root = argv[1]
    pages = argv[2:]
    if not pages:
        pages = markdown_pages(root)
    problems = []
    for page in pages:
        problems += check(root, page)
    for problem in problems:
        print(problem)
    print(f"{len(pages)} pages, {len(problems)} broken links", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
