"""What the solver-input checks (check_damask.py, check_abaqus.py) share: the output
directory from the command line, its summary.json, and a list of failed checks that
decides the exit code (0 all passed, 1 with the failures listed, 2 for a bad command)."""

import json
import os
import sys


class Checklist:
    def __init__(self, usage):
        if len(sys.argv) != 2:
            print(usage)
            sys.exit(2)
        self.out = sys.argv[1]
        self.failures = []
        with open(os.path.join(self.out, "summary.json")) as f:
            self.summary = json.load(f)

    def path(self, name):
        return os.path.join(self.out, name)

    def __call__(self, ok, message):
        if not ok:
            self.failures.append(message)

    def exit_code(self):
        if self.failures:
            print("FAILED:\n  " + "\n  ".join(self.failures))
            return 1
        return 0
