#!/usr/bin/env python3
"""Rebuilds the Table 1 comparison directories (`out/t1-*`) from the run archives.

Usage: scripts/rebuild-out.py [TARGET_DIR] [--archives DIR] [--clean] [--dry-run] [--resume NETSPEC]

  TARGET_DIR: where to extract (default: the repository's out/; it may be a symlink). It must
    be empty, unless --clean is given, which first deletes everything inside it (not the
    directory itself).
  --archives DIR: the run archives (default: docs/table1-runs/ of this repository).
  --dry-run: print the steps, touch nothing.
  --resume NETSPEC: afterwards, write each column's results.json again by resuming its
    comparison with the netspec binary NETSPEC (the command in the report's header, run from
    the repository's root), so that `netspec compare --merge` can read it. Every record must be
    reused: the script first checks each run.json's settings against the ones the resume would
    want (spec path and digest, recipe, backend, threads, limit, version, start) and refuses if
    any differs, so this never starts a solve.

Follows the extraction recipe of docs/table1-reproduction.md (the paragraph "Every run's record
... extract the first into `out/`, ...", written by scripts/table1-report.py) step by step. The
ordinals there ("the first" ... "the seventeenth") count the archives of docs/table1-runs/ in
name order:

   1 2026-12-01   (sessions 1-2)     7 2026-12-02e (session 7)    13 2026-12-03d (session 13)
   2 2026-12-01b  (session 3)        8 2026-12-02f (session 8)    14 2026-12-03e (session 14)
   3 2026-12-02   (session 4)        9 2026-12-02g (session 9)    15 2026-12-03f (session 15)
   4 2026-12-02b  (not used)        10 2026-12-03  (session 10)   16 2026-12-03g (session 16)
   5 2026-12-02c  (session 5)       11 2026-12-03b (session 11)   17 2026-12-04  (session 17)
   6 2026-12-02d  (session 6)       12 2026-12-03c (session 12)

The recipe goes from the third straight to the fifth: the fourth, 2026-12-02b, holds only side
experiments (t1-fig2d-*, t1-l4d-*, t1-shortd-*, ... none of the report's columns) and is not
extracted.

"Remove COLUMN's rows of models/table1-X.toml" deletes, for every `name` of a `[[row]]` table of
that manifest, the run directory TARGET/<column dir>/runs/<name>__*/ (e.g.
out/t1-highs-strong/runs/2a__highs+strong__default/), so that the next archive's run is the only
record of that cell (and no file of the replaced run is left behind). Columns:
HiGHS/strong = t1-highs-strong, SCIP/strong = t1-scip-strong, HiGHS/paper = t1-highs-paper,
CBC/strong = t1-cbc-strong, anneal = t1-anneal. "The strong recipe's room rows" are the eight
rows 1d, 1e, 9b1-9b4, 11a, 11b (the rows that tile rooms), in both strong columns; "2a-2g" are
2a, 2b, ..., 2g; HiGHS/strong's "7a rows" are 7a-L2, 7a-L3, 7a-L4. The recipe's "(also from
`t1-scip-beside-highs/`)" is read as applying to the 2a-2g just before it.

Archives are extracted with `tar xzf ARCHIVE -C TARGET` (after checking that every member is a
relative path inside TARGET), which keeps the files' modification times: scripts/table1-report.py
takes a run's start from its run.json's mtime (less its wall time) for the † windows.

After each extraction the script checks that every run directory removed just before it came
back from that archive, and warns otherwise. At the end it prints the number of run directories
per column. The archives hold no up-to-date results.json for the columns (the last sessions'
archives carry runs/ only; t1-cbc-strong/ and t1-anneal/ none at all), so before
`netspec compare --merge` each column's results.json has to be written again by resuming its
comparison (every record reused): --resume does that.

Then, from the repository's root:
  netspec compare --merge out/t1-highs-strong,out/t1-scip-strong,out/t1-highs-paper,out/t1-cbc-strong,out/t1-anneal \
      --manifest models/table1.toml --out out/t1-merged
  scripts/table1-report.py out/t1-merged --shared WINDOWS --hours 14.13

WINDOWS (reconstructed from the † cells of the committed report; with it the report comes out
byte for byte as committed): the six windows, one per stretch of side-by-side runs,
  2026-12-01T02:23:53Z/2026-12-01T02:37:32Z,
  2026-12-01T04:58:25Z/2026-12-01T06:47:39Z,
  2026-12-01T21:01:00Z/2026-12-01T21:27:31Z,
  2026-12-02T01:17:13Z/2026-12-02T01:17:14Z,
  2026-12-03T07:54:18Z/2026-12-03T08:38:07Z,
  2026-12-03T09:28:15Z/2026-12-03T10:28:28Z
joined by commas without spaces. Every run of the five columns that started inside one of them is
†, and no other.
"""
import glob, json, os, shutil, subprocess, sys, tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

COLUMNS = {
    "highs/strong": "t1-highs-strong",
    "scip/strong": "t1-scip-strong",
    "highs/paper": "t1-highs-paper",
    "cbc/strong": "t1-cbc-strong",
    "anneal": "t1-anneal",
}

