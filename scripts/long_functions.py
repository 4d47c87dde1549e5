#!/usr/bin/env python3
"""Lists the C++ functions longer than a bound, for the "functions short" rule of the project.

    scripts/long_functions.py [--max 60] [DIR ...]        (default: app model analysis lab base)

A function is counted from the line of its name to the line of its closing brace. The count is textual
(comments, strings and character literals are blanked first, braces are matched); namespace, class, struct
and extern "C" bodies are looked into, any other brace at file level closes a function (or an initialiser,
which is skipped when it has no parenthesised head). A lambda is part of the function that holds it.
Prints "LINES path:line name" for each function over --max, longest first, and a count; exit 0.
"""
import argparse
import os
import re
import sys

SCOPES = re.compile(r'\b(namespace|class|struct|union|enum)\b|extern\s+"C"')
CONTROL = re.compile(r'^\s*(if|for|while|switch|catch|do|else|try)\b')


def blank(text):
    """The text with comments, strings and char literals replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i)); i = j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j])); i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                out.append(c); i += 1; continue
            end = ')' + m.group(1) + '"'
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append(re.sub(r'[^\n]', ' ', text[i:j])); i = j
        elif c in '"\'':
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            j = min(j + 1, n)
            out.append(' ' * (j - i)); i = j
        else:
            out.append(c); i += 1
    return ''.join(out)


def functions(path):
    """(first line, last line, name) of each function body in the file."""
    text = blank(open(path, encoding='utf-8', errors='replace').read())
    found = []
    stack = []          # one entry per open brace: 'scope', 'init', 'inner' or (body, line, name)
    head_start = 0      # offset where the text before the next brace at this level starts
    i = 0
    while i < len(text):
        c = text[i]
        if c == '{':
            head = text[head_start:i]
            before_paren = re.sub(r'operator\s*\S+', 'operator', head.split('(')[0])
            if any(isinstance(s, tuple) for s in stack):
                stack.append('inner')
            elif SCOPES.search(head) and '(' not in head:
                stack.append('scope')
            elif ')' in head and not CONTROL.match(head) and '=' not in before_paren:
                name = re.findall(r'([~\w:<>]+)\s*\(', head)
                line = text.count('\n', 0, head_start + len(head) - len(head.lstrip())) + 1
                stack.append(('body', line, name[0] if name else '?'))
            else:
                stack.append('init')
            head_start = i + 1
        elif c == '}':
            top = stack.pop() if stack else 'scope'
            if isinstance(top, tuple):
                found.append((top[1], text.count('\n', 0, i) + 1, top[2]))
            head_start = i + 1
        elif c == ';' and not any(isinstance(s, tuple) for s in stack):
            head_start = i + 1
        i += 1
    return found


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--max', type=int, default=60)
    ap.add_argument('dirs', nargs='*', default=['app', 'model', 'analysis', 'lab', 'base'])
    args = ap.parse_args()
    rows = []
    for d in args.dirs:
        for root, _, files in os.walk(d):
            for f in files:
                if f.endswith(('.cpp', '.h')):
                    p = os.path.join(root, f)
                    for a, b, name in functions(p):
                        if b - a + 1 > args.max:
                            rows.append((b - a + 1, f'{p}:{a}', name))
    for n, where, name in sorted(rows, key=lambda r: (-r[0], r[1])):
        print(f'{n:5d} {where} {name}')
    print(f'{len(rows)} functions over {args.max} lines in {" ".join(args.dirs)}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
