#!/usr/bin/python3
"""tools/mutation-check on a miniature CMake project (seconds, not the real build).

usage: mutation_check_test.py TOOL WORKDIR

Checks: a caught mutation names the failing test; an uncaught one says NOT
CAUGHT; a spec whose text is absent says NO LONGER APPLIES (and so does --list);
ambiguous text and a regex matching no test are reported; the exit status is
non-zero when anything is not caught; only the tests named run; the source tree
is never modified; a malformed spec is refused naming file and line; and an
interrupted run (SIGINT while a mutant's test runs) leaves no mutation applied
and stops the test it was running.
"""

import os
import shutil
import signal
import subprocess
import sys
import time

TOOL, WORK = sys.argv[1], os.path.abspath(sys.argv[2])
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def snapshot(root):
    files = {}
    for dirpath, _, names in os.walk(root):
        for name in names:
            path = os.path.join(dirpath, name)
            with open(path, "rb") as f:
                files[os.path.relpath(path, root)] = (f.read(), os.stat(path).st_mtime_ns)
    return files


shutil.rmtree(WORK, ignore_errors=True)
# A sleep nobody else on the machine runs, so pgrep below finds only ours.
SLEEP = "30.%06d" % os.getpid()
src = os.path.join(WORK, "mini")
scratch = os.path.join(WORK, "scratch")
write(os.path.join(src, "CMakeLists.txt"), """cmake_minimum_required(VERSION 3.18)
project(mini CXX)
enable_testing()
add_executable(adder adder_test.cc)
add_test(NAME mini.adds COMMAND adder)
add_executable(other other_test.cc)
add_test(NAME mini.other COMMAND other)
add_test(NAME mini.slow COMMAND ${CMAKE_COMMAND} -E sleep %s)
""" % SLEEP)
write(os.path.join(src, "adder_test.cc"), """// adds
int add(int a, int b) { return a + b; }
int main() { return add(2, 2) == 4 ? 0 : 1; }
""")
write(os.path.join(src, "other_test.cc"), """// twice
// twice
int main() { return 0; }
""")
write(os.path.join(src, "slow.txt"), "marker\n")
write(os.path.join(src, "tests", "mutations", "mini.txt"), """# the miniature project's mutations
@@ mutation sum-becomes-difference
file: adder_test.cc
tests: ^mini\\.adds$
about: add subtracts
<<< original
int add(int a, int b) { return a + b; }
=== replacement
int add(int a, int b) { return a - b; }
>>>

@@ mutation comment-only
file: adder_test.cc
tests: ^mini\\.adds$
about: a comment changes, which no test can see
<<< original
// adds
=== replacement
// sums
>>>

@@ mutation text-gone
file: adder_test.cc
tests: ^mini\\.adds$
about: this text is not in the file
<<< original
int add(int a, int b) { return a * b; }
=== replacement
int add(int a, int b) { return 0; }
>>>

@@ mutation text-twice
file: other_test.cc
tests: ^mini\\.other$
about: this text occurs twice
<<< original
// twice
=== replacement
// once
>>>

@@ mutation no-such-test
file: other_test.cc
tests: ^mini\\.nothing$
about: the regex names no test
<<< original
int main() { return 0; }
=== replacement
int main() { return 1; }
>>>
""")
before = snapshot(src)

# --list: says which specs still apply, builds nothing.
listed = subprocess.run([TOOL, "--source", src, "--scratch", scratch, "--list"],
                        capture_output=True, text=True)
check(listed.returncode == 1, "--list exits 1 when a spec no longer applies")
check("text-gone" in listed.stdout and "no longer applies" in listed.stdout,
      "--list reports the absent text")
check("text-twice" in listed.stdout and "ambiguous" in listed.stdout, "--list reports ambiguity")
check(not os.path.exists(scratch), "--list builds nothing")

