"""Where a learner's notebook runs while it is graded: a private folder, limits, and nothing else.

A learner's notebook is untrusted code. For each submission the grader makes a
:class:`Sandbox`, starts the notebook's run in it, and ends it; what it guarantees:

- **A private working folder** holding only that submission's notebook; ``HOME``,
  ``TMPDIR``, ``IPYTHONDIR`` and Jupyter's folders point inside it, and all of it is
  removed afterwards (an IPython startup file a learner plants dies with it).
- **A reduced environment**: only the variables a kernel needs (``PATH``, the locale,
  the headless rendering settings), never the grader's (``CI_JOB_TOKEN``,
  ``GITHUB_TOKEN`` ...).
- **Limits** (:class:`Limits`): memory (a cgroup where the grader may make one, else
  the address space), processes, the size of any file written, core dumps off.
- **Every process ended** at the end, whatever the notebook started: the sandbox's
  process group, and every process that still carries this run's marker variable.

With ``isolation="bubblewrap"`` (Debian's ``bubblewrap`` package; the default where it
works) the run also gets its own PID, network, IPC and hostname namespaces and a file
system that shows only the system's read-only folders, the Python environment, the
package, and the private folder: no other submission, report, output folder or solution
edition is visible, there is no network, and when its first process ends the kernel
ends every process in it. Started as root, it also runs as a throwaway unprivileged
user (a fresh uid for each submission, so one can never signal or read another).

Why bubblewrap and not bare namespaces: one small, audited setuid-free program that
Debian, Ubuntu and Flatpak keep working; written by hand, namespaces need a dozen
mounts in the right order. Where neither root nor unprivileged user namespaces are
available, ``isolation="process"`` still gives the folder, environment, limits and
clean-up, but not the file-system view: run one submission per CI job there.
"""

from __future__ import annotations

import functools
import os
import secrets
import shutil
import signal
import subprocess
import sys
import sysconfig
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

#: The environment variables a sandboxed run keeps from the grader's (rendering, BLAS).
KEPT_VARIABLES = (
    "PYVISTA_JUPYTER_BACKEND", "PYVISTA_OFF_SCREEN", "VTK_DEFAULT_OPENGL_WINDOW", "VTK_WASM_DIR_OVERRIDE",
    "MPLBACKEND", "OPENBLAS_CORETYPE", "OPENBLAS_L2_SIZE", "OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS",
    "MKL_NUM_THREADS", "LIBGL_ALWAYS_SOFTWARE", "GALLIUM_DRIVER", "MESA_GL_VERSION_OVERRIDE", "TZ",
)
#: The variable that marks every process of one run, so that the clean-up finds them all.
MARKER = "HALFEDGE_EDU_GRADE_RUN"
#: Where throwaway uids are drawn from: far above any real account.
_UID_BASE, _UID_SPAN = 1_900_000_000, 90_000_000


@dataclass(frozen=True)
class Limits:
    """What one submission's run may use (each an option of ``halfedge-edu grade``).

    Attributes:
        memory_mb: memory of all its processes together.
        processes: processes and threads (enforced where it runs as its own user).
        file_size_mb: the largest file it may write.
        output_mb: cell output the grader keeps; printing beyond it is dropped.
    """

    memory_mb: int = 2048
    processes: int = 256
    file_size_mb: int = 64
    output_mb: int = 8


@functools.lru_cache(maxsize=None)
def bubblewrap_works() -> bool:
    """Whether ``bwrap`` is installed and can make the namespaces the sandbox uses here."""
    bwrap = shutil.which("bwrap")
    if bwrap is None:
        return False
    try:
        probe = subprocess.run([bwrap, "--ro-bind", "/", "/", "--proc", "/proc", "--dev", "/dev", "--unshare-pid",
                                "--unshare-net", "--die-with-parent", "true"],
                               stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               timeout=20)
    except (OSError, subprocess.SubprocessError):
        return False
    return probe.returncode == 0


def choose_isolation(asked: str) -> str:
    """``"bubblewrap"`` or ``"process"`` for ``asked`` (``"auto"`` picks bubblewrap where it works).

    Raises RuntimeError when bubblewrap is asked for and does not work here, naming the fix.
    """
    if asked not in ("auto", "bubblewrap", "process"):
        raise ValueError(f"isolation must be auto, bubblewrap or process, not {asked!r}")
    if asked == "process":
        return "process"
    if bubblewrap_works():
        return "bubblewrap"
    if asked == "bubblewrap":
        raise RuntimeError("bubblewrap (bwrap) is not installed or cannot make namespaces here: on Debian or "
                           "Ubuntu `apt-get install bubblewrap`, and run the grader as root or where unprivileged "
                           "user namespaces are allowed")
    return "process"


