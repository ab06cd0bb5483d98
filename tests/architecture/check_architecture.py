#!/usr/bin/env python3
"""The rules between the libraries (docs/architecture.md), checked against the tree.

Reads the tables of docs/architecture.md's section "The rules as the test reads them" (the one
source: the document shows what this enforces) and checks every C++ file's includes and every
library's target_link_libraries against them, and every .cpp of the libraries and the program
against a size limit (MAX_CPP_LINES). Prints one line per failure, naming the file and
line, and exits 1; exits 0 with a summary when every rule holds.

    check_architecture.py [--root DIR] [--doc FILE]
"""

import argparse
import os
import re
import sys

SECTION = "## The rules as the test reads them"
# The folders whose C++ files every rule covers, and the first path components that make an
# include ours (shadow_oracle/ is the public header's folder, include/shadow_oracle/).
SOURCE_FOLDERS = ("core", "embree", "oracle", "raster_compare", "api", "include", "python", "cli")
OUR_TOPS = {"core", "embree", "oracle", "raster_compare", "api", "cli", "python", "tests", "bench",
            "include", "shadow_oracle"}
CPP_SUFFIXES = (".h", ".hpp", ".cpp", ".cc", ".inl")
INCLUDE_RE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
COMMAND_RE = re.compile(
    r"\b(add_library|add_executable|pybind11_add_module|target_link_libraries)\s*\(([^)]*)\)",
    re.S)
LINK_KEYWORDS = {"PUBLIC", "PRIVATE", "INTERFACE", "LINK_PUBLIC", "LINK_PRIVATE"}
# Targets of ours that carry only compile options, not code.
IGNORED_TARGETS = {"so_warnings"}
# A source file past this many lines holds more than one concept (issue 62: split them by what
# they read or do, one concept per .h/.cpp, at most about 600 lines each); the rule covers the
# .cpp files of the libraries and the program.
MAX_CPP_LINES = 800
# The raster path is kept in rooms (issue 62): sub-folders by concern, each in the room table with
# the other rooms (and the folder's own files) it may include; its own folder keeps at most this
# many C++ files: the plug-in interface, not the plumbing.
ROOMED = "raster_compare/gl/"
MAX_TOP_FILES = 12
SIZE_FOLDERS = ("core", "oracle", "raster_compare", "api", "cli")


class RulesError(Exception):
    """The document's tables cannot be read: the check cannot run."""


def cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def names(cell):
    """A table cell as a list: comma-separated, backticks dropped, empty for '' or '—'."""
    cell = cell.replace("`", "").strip()
    if cell in ("", "—", "-"):
        return []
    return [n.strip() for n in cell.split(",") if n.strip()]


def read_tables(doc_text, doc_name):
    """The tables of SECTION, keyed by the first header cell."""
    start = doc_text.find("\n" + SECTION + "\n")
    if start < 0:
        raise RulesError(f"{doc_name}: no section '{SECTION}'")
    body = doc_text[start + len(SECTION) + 2:]
    end = body.find("\n## ")
    body = body if end < 0 else body[:end]
    tables, header, rows = {}, None, None
    for line in body.splitlines() + [""]:
        if line.startswith("|"):
            if header is None:
                header, rows = cells(line), []
            elif not re.fullmatch(r"\|?(\s*:?-+:?\s*\|)+\s*", line.strip()):
                row = cells(line)
                if len(row) != len(header):
                    raise RulesError(f"{doc_name}: a row of the '{header[0]}' table has "
                                     f"{len(row)} cells, not {len(header)}: {line.strip()}")
                rows.append(dict(zip(header, row)))
        elif header is not None:
            tables[header[0]] = rows
            header = None
    for key in ("dependency", "folder", "where"):
        if key not in tables:
            raise RulesError(f"{doc_name}: section '{SECTION}' has no table starting '| {key} |'")
    return tables


