#!/usr/bin/python3
"""rdtable — one row per rockdem run and body: file, title, body, overturned, overturn time,
max tilt, max tilt/alpha, max slide, status, dt, energy residual and the ground-motion intensity
measures (every numeric attribute on /ground; pga and pgv computed from the applied motion when
the file has none, column im_source). Prints an aligned table; --csv writes every column."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rdtools import cli, RDError  # noqa: E402


def main():
    p = cli.Parser(prog="rdtable", description=cli.describe(__doc__))
    p.add_argument("runs", nargs="+", metavar="RUN.h5", help="HDF5 files written by 'rockdem run'")
    p.add_argument("--csv", metavar="OUT.csv", help="write all columns to this CSV file")
    p.add_argument("-q", "--quiet", action="store_true", help="do not print the table")
    p.add_argument("--skip-bad", action="store_true",
                   help="warn about unreadable runs and go on (default: stop at the first)")
    a = p.parse_args()
    from rdtools.table import run_rows, write_csv, print_table
    rows, bad = [], 0
    for path in a.runs:
        try:
            rows.extend(run_rows(path))
        except RDError as e:
            if not a.skip_bad:
                raise
            sys.stderr.write("rdtable: warning: %s (skipped)\n" % e)
            bad += 1
    if not rows:
        raise RDError("no readable runs")
    if a.csv:
        cli.ensure_writable(a.csv)
        write_csv(rows, a.csv)
    if not a.quiet:
        print_table(rows, sys.stdout)
    if a.csv:
        sys.stderr.write("rdtable: wrote %d rows to %s\n" % (len(rows), a.csv))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(cli.run(main, "rdtable"))
