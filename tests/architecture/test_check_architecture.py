"""check_architecture.py on small trees that break each kind of rule: it must name each one."""

import os
import sys
import tempfile
import textwrap
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_architecture  # noqa: E402

DOC = """\
# Architecture

## The rules as the test reads them

| dependency | headers | link names |
|---|---|---|
| Embree | `embree3/` | `embree` |
| GL | `epoxy/` | `PkgConfig::EPOXY` |

| folder | targets | includes of ours | links of ours | never includes | never links |
|---|---|---|---|---|---|
| `core/` | `so_core` | `core/` | | Embree, GL | Embree, GL |
| `oracle/` | `so_oracle` | `core/`, `oracle/` | `so_core` | GL | GL |
| `raster_compare/gl/` | `so_raster` | `core/`, `raster_compare/gl/` | `so_core` | Embree | Embree |
| `include/shadow_oracle/` | | | | all | |
{extra_rows}
| where | breaks | why |
|---|---|---|
{exceptions}
## Where new things go
"""

CMAKE = {
    "core/CMakeLists.txt": "add_library(so_core STATIC scene.cpp)\n"
                           "target_link_libraries(so_core PUBLIC glm::glm PRIVATE so_warnings)\n",
    "oracle/CMakeLists.txt": "add_library(so_oracle STATIC accel.cpp)\n"
                             "# a comment naming target_link_libraries(so_oracle PkgConfig::EPOXY)\n"
                             "target_link_libraries(so_oracle PUBLIC so_core embree)\n",
    "raster_compare/gl/CMakeLists.txt": "add_library(so_raster STATIC renderer.cpp)\n"
                                        "target_link_libraries(so_raster PUBLIC so_core "
                                        "PkgConfig::EPOXY)\n",
}

FILES = {
    "core/scene.h": "#pragma once\n#include <vector>\n#include <glm/vec3.hpp>\n",
    "core/scene.cpp": '#include "core/scene.h"\n',
    "oracle/accel.h": '#pragma once\n#include "core/scene.h"\n#include <embree3/rtcore.h>\n',
    "oracle/accel.cpp": '#include "oracle/accel.h"\n',
    "raster_compare/gl/renderer.h": '#pragma once\n#include <epoxy/gl.h>\n#include "core/scene.h"\n',
    "raster_compare/gl/renderer.cpp": '#include "raster_compare/gl/renderer.h"\n',
    "include/shadow_oracle/shadow_oracle.h": "#pragma once\n#include <string>\n#include <cstdint>\n",
}