class Rules:
    def __init__(self, tables):
        self.deps = {}
        for row in tables["dependency"]:
            self.deps[row["dependency"]] = (names(row["headers"]), names(row["link names"]))
        self.rows = []
        for row in tables["folder"]:
            folder = names(row["folder"])[0]
            self.rows.append({
                "folder": folder,
                "targets": names(row["targets"]),
                "includes": names(row["includes of ours"]),
                "links": set(names(row["links of ours"])),
                "never_includes": self.dep_set(row["never includes"], folder),
                "never_links": self.dep_set(row["never links"], folder),
            })
        self.rooms = {names(r["room"])[0]: names(r["may include"]) for r in tables.get("room", [])}
        self.exceptions = [{"where": names(r["where"])[0], "breaks": r["breaks"].strip(),
                            "used": False} for r in tables["where"]]

    def dep_set(self, cell, folder):
        """('all' or not, the dependencies named): 'all' forbids every header but the standard
        library's and ours; 'all but X, Y' the same with X and Y allowed."""
        text = cell.replace("`", "").strip()
        every = text == "all" or text.startswith("all but ")
        allowed = names(text[len("all but "):]) if text.startswith("all but ") else []
        listed = [] if every else names(text)
        for dep in allowed + listed:
            if dep not in self.deps:
                raise RulesError(f"the row of {folder} names '{dep}', not in the dependency table")
        forbidden = [d for d in self.deps if d not in allowed] if every else listed
        return {"all": every, "allowed": allowed, "deps": forbidden}

    def row_of(self, path):
        """The row of the longest folder (or the file itself) holding path, or None."""
        best = None
        for row in self.rows:
            f = row["folder"]
            if path == f or (f.endswith("/") and path.startswith(f)):
                if best is None or len(f) > len(best["folder"]):
                    best = row
        return best

    def excused(self, where, breaks):
        for e in self.exceptions:
            if e["where"] == where and e["breaks"] == breaks:
                e["used"] = True
                return True
        return False


def is_standard(header):
    """A standard library header: <vector>, <cstdint>; no folder, no extension."""
    return "/" not in header and "." not in header


def source_files(root):
    for top in SOURCE_FOLDERS:
        base = os.path.join(root, top)
        for dirpath, dirnames, filenames in os.walk(base):
            dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
            for f in sorted(filenames):
                if f.endswith(CPP_SUFFIXES):
                    yield os.path.relpath(os.path.join(dirpath, f), root).replace(os.sep, "/")


def includes_of(root, path):
    with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, 1):
            m = INCLUDE_RE.match(line)
            if m:
                yield number, m.group(1), m.group(2)


def dep_of_header(rules, header):
    for dep, (headers, _) in rules.deps.items():
        if any(header == h or (h.endswith("/") and header.startswith(h)) for h in headers):
            return dep
    return None


def check_includes(root, rules, failures):
    """Every file's includes against its row; returns the include graph of our files."""
    graph = {}
    for path in source_files(root):
        row = rules.row_of(path)
        if row is None:
            failures.append(f"{path}: no row of docs/architecture.md's library table holds it "
                            "(add its folder to the table)")
            continue
        where = row["folder"]
        edges = graph.setdefault(path, [])
        for number, bracket, inc in includes_of(root, path):
            top = inc.split("/", 1)[0]
            at = f"{path}:{number}: includes {inc}"
            if top in OUR_TOPS and "/" in inc:
                if not any(inc == a or (a.endswith("/") and inc.startswith(a))
                           for a in row["includes"]):
                    allowed = ", ".join(row["includes"]) or "nothing of ours"
                    if not rules.excused(where, f"includes {inc}"):
                        failures.append(f"{at}: {where} may include only {allowed}")
                target = ("include/" + inc) if top == "shadow_oracle" else inc
                edges.append(target)
                continue
            if bracket == '"':
                failures.append(f"{at}: a quoted include is written from the repository root "
                                "(core/..., embree/..., oracle/..., raster_compare/...)")
                continue
            dep = dep_of_header(rules, inc)
            never = row["never_includes"]
            bad = None
            if dep is not None and dep in never["deps"]:
                bad = f"{where} never includes {dep}"
            elif dep is None and never["all"] and not is_standard(inc):
                bad = f"{where} includes only the standard library" + (
                    ", " + ", ".join(never["allowed"]) if never["allowed"] else "") + \
                    " and its own headers"
            if bad and not rules.excused(where, f"never includes {dep or inc}"):
                failures.append(f"{at}: {bad}")
    return graph


def check_cycles(graph, failures):
    """Include cycles among our files (Tarjan's strongly connected components)."""
    index, low, on_stack, stack, counter = {}, {}, set(), [], [0]
    cycles = []

    def visit(start):
        work = [(start, iter(graph.get(start, [])))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            advanced = False
            for child in children:
                if child not in graph:
                    continue  # generated or missing: not ours to follow
                if child not in index:
                    index[child] = low[child] = counter[0]
                    counter[0] += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(graph.get(child, []))))
                    advanced = True
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            if advanced:
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    n = stack.pop()
                    on_stack.discard(n)
                    component.append(n)
                    if n == node:
                        break
                if len(component) > 1 or node in graph.get(node, []):
                    cycles.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    for c in cycles:
        failures.append("include cycle: " + " <-> ".join(c))


