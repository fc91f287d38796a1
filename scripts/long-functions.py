#!/usr/bin/env python3
"""Lists functions longer than a limit (default 80 lines) in C++ sources.

A function is a body that opens with '{' at the end of a line whose brace depth is that of a
namespace (or a class, for inline member functions) and closes at the matching '}'. Lambdas and
nested blocks count towards the function that holds them.
  scripts/long-functions.py [--limit N] DIR...     exit 1 when any function is longer
"""
import re
import sys
from pathlib import Path

CONTROL = re.compile(r'^\s*(if|for|while|switch|else|do|try|catch)\b')
SCOPE = re.compile(r'^\s*(namespace|class|struct|enum|union|extern)\b|=\s*\{?$')


def strip(line):
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])*'", "''", line)
    return line.split('//')[0]


def functions(path):
    lines = path.read_text(errors='replace').split('\n')
    depth, scopes, start, found = 0, [], None, []
    header = ''
    for number, raw in enumerate(lines, 1):
        line = strip(raw)
        for ch in line:
            if ch == '{':
                stmt = header.strip()
                is_scope = bool(SCOPE.search(stmt)) or stmt.endswith('=')
                if start is None and not is_scope and not CONTROL.match(stmt) and ')' in stmt:
                    start = (number, depth, stmt)
                scopes.append(is_scope)
                depth += 1
                header = ''
            elif ch == '}':
                depth -= 1
                if scopes:
                    scopes.pop()
                if start is not None and depth == start[1]:
                    found.append((start[0], number, start[2]))
                    start = None
                header = ''
            elif ch == ';':
                header = ''
            else:
                header += ch
        header += ' '
    return found


def main(argv):
    limit = 80
    if len(argv) > 1 and argv[0] == '--limit':
        limit, argv = int(argv[1]), argv[2:]
    long = []
    for root in argv:
        for path in sorted(Path(root).rglob('*')):
            if path.suffix in ('.cpp', '.hpp', '.h', '.cc'):
                for first, last, stmt in functions(path):
                    if last - first + 1 > limit:
                        long.append((last - first + 1, f'{path}:{first}', stmt[:70]))
    for length, where, stmt in sorted(long, reverse=True):
        print(f'{length:5d}  {where}  {stmt}')
    return 1 if long else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
