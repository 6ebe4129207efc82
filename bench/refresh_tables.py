#!/usr/bin/env python3
"""The table-writing half of bench/refresh.sh: puts a benchmark's tables into a page, between its markers.

A page holds each regenerated block between `<!-- refresh:NAME -->` and `<!-- /refresh:NAME -->` (each on a line of
its own). `write` replaces what lies between one pair with a stamp (commit, date, load, command) and the tables of a
benchmark's output: every Markdown table, with the line of text just above it as its caption, and CSV output (a
header line and rows of numbers) as one table. `check` fails on unbalanced, nested, repeated or misnamed markers.
`commits` rewrites the index's list of the commits each page names (the lines after "The commits named on each
page:" in bench/README.md) from the pages themselves: every 7-digit hexadecimal word that git knows as a commit.
`selftest` runs them on made-up pages (the ctest entries run it and `check` on the real pages).

    refresh_tables.py write PAGE NAME OUTPUT --stamp TEXT --command TEXT
    refresh_tables.py check PAGE... [--expect NAME...]
    refresh_tables.py commits INDEX PAGE...
    refresh_tables.py selftest
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

OPEN = re.compile(r'^<!-- refresh:([A-Za-z0-9_.-]+) -->$')
CLOSE = re.compile(r'^<!-- /refresh:([A-Za-z0-9_.-]+) -->$')


class MarkerError(ValueError):
    pass


def blocks(lines, where):
    """The marker blocks of a page's lines: {name: (open line index, close line index)}; MarkerError if unbalanced."""
    found, current = {}, None
    for i, line in enumerate(lines):
        line = line.rstrip('\n')
        o, c = OPEN.match(line), CLOSE.match(line)
        if o:
            if current is not None:
                raise MarkerError('%s:%d: refresh:%s opens inside refresh:%s (opened at line %d)'
                                  % (where, i + 1, o.group(1), current[0], current[1] + 1))
            if o.group(1) in found:
                raise MarkerError('%s:%d: refresh:%s appears twice' % (where, i + 1, o.group(1)))
            current = (o.group(1), i)
        elif c:
            if current is None:
                raise MarkerError('%s:%d: /refresh:%s closes nothing' % (where, i + 1, c.group(1)))
            if c.group(1) != current[0]:
                raise MarkerError('%s:%d: /refresh:%s closes refresh:%s (opened at line %d)'
                                  % (where, i + 1, c.group(1), current[0], current[1] + 1))
            found[current[0]] = (current[1], i)
            current = None
        elif '<!-- refresh:' in line or '<!-- /refresh:' in line:
            raise MarkerError('%s:%d: a marker must be a line of its own: %s' % (where, i + 1, line.strip()))
    if current is not None:
        raise MarkerError('%s:%d: refresh:%s is never closed' % (where, current[1] + 1, current[0]))
    return found


def tables(output):
    """The Markdown tables of a benchmark's output, each with the text line above it; or its CSV as one table."""
    lines = [l.rstrip() for l in output.splitlines()]
    out, i = [], 0
    while i < len(lines):
        if lines[i].startswith('|'):
            j = i
            while j < len(lines) and lines[j].startswith('|'):
                j += 1
            caption = lines[i - 1] if i > 0 and lines[i - 1] and not lines[i - 1].startswith('|') else ''
            if not caption and i > 1 and not lines[i - 1] and lines[i - 2] and not lines[i - 2].startswith('|'):
                caption = lines[i - 2]
            out.append((caption, lines[i:j]))
            i = j
        else:
            i += 1
    if out:
        return out
    csv = [l for l in lines if re.fullmatch(r'[A-Za-z_]+(,[A-Za-z_]+)+', l) or re.fullmatch(r'[-0-9.e+]+(,[-0-9.e+]+)+', l)]
    if len(csv) >= 2 and not csv[0][0].isdigit():
        head = csv[0].split(',')
        rows = ['| ' + ' | '.join(head) + ' |', '|' + '---|' * len(head)]
        rows += ['| ' + ' | '.join(r.split(',')) + ' |' for r in csv[1:] if len(r.split(',')) == len(head)]
        rest = [l for l in lines if l and l not in csv]
        return [(rest[-1] if rest else '', rows)]
    return []


def write(page, name, output, stamp, command):
    with open(page) as f:
        lines = f.readlines()
    found = blocks(lines, page)
    if name not in found:
        raise MarkerError('%s: no refresh:%s block' % (page, name))
    got = tables(output)
    if not got:
        raise ValueError('%s: the output for refresh:%s holds no table' % (page, name))
    body = ['', stamp, '', 'Command: `%s`' % command, '']
    for caption, rows in got:
        if caption:
            body += [caption, '']
        body += rows + ['']
    start, end = found[name]
    lines[start + 1:end] = [l + '\n' for l in body]
    tmp = page + '.tmp'
    with open(tmp, 'w') as f:
        f.writelines(lines)
    os.replace(tmp, page)
    return len(got)


COMMIT_WORD = re.compile(r'\b[0-9a-f]{7}\b')
INDEX_HEAD = 'The commits named on each page:'


def known_commits(words):
    """The words git resolves to a commit of this repository (one git call for all)."""
    words = sorted(words)
    if not words:
        return set()
    out = subprocess.run(['git', 'cat-file', '--batch-check'], input=''.join(w + '^{commit}\n' for w in words),
                         capture_output=True, text=True, check=True).stdout.splitlines()
    return {w for w, line in zip(words, out) if not line.endswith('missing') and ' commit ' in line}


