#!/usr/bin/env python3
"""Audits kernel-config/ as the Yocto kernels use it (fragments merged onto a
defconfig by merge_config): usage: kernel-config-audit.py DIR [KERNEL_SRC]

- every fragment line is blank, a comment, CONFIG_X=value or
  '# CONFIG_X is not set', and no option is given two values across fragments;
- README's table lists exactly the fragments there are;
- cmdline.txt is one line, and the CPUs it isolates (isolcpus, nohz_full,
  rcu_nocbs) agree and are kept out of irqaffinity;
- with KERNEL_SRC (a source tree or a linux-*.tar.* file), every option a
  fragment names is declared by some Kconfig file in it. Without one the names
  are not checked, and the output says so.
"""
import pathlib
import re
import sys
import tarfile

SET = re.compile(r'^(CONFIG_[A-Z0-9_]+)=(y|m|n|"[^"]*"|-?[0-9]+|0x[0-9a-fA-F]+)$')
UNSET = re.compile(r'^# (CONFIG_[A-Z0-9_]+) is not set$')
KCONFIG_SYMBOL = re.compile(rb'^\s*(?:menu)?config\s+([A-Za-z0-9_]+)\s*$', re.M)


def parse_fragments(root):
    values, errors = {}, []
    for frag in sorted(root.glob('*.cfg')):
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
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    root = pathlib.Path(sys.argv[1])
    values, errors = parse_fragments(root)
    errors += check_readme(root) + check_cmdline(root)
    print(f'{len(values)} options in {len(list(root.glob("*.cfg")))} fragments')
    if len(sys.argv) == 3:
        symbols = kconfig_symbols(sys.argv[2])
        if not symbols:
            errors.append(f'no Kconfig symbols found in {sys.argv[2]}')
        for name, (_, where) in sorted(values.items()):
            if symbols and name[len('CONFIG_'):] not in symbols:
                errors.append(f'{where}: {name} is declared by no Kconfig in {sys.argv[2]}')
        print(f'option names checked against {len(symbols)} Kconfig symbols of {sys.argv[2]}')
    else:
        print('option names NOT checked against a Kconfig: no kernel source given (KNOBLAB_KERNEL_SRC); '
              'the CI image\'s kernel build checks them with olddefconfig')
    for e in errors:
        print(e)
    sys.exit(1 if errors else 0)


if __name__ == '__main__':
    main()
