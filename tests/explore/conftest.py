"""Shared fixtures of the explorer's tests: `impactlab explore` started as a
subprocess on a free port (IMPACTLAB_CLI, set by CTest), its address and
token read from the line it prints, and requests made with http.client."""
import http.client
import json
import os
import re
import subprocess
import urllib.parse

import pytest


def cli_binary():
    binary = os.environ.get("IMPACTLAB_CLI")
    if not binary:
        pytest.fail("IMPACTLAB_CLI is not set (CTest sets it to the impactlab binary)")
    return binary


def server_environment():
    """The server's environment. Under AddressSanitizer (scripts/test.sh
    --sanitize exports ASAN_OPTIONS) the server runs without the allocator's
    quarantine, which holds every freed block back (256 MB by default), so
    that its resident size measures what it keeps, as the peak-memory tests
    of tests/io/output_test.cpp do."""
    environment = dict(os.environ)
    if "ASAN_OPTIONS" in environment:
        environment["ASAN_OPTIONS"] += ":quarantine_size_mb=0"
    return environment


class Explorer:
    """A running `impactlab explore`: its url, port and token."""

    def __init__(self, scene="jin2003"):
        self.process = subprocess.Popen([cli_binary(), "explore", scene, "--port", "0"],
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                        env=server_environment())
        for line in self.process.stdout:
            match = re.search(r"(http://127\.0\.0\.1:(\d+)/\?token=([0-9a-f]+))", line)
            if match:
                self.url, self.port, self.token = match.group(1), int(match.group(2)), match.group(3)
                break
        else:
            raise RuntimeError("explore printed no address: " + self.process.stderr.read())

    def request(self, method, path, body=None, headers=None, token=True, timeout=30):
        """(status, parsed JSON or text, response headers) of one request."""
        connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=timeout)
        sent = {"Host": "127.0.0.1:{}".format(self.port)}
        if token is True:
            sent["Authorization"] = "token " + self.token
        sent.update(headers or {})
        data = None
        if body is not None:
            data = body if isinstance(body, (bytes, str)) else json.dumps(body)
            sent["Content-Type"] = "application/json"
        connection.request(method, path, body=data, headers=sent)
        response = connection.getresponse()
        text = response.read().decode("utf-8", "replace")
        connection.close()
        try:
            parsed = json.loads(text)
        except ValueError:
            parsed = text
        return response.status, parsed, dict(response.getheaders())

    def job(self, kind, values=None, options=None, timeout=120):
        """A view's job run to its end: its last state (result or error)."""
        status, started, _ = self.request("POST", "/api/jobs",
                                          {"kind": kind, "values": values or {},
                                           "options": options or {}})
        assert status == 202, started
        items = []
        while True:
            status, state, _ = self.request(
                "GET", "/api/jobs/{}?from={}&wait=1000".format(started["id"], len(items)))
            assert status == 200, state
            items.extend(state["items"])
            if state["state"] != "running":
                state["all_items"] = items
                return state

    def stop(self):
        self.process.terminate()
        self.process.wait(timeout=10)


@pytest.fixture(scope="module")
def explorer():
    server = Explorer()
    yield server
    server.stop()


def cli_refusal(*arguments):
    """The one line `impactlab ARGS` prints for bad input, without its prefix."""
    completed = subprocess.run([cli_binary(), *arguments], capture_output=True, text=True)
    assert completed.returncode == 2, completed.stderr
    line = completed.stderr.strip().splitlines()[-1]
    assert line.startswith("impactlab: ")
    return line[len("impactlab: "):]


def quoted(path):
    return urllib.parse.quote(path, safe="")
