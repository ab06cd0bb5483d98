"""Generated text in a markdown file: what lies between a `<!-- BEGIN NAME ... -->` line and its
`<!-- END NAME -->`, which the figure scripts (readme-figures, cycles-compare, growth-study, and the
table and figure writers beside this file) write again on every run. Nothing between the markers is
typed by hand."""
import pathlib
import re
import sys


def replace_between_markers(text, name, body, where="the document"):
    """text with NAME's generated part replaced by body (after a blank line); exits naming the
    markers unless text holds exactly one pair of them."""
    pattern = (r"(<!-- BEGIN " + re.escape(name) + r"[^\n]*-->\n).*?(<!-- END " + re.escape(name) +
               r" -->)")
    new, n = re.subn(pattern, lambda m: m.group(1) + "\n" + body + "\n" + m.group(2), text,
                     flags=re.S)
    if n != 1:
        sys.exit(f"error: {where}: needs one <!-- BEGIN {name} --> ... <!-- END {name} --> pair "
                 f"(found {n})")
    return new


def write_between_markers(path, name, body):
    """replace_between_markers on the file at path, written back."""
    path = pathlib.Path(path)
    path.write_text(replace_between_markers(path.read_text(), name, body, str(path)))
