"""The deployment recipes (deploy/, binder/) parse and agree with each other and the Makefile.

They cannot all be run here (no Docker, no Kubernetes, no Binder): each file is parsed
(Python, YAML, Dockerfile instructions, shell), the one script they share is run for
real, and the settings every recipe repeats (limits, packages, environment) are compared.
hadolint is not installable from the registries this project uses (its PyPI wrappers
download the binary at run time), so the Dockerfile check is the instruction parse below.
"""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import yaml
from traitlets.config import Config

ROOT = Path(__file__).resolve().parents[1]
START = ROOT / "deploy" / "singleuser-start.sh"
HUB_CONFIG = ROOT / "deploy" / "jupyterhub" / "jupyterhub_config.py"
VALUES = yaml.safe_load((ROOT / "deploy" / "z2jh" / "values.yaml").read_text())
DOCKERFILE = (ROOT / "deploy" / "z2jh" / "Dockerfile").read_text()
MAKEFILE = (ROOT / "Makefile").read_text()
LOCK = re.search(r"^SEMESTER \?= (\S+)$", MAKEFILE, flags=re.M).group(1)
DOCKER_INSTRUCTIONS = {
    "FROM", "RUN", "CMD", "LABEL", "EXPOSE", "ENV", "ADD", "COPY", "ENTRYPOINT", "VOLUME",
    "USER", "WORKDIR", "ARG", "ONBUILD", "STOPSIGNAL", "HEALTHCHECK", "SHELL",
}


def hub_config(tmp_path: Path) -> Config:
    """deploy/jupyterhub/jupyterhub_config.py loaded as JupyterHub loads it."""
    config = Config()
    namespace = {"get_config": lambda: config, "__file__": str(HUB_CONFIG)}
    previous = os.environ.get("HALFEDGE_HUB_STATE")
    os.environ["HALFEDGE_HUB_STATE"] = str(tmp_path / "hub")
    try:
        exec(compile(HUB_CONFIG.read_text(), str(HUB_CONFIG), "exec"), namespace)
    finally:
        if previous is None:
            del os.environ["HALFEDGE_HUB_STATE"]
        else:
            os.environ["HALFEDGE_HUB_STATE"] = previous
    return config


def docker_instructions() -> list[tuple[str, str]]:
    """(INSTRUCTION, arguments) of the Dockerfile, continuation lines joined, comments dropped."""
    logical, current = [], ""
    for line in DOCKERFILE.splitlines():
        if not current and (not line.strip() or line.lstrip().startswith("#")):
            continue
        current += line.rstrip("\\").strip() + " "
        if not line.rstrip().endswith("\\"):
            logical.append(current.strip())
            current = ""
    assert not current, "the Dockerfile ends inside a continued line"
    return [tuple(line.split(None, 1)) for line in logical]


def gib(text: str) -> float:
    number, unit = re.fullmatch(r"([\d.]+)([MG])", text).groups()
    return float(number) / (1024 if unit == "M" else 1)


# What deploy/singleuser-start.sh sets for a student's kernel's memory and CPU (see its comments).
MEMORY_SETTINGS = {"HALFEDGE_EDU_LIVE_BACKEND": "client", "MALLOC_MMAP_THRESHOLD_": "131072",
                   "MALLOC_TRIM_THRESHOLD_": "131072", "LP_NUM_THREADS": "1"}


def run_start_script(home: Path, **preset: str) -> dict:
    """The environment a command started through deploy/singleuser-start.sh sees, plus the
    live view's address prefix pyvista builds (``view_prefix``)."""
    env = {key: value for key, value in os.environ.items()
           if not key.startswith(("PYVISTA_", "VTK_", "HALFEDGE_EDU_", "JUPYTER_RUNTIME")) and key not in MEMORY_SETTINGS}
    env.update(HOME=str(home), JUPYTERHUB_SERVICE_PREFIX="/user/ann/",
               PATH=os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", ""), **preset)
    result = subprocess.run(
        [str(START), sys.executable, "-c", "import json, os, pyvista; print(json.dumps(dict(os.environ, "
         "view_prefix=pyvista.global_theme.trame.server_proxy_prefix)))"],
        capture_output=True, text=True, env=env, timeout=120,
    )
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout.splitlines()[-1])


