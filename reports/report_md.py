"""A small Markdown subset to HTML, for the report's findings pages (benchmarks/<paper>/FINDINGS.md).

Handled: ATX headings (`#`..`######`; a heading "Fxx: title" gets the anchor id="Fxx"), paragraphs,
bullet and numbered lists nested by indentation (continuation lines belong to the item above),
simple pipe tables (first row = header, the `---` row skipped), fenced code blocks, and inline
`code`, **bold**, [text](http...) links. Finding ids (F01, F123) in the text link to their
anchor on the same page when `ids` names them. Anything else is shown as plain text.
"""
import html
import re

HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
ITEM = re.compile(r"^(\s*)([-*+]|\d+[.)])\s+(.*)$")
FINDING_HEAD = re.compile(r"^(F\d{2,3})\b")
FINDING_REF = re.compile(r"\b(F\d{2,3})\b")


def inline(text, ids=None):
    """Inline Markdown of one block of text: code spans first (nothing inside them is parsed)."""
    out = []
    for part in re.split(r"(`[^`]+`)", text):
        if len(part) >= 2 and part[0] == "`" and part[-1] == "`":
            out.append("<code>%s</code>" % html.escape(part[1:-1]))
            continue
        t = html.escape(part, quote=False)
        t = re.sub(r"\*\*(.+?)\*\*", r"<b>\1</b>", t)
        t = re.sub(r"\[([^\]]+)\]\((https?://[^)\s]+)\)", r'<a href="\2">\1</a>', t)
        if ids:
            t = FINDING_REF.sub(lambda m: ('<a href="#%s">%s</a>' % (m.group(1), m.group(1)))
                                if m.group(1) in ids else m.group(1), t)
        out.append(t)
    return "".join(out)


def _table(rows, ids):
    cells = [[c.strip() for c in r.strip().strip("|").split("|")] for r in rows]
    body = [r for r in cells if not all(re.fullmatch(r":?-{2,}:?", c or "--") for c in r)]
    if not body:
        return ""
    out = ["<table class=\"md\"><tr>%s</tr>" % "".join("<th>%s</th>" % inline(c, ids) for c in body[0])]
    for r in body[1:]:
        out.append("<tr>%s</tr>" % "".join("<td>%s</td>" % inline(c, ids) for c in r))
    out.append("</table>")
    return "".join(out)


def finding_ids(text):
    """The finding ids of the headings of a FINDINGS.md text, in order."""
    out = []
    for line in text.splitlines():
        m = HEADING.match(line)
        if m:
            f = FINDING_HEAD.match(m.group(2))
            if f:
                out.append(f.group(1))
    return out


def _indent(line):
    return len(line) - len(line.lstrip(" "))


def _is_block_start(line):
    s = line.strip()
    return bool(HEADING.match(line) or ITEM.match(line) or s.startswith("|") or s.startswith("```"))


def _blocks(lines, ids, after, shift):
    """HTML blocks of a list of lines (list items hold their indented lines, parsed recursively)."""
    out, i, n = [], 0, len(lines)
    while i < n:
        line = lines[i].expandtabs(4)
        s = line.strip()
        if not s:
            i += 1
            continue
        if s.startswith("```"):
            j = i + 1
            while j < n and not lines[j].strip().startswith("```"):
                j += 1
            out.append("<pre>%s</pre>" % html.escape("\n".join(lines[i + 1:j])))
            i = j + 1
            continue
        m = HEADING.match(line)
        if m:
            level = min(6, len(m.group(1)) + shift)
            f = FINDING_HEAD.match(m.group(2))
            out.append('<h%d%s>%s</h%d>' % (level, ' id="%s"' % f.group(1) if f else "", inline(m.group(2)), level))
            if f and after:
                out.append(after(f.group(1)) or "")
            i += 1
            continue
        if s.startswith("|"):
            j = i
            while j < n and lines[j].strip().startswith("|"):
                j += 1
            out.append(_table([l.strip() for l in lines[i:j]], ids))
            i = j
            continue
        m = ITEM.match(line)
        if m:
            base, ordered = _indent(line), m.group(2)[0].isdigit()
            items = []
            while i < n:
                m = ITEM.match(lines[i].expandtabs(4))
                if not m or _indent(lines[i].expandtabs(4)) != base:
                    break
                content = [m.group(3)]
                i += 1
                while i < n:
                    l = lines[i].expandtabs(4)
                    if not l.strip():
                        j = i
                        while j < n and not lines[j].strip():
                            j += 1
                        if j < n and _indent(lines[j].expandtabs(4)) > base:
                            content.append("")
                            i += 1
                            continue
                        break
                    if _indent(l) > base:
                        content.append(l)
                    elif content[-1] == "" or _is_block_start(l):
                        break
                    else:
                        content.append(l)  # lazy continuation
                    i += 1
                items.append(content)
            tag = "ol" if ordered else "ul"
            lis = []
            for content in items:
                rest = content[1:]
                cut = min((_indent(l) for l in rest if l.strip()), default=0)
                sub = _blocks([content[0]] + [l[cut:] for l in rest], ids, after, shift)
                if sub and sub[0].startswith("<p>"):
                    sub[0] = sub[0][3:-4]  # the item's first paragraph without <p>
                lis.append("<li>%s</li>" % "".join(sub))
            out.append("<%s>%s</%s>" % (tag, "".join(lis), tag))
            continue
        para = [s]
        i += 1
        while i < n and lines[i].strip() and not _is_block_start(lines[i].expandtabs(4)):
            para.append(lines[i].strip())
            i += 1
        out.append("<p>%s</p>" % inline(" ".join(para), ids))
    return out


def to_html(text, ids=None, after_heading=None, shift=1):
    """The HTML of a Markdown text. `after_heading(fid)` may return HTML placed right after the
    heading of finding `fid`; headings are shifted down by `shift` levels (the page has an h1)."""
    return "\n".join(_blocks(text.splitlines(), set(ids or ()), after_heading, shift))
