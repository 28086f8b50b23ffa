"""JupyterHub for one server: every student gets a Jupyter server with the course.

Run it from the repository root (the hub and the students' servers in the Python
environment where halfedge_edu[notebooks], jupyterhub and jupyter-server-proxy are
installed; configurable-http-proxy from npm on PATH):

    jupyterhub -f deploy/jupyterhub/jupyterhub_config.py

As written it is the test setup: the hub on 127.0.0.1, any user name with the shared
password $HALFEDGE_HUB_PASSWORD (DummyAuthenticator), and every student's server
started as the hub's own user in /tmp/halfedge-hub/NAME (SimpleLocalProcessSpawner).

For a real class on one server (docs/deploying.md has the whole recipe):

- HALFEDGE_HUB_SPAWNER=systemdspawner.SystemdSpawner (pip install
  jupyterhub-systemdspawner; what The Littlest JupyterHub uses; needs systemd as the
  machine's init): each student's server is a systemd unit run as a *dynamic* user
  (``dynamic_users`` below), so students need no Unix account, and the memory and CPU
  limits below are enforced with cgroups. The local-process spawners only pass the
  limits on as MEM_LIMIT and CPU_LIMIT (shown in the Lab's resource indicator), they do
  not enforce them.
- a real authenticator instead of the dummy one;
- HALFEDGE_HUB_IP=0.0.0.0 only behind TLS: either the hub's own
  (HALFEDGE_HUB_SSL_CERT and HALFEDGE_HUB_SSL_KEY, port 443) or a reverse proxy
  (nginx, Caddy) that terminates TLS and forwards to 127.0.0.1:8000. Never plain HTTP on
  a public address: the shared password and every student's token would cross it.

Idle servers and kernels are stopped (memory is what a class runs out of):
jupyterhub-idle-culler stops a student's server idle for HALFEDGE_HUB_CULL_SECONDS
(default 3600), and each server shuts down a kernel idle for
HALFEDGE_HUB_KERNEL_CULL_SECONDS (default 1200) even while its tab is open: JupyterLab
keeps a chapter's kernel when its tab closes, and each one holds 300-500 MiB.

Every student's server starts through deploy/singleuser-start.sh, which sets the live
3D view's environment and copies the chapters into ~/course (halfedge-edu course).
"""

import os
import sys
from pathlib import Path

c = get_config()  # noqa: F821 (JupyterHub provides get_config when it loads this file)

DEPLOY = Path(__file__).resolve().parents[1]
# The hub's database, cookie secret and (with the test spawner) the students' homes.
STATE = Path(os.environ.get("HALFEDGE_HUB_STATE", "/tmp/halfedge-hub"))
STATE.mkdir(parents=True, exist_ok=True)

c.JupyterHub.ip = os.environ.get("HALFEDGE_HUB_IP", "127.0.0.1")
c.JupyterHub.port = int(os.environ.get("HALFEDGE_HUB_PORT", "8000"))
c.JupyterHub.hub_ip = "127.0.0.1"
# The hub's own API and the proxy's API (defaults 8081 and port + 1): the benchmark
# starts several hubs one after the other and gives each free ports.
c.JupyterHub.hub_port = int(os.environ.get("HALFEDGE_HUB_INTERNAL_PORT", "8081"))
c.ConfigurableHTTPProxy.api_url = f"http://127.0.0.1:{os.environ.get('HALFEDGE_HUB_PROXY_API_PORT', c.JupyterHub.port + 1)}"
c.JupyterHub.cookie_secret_file = str(STATE / "cookie_secret")
c.JupyterHub.db_url = f"sqlite:///{STATE / 'jupyterhub.sqlite'}"

c.JupyterHub.authenticator_class = "dummy"
c.DummyAuthenticator.password = os.environ.get("HALFEDGE_HUB_PASSWORD", "halfedge")
c.Authenticator.allow_all = True

c.JupyterHub.spawner_class = os.environ.get("HALFEDGE_HUB_SPAWNER", "simple")
c.SimpleLocalProcessSpawner.home_dir_template = str(STATE / "{username}")
c.Spawner.cmd = [str(DEPLOY / "singleuser-start.sh"), "jupyterhub-singleuser"]
c.Spawner.default_url = "/lab/tree/course"
# The test spawner runs servers as the hub's own user; when that is root (a container,
# CI), Jupyter refuses to start without this. SystemdSpawner's students are never root.
# Kernels talk to their server over Unix sockets, not TCP ports: on one machine, servers
# that start kernels at the same moment each pick "free" TCP ports and can pick the same
# ones (measured: 10 students starting at once failed twice in a row, "Address already
# in use" and a kernel that never answered). Sockets in each user's runtime folder
# cannot collide. (Zero to JupyterHub and Binder run one server per container.)
c.Spawner.args = ["--KernelManager.transport=ipc"]
if c.JupyterHub.spawner_class == "simple" and os.geteuid() == 0:
    c.Spawner.args = [*c.Spawner.args, "--ServerApp.allow_root=True"]