def test_shared_start_script_sets_the_live_environment_and_copies_the_course(tmp_path):
    started = run_start_script(tmp_path)
    # The prefix the live view's address is built with: the user's own, once.
    assert started.pop("view_prefix") == "/user/ann/proxy/"
    assert started["VTK_DEFAULT_OPENGL_WINDOW"] == re.search(r"VTK_DEFAULT_OPENGL_WINDOW=(\S+)", MAKEFILE).group(1)
    wasm = Path(started["VTK_WASM_DIR_OVERRIDE"])
    assert wasm.is_dir() and not any(wasm.iterdir())
    assert "PYVISTA_JUPYTER_BACKEND" not in started, "a hub keeps the live view (static is for CI)"
    assert len(list((tmp_path / "course").glob("[0-9][0-9]*_*.ipynb"))) == len(list((ROOT / "notebooks").glob("[0-9][0-9]*_*.ipynb")))
    assert {name: started[name] for name in MEMORY_SETTINGS} == MEMORY_SETTINGS


def test_start_script_brings_errata_to_a_course_copied_by_an_older_version(tmp_path):
    course = tmp_path / "course"
    run_start_script(tmp_path)
    chapter = sorted(course.glob("[0-9][0-9]*_*.ipynb"))[0]
    notebook = json.loads(chapter.read_text(encoding="utf-8"))
    notebook["metadata"]["halfedge_edu"]["course"]["version"] = "0.0.1"   # copied by an older release
    chapter.write_text(json.dumps(notebook), encoding="utf-8")
    run_start_script(tmp_path)
    updated = json.loads(chapter.read_text(encoding="utf-8"))["metadata"]["halfedge_edu"]["course"]["version"]
    assert updated != "0.0.1"


def test_start_script_puts_the_kernels_sockets_where_a_long_home_cannot_push_them_past_107_bytes(tmp_path):
    home = tmp_path / ("a-student-with-a-long-name-" * 3)
    home.mkdir()
    env = run_start_script(home)
    runtime = Path(env["JUPYTER_RUNTIME_DIR"])
    assert runtime.is_dir() and not str(runtime).startswith(str(home))
    assert len(f"{runtime}/kernel-{'0' * 8}-{'0' * 4}-{'0' * 4}-{'0' * 4}-{'0' * 12}-ipc-1") <= 107
    assert oct(runtime.stat().st_mode & 0o777) == "0o700"


def test_start_script_keeps_memory_settings_the_hub_already_chose(tmp_path):
    chosen = {"HALFEDGE_EDU_LIVE_BACKEND": "server", "LP_NUM_THREADS": "2", "MALLOC_MMAP_THRESHOLD_": "262144"}
    started = run_start_script(tmp_path, **chosen)
    assert {name: started[name] for name in chosen} == chosen
    assert started["MALLOC_TRIM_THRESHOLD_"] == MEMORY_SETTINGS["MALLOC_TRIM_THRESHOLD_"]


def test_start_script_sets_the_makefiles_variables_and_the_proxy_prefix():
    exported = set(re.findall(r"^export (\w+)=", START.read_text(), flags=re.M)) - set(MEMORY_SETTINGS)
    makefile_variables = set(re.findall(r"\b(VTK_\w+|PYVISTA_\w+)=", MAKEFILE))
    # Every headless/lab variable of the Makefile except the CI-only static backend.
    assert exported == makefile_variables - {"PYVISTA_JUPYTER_BACKEND"} | {"PYVISTA_TRAME_SERVER_PROXY_PREFIX"}
    deploying = (ROOT / "docs" / "deploying.md").read_text()
    assert all(f"`{name}`" in deploying for name in exported | set(MEMORY_SETTINGS)), "docs/deploying.md documents every variable"


def test_local_hub_config_starts_students_through_the_shared_script(tmp_path):
    config = hub_config(tmp_path)
    assert config.JupyterHub.ip == "127.0.0.1"
    assert config.JupyterHub.authenticator_class == "dummy"
    assert config.JupyterHub.spawner_class == "simple"
    command = config.Spawner.cmd
    assert Path(command[0]) == START and os.access(command[0], os.X_OK)
    assert command[1:] == ["jupyterhub-singleuser"]
    assert (tmp_path / "hub").is_dir()
    # Without the variables below, no API token (only the culler's service) and the
    # package's own live view.
    assert [service["name"] for service in config.JupyterHub.services] == ["idle-culler"]
    assert "environment" not in config.Spawner