def check_sizes(root, failures):
    """Every .cpp under SIZE_FOLDERS at most MAX_CPP_LINES lines."""
    for path in source_files(root):
        if path.split("/", 1)[0] not in SIZE_FOLDERS or not path.endswith(".cpp"):
            continue
        with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
            count = sum(1 for _ in f)
        if count > MAX_CPP_LINES:
            failures.append(f"{path}: {count} lines, over {MAX_CPP_LINES}: split it by concept "
                            "(one concept per .h/.cpp, at most about 600 lines each)")


def room_of(path):
    """The room of a file under ROOMED ("shadow_maps/"), "" for the folder's own files."""
    rel = path[len(ROOMED):]
    return rel.split("/", 1)[0] + "/" if "/" in rel else ""


def check_rooms(root, rules, failures):
    """Every room of ROOMED has a row of the room table and each row a room; a file includes from
    ROOMED only its own room and what its room's row lists; the folder's own files are at most
    MAX_TOP_FILES."""
    base = os.path.join(root, ROOMED)
    if not os.path.isdir(base):
        return
    rooms = sorted(d + "/" for d in os.listdir(base) if os.path.isdir(os.path.join(base, d)))
    if not rooms and not rules.rooms:
        return
    if not rules.rooms:
        failures.append(f"docs/architecture.md: no room table ('| room | holds | may include |') "
                        f"for the rooms of {ROOMED}")
        return
    for room in rooms:
        if room not in rules.rooms:
            failures.append(f"{ROOMED}{room}: a room with no row in docs/architecture.md's room "
                            "table")
    for room in rules.rooms:
        if room != "(own files)" and room not in rooms:
            failures.append(f"docs/architecture.md: the room table names {ROOMED}{room}, which "
                            "does not exist")
    own = sorted(f for f in os.listdir(base) if f.endswith(CPP_SUFFIXES))
    if len(own) > MAX_TOP_FILES:
        failures.append(f"{ROOMED}: {len(own)} C++ files directly in it, over {MAX_TOP_FILES}: "
                        "move the plumbing into its room")
    for path in source_files(root):
        if not path.startswith(ROOMED):
            continue
        room = room_of(path)
        allowed = rules.rooms.get(room or "(own files)", [])
        for number, _, inc in includes_of(root, path):
            if not inc.startswith(ROOMED):
                continue
            rel = inc[len(ROOMED):]
            same_room = rel.startswith(room) if room else "/" not in rel
            if same_room or any(
                    rel == a or (a.endswith("/") and rel.startswith(a)) for a in allowed):
                continue
            where = f"{ROOMED}{room}" if room else f"{ROOMED}'s own files"
            failures.append(f"{path}:{number}: includes {inc}: {where} may include only "
                            f"{', '.join(allowed) or 'its own room'} of {ROOMED}")


def strip_cmake_comments(text):
    """CMake line comments dropped (a '#' at a line's start or after a space, outside quotes)."""
    out = []
    for line in text.splitlines():
        quoted, cut = False, len(line)
        for i, ch in enumerate(line):
            if ch == '"' and (i == 0 or line[i - 1] != "\\"):
                quoted = not quoted
            elif ch == "#" and not quoted and (i == 0 or line[i - 1] in " \t("):
                cut = i
                break
        out.append(line[:cut])
    return "\n".join(out)


def read_targets(root):
    """Every target of the CMakeLists.txt files outside tests/ and bench/: its kind, the file
    that defines it, and its links as (scope, name)."""
    targets = {}
    for dirpath, dirnames, filenames in os.walk(root):
        rel = os.path.relpath(dirpath, root).replace(os.sep, "/")
        dirnames[:] = sorted(d for d in dirnames if not d.startswith(".") and d != "build"
                             and not (rel == "." and d in ("tests", "bench")))
        if "CMakeLists.txt" not in filenames:
            continue
        cmake = os.path.join(rel, "CMakeLists.txt").lstrip("./") if rel != "." else "CMakeLists.txt"
        with open(os.path.join(dirpath, "CMakeLists.txt"), encoding="utf-8") as f:
            text = strip_cmake_comments(f.read())
        for m in COMMAND_RE.finditer(text):
            command, args = m.group(1), m.group(2).split()
            if not args:
                continue
            name = args[0]
            if command == "add_library":
                kind = args[1] if len(args) > 1 and args[1] in (
                    "STATIC", "SHARED", "MODULE", "INTERFACE", "OBJECT") else "STATIC"
                if "ALIAS" in args:
                    continue
                targets.setdefault(name, {"links": []}).update(kind=kind, file=cmake)
            elif command == "pybind11_add_module":
                targets.setdefault(name, {"links": []}).update(kind="MODULE", file=cmake)
            elif command == "add_executable":
                targets.setdefault(name, {"links": []}).update(kind="EXECUTABLE", file=cmake)
            else:
                scope = "PUBLIC"
                for a in args[1:]:
                    if a in LINK_KEYWORDS:
                        scope = "PRIVATE" if a in ("PRIVATE", "LINK_PRIVATE") else "PUBLIC"
                    else:
                        targets.setdefault(name, {"links": []})["links"].append((scope, a))
    return targets


