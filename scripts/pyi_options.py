"""Regenerates the option keywords of python/shadow_oracle/__init__.pyi from the option tables.

Between a line "    # BEGIN <listing> (generated: scripts/update-docs)" and "    # END <listing>",
where <listing> is trace-options, raster-options or compare-options, the stub gets one keyword per
row of that table that the API offers: "    key: type = default,". Usage:
pyi_options.py SHADOW_ORACLE STUB (scripts/update-docs runs it; OptionTables.* and
TraceOptionTable.* fail where the stub and the tables differ).
"""
import json
import re
import subprocess
import sys

PYTHON_TYPES = {"integer": "int", "real": "float", "name": "str"}


def keyword_lines(program, listing):
    table = json.loads(subprocess.run([program, listing, "--json"], check=True,
                                      capture_output=True, text=True).stdout)
    lines = []
    for row in table["options"]:
        if "api" not in row["surfaces"]:
            continue
        default = row["default"]
        text = f'"{default}"' if row["type"] == "name" else repr(default)
        lines.append(f"    {row['key']}: {PYTHON_TYPES[row['type']]} = {text},\n")
    return lines


def main(program, stub):
    with open(stub) as f:
        lines = f.readlines()
    out, skipping = [], False
    begin = re.compile(r"^    # BEGIN ([a-z-]+-options) \(generated: scripts/update-docs\)$")
    for line in lines:
        m = begin.match(line.rstrip("\n"))
        if m:
            out.append(line)
            out.extend(keyword_lines(program, m.group(1)))
            skipping = True
        elif skipping and line.startswith("    # END "):
            out.append(line)
            skipping = False
        elif not skipping:
            out.append(line)
    if skipping:
        sys.exit(f"{stub}: a BEGIN line without its END")
    with open(stub, "w") as f:
        f.writelines(out)
    print(f"updated {stub}")


if __name__ == "__main__":
    main(*sys.argv[1:])