def commits(index, pages, resolve=known_commits):
    """Rewrite index's list of the commits each page names; returns the number of pages listed."""
    named = {}
    for page in pages:
        with open(page) as f:
            named[page] = set(COMMIT_WORD.findall(f.read()))
    real = resolve(set().union(*named.values()))
    with open(index) as f:
        lines = f.readlines()
    try:
        head = lines.index(INDEX_HEAD + '\n')
    except ValueError:
        raise MarkerError('%s: no line "%s"' % (index, INDEX_HEAD))
    start = head + 2  # after the heading's blank line
    end = start
    while end < len(lines) and lines[end].startswith('* '):
        end += 1
    listed = []
    for page in pages:
        found = sorted(named[page] & real)
        if found:
            name = os.path.splitext(os.path.basename(page))[0]
            listed.append('* [%s](%s.md): %s\n' % (name, name, ', '.join(found)))
    lines[start:end] = listed
    tmp = index + '.tmp'
    with open(tmp, 'w') as f:
        f.writelines(lines)
    os.replace(tmp, index)
    return len(listed)


def selftest():
    """write on a made-up page, then check: a replaced block, the others untouched; and each kind of bad marker."""
    with tempfile.TemporaryDirectory() as d:
        page = os.path.join(d, 'page.md')
        with open(page, 'w') as f:
            f.write('# t\n\n<!-- refresh:a -->\nold a\n<!-- /refresh:a -->\n\nkept\n\n<!-- refresh:b -->\nold b\n'
                    '<!-- /refresh:b -->\n')
        fake = 'noise\nRows of a:\n\n| x | y |\n|---|---|\n| 1 | 2 |\ntrailing\n'
        assert write(page, 'a', fake, 'Measured at abc1234.', 'bench --quick') == 1
        text = open(page).read()
        assert 'old a' not in text and 'old b' in text and 'kept' in text, text
        assert 'Measured at abc1234.' in text and 'Rows of a:' in text and '| 1 | 2 |' in text, text
        assert 'noise' not in text and 'trailing' not in text, text
        assert set(blocks(text.splitlines(True), page)) == {'a', 'b'}
        assert write(page, 'b', 'tenth,queries\n1,10\n2,20\nsummary line\n', 's', 'c') == 1
        assert '| tenth | queries |' in open(page).read()
        for bad in ['<!-- refresh:a -->\n', '<!-- /refresh:a -->\n', '<!-- refresh:a -->\n<!-- /refresh:b -->\n',
                    '<!-- refresh:a -->\n<!-- refresh:b -->\n<!-- /refresh:b -->\n<!-- /refresh:a -->\n',
                    '<!-- refresh:a -->\n<!-- /refresh:a -->\n<!-- refresh:a -->\n<!-- /refresh:a -->\n',
                    'text <!-- refresh:a -->\n']:
            try:
                blocks(bad.splitlines(True), 'bad')
            except MarkerError:
                continue
            raise AssertionError('not refused: %r' % bad)
        try:
            write(page, 'a', 'no table here\n', 's', 'c')
            raise AssertionError('an output without a table was written')
        except ValueError:
            pass
        # commits: words that are commits listed per page, sorted; other words and stale entries not.
        index = os.path.join(d, 'README.md')
        with open(index, 'w') as f:
            f.write('# i\n\n%s\n\n* [old](old.md): 0000abc\n\nafter\n' % INDEX_HEAD)
        other = os.path.join(d, 'other.md')
        with open(other, 'w') as f:
            f.write('at b7ee66b and 0141c74, 1182550 pairs, deadbee (not one), 0141c74 again, 1026127, 0141c745\n')
        with open(page, 'w') as f:
            f.write('nothing named\n')
        assert commits(index, [other, page], lambda words: words - {'deadbee', '1182550'}) == 1
        text = open(index).read()
        assert '* [other](other.md): 0141c74, 1026127, b7ee66b\n\nafter' in text and 'old' not in text, text
    print('selftest: write, check and commits behave')


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest='what', required=True)
    w = sub.add_parser('write')
    w.add_argument('page')
    w.add_argument('name')
    w.add_argument('output')
    w.add_argument('--stamp', required=True)
    w.add_argument('--command', required=True)
    c = sub.add_parser('check')
    c.add_argument('pages', nargs='+')
    c.add_argument('--expect', nargs='*', default=[], help='block names that must exist (NAME or PAGE:NAME)')
    m = sub.add_parser('commits')
    m.add_argument('index')
    m.add_argument('pages', nargs='+')
    sub.add_parser('selftest')
    a = p.parse_args()
    try:
        if a.what == 'write':
            with open(a.output) as f:
                n = write(a.page, a.name, f.read(), a.stamp, a.command)
            print('%s: refresh:%s, %d table(s)' % (a.page, a.name, n))
        elif a.what == 'check':
            names = {}
            for page in a.pages:
                with open(page) as f:
                    for n in blocks(f.readlines(), page):
                        names[n] = page
            missing = [e for e in a.expect if e.split(':')[-1] not in names or
                       (':' in e and os.path.basename(names[e.split(':')[-1]]) != os.path.basename(e.split(':')[0]))]
            if missing:
                raise MarkerError('blocks missing: ' + ', '.join(missing))
            print('%d page(s), %d block(s), markers balanced' % (len(a.pages), len(names)))
        elif a.what == 'commits':
            print('%s: commits of %d page(s) listed' % (a.index, commits(a.index, a.pages)))
        else:
            selftest()
    except (MarkerError, ValueError, OSError, subprocess.CalledProcessError) as e:
        print('refresh_tables.py: %s' % e, file=sys.stderr)
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