def dep_of_link(rules, link):
    for dep, (_, links) in rules.deps.items():
        if link in links:
            return dep
    return None


def link_closure(targets, name):
    """What linking `name` brings: its direct links, and theirs through static libraries and the
    public links of shared ones (a shared library's private links stay inside it)."""
    seen, order, todo = set(), [], [(name, [name])]
    while todo:
        current, via = todo.pop()
        for scope, link in targets.get(current, {}).get("links", []):
            if link in seen:
                continue
            inner = targets.get(link)
            seen.add(link)
            order.append((link, via))
            if inner is None:
                continue
            if inner.get("kind") in ("SHARED", "MODULE"):
                for s2, l2 in inner["links"]:
                    if s2 == "PUBLIC" and l2 not in seen:
                        seen.add(l2)
                        order.append((l2, via + [link]))
            else:
                todo.append((link, via + [link]))
    return order


def check_links(root, rules, failures):
    targets = read_targets(root)
    ours = {n for n in targets if n not in IGNORED_TARGETS}
    named = set()
    for row in rules.rows:
        where = row["folder"]
        for t in row["targets"]:
            named.add(t)
            if t not in targets or "kind" not in targets[t]:
                failures.append(f"docs/architecture.md: the row of {where} names target {t}, "
                                "which no CMakeLists.txt defines")
        if not row["targets"]:
            continue
        own = set(row["targets"])
        direct = {link for t in row["targets"] for _, link in targets.get(t, {}).get("links", [])
                  if link in ours} - own
        if direct != row["links"]:
            file = targets.get(row["targets"][0], {}).get("file", "CMakeLists.txt")
            extra, missing = sorted(direct - row["links"]), sorted(row["links"] - direct)
            what = "; ".join(x for x in (
                "links " + ", ".join(extra) + " beyond the table" if extra else "",
                "does not link " + ", ".join(missing) + " that the table says" if missing else "")
                if x)
            if not rules.excused(where, "links " + ", ".join(extra or missing)):
                failures.append(f"{file}: {', '.join(row['targets'])} {what} "
                                f"(links of ours for {where}: "
                                f"{', '.join(sorted(row['links'])) or 'none'})")
        for t in row["targets"]:
            for link, via in link_closure(targets, t):
                dep = dep_of_link(rules, link)
                if dep is None or dep not in row["never_links"]["deps"]:
                    continue
                if rules.excused(t, f"never links {dep}"):
                    continue
                chain = " -> ".join(via + [link])
                file = targets[t].get("file", "CMakeLists.txt")
                failures.append(f"{file}: {t} links {dep} ({chain}): {where} never links {dep}")
    for name, t in sorted(targets.items()):
        if t.get("kind") in ("STATIC", "SHARED", "MODULE", "OBJECT") and name not in named \
                and name not in IGNORED_TARGETS and \
                t["file"].split("/", 1)[0] in SOURCE_FOLDERS:
            failures.append(f"{t['file']}: library {name} has no row in docs/architecture.md's "
                            "library table")


def check(root, doc):
    """The failures, one line each (empty when every rule holds)."""
    with open(doc, encoding="utf-8") as f:
        rules = Rules(read_tables(f.read(), os.path.relpath(doc, root)))
    failures = []
    graph = check_includes(root, rules, failures)
    check_cycles(graph, failures)
    check_links(root, rules, failures)
    check_sizes(root, failures)
    check_rooms(root, rules, failures)
    for e in rules.exceptions:
        if not e["used"]:
            failures.append(f"docs/architecture.md: the exception '{e['where']}: {e['breaks']}' "
                            "no longer excuses anything: remove its row")
    return failures, len(graph), len(rules.rows)


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=os.path.normpath(os.path.join(here, "..", "..")))
    parser.add_argument("--doc", default=None, help="default: ROOT/docs/architecture.md")
    args = parser.parse_args(argv)
    doc = args.doc or os.path.join(args.root, "docs", "architecture.md")
    try:
        failures, files, rows = check(args.root, doc)
    except (RulesError, OSError) as e:
        print(f"architecture: {e}")
        return 2
    for line in failures:
        print(f"architecture: {line}")
    if failures:
        print(f"architecture: {len(failures)} rule(s) broken (docs/architecture.md, "
              f"'{SECTION[3:]}')")
        return 1
    print(f"architecture: {files} files and {rows} library rows hold to docs/architecture.md")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
