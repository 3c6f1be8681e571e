"""Two JSON files the same apart from their times and command line
(benchmarks/compare_outputs.sh). usage: json_same.py A.json B.json; exit 1,
printing each differing path, when they differ."""
import json, re, sys
SKIP = re.compile(r'(created_utc|wall_time|cpu_time|command_line|^command$|_wall_s$|elapsed|seconds)')
def strip(d):
    if isinstance(d, dict):
        return {k: strip(v) for k, v in d.items() if not SKIP.search(k)}
    if isinstance(d, list):
        return [strip(v) for v in d]
    return d
def diff(a, b, path=''):
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b: print(path + '.' + k, 'only in one'); continue
            diff(a[k], b[k], path + '.' + k)
    elif isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)): diff(x, y, f'{path}[{i}]')
    elif a != b:
        print(path, repr(a)[:80], '!=', repr(b)[:80])
a = strip(json.load(open(sys.argv[1]))); b = strip(json.load(open(sys.argv[2])))
if a != b:
    diff(a, b); sys.exit(1)