def test_local_hub_config_passes_the_live_backend_on_and_takes_an_admin_token(tmp_path, monkeypatch):
    monkeypatch.setenv("HALFEDGE_EDU_LIVE_BACKEND", "client")
    monkeypatch.setenv("HALFEDGE_HUB_API_TOKEN", "secret-of-the-script")
    monkeypatch.setenv("HALFEDGE_HUB_INTERNAL_PORT", "18081")
    config = hub_config(tmp_path)
    assert config.Spawner.environment == {"HALFEDGE_EDU_LIVE_BACKEND": "client"}
    [service] = [service for service in config.JupyterHub.services if service["name"] != "idle-culler"]
    assert service["api_token"] == "secret-of-the-script"
    [role] = [role for role in config.JupyterHub.load_roles if role["name"] != "idle-culler"]
    assert role["services"] == [service["name"]]
    assert {"admin:servers", "access:servers"} <= set(role["scopes"])
    assert config.JupyterHub.hub_port == 18081


def server_options(config: Config) -> dict[str, str]:
    """The ``--Class.trait=value`` options the hub passes to every student's server."""
    return dict(arg[2:].split("=", 1) for arg in config.Spawner.args if arg.startswith("--") and "=" in arg)


def test_idle_servers_are_culled_by_the_hubs_culler_service(tmp_path, monkeypatch):
    monkeypatch.setenv("HALFEDGE_HUB_CULL_SECONDS", "1800")
    config = hub_config(tmp_path)
    [culler] = [service for service in config.JupyterHub.services if service["name"] == "idle-culler"]
    assert culler["command"][1:3] == ["-m", "jupyterhub_idle_culler"] and "--timeout=1800" in culler["command"]
    [role] = [role for role in config.JupyterHub.load_roles if role["name"] == "idle-culler"]
    assert role["services"] == ["idle-culler"]
    assert {"list:users", "read:users:activity", "read:servers", "delete:servers"} == set(role["scopes"])
    import jupyterhub_idle_culler  # noqa: F401  (the hub extra installs it: the command runs)


def test_idle_kernels_are_culled_even_with_their_tab_open(tmp_path, monkeypatch):
    options = server_options(hub_config(tmp_path))
    assert options["MappingKernelManager.cull_idle_timeout"] == "1200"
    assert options["MappingKernelManager.cull_connected"] == "True"
    monkeypatch.setenv("HALFEDGE_HUB_KERNEL_CULL_SECONDS", "30")
    options = server_options(hub_config(tmp_path))
    assert options["MappingKernelManager.cull_idle_timeout"] == "30"
    assert options["MappingKernelManager.cull_interval"] == "3"


def test_systemd_spawner_runs_students_as_dynamic_users(tmp_path, monkeypatch):
    monkeypatch.setenv("HALFEDGE_HUB_SPAWNER", "systemdspawner.SystemdSpawner")
    config = hub_config(tmp_path)
    assert config.SystemdSpawner.dynamic_users is True
    assert config.SystemdSpawner.isolate_tmp is True and config.SystemdSpawner.isolate_devices is True
    assert "--ServerApp.allow_root=True" not in config.Spawner.args


def test_the_hub_takes_tls_and_a_public_address_only_when_told(tmp_path, monkeypatch):
    assert hub_config(tmp_path).JupyterHub.ip == "127.0.0.1" and "ssl_cert" not in hub_config(tmp_path).JupyterHub
    monkeypatch.setenv("HALFEDGE_HUB_IP", "0.0.0.0")
    monkeypatch.setenv("HALFEDGE_HUB_SSL_CERT", "/etc/letsencrypt/live/hub/fullchain.pem")
    monkeypatch.setenv("HALFEDGE_HUB_SSL_KEY", "/etc/letsencrypt/live/hub/privkey.pem")
    config = hub_config(tmp_path)
    assert config.JupyterHub.ip == "0.0.0.0"
    assert config.JupyterHub.ssl_cert.endswith("fullchain.pem") and config.JupyterHub.ssl_key.endswith("privkey.pem")


def test_kubernetes_values_cull_servers_and_kernels_like_the_local_hub(tmp_path):
    config = hub_config(tmp_path)
    assert VALUES["cull"]["enabled"] is True
    [culler] = [service for service in config.JupyterHub.services if service["name"] == "idle-culler"]
    assert f"--timeout={VALUES['cull']['timeout']}" in culler["command"]
    kernels = VALUES["singleuser"]["extraFiles"]["kernel-culling"]
    assert kernels["mountPath"].startswith("/etc/jupyter/jupyter_server_config.d/") and kernels["mountPath"].endswith(".json")
    options = server_options(config)
    for name, value in kernels["data"]["MappingKernelManager"].items():
        if name != "cull_interval":
            assert str(value).lower() == options[f"MappingKernelManager.{name}"].lower(), name


