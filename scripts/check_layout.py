#!/usr/bin/env python3
"""The layout rules of issue 40, checked (a ctest, "layout"):
  - no hand-written file over 500 lines (headers, sources, tests, examples, benchmarks);
  - no function over 100 lines (found by matching braces, comments and strings removed);
  - the library's folders include downwards only, in the order of RANKS, and no header is in an
    include loop; internal headers live in detail/ folders, and no example includes one;
  - no name defined at file scope (a function, variable, type or alias outside any class or function)
    in two source files of one folder of COMPILED_TOGETHER: programs there compile several files as
    one translation unit (hairshadow_compile_together), and which files share a unit changes as files
    come and go. Stricter than the compiler: per folder rather than per program (which program a file
    joins can change too), and an overload or a name in two named namespaces counts.
Exceptions are listed below by name, each with why it stands; a rule that fails prints the file and
line and exits 1.
    python3 scripts/check_layout.py [ROOT]
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
MOST_LINES, MOST_FUNCTION_LINES = 500, 100
# The library's folders, lowest first: a header includes its own folder's and lower ones' only.
# The umbrella headers (hairshadow.hpp, gl.hpp) may include anything; config.hpp is the lowest.
RANKS = ["config", "core", "procedural", "io", "raster", "policies", "accumulation", "placement", "reconstruction", "reference",
         "methods", "shading", "gl"]
UMBRELLAS = {"hairshadow.hpp", "gl.hpp"}
# Known exceptions, each with why it stands (none now).
LONG_FILES = set()
INCLUDE_LOOPS = set()
GENERATED = {"include/hairshadow/gl/shaders.generated.hpp"}
# Folders whose programs compile several files as one translation unit (CMakeLists.txt,
# hairshadow_compile_together): a file-scope name may appear in one file of each.
COMPILED_TOGETHER = ["tests", "tests/gl", "tools", "tools/python"]


def hand_written():
    for folder in ("include", "tools", "tests", "bench", "examples"):
        for path in sorted((ROOT / folder).rglob("*")):
            rel = path.relative_to(ROOT).as_posix()
            if path.suffix in (".hpp", ".cpp") and rel not in GENERATED and "/build" not in rel:
                yield rel, path


def strip(src):
    """The source with comments, strings and characters emptied, newlines kept."""
    out, i, n = [], 0, len(src)
    while i < n:
        if src.startswith("//", i):
            j = src.find("\n", i)
            i = n if j < 0 else j
            continue
        if src.startswith("/*", i):
            j = src.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * src.count("\n", i, j))
            i = j
            continue
        m = re.match(r'R"([^(]*)\(', src[i:]) if src.startswith('R"', i) else None
        if m:
            end = ")" + m.group(1) + '"'
            j = src.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append('""' + "\n" * src.count("\n", i, j))
            i = j
            continue
        c = src[i]
        if c == '"' or (c == "'" and not (i > 0 and src[i - 1].isalnum())):
            j = i + 1
            while j < n and src[j] != c:
                j += 2 if src[j] == "\\" else 1
            out.append(c + c + "\n" * src.count("\n", i, j))
            i = j + 1
            continue
        out.append(c)
        i += 1
    return "".join(out)


FUNCTION_HEAD = re.compile(r"\)\s*(const|noexcept(\([^)]*\))?|override|final|mutable|&|&&|->\s*[\w:<>, *&]+|HAIRSHADOW_\w+|\s)*$")
CONTROL_HEAD = re.compile(r"\b(if|for|while|switch|catch)\s*\([^;{}]*\)\s*$")
INIT_LIST_HEAD = re.compile(r"\)\s*:\s*[\w:]+[({][^;{}]*$")


def long_functions(text):
    """(lines, first line) of each outermost function body over the limit."""
    s = strip(text)
    stack, found = [], []
    for m in re.finditer(r"[{}]", s):
        if m.group() == "{":
            head = s[max(0, m.start() - 300):m.start()].rstrip()
            is_function = (FUNCTION_HEAD.search(head) and not CONTROL_HEAD.search(head)) or INIT_LIST_HEAD.search(head)
            stack.append((bool(is_function), m.start()))
        elif stack:
            is_function, start = stack.pop()
            if is_function and not any(f for f, _ in stack):
                first, last = s.count("\n", 0, start) + 1, s.count("\n", 0, m.start()) + 1
                if last - first + 1 > MOST_FUNCTION_LINES:
                    found.append((last - first + 1, first))
    return found


CALLED_NAME = re.compile(r"(?<![\w:~])([A-Za-z_]\w*)\s*(<[^<>;{}()]*>)?\s*\($")
TYPE_HEAD = re.compile(r"\b(?:struct|class|enum(?:\s+class)?|union)\s+([A-Za-z_]\w*)[^;{}]*$")
ALIAS = re.compile(r"^(?:using\s+([A-Za-z_]\w*)\s*=|typedef\b.*?([A-Za-z_]\w*)\s*$)", re.S)
VARIABLE = re.compile(r"^(?:(?:static|const|constexpr|inline|thread_local)\s+)*[\w:<>,\s*&]+?\s([A-Za-z_]\w*)\s*(\[[^\]]*\])?\s*(=|$)")
NOT_A_VARIABLE = ("using", "typedef", "template", "extern", "return", "static_assert", "struct", "class", "enum", "union", "friend", "namespace")
TRANSPARENT_BLOCK = re.compile(r"(\bnamespace\b[\w:\s]*|\bextern\s*\"\")$")


def variable_or_alias(statement):
    """The name a file-scope statement defines as a variable or type alias, if any."""
    alias = ALIAS.match(statement)
    if alias:
        return alias.group(1) or alias.group(2)
    variable = VARIABLE.match(statement)
    return variable.group(1) if variable and not statement.startswith(NOT_A_VARIABLE) else None


def function_name(head, function):
    """The name of the free function whose head ends at `function` (FUNCTION_HEAD's match), if any:
    not a member defined out of line (a::f, a::~a, a constructor's initialisers), not an operator,
    not a macro (TEST_CASE)."""
    depth = 0
    for j in range(function.start(), -1, -1):  # back to the parameter list's "("
        depth += {")": 1, "(": -1}.get(head[j], 0)
        if depth == 0:
            called = CALLED_NAME.search(head[:j + 1])
            if not called or called.group(1).isupper() or head[:called.start()].rstrip().endswith("operator"):
                return None
            return called.group(1)
    return None


def file_scope_names(text):
    """Names a source file defines outside any class or function: free functions, variables, types
    and type aliases. A heuristic (it reads text, not C++), strict where unsure: overloads and the
    same name in two named namespaces count as one name."""
    s = strip(text)
    names, open_blocks, last = set(), [], 0  # open_blocks: whether each open brace is a namespace's
    for m in re.finditer(r"[{};]", s):
        head, at_file_scope = s[last:m.start()], all(open_blocks)
        last = m.end()
        head = "\n".join(line for line in head.split("\n") if not line.lstrip().startswith("#")).strip()
        if m.group() == "}":
            if open_blocks:
                open_blocks.pop()
            continue
        if m.group() == ";":
            name = variable_or_alias(head) if at_file_scope else None
            if name:
                names.add(name)
            continue
        transparent = bool(TRANSPARENT_BLOCK.search(head))
        open_blocks.append(transparent)
        if not at_file_scope or transparent:
            continue
        function = FUNCTION_HEAD.search(head)
        if function and not CONTROL_HEAD.search(head) and not INIT_LIST_HEAD.search(head):
            name = function_name(head, function) or variable_or_alias(head)  # a lambda with parameters
        elif TYPE_HEAD.search(head):
            name = TYPE_HEAD.search(head).group(1)
        else:
            name = variable_or_alias(head)  # a braced or lambda initialiser
        if name:
            names.add(name)
    return names


def names_in_two_files():
    """(folder, name, files) for each file-scope name defined in two files of a folder compiled together."""
    found = []
    for folder in COMPILED_TOGETHER:
        files_of = {}
        for path in sorted((ROOT / folder).glob("*.cpp")):
            for name in file_scope_names(path.read_text()):
                files_of.setdefault(name, []).append(path.name)
        found += [(folder, name, files) for name, files in sorted(files_of.items()) if len(files) > 1]
    return found


def rank_of(header):
    folder = header.split("/")[0] if "/" in header else header.removesuffix(".hpp")
    return RANKS.index(folder) if folder in RANKS else None


def include_loops(graph):
    """Each set of headers that include one another round a loop (strongly connected, Tarjan)."""
    index, low, on_stack, stack, loops = {}, {}, set(), [], []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, []):
            if w not in graph:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                loops.append(sorted(component))

    for v in graph:
        if v not in index:
            visit(v)
    return loops


def main():
    problems = []
    for rel, path in hand_written():
        text = path.read_text()
        lines = text.count("\n")
        if lines > MOST_LINES and rel not in LONG_FILES:
            problems.append(f"{rel}: {lines} lines (at most {MOST_LINES})")
        for length, first in long_functions(text):
            problems.append(f"{rel}:{first}: a function of {length} lines (at most {MOST_FUNCTION_LINES})")
    library = ROOT / "include" / "hairshadow"
    graph = {}
    for path in sorted(library.rglob("*.hpp")):
        header = path.relative_to(library).as_posix()
        graph[header] = re.findall(r"^#include <hairshadow/([^>]+)>", path.read_text(), re.M)
    for header, targets in graph.items():
        if header in UMBRELLAS:
            continue
        for target in targets:
            mine, theirs = rank_of(header), rank_of(target)
            if mine is None:
                problems.append(f"include/hairshadow/{header}: its folder is not in check_layout.py's RANKS")
            elif theirs is not None and theirs > mine:
                problems.append(f"include/hairshadow/{header}: includes {target}, a folder above its own ({RANKS[theirs]} > {RANKS[mine]})")
    for path in sorted((ROOT / "examples").glob("*.cpp")):
        for target in re.findall(r"^#include <hairshadow/([^>]+)>", path.read_text(), re.M):
            if "/detail/" in target:
                problems.append(f"examples/{path.name}: includes {target}: a user's program needs no internal header")
    for loop in include_loops(graph):
        if frozenset(loop) not in INCLUDE_LOOPS:
            problems.append("include loop: " + " -> ".join(loop + [loop[0]]))
    for folder, name, files in names_in_two_files():
        problems.append(f"{folder}: `{name}` defined at file scope in {', '.join(files)}: files compiled together must not share one")
    for p in problems:
        print("layout:", p)
    print(f"layout: {'fails' if problems else 'holds'} ({len(problems)} problem(s))")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
