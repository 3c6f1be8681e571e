"""A job running in another thread when the interpreter exits, or when
Ctrl-C reaches the main thread, ends with the process: never with
"terminate called without an active exception" (SIGABRT). It did in 7 of 12
exits and 4 of 30 Ctrl-Cs: the thread took the GIL back while the
interpreter was finalizing, from a destructor. Each case runs 20 times, each
in a process of its own."""
import os
import signal
import subprocess
import sys
import textwrap

import pytest

REPEATS = 20

# short runs one after the other in a daemon thread, left running when the
# main thread ends: the interpreter exits while a run is going on or ending
EXIT_WHILE_RUNNING = textwrap.dedent("""
    import os, signal, threading, time
    import impactlab
    def simulate_forever():
        while True:
            impactlab.simulate("jin2003", periods=20)
    threading.Thread(target=simulate_forever, daemon=True).start()
    time.sleep(0.2)
""")

# the same runs, and Ctrl-C (SIGINT) to the main thread while they go on
CTRL_C_WHILE_RUNNING = EXIT_WHILE_RUNNING + textwrap.dedent("""
    os.kill(os.getpid(), signal.SIGINT)
    time.sleep(10)
""")


def run_script(script):
    return subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=60, env=os.environ.copy(), check=False)


@pytest.mark.parametrize("attempt", range(REPEATS))
def test_interpreter_exit_while_a_thread_simulates(attempt):
    completed = run_script(EXIT_WHILE_RUNNING)
    assert "terminate called" not in completed.stderr, completed.stderr
    assert completed.returncode == 0, (completed.returncode, completed.stderr)


@pytest.mark.parametrize("attempt", range(REPEATS))
def test_ctrl_c_while_a_thread_simulates(attempt):
    completed = run_script(CTRL_C_WHILE_RUNNING)
    assert "terminate called" not in completed.stderr, completed.stderr
    # KeyboardInterrupt ends the interpreter as SIGINT would (status -2)
    assert completed.returncode == -signal.SIGINT, (completed.returncode, completed.stderr)
    assert "KeyboardInterrupt" in completed.stderr, completed.stderr
