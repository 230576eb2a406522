#!/usr/bin/env python3
"""The house's rules, checked on the sources (docs/design.md "Folder layout"):

  1. each folder includes only the folders before it in the data flow (and include/),
     a subfolder of engine/ or scheduler/ only those before it there (tuning/ and vps/
     neither way); the report stage (report/) only the public API and its own files, and
     the tool (cli/) and the Python module only the public API, their own files and
     report/ (the build gives those targets include/ alone: this says why it fails);
  2. no function is longer than 120 lines (from its signature to its closing brace).

Usage: house_rules.py SOURCE_DIR    (prints each breach; exit status 1 if any)
       house_rules.py --self-test     (the checks on made-up sources)
"""
import os
import re
import sys

MAX_FUNCTION_LINES = 120

# Folders in data-flow order; a folder may include itself and those before it.
LAYERS = ["include", "core", "mesh", "io", "kernels", "engine", "pipeline", "scheduler", "jobs"]
# Within a folder, subfolders in order; a pair listed in APART includes neither way.
SUBLAYERS = {
    "engine": ["runtime", "fields", "spectra", "query", "maps"],
    "scheduler": ["modes", "haptics", "tuning", "vps"],
}
APART = {("scheduler", "tuning", "vps")}
# Clients of the public API: what they may include besides include/snapfit.
CLIENTS = {"report": {"report"}, "cli": {"cli", "report"}, "python": {"python", "report"}}
CHECKED = LAYERS[1:] + list(CLIENTS) + ["perf", "fuzz"]
SOURCE = re.compile(r"\.(cpp|h|hpp|cc)$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def sources(root):
    for top in CHECKED:
        for folder, _, files in os.walk(os.path.join(root, top)):
            if "node_modules" in folder:
                continue
            for name in sorted(files):
                if SOURCE.search(name):
                    path = os.path.join(folder, name)
                    yield os.path.relpath(path, root).replace(os.sep, "/")


def place(path):
    """(folder, subfolder or None) of a repository path."""
    parts = path.split("/")
    sub = parts[1] if len(parts) > 2 and parts[0] in SUBLAYERS else None
    return parts[0], sub


def include_breach(src, target):
    """Why `src` may not include `target`, or None."""
    if target.startswith("snapfit/"):
        return None
    folder, sub = place(src)
    to_folder, to_sub = place(target)
    if to_folder not in LAYERS and to_folder not in CLIENTS:
        return None  # not a folder of the house (a third-party or generated header)
    if folder in CLIENTS:
        return None if to_folder in CLIENTS[folder] else f"{folder}/ includes only the public API and {sorted(CLIENTS[folder])}"
    if folder not in LAYERS:
        return None  # perf/, fuzz/: on top of everything
    if to_folder in CLIENTS and to_folder != folder:
        return f"{to_folder}/ is a client, above every stage"
    if LAYERS.index(to_folder) > LAYERS.index(folder):
        return f"{to_folder}/ comes after {folder}/ in the data flow"
    if to_folder == folder and sub and to_sub and sub != to_sub:
        order = SUBLAYERS[folder]
        if (folder, sub, to_sub) in APART or (folder, to_sub, sub) in APART:
            return f"{folder}/{sub}/ and {folder}/{to_sub}/ include neither way"
        if to_sub in order and sub in order and order.index(to_sub) > order.index(sub):
            return f"{folder}/{to_sub}/ comes after {folder}/{sub}/"
    return None


def strip(text):
    """The text with comments, strings and character literals blanked (lines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            k = text.find("(", i)
            delim = ")" + text[i + 2:k] + '"'
            j = text.find(delim, k)
            j = n if j < 0 else j + len(delim)
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # a digit separator (1'000)
                out.append(c)
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        elif c == "#" and (i == 0 or text[i - 1] == "\n"):  # a preprocessor line (with continuations)
            j = i
            while True:
                j = text.find("\n", j)
                if j < 0 or text[j - 1] != "\\":
                    break
                j += 1
            j = n if j < 0 else j
            out.append("\n" * text.count("\n", i, j))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


KEYWORD_BLOCK = re.compile(r"^(template\s*<.*>\s*)?(class|struct|union|namespace|enum|extern)\b", re.S)
CONTROL = re.compile(r"\b(if|for|while|switch|catch|do|else|try)\s*$")


def long_functions(text):
    """(line, length, head) of each function body longer than MAX_FUNCTION_LINES."""
    code = strip(text)
    found = []
    stack = []  # kinds of the open braces: "scope" (namespace, class), "function", "other"
    head_start = 0
    line = 1
    starts = []  # (line of the head's first code, index in stack) of open functions
    for i, c in enumerate(code):
        if c == "\n":
            line += 1
        if c in ";{}":
            head = code[head_start:i]
            if c == "{":
                inside_function = any(k == "function" for k in stack)
                h = " ".join(head.split())
                kind = "other"
                if not inside_function and (not stack or stack[-1] == "scope"):
                    if KEYWORD_BLOCK.match(h):
                        kind = "scope" if not h.split()[0].startswith("enum") and "enum" not in h.split()[:3] else "other"
                    elif ")" in h and "=" not in re.sub(r"\(.*\)|operator\s*\S+|<[^<>]*>", "", h) and not CONTROL.search(h):
                        kind = "function"
                stack.append(kind)
                if kind == "function":
                    first = code.count("\n", 0, head_start + len(head) - len(head.lstrip())) + 1
                    starts.append((first, len(stack) - 1, h))
            elif c == "}" and stack:
                kind = stack.pop()
                if kind == "function" and starts and starts[-1][1] == len(stack):
                    first, _, h = starts.pop()
                    if line - first + 1 > MAX_FUNCTION_LINES:
                        found.append((first, line - first + 1, h[:100]))
            head_start = i + 1
    return found


def self_test():
    """The checks find what they should on made-up sources, and nothing else."""
    def function(name, body_lines):
        return f"int {name}(int a,\n        int b) {{\n" + "  a += b;\n" * (body_lines - 3) + "}\n"
    # A function of 121 lines from its signature to its brace is too long, one of 120 is not.
    source = "namespace x {\n" + function("ok", 120) + function("too_long", 121) + "}\n"
    found = long_functions(source)
    assert [(f[0], f[1]) for f in found] == [(122, 121)], found
    # Lambdas, classes, initializers and braces in strings or comments are not functions
    # of their own; a method in a class is.
    source = ("struct S {\n  void m() {\n" + "    x();\n" * 130 + "  }\n};\n"
              "const int table[] = {1, 2};\n// } {\nconst char* t = \"}\";\n"
              "int f() {\n  auto g = [] {\n" + "    y();\n" * 100 + "  };\n  return 0;\n}\n")
    found = long_functions(source)
    assert [f[2].split("(")[0] for f in found] == ["void m"], found
    # Includes: a later stage, a client and a subfolder out of order are refused.
    assert include_breach("engine/query/a.cpp", "pipeline/b.h")
    assert include_breach("engine/fields/a.cpp", "engine/query/b.h")
    assert include_breach("scheduler/tuning/a.cpp", "scheduler/vps/b.h")
    assert include_breach("jobs/a.cpp", "cli/commands.h")
    assert include_breach("cli/a.cpp", "jobs/job_record.h")
    assert include_breach("report/a.cpp", "jobs/job_record.h")
    assert include_breach("report/a.cpp", "cli/commands.h")
    assert include_breach("jobs/a.cpp", "report/run_report.h")
    assert not include_breach("engine/query/a.cpp", "engine/spectra/b.h")
    assert not include_breach("scheduler/tuning/a.cpp", "scheduler/haptics/b.h")
    assert not include_breach("cli/a.cpp", "report/run_report.h")
    assert not include_breach("report/a.cpp", "report/b.h")
    assert not include_breach("io/a.cpp", "snapfit/scene.h")
    print("house rules: self-test passed")
    return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = sys.argv[1] if len(sys.argv) > 1 else "."
    breaches = []
    for path in sources(root):
        with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
            text = f.read()
        for target in INCLUDE.findall(text):
            why = include_breach(path, target)
            if why:
                breaches.append(f"{path}: includes {target}: {why}")
        for first, length, head in long_functions(text):
            breaches.append(f"{path}:{first}: a function of {length} lines (at most {MAX_FUNCTION_LINES}): {head}")
    for b in breaches:
        print(b)
    print(f"house rules: {len(breaches)} breach(es)")
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main())
