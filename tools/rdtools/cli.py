"""Shared command-line plumbing: every tool prints one line 'tool: error: ...' and exits 2 on
bad input (missing file, not a rockdem file, missing dataset, bad CSV), 1 on an unexpected crash."""
import argparse
import os
import sys

from . import RDError


class Parser(argparse.ArgumentParser):
    """argparse, but usage errors are one line too (argparse prints usage + message)."""

    def error(self, message):
        sys.stderr.write("%s: error: %s (see --help)\n" % (self.prog, message))
        sys.exit(2)


def describe(doc):
    """A tool's module docstring as its --help description: the whole text on one paragraph,
    the leading 'name — ' dropped and the first letter capitalised."""
    text = " ".join(doc.split())
    head, sep, rest = text.partition(" — ")
    text = rest if sep and " " not in head else text
    return text[:1].upper() + text[1:]


def run(main, prog):
    """Call main(); turn RDError / OSError into a one-line message and exit code 2."""
    try:
        rc = main()
    except RDError as e:
        sys.stderr.write("%s: error: %s\n" % (prog, e))
        return 2
    except BrokenPipeError:
        return 0
    except KeyboardInterrupt:
        sys.stderr.write("%s: interrupted\n" % prog)
        return 130
    except OSError as e:
        name = e.filename if e.filename else ""
        sys.stderr.write("%s: error: %s%s\n" % (prog, (name + ": ") if name else "", e.strerror or e))
        return 2
    return rc or 0


def ensure_writable(path):
    d = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(d):
        raise RDError("%s: output folder does not exist" % path)