ARCHIVES = [
    "2026-12-01", "2026-12-01b", "2026-12-02", "2026-12-02b", "2026-12-02c", "2026-12-02d",
    "2026-12-02e", "2026-12-02f", "2026-12-02g", "2026-12-03", "2026-12-03b", "2026-12-03c",
    "2026-12-03d", "2026-12-03e", "2026-12-03f", "2026-12-03g", "2026-12-04",
]

# Each column's comparison (backend, recipe, threads): the commands in the report's header.
COMMANDS = {
    "t1-highs-strong": ("highs", "strong", 2),
    "t1-scip-strong": ("scip", "strong", 1),
    "t1-highs-paper": ("highs", "paper", 2),
    "t1-cbc-strong": ("cbc", "strong", 1),
    "t1-anneal": ("anneal", "strong", 1),
}
SEARCHES = ("heuristic", "anneal")  # src/compare.rs SEARCHES: no MIP start
TIME_LIMIT = 300.0
NETSPEC_VERSION = "0.1.0"

ROOM_ROWS = ["1d", "1e", "9b1", "9b2", "9b3", "9b4", "11a", "11b"]
FIG2 = ["2a", "2b", "2c", "2d", "2e", "2f", "2g"]
SEVEN_A = ["7a-L2", "7a-L3", "7a-L4"]
STRONG = ["highs/strong", "scip/strong"]


def manifest(name):
    """The row names of models/table1-NAME.toml (its [[row]] tables' `name`)."""
    with open(os.path.join(ROOT, "models", f"table1-{name}.toml"), "rb") as f:
        return [r["name"] for r in tomllib.load(f)["row"]]


def remove(columns, rows, dirs=None):
    """A removal step: `rows` of each of `columns` (labels), or of the literal `dirs`."""
    return ("remove", [COLUMNS[c] for c in columns] + list(dirs or []), list(rows))


def steps():
    x = lambda n: ("extract", n)
    return [
        x(1), remove(STRONG, ROOM_ROWS), remove(["highs/paper"], ["1e"]),
        x(2), remove(STRONG + ["highs/paper"], ["1e"]), remove(STRONG, ["11b"]),
        x(3), remove(["highs/strong"], manifest("cuts")),
        remove(["scip/strong"], manifest("streets-l4")),
        remove(["scip/strong"], FIG2, dirs=["t1-scip-beside-highs"]),
        # (the fourth archive is not named by the recipe)
        x(5), remove(STRONG, manifest("split")),
        x(6), remove(["highs/strong"], manifest("tuned")),
        x(7), remove(STRONG, manifest("paths")),
        x(8), remove(["highs/strong"], manifest("rooms")),
        x(9), remove(STRONG, manifest("spurs")),
        x(10), remove(["highs/strong"], manifest("indicators")), remove(["highs/strong"], SEVEN_A),
        remove(["scip/strong"], manifest("fig2")),
        x(11),
        x(12),
        x(13), remove(["highs/strong"], manifest("parallel")),
        x(14), remove(["highs/strong"], manifest("directed")),
        remove(["scip/strong"], ["1c-L2", "1c-L3", "5L3", "5L4"]),
        x(15), remove(["highs/strong", "scip/strong", "cbc/strong"], ["2a", "2b"]),
        x(16), remove(["highs/strong"], ROOM_ROWS), remove(["cbc/strong"], ["1c-L2", "1c-L3", "5L3", "5L4"]),
        x(17),
    ]


def members(archive):
    names = subprocess.run(["tar", "tzf", archive], check=True, capture_output=True, text=True).stdout.split("\n")
    names = [n for n in names if n]
    for n in names:
        parts = n.split("/")
        if n.startswith("/") or ".." in parts:
            sys.exit(f"{archive}: unsafe member {n!r}")
    return names


def digest(parts):
    """src/io/mod.rs digest: FNV-1a over the parts, each followed by 0xff."""
    h, mask = 0xCBF29CE484222325, (1 << 64) - 1
    for p in parts:
        for b in p:
            h = ((h ^ b) * 0x100000001B3) & mask
        h = ((h ^ 0xFF) * 0x100000001B3) & mask
    return f"{h:016x}"


def wanted_settings(row, solver, formulation, threads):
    """The RunSettings a resume of `row` would want (src/compare.rs RunSettings::new, run_all)."""
    spec = os.path.normpath(os.path.join("models", row["spec"]))
    data = open(os.path.join(ROOT, spec), "rb").read()
    value = json.loads(data) if spec.lower().endswith(".json") else tomllib.loads(data.decode())
    mesh_file = (value.get("mesh") or {}).get("file") if isinstance(value.get("mesh"), dict) else None
    mesh = b""
    if isinstance(mesh_file, str):
        try:
            mesh = open(os.path.join(ROOT, os.path.dirname(spec), mesh_file), "rb").read()
        except OSError:
            pass
    try:
        paper = float(str((row.get("paper") or {}).get("time")).strip())
    except ValueError:
        paper = None
    limit = min(paper, TIME_LIMIT) if paper is not None and paper > 0 else TIME_LIMIT
    return {
        "spec": spec, "spec_digest": digest([data, mesh]), "formulation": formulation,
        "solver": f"{solver}/{formulation}", "seed": None, "threads": threads, "time_limit": limit,
        "netspec_version": NETSPEC_VERSION, "start": None if solver in SEARCHES else "heuristic",
    }


