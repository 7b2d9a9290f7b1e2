"""A Ray cluster of several nodes on this one machine (`ray start --block`, each node in a
session of its own), for the cluster test and for timing a plan on one node against two.
Stopping it touches no other Ray on the machine."""
import os
import secrets
import signal
import socket
import subprocess
import sys
import time


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class LocalCluster:
    def __init__(self, cpus_per_node, logs):
        """`cpus_per_node`: one entry per node (the first is the head); logs: a folder."""
        self.cpus, self.logs = list(cpus_per_node), logs
        self.port = _free_port()
        self.address = f"127.0.0.1:{self.port}"
        self.temp = os.path.join("/tmp", f"bmfr-ray-{os.getpid()}-{self.port}")  # Ray's
        # sockets live under it, and a socket path may not be long
        # Token authentication, as a real cluster has it: every node and driver needs `env`.
        self.env = dict(os.environ, RAY_AUTH_MODE="token", RAY_AUTH_TOKEN=secrets.token_hex(16))
        self.ray = os.path.join(os.path.dirname(sys.executable), "ray")
        self.nodes = []

    def __enter__(self):
        try:
            self.start()
        except BaseException:
            self.stop()
            raise
        return self

    def __exit__(self, *_):
        self.stop()

    def start(self):
        os.makedirs(self.logs, exist_ok=True)
        for i, cpus in enumerate(self.cpus):
            argv = [self.ray, "start", "--num-cpus", str(cpus), "--block", "--disable-usage-stats"]
            if i == 0:
                argv += ["--head", "--port", str(self.port), "--include-dashboard", "false",
                         "--temp-dir", self.temp]
            else:
                argv += ["--address", self.address]
            log = open(os.path.join(self.logs, f"node{i}.log"), "w")
            self.nodes.append(subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT,
                                               start_new_session=True, env=self.env))
            self._wait_nodes(i + 1)

    def _wait_nodes(self, count):
        probe = (f"import ray, time\nray.init(address='{self.address}', logging_level='ERROR')\n"
                 "t = time.monotonic()\n"
                 f"while len([n for n in ray.nodes() if n['Alive']]) < {count}:\n"
                 "    assert time.monotonic() - t < 60, 'nodes did not join'\n"
                 "    time.sleep(0.5)\n")
        for _ in range(30):
            if any(p.poll() is not None for p in self.nodes):
                raise RuntimeError(f"a Ray node exited at start: see {self.logs}/node*.log")
            try:
                if subprocess.run([sys.executable, "-c", probe], capture_output=True, timeout=90,
                                  env=self.env).returncode == 0:
                    return
            except subprocess.TimeoutExpired:
                pass
            time.sleep(1)
        raise RuntimeError(f"the cluster did not reach {count} node(s): see {self.logs}")

    def stop(self):
        for p in reversed(self.nodes):
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGTERM)
        for p in self.nodes:
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
        # What the nodes started in sessions of their own: found by the session folder.
        for pid in os.listdir("/proc"):
            if not pid.isdigit() or int(pid) == os.getpid():
                continue
            try:
                with open(f"/proc/{pid}/cmdline", "rb") as f:
                    if self.temp.encode() in f.read():
                        os.kill(int(pid), signal.SIGKILL)
            except OSError:
                pass
        self.nodes = []
        subprocess.run(["rm", "-rf", self.temp], check=False)