class Sandbox:
    """One submission's private folder and the processes run in it; a context manager.

    Attributes:
        root: the grader's own folder for this run (not visible inside).
        work: the private working folder (the notebook, HOME, TMPDIR ...).
        exchange: a folder the grader makes before the run and the run may only read
            (the judge's socket lives there).
    """

    def __init__(self, isolation: str = "auto", limits: Limits = Limits()):
        self.isolation = choose_isolation(isolation)
        self.limits = limits
        self.token = secrets.token_hex(12)
        self.root = Path(tempfile.mkdtemp(prefix="halfedge_edu-grade-"))
        self.work = self.root / "work"
        self.exchange = self.root / "exchange"
        self.uid: int | None = None
        if self.isolation == "bubblewrap" and os.geteuid() == 0:
            self.uid = _UID_BASE + secrets.randbelow(_UID_SPAN)
        self._processes: list[subprocess.Popen] = []
        self._cgroup: Path | None = None
        os.chmod(self.root, 0o711)
        for folder in (self.work, *(self.work / name for name in ("home", "tmp", "ipython", "jupyter", "cache"))):
            folder.mkdir(mode=0o700)
        self.exchange.mkdir(mode=0o711)
        if self.uid is not None:
            for folder in self.work.rglob("*"):
                os.chown(folder, self.uid, self.uid)
            os.chown(self.work, self.uid, self.uid)

    # ----------------------------------------------------------------------------------

    def __enter__(self) -> "Sandbox":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def environment(self) -> dict[str, str]:
        """The whole environment of a sandboxed process."""
        python_bin = str(Path(sys.executable).parent)
        env = {
            "PATH": f"{python_bin}:/usr/local/bin:/usr/bin:/bin",
            "HOME": str(self.work / "home"), "TMPDIR": str(self.work / "tmp"),
            "IPYTHONDIR": str(self.work / "ipython"), "JUPYTER_CONFIG_DIR": str(self.work / "jupyter" / "config"),
            "JUPYTER_DATA_DIR": str(self.work / "jupyter" / "data"),
            "JUPYTER_RUNTIME_DIR": str(self.work / "jupyter" / "runtime"),
            "MPLCONFIGDIR": str(self.work / "cache" / "matplotlib"), "XDG_CACHE_HOME": str(self.work / "cache"),
            "LANG": "C.UTF-8", "LC_ALL": "C.UTF-8", "USER": "learner", "LOGNAME": "learner",
            "PYTHONNOUSERSITE": "1", "PYTHONDONTWRITEBYTECODE": "1", "JUPYTER_PLATFORM_DIRS": "1",
            MARKER: self.token,
        }
        env.update({name: os.environ[name] for name in KEPT_VARIABLES if name in os.environ})
        return env

    def command(self, argv: list[str]) -> list[str]:
        """``argv`` wrapped so that it runs inside the sandbox."""
        if self.isolation == "process":
            return argv
        bwrap = ["bwrap", "--die-with-parent", "--new-session", "--unshare-pid", "--unshare-net",
                 "--unshare-ipc", "--unshare-uts", "--hostname", "grading", "--proc", "/proc", "--dev", "/dev",
                 "--tmpfs", "/tmp", "--clearenv"]
        for system in ("/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32", "/etc", "/sys"):
            if Path(system).exists():
                bwrap += ["--ro-bind", system, system]
        if Path("/dev/dri").exists():
            bwrap += ["--dev-bind", "/dev/dri", "/dev/dri"]
        made: set[str] = set()

        def parents(path: str) -> list[str]:
            # bwrap makes missing parents of a mount point 0700 (root's): open them up, or the
            # unprivileged user could not reach the Python environment under /root or /work.
            found = []
            for parent in reversed(Path(path).parents[:-1]):
                if str(parent) not in made and not any(str(parent) == s or str(parent).startswith(s + "/")
                                                       for s in ("/usr", "/bin", "/sbin", "/lib", "/etc", "/sys")):
                    made.add(str(parent))
                    found += ["--perms", "0755", "--dir", str(parent)]
            return found

        for folder in _python_folders():
            bwrap += [*parents(folder), "--ro-bind", folder, folder]
        bwrap += [*parents(str(self.work)), "--bind", str(self.work), str(self.work),
                  "--ro-bind", str(self.exchange), str(self.exchange), "--chdir", str(self.work)]
        for name, value in self.environment().items():
            bwrap += ["--setenv", name, value]
        if self.uid is not None:
            bwrap += ["--", "setpriv", f"--reuid={self.uid}", f"--regid={self.uid}", "--clear-groups",
                      "--no-new-privs", "--"]
        else:
            bwrap += ["--"]
        return bwrap + argv

    def start(self, argv: list[str], stdout) -> subprocess.Popen:
        """Start ``argv`` in the sandbox with its stdout in ``stdout`` (a file the grader opened)."""
        self._make_cgroup()
        process = subprocess.Popen(
            self.command(argv), stdin=subprocess.DEVNULL, stdout=stdout, stderr=subprocess.DEVNULL,
            cwd=self.work, env=self.environment(), start_new_session=True, preexec_fn=self._limit_self,
        )
        self._processes.append(process)
        return process

    def _limit_self(self) -> None:
        """Run in the child between fork and exec: join the cgroup, set the resource limits."""
        import resource

        if self._cgroup is not None:
            try:
                (self._cgroup / "cgroup.procs").write_text(str(os.getpid()))
            except OSError:
                pass
        megabyte = 1024 * 1024
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        resource.setrlimit(resource.RLIMIT_FSIZE, (self.limits.file_size_mb * megabyte,) * 2)
        if self._cgroup is None:
            # No cgroup: bound the address space instead (generously: VTK and BLAS reserve far
            # more address space than they use).
            address_space = (self.limits.memory_mb + 3072) * megabyte
            resource.setrlimit(resource.RLIMIT_AS, (address_space, address_space))
        if self.uid is not None:
            resource.setrlimit(resource.RLIMIT_NPROC, (self.limits.processes,) * 2)

    def _make_cgroup(self) -> None:
        """A memory cgroup for this run, where the grader may make one (root; cgroup v2, else v1)."""
        if self._cgroup is not None or os.geteuid() != 0:
            return
        unified = Path("/sys/fs/cgroup")
        try:
            v2 = "memory" in (unified / "cgroup.controllers").read_text().split()
        except OSError:
            v2 = False
        if v2:
            base, limit_file = unified, "memory.max"
        elif Path("/sys/fs/cgroup/memory/memory.limit_in_bytes").exists():
            base, limit_file = Path("/sys/fs/cgroup/memory"), "memory.limit_in_bytes"
        else:
            return
        group = base / f"halfedge_edu-grade-{self.token}"
        try:
            group.mkdir()
            (group / limit_file).write_text(str(self.limits.memory_mb * 1024 * 1024))
            if v2 and (group / "memory.swap.max").exists():
                (group / "memory.swap.max").write_text("0")
        except OSError:
            try:
                group.rmdir()
            except OSError:
                pass
            return
        self._cgroup = group

    def out_of_memory(self) -> bool:
        """Whether the run's cgroup had to kill a process for memory."""
        if self._cgroup is None:
            return False
        for name in ("memory.events", "memory.oom_control", "memory.failcnt"):
            path = self._cgroup / name
            try:
                text = path.read_text()
            except OSError:
                continue
            for line in text.splitlines():
                key, _, value = line.partition(" ")
                if key in ("oom_kill", "oom") and value.strip() not in ("", "0"):
                    return True
            if name == "memory.failcnt" and text.strip() not in ("", "0"):
                return True
        return False

    def end_processes(self) -> None:
        """End every process of this run: its process groups, and any process with its marker or uid."""
        for process in self._processes:
            if process.poll() is None:
                try:
                    os.killpg(process.pid, signal.SIGKILL)
                except OSError:
                    pass
        for _ in range(3):
            stray = self._stray_processes()
            if not stray:
                break
            for pid in stray:
                try:
                    os.kill(pid, signal.SIGKILL)
                except OSError:
                    pass
            time.sleep(0.05)
        for process in self._processes:
            try:
                process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                pass

    def _stray_processes(self) -> list[int]:
        """Processes that belong to this run: its marker in their environment, or its uid."""
        found = []
        marker = f"{MARKER}={self.token}".encode()
        for entry in Path("/proc").iterdir() if Path("/proc").is_dir() else []:
            if not entry.name.isdigit() or int(entry.name) == os.getpid():
                continue
            try:
                if self.uid is not None and entry.stat().st_uid == self.uid:
                    found.append(int(entry.name))
                    continue
                if marker in (entry / "environ").read_bytes().split(b"\0"):
                    found.append(int(entry.name))
            except OSError:
                continue
        return found

    def close(self) -> None:
        """End every process and remove every file of this run."""
        self.end_processes()
        if self._cgroup is not None:
            for _ in range(20):
                try:
                    self._cgroup.rmdir()
                    break
                except OSError:
                    time.sleep(0.05)
            self._cgroup = None
        shutil.rmtree(self.root, ignore_errors=True)


def _python_folders() -> list[str]:
    """The folders a sandboxed Python needs: the environment, its base, and the package itself."""
    package = Path(__file__).resolve().parents[1]   # halfedge_edu/, wherever it is installed
    folders = {sys.prefix, sys.base_prefix, sys.exec_prefix, str(package)}
    folders |= {sysconfig.get_paths()[key] for key in ("stdlib", "platstdlib", "purelib", "platlib")}
    kept: list[str] = []
    for folder in sorted(folders, key=len):
        path = str(Path(folder).resolve())
        if Path(path).exists() and not any(path == k or path.startswith(k + "/") for k in kept):
            kept.append(path)
    # The interpreter the virtual environment links to may live elsewhere (pyenv, /usr/local).
    real_python = str(Path(sys.executable).resolve().parent.parent)
    if not any(real_python == k or real_python.startswith(k + "/") for k in kept) and Path(real_python).exists():
        kept.append(real_python)
    return kept