def test_kubernetes_values_have_the_local_hubs_limits(tmp_path):
    config = hub_config(tmp_path)
    single = VALUES["singleuser"]
    assert gib(single["memory"]["limit"]) == gib(config.Spawner.mem_limit)
    assert gib(single["memory"]["guarantee"]) == gib(config.Spawner.mem_guarantee)
    assert single["cpu"]["limit"] == config.Spawner.cpu_limit
    assert single["cpu"]["guarantee"] == config.Spawner.cpu_guarantee
    assert single["defaultUrl"] == config.Spawner.default_url
    assert single["cmd"] == config.Spawner.cmd[1]
    assert single["image"]["tag"] == LOCK


def test_dockerfile_parses_and_installs_the_package_like_binder():
    instructions = docker_instructions()
    unknown = [name for name, _ in instructions if name.upper() not in DOCKER_INSTRUCTIONS or name != name.upper()]
    assert not unknown, f"not Dockerfile instructions: {unknown}"
    assert instructions[0][0] == "FROM"
    by_name = {}
    for name, arguments in instructions:
        by_name.setdefault(name, []).append(arguments)
    assert json.loads(by_name["ENTRYPOINT"][-1]) == ["/usr/local/bin/singleuser-start.sh"]
    assert json.loads(by_name["CMD"][-1]) == [VALUES["singleuser"]["cmd"]]
    runs = " ".join(by_name["RUN"])
    apt = set((ROOT / "binder" / "apt.txt").read_text().split())
    assert apt == {"libgl1", "libegl1"} and all(package in shlex.split(runs) for package in apt)
    assert f"constraints/{LOCK}.txt" in runs and (ROOT / "constraints" / f"{LOCK}.txt").exists()
    assert '"$(ls /tmp/wheel/halfedge_edu-*.whl)[notebooks]"' in runs and " -e " not in runs, \
        "the wheel with the notebooks extra, not editable"
    python = re.match(r"python:(\d+\.\d+)", by_name["FROM"][0]).group(1)
    assert (ROOT / "binder" / "runtime.txt").read_text().strip() == f"python-{python}"


def test_the_image_keeps_no_build_context_and_pins_the_charts_jupyterhub():
    stages = re.split(r"^FROM ", DOCKERFILE, flags=re.M)[1:]
    assert len(stages) == 2 and stages[0].startswith("python:3.11-slim AS wheel")
    final = stages[1]
    copies = re.findall(r"^COPY (.*)$", final, flags=re.M)
    assert copies == ["--chmod=755 deploy/singleuser-start.sh /usr/local/bin/singleuser-start.sh"], copies
    assert "--mount=type=bind,from=wheel" in final
    chart = re.search(r"helm upgrade .*--version (\d+\.\d+\.\d+)", (ROOT / "deploy" / "z2jh" / "values.yaml").read_text())
    assert chart, "values.yaml names the chart version to install"
    hub = re.search(r'"jupyterhub==(\d+\.\d+\.\d+)"', final).group(1)
    assert f"chart {chart.group(1)}: JupyterHub {hub}" in final
    ignore = (ROOT / ".dockerignore").read_text().split()
    assert ignore[ignore.index("*") + 1:] and "!notebooks/student/" in ignore and "!notebooks/" not in ignore


def test_binder_installs_the_notebooks_extra_non_editable_and_starts_through_the_script():
    post_build = (ROOT / "binder" / "postBuild").read_text()
    installs = [shlex.split(line) for line in post_build.splitlines() if line.startswith("pip install")]
    assert len(installs) == 1
    assert '.[notebooks]' in installs[0] and "-e" not in installs[0] and "--editable" not in installs[0]
    assert f"constraints/{LOCK}.txt" in installs[0]
    assert "jupyter-server-proxy" in (ROOT / "binder" / "requirements.txt").read_text()
    start = (ROOT / "binder" / "start").read_text()
    assert "deploy/singleuser-start.sh" in start and '"$@"' in start
    for script in ("postBuild", "start"):
        path = ROOT / "binder" / script
        assert os.access(path, os.X_OK), f"binder/{script} must be executable"
        syntax = subprocess.run(["bash", "-n", str(path)], capture_output=True, text=True)
        assert syntax.returncode == 0, syntax.stderr
    assert "jupyter-server-proxy" in DOCKERFILE


# ------------------------------------------------ what is published hands out no answers (issue 24)

