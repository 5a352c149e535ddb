#!/usr/bin/env python3
"""Every relative link of README.md and docs/*.md leads somewhere: the file exists and, with a
#fragment into a Markdown page, that page has a heading of that anchor (GitHub's rule: lower case,
punctuation but '-' and '_' dropped, spaces to '-'). The README is the front door and links into
docs/ (issue 30); a moved or renamed section must not leave a dead link behind.

  check_doc_links.py PACKAGE_ROOT
"""
import glob
import os
import re
import sys

LINK = re.compile(r'!?\[[^\]]*\]\(([^)\s]+)\)')


def anchors(path):
    out, fence = set(), False
    for line in open(path, encoding='utf-8'):
        if line.startswith('```'):
            fence = not fence
        m = None if fence else re.match(r'#{1,6} (.*)', line)
        if m:
            slug = re.sub(r'[^\w\- ]', '', m.group(1).strip().lower()).replace(' ', '-')
            out.add(slug)
    return out


def main(root):
    pages = [os.path.join(root, 'README.md')] + sorted(glob.glob(os.path.join(root, 'docs', '*.md')))
    errors, count = [], 0
    for page in pages:
        fence = False
        for n, line in enumerate(open(page, encoding='utf-8'), 1):
            if line.startswith('```'):
                fence = not fence
            if fence:
                continue
            for target in LINK.findall(line):
                if re.match(r'[a-z]+:', target):  # http:, https:, mailto:
                    continue
                count += 1
                path, _, fragment = target.partition('#')
                dest = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
                where = '%s:%d' % (os.path.relpath(page, root), n)
                if not os.path.exists(dest):
                    errors.append('%s: link to %s: no such file' % (where, target))
                elif fragment and dest.endswith('.md') and fragment not in anchors(dest):
                    errors.append('%s: link to %s: no heading #%s in %s' % (where, target, fragment,
                                                                           os.path.relpath(dest, root)))
    for e in errors:
        print('DEAD LINK: ' + e)
    if errors:
        return 1
    print('ok: %d relative links in %d pages lead somewhere' % (count, len(pages)))
    return 0


if __name__ == '__main__':
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
