#!/usr/bin/env python3
"""List the C++ functions longer than a limit (80 lines unless --limit says otherwise), from the line their
signature starts on (a template's `template <...>` line included) to the line of their closing brace.

The code base's rule: no function over ~80 lines outside ImGui view code. Functions named draw_* in ui/gui/ and
app/studio/ are view code and are listed with "(view)"; the exit status is 1 when any other function is listed.

A brace matcher over the source with comments, string and character literals and preprocessor lines blanked
out, not a C++ parser: it finds free functions, member functions defined in or out of their class and
constructors (their initialiser lists included); lambdas and local classes count as part of the function that
holds them. Usage: tests/tools/long_functions.py [--limit N] [PATH ...] (default: core app ui)."""
import argparse
import os
import re
import sys


def blank_non_code(text):
    """Comments, string/char literals (raw strings too) and preprocessor lines become spaces; newlines stay."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == '#':
            # a preprocessor line, with its backslash continuations
            while i < n and text[i] != '\n':
                if text[i] == '\\' and i + 1 < n and text[i + 1] == '\n':
                    out.append(' \n')
                    i += 2
                    continue
                out.append(' ')
                i += 1
            continue
        if c == '\n':
            out.append(c)
            i += 1
            at_line_start = True
            continue
        if c in ' \t':
            out.append(c)
            i += 1
            continue
        at_line_start = False
        if text.startswith('//', i):
            while i < n and text[i] != '\n':
                out.append(' ')
                i += 1
            continue
        if text.startswith('/*', i):
            end = text.find('*/', i + 2)
            end = n if end < 0 else end + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:end]))
            i = end
            continue
        m = re.match(r'(?:u8|u|U|L)?R"([^(\s]{0,16})\(', text[i:i + 40])
        if m and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == '_')):
            close = ')' + m.group(1) + '"'
            end = text.find(close, i + m.end())
            end = n if end < 0 else end + len(close)
            out.append(re.sub(r'[^\n]', ' ', text[i:end]))
            i = end
            continue
        if c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):  # 1'000 is a digit separator
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            end = min(j + 1, n)
            out.append(c + re.sub(r'[^\n]', ' ', text[i + 1:end - 1]) + c if end - i >= 2 else c)
            i = end
            continue
        out.append(c)
        i += 1
    return ''.join(out)


def strip_template_heads(h):
    """The text after any leading `template <...>` parameter lists (nested angle brackets matched)."""
    while True:
        m = re.match(r'\s*template\s*<', h)
        if not m:
            return h
        depth, k = 1, m.end()
        while k < len(h) and depth:
            depth += {'<': 1, '>': -1}.get(h[k], 0)
            k += 1
        h = h[k:]


def header_kind(header):
    """What a '{' at namespace or class scope opens, judged by the text before it."""
    h = ' '.join(header.split())
    h = re.sub(r'\boperator\s*(\(\)|\[\]|[^\s(]+)', 'operator', h)  # operator==, operator= and operator() are names
    h = strip_template_heads(h)  # `template <class T = int>`: its '=' is no initialiser
    if re.match(r'^(inline\s+)?namespace\b', h) or re.match(r'^extern\s+"', h):
        return 'namespace'
    if re.search(r'\benum\b', h):
        return 'other'
    if re.search(r'(^|\s|>)(class|struct|union)\s', h) and not h.endswith(')') and '(' not in h.split(':')[0]:
        return 'class'
    # a function: a parameter list, then qualifiers, a trailing return type or a constructor's initialiser list
    if '(' in h and ')' in h and not re.search(r'(^|[^=!<>])=\s*$', h):
        if re.search(r'=\s*\[', h) or re.match(r'^[^(]*=', h):
            return 'other'  # a variable initialised with a lambda or a braced list
        return 'function'
    return 'other'


def functions(path):
    text = open(path, encoding='utf-8', errors='replace').read()
    code = blank_non_code(text)
    line_of = [0] * (len(code) + 1)
    line = 1
    for k, ch in enumerate(code):
        line_of[k] = line
        if ch == '\n':
            line += 1
    line_of[len(code)] = line
    stack = []  # (kind, start offset of its header, name)
    header_start = 0
    found = []
    for k, ch in enumerate(code):
        scope = stack[-1][0] if stack else 'namespace'
        if ch in '{}' and scope not in ('namespace', 'class'):
            # inside a function, an initialiser or a member's brace initialiser: only depth matters
            if ch == '{':
                stack.append(('init' if scope == 'init' else 'inner', k, ''))
            else:
                kind, start, name = stack.pop()
                if kind == 'function':
                    found.append((name, line_of[start], line_of[k]))
                if kind != 'init':  # a constructor's header goes on after a member's brace initialiser
                    header_start = k + 1
            continue
        if scope not in ('namespace', 'class'):
            continue  # a ';' inside a lambda of an initialiser list does not end the constructor's header
        if ch == ';':
            header_start = k + 1
        elif ch == '{':
            header = code[header_start:k]
            if header.count('(') > header.count(')'):
                stack.append(('init', k, ''))  # a braced default argument inside a parameter list
                continue
            kind = header_kind(header)
            # A brace in a constructor's initialiser list (after a name, or inside an argument list) initialises
            # a member or an argument; the body's brace follows a closed list.
            if kind == 'function' and re.search(r'\)\s*:', ' '.join(header.split())) and \
                    ((code[k - 1].isalnum() or code[k - 1] in '_>') or header.count('(') > header.count(')')):
                kind = 'inner-init'
            if kind == 'inner-init':
                stack.append(('init', k, ''))
                continue
            stripped = re.sub(r'^(\s*(public|private|protected)\s*:(?!:))+', '', header).lstrip()
            start = header_start + (len(header) - len(stripped))
            name = ''
            if kind == 'function':
                m = re.search(r'([\w:]*\boperator\s*(?:\(\)|\[\]|[^\s(]+)|[~\w:]+)\s*\(', ' '.join(header.split()))
                name = m.group(1) if m else '?'
            stack.append((kind if kind != 'other' else 'inner', start, name))
            header_start = k + 1
        elif ch == '}':
            if stack:
                kind, start, name = stack.pop()
                if kind == 'init':
                    continue
            header_start = k + 1
    return found


def is_view_code(path, name):
    """ImGui view code, which may stay long: the draw_* functions of the views and of the studio's window."""
    folder = path.replace(os.sep, '/')
    return ('ui/gui/' in folder or 'app/studio/' in folder) and name.split('::')[-1].startswith('draw_')


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('paths', nargs='*', help='files or folders (default: core, app and ui of this checkout)')
    parser.add_argument('--limit', type=int, default=80, help='longest allowed function, in lines (default 80)')
    args = parser.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    paths = args.paths or [os.path.join(root, d) for d in ('core', 'app', 'ui')]
    rows = []
    for top in paths:
        if not os.path.exists(top):
            parser.error(f'{top}: no such file or folder')
        walk = [(os.path.dirname(top), [], [os.path.basename(top)])] if os.path.isfile(top) else os.walk(top)
        for folder, _, files in walk:
            for f in files:
                if f.endswith(('.cpp', '.h', '.hpp', '.cc')):
                    p = os.path.join(folder, f)
                    shown = os.path.relpath(p, root) if not args.paths else p
                    for name, first, last in functions(p):
                        length = last - first + 1
                        if length > args.limit:
                            rows.append((length, shown, first, name))
    outside_views = 0
    for length, p, first, name in sorted(rows, key=lambda r: (r[1], r[2])):
        view = is_view_code(p, name)
        outside_views += not view
        print(f'{length:5d}  {p}:{first}  {name}{"  (view)" if view else ""}')
    return 1 if outside_views else 0


if __name__ == '__main__':
    sys.exit(main())
