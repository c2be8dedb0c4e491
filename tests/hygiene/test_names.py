#!/usr/bin/env python3
"""No Catch2 TEST_CASE name holds a ';'.

catch_discover_tests (CMakeLists.txt) registers each test case with CTest by
name, and CMake splits a list at ';': a name with one became two CTest
entries whose filters matched no test case, and both "passed" having run
nothing (six tests, among them the shard merge test, found so in issue 30's
work). Usage: test_names.py ROOT, or --self-test (plants such a name and
shows the check find it).
"""
import pathlib
import re
import sys
import tempfile

NAME = re.compile(r'TEST_CASE\(((?:\s*"(?:[^"\\]|\\.)*")+)')
PART = re.compile(r'"((?:[^"\\]|\\.)*)"')


def bad_names(root):
    out = []
    for path in sorted(pathlib.Path(root, "tests").rglob("*.cpp")):
        text = path.read_text(errors="replace")
        for m in NAME.finditer(text):
            name = "".join(PART.findall(m.group(1)))
            if ";" in name:
                out.append(f"{path}:{text.count(chr(10), 0, m.start()) + 1}: {name}")
    return out


def main():
    if sys.argv[1:] == ["--self-test"]:
        with tempfile.TemporaryDirectory() as d:
            pathlib.Path(d, "tests").mkdir()
            pathlib.Path(d, "tests/t.cpp").write_text('TEST_CASE("fine", "[a]") {}\nTEST_CASE("one; "\n  "two") {}\n')
            found = bad_names(d)
            if len(found) != 1 or not found[0].endswith("one; two"):
                print("self-test: the planted name was not found:", found)
                return 1
        print("self-test: the planted ';' name was found")
        return 0
    found = bad_names(sys.argv[1])
    for line in found:
        print(line, "-- a ';' splits this test in two CTest entries that run nothing")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
