#!/usr/bin/python3
"""Checks the size of PolyFloe's source: files and functions short enough to read.

    /usr/bin/python3 tests/docs/check_code_size.py [--list [N]]

Rules, for every C++ file of dem/ and coupling/ (tests are not held to them):
- a file has at most 500 lines;
- a function body has at most 80 lines (the lines between its braces), unless the function is named in
  docs/architecture.md's table "Functions past 80 lines" (the geometric kernels, kept whole where cutting them would
  hide the algorithm), with its file. A listed function that no longer exceeds 80 lines, or no longer exists, is an
  error too, so that the table stays true.

Functions are found by scanning the braces of each file with its comments, strings and character literals blanked
out: at namespace or class scope, a brace that follows a parameter list (a `(` since the last `;` or brace, and no
`namespace`, `class`, `struct`, `union`, `enum` or `extern` heading it) opens a function body; lambdas and local
classes count toward the function that holds them. The tree is formatted by .clang-format, which this relies on
only for line numbers. `--list` prints the N longest functions (default 20). Exit 1 naming each file or function.
"""
import argparse
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MAX_FILE_LINES = 500
MAX_FUNCTION_LINES = 80
SOURCE_DIRS = ("dem", "coupling")
DOC = os.path.join("docs", "architecture.md")
TABLE_HEADING = "### Functions past 80 lines"


def blank_comments_and_strings(text):
    """`text` with comments, string and character literals replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i)
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # a digit separator: 1'000'000
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


SCOPE_WORDS = re.compile(r"^\s*(template\s*<.*>\s*)?(inline\s+)?(namespace|class|struct|union|enum|extern)\b", re.S)


def function_name(head):
    """The (qualified) name before the first top-level `(` of a declaration, or '?'."""
    depth = 0
    for k, ch in enumerate(head):
        if ch in "<[":
            depth += 1
        elif ch in ">]":
            depth = max(depth - 1, 0)
        elif ch == "(" and depth == 0:
            m = re.search(r"((?:[A-Za-z_]\w*\s*(?:<[^()]*>)?\s*::\s*)*~?[A-Za-z_]\w*|operator\s*\S+)\s*$", head[:k])
            return re.sub(r"\s+", "", m.group(1)) if m else "?"
    return "?"


def member_initializer(head):
    """Whether a brace after `head` initializes a member in a constructor's initializer list (`S() : v_{1}`)."""
    depth, close = 0, -1
    for k, ch in enumerate(head):
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
            if depth == 0:
                close = k
                break
    tail = head[close + 1 :] if close >= 0 else ""
    return bool(re.search(r"(?<!:):(?!:)", tail)) and bool(re.search(r"[\w>]\s*$", tail))


def functions(text):
    """[(name, first line of the body, body lines)] of the functions defined in a file's text."""
    code = blank_comments_and_strings(text)
    # Preprocessor lines (with their continuations) blanked too: `#if defined(X)` is no declaration.
    code = re.sub(r"^[ \t]*#(?:[^\n]*\\\n)*[^\n]*", lambda m: re.sub(r"[^\n]", " ", m.group(0)), code, flags=re.M)
    found = []
    # Stack of open braces: ("scope" | "function" | "other", line, name). Inside a function nothing is classified.
    stack = []
    head_start = 0  # where the current declaration's text starts (after the last ; { or } at this level)
    line = 1
    for k, ch in enumerate(code):
        if ch == "\n":
            line += 1
            continue
        in_function = any(kind == "function" for kind, _, _ in stack)
        if ch == ";" and not in_function and not (stack and stack[-1][0] == "other"):
            head_start = k + 1
        elif ch == "{":
            if in_function or (stack and stack[-1][0] == "other"):
                stack.append(("other", line, None))
                continue
            head = code[head_start:k]
            if SCOPE_WORDS.match(head) or re.search(r"\b(class|struct|union|enum)\s+\w*[^()]*$", head):
                m = re.search(r"\b(?:class|struct|union)\s+(?:alignas\s*\(\s*\w+\s*\)\s*)?(\w+(?:\s*::\s*\w+)*)", head)
                stack.append(("scope", line, re.sub(r"\s+", "", m.group(1)) if m else None))
                head_start = k + 1
            elif "(" in head and not re.match(r"^[^(]*=", head) and not member_initializer(head):
                classes = [name for kind, _, name in stack if kind == "scope" and name]
                stack.append(("function", line, "::".join(classes + [function_name(head)])))
            else:
                stack.append(("other", line, None))  # an initializer: the declaration goes on after it
        elif ch == "}":
            if not stack:
                continue
            kind, first, name = stack.pop()
            if kind == "function":
                found.append((name, first, max(line - first - 1, 0)))
                head_start = k + 1
            elif kind == "scope":
                head_start = k + 1
    return found


