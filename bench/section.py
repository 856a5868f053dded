"""Rewrites one `## ` section of docs/performance.md in place (appends it where absent):
the bench scripts that each own a section write it through here."""


def write_section(lines, path="docs/performance.md"):
    title = lines[0]
    text = open(path).read()
    start = text.find(title)
    if start < 0:
        text = text.rstrip("\n") + "\n\n" + "\n".join(lines)
    else:
        end = text.find("\n## ", start + 1)
        text = text[:start] + "\n".join(lines) + ("\n" + text[end + 1:] if end >= 0 else "")
    open(path, "w").write(text)
