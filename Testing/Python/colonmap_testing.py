"""Shared helpers of the module tests that run ColonMap programs as a user does."""
import os
import re
import subprocess


class Checks:
    """Counts checks; prints each failure; ends with the 'N passed, N failed' line."""

    def __init__(self):
        self.passed = 0
        self.failed = 0

    def check(self, condition, message):
        if condition:
            self.passed += 1
        else:
            self.failed += 1
            print("FAIL: " + message)
        return condition

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        return 1 if self.failed else 0


def run_program(*args):
    """Runs a command with no standard input; returns the CompletedProcess (text output)."""
    return subprocess.run(list(args), capture_output=True, text=True, stdin=subprocess.DEVNULL)


def return_parameters(path):
    """The `name = value` lines of a --returnparameterfile, as a dict ({} when missing)."""
    if not os.path.exists(path):
        return {}
    return {m.group(1): m.group(2).strip() for m in re.finditer(r"^(\w+) = (.*)$", open(path).read(), re.M)}