SELF_TEST = r"""
namespace a::b {
#if defined(X)
#endif
const int kTable[] = {1, 2, 3};
struct S : Base<int> {
  int v_{0};
  int get() const { return v_; }
  S(int v) : v_{v}, w_(v) {
    auto f = [&](int x) { return x + '}'; };
    const char* s = R"(})";
  }
};
struct alignas(64) T {
  void f();
};
void T::f() {
  // }
  if (1) {
  }
}
}  // namespace a::b
"""


def self_test():
    """The scan on a snippet with the constructs that could mislead it (raises AssertionError)."""
    got = [(name, first, body) for name, first, body in functions(SELF_TEST)]
    want = [("S::get", 8, 0), ("S::S", 9, 2), ("T::f", 17, 3)]
    assert got == want, f"check_code_size's scan is broken: found {got}, expected {want}"


def sources():
    for top in SOURCE_DIRS:
        for dirpath, _, files in os.walk(os.path.join(ROOT, top)):
            for f in sorted(files):
                if f.endswith((".h", ".cpp", ".hpp", ".cc")):
                    yield os.path.relpath(os.path.join(dirpath, f), ROOT)


def allowed_long_functions():
    """{(file, function)} from the architecture document's table of functions past 80 lines."""
    path = os.path.join(ROOT, DOC)
    text = open(path, encoding="utf-8").read()
    at = text.find(TABLE_HEADING)
    if at < 0:
        sys.exit(f"check_code_size: {DOC} has no section '{TABLE_HEADING}'")
    allowed = set()
    for row in text[at:].splitlines()[1:]:
        if row.startswith("#"):
            break
        cells = [c.strip().strip("`") for c in row.strip().strip("|").split("|")]
        if len(cells) >= 2 and cells[0].startswith(("dem/", "coupling/")):
            allowed.add((cells[0], cells[1]))
    return allowed


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--list", nargs="?", const=20, type=int, help="print the N longest functions")
    args = parser.parse_args()

    self_test()
    allowed = allowed_long_functions()
    errors, every, seen_allowed = [], [], set()
    for rel in sources():
        text = open(os.path.join(ROOT, rel), encoding="utf-8").read()
        lines = text.count("\n") + (0 if text.endswith("\n") else 1)
        if lines > MAX_FILE_LINES:
            errors.append(f"{rel}: {lines} lines (at most {MAX_FILE_LINES}): split it")
        for name, first, body in functions(text):
            every.append((body, rel, first, name))
            if body <= MAX_FUNCTION_LINES:
                continue
            if (rel, name) in allowed:
                seen_allowed.add((rel, name))
            else:
                errors.append(f"{rel}:{first}: function {name} has {body} lines (at most {MAX_FUNCTION_LINES}, "
                              f"unless it is a geometric kernel listed in {DOC}, '{TABLE_HEADING}')")
    for rel, name in sorted(allowed - seen_allowed):
        errors.append(f"{DOC}: '{TABLE_HEADING}' lists {rel} {name}, which is not a function past "
                      f"{MAX_FUNCTION_LINES} lines there: take it off the table")
    if args.list:
        for body, rel, first, name in sorted(every, reverse=True)[: args.list]:
            print(f"{body:5d}  {rel}:{first}  {name}")
    if not every:
        errors.append("found no function at all (has the scan broken?)")
    for e in errors:
        print(e, file=sys.stderr)
    if errors:
        print(f"check_code_size: {len(errors)} problem(s)", file=sys.stderr)
        return 1
    print(f"check_code_size: {len(every)} functions in {len(set(r for _, r, _, _ in every))} files, "
          f"none past {MAX_FUNCTION_LINES} lines but the {len(seen_allowed)} listed in {DOC}; no file past "
          f"{MAX_FILE_LINES} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
