#!/usr/bin/env python3
"""libsss.so exports exactly what the public headers declare (docs/versioning.md, "The exported surface").

Usage: check_exports.py [--cc CC] [--nm NM] LIBSSS_SO INCLUDE_DIR...

The declared set: every function and extern datum declared at file scope by a header INCLUDE_DIR/sss/*.h,
read from the C preprocessor's output (comments, #if blocks and macros resolved as a C compiler sees
them; the line markers tell which header a declaration comes from). The exported set: `nm -D
--defined-only LIBSSS_SO`. Both directions must hold: a symbol exported but not declared is an internal
helper that leaked (a program could bind to it and break when it changes); a declaration not exported
lacks SSS_API (a program using it would not link). Every name must be in the sss_ namespace.
Exit status 1 with the differences listed, else 0.
"""
import argparse
import glob
import os
import re
import subprocess
import sys
import tempfile

ATTRIBUTE = re.compile(r'__attribute__\s*\(\(')
IDENT_CALL = re.compile(r'(\(\s*\*\s*)?\b([A-Za-z_]\w*)\s*\(')
IDENT = re.compile(r'\b([A-Za-z_]\w*)\b')


def strip_attributes(text):
    """Removes __attribute__((...)) groups (balanced parentheses), which look like calls."""
    while True:
        m = ATTRIBUTE.search(text)
        if not m:
            return text
        depth, i = 2, m.end()
        while depth and i < len(text):
            depth += {'(': 1, ')': -1}.get(text[i], 0)
            i += 1
        text = text[:m.start()] + ' ' + text[i:]


def preprocess(cc, include_dirs, headers):
    with tempfile.NamedTemporaryFile('w', suffix='.c', delete=False) as f:
        for h in headers:
            f.write('#include "sss/%s"\n' % os.path.basename(h))
        tu = f.name
    try:
        cmd = [cc, '-E', '-std=c11'] + ['-I' + d for d in include_dirs] + [tu]
        out = subprocess.run(cmd, check=True, capture_output=True, text=True)
    except subprocess.CalledProcessError as e:
        sys.exit('FAIL: the public headers do not preprocess (%s):\n%s' % (' '.join(cmd), e.stderr))
    finally:
        os.unlink(tu)
    return out.stdout


def statements(cpp_output, public):
    """Yields (file, text) for each file-scope statement of the files in `public`: declarations end at
    ';', function definitions at their closing brace (bodies and struct/enum bodies are left out)."""
    current, depth, text = None, 0, []
    for line in cpp_output.splitlines():
        marker = re.match(r'#\s*\d+\s+"([^"]*)"', line)
        if marker:
            current = os.path.realpath(marker.group(1)) if not marker.group(1).startswith('<') else None
            continue
        if current not in public:
            continue
        for c in line + '\n':
            if c == '{':
                depth += 1
            elif c == '}':
                depth -= 1
                if depth == 0 and re.search(r'\)\s*$', ''.join(text)):  # the end of a function's body
                    yield current, ''.join(text) + '{}'
                    text = []
            elif depth == 0 and c == ';':
                yield current, ''.join(text)
                text = []
            elif depth == 0:
                text.append(c)


def declared_symbols(cc, include_dirs):
    headers = sorted(h for d in include_dirs for h in glob.glob(os.path.join(d, 'sss', '*.h')))
    if not headers:
        sys.exit('FAIL: no headers in %s' % ' '.join(os.path.join(d, 'sss') for d in include_dirs))
    public = {os.path.realpath(h) for h in headers}
    names, problems = {}, []
    for path, stmt in statements(preprocess(cc, include_dirs, headers), public):
        s = ' '.join(strip_attributes(stmt).split())
        if not s or re.match(r'(typedef|struct|union|enum)\b', s):
            continue
        where = os.path.basename(path)
        call = IDENT_CALL.search(s)
        if s.endswith('{}'):
            if not s.startswith('static'):
                problems.append('%s defines a non-static function: %s' % (where, s[:80]))
        elif call and not call.group(1):  # a function: its name is the first identifier called
            if not s.startswith('static'):
                names[call.group(2)] = where
        elif s.startswith('extern'):  # a datum (or a pointer to a function): the name before [ or =
            head = re.split(r'[\[=]', s)[0]
            name = call.group(2) if call else IDENT.findall(head)[-1]
            names[name] = where
    return names, problems


def exported_symbols(nm, lib):
    out = subprocess.run([nm, '-D', '--defined-only', lib], check=True, capture_output=True, text=True)
    return {line.split()[-1].split('@')[0] for line in out.stdout.splitlines() if line.strip()}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--cc', default=os.environ.get('CC', 'cc'))
    ap.add_argument('--nm', default='nm')
    ap.add_argument('lib')
    ap.add_argument('include_dirs', nargs='+')
    a = ap.parse_args()
    declared, problems = declared_symbols(a.cc, a.include_dirs)
    exported = exported_symbols(a.nm, a.lib)
    leaked = sorted(exported - set(declared))
    missing = sorted(set(declared) - exported)
    print('%s exports %d symbols; the headers declare %d' % (os.path.basename(a.lib), len(exported), len(declared)))
    foreign = sorted(n for n in declared if not n.startswith('sss_'))
    if foreign:  # a program's own symbols must not clash with the library's
        problems.append('declared outside the sss_ namespace: %s' % ' '.join(foreign))
    if leaked:
        problems.append('exported but declared in no public header (%d): %s' % (len(leaked), ' '.join(leaked)))
    if missing:
        problems.append('declared but not exported (%d; no SSS_API?): %s'
                        % (len(missing), ' '.join('%s (%s)' % (n, declared[n]) for n in missing)))
    for p in problems:
        print('FAIL: ' + p)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
