#!/usr/bin/env python3
"""Checks README.md and docs/*.md the way a reader meets them:

- every relative link and image resolves to a file of the repository, and every #anchor to a
  heading of the page it names (slugs as MkDocs makes them);
- the README stays a front page: at most 250 lines;
- the figures table of docs/evaluation.md says what the HTML report says of each figure
  (libs/eval/src/html_report.cpp, kMeanings), word for word.

  tools/check_docs.py [ROOT]     exits 1 with one line per problem
"""
import os
import re
import sys
import unicodedata

README_MAX_LINES = 250
LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
HTML_REF = re.compile(r"""(?:src|href)="([^"]+)\"""")


def slug(heading):
    """MkDocs' (Python-Markdown toc) slug: ASCII, no punctuation, lower case, dashes."""
    text = re.sub(r"`|\*\*|\*|_(?=\w)", "", heading)
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode("ascii")
    text = re.sub(r"[^\w\s-]", "", text).strip().lower()
    return re.sub(r"[-\s]+", "-", text)


def prose_lines(path):
    """(line number, text) of the lines outside fenced code blocks."""
    fenced = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if line.lstrip().startswith("```"):
                fenced = not fenced
                continue
            if not fenced:
                yield number, line


def anchors(path):
    found = set()
    for _, line in prose_lines(path):
        m = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
        if m:
            found.add(slug(m.group(2)))
    return found


def check_links(root, page, problems):
    here = os.path.dirname(page)
    for number, line in prose_lines(page):
        line = re.sub(r"`[^`]*`", "", line)  # inline code is not a link
        for target in LINK.findall(line) + HTML_REF.findall(line):
            if re.match(r"^[a-z]+:", target):  # http:, https:, mailto:
                continue
            path, _, anchor = target.partition("#")
            resolved = os.path.normpath(os.path.join(here, path)) if path else page
            where = f"{os.path.relpath(page, root)}:{number}"
            if not resolved.startswith(root) or not os.path.exists(resolved):
                problems.append(f"{where}: '{target}' does not resolve to a file")
            elif anchor and resolved.endswith(".md") and anchor not in anchors(resolved):
                problems.append(f"{where}: '{target}': no heading with anchor '#{anchor}' in "
                                f"{os.path.relpath(resolved, root)}")


def check_meanings(root, problems):
    source = open(os.path.join(root, "libs/eval/src/html_report.cpp"), encoding="utf-8").read()
    page = open(os.path.join(root, "docs/evaluation.md"), encoding="utf-8").read()
    meanings = re.findall(r'\{"([a-z0-9_]+)",\s*"([^"]+)",', source)
    if not meanings:
        problems.append("libs/eval/src/html_report.cpp: no figure meanings found (kMeanings)")
    for name, meaning in meanings:
        if f"| `{name}` | {meaning} |" not in page:
            problems.append(f"docs/evaluation.md: the figures table does not say what the report says of "
                            f"`{name}`: '{meaning}'")


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    pages = [os.path.join(root, "README.md")]
    pages += sorted(os.path.join(root, "docs", f) for f in os.listdir(os.path.join(root, "docs")) if f.endswith(".md"))
    problems = []
    for page in pages:
        check_links(root, page, problems)
    lines = sum(1 for _ in open(pages[0], encoding="utf-8"))
    if lines > README_MAX_LINES:
        problems.append(f"README.md: {lines} lines, more than {README_MAX_LINES}: move the detail into docs/")
    check_meanings(root, problems)
    for p in problems:
        print(p)
    print(f"check_docs: {len(pages)} pages, README {lines} lines, {len(problems)} problems", file=sys.stderr)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
