#!/usr/bin/env python3
"""Audits kernel-config/ as the Yocto kernels use it (fragments merged onto a
defconfig by merge_config):
  kernel-config-audit.py [--kernel-src SRC] [--format-only FRAGMENT...] DIR

- every fragment line is blank, a comment, CONFIG_X=value or
  '# CONFIG_X is not set', and no option is given two values across fragments;
- README's table lists exactly the fragments there are;
- cmdline.txt is one line, and the CPUs it isolates (isolcpus, nohz_full,
  rcu_nocbs) agree and are kept out of irqaffinity;
- with KERNEL_SRC (a source tree or a linux-*.tar.* file), every option a
  fragment names is declared by some Kconfig file in it. Without one the names
  are not checked, and the output says so;
- --format-only fragments (the layer's own, for patched kernels whose options
  no mainline Kconfig declares) only for their lines.
"""
import argparse
import pathlib
import re
import sys
import tarfile

SET = re.compile(r'^(CONFIG_[A-Z0-9_]+)=(y|m|n|"[^"]*"|-?[0-9]+|0x[0-9a-fA-F]+)$')
UNSET = re.compile(r'^# (CONFIG_[A-Z0-9_]+) is not set$')
KCONFIG_SYMBOL = re.compile(rb'^\s*(?:menu)?config\s+([A-Za-z0-9_]+)\s*$', re.M)


def parse_fragments(frags):
    values, errors = {}, []
    for frag in frags:
        for n, raw in enumerate(frag.read_text().splitlines(), 1):
            line = raw.strip()
            m = SET.match(line) or UNSET.match(line)
            if not m:
                if line and not line.startswith('#'):
                    errors.append(f'{frag.name}:{n}: not a CONFIG_ line: {raw!r}')
                continue
            name, value = m.group(1), (m.group(2) if m.re is SET else 'n')
            where = f'{frag.name}:{n}'
            if name in values and values[name][0] != value:
                errors.append(f'{where}: {name}={value}, but {values[name][1]} sets {values[name][0]}')
            values.setdefault(name, (value, where))
    return values, errors


def check_readme(root):
    listed = set(re.findall(r'^\|\s*`([^`]+)`', (root / 'README.md').read_text(), re.M))
    present = {p.name for p in root.iterdir() if p.name != 'README.md'}
    return [f'README.md lists {f}, which does not exist' for f in sorted(listed - present)] + \
           [f'{f} is not in README.md' for f in sorted(present - listed)]


def cpu_list(text):
    cpus = set()
    for part in text.split(','):
        if re.fullmatch(r'\d+-\d+', part):
            a, b = map(int, part.split('-'))
            cpus.update(range(a, b + 1))
        elif part.isdigit():
            cpus.add(int(part))
    return cpus


def check_cmdline(root):
    lines = [l for l in (root / 'cmdline.txt').read_text().splitlines() if l.strip()]
    if len(lines) != 1:
        return ['cmdline.txt: want one line, found %d' % len(lines)]
    args = dict(a.split('=', 1) if '=' in a else (a, '') for a in lines[0].split())
    isolated = {k: cpu_list(args[k]) for k in ('isolcpus', 'nohz_full', 'rcu_nocbs') if k in args}
    errors = []
    if len({frozenset(v) for v in isolated.values()}) > 1:
        errors.append(f'cmdline.txt: isolated CPUs differ: {isolated}')
    if 'irqaffinity' in args and isolated:
        overlap = cpu_list(args['irqaffinity']) & set.union(*isolated.values())
        if overlap:
            errors.append(f'cmdline.txt: irqaffinity includes isolated CPU(s) {sorted(overlap)}')
    return errors


def kconfig_symbols(src):
    src = pathlib.Path(src)
    symbols = set()
    if src.is_dir():
        for k in src.rglob('Kconfig*'):
            symbols.update(KCONFIG_SYMBOL.findall(k.read_bytes()))
    else:
        with tarfile.open(src) as tar:
            for member in tar:
                if member.isfile() and pathlib.PurePath(member.name).name.startswith('Kconfig'):
                    symbols.update(KCONFIG_SYMBOL.findall(tar.extractfile(member).read()))
    return {s.decode() for s in symbols}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('dir', type=pathlib.Path)
    ap.add_argument('--kernel-src')
    ap.add_argument('--format-only', nargs='*', default=[], type=pathlib.Path)
    args = ap.parse_args()
    frags = sorted(args.dir.glob('*.cfg'))
    values, errors = parse_fragments(frags)
    errors += check_readme(args.dir) + check_cmdline(args.dir)
    for extra in args.format_only:
        errors += parse_fragments([extra])[1]
    print(f'{len(values)} options in {len(frags)} fragments; {len(args.format_only)} more checked for format')
    if args.kernel_src:
        symbols = kconfig_symbols(args.kernel_src)
        if not symbols:
            errors.append(f'no Kconfig symbols found in {args.kernel_src}')
        for name, (_, where) in sorted(values.items()):
            if symbols and name[len('CONFIG_'):] not in symbols:
                errors.append(f'{where}: {name} is declared by no Kconfig in {args.kernel_src}')
        print(f'option names checked against {len(symbols)} Kconfig symbols of {args.kernel_src}')
    else:
        print('option names NOT checked against a Kconfig: no kernel source given '
              '(KNOBLAB_KERNEL_SRC, or Debian\'s linux-source package in /usr/src)')
    for e in errors:
        print(e)
    sys.exit(1 if errors else 0)


if __name__ == '__main__':
    main()