# A full run.
full = subprocess.run([TOOL, "--source", src, "--scratch", scratch, "--jobs", "2"],
                      capture_output=True, text=True)
out = full.stdout
print(out + full.stderr)
check(full.returncode == 1, "exit status 1 when a mutation is not caught or does not apply")
lines = {line.split()[0]: line for line in out.splitlines() if line.strip()}
check("mini.adds" in lines.get("sum-becomes-difference", ""), "caught mutation names mini.adds")
check("NOT CAUGHT" in lines.get("comment-only", ""), "comment-only is NOT CAUGHT")
check("NO LONGER APPLIES" in lines.get("text-gone", ""), "absent text: NO LONGER APPLIES")
check("AMBIGUOUS" in lines.get("text-twice", ""), "repeated text: AMBIGUOUS")
check("NO TESTS" in lines.get("no-such-test", ""), "regex matching nothing: NO TESTS")
check("mini.other" not in lines.get("sum-becomes-difference", ""), "only the named tests ran")
check("1 of 5 mutations caught" in out, "summary line")
check(snapshot(src) == before, "the source tree is untouched (bytes and time stamps)")
with open(os.path.join(scratch, "src", "adder_test.cc")) as f:
    check("return a + b;" in f.read(), "the scratch copy is reverted after the run")

# Only the caught mutation: exit 0.
only = subprocess.run([TOOL, "--source", src, "--scratch", scratch, "--only",
                       "sum-becomes-difference"], capture_output=True, text=True)
check(only.returncode == 0, "exit 0 when every selected mutation is caught")

# A malformed spec is refused naming file and line.
bad = os.path.join(WORK, "bad.txt")
write(bad, "@@ mutation broken\nfile: adder_test.cc\ntests: x\n<<< original\nfoo\n>>>\n")
refused = subprocess.run([TOOL, "--source", src, "--scratch", scratch, bad],
                         capture_output=True, text=True)
check(refused.returncode == 2, "malformed spec: exit 2")
check(bad + ":" in refused.stderr and "broken" in refused.stderr, "malformed spec: names file and mutation")

# Interrupted while a mutant's (slow) test runs: the mutant is reverted, the
# test is stopped, exit 130.
slow_spec = os.path.join(WORK, "slow.txt")
write(slow_spec, """@@ mutation slow
file: slow.txt
tests: ^mini\\.slow$
about: waits for the interruption
<<< original
marker
=== replacement
mutant
>>>
""")
proc = subprocess.Popen([TOOL, "--source", src, "--scratch", scratch, "--no-baseline", slow_spec],
                        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
scratch_marker = os.path.join(scratch, "src", "slow.txt")
deadline = time.time() + 60
mutated = False
while time.time() < deadline and not mutated:
    time.sleep(0.2)
    with open(scratch_marker) as f:
        mutated = f.read() == "mutant\n"
def sleeping():
    found = subprocess.run(["pgrep", "-f", "--", "sleep " + SLEEP], capture_output=True, text=True)
    return found.stdout.strip() != ""


deadline = time.time() + 30
while time.time() < deadline and not sleeping():
    time.sleep(0.2)
check(sleeping(), "the mutant's slow test is running")
proc.send_signal(signal.SIGINT)
try:
    output = proc.communicate(timeout=30)[0]
except subprocess.TimeoutExpired:
    proc.kill()
    output = proc.communicate()[0]
print(output)
check(mutated, "the slow mutation was applied")
check(proc.returncode == 130, "interrupted: exit 130 (got %s)" % proc.returncode)
with open(scratch_marker) as f:
    check(f.read() == "marker\n", "interrupted: the mutation is reverted")
time.sleep(0.5)
check(not sleeping(), "interrupted: the running test was stopped")
check(snapshot(src) == before, "interrupted: the source tree is untouched")

shutil.rmtree(WORK, ignore_errors=True)
print("%d checks failed" % len(failures))
sys.exit(1 if failures else 0)