def book_settings(edition: str | None) -> dict:
    """docs/conf.py's settings as Sphinx reads them, with HALFEDGE_EDU_BOOK_EDITION=edition."""
    env = {key: value for key, value in os.environ.items() if key != "HALFEDGE_EDU_BOOK_EDITION"}
    if edition is not None:
        env["HALFEDGE_EDU_BOOK_EDITION"] = edition
    code = ("import json, runpy; s = runpy.run_path('docs/conf.py'); "
            "print(json.dumps({k: s[k] for k in ('CHAPTERS', 'include_patterns', 'exclude_patterns', 'html_title')}))")
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True, text=True, timeout=60)
    assert result.returncode == 0 or edition == "answers", result.stderr
    return json.loads(result.stdout) if result.returncode == 0 else {"error": result.stderr}


def test_the_website_shows_the_student_edition_unless_the_solutions_are_asked_for():
    student = book_settings(None)
    folder = (ROOT / "docs" / student["CHAPTERS"]).resolve()
    assert folder == (ROOT / "notebooks" / "student").resolve()
    assert [p for p in student["include_patterns"] if "ipynb" in p] == ["chapters/[0-9][0-9]*_*.ipynb"]
    for chapter in folder.glob("[0-9][0-9]*_*.ipynb"):
        text = chapter.read_text(encoding="utf-8")
        assert json.loads(text)["metadata"]["halfedge_edu"]["edition"] == "student", chapter.name
        assert "### BEGIN SOLUTION" not in text, chapter.name

    solutions = book_settings("solutions")
    assert (ROOT / "docs" / solutions["CHAPTERS"]).resolve() == (ROOT / "notebooks").resolve()
    assert "instructors only" in solutions["html_title"]
    assert "ValueError" in book_settings("answers")["error"]


def test_make_book_builds_the_student_edition_and_the_solutions_only_when_asked(tmp_path):
    def dry(*options: str) -> str:
        return subprocess.run(["make", "-n", "book", f"VENV={tmp_path / 'venv'}", *options], cwd=ROOT,
                              capture_output=True, text=True, check=True).stdout

    assert "HALFEDGE_EDU_BOOK_EDITION=student" in dry() and "build/book\n" in dry() + "\n"
    assert "HALFEDGE_EDU_BOOK_EDITION=solutions" in dry("EDITION=solutions")
    assert "build/book-solutions" in dry("EDITION=solutions")


def test_a_chapter_page_and_the_api_reference_build_cleanly_with_described_pictures(tmp_path):
    """The website's machinery on one chapter and the API page (the whole site is
    tests/browser/test_book.py's): no docutils error or warning (the Google-style
    docstrings need napoleon), and each picture's alt text says what it shows, not its
    file name."""
    source = tmp_path / "src"
    (source / "chapters").mkdir(parents=True)
    chapter = "03_navigating.ipynb"
    (source / "chapters" / chapter).symlink_to(ROOT / "notebooks" / "student" / chapter)
    (source / "api.md").symlink_to(ROOT / "docs" / "api.md")
    (source / "index.md").write_text("# t\n\n```{toctree}\napi\nchapters/03_navigating\n```\n", encoding="utf-8")
    build = subprocess.run([sys.executable, "-m", "sphinx", "-q", "-b", "html", "-c", str(ROOT / "docs"),
                            str(source), str(tmp_path / "out")], capture_output=True, text=True, timeout=600)
    assert build.returncode == 0, build.stderr[-3000:]
    assert build.stderr.strip() == "", build.stderr[-3000:]
    page = (tmp_path / "out" / "chapters" / "03_navigating.html").read_text(encoding="utf-8")
    alts = re.findall(r'<img alt="([^"]*)"', page)
    assert len(alts) >= 3
    for alt in alts:
        assert not re.search(r"\.(png|jpe?g)$", alt) and len(alt.split()) >= 5, alt
    assert "halfedge 7" in alts[0]
    assert "BEGIN SOLUTION" not in page, "the website hands out an answer"


def test_binder_removes_the_solution_edition_and_history_after_installing():
    post_build = (ROOT / "binder" / "postBuild").read_text()
    commands = [line for line in post_build.splitlines() if line.strip() and not line.lstrip().startswith("#")]
    install = next(i for i, line in enumerate(commands) if "pip install" in line)
    removal = next(i for i, line in enumerate(commands) if line.startswith("rm -rf"))
    assert install < removal
    removed = shlex.split(commands[removal])[2:]
    assert {"notebooks", ".git", "docs/solutions"} <= set(removed)
