#!/usr/bin/env python3
"""Stages the documentation for MkDocs: docs/ copied into OUT, the README as its home page
(index.md), and every relative link that leaves docs/ (a source file, an example) turned into
the repository path as code, since the site holds only the pages.

  tools/stage_docs.py OUT
"""
import os
import re
import shutil
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
out = sys.argv[1]
docs = os.path.join(root, "docs")
shutil.rmtree(out, ignore_errors=True)
shutil.copytree(docs, out)
LINK = re.compile(r"(!?)\[((?:[^\]\[]|\[[^\]]*\])*)\]\(([^)\s#]*)(#[^)\s]*)?\)")


def rewrite(text, page_dir):
    def link(m):
        image, label, path, anchor = m.group(1), m.group(2), m.group(3), m.group(4) or ""
        if not path or re.match(r"^[a-z]+:", path):
            return m.group(0)
        target = os.path.normpath(os.path.join(page_dir, path))
        if target.startswith(docs + os.sep):
            return f"{image}[{label}]({os.path.relpath(target, docs)}{anchor})"
        repo_path = os.path.relpath(target, root)
        return f"{label} (`{repo_path}`)" if label and label.strip("`") != repo_path else f"`{repo_path}`"
    fenced, lines = False, []
    for line in text.split("\n"):
        if line.lstrip().startswith("```"):
            fenced = not fenced
        # Python-Markdown starts a list only after a blank line (GitHub does not ask for one).
        previous = lines[-1] if lines else ""
        if (not fenced and re.match(r"^(- |\* |\d+\. )", line) and previous.strip()
                and not re.match(r"^(\s|- |\* |\d+\. )", previous)):
            lines.append("")
        lines.append(line if fenced else LINK.sub(link, line))
    return "\n".join(lines)


for name in os.listdir(docs):
    if name.endswith(".md"):
        path = os.path.join(out, name)
        open(path, "w").write(rewrite(open(os.path.join(docs, name)).read(), docs))
readme = open(os.path.join(root, "README.md")).read()
open(os.path.join(out, "index.md"), "w").write(rewrite(readme, root))
print(f"stage_docs: {out}", file=sys.stderr)
