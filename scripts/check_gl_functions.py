#!/usr/bin/env python3
"""The published list of the GL functions the library calls is complete (a ctest, "gl functions"):
every GL function named in the GL back end's code (include/hairshadow/gl.hpp and gl/, comments,
strings and the embedded GLSL of shaders.generated.hpp left out; called, or passed as a value) is an entry of
HAIRSHADOW_GL_FUNCTIONS in include/hairshadow/gl/context/gl_functions.hpp, and every entry is named
there. Each entry is X(glName, PFNGLNAMEPROC): the second name must be the first's Khronos typedef.
The list is sorted, README.md gives its length, and no call is qualified (::glName), which would
pass by the names a user declares in namespace hairshadow::gl. A difference prints the names and
exits 1.
    python3 scripts/check_gl_functions.py [ROOT]
    python3 scripts/check_gl_functions.py --print [ROOT]   the entries the code asks for, as the header's lines
"""
import pathlib
import re
import sys

ARGS = [a for a in sys.argv[1:] if a != "--print"]
ROOT = pathlib.Path(ARGS[0] if ARGS else pathlib.Path(__file__).resolve().parent.parent)
GL_DIR = ROOT / "include" / "hairshadow" / "gl"
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from check_layout import strip  # noqa: E402 (comments, strings and raw strings emptied)

LIST_HEADER = GL_DIR / "context" / "gl_functions.hpp"
SKIPPED = {"shaders.generated.hpp"}  # GLSL text: its built-ins are no GL API calls
# A GL API function: gl, then a capital (gl_error, glm::, GLuint and GL_ enums do not match).
GL_NAME = re.compile(r"\bgl[A-Z][A-Za-z0-9_]*\b")
ENTRY = re.compile(r"\bX\(\s*(\w+)\s*,\s*(\w+)\s*\)")


def used_functions():
    """{name: the first file naming it} of every GL function the GL back end's code names, and the
    places that qualify one (::glName), which a user's declarations in hairshadow::gl would not reach."""
    used, qualified = {}, []
    for path in [p for p in [GL_DIR.with_suffix(".hpp")] if p.exists()] + sorted(GL_DIR.rglob("*.hpp")):
        if path.name in SKIPPED or path == LIST_HEADER:
            continue
        code = strip(path.read_text())
        for m in GL_NAME.finditer(code):
            used.setdefault(m.group(), path.relative_to(ROOT).as_posix())
        qualified += [f"{path.relative_to(ROOT).as_posix()}: calls {m.group(1)}" for m in re.finditer(r"::\s*(gl[A-Z]\w*)", code)]
    return used, qualified


def pfn_of(name):
    return "PFN" + name.upper() + "PROC"


def main():
    used, qualified = used_functions()
    if "--print" in sys.argv[1:]:
        for name in sorted(used):
            print(f"    X({name}, {pfn_of(name)}) \\")
        return 0
    text = LIST_HEADER.read_text()
    body = re.search(r"#define HAIRSHADOW_GL_FUNCTIONS\(X\)((?:.*\\\n)*.*)", text)
    if not body:
        print(f"gl functions: {LIST_HEADER.relative_to(ROOT)} defines no HAIRSHADOW_GL_FUNCTIONS(X)")
        return 1
    entries = ENTRY.findall(body.group(1))
    listed = [name for name, _ in entries]
    count = re.search(r"#define HAIRSHADOW_GL_FUNCTION_COUNT (\d+)", text)
    problems = []
    problems += [f"{name} (in {where}) is not listed" for name, where in sorted(used.items()) if name not in listed]
    problems += [f"{name} is listed, but the library does not use it" for name in listed if name not in used]
    problems += [f"{name}'s type is {pfn}, not {pfn_of(name)}" for name, pfn in entries if pfn != pfn_of(name)]
    problems += [f"{name} is listed twice" for name in sorted(set(listed)) if listed.count(name) > 1]
    problems += [f"{where} qualified: call it by its bare name, so that a table of the user's is found" for where in qualified]
    if listed != sorted(listed):
        problems.append("the list is not sorted")
    if not count or int(count.group(1)) != len(listed):
        problems.append(f"HAIRSHADOW_GL_FUNCTION_COUNT is not {len(listed)}, the number of entries")
    readme = ROOT / "README.md"
    said = re.search(r"each of the (\d+)\s+GL functions", readme.read_text()) if readme.exists() else None
    if readme.exists() and (not said or int(said.group(1)) != len(listed)):
        problems.append(f"README.md's \"The GL functions the library calls\" does not say \"each of the {len(listed)} GL functions\"")
    for p in problems:
        print("gl functions:", p)
    print(f"gl functions: {len(listed)} listed, {len(used)} used; the list {'is wrong' if problems else 'is complete'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