class CheckArchitecture(unittest.TestCase):
    def tree(self, files=None, cmake=None, exceptions="", extra_rows=""):
        """A tree with the clean files, overridden by `files` and `cmake`; the failures."""
        root = tempfile.mkdtemp(prefix="so_arch_")
        self.addCleanup(lambda: __import__("shutil").rmtree(root))
        contents = dict(FILES, **CMAKE)
        contents.update(files or {})
        contents.update(cmake or {})
        contents["docs/architecture.md"] = DOC.format(exceptions=exceptions, extra_rows=extra_rows)
        for path, text in contents.items():
            if text is None:
                continue
            os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
            with open(os.path.join(root, path), "w") as f:
                f.write(text)
        failures, _, _ = check_architecture.check(root, os.path.join(root, "docs/architecture.md"))
        return failures

    def assertOneFailure(self, failures, *parts):
        self.assertEqual(len(failures), 1, failures)
        for p in parts:
            self.assertIn(p, failures[0])

    def test_clean_tree_passes(self):
        self.assertEqual(self.tree(), [])

    def test_include_of_another_library(self):
        f = self.tree({"oracle/accel.cpp": '#include "oracle/accel.h"\n'
                                           '#include "raster_compare/gl/renderer.h"\n'})
        self.assertOneFailure(f, "oracle/accel.cpp:2", "raster_compare/gl/renderer.h",
                              "oracle/ may include only core/, oracle/")

    def test_forbidden_third_party_header(self):
        f = self.tree({"core/scene.cpp": '#include "core/scene.h"\n#include <epoxy/gl.h>\n'})
        self.assertOneFailure(f, "core/scene.cpp:2", "core/ never includes GL")

    def test_quoted_include_relative_to_the_file(self):
        f = self.tree({"core/scene.cpp": '#include "scene.h"\n'})
        self.assertOneFailure(f, "core/scene.cpp:1", "written from the repository root")

    def test_public_header_includes_only_the_standard_library(self):
        f = self.tree({"include/shadow_oracle/shadow_oracle.h": "#include <glm/vec3.hpp>\n"})
        self.assertOneFailure(f, "shadow_oracle.h:1", "glm/vec3.hpp", "only the standard library")

    def test_direct_link_beyond_the_table(self):
        f = self.tree(cmake={"raster_compare/gl/CMakeLists.txt":
                             "add_library(so_raster STATIC renderer.cpp)\n"
                             "target_link_libraries(so_raster PUBLIC so_core so_oracle "
                             "PkgConfig::EPOXY)\n"})
        self.assertIn("so_raster links so_oracle beyond the table", "\n".join(f))
        # and, through so_oracle, Embree
        self.assertIn("so_raster links Embree (so_raster -> so_oracle -> embree)", "\n".join(f))
        self.assertEqual(len(f), 2, f)

    def test_missing_link_the_table_names(self):
        f = self.tree(cmake={"oracle/CMakeLists.txt": "add_library(so_oracle STATIC accel.cpp)\n"
                                                      "target_link_libraries(so_oracle embree)\n"})
        self.assertOneFailure(f, "so_oracle does not link so_core")

    def test_transitive_forbidden_link(self):
        f = self.tree(cmake={"core/CMakeLists.txt": "add_library(so_core STATIC scene.cpp)\n"
                                                    "add_library(so_extra STATIC x.cpp)\n"
                                                    "target_link_libraries(so_extra embree)\n"
                                                    "target_link_libraries(so_core so_extra)\n"},
                      extra_rows="| `core/extra/` | `so_extra` | `core/` | | | |\n")
        joined = "\n".join(f)
        self.assertIn("so_core links so_extra beyond the table", joined)
        self.assertIn("so_core links Embree (so_core -> so_extra -> embree)", joined)
        # so_oracle links so_core and may link Embree; so_raster may not, through so_core.
        self.assertIn("so_raster links Embree (so_raster -> so_core -> so_extra -> embree)", joined)

    def test_library_without_a_row(self):
        f = self.tree(cmake={"core/CMakeLists.txt": "add_library(so_core STATIC scene.cpp)\n"
                                                    "add_library(so_more STATIC more.cpp)\n"})
        self.assertOneFailure(f, "library so_more has no row")

    def test_file_outside_every_row(self):
        f = self.tree({"api/trace.cpp": "#include <string>\n"})
        self.assertOneFailure(f, "api/trace.cpp", "no row")

    def test_cpp_over_the_size_limit(self):
        limit = check_architecture.MAX_CPP_LINES
        body = '#include "core/scene.h"\n' + "// a line\n" * (limit - 1)
        self.assertEqual(self.tree({"core/scene.cpp": body}), [])
        f = self.tree({"core/scene.cpp": body + "// one more\n"})
        self.assertOneFailure(f, "core/scene.cpp", f"{limit + 1} lines, over {limit}")
        # The limit is on the .cpp files of the library folders only.
        self.assertEqual(self.tree({"core/scene.h": "#pragma once\n" * (limit + 1)}), [])

    def test_include_cycle(self):
        f = self.tree({"core/a.h": '#include "core/b.h"\n', "core/b.h": '#include "core/a.h"\n'})
        self.assertOneFailure(f, "include cycle", "core/a.h <-> core/b.h")

    def test_exception_excuses_and_must_be_used(self):
        bad = {"raster_compare/gl/CMakeLists.txt": "add_library(so_raster STATIC renderer.cpp)\n"
                                                   "target_link_libraries(so_raster so_core embree "
                                                   "PkgConfig::EPOXY)\n"}
        self.assertOneFailure(self.tree(cmake=bad), "so_raster links Embree")
        exception = "| `so_raster` | never links Embree | a reason |\n"
        self.assertEqual(self.tree(cmake=bad, exceptions=exception), [])
        self.assertOneFailure(self.tree(exceptions=exception), "no longer excuses anything")

    def test_unknown_dependency_in_a_row(self):
        with self.assertRaisesRegex(check_architecture.RulesError, "Vulkan"):
            self.tree(extra_rows="| `api/` | | | | Vulkan | |\n")

    def test_missing_section(self):
        root = tempfile.mkdtemp(prefix="so_arch_")
        self.addCleanup(lambda: __import__("shutil").rmtree(root))
        doc = os.path.join(root, "architecture.md")
        with open(doc, "w") as f:
            f.write(textwrap.dedent("# Architecture\n\nNo rules.\n"))
        with self.assertRaisesRegex(check_architecture.RulesError, "no section"):
            check_architecture.check(root, doc)


    ROOMS = ("\n| room | holds | may include |\n|---|---|---|\n"
             "| (own files) | the interface | `context/x.h` |\n"
             "| `context/` | plumbing | |\n"
             "| `maps/` | maps | `context/` |\n")

    def rooms_tree(self, files, rooms=None):
        """A tree whose raster path has the rooms context/ and maps/ and the table ROOMS."""
        base = {"raster_compare/gl/context/x.h": "#pragma once\n",
                "raster_compare/gl/maps/m.h": '#pragma once\n#include "raster_compare/gl/context/x.h"\n'}
        base.update(files)
        doc_rooms = self.ROOMS if rooms is None else rooms
        return self.tree(files=base, extra_rows=doc_rooms)

    def test_rooms_hold(self):
        self.assertEqual(self.rooms_tree({}), [])

    def test_a_room_including_another_not_in_its_row(self):
        f = self.rooms_tree({"raster_compare/gl/context/y.h":
                             '#pragma once\n#include "raster_compare/gl/maps/m.h"\n'})
        self.assertOneFailure(f, "raster_compare/gl/context/y.h:2", "may include only")

    def test_a_room_without_a_row(self):
        f = self.rooms_tree({"raster_compare/gl/time/t.h": "#pragma once\n"})
        self.assertOneFailure(f, "raster_compare/gl/time/", "no row")

    def test_a_row_without_its_room(self):
        f = self.rooms_tree({}, rooms=self.ROOMS + "| `gone/` | nothing | |\n")
        self.assertOneFailure(f, "gone/", "does not exist")

    def test_too_many_files_in_the_folder_itself(self):
        many = {f"raster_compare/gl/f{i}.h": "#pragma once\n" for i in range(12)}
        f = self.rooms_tree(many)  # 12 here and renderer.h, .cpp: 14
        self.assertOneFailure(f, "14 C++ files directly in it")

if __name__ == "__main__":
    unittest.main()