def resume(netspec, target, real):
    """Writes each column's results.json again by resuming its comparison (nothing solved)."""
    with open(os.path.join(ROOT, "models", "table1.toml"), "rb") as f:
        rows = [r for r in tomllib.load(f)["row"] if r.get("spec")]
    problems = []
    for d, (solver, formulation, threads) in COMMANDS.items():
        for row in rows:
            want = wanted_settings(row, solver, formulation, threads)
            path = os.path.join(real, d, "runs", f"{row['name']}__{want['solver'].replace('/', '+')}__default", "run.json")
            try:
                r = json.load(open(path))
            except OSError:
                problems.append(f"{path}: missing")
                continue
            if r.get("status") == "interrupted" or r.get("instance") != row["name"] or r.get("settings") != want:
                had = r.get("settings") or {}
                problems.append(f"{path}: " + ", ".join(f"{k} {had.get(k)!r} != {v!r}" for k, v in want.items() if had.get(k) != v))
    if problems:
        sys.exit("a resume would solve again (not run):\n  " + "\n  ".join(problems))
    # The --out the report's header names (out/t1-...), when TARGET is the repository's out/.
    base = "out" if real == os.path.realpath(os.path.join(ROOT, "out")) else os.path.abspath(target)
    for d, (solver, formulation, threads) in COMMANDS.items():
        cmd = [netspec, "compare", "--manifest", "models/table1.toml", "--solvers", solver, "--formulations",
               formulation, "--threads", str(threads), "--paper-limits", "--time-limit", "300", "--grace", "30",
               "--out", os.path.join(base, d)]
        print("resume:", " ".join(cmd[1:]))
        out = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
        lines = [l for l in out.split("\n") if l.strip() and l.split()[0] in {r["name"] for r in rows}]
        fresh = [l for l in lines if not l.rstrip().endswith("(resumed)")]
        print(f"  {len(lines) - len(fresh)} records resumed" + (f", NOT resumed: {fresh}" if fresh else ""))


def run_count(target, d):
    return len(glob.glob(os.path.join(target, d, "runs", "*", "run.json")))


def main():
    args = sys.argv[1:]
    if "-h" in args or "--help" in args:
        print(__doc__)
        return
    netspec = None
    if "--resume" in args:
        i = args.index("--resume")
        netspec = os.path.abspath(args[i + 1])
        del args[i:i + 2]
    clean = "--clean" in args
    dry = "--dry-run" in args
    args = [a for a in args if a not in ("--clean", "--dry-run")]
    archives = os.path.join(ROOT, "docs", "table1-runs")
    if "--archives" in args:
        i = args.index("--archives")
        archives = args[i + 1]
        del args[i:i + 2]
    if len(args) > 1:
        sys.exit(__doc__)
    target = args[0] if args else os.path.join(ROOT, "out")
    real = os.path.realpath(target)
    if not dry:
        os.makedirs(real, exist_ok=True)
        if os.listdir(real):
            if not clean:
                sys.exit(f"{target} ({real}) is not empty: pass --clean to empty it first")
            for e in os.listdir(real):
                p = os.path.join(real, e)
                shutil.rmtree(p) if os.path.isdir(p) and not os.path.islink(p) else os.remove(p)
    pending = []  # run directories removed since the last extraction
    for step in steps():
        if step[0] == "extract":
            n = step[1]
            archive = os.path.join(archives, ARCHIVES[n - 1] + ".tar.gz")
            names = members(archive)
            print(f"extract #{n} {os.path.relpath(archive, ROOT)} ({len(names)} members)")
            if dry:
                continue
            subprocess.run(["tar", "xzf", archive, "-C", real], check=True)
            for d in pending:
                if not os.path.exists(os.path.join(d, "run.json")):
                    print(f"  warning: {os.path.relpath(d, real)} was removed and not replaced by #{n}")
            pending = []
        else:
            _, dirs, rows = step
            gone = []
            for d in dirs:
                for row in rows:
                    for p in sorted(glob.glob(os.path.join(real, d, "runs", glob.escape(row) + "__*"))):
                        gone.append(os.path.relpath(p, real))
                        if not dry:
                            shutil.rmtree(p)
                        if d in COLUMNS.values():
                            pending.append(p)
            print(f"  remove {', '.join(dirs)}: {len(rows)} rows ({' '.join(rows)}): {len(gone)} run dirs")
    if dry:
        return
    print("runs per column:")
    for label, d in COLUMNS.items():
        print(f"  {d} ({label}): {run_count(real, d)}")
    others = sorted(e for e in os.listdir(real) if e not in COLUMNS.values())
    print("other directories (kept runs, not columns of the report):", " ".join(others))
    if netspec:
        resume(netspec, target, real)


if __name__ == "__main__":
    main()
