#!/usr/bin/env python3
"""Reports functions longer than --max-function lines and source files longer than --max-file
lines in the project's own C++ (app, base, engine, media, render, assets/tools). Exit 1 when any
is found.

Functions are found by brace matching on the source with comments, strings and character
literals blanked out: a '{' opens a function body when it is not inside another function and
the text before it (back to the last ';', '{' or '}') ends a parameter list, optionally
followed by qualifiers, a trailing return type or a constructor's initializer list. A function's
length counts its lines from the signature's first line to its closing brace, as a reader sees
it. Lambdas and local classes count towards the function that holds them.
"""
import argparse
import pathlib
import re
import sys

ROOTS = ["app", "base", "engine", "media", "render", "assets/tools"]
SUFFIXES = {".cpp", ".hpp", ".h", ".cc"}
SCOPE_WORDS = re.compile(r"\b(namespace|class|struct|union|enum)\b[^()]*$|\bextern\s+\"C\"\s*$")
CONTROL = re.compile(r"^\s*(if|for|while|switch|catch|do|else|try)\b")


def blank(text: str) -> str:
    """Comments, string and character literals replaced by spaces (newlines kept)."""
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
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i)
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            # a digit separator (1'000'000) is not a character literal
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum():
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def opens_function(before: str) -> bool:
    text = before.strip()
    if not text or CONTROL.match(text) or SCOPE_WORDS.search(text):
        return False
    if "=" in text.split("(")[0] and not text.lstrip().startswith("operator"):
        # `auto x = [..](..) {` or `int a[] = {`: a lambda or an initializer, not a function
        if "operator" not in text:
            return False
    # strip a constructor's initializer list: `X::X(...) : a_(1), b_{2}`
    depth = 0
    for k, ch in enumerate(text):
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
        elif ch == ":" and depth == 0 and text[k - 1:k + 1] != "::" and text[k:k + 2] != "::":
            text = text[:k]
            break
    text = re.sub(r"->\s*[\w:<>,\s*&]+$", "", text)
    text = re.sub(r"\b(const|noexcept|override|final|mutable|volatile|&|&&)\s*$", "", text).strip()
    text = re.sub(r"\b(const|noexcept|override|final)\b", "", text).strip()
    return text.endswith(")")


def functions(path: pathlib.Path):
    source = path.read_text(encoding="utf-8", errors="replace")
    text = blank(source)
    line_of = [0] * (len(text) + 1)
    line = 1
    for k, ch in enumerate(text):
        line_of[k] = line
        if ch == "\n":
            line += 1
    stack = []  # per open brace: True when it opened a function body
    last_break = 0
    in_function = 0
    start_line = 0
    name = ""
    for k, ch in enumerate(text):
        if ch in ";{}":
            before = text[last_break:k]
            if ch == "{":
                is_function = in_function == 0 and opens_function(before)
                if is_function:
                    first = last_break + (len(before) - len(before.lstrip()))
                    start_line = line_of[first]
                    m = re.search(r"([\w:~<>]+|operator\S*)\s*\([^()]*", before)
                    name = m.group(1) if m else "?"
                stack.append(is_function)
                if is_function or in_function:
                    in_function += 1
            elif ch == "}":
                if stack:
                    stack.pop()
                if in_function:
                    in_function -= 1
                    if in_function == 0:
                        yield name, start_line, line_of[k] - start_line + 1
            last_break = k + 1


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-function", type=int, default=80)
    parser.add_argument("--max-file", type=int, default=800)
    parser.add_argument("paths", nargs="*", help="files or folders (default: the project's own)")
    args = parser.parse_args()
    top = pathlib.Path(__file__).resolve().parent.parent
    roots = [pathlib.Path(p) for p in args.paths] or [top / r for r in ROOTS]
    files = []
    for root in roots:
        files += [root] if root.is_file() else sorted(
            p for p in root.rglob("*") if p.suffix in SUFFIXES)
    problems = 0
    for path in files:
        shown = path.relative_to(top) if path.is_absolute() and top in path.parents else path
        lines = path.read_text(encoding="utf-8", errors="replace").count("\n")
        if lines > args.max_file:
            print(f"{shown}: {lines} lines (at most {args.max_file})")
            problems += 1
        for name, first, length in functions(path):
            if length > args.max_function:
                print(f"{shown}:{first}: {name}: {length} lines (at most {args.max_function})")
                problems += 1
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