# Kernel culling in each student's server: a kernel with nothing running for this long is
# shut down, connected (its tab open) or not; checked every tenth of that (at least 1 s).
KERNEL_CULL_SECONDS = int(os.environ.get("HALFEDGE_HUB_KERNEL_CULL_SECONDS", "1200"))
c.Spawner.args = [
    *c.Spawner.args,
    f"--MappingKernelManager.cull_idle_timeout={KERNEL_CULL_SECONDS}",
    f"--MappingKernelManager.cull_interval={max(1, KERNEL_CULL_SECONDS // 10)}",
    "--MappingKernelManager.cull_connected=True",
    "--MappingKernelManager.cull_busy=False",
]

# Students with no Unix account: SystemdSpawner runs each server as a dynamic user
# (systemd's DynamicUser=yes), with its home in /var/lib/private/ (StateDirectory), kept
# between sessions. isolate_tmp and isolate_devices keep students out of each other's
# /tmp and of the machine's devices.
if "systemdspawner" in c.JupyterHub.spawner_class.lower():
    c.SystemdSpawner.dynamic_users = True
    c.SystemdSpawner.isolate_tmp = True
    c.SystemdSpawner.isolate_devices = True
    c.SystemdSpawner.disable_user_sudo = True

# TLS on the hub itself, when it faces the network without a reverse proxy.
if os.environ.get("HALFEDGE_HUB_SSL_CERT"):
    c.JupyterHub.ssl_cert = os.environ["HALFEDGE_HUB_SSL_CERT"]
    c.JupyterHub.ssl_key = os.environ["HALFEDGE_HUB_SSL_KEY"]
# Measured (issue 14, benchmarks/bench_class.py, PSS after chapter 03): with the views
# drawn in the browser (the default) about 350-380 MiB per student, server plus kernel,
# and nothing while a student rotates a view; with HALFEDGE_EDU_LIVE_BACKEND=server
# 450-490 MiB and up to a core while dragging. With three chapters' kernels open
# (benchmarks/bench_chapters_open.py, issue 27) 812-846 MiB at N = 5-20: the guarantee,
# which Kubernetes places students by, is that, so a node never holds more students than
# fit when each has three chapters open (docs/deploying.md, "Sizing").
c.Spawner.mem_limit = "1G"
c.Spawner.mem_guarantee = "850M"
c.Spawner.cpu_limit = 1.0
c.Spawner.cpu_guarantee = 0.25
c.Spawner.start_timeout = 120
c.Spawner.http_timeout = 120

# The live 3D view for everyone: deploy/singleuser-start.sh makes it "client" (vtk.js
# draws in the browser); HALFEDGE_EDU_LIVE_BACKEND=server in the hub's environment gives
# everyone the kernel-rendered view instead (labels drawn; more memory and CPU). See
# docs/deploying.md.
if "HALFEDGE_EDU_LIVE_BACKEND" in os.environ:
    c.Spawner.environment = {"HALFEDGE_EDU_LIVE_BACKEND": os.environ["HALFEDGE_EDU_LIVE_BACKEND"]}

# The idle-server culler, run by the hub as a service with only the rights it needs.
CULL_SECONDS = int(os.environ.get("HALFEDGE_HUB_CULL_SECONDS", "3600"))
c.JupyterHub.services = [{
    "name": "idle-culler",
    "command": [sys.executable, "-m", "jupyterhub_idle_culler", f"--timeout={CULL_SECONDS}",
                f"--cull-every={max(10, CULL_SECONDS // 10)}"],
}]
c.JupyterHub.load_roles = [{
    "name": "idle-culler",
    "scopes": ["list:users", "read:users:activity", "read:servers", "delete:servers"],
    "services": ["idle-culler"],
}]

# An admin token for scripts (benchmarks/bench_class.py): start and stop servers, and
# reach them (run a chapter in a student's kernel). Only when the variable is set.
if os.environ.get("HALFEDGE_HUB_API_TOKEN"):
    c.JupyterHub.services.append({"name": "class-admin", "api_token": os.environ["HALFEDGE_HUB_API_TOKEN"]})
    c.JupyterHub.load_roles.append({
        "name": "class-admin",
        "scopes": ["admin:users", "admin:servers", "access:servers", "list:users", "read:users"],
        "services": ["class-admin"],
    })
